// Rigid bodies through the C# package: a box heeled 15° rights itself as a built-in body,
// in an engine's own explicit integrator driven by BodyForces, and as a Hull; refusals.
using System;
using Springwater;

static unsafe partial class Runner
{
    const float Tick = 1f / 60f;

    /// 15° about the world's x axis: sin and cos of 7.5°.
    static readonly Rotation Heeled = new Rotation(0.13052619f, 0, 0, 0.9914449f);

    /// The box: 6 × 1.5 × 3 at half the water's density, upright at the pool's centre.
    static SwFloater TheBox(WaterSurface w)
    {
        float mass = 0.5f * w.Buoyancy.density * 8f * 3f * 0.75f * 1.5f;
        return SwFloater.Box(3, 0.75f, 1.5f, mass, 24, 0, 24);
    }

    /// Kept in step with `righted_box()` in ffi/tests/common/mod.rs, which runs the built-in
    /// box through Rust: ten seconds of 60 Hz frames on a 48 × 48 pool.
    static void RigidBodies()
    {
        using (var w = new WaterSurface(48, 48))
        {
            var box = TheBox(w);
            box.Orientation = Heeled;
            ulong id = w.AddFloater(box);
            Assert(Math.Abs(w.Floater(id).Orientation.HeelDegrees - 15) < 0.01f, "added heeled");
            float late = 0;
            for (int frame = 0; frame < 600; frame++)
            {
                w.Advance(Tick);
                if (frame == 0)
                    Assert(w.Floater(id).AngularVelocity.x < 0 && w.Floater(id).WaterTorque.x < 0,
                        "the water turns it back");
                if (frame >= 540)
                    late = Math.Max(late, w.Floater(id).Orientation.HeelDegrees);
            }
            Assert(late < 1, "the built-in box rights itself: " + late + "°");
            var q = w.Floater(id).Orientation;
            Value("righted_orientation", Hex(q.x) + " " + Hex(q.y) + " " + Hex(q.z) + " " + Hex(q.w));
            Value("righted_position", Hex(w.Floater(id).Position.y));
        }
        EngineBox();
        HullBox();
    }

    /// A game engine's body: semi-implicit Euler at 60 Hz with the water's force and torque
    /// and gravity; the orientation turned by the angular velocity and normalised.
    static void EngineBox()
    {
        using (var w = new WaterSurface(48, 48))
        {
            float g = w.Buoyancy.gravity;
            var body = TheBox(w);
            body.Orientation = Heeled;
            // A box's inertia is diagonal in its axes: the torque is turned into them, divided, turned back.
            var moments = new Float3(body.Inertia(0, 0), body.Inertia(1, 1), body.Inertia(2, 2));
            float late = 0;
            for (int frame = 0; frame < 600; frame++)
            {
                SwBodyForces push = w.BodyForces(body, Tick);
                var q = body.Orientation;
                var inverse = new Rotation(-q.x, -q.y, -q.z, q.w);
                Float3 local = inverse.Rotate(push.Torque);
                Float3 alpha = q.Rotate(new Float3(local.x / moments.x, local.y / moments.y, local.z / moments.z));
                var v = body.Velocity;
                var f = push.Force;
                v = new Float3(v.x + Tick * f.x / body.mass, v.y + Tick * (f.y / body.mass - g), v.z + Tick * f.z / body.mass);
                var om = body.AngularVelocity;
                om = new Float3(om.x + Tick * alpha.x, om.y + Tick * alpha.y, om.z + Tick * alpha.z);
                var p = body.Position;
                body.Position = new Float3(p.x + Tick * v.x, p.y + Tick * v.y, p.z + Tick * v.z);
                body.Velocity = v;
                body.AngularVelocity = om;
                // q += dt/2 (ω, 0) q, normalised.
                var dq = new Rotation(
                    q.w * om.x + om.y * q.z - om.z * q.y,
                    q.w * om.y + om.z * q.x - om.x * q.z,
                    q.w * om.z + om.x * q.y - om.y * q.x,
                    -(om.x * q.x + om.y * q.y + om.z * q.z));
                var n = new Rotation(q.x + 0.5f * Tick * dq.x, q.y + 0.5f * Tick * dq.y,
                    q.z + 0.5f * Tick * dq.z, q.w + 0.5f * Tick * dq.w);
                float norm = (float)Math.Sqrt(n.x * n.x + n.y * n.y + n.z * n.z + n.w * n.w);
                body.Orientation = new Rotation(n.x / norm, n.y / norm, n.z / norm, n.w / norm);
                w.Advance(Tick);
                Assert(!float.IsNaN(body.Position.y), "finite");
                if (frame >= 540)
                    late = Math.Max(late, body.Orientation.HeelDegrees);
            }
            Assert(late < 1, "the engine's box rights itself: " + late + "°");
            Assert(Math.Abs(body.Position.y) < 0.15f, "floats at its draft: " + body.Position.y);
        }
    }

    /// The box as a hull mesh: vertex i has x, y, z from its bits 0, 1, 2.
    static void HullBox()
    {
        var xyz = new float[24];
        for (int i = 0; i < 8; i++)
            for (int k = 0; k < 3; k++)
                xyz[3 * i + k] = ((i >> k) & 1) == 1 ? new[] { 3f, 0.75f, 1.5f }[k] : -new[] { 3f, 0.75f, 1.5f }[k];
        int[] triangles = {
            0, 4, 6, 0, 6, 2, 1, 7, 5, 1, 3, 7, 0, 1, 5, 0, 5, 4,
            2, 7, 3, 2, 6, 7, 0, 2, 3, 0, 3, 1, 4, 5, 7, 4, 7, 6 };
        using (var w = new WaterSurface(48, 48))
        {
            var hull = new Hull(xyz, triangles);
            Assert(hull.Volume == 27, "the hull's volume: " + hull.Volume);
            var box = TheBox(w);
            var body = hull.Floater(box.mass, 24, 0, 24);
            Assert(body.shape == Native.SW_SHAPE_HULL, "a hull body");
            body.Orientation = Heeled;
            box.Orientation = Heeled;
            float lift = w.BodyForces(box, Tick).Force.y, meshLift = w.BodyForces(hull, body, Tick).Force.y;
            Assert(Math.Abs(lift - meshLift) < 0.02f * lift, "the mesh feels the box's force: " + lift + " " + meshLift);
            ulong id = w.AddHullFloater(hull, body);
            hull.Dispose();
            hull.Dispose();
            Refused("csharp_disposed_hull", Native.SW_ERROR_INVALID_HANDLE, "hull",
                () => w.AddHullFloater(hull, body));
            Refused("hull_body_without_mesh", Native.SW_ERROR_INVALID_ARGUMENT, "SW_SHAPE_HULL",
                () => w.AddFloater(body));
            Refused("hull_open", Native.SW_ERROR_INVALID_ARGUMENT, "",
                () => new Hull(xyz, new int[] { 0, 4, 6 }));
            Refused("csharp_hull_not_triples", Native.SW_ERROR_INVALID_ARGUMENT, "triples",
                () => new Hull(new float[4], triangles));
            Refused("body_forces_tick", Native.SW_ERROR_INVALID_ARGUMENT, "tick",
                () => w.BodyForces(box, 0));
            Refused("push_at_nan", Native.SW_ERROR_INVALID_ARGUMENT, "NaN",
                () => w.PushFloaterAt(id, new Float3(0, 1, 0), new Float3(float.NaN, 0, 0)));
            float late = 0;
            for (int frame = 0; frame < 600; frame++)
            {
                w.Advance(Tick);
                if (frame >= 540)
                    late = Math.Max(late, w.Floater(id).Orientation.HeelDegrees);
            }
            Assert(late < 1, "the hull box rights itself: " + late + "°");
            Assert(w.Floater(id).shape == Native.SW_SHAPE_HULL, "read back as a hull");
            // A push on its side turns it: the torque (point − position) × force.
            var at = w.Floater(id).Position;
            w.PushFloaterAt(id, new Float3(0, 3, 0), new Float3(at.x + 2, at.y, at.z));
            Assert(Math.Abs(w.Floater(id).PushTorque.z - 6) < 1e-3f, "a push at a point is a torque");
        }
    }
}
