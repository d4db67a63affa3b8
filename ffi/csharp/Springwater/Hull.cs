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
