//! Floating bodies from C: rigid spheres, boxes and hulls that pitch, roll and ride the
//! waves and push back into them (the library's `Floater`, whose docs explain the model).
//! Units are the game's: world units for lengths, the lattice's mass units, seconds for
//! time (velocities per second, angular velocities radians per second, gravity and forces
//! per second², the drag rate per second), as in the Rust API. Hull meshes and the forces
//! on bodies another engine owns are in `bodies.rs`.

use crate::handle::{self, SwSurface};
use crate::params::SwBool;
use crate::ptr::{
    copy_list_into, input, input_over, out_array, out_ref, read_into, read_sized_into, Input,
};
use crate::status::{guard, Failure, Outcome, SwStatus};
use glam::{Mat3, Quat, Vec3};
use springwater::body::Hull;
use springwater::{Buoyancy, Floater, FloaterId, Shape};
use std::sync::Arc;

/// The shape of a floating body (`SW_SHAPE_*`; a body read back with a shape this version
/// of the C ABI has no code for, which it cannot make, would say -1).
pub type SwShape = i32;
/// A ball of `SwFloater::radius`.
pub const SW_SHAPE_SPHERE: SwShape = 0;
/// A box of `SwFloater::half_extents`, its faces along the body's axes.
pub const SW_SHAPE_BOX: SwShape = 1;
/// A closed triangle mesh (`SwHull`): added with `sw_surface_add_hull_floater`, which
/// keeps the mesh with the surface; a hull body read back says this code, and
/// `sw_surface_set_floater` with it keeps the body's mesh.
pub const SW_SHAPE_HULL: SwShape = 2;

/// A floating body's id on its surface, never reused by that surface (also not after the
/// body is removed, or across a snapshot).
pub type SwFloaterId = u64;

/// A floating body, a rigid body with six degrees of freedom: `sw_floater_sphere()`,
/// `sw_floater_box()` and `sw_floater_hull()` make one at rest, upright, with the default
/// drag. Plain data: hand it to `sw_surface_add_floater` (`sw_surface_add_hull_floater`),
/// read it back with `sw_surface_floater`; or keep it in your own engine and ask
/// `sw_surface_body_forces` for the water's push.
///
/// The struct grows at its end between versions. `struct_size` says which one the caller
/// has: this version's, or `SW_FLOATER_SIZE_V1` (80 bytes: up to `water_force`, the
/// bodies that did not rotate). A version 1 struct is still taken: the fields it lacks are
/// the defaults for a new body (upright, no spin, no torque, the shape's inertia) and the
/// body's current values for `sw_surface_set_floater`; reading one back fills only the
/// fields it has.
#[repr(C)]
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct SwFloater {
    /// `sizeof(SwFloater)`, set by `sw_floater_sphere()`, `sw_floater_box()`,
    /// `sw_floater_hull()` and `sw_surface_floater()`: calls that read or fill the struct
    /// refuse any other value but `SW_FLOATER_SIZE_V1` (a struct not started from one of
    /// them, or built with a header of another version than the library's).
    pub struct_size: u32,
    /// `SW_SHAPE_SPHERE`, `SW_SHAPE_BOX` or `SW_SHAPE_HULL`.
    pub shape: SwShape,
    /// The sphere's radius, world units (> 0, at most 1e9). Ignored for other shapes, read
    /// back as 0.
    pub radius: f32,
    /// The box's half size along its x, y and z, world units (each > 0, at most 1e9).
    /// Ignored for other shapes, read back as 0.
    pub half_extents: [f32; 3],
    /// Mass, in the lattice's mass units (> 0; a node has `SwParams::mass`).
    pub mass: f32,
    /// Drag rate, per second (0 to 1e8; default 6): the drag is this times the mass of the
    /// displaced water times the velocity relative to the water.
    pub drag: f32,
    /// Centre of mass in the water's local space (the calm surface is y = 0), world units
    /// (each component at most 1e15 in magnitude); a hull's origin.
    pub position: [f32; 3],
    /// Velocity of the centre of mass, world units per second (each component at most 1e11
    /// in magnitude; default 0).
    pub velocity: [f32; 3],
    /// External force through the centre of mass (an engine, the wind, a player's push) for
    /// the next step only, cleared by it; `sw_surface_push_floater` and
    /// `sw_surface_push_floater_at` add to it. Mass units × world units per second², finite
    /// (default 0).
    pub push: [f32; 3],
    /// Read only: the force the water exerted on the body during its last step (buoyancy and
    /// drag, without gravity and push), mass units × world units per second²; the water got
    /// exactly minus this (in its own units, divided by `time_scale²`). Ignored on input:
    /// a body added starts at 0, a body set keeps its current value.
    pub water_force: [f32; 3],
    /// Orientation, body to world, as a unit quaternion `(x, y, z, w)` (its squared norm
    /// within 1e-3 of 1; the surface keeps it normalised). Default `(0, 0, 0, 1)`, upright.
    pub orientation: [f32; 4],
    /// Angular velocity, radians per second about the world's axes (each component at most
    /// 1e6 in magnitude; default 0).
    pub angular_velocity: [f32; 3],
    /// External torque about the centre of mass, world axes, for the next step only,
    /// cleared by it; `sw_surface_push_floater_at` adds to it. Finite (default 0).
    pub push_torque: [f32; 3],
    /// Read only: the torque about the centre of mass the water exerted on the body during
    /// its last step; the water got exactly minus this. Ignored on input, like
    /// `water_force`.
    pub water_torque: [f32; 3],
    /// 1: `inertia` is the body's inertia tensor; 0 (the default): the shape's at uniform
    /// density. Any other value is refused.
    pub has_inertia: SwBool,
    /// The inertia tensor about the centre of mass in the body's axes, mass × world units²,
    /// column by column (`inertia[3 * col + row]`; it is symmetric). Read only when
    /// `has_inertia` is 1: symmetric, positive definite, each principal moment at
    /// most the sum of the other two. Read back, it is the tensor in use (the shape's for
    /// the body's mass when `has_inertia` is 0): what an engine integrating the
    /// body itself must use.
    pub inertia: [f32; 9],
}

/// `sizeof(SwFloater)` in version 1 of the header (up to `water_force`), which the calls
/// still take: see `SwFloater`.
pub const SW_FLOATER_SIZE_V1: u32 = 80;

/// The world the bodies of a surface float in; `sw_buoyancy_default()` gives the defaults.
#[repr(C)]
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct SwBuoyancy {
    /// `sizeof(SwBuoyancy)`, set by `sw_buoyancy_default()` and `sw_surface_buoyancy()`:
    /// calls that read or fill the struct refuse any other value (a struct not started from
    /// one of them, or built with a header of another version than the library's).
    pub struct_size: u32,
    /// Gravity pulling bodies down (−y), world units per second² (0 to 1e9; default 57.6,
    /// which is 0.1 per unit of model time² at the default time scale of 24).
    pub gravity: f32,
    /// Density of the water, mass units per cubic world unit (0 to 1e6; default 1: the
    /// seed's node mass 4 per cell is a layer 4 cells deep).
    pub density: f32,
}

/// All zeros but `struct_size`, which is this version's, and the
/// orientation, upright: a struct ready for `sw_surface_floater` to fill (from Rust; C
/// starts one with `{.struct_size = sizeof f}`).
impl Default for SwFloater {
    fn default() -> Self {
        Self::NEW
    }
}

/// All zeros but `struct_size`, which is this version's: a struct ready for
/// `sw_surface_buoyancy` to fill.
impl Default for SwBuoyancy {
    fn default() -> Self {
        Self {
            struct_size: size_of::<Self>() as u32,
            gravity: 0.0,
            density: 0.0,
        }
    }
}

impl Input for SwFloater {
    const MAKER: &'static str = "sw_floater_sphere(), sw_floater_box() or sw_floater_hull()";
    const EARLIER: &'static [usize] = &[SW_FLOATER_SIZE_V1 as usize];
}

impl Input for SwBuoyancy {
    const MAKER: &'static str = "sw_buoyancy_default()";
}

const _: () = {
    assert!(std::mem::offset_of!(SwFloater, struct_size) == 0);
    // Version 1 ends where the rigid bodies' fields begin.
    assert!(std::mem::offset_of!(SwFloater, orientation) == SW_FLOATER_SIZE_V1 as usize);
    assert!(std::mem::offset_of!(SwBuoyancy, struct_size) == 0);
};

/// A sphere of `radius` and `mass` centred at `(x, y, z)`, at rest, upright, with the
/// default drag (6 per second). Not checked here: `sw_surface_add_floater` checks it.
#[no_mangle]
pub extern "C" fn sw_floater_sphere(radius: f32, mass: f32, x: f32, y: f32, z: f32) -> SwFloater {
    c_floater(&Floater::sphere(radius, mass, [x, y, z]))
}

/// A box of half extents `(half_x, half_y, half_z)` and `mass` centred at `(x, y, z)`, at
/// rest, upright, with the default drag (6 per second). Not checked here:
/// `sw_surface_add_floater` checks it.
#[no_mangle]
pub extern "C" fn sw_floater_box(
    half_x: f32,
    half_y: f32,
    half_z: f32,
    mass: f32,
    x: f32,
    y: f32,
    z: f32,
) -> SwFloater {
    c_floater(&Floater::cuboid([half_x, half_y, half_z], mass, [x, y, z]))
}

/// The default gravity and water density.
#[no_mangle]
pub extern "C" fn sw_buoyancy_default() -> SwBuoyancy {
    c_buoyancy(Buoyancy::default())
}

/// Adds a floating body and writes its id to `id`. The body steps with every step and
/// substep of the surface and is part of its snapshots. Refused (nothing changes) when a
/// field is out of range, the shape code is unknown or `SW_SHAPE_HULL` (a hull body is
/// added with `sw_surface_add_hull_floater`), or when the water under the bodies would need
/// a smaller timestep than the surface's `dt` (a stiff waterline: large gravity times
/// density).
///
/// # Safety
///
/// `floater` and `id` are NULL or valid pointers.
#[no_mangle]
pub unsafe extern "C" fn sw_surface_add_floater(
    surface: *mut SwSurface,
    floater: *const SwFloater,
    id: *mut SwFloaterId,
) -> SwStatus {
    guard(|| {
        let body = rust_floater(input_over(floater, "floater", SwFloater::NEW)?, None)?;
        let id = out_ref(id, "id")?;
        *id = handle::with(surface, |w| Ok(w.surface.add_floater(body)?.to_raw()))?;
        Ok(())
    })
}

/// Removes a floating body; its id stays unused. An unknown id is
/// `SW_ERROR_NO_SUCH_FLOATER`.
#[no_mangle]
pub extern "C" fn sw_surface_remove_floater(surface: *mut SwSurface, id: SwFloaterId) -> SwStatus {
    handle::call(surface, |w| {
        w.surface.remove_floater(FloaterId::from_raw(id))?;
        Ok(())
    })
}

/// Writes a floating body's current state to `out`, whose `struct_size` must be
/// `sizeof(SwFloater)` or `SW_FLOATER_SIZE_V1` (or the call is `SW_ERROR_INVALID_ARGUMENT`
/// and writes nothing). A hull body says `SW_SHAPE_HULL`; its mesh stays with the surface.
/// An unknown id is `SW_ERROR_NO_SUCH_FLOATER`.
///
/// # Safety
///
/// `out` is NULL or points to a writable struct whose `struct_size` (its first field) is
/// initialised.
#[no_mangle]
pub unsafe extern "C" fn sw_surface_floater(
    surface: *const SwSurface,
    id: SwFloaterId,
    out: *mut SwFloater,
) -> SwStatus {
    read_floater(surface, id, out)
}

/// Deprecated: the earlier name of `sw_surface_floater`, which it calls (so `out` must say
/// its size, as there).
///
/// # Safety
///
/// `out` is NULL or points to a writable struct whose `struct_size` (its first field) is
/// initialised.
#[no_mangle]
pub unsafe extern "C" fn sw_surface_get_floater(
    surface: *const SwSurface,
    id: SwFloaterId,
    out: *mut SwFloater,
) -> SwStatus {
    read_floater(surface, id, out)
}

/// Replaces a floating body's state (teleport it, turn it, change its velocities, mass,
/// drag, inertia or shape), checked like `sw_surface_add_floater`; `water_force` and
/// `water_torque` are ignored and keep the body's current values. `SW_SHAPE_HULL` keeps a
/// hull body's mesh (and is refused for a sphere or a box: a new hull body is added with
/// `sw_surface_add_hull_floater`). A `SW_FLOATER_SIZE_V1` struct leaves the fields it has
/// not (orientation, angular velocity, push torque, inertia) as they are. An unknown id is
/// `SW_ERROR_NO_SUCH_FLOATER`. On error nothing changes.
///
/// # Safety
///
/// `floater` is NULL or a valid pointer.
#[no_mangle]
pub unsafe extern "C" fn sw_surface_set_floater(
    surface: *mut SwSurface,
    id: SwFloaterId,
    floater: *const SwFloater,
) -> SwStatus {
    guard(|| {
        handle::with(surface, |w| {
            let id = FloaterId::from_raw(id);
            let current = w.surface.floater(id)?;
            let hull = match &current.shape {
                Shape::Hull(hull) => Some(Arc::clone(hull)),
                _ => None,
            };
            let body = rust_floater(input_over(floater, "floater", c_floater(current))?, hull)?;
            Ok(w.surface.set_floater(id, body)?)
        })
    })
}

/// Adds the force `(fx, fy, fz)` through a floating body's centre of mass for the next step
/// only (an engine, the wind, a player's push), in mass units × world units per second²;
/// pushes add up until that step. Refused (nothing changes) when a component, or the sum
/// with what was pushed before, is not finite. An unknown id is
/// `SW_ERROR_NO_SUCH_FLOATER`.
#[no_mangle]
pub extern "C" fn sw_surface_push_floater(
    surface: *mut SwSurface,
    id: SwFloaterId,
    fx: f32,
    fy: f32,
    fz: f32,
) -> SwStatus {
    handle::call(surface, |w| {
        Ok(w.surface
            .push_floater(FloaterId::from_raw(id), [fx, fy, fz])?)
    })
}

/// Writes the number of floating bodies on the surface to `out`.
///
/// # Safety
///
/// `out` is NULL or a valid pointer.
#[no_mangle]
pub unsafe extern "C" fn sw_surface_floater_count(
    surface: *const SwSurface,
    out: *mut usize,
) -> SwStatus {
    read_into(surface, out, |w| Ok(w.surface.floaters().len()))
}

/// Copies the ids of the surface's floating bodies, in the order they were added (ids
/// increase along it), to `ids` and writes their number to `count`. With `ids` NULL only
/// `count` is written (ask the size first); a `len` smaller than the number of bodies is
/// `SW_ERROR_BUFFER_TOO_SMALL`, with `count` still written.
///
/// # Safety
///
/// `ids` is NULL or points to `len` writable ids; `count` is NULL or valid.
#[no_mangle]
pub unsafe extern "C" fn sw_surface_floater_ids(
    surface: *const SwSurface,
    ids: *mut SwFloaterId,
    len: usize,
    count: *mut usize,
) -> SwStatus {
    copy_list_into(surface, (ids, len, "ids"), (count, "count"), |w| {
        w.surface.floaters().map(|(id, _)| id.to_raw()).collect()
    })
}

/// Writes the gravity and water density the surface's bodies float in to `out`, whose
/// `struct_size` must be `sizeof(SwBuoyancy)` (or the call is `SW_ERROR_INVALID_ARGUMENT`
/// and writes nothing).
///
/// # Safety
///
/// `out` is NULL or points to a writable struct whose `struct_size` (its first field) is
/// initialised.
#[no_mangle]
pub unsafe extern "C" fn sw_surface_buoyancy(
    surface: *const SwSurface,
    out: *mut SwBuoyancy,
) -> SwStatus {
    read_buoyancy(surface, out)
}

/// Deprecated: the earlier name of `sw_surface_buoyancy`, which it calls (so `out` must
/// say its size, as there).
///
/// # Safety
///
/// `out` is NULL or points to a writable struct whose `struct_size` (its first field) is
/// initialised.
#[no_mangle]
pub unsafe extern "C" fn sw_surface_get_buoyancy(
    surface: *const SwSurface,
    out: *mut SwBuoyancy,
) -> SwStatus {
    read_buoyancy(surface, out)
}

/// Sets the gravity and water density for every body of the surface. Refused (nothing
/// changes) when a field is out of range, or when bodies float and the stiffer waterline
/// would need a smaller timestep than the surface's `dt`.
///
/// # Safety
///
/// `buoyancy` is NULL or a valid pointer.
#[no_mangle]
pub unsafe extern "C" fn sw_surface_set_buoyancy(
    surface: *mut SwSurface,
    buoyancy: *const SwBuoyancy,
) -> SwStatus {
    guard(|| {
        let b = input(buoyancy, "buoyancy")?;
        let b = Buoyancy {
            gravity: b.gravity,
            density: b.density,
        };
        handle::with(surface, |w| Ok(w.surface.set_buoyancy(b)?))
    })
}

/// Writes to `out[0..3]` the world velocity of the body's point at world `(x, y, z)`,
/// world units per second: `velocity + angular_velocity × (point − position)`. Only those
/// three fields of `floater` count (a body of any shape, `SW_SHAPE_HULL` too, read back
/// from `sw_surface_floater` or kept in the caller's engine); they and the point must be
/// finite, or the call is `SW_ERROR_INVALID_ARGUMENT` and writes nothing.
///
/// # Safety
///
/// `floater` is NULL or a valid pointer; `out` is NULL or points to 3 writable floats.
#[no_mangle]
pub unsafe extern "C" fn sw_floater_velocity_at(
    floater: *const SwFloater,
    x: f32,
    y: f32,
    z: f32,
    out: *mut f32,
) -> SwStatus {
    guard(|| {
        let f = input_over(floater, "floater", SwFloater::NEW)?;
        let out = out_array(out, "out")?;
        for (what, v) in [
            ("point", [x, y, z]),
            ("floater position", f.position),
            ("floater velocity", f.velocity),
            ("floater angular_velocity", f.angular_velocity),
        ] {
            if !v.iter().all(|c| c.is_finite()) {
                return Err(Failure::invalid(format!(
                    "{what} is {v:?}: every component must be finite"
                )));
            }
        }
        // The motion alone: the point's velocity does not depend on the shape or the mass.
        let mut body = Floater::sphere(1.0, 1.0, f.position);
        body.velocity = Vec3::from_array(f.velocity);
        body.angular_velocity = Vec3::from_array(f.angular_velocity);
        *out = body.velocity_at([x, y, z]).to_array();
        Ok(())
    })
}

/// Writes to `out` the distance from a sphere's or a box's centre to its farthest point,
/// world units: the radius of a ball that holds the body in any orientation. The body is
/// checked as `sw_surface_add_floater` checks it; a hull's is `sw_hull_bounding_radius`.
///
/// # Safety
///
/// `floater` and `out` are NULL or valid pointers.
#[no_mangle]
pub unsafe extern "C" fn sw_floater_bounding_radius(
    floater: *const SwFloater,
    out: *mut f32,
) -> SwStatus {
    guard(|| {
        let f = input_over(floater, "floater", SwFloater::NEW)?;
        if f.shape == SW_SHAPE_HULL {
            return Err(Failure::invalid(
                "floater shape = SW_SHAPE_HULL (2): a hull body's bounding radius is its \
                 hull's, sw_hull_bounding_radius",
            ));
        }
        let body = rust_floater(f, None)?;
        let out = out_ref(out, "out")?;
        body.validate()?;
        *out = body.shape.bounding_radius();
        Ok(())
    })
}

/// The body of `sw_surface_floater` and its earlier name.
fn read_floater(surface: *const SwSurface, id: SwFloaterId, out: *mut SwFloater) -> SwStatus {
    read_sized_into(surface, out, |w| {
        Ok(c_floater(w.surface.floater(FloaterId::from_raw(id))?))
    })
}

/// The body of `sw_surface_buoyancy` and its earlier name.
fn read_buoyancy(surface: *const SwSurface, out: *mut SwBuoyancy) -> SwStatus {
    read_sized_into(surface, out, |w| Ok(c_buoyancy(w.surface.buoyancy())))
}

/// The one conversion of `Floater` to `SwFloater`; [`rust_floater`] is its inverse except
/// for the read-only `water_force` and `water_torque`, and the mesh of a hull.
pub(crate) fn c_floater(f: &Floater) -> SwFloater {
    let (shape, radius, half_extents) = match f.shape {
        Shape::Sphere { radius } => (SW_SHAPE_SPHERE, radius, [0.0; 3]),
        Shape::Box { half_extents } => (SW_SHAPE_BOX, 0.0, half_extents.to_array()),
        Shape::Hull(_) => (SW_SHAPE_HULL, 0.0, [0.0; 3]),
        // A shape a later library adds gets its own code here; until then it cannot be
        // built through this ABI, so no body has it.
        _ => (-1, 0.0, [0.0; 3]),
    };
    SwFloater {
        struct_size: size_of::<SwFloater>() as u32,
        shape,
        radius,
        half_extents,
        mass: f.mass,
        drag: f.drag,
        position: f.position.to_array(),
        velocity: f.velocity.to_array(),
        push: f.push.to_array(),
        water_force: f.water_force.to_array(),
        orientation: f.orientation.to_array(),
        angular_velocity: f.angular_velocity.to_array(),
        push_torque: f.push_torque.to_array(),
        water_torque: f.water_torque.to_array(),
        has_inertia: f.inertia.is_some() as SwBool,
        inertia: f.inertia_tensor().to_cols_array(),
    }
}

impl SwFloater {
    /// All zeros but `struct_size` and the orientation (upright): what a version 1 struct
    /// lacks, for a new body (no spin, no torque, the shape's inertia).
    pub(crate) const NEW: SwFloater = SwFloater {
        struct_size: size_of::<SwFloater>() as u32,
        shape: SW_SHAPE_SPHERE,
        radius: 0.0,
        half_extents: [0.0; 3],
        mass: 0.0,
        drag: 0.0,
        position: [0.0; 3],
        velocity: [0.0; 3],
        push: [0.0; 3],
        water_force: [0.0; 3],
        orientation: [0.0, 0.0, 0.0, 1.0],
        angular_velocity: [0.0; 3],
        push_torque: [0.0; 3],
        water_torque: [0.0; 3],
        has_inertia: 0,
        inertia: [0.0; 9],
    };
}

/// The body `f` describes, with zero water force and torque; the library checks its fields
/// when it takes it. `hull` is the mesh of a `SW_SHAPE_HULL` body, where the call has one.
pub(crate) fn rust_floater(f: SwFloater, hull: Option<Arc<Hull>>) -> Outcome<Floater> {
    let shape = match (f.shape, hull) {
        (SW_SHAPE_SPHERE, _) => Shape::Sphere { radius: f.radius },
        (SW_SHAPE_BOX, _) => Shape::Box {
            half_extents: Vec3::from_array(f.half_extents),
        },
        (SW_SHAPE_HULL, Some(hull)) => Shape::Hull(hull),
        (SW_SHAPE_HULL, None) => {
            return Err(Failure::invalid(
                "floater shape = SW_SHAPE_HULL (2) needs its mesh: add a hull body with \
                 sw_surface_add_hull_floater, ask for its forces with \
                 sw_surface_hull_body_forces",
            ))
        }
        (other, _) => {
            return Err(Failure::invalid(format!(
                "floater shape = {other} is invalid: use SW_SHAPE_SPHERE (0), SW_SHAPE_BOX (1) \
                 or SW_SHAPE_HULL (2)"
            )))
        }
    };
    let inertia = match f.has_inertia {
        0 => None,
        1 => Some(Mat3::from_cols_array(&f.inertia)),
        other => {
            return Err(Failure::invalid(format!(
                "floater has_inertia = {other} is invalid: use 1 (the tensor in inertia) or 0 (the shape's)"
            )))
        }
    };
    let mut body = Floater::with_shape(shape, f.mass, f.position);
    body.inertia = inertia;
    body.drag = f.drag;
    body.orientation = Quat::from_array(f.orientation);
    body.velocity = Vec3::from_array(f.velocity);
    body.angular_velocity = Vec3::from_array(f.angular_velocity);
    body.push = Vec3::from_array(f.push);
    body.push_torque = Vec3::from_array(f.push_torque);
    Ok(body)
}

fn c_buoyancy(b: Buoyancy) -> SwBuoyancy {
    SwBuoyancy {
        struct_size: size_of::<SwBuoyancy>() as u32,
        gravity: b.gravity,
        density: b.density,
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn floaters_convert_both_ways_except_the_read_only_fields() {
        let mut ball = Floater::sphere(1.5, 2.0, [3.0, -0.5, 4.0]);
        ball.velocity = Vec3::new(0.1, 0.2, -0.3);
        ball.push = Vec3::new(1.0, 0.0, -1.0);
        ball.orientation = Quat::from_rotation_x(0.3);
        ball.angular_velocity = Vec3::new(0.0, 0.5, 1.0);
        ball.push_torque = Vec3::new(2.0, 0.0, 0.0);
        let mut boxy = Floater::cuboid([1.0, 0.5, 2.0], 3.0, [5.0, 0.0, 6.0]);
        boxy.inertia = Some(Mat3::from_diagonal(Vec3::new(2.0, 3.0, 4.0)));
        let hull = Arc::new(Hull::cuboid([1.0, 0.5, 2.0]).unwrap());
        let boat = Floater::with_hull(Arc::clone(&hull), 3.0, [5.0, 0.0, 6.0]);
        for (f, mesh) in [
            (ball.clone(), None),
            (boxy.clone(), None),
            (boat, Some(hull)),
        ] {
            let mut felt = f.clone();
            felt.water_force = Vec3::new(0.0, 9.0, 0.0);
            felt.water_torque = Vec3::new(0.0, 0.0, -1.0);
            let c = c_floater(&felt);
            assert_eq!(c.water_force, [0.0, 9.0, 0.0]);
            assert_eq!(c.water_torque, [0.0, 0.0, -1.0]);
            assert_eq!(c.inertia, f.inertia_tensor().to_cols_array());
            assert_eq!(rust_floater(c, mesh).unwrap(), f);
        }
        assert_eq!(c_floater(&ball).half_extents, [0.0; 3]);
        assert_eq!(c_floater(&ball).has_inertia, 0);
        assert_eq!(c_floater(&boxy).radius, 0.0);
        assert_eq!(c_floater(&boxy).has_inertia, 1);
        let upright = sw_floater_sphere(1.5, 2.0, 3.0, -0.5, 4.0);
        assert_eq!(
            upright,
            c_floater(&Floater::sphere(1.5, 2.0, [3.0, -0.5, 4.0]))
        );
        assert_eq!(upright.orientation, [0.0, 0.0, 0.0, 1.0]);
        for bad in [
            SwFloater {
                shape: 3,
                ..c_floater(&ball)
            },
            SwFloater {
                shape: SW_SHAPE_HULL,
                ..c_floater(&ball)
            },
            SwFloater {
                has_inertia: 2,
                ..c_floater(&ball)
            },
        ] {
            assert!(rust_floater(bad, None).is_err());
        }
    }
}
