//! Parameters: the structs a caller fills in before a call (the model's `SwParams`, the LOD
//! and refraction settings), the codes of the edges and SIMD levels, their defaults, and
//! the conversions to and from the library's types. Also what a caller may ask before it
//! has a surface: the library's version and the CPU's SIMD level.

use crate::ptr::{input, out_ref, Input};
use crate::status::{guard, Failure, Outcome, SwStatus};
use springwater::mesh::LodParams;
use springwater::refraction::RefractionParams;
use springwater::{Boundary, Params, SimdLevel};
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
    c_lod_params(&LodParams::default())
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

/// The widest SIMD level this CPU has: what a new surface runs until
/// `sw_surface_set_simd_level` chooses another (the library never reads the environment).
#[no_mangle]
pub extern "C" fn sw_simd_level_detect() -> SwSimdLevel {
    simd_code(SimdLevel::detect())
}

/// 1 if this CPU (and this build) can run SIMD `level`, else 0 (an unknown level too):
/// what `sw_surface_set_simd_level` runs without clamping.
#[no_mangle]
pub extern "C" fn sw_simd_level_available(level: SwSimdLevel) -> i32 {
    simd_level(level).is_ok_and(SimdLevel::is_available) as i32
}

/// Writes to `out` the guaranteed (large-wave) stability limit of `params`: `sqrt(m / 3c)`
/// without viscosity, a little less with it. `params` is checked like `sw_surface_create`
/// checks it, except that its `dt` may be above the limit.
///
/// # Safety
///
/// `params` and `out` are NULL or valid pointers.
#[no_mangle]
pub unsafe extern "C" fn sw_params_critical_dt(params: *const SwParams, out: *mut f32) -> SwStatus {
    params_limit(params, out, Params::critical_dt)
}

/// Writes to `out` the linear stability limit at rest of `params`,
/// `sqrt(m / (c (3 − rest_ratio)))`: the largest `dt` for which small waves on still water
/// stay bounded. `params` is checked as for `sw_params_critical_dt`.
///
/// # Safety
///
/// `params` and `out` are NULL or valid pointers.
#[no_mangle]
pub unsafe extern "C" fn sw_params_linear_dt_limit(
    params: *const SwParams,
    out: *mut f32,
) -> SwStatus {
    params_limit(params, out, Params::linear_dt_limit)
}

/// Writes to `out` how fast ripples travel on a surface of `params`, world units per
/// second: `time_scale · spacing · sqrt(3c (1 − rest_ratio) / m)`. `params` is checked as
/// for `sw_params_critical_dt`.
///
/// # Safety
///
/// `params` and `out` are NULL or valid pointers.
#[no_mangle]
pub unsafe extern "C" fn sw_params_ripple_speed(
    params: *const SwParams,
    out: *mut f32,
) -> SwStatus {
    params_limit(params, out, Params::ripple_speed)
}

/// Sets `params->time_scale` so that ripples travel `speed` world units per second (finite
/// and above 0), leaving every other field as it is. `params` is checked as for
/// `sw_params_critical_dt`; refused (`SW_ERROR_INVALID_ARGUMENT`, the struct unchanged) when
/// the speed is not finite and positive, when the other fields give ripples no speed to
/// scale (`rest_ratio` 1), or when the time scale it needs is out of range.
///
/// # Safety
///
/// `params` is NULL or a valid pointer.
#[no_mangle]
pub unsafe extern "C" fn sw_params_set_ripple_speed(params: *mut SwParams, speed: f32) -> SwStatus {
    guard(|| {
        let given = input(params.cast_const(), "params")?;
        let mut rust = rust_params(&given)?;
        rust.validate_except_dt()?;
        rust.set_ripple_speed(speed)?;
        out_ref(params, "params")?.time_scale = rust.time_scale;
        Ok(())
    })
}

/// Writes to `out` the most levels `params->patch_cells` allows, `log2(patch_cells) + 1`:
/// the largest `levels` `sw_surface_set_lod_params` takes with it. The other fields but
/// `levels` are checked as `sw_surface_set_lod_params` checks them.
///
/// # Safety
///
/// `params` and `out` are NULL or valid pointers.
#[no_mangle]
pub unsafe extern "C" fn sw_lod_params_max_levels(
    params: *const SwLodParams,
    out: *mut u32,
) -> SwStatus {
    guard(|| {
        let params = rust_lod_params(&input(params, "params")?);
        let out = out_ref(out, "out")?;
        // One level is always allowed: the check is then of the other fields.
        params.with_levels(1).validate()?;
        *out = params.max_levels();
        Ok(())
    })
}

/// Writes to `out` Schlick's reflectance at normal incidence of the water in `refraction`,
/// `((ior − 1) / (ior + 1))²`: the `R0` of a shader's Fresnel term. `refraction` is checked
/// as `sw_surface_write_refraction_uvs` checks it.
///
/// # Safety
///
/// `refraction` and `out` are NULL or valid pointers.
#[no_mangle]
pub unsafe extern "C" fn sw_refraction_r0(
    refraction: *const SwRefraction,
    out: *mut f32,
) -> SwStatus {
    guard(|| {
        let refraction = input(refraction, "refraction")?;
        let out = out_ref(out, "out")?;
        let (_, params) = refraction_params(refraction)?;
        *out = params.r0();
        Ok(())
    })
}

/// `limit` of the parameters at `params`, written to `out`.
fn params_limit(params: *const SwParams, out: *mut f32, limit: fn(&Params) -> f32) -> SwStatus {
    guard(|| {
        let params = input(params, "params")?;
        let out = out_ref(out, "out")?;
        let params = rust_params(&params)?;
        params.validate_except_dt()?;
        *out = limit(&params);
        Ok(())
    })
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

/// The one conversion of `Params` to `SwParams` (`sw_params_default`, `sw_surface_params`);
/// [`rust_params`] is its inverse: `rust_params(&c_params(p)) == Ok(*p)`.
pub(crate) fn c_params(p: &Params) -> SwParams {
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
pub(crate) fn rust_params(p: &SwParams) -> Outcome<Params> {
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

/// The one conversion of `LodParams` to `SwLodParams` (`sw_lod_params_default`,
/// `sw_surface_lod_params`); [`rust_lod_params`] is its inverse.
pub(crate) fn c_lod_params(p: &LodParams) -> SwLodParams {
    SwLodParams {
        struct_size: size_of::<SwLodParams>() as u32,
        // Validation bounds the patch size by 4096, so it fits.
        patch_cells: p.patch_cells.min(u32::MAX as usize) as u32,
        levels: p.levels,
        first_range: p.first_range,
        hysteresis: p.hysteresis,
    }
}

/// The inverse of [`c_lod_params`]; the library validates the result when it takes it.
pub(crate) fn rust_lod_params(p: &SwLodParams) -> LodParams {
    LodParams::default()
        .with_patch_cells(p.patch_cells as usize)
        .with_levels(p.levels)
        .with_first_range(p.first_range)
        .with_hysteresis(p.hysteresis)
}

pub(crate) fn simd_code(level: SimdLevel) -> SwSimdLevel {
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

pub(crate) fn simd_level(code: SwSimdLevel) -> Outcome<SimdLevel> {
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

/// Fails unless `value` is finite and above 0, naming it `what`.
pub(crate) fn finite_positive(what: &str, value: f32) -> Outcome {
    if value.is_finite() && value > 0.0 {
        Ok(())
    } else {
        Err(Failure::invalid(format!(
            "{what} is {value}, expected a finite number > 0"
        )))
    }
}

pub(crate) fn finite_eye(x: f32, y: f32, z: f32) -> Outcome<glam::Vec3> {
    let eye = glam::Vec3::new(x, y, z);
    if eye.is_finite() {
        Ok(eye)
    } else {
        Err(Failure::invalid(format!(
            "eye ({x}, {y}, {z}) is invalid: every coordinate must be finite"
        )))
    }
}

pub(crate) fn refraction_params(r: SwRefraction) -> Outcome<(glam::Vec3, RefractionParams)> {
    let eye = finite_eye(r.eye_x, r.eye_y, r.eye_z)?;
    let params = RefractionParams {
        depth: r.depth,
        ior: r.ior,
    };
    params.validate()?;
    Ok((eye, params))
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
