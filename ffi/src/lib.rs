//! # springwater-ffi
//!
//! The C ABI of [springwater](https://docs.rs/springwater): a water surface simulated on
//! the CPU as a mass-spring lattice, for C, C++ and C# engines. Build it with
//! `cargo build --release -p springwater-ffi` and link `libspringwater_ffi.a`
//! (static) or `libspringwater_ffi.so` / `.dylib` / `springwater_ffi.dll` (dynamic);
//! include `ffi/include/springwater.h`, which cbindgen generates from this crate (a test
//! fails when the checked-in header is out of date).
//!
//! This crate is a thin layer over the library's public API: every function checks its
//! arguments, calls the Rust method of the same name and turns the result into a status.
//!
//! ## Conventions
//!
//! * **Handles.** A `SwSurface *` is opaque and never dereferenced by the library: it is a
//!   key into a table of live surfaces. NULL, destroyed and made-up handles give
//!   `SW_ERROR_INVALID_HANDLE` (or `SW_ERROR_NULL_POINTER`), never a crash. Different
//!   surfaces may be used from different threads at once; calls on one surface must not
//!   overlap (an overlapping call returns `SW_ERROR_BUSY` and changes nothing).
//! * **Status codes.** Every function that can fail returns an `SwStatus` (`int32_t`):
//!   `SW_OK` (0) or a negative `SW_ERROR_*` code. `sw_last_error` gives the calling
//!   thread's last message. A call that fails changes nothing.
//! * **Checked input.** Every pointer is checked for NULL (out-pointers documented as
//!   optional may be NULL), every buffer length against what the call writes, every
//!   float for finiteness, every enum value against its constants. No panic crosses the
//!   boundary: an internal failure is `SW_ERROR_INTERNAL`, and that surface should be
//!   destroyed.
//! * **Types for any language.** Enums and booleans are `int32_t` with `#define`d
//!   values; structs hold only integers, floats and pointers (C# `StructLayout.Sequential`
//!   maps them as they are); no varargs, no callbacks but the job system's.
//! * **Units.** World units for lengths and points (`x, z` in the water's local space, y
//!   up), and seconds for everything with time in it that a game sets or reads: frame
//!   times, velocities (per second), the uniform acceleration and the buoyancy's gravity
//!   (per second²), floating bodies' state and forces. `SwParams`' lattice constants
//!   (`mass`, `stiffness`, `viscosity`, `dt`) are in model time, and `time_scale` converts;
//!   forces pushed into the water (`sw_surface_add_force_at`) are in the lattice's force
//!   units. The same as the Rust API (docs/units.md).

mod floaters;
mod handle;
mod jobs;
mod status;

pub use floaters::*;
pub use handle::SwSurface;
pub use jobs::{
    sw_job_system_default, sw_surface_set_job_system, SwEnqueueTaskFn, SwFinishTaskFn, SwJobSystem,
    SwTaskFn,
};
pub use status::*;

use handle::Water;
use springwater::buffers::{fill_frame, Vertex, VertexBuffers};
use springwater::mesh::{compute_normals, LodMesh, LodParams, Normals};
use springwater::refraction::RefractionParams;
use springwater::{Boundary, Overflow, Params, SimdLevel, Surface};
use std::ffi::c_char;

/// What happens at the edge of the grid (`SW_BOUNDARY_*`; parameters read back with an
/// edge this version of the C ABI has no code for, which it cannot make, would say -1).
pub type SwBoundary = i32;
/// The outer ring of nodes is pinned: a pool with walls.
pub const SW_BOUNDARY_PINNED: SwBoundary = 0;
/// No node is pinned: the sheet floats freely.
pub const SW_BOUNDARY_FREE: SwBoundary = 1;
/// Open water: waves leave the patch instead of coming back. The outer ring of nodes is
/// pinned and the `SwParams::absorbing_width` rings inside it damp outgoing waves; the
/// frame lies inside the grid, so the undamped water is the
/// `(cols − 2·width) × (rows − 2·width)` middle.
pub const SW_BOUNDARY_ABSORBING: SwBoundary = 2;

/// An instruction set the engine can run (`SW_SIMD_*`). Every level gives the same bits.
pub type SwSimdLevel = i32;
/// No SIMD: the scalar reference loops.
pub const SW_SIMD_SCALAR: SwSimdLevel = 0;
/// SSE2 (every x86-64 CPU).
pub const SW_SIMD_SSE2: SwSimdLevel = 1;
/// AVX2.
pub const SW_SIMD_AVX2: SwSimdLevel = 2;
/// AVX-512F.
pub const SW_SIMD_AVX512: SwSimdLevel = 3;
/// The lane kernels on plain arrays, vectorised by the compiler (targets without a SIMD
/// level of their own).
pub const SW_SIMD_PORTABLE: SwSimdLevel = 4;
/// NEON (every AArch64 CPU).
pub const SW_SIMD_NEON: SwSimdLevel = 5;
/// WebAssembly SIMD128 (a `wasm32` build made with `+simd128`).
pub const SW_SIMD_SIMD128: SwSimdLevel = 6;

/// A boolean: 0 false, 1 true.
pub type SwBool = i32;

/// The model's parameters; `sw_params_default()` gives the seed's defaults.
#[repr(C)]
#[derive(Debug, Clone, Copy)]
pub struct SwParams {
    /// `sizeof(SwParams)`, set by `sw_params_default()`: calls that read or fill the struct
    /// refuse any other value (a struct not started from `sw_params_default()`, or built with
    /// a header of another version than the library's).
    pub struct_size: u32,
    /// Nodes per row (at least 2).
    pub cols: u32,
    /// Rows of nodes (at least 2).
    pub rows: u32,
    /// Rest distance between neighbouring nodes, in world units.
    pub spacing: f32,
    /// Mass of each node, mass units.
    pub mass: f32,
    /// Spring coefficient `c`, mass units per unit of model time².
    pub stiffness: f32,
    /// Viscosity `γ` (damping per unit of velocity), mass units per unit of model time.
    pub viscosity: f32,
    /// Timestep of one step, in model time (below the critical timestep).
    pub dt: f32,
    /// Rest length over initial length of every spring (below 1: the sheet is under
    /// tension and ripples travel).
    pub rest_ratio: f32,
    /// Model time per second of the caller's clock (how fast the water moves).
    pub time_scale: f32,
    /// Uniform acceleration on free nodes, x, world units per second² (default 0).
    pub acceleration_x: f32,
    /// Uniform acceleration on free nodes, y, world units per second² (default 0).
    pub acceleration_y: f32,
    /// Uniform acceleration on free nodes, z, world units per second² (default 0).
    pub acceleration_z: f32,
    /// `SW_BOUNDARY_PINNED`, `SW_BOUNDARY_FREE` or `SW_BOUNDARY_ABSORBING`.
    pub boundary: SwBoundary,
    /// Rings of damping of an `SW_BOUNDARY_ABSORBING` boundary, inside its pinned outer
    /// ring: at least 1, and the grid must be at least `2 · absorbing_width + 2` nodes
    /// across. 32 in `sw_params_default()`: the default width, which fits itself to grids
    /// under 98 nodes across (15 rings on 64², 3 on 16²) and reflects at most 1.2·10⁻³ of a
    /// ring wave's energy at 32 rings. Ignored by the other boundaries, which read it back
    /// as 32.
    pub absorbing_width: u32,
}

/// The view-dependent LOD index buffer's parameters; `sw_lod_params_default()` gives the
/// defaults.
#[repr(C)]
#[derive(Debug, Clone, Copy)]
pub struct SwLodParams {
    /// `sizeof(SwLodParams)`, set by `sw_lod_params_default()`: calls that read the struct refuse any
    /// other value (a struct not started from `sw_lod_params_default()`, or built with a header of
    /// another version than the library's).
    pub struct_size: u32,
    /// Patch size in cells, a power of two from 1 to 4096.
    pub patch_cells: u32,
    /// Number of levels, 1 to log2(patch_cells) + 1.
    pub levels: u32,
    /// Distance from the eye within which patches get full detail, in world units; each
    /// further level's range is twice the previous one's.
    pub first_range: f32,
    /// Relative distance past a range boundary before a patch changes level, 0 to 1.
    pub hysteresis: f32,
}

/// The eye and the bottom for the refraction texture coordinates;
/// `sw_refraction_default()` gives the defaults (set the eye).
#[repr(C)]
#[derive(Debug, Clone, Copy)]
pub struct SwRefraction {
    /// `sizeof(SwRefraction)`, set by `sw_refraction_default()`: calls that read the struct refuse any
    /// other value (a struct not started from `sw_refraction_default()`, or built with a header of
    /// another version than the library's).
    pub struct_size: u32,
    /// The eye in the water's local space, x.
    pub eye_x: f32,
    /// The eye, y (up).
    pub eye_y: f32,
    /// The eye, z.
    pub eye_z: f32,
    /// Depth of the flat bottom below the rest surface `y = 0` (at least 0).
    pub depth: f32,
    /// Index of refraction of the water (1 to 10; water 1.333).
    pub ior: f32,
}

/// One node's packed vertex: 8 floats, 32 bytes (position at byte 0, normal at 12, the
/// refracted bottom texture coordinate at 24). The layout of the library's `Vertex`.
#[repr(C)]
#[derive(Debug, Clone, Copy, Default, PartialEq)]
pub struct SwVertex {
    /// Position in the water's local space (y up).
    pub position: [f32; 3],
    /// Unit normal.
    pub normal: [f32; 3],
    /// Bottom texture coordinate seen through the surface.
    pub uv: [f32; 2],
}

const _: () = {
    assert!(std::mem::size_of::<SwVertex>() == std::mem::size_of::<Vertex>());
    assert!(std::mem::align_of::<SwVertex>() == std::mem::align_of::<Vertex>());
    assert!(std::mem::offset_of!(SwVertex, normal) == std::mem::offset_of!(Vertex, normal));
    assert!(std::mem::offset_of!(SwVertex, uv) == std::mem::offset_of!(Vertex, uv));
};

/// The water at one point: height, unit normal, velocity.
#[repr(C)]
#[derive(Debug, Clone, Copy, Default, PartialEq)]
pub struct SwSample {
    /// Height (y).
    pub height: f32,
    /// Unit normal, x y z.
    pub normal: [f32; 3],
    /// Velocity, x y z, world units per second.
    pub velocity: [f32; 3],
}

/// Kinetic and spring potential energy (a diagnostic).
#[repr(C)]
#[derive(Debug, Clone, Copy, Default)]
pub struct SwEnergy {
    /// Sum of ½ m |v|² over free nodes.
    pub kinetic: f64,
    /// Sum of ½ c (L − L0)² over all springs.
    pub potential: f64,
    /// Kinetic plus potential.
    pub total: f64,
}

/// The library's version, a static NUL-terminated string such as `"0.1.0"`.
#[no_mangle]
pub extern "C" fn sw_version() -> *const c_char {
    concat!(env!("CARGO_PKG_VERSION"), "\0").as_ptr().cast()
}

/// The seed's defaults on a 128 × 128 grid.
#[no_mangle]
pub extern "C" fn sw_params_default() -> SwParams {
    c_params(&Params::default())
}

/// The default LOD parameters.
#[no_mangle]
pub extern "C" fn sw_lod_params_default() -> SwLodParams {
    let p = LodParams::default();
    SwLodParams {
        struct_size: size_of::<SwLodParams>() as u32,
        patch_cells: p.patch_cells.min(u32::MAX as usize) as u32,
        levels: p.levels,
        first_range: p.first_range,
        hysteresis: p.hysteresis,
    }
}

/// The default bottom depth and index of refraction, with the eye at the origin.
#[no_mangle]
pub extern "C" fn sw_refraction_default() -> SwRefraction {
    let p = RefractionParams::default();
    SwRefraction {
        struct_size: size_of::<SwRefraction>() as u32,
        eye_x: 0.0,
        eye_y: 0.0,
        eye_z: 0.0,
        depth: p.depth,
        ior: p.ior,
    }
}

/// The widest SIMD level this CPU has (what a new surface runs, unless the environment
/// variable `SPRINGWATER_SIMD` says otherwise).
#[no_mangle]
pub extern "C" fn sw_simd_level_detect() -> SwSimdLevel {
    simd_code(SimdLevel::detect())
}

/// A static NUL-terminated name for a SIMD level (`"scalar"`, `"sse2"`, `"avx2"`,
/// `"avx512"`, `"portable"`, `"neon"`, `"simd128"`), or `"unknown"`.
#[no_mangle]
pub extern "C" fn sw_simd_level_name(level: SwSimdLevel) -> *const c_char {
    let name: &'static std::ffi::CStr = match simd_level(level) {
        Ok(SimdLevel::Scalar) => c"scalar",
        Ok(SimdLevel::Sse2) => c"sse2",
        Ok(SimdLevel::Avx2) => c"avx2",
        Ok(SimdLevel::Avx512) => c"avx512",
        Ok(SimdLevel::Portable) => c"portable",
        Ok(SimdLevel::Neon) => c"neon",
        Ok(SimdLevel::Simd128) => c"simd128",
        _ => c"unknown",
    };
    name.as_ptr()
}

/// Creates a flat surface at rest from `params` (validated: the message names the field
/// that is wrong) and writes its handle to `out`.
///
/// # Safety
///
/// `params` and `out` are NULL or valid pointers.
#[no_mangle]
pub unsafe extern "C" fn sw_surface_create(
    params: *const SwParams,
    out: *mut *mut SwSurface,
) -> SwStatus {
    guard(|| {
        // SAFETY: the caller gives NULL or a valid pointer.
        let params = unsafe { input(params, "params") }?;
        let out = out_ref(out, "out")?;
        let surface = Surface::new(rust_params(&params)?)?;
        *out = handle::insert(Water::new(surface));
        Ok(())
    })
}

/// Destroys a surface and frees everything it owns. NULL, and a handle already
/// destroyed, are no-ops.
#[no_mangle]
pub extern "C" fn sw_surface_destroy(surface: *mut SwSurface) {
    let _ = std::panic::catch_unwind(|| handle::remove(surface));
}

/// Writes the surface's parameters to `out`, whose `struct_size` must be
/// `sizeof(SwParams)` (start it from `sw_params_default()`, or set the field), or the call
/// is `SW_ERROR_INVALID_ARGUMENT` and writes nothing.
///
/// # Safety
///
/// `out` is NULL or points to a writable struct whose `struct_size` (its first field) is
/// initialised.
#[no_mangle]
pub unsafe extern "C" fn sw_surface_params(
    surface: *const SwSurface,
    out: *mut SwParams,
) -> SwStatus {
    // SAFETY: `out` is NULL or a writable `SwParams` with its size initialised (the
    // caller's promise), as `read_sized_into` asks.
    unsafe { read_sized_into(surface, out, |w| Ok(c_params(w.surface.params()))) }
}

/// Writes the number of nodes (`cols × rows`) to `out`: the length, in elements, of every
/// per-node buffer.
///
/// # Safety
///
/// `out` is NULL or a valid pointer.
#[no_mangle]
pub unsafe extern "C" fn sw_surface_node_count(
    surface: *const SwSurface,
    out: *mut usize,
) -> SwStatus {
    read_into(surface, out, |w| Ok(w.surface.node_count()))
}

/// Advances the water by one frame of the caller's clock: `frame_time` seconds (finite,
/// at least 0) go into the surface's accumulator, and every whole timestep it holds is
/// taken (a fixed-step clock: the same total time gives the same state, however it is cut
/// into frames). Writes the number of steps taken to `substeps` (optional, may be NULL):
/// 0 when the frame did not complete a step, at most the cap (`sw_surface_set_step_cap`).
/// A failing step stops the frame there, earlier steps stay applied.
///
/// # Safety
///
/// `substeps` is NULL or a valid pointer.
#[no_mangle]
pub unsafe extern "C" fn sw_surface_advance(
    surface: *mut SwSurface,
    frame_time: f32,
    substeps: *mut u32,
) -> SwStatus {
    guard(|| {
        let substeps = optional(substeps, "substeps")?;
        handle::with(surface, |w| {
            let taken = w.surface.advance(frame_time)?;
            if let Some(out) = substeps {
                *out = taken as u32;
            }
            Ok(())
        })
    })
}

/// Sets the most steps one `sw_surface_advance` call takes (1 to 10000; 16 by default)
/// and what happens to the steps a longer frame owes: `carry` 0 drops them (the water falls
/// behind the caller's clock, the default), 1 carries them into the following calls.
#[no_mangle]
pub extern "C" fn sw_surface_set_step_cap(
    surface: *mut SwSurface,
    max_steps: u32,
    carry: i32,
) -> SwStatus {
    guard(|| {
        let overflow = match carry {
            0 => Overflow::Drop,
            1 => Overflow::Carry,
            other => return Err(Failure::invalid(format!("carry is {other}, not 0 or 1"))),
        };
        handle::with(surface, |w| {
            Ok(w.surface.set_step_cap(max_steps, overflow)?)
        })
    })
}

/// Writes to `out` how far the caller's clock is past the water's last step, as a
/// fraction of a step in `[0, 1)`: what a renderer that blends the last two states uses.
///
/// # Safety
///
/// `out` is NULL or a valid pointer.
#[no_mangle]
pub unsafe extern "C" fn sw_surface_interpolation(
    surface: *const SwSurface,
    out: *mut f32,
) -> SwStatus {
    read_into(surface, out, |w| Ok(w.surface.interpolation()))
}

/// Advances `steps` steps of the model's timestep, several per pass over memory (bitwise
/// the same as one at a time). Stops at a failing step; the steps before it stay applied.
#[no_mangle]
pub extern "C" fn sw_surface_step(surface: *mut SwSurface, steps: u32) -> SwStatus {
    guard(|| handle::with(surface, |w| Ok(w.surface.step_n(steps as u64)?)))
}

/// Drops water at world `(x, z)`: adds `height · exp(−d²/radius²)` to the height of every
/// free node, `d` its rest distance from the point. `radius` > 0; a drop steeper than one
/// height per radius may fold the surface.
#[no_mangle]
pub extern "C" fn sw_surface_drop_at(
    surface: *mut SwSurface,
    x: f32,
    z: f32,
    height: f32,
    radius: f32,
) -> SwStatus {
    guard(|| handle::with(surface, |w| Ok(w.surface.drop_at(x, z, height, radius)?)))
}

/// Deprecated: the earlier name of `sw_surface_drop_at`, which it calls.
#[no_mangle]
pub extern "C" fn sw_surface_drop(
    surface: *mut SwSurface,
    x: f32,
    z: f32,
    height: f32,
    radius: f32,
) -> SwStatus {
    sw_surface_drop_at(surface, x, z, height, radius)
}

/// Moves the window `dcols` cells along +x and `drows` along +z (negative values go the
/// other way): node `(col, row)` afterwards is the water that was at node
/// `(col + dcols, row + drows)`, bit for bit; the strip that comes in is calm. Positions and
/// every world-unit call stay in the frame the surface was created in: node `(col, row)`
/// rests at `origin + (col, row)·spacing` (`sw_surface_origin`). Values a caller set per
/// node travel with the water; the boundary (pinned ring, absorbing frame) stays at the
/// window's edge. `SW_ERROR_INVALID_ARGUMENT`, with nothing changed, if the window would go
/// more than 15,728,640 cells from the frame's origin.
#[no_mangle]
pub extern "C" fn sw_surface_shift(surface: *mut SwSurface, dcols: i32, drows: i32) -> SwStatus {
    guard(|| handle::with(surface, |w| Ok(w.surface.shift(dcols, drows)?)))
}

/// Shifts the window so that world `(x, z)` is back near its middle once the point has
/// left a dead zone around the middle (an eighth of the shorter side, at least one cell,
/// either side of the centre), and writes the shift made, `[dcols, drows]`, to
/// `out[0..2]` (`[0, 0]` inside the dead zone). A non-finite point is
/// `SW_ERROR_INVALID_ARGUMENT` and changes nothing.
///
/// # Safety
///
/// `out` is NULL or points to 2 writable `int32_t`.
#[no_mangle]
pub unsafe extern "C" fn sw_surface_follow(
    surface: *mut SwSurface,
    x: f32,
    z: f32,
    out: *mut i32,
) -> SwStatus {
    guard(|| {
        // SAFETY: the caller gives 2 ints at `out`; checked before the window moves.
        let out = unsafe { out_slice(out, 2, "out") }?;
        let made = handle::with(surface, |w| Ok(w.surface.follow(x, z)?))?;
        out.copy_from_slice(&made);
        Ok(())
    })
}

/// The world `(x, z)` of node `(0, 0)`'s rest place, written to `out[0..2]`: `spacing`
/// times the whole cells the window has travelled (`[0, 0]` until it moves).
///
/// # Safety
///
/// `out` is NULL or points to 2 writable floats.
#[no_mangle]
pub unsafe extern "C" fn sw_surface_origin(surface: *const SwSurface, out: *mut f32) -> SwStatus {
    guard(|| {
        // SAFETY: the caller gives 2 floats at `out`.
        let out = unsafe { out_slice(out, 2, "out") }?;
        out.copy_from_slice(&handle::with(surface, |w| Ok(w.surface.origin()))?);
        Ok(())
    })
}

/// A floating origin: moves the frame the surface speaks `dcols` cells along +x and `drows`
/// along +z, for a host that moved its own world's origin (round the host's offset to whole
/// cells and put the remainder into the water's transform). Every node position, floater
/// and world-unit call is afterwards measured from the new point, so coordinates far from
/// the old origin become small again and keep full `float` resolution; heights and
/// velocities do not change, and `sw_surface_origin` reads `spacing` times the cells less.
/// `SW_ERROR_INVALID_ARGUMENT`, with nothing changed, if the window would be more than
/// 15,728,640 cells from the new origin.
#[no_mangle]
pub extern "C" fn sw_surface_rebase(surface: *mut SwSurface, dcols: i64, drows: i64) -> SwStatus {
    guard(|| handle::with(surface, |w| Ok(w.surface.rebase(dcols, drows)?)))
}

/// Adds the force `(fx, fy, fz)` at world `(x, z)` for the next step, spread onto the
/// four nodes around the point with the weights `sw_surface_height_at` reads with: what
/// a floating body feels and what it pushes back agree. In the lattice's force units
/// (mass units × world units per unit of model time²): a force in per-second² units
/// goes in divided by `time_scale²`.
#[no_mangle]
pub extern "C" fn sw_surface_add_force_at(
    surface: *mut SwSurface,
    x: f32,
    z: f32,
    fx: f32,
    fy: f32,
    fz: f32,
) -> SwStatus {
    guard(|| {
        handle::with(surface, |w| {
            Ok(w.surface.add_force_at(x, z, [fx, fy, fz])?)
        })
    })
}

/// The water's height at world `(x, z)` (inside the rest footprint
/// `[0, (cols−1)·spacing] × [0, (rows−1)·spacing]`), interpolated between nodes.
///
/// # Safety
///
/// `out` is NULL or a valid pointer.
#[no_mangle]
pub unsafe extern "C" fn sw_surface_height_at(
    surface: *const SwSurface,
    x: f32,
    z: f32,
    out: *mut f32,
) -> SwStatus {
    read_into(surface, out, |w| Ok(w.surface.height_at(x, z)?))
}

/// The water's unit normal at world `(x, z)`, written to `out[0..3]`.
///
/// # Safety
///
/// `out` is NULL or points to 3 writable floats.
#[no_mangle]
pub unsafe extern "C" fn sw_surface_normal_at(
    surface: *const SwSurface,
    x: f32,
    z: f32,
    out: *mut f32,
) -> SwStatus {
    guard(|| {
        // SAFETY: the caller gives 3 floats at `out`.
        let out = unsafe { out_slice(out, 3, "out") }?;
        handle::with(surface, |w| {
            out.copy_from_slice(&w.surface.normal_at(x, z)?.to_array());
            Ok(())
        })
    })
}

/// The water's velocity at world `(x, z)`, world units per second, written to `out[0..3]`.
///
/// # Safety
///
/// `out` is NULL or points to 3 writable floats.
#[no_mangle]
pub unsafe extern "C" fn sw_surface_velocity_at(
    surface: *const SwSurface,
    x: f32,
    z: f32,
    out: *mut f32,
) -> SwStatus {
    guard(|| {
        // SAFETY: the caller gives 3 floats at `out`.
        let out = unsafe { out_slice(out, 3, "out") }?;
        handle::with(surface, |w| {
            out.copy_from_slice(&w.surface.velocity_at(x, z)?.to_array());
            Ok(())
        })
    })
}

/// Samples the water at `count` points (`xz[2k]`, `xz[2k+1]` is point `k`), writing
/// height, normal and velocity to `out[k]`; `out_len` (in elements) must be at least
/// `count`. If any point is outside the footprint, nothing is written.
///
/// # Safety
///
/// `xz` points to `2 · count` floats and `out` to `out_len` writable `SwSample`s (either
/// may be NULL when `count` is 0).
#[no_mangle]
pub unsafe extern "C" fn sw_surface_sample(
    surface: *const SwSurface,
    xz: *const f32,
    count: usize,
    out: *mut SwSample,
    out_len: usize,
) -> SwStatus {
    guard(|| {
        let floats = count
            .checked_mul(2)
            .ok_or_else(|| Failure::invalid("count is too large"))?;
        // SAFETY: the caller gives `2·count` floats at `xz`.
        let xz = unsafe { in_slice(xz, floats, "xz") }?;
        need(out_len, count, "out")?;
        // SAFETY: the caller gives `out_len ≥ count` samples at `out`.
        let out = unsafe { out_slice(out, count, "out") }?;
        handle::with(surface, |w| {
            let q = &mut w.queries;
            q.points.clear();
            q.points.extend(xz.chunks_exact(2).map(|p| [p[0], p[1]]));
            w.surface.heights_at(&q.points, &mut q.heights)?;
            w.surface.normals_at(&q.points, &mut q.normals)?;
            w.surface.velocities_at(&q.points, &mut q.velocities)?;
            for (k, o) in out.iter_mut().enumerate() {
                *o = SwSample {
                    height: q.heights[k],
                    normal: q.normals[k].to_array(),
                    velocity: q.velocities[k].to_array(),
                };
            }
            Ok(())
        })
    })
}

/// Samples the water at `count` points point by point (`xz[2k]`, `xz[2k+1]` is point
/// `k`): where point `k` is on the water, `found[k]` is 1 and `out[k]` its height, normal
/// and velocity; where it is off the window or not finite, `found[k]` is 0 and `out[k]`
/// is calm water (height 0, normal up, velocity 0). Unlike [`sw_surface_sample`], one point
/// off the water does not fail the others. `out_len` and `found_len` (in elements) must be
/// at least `count`.
///
/// # Safety
///
/// `xz` points to `2 · count` floats, `out` to `out_len` writable `SwSample`s and `found`
/// to `found_len` writable bytes (any may be NULL when `count` is 0).
#[no_mangle]
pub unsafe extern "C" fn sw_surface_sample_each(
    surface: *const SwSurface,
    xz: *const f32,
    count: usize,
    out: *mut SwSample,
    out_len: usize,
    found: *mut u8,
    found_len: usize,
) -> SwStatus {
    guard(|| {
        let floats = count
            .checked_mul(2)
            .ok_or_else(|| Failure::invalid("count is too large"))?;
        // SAFETY: the caller gives `2·count` floats at `xz`.
        let xz = unsafe { in_slice(xz, floats, "xz") }?;
        need(out_len, count, "out")?;
        need(found_len, count, "found")?;
        // SAFETY: the caller gives `out_len ≥ count` samples at `out`.
        let out = unsafe { out_slice(out, count, "out") }?;
        // SAFETY: the caller gives `found_len ≥ count` bytes at `found`.
        let found = unsafe { out_slice(found, count, "found") }?;
        handle::with(surface, |w| {
            let q = &mut w.queries;
            q.points.clear();
            q.points.extend(xz.chunks_exact(2).map(|p| [p[0], p[1]]));
            w.surface.samples_at(&q.points, &mut q.each);
            for ((o, f), s) in out.iter_mut().zip(found.iter_mut()).zip(&q.each) {
                (*o, *f) = match s {
                    Some(s) => (
                        SwSample {
                            height: s.height,
                            normal: s.normal.to_array(),
                            velocity: s.velocity.to_array(),
                        },
                        1,
                    ),
                    None => (
                        SwSample {
                            height: 0.0,
                            normal: [0.0, 1.0, 0.0],
                            velocity: [0.0; 3],
                        },
                        0,
                    ),
                };
            }
            Ok(())
        })
    })
}

/// Writes every node's position, interleaved `x, y, z`, row-major (node `(col, row)` at
/// `3·(row·cols + col)`). `len` is in floats and must be at least `3 · nodes`.
///
/// # Safety
///
/// `xyz` is NULL or points to `len` writable floats.
#[no_mangle]
pub unsafe extern "C" fn sw_surface_write_positions(
    surface: *const SwSurface,
    xyz: *mut f32,
    len: usize,
) -> SwStatus {
    guard(|| {
        handle::with(surface, |w| {
            // SAFETY: the caller gives `len` floats at `xyz`.
            let out = unsafe { out_triples(xyz, len, w.surface.node_count(), "xyz") }?;
            Ok(w.surface.mesh_view().write_positions(out)?)
        })
    })
}

/// Computes every node's unit normal and writes them interleaved `x, y, z`, row-major.
/// `len` is in floats and must be at least `3 · nodes`.
///
/// # Safety
///
/// `xyz` is NULL or points to `len` writable floats.
#[no_mangle]
pub unsafe extern "C" fn sw_surface_write_normals(
    surface: *mut SwSurface,
    xyz: *mut f32,
    len: usize,
) -> SwStatus {
    guard(|| {
        handle::with(surface, |w| {
            // SAFETY: the caller gives `len` floats at `xyz`.
            let out = unsafe { out_triples(xyz, len, w.surface.node_count(), "xyz") }?;
            compute_normals(&w.surface.mesh_view(), &mut w.normals);
            let Normals { x, y, z } = &w.normals;
            for (o, ((x, y), z)) in out.iter_mut().zip(x.iter().zip(y).zip(z)) {
                *o = [*x, *y, *z];
            }
            Ok(())
        })
    })
}

/// Computes every node's bottom texture coordinate seen through the surface from the eye
/// (Snell refraction onto the bottom plane; the texture spans the grid's rest footprint)
/// and writes them interleaved `u, v`, row-major. `len` is in floats and must be at least
/// `2 · nodes`.
///
/// # Safety
///
/// `refraction` is NULL or valid; `uv` is NULL or points to `len` writable floats.
#[no_mangle]
pub unsafe extern "C" fn sw_surface_write_refraction_uvs(
    surface: *mut SwSurface,
    refraction: *const SwRefraction,
    uv: *mut f32,
    len: usize,
) -> SwStatus {
    guard(|| {
        // SAFETY: the caller gives NULL or a valid pointer.
        let (eye, params) = refraction_params(unsafe { input(refraction, "refraction") }?)?;
        handle::with(surface, |w| {
            let n = w.surface.node_count();
            need(len, n * 2, "uv")?;
            // SAFETY: the caller gives `len ≥ 2n` floats at `uv`.
            let out = unsafe { out_slice(uv.cast::<[f32; 2]>(), n, "uv") }?;
            let buffers = VertexBuffers {
                uvs: Some(out),
                ..Default::default()
            };
            Ok(fill_frame(&w.surface.mesh_view(), eye, &params, buffers)?)
        })
    })
}

/// Computes normals and refraction coordinates and writes one packed `SwVertex` per node
/// (position, normal, uv), row-major, in one pass: the vertex buffer a renderer uploads.
/// `len` is in vertices and must be at least the node count.
///
/// # Safety
///
/// `refraction` is NULL or valid; `vertices` is NULL or points to `len` writable vertices.
#[no_mangle]
pub unsafe extern "C" fn sw_surface_write_vertices(
    surface: *mut SwSurface,
    refraction: *const SwRefraction,
    vertices: *mut SwVertex,
    len: usize,
) -> SwStatus {
    guard(|| {
        // SAFETY: the caller gives NULL or a valid pointer.
        let (eye, params) = refraction_params(unsafe { input(refraction, "refraction") }?)?;
        handle::with(surface, |w| {
            let n = w.surface.node_count();
            need(len, n, "vertices")?;
            // SAFETY: the caller gives `len ≥ n` vertices; `SwVertex` has `Vertex`'s layout
            // (checked at compile time above).
            let out = unsafe { out_slice(vertices.cast::<Vertex>(), n, "vertices") }?;
            let view = w.surface.mesh_view();
            let buffers = VertexBuffers {
                vertices: Some(out),
                ..Default::default()
            };
            Ok(fill_frame(&view, eye, &params, buffers)?)
        })
    })
}

/// Replaces the LOD parameters (the next `sw_surface_update_lod` rebuilds the index
/// buffer with them).
///
/// # Safety
///
/// `params` is NULL or a valid pointer.
#[no_mangle]
pub unsafe extern "C" fn sw_surface_set_lod_params(
    surface: *mut SwSurface,
    params: *const SwLodParams,
) -> SwStatus {
    guard(|| {
        // SAFETY: the caller gives NULL or a valid pointer.
        let p = unsafe { input(params, "params") }?;
        let lod = LodMesh::new(
            LodParams::default()
                .with_patch_cells(p.patch_cells as usize)
                .with_levels(p.levels)
                .with_first_range(p.first_range)
                .with_hysteresis(p.hysteresis),
        )?;
        handle::with(surface, |w| {
            w.lod = lod;
            Ok(())
        })
    })
}

/// Updates the view-dependent LOD index buffer for an eye at `(eye_x, eye_y, eye_z)` in
/// the water's local space: patches get coarser with distance, neighbours differ by at
/// most one level and are stitched (no cracks). Writes 1 to `changed` (optional) if the
/// index buffer was rebuilt (upload it again), 0 if the previous one still holds.
///
/// # Safety
///
/// `changed` is NULL or a valid pointer.
#[no_mangle]
pub unsafe extern "C" fn sw_surface_update_lod(
    surface: *mut SwSurface,
    eye_x: f32,
    eye_y: f32,
    eye_z: f32,
    changed: *mut SwBool,
) -> SwStatus {
    guard(|| {
        let eye = finite_eye(eye_x, eye_y, eye_z)?;
        let changed = optional(changed, "changed")?;
        handle::with(surface, |w| {
            let rebuilt = w.lod.update(&w.surface.mesh_view(), eye);
            if let Some(out) = changed {
                *out = rebuilt as SwBool;
            }
            Ok(())
        })
    })
}

/// Copies the LOD index buffer (triangles as 3 node indices each, counter-clockwise seen
/// from +y) to `indices` and writes its length, in indices, to `count`. With `indices`
/// NULL only `count` is written (ask the size first, Box2D style); a `len` smaller than
/// the buffer is `SW_ERROR_BUFFER_TOO_SMALL`, with `count` still written. Before the first
/// `sw_surface_update_lod` the buffer is empty.
///
/// # Safety
///
/// `indices` is NULL or points to `len` writable `uint32_t`; `count` is NULL or valid.
#[no_mangle]
pub unsafe extern "C" fn sw_surface_lod_indices(
    surface: *const SwSurface,
    indices: *mut u32,
    len: usize,
    count: *mut usize,
) -> SwStatus {
    guard(|| {
        let count = out_ref(count, "count")?;
        handle::with(surface, |w| {
            let src = w.lod.indices();
            // SAFETY: `indices` is NULL or holds `len` indices.
            unsafe {
                write_sized(indices, len, count, src.len(), "indices", |out| {
                    out.copy_from_slice(src)
                })
            }
        })
    })
}

/// Writes a snapshot of the whole state (a versioned binary format with a checksum) to
/// `buf` and its size in bytes to `size`. With `buf` NULL only `size` is written; a `len`
/// smaller than the snapshot is `SW_ERROR_BUFFER_TOO_SMALL`, with `size` still written.
///
/// # Safety
///
/// `buf` is NULL or points to `len` writable bytes; `size` is NULL or valid.
#[no_mangle]
pub unsafe extern "C" fn sw_surface_save(
    surface: *const SwSurface,
    buf: *mut u8,
    len: usize,
    size: *mut usize,
) -> SwStatus {
    guard(|| {
        let size = out_ref(size, "size")?;
        handle::with(surface, |w| {
            let bytes = w.surface.to_bytes();
            // SAFETY: `buf` is NULL or holds `len` bytes.
            unsafe {
                write_sized(buf, len, size, bytes.len(), "buf", |out| {
                    out.copy_from_slice(&bytes)
                })
            }
        })
    })
}

/// Replaces the surface's state with a snapshot (`len` bytes at `buf`), keeping its job
/// system, SIMD level and LOD parameters. A damaged snapshot is refused and nothing
/// changes.
///
/// # Safety
///
/// `buf` is NULL or points to `len` readable bytes.
#[no_mangle]
pub unsafe extern "C" fn sw_surface_restore(
    surface: *mut SwSurface,
    buf: *const u8,
    len: usize,
) -> SwStatus {
    guard(|| {
        // SAFETY: the caller gives `len` bytes at `buf`.
        let bytes = unsafe { in_slice(buf, len, "buf") }?;
        handle::with(surface, |w| Ok(w.surface.restore(bytes)?))
    })
}

/// Creates a surface from a snapshot (`len` bytes at `buf`) and writes its handle to
/// `out`.
///
/// # Safety
///
/// `buf` is NULL or points to `len` readable bytes; `out` is NULL or valid.
#[no_mangle]
pub unsafe extern "C" fn sw_surface_load(
    buf: *const u8,
    len: usize,
    out: *mut *mut SwSurface,
) -> SwStatus {
    guard(|| {
        // SAFETY: the caller gives `len` bytes at `buf`.
        let bytes = unsafe { in_slice(buf, len, "buf") }?;
        let out = out_ref(out, "out")?;
        let surface = Surface::from_bytes(bytes)?;
        *out = handle::insert(Water::new(surface));
        Ok(())
    })
}

/// Writes the kinetic and spring potential energy to `out`.
///
/// # Safety
///
/// `out` is NULL or a valid pointer.
#[no_mangle]
pub unsafe extern "C" fn sw_surface_energy(
    surface: *const SwSurface,
    out: *mut SwEnergy,
) -> SwStatus {
    read_into(surface, out, |w| {
        let e = w.surface.energy();
        Ok(SwEnergy {
            kinetic: e.kinetic,
            potential: e.potential,
            total: e.total(),
        })
    })
}

/// Writes the SIMD level the surface runs to `out`.
///
/// # Safety
///
/// `out` is NULL or a valid pointer.
#[no_mangle]
pub unsafe extern "C" fn sw_surface_simd_level(
    surface: *const SwSurface,
    out: *mut SwSimdLevel,
) -> SwStatus {
    read_into(surface, out, |w| Ok(simd_code(w.surface.simd_level())))
}

/// Runs the surface at `level`, clamped to what the CPU has, and writes the level it will
/// run to `ran` (optional). Results do not change by a bit; only the speed does.
///
/// # Safety
///
/// `ran` is NULL or a valid pointer.
#[no_mangle]
pub unsafe extern "C" fn sw_surface_set_simd_level(
    surface: *mut SwSurface,
    level: SwSimdLevel,
    ran: *mut SwSimdLevel,
) -> SwStatus {
    guard(|| {
        let level = simd_level(level)?;
        let ran = optional(ran, "ran")?;
        handle::with(surface, |w| {
            let level = w.surface.set_simd_level(level);
            if let Some(out) = ran {
                *out = simd_code(level);
            }
            Ok(())
        })
    })
}

impl Water {
    fn new(surface: Surface) -> Self {
        Self {
            surface,
            lod: LodMesh::new(LodParams::default()).expect("the default LOD parameters are valid"),
            normals: Normals::new(),
            queries: Default::default(),
        }
    }
}

/// The body of every call that reads one value of a surface into `out`: the guard, the
/// out-pointer check, the handle lookup.
fn read_into<T>(
    surface: *const SwSurface,
    out: *mut T,
    read: impl FnOnce(&mut Water) -> Outcome<T>,
) -> SwStatus {
    guard(|| {
        let out = out_ref(out, "out")?;
        *out = handle::with(surface, read)?;
        Ok(())
    })
}

/// The one conversion of `Params` to `SwParams` (`sw_params_default`, `sw_surface_params`);
/// [`rust_params`] is its inverse: `rust_params(&c_params(p)) == Ok(*p)`.
fn c_params(p: &Params) -> SwParams {
    let (boundary, absorbing_width) = match p.boundary {
        Boundary::Pinned => (SW_BOUNDARY_PINNED, Boundary::ABSORBING_WIDTH),
        Boundary::Free => (SW_BOUNDARY_FREE, Boundary::ABSORBING_WIDTH),
        Boundary::Absorbing { width } => (SW_BOUNDARY_ABSORBING, width),
        // An edge a later library adds gets its own code here; until then it cannot be
        // built through this ABI.
        _ => (-1, Boundary::ABSORBING_WIDTH),
    };
    SwParams {
        struct_size: size_of::<SwParams>() as u32,
        cols: p.cols as u32,
        rows: p.rows as u32,
        spacing: p.spacing,
        mass: p.mass,
        stiffness: p.stiffness,
        viscosity: p.viscosity,
        dt: p.dt,
        rest_ratio: p.rest_ratio,
        time_scale: p.time_scale,
        acceleration_x: p.acceleration[0],
        acceleration_y: p.acceleration[1],
        acceleration_z: p.acceleration[2],
        boundary,
        // Validation bounds the width by the grid, so it fits.
        absorbing_width: u32::try_from(absorbing_width).unwrap_or(u32::MAX),
    }
}

/// The inverse of [`c_params`]; the library validates the result when it builds a surface.
fn rust_params(p: &SwParams) -> Outcome<Params> {
    let boundary = match p.boundary {
        SW_BOUNDARY_PINNED => Boundary::Pinned,
        SW_BOUNDARY_FREE => Boundary::Free,
        SW_BOUNDARY_ABSORBING => Boundary::Absorbing {
            width: p.absorbing_width as usize,
        },
        other => {
            return Err(Failure::invalid(format!(
                "boundary = {other} is invalid: use SW_BOUNDARY_PINNED (0), SW_BOUNDARY_FREE (1) \
                 or SW_BOUNDARY_ABSORBING (2)"
            )))
        }
    };
    Ok(Params::with_size(p.cols as usize, p.rows as usize)
        .with_spacing(p.spacing)
        .with_mass(p.mass)
        .with_stiffness(p.stiffness)
        .with_viscosity(p.viscosity)
        .with_dt(p.dt)
        .with_rest_ratio(p.rest_ratio)
        .with_time_scale(p.time_scale)
        .with_acceleration([p.acceleration_x, p.acceleration_y, p.acceleration_z])
        .with_boundary(boundary))
}

fn simd_code(level: SimdLevel) -> SwSimdLevel {
    match level {
        SimdLevel::Scalar => SW_SIMD_SCALAR,
        SimdLevel::Sse2 => SW_SIMD_SSE2,
        SimdLevel::Avx2 => SW_SIMD_AVX2,
        SimdLevel::Avx512 => SW_SIMD_AVX512,
        SimdLevel::Neon => SW_SIMD_NEON,
        SimdLevel::Simd128 => SW_SIMD_SIMD128,
        // The portable lanes, and any level a later version of the library adds (it
        // runs as fast as the portable lanes or faster, with the same bits).
        _ => SW_SIMD_PORTABLE,
    }
}

fn simd_level(code: SwSimdLevel) -> Outcome<SimdLevel> {
    match code {
        SW_SIMD_SCALAR => Ok(SimdLevel::Scalar),
        SW_SIMD_SSE2 => Ok(SimdLevel::Sse2),
        SW_SIMD_AVX2 => Ok(SimdLevel::Avx2),
        SW_SIMD_AVX512 => Ok(SimdLevel::Avx512),
        SW_SIMD_PORTABLE => Ok(SimdLevel::Portable),
        SW_SIMD_NEON => Ok(SimdLevel::Neon),
        SW_SIMD_SIMD128 => Ok(SimdLevel::Simd128),
        other => Err(Failure::invalid(format!(
            "SIMD level {other} is unknown: use SW_SIMD_SCALAR (0), SW_SIMD_SSE2 (1), \
             SW_SIMD_AVX2 (2), SW_SIMD_AVX512 (3), SW_SIMD_PORTABLE (4), SW_SIMD_NEON (5) \
             or SW_SIMD_SIMD128 (6)"
        ))),
    }
}

fn finite_eye(x: f32, y: f32, z: f32) -> Outcome<glam::Vec3> {
    let eye = glam::Vec3::new(x, y, z);
    if eye.is_finite() {
        Ok(eye)
    } else {
        Err(Failure::invalid(format!(
            "eye ({x}, {y}, {z}) is invalid: every coordinate must be finite"
        )))
    }
}

fn refraction_params(r: SwRefraction) -> Outcome<(glam::Vec3, RefractionParams)> {
    let eye = finite_eye(r.eye_x, r.eye_y, r.eye_z)?;
    let params = RefractionParams {
        depth: r.depth,
        ior: r.ior,
    };
    params.validate()?;
    Ok((eye, params))
}

/// Fails unless a buffer of `len` holds `needed`.
fn need(len: usize, needed: usize, what: &str) -> Outcome {
    if len >= needed {
        Ok(())
    } else {
        Err(Failure::new(
            SW_ERROR_BUFFER_TOO_SMALL,
            format!("{what} holds {len}, the call needs {needed}"),
        ))
    }
}

/// A struct the caller fills and hands to the library. Its first field is `struct_size`,
/// which must be `sizeof` the struct of this library's version.
pub(crate) trait Input: Copy {
    /// The function that makes one with its size set.
    const MAKER: &'static str;
}

impl Input for SwParams {
    const MAKER: &'static str = "sw_params_default()";
}

impl Input for SwLodParams {
    const MAKER: &'static str = "sw_lod_params_default()";
}

impl Input for SwRefraction {
    const MAKER: &'static str = "sw_refraction_default()";
}

const _: () = {
    assert!(std::mem::offset_of!(SwParams, struct_size) == 0);
    assert!(std::mem::offset_of!(SwLodParams, struct_size) == 0);
    assert!(std::mem::offset_of!(SwRefraction, struct_size) == 0);
};

/// Copies the struct the caller passed at `ptr` after checking it: not NULL, aligned, and
/// its `struct_size` this version's ([`sized`]).
///
/// # Safety
///
/// `ptr` is NULL or points to a readable struct that starts with a `u32` size.
pub(crate) unsafe fn input<T: Input>(ptr: *const T, what: &str) -> Outcome<T> {
    // SAFETY: as the caller promises.
    unsafe { sized(ptr, what) }?;
    // SAFETY: the caller's struct is as large as this version's (its size says so).
    Ok(unsafe { ptr.read() })
}

/// Checks that the struct at `ptr` is not NULL, is aligned, and says in its `struct_size`
/// that it is as large as this version's. The size is read alone, so that a smaller
/// struct (from an older header) is never read or written past its end.
///
/// # Safety
///
/// `ptr` is NULL or points to a readable struct that starts with a `u32` size.
unsafe fn sized<T: Input>(ptr: *const T, what: &str) -> Outcome {
    aligned(ptr, what)?;
    if ptr.is_null() {
        return Err(Failure::null(what));
    }
    // SAFETY: non-NULL and aligned; every `Input` struct starts with its `u32` size.
    let size = unsafe { ptr.cast::<u32>().read() };
    let want = size_of::<T>();
    if size as usize != want {
        return Err(Failure::invalid(format!(
            "{what}->struct_size is {size}, this library's struct is {want} bytes: start it \
             from {} or set it to sizeof the struct (a header of another version than the \
             library's gives another size)",
            T::MAKER
        )));
    }
    Ok(())
}

/// The body of every call that writes a sized struct (one with `struct_size` first) to
/// `out`: like [`read_into`], and the caller's struct must first say it is this version's
/// size, so that a caller built against another header is never written past its end.
///
/// # Safety
///
/// `out` is NULL or points to a writable struct that starts with an initialised `u32` size.
pub(crate) unsafe fn read_sized_into<T: Input>(
    surface: *const SwSurface,
    out: *mut T,
    read: impl FnOnce(&mut Water) -> Outcome<T>,
) -> SwStatus {
    guard(|| {
        // SAFETY: as the caller promises.
        unsafe { sized(out.cast_const(), "out") }?;
        let out = out_ref(out, "out")?;
        *out = handle::with(surface, read)?;
        Ok(())
    })
}

/// An out-pointer the call must write.
fn out_ref<'a, T>(ptr: *mut T, what: &str) -> Outcome<&'a mut T> {
    aligned(ptr, what)?;
    // SAFETY: non-NULL and aligned (checked); the caller gives a valid pointer.
    unsafe { ptr.as_mut() }.ok_or_else(|| Failure::null(what))
}

/// An optional out-pointer: NULL means "not wanted".
fn optional<'a, T>(ptr: *mut T, what: &str) -> Outcome<Option<&'a mut T>> {
    aligned(ptr, what)?;
    // SAFETY: aligned (checked); the caller gives a valid pointer or NULL.
    Ok(unsafe { ptr.as_mut() })
}

fn aligned<T>(ptr: *const T, what: &str) -> Outcome {
    if ptr.is_null() || ptr.align_offset(std::mem::align_of::<T>()) == 0 {
        Ok(())
    } else {
        Err(Failure::invalid(format!(
            "{what} ({ptr:p}) is not aligned to {} bytes",
            std::mem::align_of::<T>()
        )))
    }
}

/// `len` elements at `ptr`, read only. NULL is allowed for `len` 0.
///
/// # Safety
///
/// `ptr` is NULL or points to `len` readable elements.
unsafe fn in_slice<'a, T>(ptr: *const T, len: usize, what: &str) -> Outcome<&'a [T]> {
    if len == 0 {
        return Ok(&[]);
    }
    if ptr.is_null() {
        return Err(Failure::null(what));
    }
    aligned(ptr, what)?;
    too_long::<T>(len, what)?;
    // SAFETY: non-NULL, aligned, not too long for a slice; the caller gives `len` elements.
    Ok(unsafe { std::slice::from_raw_parts(ptr, len) })
}

/// A result of variable size, the C way: `*count = n`; a NULL `ptr` only asks for the
/// size, otherwise `len` must hold `n` elements and `fill` writes them.
///
/// # Safety
///
/// `ptr` is NULL or points to `len` writable elements.
unsafe fn write_sized<T>(
    ptr: *mut T,
    len: usize,
    count: &mut usize,
    n: usize,
    what: &str,
    fill: impl FnOnce(&mut [T]),
) -> Outcome {
    *count = n;
    if ptr.is_null() {
        return Ok(());
    }
    need(len, n, what)?;
    // SAFETY: the caller gives `len ≥ n` elements at `ptr`.
    let out = unsafe { out_slice(ptr, n, what) }?;
    fill(out);
    Ok(())
}

/// `len` writable elements at `ptr`. NULL is allowed for `len` 0.
///
/// # Safety
///
/// `ptr` is NULL or points to `len` writable elements.
unsafe fn out_slice<'a, T>(ptr: *mut T, len: usize, what: &str) -> Outcome<&'a mut [T]> {
    if len == 0 {
        return Ok(&mut []);
    }
    if ptr.is_null() {
        return Err(Failure::null(what));
    }
    aligned(ptr, what)?;
    too_long::<T>(len, what)?;
    // SAFETY: non-NULL, aligned, not too long for a slice; the caller gives `len` elements.
    Ok(unsafe { std::slice::from_raw_parts_mut(ptr, len) })
}

/// `n` writable `[x, y, z]` triples at `ptr`, whose buffer holds `len` floats.
///
/// # Safety
///
/// `ptr` is NULL or points to `len` writable floats.
unsafe fn out_triples<'a>(
    ptr: *mut f32,
    len: usize,
    n: usize,
    what: &str,
) -> Outcome<&'a mut [[f32; 3]]> {
    need(len, n * 3, what)?;
    // SAFETY: the caller gives `len ≥ 3n` floats; `[f32; 3]` has the alignment of `f32`.
    unsafe { out_slice(ptr.cast::<[f32; 3]>(), n, what) }
}

fn too_long<T>(len: usize, what: &str) -> Outcome {
    match len.checked_mul(std::mem::size_of::<T>().max(1)) {
        Some(bytes) if bytes <= isize::MAX as usize => Ok(()),
        _ => Err(Failure::invalid(format!(
            "{what}: length {len} is too large"
        ))),
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn params_convert_both_ways_for_every_boundary() {
        for boundary in [
            Boundary::Pinned,
            Boundary::Free,
            Boundary::absorbing(),
            Boundary::Absorbing { width: 5 },
        ] {
            let p = Params::with_size(40, 30)
                .with_boundary(boundary)
                .with_acceleration([0.5, -1.0, 0.25]);
            assert_eq!(rust_params(&c_params(&p)).unwrap(), p, "{boundary:?}");
        }
        let d = sw_params_default();
        assert_eq!(
            (d.boundary, d.absorbing_width),
            (SW_BOUNDARY_PINNED, Boundary::ABSORBING_WIDTH as u32)
        );
        let open = SwParams {
            boundary: SW_BOUNDARY_ABSORBING,
            ..d
        };
        assert_eq!(rust_params(&open).unwrap().boundary, Boundary::absorbing());
        let unknown = SwParams { boundary: 3, ..d };
        assert!(rust_params(&unknown).is_err());
    }
}
