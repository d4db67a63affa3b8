using System;

namespace Springwater
{
    // Frames beyond Advance (variable substeps, rain and wakes), every node's pending force
    // and velocity, the uniform acceleration, and the LOD mesh read back and built from
    // levels the caller chose.
    public sealed unsafe partial class WaterSurface
    {
        internal Borrow Borrowed()
        {
            return Enter();
        }

        // ---- Frames ----

        /// <summary>
        /// Advances by one frame of <paramref name="seconds"/> in equal substeps of variable
        /// length, never longer than dt, so that the frame ends exactly on the caller's clock
        /// (the results then depend on how time is cut into frames); Advance's accumulator is
        /// left as it is. Returns the substeps taken.
        /// </summary>
        public uint AdvanceVariable(float seconds)
        {
            uint substeps;
            using (var s = Enter())
                SpringwaterException.Check(Native.sw_surface_advance_variable(s.Ptr, seconds, &substeps));
            return substeps;
        }

        /// <summary>How AdvanceVariable would cut a frame of <paramref name="seconds"/>: the substeps and the seconds of each.</summary>
        public void SplitFrame(float seconds, out uint substeps, out float substepSeconds)
        {
            uint n;
            float each;
            using (var s = Enter())
                SpringwaterException.Check(Native.sw_surface_split_frame(s.Ptr, seconds, &n, &each));
            substeps = n;
            substepSeconds = each;
        }

        /// <summary>
        /// Advance with rain and wakes applied, in their order, before every substep; returns
        /// the steps taken. Each disturbance is listed once. Allocates nothing.
        /// </summary>
        public uint AdvanceWith(float seconds, params Disturbance[] disturbances)
        {
            int count = disturbances == null ? 0 : disturbances.Length;
            IntPtr* handles = stackalloc IntPtr[Math.Max(count, 1)];
            return AdvanceWith(seconds, disturbances, handles, 0, count);
        }

        /// Holds disturbance `at` (and, by recursion, the rest) for the call, then makes it.
        uint AdvanceWith(float seconds, Disturbance[] list, IntPtr* handles, int at, int count)
        {
            if (at < count)
            {
                if (list[at] == null)
                    throw new SpringwaterException(
                        Native.SW_ERROR_NULL_POINTER, "disturbance " + at + " is null");
                using (var d = list[at].Enter())
                {
                    handles[at] = d.Ptr;
                    return AdvanceWith(seconds, list, handles, at + 1, count);
                }
            }
            uint substeps;
            using (var s = Enter())
                SpringwaterException.Check(Native.sw_surface_advance_with(
                    s.Ptr, seconds, handles, (UIntPtr)count, &substeps));
            return substeps;
        }

        // ---- Every node's force and velocity, the acceleration ----

        /// <summary>
        /// Replaces every node's force for the next step with <paramref name="xyz"/>,
        /// interleaved x, y, z (at least 3 × NodeCount floats), in the lattice's force units.
        /// </summary>
        public void SetForces(float[] xyz)
        {
            using (var s = Enter())
            fixed (float* p = xyz)
                SpringwaterException.Check(Native.sw_surface_set_forces(s.Ptr, p, Size(Count(xyz))));
        }

        /// <summary>Every node's force waiting for the next step, interleaved x, y, z.</summary>
        public void WriteForces(float[] xyz)
        {
            using (var s = Enter())
            fixed (float* p = xyz)
                SpringwaterException.Check(Native.sw_surface_write_forces(s.Ptr, p, Size(Count(xyz))));
        }

        /// <summary>
        /// Every node's velocity, interleaved x, y, z, per unit of model time as the lattice
        /// holds it (times time_scale is per second, what VelocityAt gives).
        /// </summary>
        public void WriteVelocities(float[] xyz)
        {
            fixed (float* p = xyz)
                WriteVelocities(p, Count(xyz));
        }

        public void WriteVelocities(float* xyz, int length)
        {
            using (var s = Enter())
                SpringwaterException.Check(Native.sw_surface_write_velocities(s.Ptr, xyz, Size(length)));
        }

        /// <summary>Sets the uniform acceleration on every free node (gravity, wind), world units per second².</summary>
        public void SetAcceleration(float x, float y, float z)
        {
            using (var s = Enter())
                SpringwaterException.Check(Native.sw_surface_set_acceleration(s.Ptr, x, y, z));
        }

        // ---- The LOD mesh ----

        /// <summary>The LOD parameters the index buffer is built with.</summary>
        public SwLodParams LodParams
        {
            get
            {
                SwLodParams p = SwLodParams.Default();
                using (var s = Enter())
                    SpringwaterException.Check(Native.sw_surface_lod_params(s.Ptr, &p));
                return p;
            }
        }

        /// <summary>The LOD mesh's patches across and down (0 and 0 before it is first built).</summary>
        public void GetLodPatchGrid(out int across, out int down)
        {
            UIntPtr* grid = stackalloc UIntPtr[2];
            using (var s = Enter())
                SpringwaterException.Check(Native.sw_surface_lod_patch_grid(s.Ptr, grid));
            across = checked((int)grid[0].ToUInt64());
            down = checked((int)grid[1].ToUInt64());
        }

        /// <summary>Copies each patch's level (0 is full detail), row-major, and returns their number; a shorter array is refused.</summary>
        public int WriteLodPatchLevels(byte[] levels)
        {
            UIntPtr count;
            byte none;
            using (var s = Enter())
            fixed (byte* p = levels)
                SpringwaterException.Check(Native.sw_surface_lod_patch_levels(
                    s.Ptr, p == null ? &none : p, Size(Count(levels)), &count));
            return checked((int)count.ToUInt64());
        }

        /// <summary>Copies each triangle's LOD level, in the index buffer's order, and returns their number; a shorter array is refused.</summary>
        public int WriteLodTriangleLevels(byte[] levels)
        {
            UIntPtr count;
            byte none;
            using (var s = Enter())
            fixed (byte* p = levels)
                SpringwaterException.Check(Native.sw_surface_lod_triangle_levels(
                    s.Ptr, p == null ? &none : p, Size(Count(levels)), &count));
            return checked((int)count.ToUInt64());
        }

        /// <summary>
        /// Builds the index buffer from one level per patch, row-major (exactly the number of
        /// patches: ceil((cols − 1) / patch_cells) × ceil((rows − 1) / patch_cells)) instead
        /// of from an eye; true if it changed (upload it again).
        /// </summary>
        public bool SetLodLevels(byte[] levels)
        {
            int changed;
            using (var s = Enter())
            fixed (byte* p = levels)
                SpringwaterException.Check(Native.sw_surface_set_lod_levels(
                    s.Ptr, p, Size(Count(levels)), &changed));
            return changed != 0;
        }
    }
}
