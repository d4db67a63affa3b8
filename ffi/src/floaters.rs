//! Floating bodies from C: spheres and boxes that ride the waves and push back into them
//! (the library's `Floater`, whose docs explain the model). Units are the game's: world
//! units for lengths, the lattice's mass units, seconds for time (velocities per second,
//! gravity and forces per second², the drag rate per second), as in the Rust API.

use crate::handle::{self, SwSurface};
use crate::ptr::{copy_list_into, input, out_ref, read_into, read_sized_into, Input};
use crate::status::{guard, Failure, Outcome, SwStatus};
use glam::Vec3;
use springwater::{Buoyancy, Floater, FloaterId, Shape};

/// The shape of a floating body (`SW_SHAPE_*`; a body read back with a shape this version
/// of the C ABI has no code for, which it cannot make, would say -1).
pub type SwShape = i32;
/// A ball of `SwFloater::radius`.
pub const SW_SHAPE_SPHERE: SwShape = 0;
/// A box aligned with the water's axes (bodies do not rotate) of `SwFloater::half_extents`.
pub const SW_SHAPE_BOX: SwShape = 1;

/// A floating body's id on its surface, never reused by that surface (also not after the
/// body is removed, or across a snapshot).
pub type SwFloaterId = u64;

/// A floating body: `sw_floater_sphere()` and `sw_floater_box()` make one at rest with the
/// default drag. Plain data: hand it to `sw_surface_add_floater`, read it back with
/// `sw_surface_floater`.
#[repr(C)]
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct SwFloater {
    /// `sizeof(SwFloater)`, set by `sw_floater_sphere()`, `sw_floater_box()` and
    /// `sw_surface_floater()`: calls that read or fill the struct refuse any other value (a
    /// struct not started from one of them, or built with a header of another version than
    /// the library's).
    pub struct_size: u32,
    /// `SW_SHAPE_SPHERE` or `SW_SHAPE_BOX`.
    pub shape: SwShape,
    /// The sphere's radius, world units (> 0, at most 1e9). Ignored for a box, read back as
    /// 0.
    pub radius: f32,
    /// The box's half size along x, y and z, world units (each > 0, at most 1e9). Ignored
    /// for a sphere, read back as 0.
    pub half_extents: [f32; 3],
    /// Mass, in the lattice's mass units (> 0; a node has `SwParams::mass`).
    pub mass: f32,
    /// Drag rate, per second (0 to 1e8; default 6): the drag is this times the mass of the
    /// displaced water times the velocity relative to the water.
    pub drag: f32,
    /// Centre in the water's local space (the calm surface is y = 0), world units (each
    /// component at most 1e15 in magnitude).
    pub position: [f32; 3],
    /// Velocity, world units per second (each component at most 1e11 in magnitude; default
    /// 0).
    pub velocity: [f32; 3],
    /// External force (an engine, the wind, a player's push) for the next step only, cleared
    /// by it; `sw_surface_push_floater` adds to it. Mass units × world units per second²,
    /// finite (default 0).
    pub push: [f32; 3],
    /// Read only: the force the water exerted on the body during its last step (buoyancy and
    /// drag, without gravity and push), mass units × world units per second²; the water got
    /// exactly minus this (in its own units, divided by `time_scale²`). Ignored on input:
    /// a body added starts at 0, a body set keeps its current value.
    pub water_force: [f32; 3],
}

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

/// All zeros but `struct_size`, which is this version's: a struct ready for
/// `sw_surface_floater` to fill (from Rust; C starts one with `{.struct_size = sizeof f}`).
impl Default for SwFloater {
    fn default() -> Self {
        Self {
            struct_size: size_of::<Self>() as u32,
            shape: 0,
            radius: 0.0,
            half_extents: [0.0; 3],
            mass: 0.0,
            drag: 0.0,
            position: [0.0; 3],
            velocity: [0.0; 3],
            push: [0.0; 3],
            water_force: [0.0; 3],
        }
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
    const MAKER: &'static str = "sw_floater_sphere() or sw_floater_box()";
}

impl Input for SwBuoyancy {
    const MAKER: &'static str = "sw_buoyancy_default()";
}

const _: () = {
    assert!(std::mem::offset_of!(SwFloater, struct_size) == 0);
    assert!(std::mem::offset_of!(SwBuoyancy, struct_size) == 0);
};

/// A sphere of `radius` and `mass` centred at `(x, y, z)`, at rest, with the default drag
/// (0.25). Not checked here: `sw_surface_add_floater` checks it.
#[no_mangle]
pub extern "C" fn sw_floater_sphere(radius: f32, mass: f32, x: f32, y: f32, z: f32) -> SwFloater {
    c_floater(&Floater::sphere(radius, mass, [x, y, z]))
}

/// A box of half extents `(half_x, half_y, half_z)` and `mass` centred at `(x, y, z)`, at
/// rest, with the default drag (0.25). Not checked here: `sw_surface_add_floater` checks
/// it.
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
/// field is out of range or the shape code is unknown, or when the water under the bodies
/// would need a smaller timestep than the surface's `dt` (a stiff waterline: large gravity
/// times density).
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
        let body = rust_floater(input(floater, "floater")?)?;
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
/// `sizeof(SwFloater)` (or the call is `SW_ERROR_INVALID_ARGUMENT` and writes nothing). An
/// unknown id is `SW_ERROR_NO_SUCH_FLOATER`.
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

/// Replaces a floating body's state (teleport it, change its velocity, mass, drag or
/// shape), checked like `sw_surface_add_floater`; `water_force` is ignored and keeps the
/// body's current value. An unknown id is `SW_ERROR_NO_SUCH_FLOATER`. On error nothing
/// changes.
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
        let body = rust_floater(input(floater, "floater")?)?;
        handle::with(surface, |w| {
            let id = FloaterId::from_raw(id);
            let mut body = body;
            body.water_force = w.surface.floater(id)?.water_force;
            Ok(w.surface.set_floater(id, body)?)
        })
    })
}

/// Adds the force `(fx, fy, fz)` to a floating body for the next step only (an engine, the
/// wind, a player's push), in mass units × world units per second²; pushes add up until
/// that step. Refused (nothing changes) when a
/// component, or the sum with what was pushed before, is not finite. An unknown id is
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
/// for `water_force`, which is output only.
fn c_floater(f: &Floater) -> SwFloater {
    let (shape, radius, half_extents) = match f.shape {
        Shape::Sphere { radius } => (SW_SHAPE_SPHERE, radius, [0.0; 3]),
        Shape::Box { half_extents } => (SW_SHAPE_BOX, 0.0, half_extents.to_array()),
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
    }
}

/// The body `f` describes, with a zero water force; the library checks its fields when it
/// takes it.
fn rust_floater(f: SwFloater) -> Outcome<Floater> {
    let shape = match f.shape {
        SW_SHAPE_SPHERE => Shape::Sphere { radius: f.radius },
        SW_SHAPE_BOX => Shape::Box {
            half_extents: Vec3::from_array(f.half_extents),
        },
        other => {
            return Err(Failure::invalid(format!(
                "floater shape = {other} is invalid: use SW_SHAPE_SPHERE (0) or SW_SHAPE_BOX (1)"
            )))
        }
    };
    let mut body = Floater::sphere(1.0, f.mass, f.position);
    body.shape = shape;
    body.drag = f.drag;
    body.velocity = Vec3::from_array(f.velocity);
    body.push = Vec3::from_array(f.push);
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
    fn floaters_convert_both_ways_except_the_water_force() {
        let mut ball = Floater::sphere(1.5, 2.0, [3.0, -0.5, 4.0]);
        ball.velocity = Vec3::new(0.1, 0.2, -0.3);
        ball.push = Vec3::new(1.0, 0.0, -1.0);
        let boxy = Floater::cuboid([1.0, 0.5, 2.0], 3.0, [5.0, 0.0, 6.0]);
        for f in [ball, boxy] {
            let mut felt = f;
            felt.water_force = Vec3::new(0.0, 9.0, 0.0);
            let c = c_floater(&felt);
            assert_eq!(c.water_force, [0.0, 9.0, 0.0]);
            assert_eq!(rust_floater(c).unwrap(), f);
        }
        assert_eq!(c_floater(&ball).half_extents, [0.0; 3]);
        assert_eq!(c_floater(&boxy).radius, 0.0);
        assert_eq!(
            sw_floater_sphere(1.5, 2.0, 3.0, -0.5, 4.0),
            c_floater(&Floater::sphere(1.5, 2.0, [3.0, -0.5, 4.0]))
        );
        let bad = SwFloater {
            shape: 2,
            ..c_floater(&ball)
        };
        assert!(rust_floater(bad).is_err());
    }
}
