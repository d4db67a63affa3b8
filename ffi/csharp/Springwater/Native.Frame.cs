// More of the C ABI, declaration for declaration (the rest is in Native.cs): parameters'
// ripple speed and limits, frames cut into variable substeps, every node's pending force
// and velocity, the uniform acceleration, the LOD mesh read back and built from chosen
// levels. Checked against the header by ffi/tests/csharp.rs like Native.cs.
using System;
using System.Runtime.InteropServices;

namespace Springwater
{
    public static unsafe partial class Native
    {
        /// <summary>Writes how fast ripples travel on a surface of `params` to `out`, world units
        /// per second.</summary>
        [DllImport(Library, CallingConvention = CallingConvention.Cdecl, ExactSpelling = true)]
        public static extern int sw_params_ripple_speed(SwParams* @params, float* @out);

        /// <summary>Sets `params->time_scale` so that ripples travel `speed` world units per second,
        /// leaving every other field as it is.</summary>
        [DllImport(Library, CallingConvention = CallingConvention.Cdecl, ExactSpelling = true)]
        public static extern int sw_params_set_ripple_speed(SwParams* @params, float speed);

        /// <summary>Writes the most levels `params->patch_cells` allows to `out`.</summary>
        [DllImport(Library, CallingConvention = CallingConvention.Cdecl, ExactSpelling = true)]
        public static extern int sw_lod_params_max_levels(SwLodParams* @params, uint* @out);

        /// <summary>Writes Schlick's reflectance at normal incidence of the water in `refraction` to
        /// `out`.</summary>
        [DllImport(Library, CallingConvention = CallingConvention.Cdecl, ExactSpelling = true)]
        public static extern int sw_refraction_r0(SwRefraction* refraction, float* @out);

        /// <summary>Advances the water by one frame of `frame_time` seconds in equal substeps of
        /// variable length, never longer than `dt`; writes their number to `substeps`
        /// (optional).</summary>
        [DllImport(Library, CallingConvention = CallingConvention.Cdecl, ExactSpelling = true)]
        public static extern int sw_surface_advance_variable(
            IntPtr surface,
            float frame_time,
            uint* substeps);

        /// <summary>How `sw_surface_advance_variable` would cut a frame: the number of substeps and
        /// the seconds of each (either may be NULL).</summary>
        [DllImport(Library, CallingConvention = CallingConvention.Cdecl, ExactSpelling = true)]
        public static extern int sw_surface_split_frame(
            IntPtr surface,
            float frame_time,
            uint* substeps,
            float* substep_seconds);

        /// <summary>Replaces every node's force for the next step with `xyz`, interleaved x, y, z
        /// (`len` floats, at least 3 · nodes).</summary>
        [DllImport(Library, CallingConvention = CallingConvention.Cdecl, ExactSpelling = true)]
        public static extern int sw_surface_set_forces(IntPtr surface, float* xyz, UIntPtr len);

        /// <summary>Writes every node's force waiting for the next step, interleaved x, y, z.</summary>
        [DllImport(Library, CallingConvention = CallingConvention.Cdecl, ExactSpelling = true)]
        public static extern int sw_surface_write_forces(IntPtr surface, float* xyz, UIntPtr len);

        /// <summary>Sets the uniform acceleration on every free node, world units per second².</summary>
        [DllImport(Library, CallingConvention = CallingConvention.Cdecl, ExactSpelling = true)]
        public static extern int sw_surface_set_acceleration(IntPtr surface, float ax, float ay, float az);

        /// <summary>Writes every node's velocity, interleaved x, y, z, per unit of model time.</summary>
        [DllImport(Library, CallingConvention = CallingConvention.Cdecl, ExactSpelling = true)]
        public static extern int sw_surface_write_velocities(IntPtr surface, float* xyz, UIntPtr len);

        /// <summary>Writes the LOD parameters the index buffer is built with to `out` (whose
        /// `struct_size` must be set).</summary>
        [DllImport(Library, CallingConvention = CallingConvention.Cdecl, ExactSpelling = true)]
        public static extern int sw_surface_lod_params(IntPtr surface, SwLodParams* @out);

        /// <summary>Writes the LOD mesh's patches [across, down] to `out[0..2]` ([0, 0] before it is
        /// built).</summary>
        [DllImport(Library, CallingConvention = CallingConvention.Cdecl, ExactSpelling = true)]
        public static extern int sw_surface_lod_patch_grid(IntPtr surface, UIntPtr* @out);

        /// <summary>Copies each patch's level, row-major, to `levels` and writes their number to
        /// `count` (NULL `levels`: only the count).</summary>
        [DllImport(Library, CallingConvention = CallingConvention.Cdecl, ExactSpelling = true)]
        public static extern int sw_surface_lod_patch_levels(
            IntPtr surface,
            byte* levels,
            UIntPtr len,
            UIntPtr* count);

        /// <summary>Copies each triangle's LOD level to `levels` and writes their number to `count`
        /// (NULL `levels`: only the count).</summary>
        [DllImport(Library, CallingConvention = CallingConvention.Cdecl, ExactSpelling = true)]
        public static extern int sw_surface_lod_triangle_levels(
            IntPtr surface,
            byte* levels,
            UIntPtr len,
            UIntPtr* count);

        /// <summary>Builds the LOD index buffer from one level per patch (`len` exactly the number
        /// of patches); writes 1 to `changed` (optional) if it was rebuilt.</summary>
        [DllImport(Library, CallingConvention = CallingConvention.Cdecl, ExactSpelling = true)]
        public static extern int sw_surface_set_lod_levels(
            IntPtr surface,
            byte* levels,
            UIntPtr len,
            int* changed);
    }
}
