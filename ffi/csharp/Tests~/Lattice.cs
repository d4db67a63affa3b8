// The lattice node by node through the C# package: pins, masses, viscosities, a spring and
// a torque push, each read back; the state they make is printed for ffi/tests/csharp.rs to
// recompute through the Rust API.
using System;
using Springwater;

static unsafe partial class Runner
{
    /// Kept in step with `lattice()` in ffi/tests/csharp.rs.
    static void Lattice()
    {
        using (var w = new WaterSurface(20, 16))
        {
            int n = w.NodeCount;
            var masses = new float[n];
            for (int i = 0; i < n; i++)
                masses[i] = 4 + 0.25f * (i % 8);
            w.SetMasses(masses);
            w.SetMass(21, 5);
            masses[21] = 5;
            w.SetViscosity(5 * 20 + 5, 0.2f);
            w.SetPinned(8 * 20 + 10, true);
            w.SetSpring(Native.SW_FAMILY_SE, 6 * 20 + 6, 0.9f, 6);
            ulong id = w.AddFloater(SwFloater.Box(1, 0.5f, 1, 2, 10, 0, 8));
            w.PushFloaterTorque(id, 0, 30, 0);
            Assert(w.Floater(id).PushTorque.y == 30, "the torque waits for the next step");

            var back = new float[n];
            w.WriteMasses(back);
            for (int i = 0; i < n; i++)
                Assert(back[i] == masses[i], "mass " + i + " reads back");
            w.WriteViscosities(back);
            Assert(back[5 * 20 + 5] == 0.2f && back[5 * 20 + 6] == SwParams.Default().viscosity,
                "one node's viscosity");
            var pinned = new byte[n];
            w.WritePinned(pinned);
            Assert(w.IsPinned(8 * 20 + 10) && pinned[8 * 20 + 10] == 1 && pinned[0] == 1 && pinned[21] == 0,
                "the pins: the ring and one more");
            float rest, stiffness;
            w.Spring(Native.SW_FAMILY_SE, 6 * 20 + 6, out rest, out stiffness);
            Assert(rest == 0.9f && stiffness == 6, "the spring reads back");

            w.DropAt(10, 8, 0.5f, 2);
            w.Advance(0.5f);
            Assert(w.Floater(id).AngularVelocity.y > 0, "the torque turned the box");
            Value("lattice_hash", w.StateHash().ToString("x16"));
        }
    }
}
