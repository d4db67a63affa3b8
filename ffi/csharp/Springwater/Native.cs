// The C ABI of springwater (ffi/include/springwater.h), declaration for declaration: every
// `sw_*` function under its C name with its C types, every `SW_*` constant. Written by hand
// and checked against the header by ffi/tests/csharp.rs (names, parameter and return
// types, constants), so it cannot drift from the library. The idiomatic layer over it is
// WaterSurface.
using System;
using System.Runtime.InteropServices;

namespace Springwater
{
    /// <summary>
    /// The raw C ABI. Pointers are C# pointers (call from an <c>unsafe</c> context), a
    /// <c>SwSurface *</c> is an <see cref="IntPtr"/>, <c>size_t</c> is <see cref="UIntPtr"/>,
    /// every status, boolean and enum is an <c>int</c>. Prefer <see cref="WaterSurface"/>,
    /// which owns the handle and turns statuses into exceptions.
    /// </summary>
    public static unsafe partial class Native
    {
        /// <summary>
        /// The native library's name: <c>springwater_ffi</c> (libspringwater_ffi.so,
        /// libspringwater_ffi.dylib, springwater_ffi.dll); on iOS the static library linked
        /// into the player (<c>__Internal</c>).
        /// </summary>
#if UNITY_IOS && !UNITY_EDITOR
        public const string Library = "__Internal";
#else
        public const string Library = "springwater_ffi";
#endif

        /// <summary>The outer ring of nodes is pinned: a pool with walls.</summary>
        public const int SW_BOUNDARY_PINNED = 0;
        /// <summary>No node is pinned: the sheet floats freely.</summary>
        public const int SW_BOUNDARY_FREE = 1;
        /// <summary>Open water: a damping frame of <c>absorbing_width</c> rings.</summary>
        public const int SW_BOUNDARY_ABSORBING = 2;

        /// <summary>No SIMD: the scalar reference loops.</summary>
        public const int SW_SIMD_SCALAR = 0;
        /// <summary>SSE2 (every x86-64 CPU).</summary>
        public const int SW_SIMD_SSE2 = 1;
        /// <summary>AVX2.</summary>
        public const int SW_SIMD_AVX2 = 2;
        /// <summary>AVX-512F.</summary>
        public const int SW_SIMD_AVX512 = 3;
        /// <summary>The lane kernels on plain arrays (targets without a level of their own).</summary>
        public const int SW_SIMD_PORTABLE = 4;
        /// <summary>NEON (every AArch64 CPU).</summary>
        public const int SW_SIMD_NEON = 5;
        /// <summary>WebAssembly SIMD128.</summary>
        public const int SW_SIMD_SIMD128 = 6;

        /// <summary>A ball of <c>SwFloater.radius</c>.</summary>
        public const int SW_SHAPE_SPHERE = 0;
        /// <summary>A box of <c>SwFloater.half_extents</c>, its faces along the body's axes.</summary>
        public const int SW_SHAPE_BOX = 1;
        /// <summary>A closed triangle mesh (a hull handle), kept by the surface.</summary>
        public const int SW_SHAPE_HULL = 2;
        /// <summary><c>sizeof(SwFloater)</c> in version 1 of the header, which the calls still take.</summary>
        public const int SW_FLOATER_SIZE_V1 = 80;

        /// <summary>East springs: from node (col, row) to (col + 1, row).</summary>
        public const int SW_FAMILY_E = 0;
        /// <summary>South springs: from node (col, row) to (col, row + 1).</summary>
        public const int SW_FAMILY_S = 1;
        /// <summary>South-east diagonals: from node (col, row) to (col + 1, row + 1).</summary>
        public const int SW_FAMILY_SE = 2;
        /// <summary>South-west diagonals: from node (col, row) to (col − 1, row + 1).</summary>
        public const int SW_FAMILY_SW = 3;

        /// <summary>Success.</summary>
        public const int SW_OK = 0;
        /// <summary>A required pointer argument was NULL.</summary>
        public const int SW_ERROR_NULL_POINTER = -1;
        /// <summary>The surface handle is not a live surface (never created, or destroyed).</summary>
        public const int SW_ERROR_INVALID_HANDLE = -2;
        /// <summary>A number is not finite or outside its range, or an enum value is unknown.</summary>
        public const int SW_ERROR_INVALID_ARGUMENT = -3;
        /// <summary>A caller's buffer is shorter than the call needs.</summary>
        public const int SW_ERROR_BUFFER_TOO_SMALL = -4;
        /// <summary>A query point is outside the water's rest footprint.</summary>
        public const int SW_ERROR_OUTSIDE_GRID = -5;
        /// <summary>A step would have made the state non-finite; it was not applied.</summary>
        public const int SW_ERROR_NON_FINITE = -6;
        /// <summary>A snapshot was refused: truncated, corrupted, or another format version.</summary>
        public const int SW_ERROR_SNAPSHOT = -7;
        /// <summary>The host's job system returned before running every task.</summary>
        public const int SW_ERROR_JOB_SYSTEM = -8;
        /// <summary>Another call on the same surface is in progress.</summary>
        public const int SW_ERROR_BUSY = -9;
        /// <summary>The library failed internally; the surface is unusable, destroy it.</summary>
        public const int SW_ERROR_INTERNAL = -10;
        /// <summary>No floating body of this surface has the id.</summary>
        public const int SW_ERROR_NO_SUCH_FLOATER = -11;

        /// <summary>The library's version, a static NUL-terminated string such as `"0.1.0"`.</summary>
        [DllImport(Library, CallingConvention = CallingConvention.Cdecl, ExactSpelling = true)]
        public static extern IntPtr sw_version();

        /// <summary>The seed's defaults on a 128 × 128 grid.</summary>
        [DllImport(Library, CallingConvention = CallingConvention.Cdecl, ExactSpelling = true)]
        public static extern SwParams sw_params_default();

        /// <summary>The default LOD parameters.</summary>
        [DllImport(Library, CallingConvention = CallingConvention.Cdecl, ExactSpelling = true)]
        public static extern SwLodParams sw_lod_params_default();

        /// <summary>The default bottom depth and index of refraction, with the eye at the
        /// origin.</summary>
        [DllImport(Library, CallingConvention = CallingConvention.Cdecl, ExactSpelling = true)]
        public static extern SwRefraction sw_refraction_default();

        /// <summary>The widest SIMD level this CPU has: what a new surface runs until
        /// `sw_surface_set_simd_level` chooses another (the library never reads the environment).</summary>
        [DllImport(Library, CallingConvention = CallingConvention.Cdecl, ExactSpelling = true)]
        public static extern int sw_simd_level_detect();

        /// <summary>A static NUL-terminated name for a SIMD level (`"scalar"`, `"sse2"`, `"avx2"`,
        /// `"avx512"`, `"portable"`, `"neon"`, `"simd128"`), or `"unknown"`.</summary>
        [DllImport(Library, CallingConvention = CallingConvention.Cdecl, ExactSpelling = true)]
        public static extern IntPtr sw_simd_level_name(int level);

        /// <summary>1 if this CPU (and this build) can run SIMD `level`, else 0 (an unknown level
        /// too): what `sw_surface_set_simd_level` runs without clamping.</summary>
        [DllImport(Library, CallingConvention = CallingConvention.Cdecl, ExactSpelling = true)]
        public static extern int sw_simd_level_available(int level);

        /// <summary>Writes the guaranteed (large-wave) stability limit of `params` to `out`;
        /// `params` is checked like `sw_surface_create` checks it, except its `dt`.</summary>
        [DllImport(Library, CallingConvention = CallingConvention.Cdecl, ExactSpelling = true)]
        public static extern int sw_params_critical_dt(SwParams* @params, float* @out);

        /// <summary>Writes the linear stability limit at rest of `params` to `out`.</summary>
        [DllImport(Library, CallingConvention = CallingConvention.Cdecl, ExactSpelling = true)]
        public static extern int sw_params_linear_dt_limit(SwParams* @params, float* @out);

        /// <summary>Creates a flat surface at rest from `params` (validated: the message names the
        /// field that is wrong) and writes its handle to `out`.</summary>
        [DllImport(Library, CallingConvention = CallingConvention.Cdecl, ExactSpelling = true)]
        public static extern int sw_surface_create(SwParams* @params, IntPtr* @out);

        /// <summary>Destroys a surface and frees everything it owns. NULL, and a handle already
        /// destroyed, are no-ops.</summary>
        [DllImport(Library, CallingConvention = CallingConvention.Cdecl, ExactSpelling = true)]
        public static extern void sw_surface_destroy(IntPtr surface);

        /// <summary>Writes the surface's parameters to `out`, whose `struct_size` must be
        /// `sizeof(SwParams)` (start it from `sw_params_default()`, or set the field), or the call is
        /// `SW_ERROR_INVALID_ARGUMENT` and writes nothing.</summary>
        [DllImport(Library, CallingConvention = CallingConvention.Cdecl, ExactSpelling = true)]
        public static extern int sw_surface_params(IntPtr surface, SwParams* @out);

        /// <summary>Writes the number of nodes (`cols × rows`) to `out`: the length, in elements, of
        /// every per-node buffer.</summary>
        [DllImport(Library, CallingConvention = CallingConvention.Cdecl, ExactSpelling = true)]
        public static extern int sw_surface_node_count(IntPtr surface, UIntPtr* @out);

        /// <summary>Advances the water by one frame of the caller's clock: `frame_time` seconds
        /// (finite, at least 0) go into the surface's accumulator, and every whole timestep it holds is
        /// taken (a fixed-step clock: the same total time gives the same state, however it is cut into
        /// frames). Writes the number of steps taken to `substeps` (optional, may be NULL): 0 when the
        /// frame did not complete a step, at most the cap (`sw_surface_set_step_cap`). A failing step
        /// stops the frame there, earlier steps stay applied.</summary>
        [DllImport(Library, CallingConvention = CallingConvention.Cdecl, ExactSpelling = true)]
        public static extern int sw_surface_advance(
            IntPtr surface,
            float frame_time,
            uint* substeps);

        /// <summary>Sets the most steps one `sw_surface_advance` call takes (1 to 10000; 16 by default)
        /// and what happens to the steps a longer frame owes: `carry` 0 drops them (the water falls
        /// behind the caller's clock, the default), 1 carries them into the following calls.</summary>
        [DllImport(Library, CallingConvention = CallingConvention.Cdecl, ExactSpelling = true)]
        public static extern int sw_surface_set_step_cap(IntPtr surface, uint max_steps, int carry);

        /// <summary>Writes to `out` how far the caller's clock is past the water's last step, as a
        /// fraction of a step in `[0, 1)`: what a renderer that blends the last two states
        /// uses.</summary>
        [DllImport(Library, CallingConvention = CallingConvention.Cdecl, ExactSpelling = true)]
        public static extern int sw_surface_interpolation(IntPtr surface, float* @out);

        /// <summary>Writes the cap on steps per `sw_surface_advance` call to `max_steps` and what
        /// happens past it to `carry` (0 drops, 1 carries), as `sw_surface_set_step_cap` takes them.
        /// Either may be NULL.</summary>
        [DllImport(Library, CallingConvention = CallingConvention.Cdecl, ExactSpelling = true)]
        public static extern int sw_surface_step_cap(IntPtr surface, uint* max_steps, int* carry);

        /// <summary>Writes the steps taken so far to `out`.</summary>
        [DllImport(Library, CallingConvention = CallingConvention.Cdecl, ExactSpelling = true)]
        public static extern int sw_surface_steps(IntPtr surface, ulong* @out);

        /// <summary>Writes the seconds of the caller's clock simulated so far to `out`.</summary>
        [DllImport(Library, CallingConvention = CallingConvention.Cdecl, ExactSpelling = true)]
        public static extern int sw_surface_time(IntPtr surface, double* @out);

        /// <summary>Writes the model time simulated so far to `out` (the sum of the steps' dt).</summary>
        [DllImport(Library, CallingConvention = CallingConvention.Cdecl, ExactSpelling = true)]
        public static extern int sw_surface_model_time(IntPtr surface, double* @out);

        /// <summary>Writes the seconds `sw_surface_advance` owes and has not stepped yet to `out`.</summary>
        [DllImport(Library, CallingConvention = CallingConvention.Cdecl, ExactSpelling = true)]
        public static extern int sw_surface_owed_seconds(IntPtr surface, double* @out);

        /// <summary>Writes the seconds the step cap has dropped so far to `out`.</summary>
        [DllImport(Library, CallingConvention = CallingConvention.Cdecl, ExactSpelling = true)]
        public static extern int sw_surface_dropped_seconds(IntPtr surface, double* @out);

        /// <summary>Writes the largest safe timestep for the current tables and bodies to `out`.</summary>
        [DllImport(Library, CallingConvention = CallingConvention.Cdecl, ExactSpelling = true)]
        public static extern int sw_surface_critical_dt(IntPtr surface, float* @out);

        /// <summary>Advances `steps` steps of the model's timestep, several per pass over memory
        /// (bitwise the same as one at a time). Stops at a failing step; the steps before it stay
        /// applied.</summary>
        [DllImport(Library, CallingConvention = CallingConvention.Cdecl, ExactSpelling = true)]
        public static extern int sw_surface_step(IntPtr surface, uint steps);

        /// <summary>Drops water at world `(x, z)`: adds `height · exp(−d²/radius²)` to the height of
        /// every free node, `d` its rest distance from the point. `radius` &gt; 0; a drop steeper than
        /// one height per radius may fold the surface.</summary>
        [DllImport(Library, CallingConvention = CallingConvention.Cdecl, ExactSpelling = true)]
        public static extern int sw_surface_drop_at(
            IntPtr surface,
            float x,
            float z,
            float height,
            float radius);

        /// <summary>Deprecated: the earlier name of `sw_surface_drop_at`, which it calls.</summary>
        [DllImport(Library, CallingConvention = CallingConvention.Cdecl, ExactSpelling = true)]
        public static extern int sw_surface_drop(
            IntPtr surface,
            float x,
            float z,
            float height,
            float radius);

        /// <summary>Moves the window `dcols` cells along +x and `drows` along +z (negative values go
        /// the other way): node `(col, row)` afterwards is the water that was at node `(col + dcols,
        /// row + drows)`, bit for bit; the strip that comes in is calm. Positions and every world-unit
        /// call stay in the frame the surface was created in: node `(col, row)` rests at `origin +
        /// (col, row)·spacing` (`sw_surface_origin`). Values a caller set per node travel with the
        /// water; the boundary (pinned ring, absorbing frame) stays at the window's edge.
        /// `SW_ERROR_INVALID_ARGUMENT`, with nothing changed, if the window would go more than
        /// 15,728,640 cells from the frame's origin.</summary>
        [DllImport(Library, CallingConvention = CallingConvention.Cdecl, ExactSpelling = true)]
        public static extern int sw_surface_shift(IntPtr surface, int dcols, int drows);

        /// <summary>Shifts the window so that world `(x, z)` is back near its middle once the point has
        /// left a dead zone around the middle (an eighth of the shorter side, at least one cell, either
        /// side of the centre), and writes the shift made, `[dcols, drows]`, to `out[0..2]` (`[0, 0]`
        /// inside the dead zone). A non-finite point is `SW_ERROR_INVALID_ARGUMENT` and changes
        /// nothing.</summary>
        [DllImport(Library, CallingConvention = CallingConvention.Cdecl, ExactSpelling = true)]
        public static extern int sw_surface_follow(IntPtr surface, float x, float z, int* @out);

        /// <summary>The world `(x, z)` of node `(0, 0)`'s rest place, written to `out[0..2]`: `spacing`
        /// times the whole cells the window has travelled (`[0, 0]` until it moves).</summary>
        [DllImport(Library, CallingConvention = CallingConvention.Cdecl, ExactSpelling = true)]
        public static extern int sw_surface_origin(IntPtr surface, float* @out);

        /// <summary>Writes the whole cells the window has travelled, `[cols, rows]`, to `out[0..2]`
        /// (`sw_surface_origin` is this times `spacing`).</summary>
        [DllImport(Library, CallingConvention = CallingConvention.Cdecl, ExactSpelling = true)]
        public static extern int sw_surface_origin_cells(IntPtr surface, long* @out);

        /// <summary>Writes half the side of `sw_surface_follow`'s dead zone, in cells, to `out`.</summary>
        [DllImport(Library, CallingConvention = CallingConvention.Cdecl, ExactSpelling = true)]
        public static extern int sw_surface_follow_dead_zone(IntPtr surface, uint* @out);

        /// <summary>A floating origin: moves the frame the surface speaks `dcols` cells along +x and
        /// `drows` along +z, for a host that moved its own world's origin (round the host's offset to
        /// whole cells and put the remainder into the water's transform). Every node position, floater
        /// and world-unit call is afterwards measured from the new point, so coordinates far from the
        /// old origin become small again and keep full `float` resolution; heights and velocities do
        /// not change, and `sw_surface_origin` reads `spacing` times the cells less.
        /// `SW_ERROR_INVALID_ARGUMENT`, with nothing changed, if the window would be more than
        /// 15,728,640 cells from the new origin.</summary>
        [DllImport(Library, CallingConvention = CallingConvention.Cdecl, ExactSpelling = true)]
        public static extern int sw_surface_rebase(IntPtr surface, long dcols, long drows);

        /// <summary>Adds the force `(fx, fy, fz)` at world `(x, z)` for the next step, spread onto the
        /// four nodes around the point with the weights `sw_surface_height_at` reads with: what a
        /// floating body feels and what it pushes back agree. In the lattice's force units (mass units
        /// × world units per unit of model time²): a force in per-second² units goes in divided by
        /// `time_scale²`.</summary>
        [DllImport(Library, CallingConvention = CallingConvention.Cdecl, ExactSpelling = true)]
        public static extern int sw_surface_add_force_at(
            IntPtr surface,
            float x,
            float z,
            float fx,
            float fy,
            float fz);

        /// <summary>The water's height at world `(x, z)` (inside the rest footprint `[0,
        /// (cols−1)·spacing] × [0, (rows−1)·spacing]`), interpolated between nodes.</summary>
        [DllImport(Library, CallingConvention = CallingConvention.Cdecl, ExactSpelling = true)]
        public static extern int sw_surface_height_at(
            IntPtr surface,
            float x,
            float z,
            float* @out);

        /// <summary>The water's unit normal at world `(x, z)`, written to `out[0..3]`.</summary>
        [DllImport(Library, CallingConvention = CallingConvention.Cdecl, ExactSpelling = true)]
        public static extern int sw_surface_normal_at(
            IntPtr surface,
            float x,
            float z,
            float* @out);

        /// <summary>The water's velocity at world `(x, z)`, world units per second, written to
        /// `out[0..3]`.</summary>
        [DllImport(Library, CallingConvention = CallingConvention.Cdecl, ExactSpelling = true)]
        public static extern int sw_surface_velocity_at(
            IntPtr surface,
            float x,
            float z,
            float* @out);

        /// <summary>Samples the water at `count` points (`xz[2k]`, `xz[2k+1]` is point `k`), writing
        /// height, normal and velocity to `out[k]`; `out_len` (in elements) must be at least `count`.
        /// If any point is outside the footprint, nothing is written.</summary>
        [DllImport(Library, CallingConvention = CallingConvention.Cdecl, ExactSpelling = true)]
        public static extern int sw_surface_sample(
            IntPtr surface,
            float* xz,
            UIntPtr count,
            SwSample* @out,
            UIntPtr out_len);

        /// <summary>Samples the water at `count` points point by point (`xz[2k]`, `xz[2k+1]` is point
        /// `k`): where point `k` is on the water, `found[k]` is 1 and `out[k]` its height, normal and
        /// velocity; where it is off the window or not finite, `found[k]` is 0 and `out[k]` is calm
        /// water (height 0, normal up, velocity 0). Unlike [`sw_surface_sample`], one point off the
        /// water does not fail the others. `out_len` and `found_len` (in elements) must be at least
        /// `count`.</summary>
        [DllImport(Library, CallingConvention = CallingConvention.Cdecl, ExactSpelling = true)]
        public static extern int sw_surface_sample_each(
            IntPtr surface,
            float* xz,
            UIntPtr count,
            SwSample* @out,
            UIntPtr out_len,
            byte* found,
            UIntPtr found_len);

        /// <summary>Pins (`pinned` 1) or frees (0) a node; pinning zeroes its velocity.</summary>
        [DllImport(Library, CallingConvention = CallingConvention.Cdecl, ExactSpelling = true)]
        public static extern int sw_surface_set_pinned(IntPtr surface, UIntPtr node, int pinned);

        /// <summary>Writes 1 to `out` if the node is pinned, 0 if it is free.</summary>
        [DllImport(Library, CallingConvention = CallingConvention.Cdecl, ExactSpelling = true)]
        public static extern int sw_surface_is_pinned(IntPtr surface, UIntPtr node, int* @out);

        /// <summary>Writes every node's pin, 1 pinned or 0 free, to `out[0..nodes]`.</summary>
        [DllImport(Library, CallingConvention = CallingConvention.Cdecl, ExactSpelling = true)]
        public static extern int sw_surface_write_pinned(IntPtr surface, byte* @out, UIntPtr len);

        /// <summary>Sets a node's mass (> 0); refused if it would put `dt` past the critical
        /// timestep.</summary>
        [DllImport(Library, CallingConvention = CallingConvention.Cdecl, ExactSpelling = true)]
        public static extern int sw_surface_set_mass(IntPtr surface, UIntPtr node, float mass);

        /// <summary>Sets every node's mass from `masses[0..nodes]`, all checked before any
        /// changes.</summary>
        [DllImport(Library, CallingConvention = CallingConvention.Cdecl, ExactSpelling = true)]
        public static extern int sw_surface_set_masses(IntPtr surface, float* masses, UIntPtr len);

        /// <summary>Writes every node's mass to `out[0..nodes]`.</summary>
        [DllImport(Library, CallingConvention = CallingConvention.Cdecl, ExactSpelling = true)]
        public static extern int sw_surface_write_masses(IntPtr surface, float* @out, UIntPtr len);

        /// <summary>Sets a node's viscosity (≥ 0); refused if it would put `dt` past the critical
        /// timestep.</summary>
        [DllImport(Library, CallingConvention = CallingConvention.Cdecl, ExactSpelling = true)]
        public static extern int sw_surface_set_viscosity(IntPtr surface, UIntPtr node, float viscosity);

        /// <summary>Sets every node's viscosity from `viscosities[0..nodes]`, all checked before
        /// any changes.</summary>
        [DllImport(Library, CallingConvention = CallingConvention.Cdecl, ExactSpelling = true)]
        public static extern int sw_surface_set_viscosities(
            IntPtr surface,
            float* viscosities,
            UIntPtr len);

        /// <summary>Writes every node's viscosity, the absorbing frame's ramp included, to
        /// `out[0..nodes]`.</summary>
        [DllImport(Library, CallingConvention = CallingConvention.Cdecl, ExactSpelling = true)]
        public static extern int sw_surface_write_viscosities(IntPtr surface, float* @out, UIntPtr len);

        /// <summary>Writes the rest length and coefficient of the spring of `family` (`SW_FAMILY_*`)
        /// whose origin is `node` to `out[0..2]`.</summary>
        [DllImport(Library, CallingConvention = CallingConvention.Cdecl, ExactSpelling = true)]
        public static extern int sw_surface_spring(IntPtr surface, int family, UIntPtr node, float* @out);

        /// <summary>Sets the rest length (≥ 0) and coefficient (> 0) of the spring of `family`
        /// whose origin is `node`.</summary>
        [DllImport(Library, CallingConvention = CallingConvention.Cdecl, ExactSpelling = true)]
        public static extern int sw_surface_set_spring(
            IntPtr surface,
            int family,
            UIntPtr node,
            float rest,
            float stiffness);

        /// <summary>Adds the force `(fx, fy, fz)` to node `node` for the next step only, in the
        /// lattice's force units.</summary>
        [DllImport(Library, CallingConvention = CallingConvention.Cdecl, ExactSpelling = true)]
        public static extern int sw_surface_add_force(IntPtr surface, UIntPtr node, float fx, float fy, float fz);

        /// <summary>Discards every force waiting for the next step, the water's share of
        /// `sw_surface_body_forces` among them.</summary>
        [DllImport(Library, CallingConvention = CallingConvention.Cdecl, ExactSpelling = true)]
        public static extern int sw_surface_clear_forces(IntPtr surface);

        /// <summary>Adds the velocity change `(dvx, dvy, dvz)` to free node `node` now.</summary>
        [DllImport(Library, CallingConvention = CallingConvention.Cdecl, ExactSpelling = true)]
        public static extern int sw_surface_add_velocity(IntPtr surface, UIntPtr node, float dvx, float dvy, float dvz);

        /// <summary>Writes 1 to `out` if world `(x, z)` is finite and inside the rest footprint,
        /// where the queries answer, else 0.</summary>
        [DllImport(Library, CallingConvention = CallingConvention.Cdecl, ExactSpelling = true)]
        public static extern int sw_surface_contains(IntPtr surface, float x, float z, int* @out);

        /// <summary>Writes every node's position, interleaved `x, y, z`, row-major (node `(col, row)`
        /// at `3·(row·cols + col)`). `len` is in floats and must be at least `3 · nodes`.</summary>
        [DllImport(Library, CallingConvention = CallingConvention.Cdecl, ExactSpelling = true)]
        public static extern int sw_surface_write_positions(
            IntPtr surface,
            float* xyz,
            UIntPtr len);

        /// <summary>Computes every node's unit normal and writes them interleaved `x, y, z`, row-major.
        /// `len` is in floats and must be at least `3 · nodes`.</summary>
        [DllImport(Library, CallingConvention = CallingConvention.Cdecl, ExactSpelling = true)]
        public static extern int sw_surface_write_normals(IntPtr surface, float* xyz, UIntPtr len);

        /// <summary>Computes every node's bottom texture coordinate seen through the surface from the
        /// eye (Snell refraction onto the bottom plane; the texture spans the grid's rest footprint)
        /// and writes them interleaved `u, v`, row-major. `len` is in floats and must be at least `2 ·
        /// nodes`.</summary>
        [DllImport(Library, CallingConvention = CallingConvention.Cdecl, ExactSpelling = true)]
        public static extern int sw_surface_write_refraction_uvs(
            IntPtr surface,
            SwRefraction* refraction,
            float* uv,
            UIntPtr len);

        /// <summary>Computes normals and refraction coordinates and writes one packed `SwVertex` per
        /// node (position, normal, uv), row-major, in one pass: the vertex buffer a renderer uploads.
        /// `len` is in vertices and must be at least the node count.</summary>
        [DllImport(Library, CallingConvention = CallingConvention.Cdecl, ExactSpelling = true)]
        public static extern int sw_surface_write_vertices(
            IntPtr surface,
            SwRefraction* refraction,
            SwVertex* vertices,
            UIntPtr len);

        /// <summary>Replaces the LOD parameters (the next `sw_surface_update_lod` rebuilds the index
        /// buffer with them).</summary>
        [DllImport(Library, CallingConvention = CallingConvention.Cdecl, ExactSpelling = true)]
        public static extern int sw_surface_set_lod_params(IntPtr surface, SwLodParams* @params);

        /// <summary>Updates the view-dependent LOD index buffer for an eye at `(eye_x, eye_y, eye_z)`
        /// in the water's local space: patches get coarser with distance, neighbours differ by at most
        /// one level and are stitched (no cracks). Writes 1 to `changed` (optional) if the index buffer
        /// was rebuilt (upload it again), 0 if the previous one still holds.</summary>
        [DllImport(Library, CallingConvention = CallingConvention.Cdecl, ExactSpelling = true)]
        public static extern int sw_surface_update_lod(
            IntPtr surface,
            float eye_x,
            float eye_y,
            float eye_z,
            int* changed);

        /// <summary>Copies the LOD index buffer (triangles as 3 node indices each, counter-clockwise
        /// seen from +y) to `indices` and writes its length, in indices, to `count`. With `indices`
        /// NULL only `count` is written (ask the size first, Box2D style); a `len` smaller than the
        /// buffer is `SW_ERROR_BUFFER_TOO_SMALL`, with `count` still written. Before the first
        /// `sw_surface_update_lod` the buffer is empty.</summary>
        [DllImport(Library, CallingConvention = CallingConvention.Cdecl, ExactSpelling = true)]
        public static extern int sw_surface_lod_indices(
            IntPtr surface,
            uint* indices,
            UIntPtr len,
            UIntPtr* count);

        /// <summary>Writes a snapshot of the whole state (a versioned binary format with a checksum) to
        /// `buf` and its size in bytes to `size`. With `buf` NULL only `size` is written; a `len`
        /// smaller than the snapshot is `SW_ERROR_BUFFER_TOO_SMALL`, with `size` still
        /// written.</summary>
        [DllImport(Library, CallingConvention = CallingConvention.Cdecl, ExactSpelling = true)]
        public static extern int sw_surface_save(
            IntPtr surface,
            byte* buf,
            UIntPtr len,
            UIntPtr* size);

        /// <summary>Replaces the surface's state with a snapshot (`len` bytes at `buf`), keeping its
        /// job system, SIMD level and LOD parameters. A damaged snapshot is refused and nothing
        /// changes.</summary>
        [DllImport(Library, CallingConvention = CallingConvention.Cdecl, ExactSpelling = true)]
        public static extern int sw_surface_restore(IntPtr surface, byte* buf, UIntPtr len);

        /// <summary>Writes a 64-bit hash of everything that decides the surface's future (XXH3-64)
        /// to `out`: equal states give equal hashes on every SIMD level, thread count and
        /// platform.</summary>
        [DllImport(Library, CallingConvention = CallingConvention.Cdecl, ExactSpelling = true)]
        public static extern int sw_surface_state_hash(IntPtr surface, ulong* @out);

        /// <summary>Creates a surface from a snapshot (`len` bytes at `buf`) and writes its handle to
        /// `out`.</summary>
        [DllImport(Library, CallingConvention = CallingConvention.Cdecl, ExactSpelling = true)]
        public static extern int sw_surface_load(byte* buf, UIntPtr len, IntPtr* @out);

        /// <summary>Writes the kinetic and spring potential energy to `out`.</summary>
        [DllImport(Library, CallingConvention = CallingConvention.Cdecl, ExactSpelling = true)]
        public static extern int sw_surface_energy(IntPtr surface, SwEnergy* @out);

        /// <summary>Writes the SIMD level the surface runs to `out`.</summary>
        [DllImport(Library, CallingConvention = CallingConvention.Cdecl, ExactSpelling = true)]
        public static extern int sw_surface_simd_level(IntPtr surface, int* @out);

        /// <summary>Runs the surface at `level`, clamped to what the CPU has, and writes the level it
        /// will run to `ran` (optional). Results do not change by a bit; only the speed does.</summary>
        [DllImport(Library, CallingConvention = CallingConvention.Cdecl, ExactSpelling = true)]
        public static extern int sw_surface_set_simd_level(IntPtr surface, int level, int* ran);

        /// <summary>A sphere of `radius` and `mass` centred at `(x, y, z)`, at rest, with the default
        /// drag (0.25). Not checked here: `sw_surface_add_floater` checks it.</summary>
        [DllImport(Library, CallingConvention = CallingConvention.Cdecl, ExactSpelling = true)]
        public static extern SwFloater sw_floater_sphere(
            float radius,
            float mass,
            float x,
            float y,
            float z);

        /// <summary>A box of half extents `(half_x, half_y, half_z)` and `mass` centred at `(x, y, z)`,
        /// at rest, with the default drag (0.25). Not checked here: `sw_surface_add_floater` checks
        /// it.</summary>
        [DllImport(Library, CallingConvention = CallingConvention.Cdecl, ExactSpelling = true)]
        public static extern SwFloater sw_floater_box(
            float half_x,
            float half_y,
            float half_z,
            float mass,
            float x,
            float y,
            float z);

        /// <summary>The default gravity and water density.</summary>
        [DllImport(Library, CallingConvention = CallingConvention.Cdecl, ExactSpelling = true)]
        public static extern SwBuoyancy sw_buoyancy_default();

        /// <summary>Adds a floating body and writes its id to `id`. The body steps with every step and
        /// substep of the surface and is part of its snapshots. Refused (nothing changes) when a field
        /// is out of range or the shape code is unknown, or when the water under the bodies would need
        /// a smaller timestep than the surface's `dt` (a stiff waterline: large gravity times
        /// density).</summary>
        [DllImport(Library, CallingConvention = CallingConvention.Cdecl, ExactSpelling = true)]
        public static extern int sw_surface_add_floater(
            IntPtr surface,
            SwFloater* floater,
            ulong* id);

        /// <summary>Removes a floating body; its id stays unused. An unknown id is
        /// `SW_ERROR_NO_SUCH_FLOATER`.</summary>
        [DllImport(Library, CallingConvention = CallingConvention.Cdecl, ExactSpelling = true)]
        public static extern int sw_surface_remove_floater(IntPtr surface, ulong id);

        /// <summary>Writes a floating body's current state to `out`, whose `struct_size` must be
        /// `sizeof(SwFloater)` (or the call is `SW_ERROR_INVALID_ARGUMENT` and writes nothing). An
        /// unknown id is `SW_ERROR_NO_SUCH_FLOATER`.</summary>
        [DllImport(Library, CallingConvention = CallingConvention.Cdecl, ExactSpelling = true)]
        public static extern int sw_surface_floater(IntPtr surface, ulong id, SwFloater* @out);

        /// <summary>Deprecated: the earlier name of `sw_surface_floater`, which it calls (so `out` must
        /// say its size, as there).</summary>
        [DllImport(Library, CallingConvention = CallingConvention.Cdecl, ExactSpelling = true)]
        public static extern int sw_surface_get_floater(IntPtr surface, ulong id, SwFloater* @out);

        /// <summary>Replaces a floating body's state (teleport it, change its velocity, mass, drag or
        /// shape), checked like `sw_surface_add_floater`; `water_force` is ignored and keeps the body's
        /// current value. An unknown id is `SW_ERROR_NO_SUCH_FLOATER`. On error nothing
        /// changes.</summary>
        [DllImport(Library, CallingConvention = CallingConvention.Cdecl, ExactSpelling = true)]
        public static extern int sw_surface_set_floater(
            IntPtr surface,
            ulong id,
            SwFloater* floater);

        /// <summary>Adds the force `(fx, fy, fz)` to a floating body for the next step only (an engine,
        /// the wind, a player's push), in mass units × world units per second²; pushes add up until
        /// that step. Refused (nothing changes) when a component, or the sum with what was pushed
        /// before, is not finite. An unknown id is `SW_ERROR_NO_SUCH_FLOATER`.</summary>
        [DllImport(Library, CallingConvention = CallingConvention.Cdecl, ExactSpelling = true)]
        public static extern int sw_surface_push_floater(
            IntPtr surface,
            ulong id,
            float fx,
            float fy,
            float fz);

        /// <summary>Writes the number of floating bodies on the surface to `out`.</summary>
        [DllImport(Library, CallingConvention = CallingConvention.Cdecl, ExactSpelling = true)]
        public static extern int sw_surface_floater_count(IntPtr surface, UIntPtr* @out);

        /// <summary>Copies the ids of the surface's floating bodies, in the order they were added (ids
        /// increase along it), to `ids` and writes their number to `count`. With `ids` NULL only
        /// `count` is written (ask the size first); a `len` smaller than the number of bodies is
        /// `SW_ERROR_BUFFER_TOO_SMALL`, with `count` still written.</summary>
        [DllImport(Library, CallingConvention = CallingConvention.Cdecl, ExactSpelling = true)]
        public static extern int sw_surface_floater_ids(
            IntPtr surface,
            ulong* ids,
            UIntPtr len,
            UIntPtr* count);

        /// <summary>Writes the gravity and water density the surface's bodies float in to `out`, whose
        /// `struct_size` must be `sizeof(SwBuoyancy)` (or the call is `SW_ERROR_INVALID_ARGUMENT` and
        /// writes nothing).</summary>
        [DllImport(Library, CallingConvention = CallingConvention.Cdecl, ExactSpelling = true)]
        public static extern int sw_surface_buoyancy(IntPtr surface, SwBuoyancy* @out);

        /// <summary>Deprecated: the earlier name of `sw_surface_buoyancy`, which it calls (so `out`
        /// must say its size, as there).</summary>
        [DllImport(Library, CallingConvention = CallingConvention.Cdecl, ExactSpelling = true)]
        public static extern int sw_surface_get_buoyancy(IntPtr surface, SwBuoyancy* @out);

        /// <summary>Sets the gravity and water density for every body of the surface. Refused (nothing
        /// changes) when a field is out of range, or when bodies float and the stiffer waterline would
        /// need a smaller timestep than the surface's `dt`.</summary>
        [DllImport(Library, CallingConvention = CallingConvention.Cdecl, ExactSpelling = true)]
        public static extern int sw_surface_set_buoyancy(IntPtr surface, SwBuoyancy* buoyancy);

        /// <summary>An empty `SwBodyForces` with its size set, for `sw_surface_body_forces` to fill.</summary>
        [DllImport(Library, CallingConvention = CallingConvention.Cdecl, ExactSpelling = true)]
        public static extern SwBodyForces sw_body_forces_default();

        /// <summary>Validates a closed triangle mesh (`vertex_count` vertices of three floats,
        /// `triangle_count` triangles of three indices, counter-clockwise from outside) and writes a
        /// new hull handle to `out`.</summary>
        [DllImport(Library, CallingConvention = CallingConvention.Cdecl, ExactSpelling = true)]
        public static extern int sw_hull_create(
            float* xyz,
            UIntPtr vertex_count,
            uint* triangles,
            UIntPtr triangle_count,
            IntPtr* @out);

        /// <summary>Destroys a hull handle; the bodies made of it keep their mesh. NULL and a
        /// destroyed handle are no-ops.</summary>
        [DllImport(Library, CallingConvention = CallingConvention.Cdecl, ExactSpelling = true)]
        public static extern void sw_hull_destroy(IntPtr hull);

        /// <summary>Writes the hull's volume, cubic world units, to `out`.</summary>
        [DllImport(Library, CallingConvention = CallingConvention.Cdecl, ExactSpelling = true)]
        public static extern int sw_hull_volume(IntPtr hull, float* @out);

        /// <summary>Writes a body of the hull's shape, of `mass`, at `(x, y, z)`, at rest, upright,
        /// to `out` (whose `struct_size` must be set); its inertia is the hull's.</summary>
        [DllImport(Library, CallingConvention = CallingConvention.Cdecl, ExactSpelling = true)]
        public static extern int sw_floater_hull(
            IntPtr hull,
            float mass,
            float x,
            float y,
            float z,
            SwFloater* @out);

        /// <summary>Adds a body whose shape is `hull` (`floater->shape` is `SW_SHAPE_HULL`) and
        /// writes its id to `id`; the surface keeps the mesh.</summary>
        [DllImport(Library, CallingConvention = CallingConvention.Cdecl, ExactSpelling = true)]
        public static extern int sw_surface_add_hull_floater(
            IntPtr surface,
            IntPtr hull,
            SwFloater* floater,
            ulong* id);

        /// <summary>Adds the force `(fx, fy, fz)` acting at the world point `(x, y, z)` to a body for
        /// the next step only: a force and a torque about its centre of mass.</summary>
        [DllImport(Library, CallingConvention = CallingConvention.Cdecl, ExactSpelling = true)]
        public static extern int sw_surface_push_floater_at(
            IntPtr surface,
            ulong id,
            float fx,
            float fy,
            float fz,
            float x,
            float y,
            float z);

        /// <summary>Adds the torque `(tx, ty, tz)` about a body's centre of mass (world axes) for the
        /// next step only; pushes add up until that step.</summary>
        [DllImport(Library, CallingConvention = CallingConvention.Cdecl, ExactSpelling = true)]
        public static extern int sw_surface_push_floater_torque(
            IntPtr surface,
            ulong id,
            float tx,
            float ty,
            float tz);

        /// <summary>The water's force and torque on a sphere or box body another engine owns, over
        /// its coming tick of `seconds`, written to `out`; the water gets the opposite.</summary>
        [DllImport(Library, CallingConvention = CallingConvention.Cdecl, ExactSpelling = true)]
        public static extern int sw_surface_body_forces(
            IntPtr surface,
            SwFloater* floater,
            float seconds,
            SwBodyForces* @out);

        /// <summary>`sw_surface_body_forces` for a body whose shape is `hull`.</summary>
        [DllImport(Library, CallingConvention = CallingConvention.Cdecl, ExactSpelling = true)]
        public static extern int sw_surface_hull_body_forces(
            IntPtr surface,
            IntPtr hull,
            SwFloater* floater,
            float seconds,
            SwBodyForces* @out);

        /// <summary>An empty job system with its size set: fill in `worker_count`, the two callbacks
        /// and `user_context`, then hand it to `sw_surface_set_job_system`.</summary>
        [DllImport(Library, CallingConvention = CallingConvention.Cdecl, ExactSpelling = true)]
        public static extern SwJobSystem sw_job_system_default();

        /// <summary>Runs the surface's steps and its normals, refraction and vertex buffers on the
        /// host's job system (`jobs`), or on the library's built-in thread pool again when `jobs` is
        /// NULL. The job system is copied; its `user_context` must stay valid until the surface is
        /// destroyed or another job system is set.</summary>
        [DllImport(Library, CallingConvention = CallingConvention.Cdecl, ExactSpelling = true)]
        public static extern int sw_surface_set_job_system(IntPtr surface, SwJobSystem* jobs);

        /// <summary>Copies this thread's last error message into `buf` (at most `len` bytes including
        /// the terminating NUL; a longer message is cut) and returns the size the whole message needs,
        /// NUL included: 1 if no call on this thread has failed yet. With `buf` NULL or `len` 0 it only
        /// returns the size. Messages are UTF-8 and stay until the next failing call on the same
        /// thread.</summary>
        [DllImport(Library, CallingConvention = CallingConvention.Cdecl, ExactSpelling = true)]
        public static extern UIntPtr sw_last_error(byte* buf, UIntPtr len);

        /// <summary>A short, static, NUL-terminated name for a status code (`"SW_OK"`,
        /// `"SW_ERROR_NULL_POINTER"`, …; `"unknown status"` for any other value).</summary>
        [DllImport(Library, CallingConvention = CallingConvention.Cdecl, ExactSpelling = true)]
        public static extern IntPtr sw_status_name(int status);
    }
}
