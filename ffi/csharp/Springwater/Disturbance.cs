using System;

namespace Springwater
{
    /// <summary>
    /// The library's rain or a wake, applied before every substep of a frame by
    /// <see cref="WaterSurface.AdvanceWith"/> with the substep's length, so drops fall and
    /// wakes move on the water's clock. Not tied to one surface. <see cref="Dispose"/> frees
    /// the native disturbance (twice is harmless; the finalizer frees a forgotten one); any
    /// use after it throws SpringwaterException with SW_ERROR_INVALID_HANDLE.
    /// </summary>
    public abstract unsafe class Disturbance : IDisposable
    {
        readonly DisturbanceHandle handle;
        readonly IntPtr raw;

        internal Disturbance(IntPtr created)
        {
            raw = created;
            handle = new DisturbanceHandle(created);
        }

        /// <summary>Frees the native disturbance. Twice is harmless.</summary>
        public void Dispose()
        {
            handle.Dispose();
        }

        internal Borrow Enter()
        {
            return new Borrow(handle, raw);
        }
    }

    /// <summary>
    /// Rain: drops at random places and times over the surface's window, the same ones for
    /// the same seed however the time is cut into frames.
    /// </summary>
    public sealed unsafe class Rain : Disturbance
    {
        /// <summary>
        /// <paramref name="rate"/> drops per second (0: none) from <paramref name="seed"/>,
        /// radii from <paramref name="radiusMin"/> to <paramref name="radiusMax"/> world
        /// units, each <paramref name="depth"/> of its radius deep (in (0, 1]); the library's
        /// own defaults are radii 1.5 to 3 and depth 0.6.
        /// </summary>
        public Rain(float rate, ulong seed, float radiusMin, float radiusMax, float depth)
            : base(Create(rate, seed, radiusMin, radiusMax, depth)) { }

        static IntPtr Create(float rate, ulong seed, float radiusMin, float radiusMax, float depth)
        {
            IntPtr created;
            SpringwaterException.Check(Native.sw_rain_create(rate, seed, radiusMin, radiusMax, depth, &created));
            return created;
        }

        /// <summary>Sets the drops per second (0 stops the rain).</summary>
        public void SetRate(float rate)
        {
            using (var d = Enter())
                SpringwaterException.Check(Native.sw_rain_set_rate(d.Ptr, rate));
        }

        /// <summary>Drops fallen so far.</summary>
        public ulong Fallen
        {
            get
            {
                ulong n;
                using (var d = Enter())
                    SpringwaterException.Check(Native.sw_rain_fallen(d.Ptr, &n));
                return n;
            }
        }

        /// <summary>Seconds of rain so far.</summary>
        public double Time
        {
            get
            {
                double t;
                using (var d = Enter())
                    SpringwaterException.Check(Native.sw_rain_time(d.Ptr, &t));
                return t;
            }
        }
    }

    /// <summary>
    /// A wake: an object moving along a closed path at a constant speed, pressing the water
    /// down under it (faster than the ripples, it leaves a V behind).
    /// </summary>
    public sealed unsafe class Wake : Disturbance
    {
        Wake(IntPtr created)
            : base(created) { }

        /// <summary>
        /// Along the closed path of x, z corners <paramref name="xz"/> (world units), at
        /// <paramref name="speed"/> world units per second, pressing with
        /// <paramref name="strength"/> · exp(−d²/radius²) out to three
        /// <paramref name="radius"/>; the library's own defaults are 60, 2.5 and 1.5.
        /// </summary>
        public Wake(float[] xz, float speed, float radius, float strength)
            : base(Create(xz, speed, radius, strength)) { }

        static IntPtr Create(float[] xz, float speed, float radius, float strength)
        {
            IntPtr created;
            if (xz != null && xz.Length % 2 != 0)
                throw new SpringwaterException(
                    Native.SW_ERROR_INVALID_ARGUMENT,
                    "xz holds " + xz.Length + " floats: it must hold an x, z pair per corner");
            fixed (float* p = xz)
                SpringwaterException.Check(Native.sw_wake_create(
                    p, (UIntPtr)(xz == null ? 0 : xz.Length / 2), speed, radius, strength, &created));
            return created;
        }

        /// <summary>Round a circle of <paramref name="circleRadius"/> about the middle of the surface's window, counter-clockwise seen from above.</summary>
        public static Wake Circle(WaterSurface surface, float circleRadius, float speed, float radius, float strength)
        {
            IntPtr created;
            using (var s = surface.Borrowed())
                SpringwaterException.Check(Native.sw_wake_circle(
                    s.Ptr, circleRadius, speed, radius, strength, &created));
            return new Wake(created);
        }

        /// <summary>Where the object is now, world x and z.</summary>
        public void Position(out float x, out float z)
        {
            float* at = stackalloc float[2];
            using (var d = Enter())
                SpringwaterException.Check(Native.sw_wake_position(d.Ptr, at));
            x = at[0];
            z = at[1];
        }

        /// <summary>Moves the whole path by (dx, dz), keeping the object's progress: after Rebase(dcols, drows), (−dcols·spacing, −drows·spacing).</summary>
        public void Translate(float dx, float dz)
        {
            using (var d = Enter())
                SpringwaterException.Check(Native.sw_wake_translate(d.Ptr, dx, dz));
        }
    }

    /// <summary>Owns a live disturbance handle; releasing it frees the rain or wake.</summary>
    internal sealed class DisturbanceHandle : OwnedHandle
    {
        internal DisturbanceHandle(IntPtr disturbance)
            : base(disturbance) { }

        protected override bool ReleaseHandle()
        {
            Native.sw_disturbance_destroy(handle);
            return true;
        }
    }
}
