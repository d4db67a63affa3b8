// More of the C ABI, declaration for declaration (the rest is in Native.cs): a point's
// velocity on a body, bounding radii, the hulls the library makes and reads, and rain and
// wakes. Checked against the header by ffi/tests/csharp.rs like Native.cs.
using System;
using System.Runtime.InteropServices;

namespace Springwater
{
    public static unsafe partial class Native
    {
        /// <summary>Writes the world velocity of the body's point at (x, y, z) to `out[0..3]`, world
        /// units per second: velocity + angular_velocity × (point − position).</summary>
        [DllImport(Library, CallingConvention = CallingConvention.Cdecl, ExactSpelling = true)]
        public static extern int sw_floater_velocity_at(
            SwFloater* floater,
            float x,
            float y,
            float z,
            float* @out);

        /// <summary>Writes the distance from a sphere's or a box's centre to its farthest point to
        /// `out`.</summary>
        [DllImport(Library, CallingConvention = CallingConvention.Cdecl, ExactSpelling = true)]
        public static extern int sw_floater_bounding_radius(SwFloater* floater, float* @out);

        /// <summary>The library's default boat's dimensions and resolution.</summary>
        [DllImport(Library, CallingConvention = CallingConvention.Cdecl, ExactSpelling = true)]
        public static extern SwBoatShape sw_boat_shape_default();

        /// <summary>Generates the boat `shape` describes and writes a new hull handle to `out`.</summary>
        [DllImport(Library, CallingConvention = CallingConvention.Cdecl, ExactSpelling = true)]
        public static extern int sw_hull_boat(SwBoatShape* shape, IntPtr* @out);

        /// <summary>Writes a new handle of a box hull of half extents (half_x, half_y, half_z) to
        /// `out`.</summary>
        [DllImport(Library, CallingConvention = CallingConvention.Cdecl, ExactSpelling = true)]
        public static extern int sw_hull_cuboid(float half_x, float half_y, float half_z, IntPtr* @out);

        /// <summary>Writes a new handle of the hull's mesh moved onto its centroid to `out`.</summary>
        [DllImport(Library, CallingConvention = CallingConvention.Cdecl, ExactSpelling = true)]
        public static extern int sw_hull_centred(IntPtr hull, IntPtr* @out);

        /// <summary>Writes the centroid of the hull's volume, body frame, to `out[0..3]`.</summary>
        [DllImport(Library, CallingConvention = CallingConvention.Cdecl, ExactSpelling = true)]
        public static extern int sw_hull_centroid(IntPtr hull, float* @out);

        /// <summary>Writes the distance from the body frame's origin to the hull's farthest vertex
        /// to `out`.</summary>
        [DllImport(Library, CallingConvention = CallingConvention.Cdecl, ExactSpelling = true)]
        public static extern int sw_hull_bounding_radius(IntPtr hull, float* @out);

        /// <summary>Copies the hull's vertices, three floats each, to `xyz` and writes their number
        /// to `count` (NULL `xyz`: only the count).</summary>
        [DllImport(Library, CallingConvention = CallingConvention.Cdecl, ExactSpelling = true)]
        public static extern int sw_hull_vertices(IntPtr hull, float* xyz, UIntPtr len, UIntPtr* count);

        /// <summary>Copies the hull's triangles, three indices each, to `indices` and writes their
        /// number to `count` (NULL `indices`: only the count).</summary>
        [DllImport(Library, CallingConvention = CallingConvention.Cdecl, ExactSpelling = true)]
        public static extern int sw_hull_triangles(IntPtr hull, uint* indices, UIntPtr len, UIntPtr* count);

        /// <summary>Makes rain of `rate` drops per second from `seed`, radii from `radius_min` to
        /// `radius_max`, depth `depth` of the radius; writes its handle to `out`.</summary>
        [DllImport(Library, CallingConvention = CallingConvention.Cdecl, ExactSpelling = true)]
        public static extern int sw_rain_create(
            float rate,
            ulong seed,
            float radius_min,
            float radius_max,
            float depth,
            IntPtr* @out);

        /// <summary>Sets the rate of rain, drops per second (0 stops it).</summary>
        [DllImport(Library, CallingConvention = CallingConvention.Cdecl, ExactSpelling = true)]
        public static extern int sw_rain_set_rate(IntPtr rain, float rate);

        /// <summary>Writes the drops the rain has let fall so far to `out`.</summary>
        [DllImport(Library, CallingConvention = CallingConvention.Cdecl, ExactSpelling = true)]
        public static extern int sw_rain_fallen(IntPtr rain, ulong* @out);

        /// <summary>Writes the seconds the rain has fallen so far to `out`.</summary>
        [DllImport(Library, CallingConvention = CallingConvention.Cdecl, ExactSpelling = true)]
        public static extern int sw_rain_time(IntPtr rain, double* @out);

        /// <summary>Makes a wake along the closed path of `corners` x, z points at `speed`, with
        /// footprint `radius` and pressure `strength`; writes its handle to `out`.</summary>
        [DllImport(Library, CallingConvention = CallingConvention.Cdecl, ExactSpelling = true)]
        public static extern int sw_wake_create(
            float* xz,
            UIntPtr corners,
            float speed,
            float radius,
            float strength,
            IntPtr* @out);

        /// <summary>Makes a wake round a circle of `circle_radius` about the middle of the surface's
        /// window; writes its handle to `out`.</summary>
        [DllImport(Library, CallingConvention = CallingConvention.Cdecl, ExactSpelling = true)]
        public static extern int sw_wake_circle(
            IntPtr surface,
            float circle_radius,
            float speed,
            float radius,
            float strength,
            IntPtr* @out);

        /// <summary>Writes where the wake's object is now, world [x, z], to `out[0..2]`.</summary>
        [DllImport(Library, CallingConvention = CallingConvention.Cdecl, ExactSpelling = true)]
        public static extern int sw_wake_position(IntPtr wake, float* @out);

        /// <summary>Moves the wake's whole path by (dx, dz), keeping the object's progress.</summary>
        [DllImport(Library, CallingConvention = CallingConvention.Cdecl, ExactSpelling = true)]
        public static extern int sw_wake_translate(IntPtr wake, float dx, float dz);

        /// <summary>Frees rain or a wake. NULL and a destroyed handle are no-ops.</summary>
        [DllImport(Library, CallingConvention = CallingConvention.Cdecl, ExactSpelling = true)]
        public static extern void sw_disturbance_destroy(IntPtr disturbance);

        /// <summary>`sw_surface_advance` with the `count` disturbances applied, in their order,
        /// before every substep; writes the steps taken to `substeps` (optional).</summary>
        [DllImport(Library, CallingConvention = CallingConvention.Cdecl, ExactSpelling = true)]
        public static extern int sw_surface_advance_with(
            IntPtr surface,
            float frame_time,
            IntPtr* disturbances,
            UIntPtr count,
            uint* substeps);
    }
}
