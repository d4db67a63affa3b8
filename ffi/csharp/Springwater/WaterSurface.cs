using System;
using System.Runtime.InteropServices;

namespace Springwater
{
    /// <summary>
    /// A water surface: a mass-spring lattice of cols × rows nodes, in world units, y up.
    /// Every method either does what it says or throws <see cref="SpringwaterException"/>
    /// with the library's message, changing nothing. The frame-loop methods allocate
    /// nothing: buffers are the caller's, kept between frames. Calls on one surface must not
    /// overlap (another thread's call in progress is refused, SW_ERROR_BUSY); different
    /// surfaces run on different threads at once. <see cref="Dispose"/> frees the native
    /// surface (twice is harmless; the finalizer frees a forgotten one); any call after it
    /// throws SpringwaterException with SW_ERROR_INVALID_HANDLE.
    /// </summary>
    public sealed unsafe partial class WaterSurface : IDisposable
    {
        readonly SurfaceHandle handle;
        /// The handle's value, kept after Dispose: the library refuses it from then on.
        readonly IntPtr raw;

        /// <summary>A flat surface at rest with the seed's defaults.</summary>
        public WaterSurface(int cols, int rows)
            : this(Sized(cols, rows)) { }

        /// <summary>A flat surface at rest; start <paramref name="parameters"/> from SwParams.Default().</summary>
        public WaterSurface(SwParams parameters)
        {
            IntPtr created;
            SpringwaterException.Check(Native.sw_surface_create(&parameters, &created));
            raw = created;
            handle = new SurfaceHandle(created);
        }

        WaterSurface(IntPtr created)
        {
            raw = created;
            handle = new SurfaceHandle(created);
        }

        static SwParams Sized(int cols, int rows)
        {
            SwParams p = Native.sw_params_default();
            // A negative size becomes a huge one, which the library refuses by name.
            p.cols = unchecked((uint)cols);
            p.rows = unchecked((uint)rows);
            return p;
        }

        /// <summary>A surface restored from a snapshot (<see cref="Save"/>), every body included.</summary>
        public static WaterSurface Load(byte[] snapshot)
        {
            IntPtr created;
            fixed (byte* p = snapshot)
                SpringwaterException.Check(Native.sw_surface_load(p, Length(snapshot), &created));
            return new WaterSurface(created);
        }

        /// <summary>Frees the native surface. Twice is harmless.</summary>
        public void Dispose()
        {
            handle.Dispose();
        }

        /// <summary>Whether <see cref="Dispose"/> has run.</summary>
        public bool IsDisposed
        {
            get { return handle.IsClosed; }
        }

        internal IntPtr RawHandle
        {
            get { return raw; }
        }

        Borrow Enter()
        {
            return new Borrow(handle, raw);
        }

        static UIntPtr Length(Array buffer)
        {
            return (UIntPtr)(buffer == null ? 0 : buffer.Length);
        }

        // ---- The model ----

        /// <summary>The parameters the surface runs.</summary>
        public SwParams Params
        {
            get
            {
                SwParams p = Native.sw_params_default();
                using (var s = Enter())
                    SpringwaterException.Check(Native.sw_surface_params(s.Ptr, &p));
                return p;
            }
        }

        /// <summary>Nodes per row.</summary>
        public int Cols
        {
            get { return (int)Params.cols; }
        }

        /// <summary>Rows of nodes.</summary>
        public int Rows
        {
            get { return (int)Params.rows; }
        }

        /// <summary>cols × rows: the length, in elements, of every per-node buffer.</summary>
        public int NodeCount
        {
            get
            {
                UIntPtr n;
                using (var s = Enter())
                    SpringwaterException.Check(Native.sw_surface_node_count(s.Ptr, &n));
                return checked((int)n.ToUInt64());
            }
        }

        // ---- The frame loop ----

        /// <summary>
        /// Advances the water by one frame of <paramref name="seconds"/> (a fixed-step clock:
        /// the same total time gives the same state however it is cut into frames); returns
        /// the steps taken.
        /// </summary>
        public uint Advance(float seconds)
        {
            uint substeps;
            using (var s = Enter())
                SpringwaterException.Check(Native.sw_surface_advance(s.Ptr, seconds, &substeps));
            return substeps;
        }

        /// <summary>Takes <paramref name="steps"/> steps of the model's timestep.</summary>
        public void Step(uint steps)
        {
            using (var s = Enter())
                SpringwaterException.Check(Native.sw_surface_step(s.Ptr, steps));
        }

        /// <summary>The most steps one Advance takes (16 by default) and whether a longer frame's owed steps carry over.</summary>
        public void SetStepCap(uint maxSteps, bool carry)
        {
            using (var s = Enter())
                SpringwaterException.Check(Native.sw_surface_set_step_cap(s.Ptr, maxSteps, carry ? 1 : 0));
        }

        /// <summary>How far the clock is past the last step, as a fraction of a step in [0, 1).</summary>
        public float Interpolation
        {
            get
            {
                float f;
                using (var s = Enter())
                    SpringwaterException.Check(Native.sw_surface_interpolation(s.Ptr, &f));
                return f;
            }
        }

        /// <summary>The cap on steps per Advance call and whether owed steps carry past it, as SetStepCap takes them.</summary>
        public void GetStepCap(out uint maxSteps, out bool carry)
        {
            uint max;
            int c;
            using (var s = Enter())
                SpringwaterException.Check(Native.sw_surface_step_cap(s.Ptr, &max, &c));
            maxSteps = max;
            carry = c == 1;
        }

        /// <summary>Steps taken so far.</summary>
        public ulong Steps
        {
            get
            {
                ulong n;
                using (var s = Enter())
                    SpringwaterException.Check(Native.sw_surface_steps(s.Ptr, &n));
                return n;
            }
        }

        /// <summary>Seconds of the caller's clock simulated so far (ModelTime / time_scale).</summary>
        public double Time
        {
            get
            {
                double v;
                using (var s = Enter())
                    SpringwaterException.Check(Native.sw_surface_time(s.Ptr, &v));
                return v;
            }
        }

        /// <summary>Model time simulated so far, the sum of the steps' dt.</summary>
        public double ModelTime
        {
            get
            {
                double v;
                using (var s = Enter())
                    SpringwaterException.Check(Native.sw_surface_model_time(s.Ptr, &v));
                return v;
            }
        }

        /// <summary>Seconds Advance owes and has not stepped yet.</summary>
        public double OwedSeconds
        {
            get
            {
                double v;
                using (var s = Enter())
                    SpringwaterException.Check(Native.sw_surface_owed_seconds(s.Ptr, &v));
                return v;
            }
        }

        /// <summary>Seconds the step cap has dropped so far.</summary>
        public double DroppedSeconds
        {
            get
            {
                double v;
                using (var s = Enter())
                    SpringwaterException.Check(Native.sw_surface_dropped_seconds(s.Ptr, &v));
                return v;
            }
        }

        /// <summary>The largest safe timestep for the current tables and bodies.</summary>
        public float CriticalDt
        {
            get
            {
                float dt;
                using (var s = Enter())
                    SpringwaterException.Check(Native.sw_surface_critical_dt(s.Ptr, &dt));
                return dt;
            }
        }

        /// <summary>Adds height · exp(−d²/radius²) to every free node, d its rest distance from (x, z).</summary>
        public void DropAt(float x, float z, float height, float radius)
        {
            using (var s = Enter())
                SpringwaterException.Check(Native.sw_surface_drop_at(s.Ptr, x, z, height, radius));
        }

        /// <summary>
        /// Adds the force (fx, fy, fz) at (x, z) for the next step, spread like HeightAt
        /// reads; in the lattice's units (a per-second² force divided by time_scale²).
        /// </summary>
        public void AddForceAt(float x, float z, float fx, float fy, float fz)
        {
            using (var s = Enter())
                SpringwaterException.Check(Native.sw_surface_add_force_at(s.Ptr, x, z, fx, fy, fz));
        }

        // ---- Point queries ----

        /// <summary>Whether world (x, z) is finite and inside the rest footprint, where the queries answer.</summary>
        public bool Contains(float x, float z)
        {
            int inside;
            using (var s = Enter())
                SpringwaterException.Check(Native.sw_surface_contains(s.Ptr, x, z, &inside));
            return inside != 0;
        }

        /// <summary>The height at world (x, z), inside the rest footprint.</summary>
        public float HeightAt(float x, float z)
        {
            float h;
            using (var s = Enter())
                SpringwaterException.Check(Native.sw_surface_height_at(s.Ptr, x, z, &h));
            return h;
        }

        /// <summary>The unit normal at world (x, z).</summary>
        public Float3 NormalAt(float x, float z)
        {
            var n = new Float3();
            using (var s = Enter())
                SpringwaterException.Check(Native.sw_surface_normal_at(s.Ptr, x, z, &n.x));
            return n;
        }

        /// <summary>The water's velocity at world (x, z), world units per second.</summary>
        public Float3 VelocityAt(float x, float z)
        {
            var v = new Float3();
            using (var s = Enter())
                SpringwaterException.Check(Native.sw_surface_velocity_at(s.Ptr, x, z, &v.x));
            return v;
        }

        /// <summary>
        /// Samples xz.Length / 2 points (x, z pairs) into <paramref name="results"/>; one point
        /// off the water refuses them all.
        /// </summary>
        public void Sample(float[] xz, SwSample[] results)
        {
            fixed (float* p = xz)
            fixed (SwSample* r = results)
                Sample(p, Points(xz), r, Count(results));
        }

        /// <summary>Like Sample, point by point: found[k] is 0 where point k is off the water.</summary>
        public void SampleEach(float[] xz, SwSample[] results, byte[] found)
        {
            fixed (float* p = xz)
            fixed (SwSample* r = results)
            fixed (byte* f = found)
                SampleEach(p, Points(xz), r, Count(results), f, Count(found));
        }

        public void Sample(float* xz, int points, SwSample* results, int resultsLength)
        {
            using (var s = Enter())
                SpringwaterException.Check(Native.sw_surface_sample(
                    s.Ptr, xz, Size(points), results, Size(resultsLength)));
        }

        public void SampleEach(float* xz, int points, SwSample* results, int resultsLength, byte* found, int foundLength)
        {
            using (var s = Enter())
                SpringwaterException.Check(Native.sw_surface_sample_each(
                    s.Ptr, xz, Size(points), results, Size(resultsLength), found, Size(foundLength)));
        }

        static int Count(Array buffer)
        {
            return buffer == null ? 0 : buffer.Length;
        }

        /// The points of an x, z array. The C ABI trusts the caller for xz's length (it
        /// reads 2 floats per point), so an odd length is refused here.
        static int Points(float[] xz)
        {
            if (xz != null && xz.Length % 2 != 0)
                throw new SpringwaterException(
                    Native.SW_ERROR_INVALID_ARGUMENT,
                    "xz holds " + xz.Length + " floats: it must hold an x, z pair per point");
            return xz == null ? 0 : xz.Length / 2;
        }

        /// A length for the C ABI; a negative one (a pointer caller's mistake) is refused.
        static UIntPtr Size(int length)
        {
            if (length < 0)
                throw new SpringwaterException(
                    Native.SW_ERROR_INVALID_ARGUMENT, "buffer length " + length + " is negative");
            return (UIntPtr)length;
        }

        // ---- Per-node buffers (row-major, node (col, row) at row * cols + col) ----

        /// <summary>Every node's position, interleaved x, y, z: xyz.Length at least 3 × NodeCount.</summary>
        public void WritePositions(float[] xyz)
        {
            fixed (float* p = xyz)
                WritePositions(p, Count(xyz));
        }

        public void WritePositions(float* xyz, int length)
        {
            using (var s = Enter())
                SpringwaterException.Check(Native.sw_surface_write_positions(s.Ptr, xyz, Size(length)));
        }

        /// <summary>Every node's unit normal, interleaved x, y, z.</summary>
        public void WriteNormals(float[] xyz)
        {
            fixed (float* p = xyz)
                WriteNormals(p, Count(xyz));
        }

        public void WriteNormals(float* xyz, int length)
        {
            using (var s = Enter())
                SpringwaterException.Check(Native.sw_surface_write_normals(s.Ptr, xyz, Size(length)));
        }

        /// <summary>Every node's refracted bottom texture coordinate seen from view's eye, interleaved u, v.</summary>
        public void WriteRefractionUvs(SwRefraction view, float[] uv)
        {
            fixed (float* p = uv)
                WriteRefractionUvs(view, p, Count(uv));
        }

        public void WriteRefractionUvs(SwRefraction view, float* uv, int length)
        {
            using (var s = Enter())
                SpringwaterException.Check(Native.sw_surface_write_refraction_uvs(s.Ptr, &view, uv, Size(length)));
        }

        /// <summary>
        /// The packed vertex buffer a renderer uploads, one SwVertex per node (position,
        /// normal, refraction uv), in one pass.
        /// </summary>
        public void WriteVertices(SwRefraction view, SwVertex[] vertices)
        {
            fixed (SwVertex* p = vertices)
                WriteVertices(view, p, Count(vertices));
        }

        /// <summary>Into native memory, such as a Unity NativeArray's GetUnsafePtr().</summary>
        public void WriteVertices(SwRefraction view, SwVertex* vertices, int length)
        {
            using (var s = Enter())
                SpringwaterException.Check(Native.sw_surface_write_vertices(s.Ptr, &view, vertices, Size(length)));
        }

        // ---- LOD index buffer ----

        /// <summary>Replaces the LOD parameters (the next UpdateLod rebuilds with them).</summary>
        public void SetLodParams(SwLodParams parameters)
        {
            using (var s = Enter())
                SpringwaterException.Check(Native.sw_surface_set_lod_params(s.Ptr, &parameters));
        }

        /// <summary>Updates the view-dependent index buffer for an eye; true if it changed (upload it again).</summary>
        public bool UpdateLod(float eyeX, float eyeY, float eyeZ)
        {
            int changed;
            using (var s = Enter())
                SpringwaterException.Check(Native.sw_surface_update_lod(s.Ptr, eyeX, eyeY, eyeZ, &changed));
            return changed != 0;
        }

        /// <summary>The index buffer's length in indices (3 per triangle).</summary>
        public int LodIndexCount
        {
            get
            {
                UIntPtr count;
                using (var s = Enter())
                    SpringwaterException.Check(Native.sw_surface_lod_indices(s.Ptr, null, UIntPtr.Zero, &count));
                return checked((int)count.ToUInt64());
            }
        }

        /// <summary>
        /// Copies the index buffer (counter-clockwise seen from +y) and returns its length;
        /// a shorter array is refused (SW_ERROR_BUFFER_TOO_SMALL).
        /// </summary>
        public int WriteLodIndices(uint[] indices)
        {
            fixed (uint* p = indices)
                return WriteLodIndices(p, Count(indices));
        }

        public int WriteLodIndices(uint* indices, int length)
        {
            UIntPtr count;
            // A NULL buffer would only ask for the count: hand an empty one instead, which
            // the library refuses as too small unless the index buffer is empty.
            uint none;
            if (indices == null)
                length = 0;
            using (var s = Enter())
                SpringwaterException.Check(Native.sw_surface_lod_indices(
                    s.Ptr, length == 0 ? &none : indices, Size(length), &count));
            return checked((int)count.ToUInt64());
        }

        // ---- Diagnostics and the engine ----

        /// <summary>Kinetic and spring potential energy.</summary>
        public SwEnergy Energy
        {
            get
            {
                SwEnergy e;
                using (var s = Enter())
                    SpringwaterException.Check(Native.sw_surface_energy(s.Ptr, &e));
                return e;
            }
        }

        /// <summary>The SIMD level the surface runs (Native.SW_SIMD_*); every level gives the same bits.</summary>
        public int SimdLevel
        {
            get
            {
                int level;
                using (var s = Enter())
                    SpringwaterException.Check(Native.sw_surface_simd_level(s.Ptr, &level));
                return level;
            }
        }

        /// <summary>Runs the surface at a level, clamped to what the CPU has; returns the level it will run.</summary>
        public int SetSimdLevel(int level)
        {
            int ran;
            using (var s = Enter())
                SpringwaterException.Check(Native.sw_surface_set_simd_level(s.Ptr, level, &ran));
            return ran;
        }

        /// <summary>The library's version, such as "0.1.0".</summary>
        public static string Version
        {
            get { return Marshal.PtrToStringAnsi(Native.sw_version()); }
        }

        /// <summary>A SIMD level's name ("avx2", "neon", ...).</summary>
        public static string SimdLevelName(int level)
        {
            return Marshal.PtrToStringAnsi(Native.sw_simd_level_name(level));
        }

        /// <summary>The widest SIMD level this CPU has (Native.SW_SIMD_*): what a new surface runs.</summary>
        public static int DetectSimdLevel()
        {
            return Native.sw_simd_level_detect();
        }

        /// <summary>Whether this CPU (and this build) can run a SIMD level without clamping it.</summary>
        public static bool SimdLevelAvailable(int level)
        {
            return Native.sw_simd_level_available(level) == 1;
        }
    }
}
