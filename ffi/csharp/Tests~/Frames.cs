// Frames beyond Advance, every node's force and velocity, the acceleration, the ripple
// speed, the reflectance and the LOD mesh read back and built from chosen levels, through
// the C# package; the values are printed for ffi/tests/csharp.rs to recompute through the
// Rust API.
using System;
using Springwater;

static unsafe partial class Runner
{
    /// Kept in step with `frames()` in ffi/tests/csharp.rs.
    static void Frames()
    {
        const int Arg = Native.SW_ERROR_INVALID_ARGUMENT, Small = Native.SW_ERROR_BUFFER_TOO_SMALL;
        using (var w = new WaterSurface(24, 20))
        {
            int n = w.NodeCount;
            w.DropAt(10, 8, 0.5f, 2);
            uint substeps;
            float each;
            w.SplitFrame(0.05f, out substeps, out each);
            Value("split_frame", substeps + " " + Hex(each));
            Assert(w.AdvanceVariable(0.05f) == substeps, "AdvanceVariable takes the split's substeps");

            w.SetAcceleration(0, -1, 0.5f);
            Assert(w.Params.acceleration_y == -1 && w.Params.acceleration_z == 0.5f, "the acceleration reads back");
            var forces = new float[3 * n];
            for (int i = 0; i < forces.Length; i++)
                forces[i] = 0.01f * (i % 7) - 0.03f;
            w.SetForces(forces);
            w.AddForce(30, 0, 0.25f, 0);
            var back = new float[3 * n];
            w.WriteForces(back);
            for (int i = 0; i < back.Length; i++)
                Assert(back[i] == forces[i] + (i == 3 * 30 + 1 ? 0.25f : 0), "force " + i + " reads back");
            w.Step(2);
            var velocities = new float[3 * n];
            w.WriteVelocities(velocities);
            Value("frames_velocities", Fnv(velocities, velocities.Length).ToString("x16"));
            Value("frames_hash", w.StateHash().ToString("x16"));
            ulong before = w.StateHash();
            forces[5] = float.NaN;
            Refused("forces_not_finite", Arg, "force", () => w.SetForces(forces));
            Refused("forces_short", Small, "xyz", () => w.SetForces(new float[3 * n - 1]));
            Refused("velocities_short", Small, "xyz", () => w.WriteVelocities(new float[5]));
            Refused("acceleration_not_finite", Arg, "acceleration", () => w.SetAcceleration(float.NaN, 0, 0));
            Refused("frame_negative", Arg, "frame", () => w.AdvanceVariable(-1));
            Assert(w.StateHash() == before && w.Params.acceleration_y == -1, "refusals change nothing");

            // The LOD mesh: 3 × 3 patches of 8 cells, levels chosen here.
            var lod = SwLodParams.Default();
            Assert(lod.MaxLevels() == 5, "16 cells allow 5 levels");
            lod.patch_cells = 8;
            lod.levels = 3;
            Assert(lod.MaxLevels() == 4, "8 cells allow 4 levels");
            w.SetLodParams(lod);
            Assert(w.LodParams.patch_cells == 8 && w.LodParams.levels == 3, "the LOD parameters read back");
            int across, down;
            w.GetLodPatchGrid(out across, out down);
            Assert(across == 0 && down == 0, "no patches before the mesh is built");
            var chosen = new byte[] { 0, 1, 2, 2, 0, 7, 1, 1, 0 };
            Assert(w.SetLodLevels(chosen), "the chosen levels build the mesh");
            Assert(!w.SetLodLevels(chosen), "the same levels again keep it");
            w.GetLodPatchGrid(out across, out down);
            Assert(across == 3 && down == 3, "3 × 3 patches");
            var patches = new byte[9];
            Assert(w.WriteLodPatchLevels(patches) == 9, "nine patches");
            var triangles = new byte[w.LodIndexCount / 3];
            Assert(w.WriteLodTriangleLevels(triangles) == triangles.Length, "a level per triangle");
            Value("lod_patch_levels", BitConverter.ToString(patches));
            Value("lod_triangles", triangles.Length.ToString());
            Refused("lod_levels_count", Small, "patch levels", () => w.SetLodLevels(new byte[8]));
            Refused("lod_patch_levels_short", Small, "levels", () => w.WriteLodPatchLevels(new byte[8]));
        }

        var p = SwParams.Default();
        p.SetRippleSpeed(100);
        Assert(Math.Abs(p.RippleSpeed() - 100) < 1e-3, "the ripple speed set reads back");
        Assert(p.dt == SwParams.Default().dt, "only the time scale changed");
        Value("ripple_time_scale", Hex(p.time_scale));
        Refused("ripple_speed_zero", Arg, "ripple speed", () => p.SetRippleSpeed(0));
        Value("r0", Hex(SwRefraction.Default().R0()));
    }
}
