//! The water at points: the height, normal and velocity under a point, one at a time or
//! in batches, and a force pushed into the water at a point (spread with the same weights
//! the queries read with).

use crate::handle::{self, Queries, SwSurface};
use crate::params::SwBool;
use crate::ptr::{in_slice, need, out_array, out_buffer, out_slice, read_into};
use crate::status::{guard, Failure, Outcome, SwStatus};
use glam::Vec3;
use springwater::Surface;

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
    handle::call(surface, |w| {
        Ok(w.surface.add_force_at(x, z, [fx, fy, fz])?)
    })
}

/// Writes 1 to `out` if world `(x, z)` is finite and inside the rest footprint
/// `[0, (cols−1)·spacing] × [0, (rows−1)·spacing]` (moved with the window), where the
/// queries answer, else 0.
///
/// # Safety
///
/// `out` is NULL or a valid pointer.
#[no_mangle]
pub unsafe extern "C" fn sw_surface_contains(
    surface: *const SwSurface,
    x: f32,
    z: f32,
    out: *mut SwBool,
) -> SwStatus {
    read_into(surface, out, |w| Ok(w.surface.contains(x, z) as SwBool))
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
    vector_at(surface, out, |s| s.normal_at(x, z))
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
    vector_at(surface, out, |s| s.velocity_at(x, z))
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
        let xz = points(xz, count)?;
        let out = out_buffer(out, out_len, count, "out")?;
        handle::with(surface, |w| {
            let q = load(&mut w.queries, xz);
            w.surface.heights_at(&q.points, &mut q.heights)?;
            w.surface.normals_at(&q.points, &mut q.normals)?;
            w.surface.velocities_at(&q.points, &mut q.velocities)?;
            for (k, o) in out.iter_mut().enumerate() {
                *o = c_sample(q.heights[k], q.normals[k], q.velocities[k]);
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
        let xz = points(xz, count)?;
        need(out_len, count, "out")?;
        need(found_len, count, "found")?;
        let out = out_slice(out, count, "out")?;
        let found = out_slice(found, count, "found")?;
        handle::with(surface, |w| {
            let q = load(&mut w.queries, xz);
            w.surface.samples_at(&q.points, &mut q.each);
            for ((o, f), s) in out.iter_mut().zip(found.iter_mut()).zip(&q.each) {
                (*o, *f) = match s {
                    Some(s) => (c_sample(s.height, s.normal, s.velocity), 1),
                    None => (c_sample(0.0, Vec3::Y, Vec3::ZERO), 0),
                };
            }
            Ok(())
        })
    })
}

/// The body of the calls that write one vector of the water at a point to `out[0..3]`.
fn vector_at(
    surface: *const SwSurface,
    out: *mut f32,
    query: impl FnOnce(&Surface) -> springwater::Result<Vec3>,
) -> SwStatus {
    guard(|| {
        let out = out_array(out, "out")?;
        handle::with(surface, |w| {
            *out = query(&w.surface)?.to_array();
            Ok(())
        })
    })
}

/// The `2 · count` floats of `count` points `x, z` at `xz`.
fn points<'a>(xz: *const f32, count: usize) -> Outcome<&'a [f32]> {
    let floats = count
        .checked_mul(2)
        .ok_or_else(|| Failure::invalid("count is too large"))?;
    in_slice(xz, floats, "xz")
}

/// The batch buffers with `xz`'s points in them.
fn load<'q>(q: &'q mut Queries, xz: &[f32]) -> &'q mut Queries {
    q.points.clear();
    q.points.extend(xz.chunks_exact(2).map(|p| [p[0], p[1]]));
    q
}

fn c_sample(height: f32, normal: Vec3, velocity: Vec3) -> SwSample {
    SwSample {
        height,
        normal: normal.to_array(),
        velocity: velocity.to_array(),
    }
}
