using System;

namespace Springwater
{
    /// <summary>
    /// A closed triangle mesh for floating bodies (a boat's hull), validated once and shared
    /// by every body made of it: <see cref="Floater"/> makes a body, and
    /// <see cref="WaterSurface.AddHullFloater"/> adds one (the surface keeps its own copy of
    /// the mesh, so disposing the hull never changes a body). <see cref="Dispose"/> frees
    /// the native hull (twice is harmless; the finalizer frees a forgotten one); any use
    /// after it throws SpringwaterException with SW_ERROR_INVALID_HANDLE.
    /// </summary>
    public sealed unsafe class Hull : IDisposable
    {
        readonly HullHandle handle;
        readonly IntPtr raw;

        /// <summary>
        /// A hull from <paramref name="xyz"/> (three floats a vertex, in the body's frame with
        /// the centre of mass at the origin) and <paramref name="triangles"/> (three vertex
        /// indices a triangle, counter-clockwise seen from outside: Unity's Mesh.triangles
        /// order for an outward mesh). An open, inside-out or degenerate mesh throws with the
        /// defect named.
        /// </summary>
        public Hull(float[] xyz, int[] triangles)
        {
            IntPtr created;
            int vertexFloats = xyz == null ? 0 : xyz.Length;
            int indices = triangles == null ? 0 : triangles.Length;
            if (vertexFloats % 3 != 0 || indices % 3 != 0)
                throw new SpringwaterException(
                    Native.SW_ERROR_INVALID_ARGUMENT,
                    "xyz holds " + vertexFloats + " floats and triangles " + indices
                    + " indices: both must be whole triples");
            fixed (float* v = xyz)
            fixed (int* t = triangles)
                SpringwaterException.Check(Native.sw_hull_create(
                    v, (UIntPtr)(vertexFloats / 3), (uint*)t, (UIntPtr)(indices / 3), &created));
            raw = created;
            handle = new HullHandle(created);
        }

        Hull(IntPtr created)
        {
            raw = created;
            handle = new HullHandle(created);
        }

        /// <summary>A box hull of half extents (hx, hy, hz) centred on the origin: 8 vertices, 12 triangles.</summary>
        public static Hull Cuboid(float hx, float hy, float hz)
        {
            IntPtr created;
            SpringwaterException.Check(Native.sw_hull_cuboid(hx, hy, hz, &created));
            return new Hull(created);
        }

        /// <summary>
        /// The library's procedural boat of <paramref name="shape"/> (start it from
        /// SwBoatShape.Default()): bow to +x, y up, the origin on the keel amidships
        /// (<see cref="Centred"/> moves it onto its centroid).
        /// </summary>
        public static Hull Boat(SwBoatShape shape)
        {
            IntPtr created;
            SpringwaterException.Check(Native.sw_hull_boat(&shape, &created));
            return new Hull(created);
        }

        /// <summary>A new hull of this mesh moved so that its centroid is at the origin; this one stays as it is.</summary>
        public Hull Centred()
        {
            IntPtr created;
            using (var h = Enter())
                SpringwaterException.Check(Native.sw_hull_centred(h.Ptr, &created));
            return new Hull(created);
        }

        /// <summary>The centroid of the enclosed volume, body frame: the centre of mass at uniform density.</summary>
        public Float3 Centroid
        {
            get
            {
                var c = new Float3();
                using (var h = Enter())
                    SpringwaterException.Check(Native.sw_hull_centroid(h.Ptr, &c.x));
                return c;
            }
        }

        /// <summary>The distance from the body frame's origin to the farthest vertex.</summary>
        public float BoundingRadius
        {
            get
            {
                float r;
                using (var h = Enter())
                    SpringwaterException.Check(Native.sw_hull_bounding_radius(h.Ptr, &r));
                return r;
            }
        }

        /// <summary>The vertices, body frame, three floats each (to draw a hull the library made).</summary>
        public float[] Vertices()
        {
            UIntPtr count;
            using (var h = Enter())
            {
                SpringwaterException.Check(Native.sw_hull_vertices(h.Ptr, null, UIntPtr.Zero, &count));
                var xyz = new float[3 * checked((int)count.ToUInt64())];
                fixed (float* p = xyz)
                    SpringwaterException.Check(Native.sw_hull_vertices(h.Ptr, p, (UIntPtr)xyz.Length, &count));
                return xyz;
            }
        }

        /// <summary>The triangles, three vertex indices each, counter-clockwise seen from outside.</summary>
        public int[] Triangles()
        {
            UIntPtr count;
            using (var h = Enter())
            {
                SpringwaterException.Check(Native.sw_hull_triangles(h.Ptr, null, UIntPtr.Zero, &count));
                var indices = new int[3 * checked((int)count.ToUInt64())];
                fixed (int* p = indices)
                    SpringwaterException.Check(Native.sw_hull_triangles(
                        h.Ptr, (uint*)p, (UIntPtr)indices.Length, &count));
                return indices;
            }
        }

        /// <summary>Frees the native hull; bodies made of it keep their mesh. Twice is harmless.</summary>
        public void Dispose()
        {
            handle.Dispose();
        }

        internal Borrow Enter()
        {
            return new Borrow(handle, raw);
        }

        /// <summary>The enclosed volume, cubic world units: a body at a fraction f of the water's density has mass f · density · Volume.</summary>
        public float Volume
        {
            get
            {
                float volume;
                using (var h = Enter())
                    SpringwaterException.Check(Native.sw_hull_volume(h.Ptr, &volume));
                return volume;
            }
        }

        /// <summary>
        /// A body of this hull of <paramref name="mass"/> with its origin at (x, y, z), at
        /// rest, upright, with the default drag; its inertia is the hull's for that mass.
        /// </summary>
        public SwFloater Floater(float mass, float x, float y, float z)
        {
            SwFloater body = Native.sw_floater_sphere(1, 1, 0, 0, 0); // sets struct_size
            using (var h = Enter())
                SpringwaterException.Check(Native.sw_floater_hull(h.Ptr, mass, x, y, z, &body));
            return body;
        }
    }
}
