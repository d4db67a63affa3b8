//! Rigid bodies from C beyond spheres and boxes: hull meshes (`SwHull`), pushes at a
//! point and torques, and the water's force and torque on a body another physics engine owns
//! (`sw_surface_body_forces`, the library's `Surface::body_forces`).
//!
//! A hull is a handle, made once from the game's mesh and shared by every body of that
//! hull: the mesh is validated and its mass properties computed once, a surface's bodies
//! and `sw_surface_hull_body_forces` hold it without copying its triangles every tick, and
//! the client frees it when it no longer makes bodies of it (the bodies keep their own
//! reference, so destroying a hull never changes a body).

use crate::floaters::{c_floater, rust_floater, SwFloater, SwFloaterId, SW_SHAPE_HULL};
use crate::handle::{self, Registry, SwSurface};
use crate::ptr::{in_slice, input_over, out_ref, sized_out, Input};
use crate::status::{guard, Failure, Outcome, SwStatus, SW_ERROR_INVALID_HANDLE};
use springwater::body::Hull;
use springwater::{Floater, FloaterId};
use std::sync::Arc;

/// A closed triangle mesh for floating bodies (opaque). Create it with `sw_hull_create`,
/// free it with `sw_hull_destroy`.
pub struct SwHull {
    _opaque: [u8; 0],
}

/// The water's push on a body over one tick (`sw_surface_body_forces`), in the world frame:
/// mass units × world units per second², the torque about the body's centre of mass
/// (`SwFloater::position`). `sw_body_forces_default()` makes one to fill.
#[repr(C)]
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct SwBodyForces {
    /// `sizeof(SwBodyForces)`, set by `sw_body_forces_default()`: the calls that fill the
    /// struct refuse any other value.
    pub struct_size: u32,
    /// The force through the centre of mass: buoyancy and drag (gravity is the engine's).
    pub force: [f32; 3],
    /// The torque about the centre of mass, world axes.
    pub torque: [f32; 3],
}

impl Input for SwBodyForces {
    const MAKER: &'static str = "sw_body_forces_default()";
}

const _: () = assert!(std::mem::offset_of!(SwBodyForces, struct_size) == 0);

pub(crate) static HULLS: Registry<Hull> = Registry::new();

/// The hull behind `hull`.
pub(crate) fn hull_of(hull: *const SwHull) -> Outcome<Arc<Hull>> {
    if hull.is_null() {
        return Err(Failure::null("hull"));
    }
    HULLS.get(hull as usize).ok_or_else(|| {
        Failure::new(
            SW_ERROR_INVALID_HANDLE,
            format!("hull handle {hull:p} is not a live hull (never created, or destroyed)"),
        )
    })
}

/// The body `floater` describes, with the mesh of `hull`; its shape must say so.
fn hull_floater(hull: *const SwHull, floater: *const SwFloater) -> Outcome<Floater> {
    let hull = hull_of(hull)?;
    let body = input_over(floater, "floater", SwFloater::NEW)?;
    if body.shape != SW_SHAPE_HULL {
        return Err(Failure::invalid(format!(
            "floater shape = {} with a hull: a hull body says SW_SHAPE_HULL (2); \
             sw_floater_hull makes one",
            body.shape
        )));
    }
    rust_floater(body, Some(hull))
}

/// An empty `SwBodyForces` with its size set, for `sw_surface_body_forces` to fill.
#[no_mangle]
pub extern "C" fn sw_body_forces_default() -> SwBodyForces {
    SwBodyForces {
        struct_size: size_of::<SwBodyForces>() as u32,
        force: [0.0; 3],
        torque: [0.0; 3],
    }
}

/// Validates a closed triangle mesh and writes a new hull handle to `out`. `xyz` holds
/// `vertex_count` vertices, three floats each, in the body's frame (world units, the body's
/// centre of mass at the origin); `triangles` holds `triangle_count` triangles, three
/// vertex indices each, counter-clockwise seen from outside. Refused with the defect named
/// (`SW_ERROR_INVALID_ARGUMENT`): 4 to 65,536 triangles, finite coordinates of at most 1e9,
/// indices in range, no degenerate triangle, closed (every edge shared by two triangles
/// running along it in opposite directions; vertices at the same position count as one),
/// wound outward (positive volume), a positive definite inertia.
///
/// # Safety
///
/// `xyz` is NULL or points to `3 * vertex_count` floats, `triangles` NULL or to
/// `3 * triangle_count` indices; `out` is NULL or a valid pointer.
#[no_mangle]
pub unsafe extern "C" fn sw_hull_create(
    xyz: *const f32,
    vertex_count: usize,
    triangles: *const u32,
    triangle_count: usize,
    out: *mut *mut SwHull,
) -> SwStatus {
    guard(|| {
        // `[T; 3]` has the size of three elements and the alignment of one.
        let vertices = in_slice(xyz.cast::<[f32; 3]>(), vertex_count, "xyz")?;
        let triangles = in_slice(triangles.cast::<[u32; 3]>(), triangle_count, "triangles")?;
        let out = out_ref(out, "out")?;
        let hull = Hull::new(vertices, triangles)?;
        *out = HULLS.insert(hull) as *mut SwHull;
        Ok(())
    })
}

/// Destroys a hull handle. The bodies made of it keep their mesh. NULL, and a handle
/// already destroyed, are no-ops.
#[no_mangle]
pub extern "C" fn sw_hull_destroy(hull: *mut SwHull) {
    let _ = std::panic::catch_unwind(|| HULLS.remove(hull as usize));
}

/// Writes the hull's volume, in cubic world units, to `out`: a body of the hull at
/// `fraction` of the water's density has mass `fraction * density * volume`.
///
/// # Safety
///
/// `out` is NULL or a valid pointer.
#[no_mangle]
pub unsafe extern "C" fn sw_hull_volume(hull: *const SwHull, out: *mut f32) -> SwStatus {
    guard(|| {
        let out = out_ref(out, "out")?;
        *out = hull_of(hull)?.volume();
        Ok(())
    })
}

/// Writes a body of the hull's shape, of `mass`, with its origin at `(x, y, z)`, at rest,
/// upright, with the default drag, to `out` (whose `struct_size` must be
/// `sizeof(SwFloater)`): shape `SW_SHAPE_HULL`, and `inertia` the hull's at uniform density
/// for `mass`. Not checked here but the handle: `sw_surface_add_hull_floater` checks it.
///
/// # Safety
///
/// `out` is NULL or points to a writable struct whose `struct_size` (its first field) is
/// initialised.
#[no_mangle]
pub unsafe extern "C" fn sw_floater_hull(
    hull: *const SwHull,
    mass: f32,
    x: f32,
    y: f32,
    z: f32,
    out: *mut SwFloater,
) -> SwStatus {
    guard(|| {
        sized_out(out, || {
            let hull = hull_of(hull)?;
            Ok(c_floater(&Floater::with_hull(hull, mass, [x, y, z])))
        })
    })
}

/// Adds a floating body whose shape is `hull` and writes its id to `id`; `floater` says
/// the rest (its shape must be `SW_SHAPE_HULL`: start it from `sw_floater_hull`). The
/// surface keeps the mesh for the body: the hull handle may be destroyed afterwards.
/// Refused (nothing changes) as `sw_surface_add_floater` is, and when the hull is more
/// than 64 cells across.
///
/// # Safety
///
/// `floater` and `id` are NULL or valid pointers.
#[no_mangle]
pub unsafe extern "C" fn sw_surface_add_hull_floater(
    surface: *mut SwSurface,
    hull: *const SwHull,
    floater: *const SwFloater,
    id: *mut SwFloaterId,
) -> SwStatus {
    guard(|| {
        let body = hull_floater(hull, floater)?;
        let id = out_ref(id, "id")?;
        *id = handle::with(surface, |w| Ok(w.surface.add_floater(body)?.to_raw()))?;
        Ok(())
    })
}

/// Adds the force `(fx, fy, fz)` acting at the world point `(x, y, z)` to a floating body
/// for the next step only: the force through its centre of mass and the torque
/// `(point − position) × force` (a push on the bow turns the boat). Refused (nothing
/// changes) when a number, or a sum with what was pushed before, is not finite. An unknown
/// id is `SW_ERROR_NO_SUCH_FLOATER`.
#[allow(clippy::too_many_arguments)]
#[no_mangle]
pub extern "C" fn sw_surface_push_floater_at(
    surface: *mut SwSurface,
    id: SwFloaterId,
    fx: f32,
    fy: f32,
    fz: f32,
    x: f32,
    y: f32,
    z: f32,
) -> SwStatus {
    handle::call(surface, |w| {
        let id = FloaterId::from_raw(id);
        Ok(w.surface.push_floater_at(id, [fx, fy, fz], [x, y, z])?)
    })
}

/// Adds the torque `(tx, ty, tz)` about a floating body's centre of mass (world axes; mass
/// units × world units² per second²) for the next step only: a rudder, a player's twist.
/// Pushes add up until that step. Refused (nothing changes) when a component, or the sum
/// with what was pushed before, is not finite. An unknown id is
/// `SW_ERROR_NO_SUCH_FLOATER`.
#[no_mangle]
pub extern "C" fn sw_surface_push_floater_torque(
    surface: *mut SwSurface,
    id: SwFloaterId,
    tx: f32,
    ty: f32,
    tz: f32,
) -> SwStatus {
    handle::call(surface, |w| {
        let id = FloaterId::from_raw(id);
        Ok(w.surface.push_floater_torque(id, [tx, ty, tz])?)
    })
}

/// The water's force and torque on a sphere or box body another physics engine owns
/// (`floater`, which the surface does not keep), over the engine's coming tick of
/// `seconds`, written to `out` (whose `struct_size` must be `sizeof(SwBodyForces)`). The
/// body's shape, mass, inertia, drag, pose and velocities count; its pushes and read-only
/// fields are ignored. The water gets the opposite of both, where each part of the hull
/// meets it, in its next step: call this once per tick and body.
///
/// The forces are taken implicitly over the tick for the velocities the body will have at
/// its end, so an engine that applies them with an explicit step of the same `seconds`,
/// mass and inertia (`SwFloater::inertia` as read back) gets the stable step of a built-in
/// body, however light the body: keep `seconds` equal to the engine's tick, and the
/// surface's `SwBuoyancy::gravity` equal to the engine's. Refused (nothing changes): an
/// invalid body (as `sw_surface_add_floater`; `SW_SHAPE_HULL` goes through
/// `sw_surface_hull_body_forces`), `seconds` not above 0 and at most 1, or reactions the
/// water cannot hold.
///
/// # Safety
///
/// `floater` is NULL or a valid pointer; `out` is NULL or points to a writable struct
/// whose `struct_size` (its first field) is initialised.
#[no_mangle]
pub unsafe extern "C" fn sw_surface_body_forces(
    surface: *mut SwSurface,
    floater: *const SwFloater,
    seconds: f32,
    out: *mut SwBodyForces,
) -> SwStatus {
    body_forces(
        surface,
        || rust_floater(input_over(floater, "floater", SwFloater::NEW)?, None),
        seconds,
        out,
    )
}

/// `sw_surface_body_forces` for a body whose shape is `hull` (`floater`'s shape must be
/// `SW_SHAPE_HULL`).
///
/// # Safety
///
/// `floater` is NULL or a valid pointer; `out` is NULL or points to a writable struct
/// whose `struct_size` (its first field) is initialised.
#[no_mangle]
pub unsafe extern "C" fn sw_surface_hull_body_forces(
    surface: *mut SwSurface,
    hull: *const SwHull,
    floater: *const SwFloater,
    seconds: f32,
    out: *mut SwBodyForces,
) -> SwStatus {
    body_forces(surface, || hull_floater(hull, floater), seconds, out)
}

/// The body of both `body_forces` calls: the body `body` gives, then the surface.
fn body_forces(
    surface: *mut SwSurface,
    body: impl FnOnce() -> Outcome<Floater>,
    seconds: f32,
    out: *mut SwBodyForces,
) -> SwStatus {
    guard(|| {
        let body = body()?;
        sized_out(out, || {
            handle::with(surface, |w| {
                let push = w.surface.body_forces(&body, seconds)?;
                Ok(SwBodyForces {
                    force: push.force.to_array(),
                    torque: push.torque.to_array(),
                    ..sw_body_forces_default()
                })
            })
        })
    })
}
