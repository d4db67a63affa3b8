//! The lattice node by node and spring by spring: pins, per-node masses and viscosities,
//! forces and velocity changes on one node, every node's pending force, the uniform
//! acceleration, and single springs' rest lengths and coefficients (the library's
//! `Surface::set_pinned`, `set_mass`, `set_masses`, `set_viscosity`, `set_viscosities`,
//! `set_spring`, `add_force`, `set_forces`, `add_velocity`, `clear_forces`,
//! `set_acceleration` and their readers). Nodes are row-major indices, `row * cols + col`; per-node buffers hold one
//! value per node (`sw_surface_node_count`). Masses and viscosities are the lattice's
//! (`SwParams::mass`, `SwParams::viscosity`), in model time like them.

use crate::buffers::write_components;
use crate::handle::{self, SwSurface};
use crate::params::SwBool;
use crate::ptr::{in_slice, need, out_array, out_buffer, read_into};
use crate::status::{guard, Failure, Outcome, SwStatus};
use springwater::{Family, Spring, SpringId, Surface};

/// A family of springs, by the direction from a spring's origin node to its other end
/// (`SW_FAMILY_*`). Every grid edge and both diagonals of every cell carry one spring, kept
/// at its origin: an interior node is the origin of four springs and the far end of four.
pub type SwFamily = i32;
/// East, to node `(col + 1, row)`.
pub const SW_FAMILY_E: SwFamily = 0;
/// South, to node `(col, row + 1)`.
pub const SW_FAMILY_S: SwFamily = 1;
/// South-east diagonal, to node `(col + 1, row + 1)`.
pub const SW_FAMILY_SE: SwFamily = 2;
/// South-west diagonal, to node `(col − 1, row + 1)`.
pub const SW_FAMILY_SW: SwFamily = 3;

/// Pins (`pinned` 1) or frees (0) a node: a pinned node never moves, and pinning zeroes
/// its velocity. A node past the last, or another `pinned` value, is
/// `SW_ERROR_INVALID_ARGUMENT` and changes nothing.
#[no_mangle]
pub extern "C" fn sw_surface_set_pinned(
    surface: *mut SwSurface,
    node: usize,
    pinned: SwBool,
) -> SwStatus {
    guard(|| {
        let pinned = match pinned {
            0 => false,
            1 => true,
            other => return Err(Failure::invalid(format!("pinned is {other}, not 0 or 1"))),
        };
        handle::with(surface, |w| Ok(w.surface.set_pinned(node, pinned)?))
    })
}

/// Writes 1 to `out` if the node is pinned, 0 if it is free.
///
/// # Safety
///
/// `out` is NULL or a valid pointer.
#[no_mangle]
pub unsafe extern "C" fn sw_surface_is_pinned(
    surface: *const SwSurface,
    node: usize,
    out: *mut SwBool,
) -> SwStatus {
    read_into(surface, out, |w| Ok(w.surface.is_pinned(node)? as SwBool))
}

/// Writes every node's pin, 1 pinned or 0 free, to `out[0..nodes]` (`len` at least the
/// node count).
///
/// # Safety
///
/// `out` is NULL or points to `len` writable bytes.
#[no_mangle]
pub unsafe extern "C" fn sw_surface_write_pinned(
    surface: *const SwSurface,
    out: *mut u8,
    len: usize,
) -> SwStatus {
    handle::call(surface, |w| {
        let pinned = w.surface.pinned();
        let out = out_buffer(out, len, pinned.len(), "out")?;
        for (o, &p) in out.iter_mut().zip(pinned) {
            *o = p as u8;
        }
        Ok(())
    })
}

/// Sets a node's mass (> 0, in the lattice's mass units). Refused, with nothing changed, if
/// it would put the surface's `dt` at or past the critical timestep (the bound remembers
/// the smallest mass ever set).
#[no_mangle]
pub extern "C" fn sw_surface_set_mass(surface: *mut SwSurface, node: usize, mass: f32) -> SwStatus {
    handle::call(surface, |w| Ok(w.surface.set_mass(node, mass)?))
}

/// Sets every node's mass from `masses[0..nodes]` (`len` at least the node count),
/// each checked as by `sw_surface_set_mass`, all before anything changes: a refused call
/// changes no node.
///
/// # Safety
///
/// `masses` is NULL or points to `len` floats.
#[no_mangle]
pub unsafe extern "C" fn sw_surface_set_masses(
    surface: *mut SwSurface,
    masses: *const f32,
    len: usize,
) -> SwStatus {
    handle::call(surface, |w| {
        let masses = per_node(masses, len, w.surface.node_count(), "masses")?;
        Ok(w.surface.set_masses(masses)?)
    })
}

/// Writes every node's mass to `out[0..nodes]` (`len` at least the node count).
///
/// # Safety
///
/// `out` is NULL or points to `len` writable floats.
#[no_mangle]
pub unsafe extern "C" fn sw_surface_write_masses(
    surface: *const SwSurface,
    out: *mut f32,
    len: usize,
) -> SwStatus {
    handle::call(surface, |w| {
        let masses = w.surface.masses();
        let out = out_buffer(out, len, masses.len(), "out")?;
        for (o, &m) in out.iter_mut().zip(masses) {
            *o = m;
        }
        Ok(())
    })
}

/// Sets a node's viscosity (≥ 0, in the lattice's units, like `SwParams::viscosity`).
/// Refused, with nothing changed, if it would put the surface's `dt` at or past the
/// critical timestep (the bound remembers the largest viscosity ever set).
#[no_mangle]
pub extern "C" fn sw_surface_set_viscosity(
    surface: *mut SwSurface,
    node: usize,
    viscosity: f32,
) -> SwStatus {
    handle::call(surface, |w| Ok(w.surface.set_viscosity(node, viscosity)?))
}

/// Sets every node's viscosity from `viscosities[0..nodes]` (`len` at least the node
/// count), each checked as by `sw_surface_set_viscosity`, all before anything changes: a
/// refused call changes no node.
///
/// # Safety
///
/// `viscosities` is NULL or points to `len` floats.
#[no_mangle]
pub unsafe extern "C" fn sw_surface_set_viscosities(
    surface: *mut SwSurface,
    viscosities: *const f32,
    len: usize,
) -> SwStatus {
    handle::call(surface, |w| {
        let viscosities = per_node(viscosities, len, w.surface.node_count(), "viscosities")?;
        Ok(w.surface.set_viscosities(viscosities)?)
    })
}

/// Writes every node's viscosity, the absorbing frame's ramp included, to
/// `out[0..nodes]` (`len` at least the node count).
///
/// # Safety
///
/// `out` is NULL or points to `len` writable floats.
#[no_mangle]
pub unsafe extern "C" fn sw_surface_write_viscosities(
    surface: *const SwSurface,
    out: *mut f32,
    len: usize,
) -> SwStatus {
    handle::call(surface, |w| {
        let viscosities = w.surface.viscosities();
        let out = out_buffer(out, len, viscosities.len(), "out")?;
        for (o, &v) in out.iter_mut().zip(viscosities) {
            *o = v;
        }
        Ok(())
    })
}

/// Writes the spring of `family` whose origin is `node` to `out[0..2]`: its rest length
/// (world units) and its coefficient. A spring the grid does not have (its other end off
/// the grid, an unknown family, a node past the last) is `SW_ERROR_INVALID_ARGUMENT`, and
/// nothing is written.
///
/// # Safety
///
/// `out` is NULL or points to 2 writable floats.
#[no_mangle]
pub unsafe extern "C" fn sw_surface_spring(
    surface: *const SwSurface,
    family: SwFamily,
    node: usize,
    out: *mut f32,
) -> SwStatus {
    guard(|| {
        let id = spring_id(family, node)?;
        let out = out_array(out, "out")?;
        let spring = handle::with(surface, |w| {
            w.surface.spring(id).ok_or_else(|| {
                Failure::invalid(format!(
                    "the grid has no spring of family {family} at node {node}: its other end \
                     is off the grid, or the node is past the last"
                ))
            })
        })?;
        *out = [spring.rest, spring.stiffness];
        Ok(())
    })
}

/// Sets the rest length (≥ 0, world units) and coefficient (> 0) of the spring of
/// `family` whose origin is `node`. Refused, with nothing changed, if the grid has no such
/// spring or the coefficient would put the surface's `dt` at or past the critical
/// timestep.
#[no_mangle]
pub extern "C" fn sw_surface_set_spring(
    surface: *mut SwSurface,
    family: SwFamily,
    node: usize,
    rest: f32,
    stiffness: f32,
) -> SwStatus {
    guard(|| {
        let id = spring_id(family, node)?;
        handle::with(surface, |w| {
            Ok(w.surface.set_spring(id, Spring { rest, stiffness })?)
        })
    })
}

/// The caller's per-node values: the first `nodes` of the `len` at `ptr`.
fn per_node<'a>(ptr: *const f32, len: usize, nodes: usize, what: &str) -> Outcome<&'a [f32]> {
    need(len, nodes, what)?;
    in_slice(ptr, nodes, what)
}

fn spring_id(family: SwFamily, node: usize) -> Outcome<SpringId> {
    let family = match family {
        SW_FAMILY_E => Family::E,
        SW_FAMILY_S => Family::S,
        SW_FAMILY_SE => Family::SE,
        SW_FAMILY_SW => Family::SW,
        other => {
            return Err(Failure::invalid(format!(
                "family is {other}: use SW_FAMILY_E (0), SW_FAMILY_S (1), SW_FAMILY_SE (2) or \
                 SW_FAMILY_SW (3)"
            )))
        }
    };
    Ok(SpringId {
        family,
        origin: node,
    })
}

/// Adds the force `(fx, fy, fz)` to node `node` for the next step only, in the lattice's
/// force units (`sw_surface_add_force_at` spreads one at a world point instead).
/// Refused, with nothing changed, for a node out of range or a force or sum that is not
/// finite.
#[no_mangle]
pub extern "C" fn sw_surface_add_force(
    surface: *mut SwSurface,
    node: usize,
    fx: f32,
    fy: f32,
    fz: f32,
) -> SwStatus {
    handle::call(surface, |w| Ok(w.surface.add_force(node, [fx, fy, fz])?))
}

/// Discards every force waiting for the next step: those added node by node or at a
/// point, and the water's share of `sw_surface_body_forces` (what the water column under
/// the bodies carries stays).
#[no_mangle]
pub extern "C" fn sw_surface_clear_forces(surface: *mut SwSurface) -> SwStatus {
    handle::call(surface, |w| {
        w.surface.clear_forces();
        Ok(())
    })
}

/// Adds the velocity change `(dvx, dvy, dvz)` to free node `node` now (an impulse divided
/// by its mass), in world units per unit of model time. Refused, with nothing changed, for
/// a node out of range or pinned, or a change or sum that is not finite.
#[no_mangle]
pub extern "C" fn sw_surface_add_velocity(
    surface: *mut SwSurface,
    node: usize,
    dvx: f32,
    dvy: f32,
    dvz: f32,
) -> SwStatus {
    handle::call(surface, |w| {
        Ok(w.surface.add_velocity(node, [dvx, dvy, dvz])?)
    })
}

/// Replaces every node's force for the next step with `xyz[0..3·nodes]`, interleaved
/// `x, y, z`, row-major (`len`, in floats, at least `3 · nodes`), in the lattice's force
/// units like `sw_surface_add_force`: what was added before is replaced (the water's share
/// of `sw_surface_body_forces`, kept apart, stays). Every value must be finite; a refused
/// call changes nothing.
///
/// # Safety
///
/// `xyz` is NULL or points to `len` floats.
#[no_mangle]
pub unsafe extern "C" fn sw_surface_set_forces(
    surface: *mut SwSurface,
    xyz: *const f32,
    len: usize,
) -> SwStatus {
    handle::call(surface, |w| {
        let nodes = w.surface.node_count();
        need(len, nodes.saturating_mul(3), "xyz")?;
        // `[f32; 3]` has the size of three floats and the alignment of one.
        let triples = in_slice(xyz.cast::<[f32; 3]>(), nodes, "xyz")?;
        let [x, y, z]: [Vec<f32>; 3] =
            std::array::from_fn(|k| triples.iter().map(|f| f[k]).collect());
        Ok(w.surface.set_forces([&x, &y, &z])?)
    })
}

/// Writes every node's force waiting for the next step, interleaved `x, y, z`, row-major,
/// in the lattice's force units: what `sw_surface_add_force`, `sw_surface_add_force_at`
/// and `sw_surface_set_forces` put there (not the water's share of
/// `sw_surface_body_forces`, which is kept apart). `len` is in floats and must be at least
/// `3 · nodes`.
///
/// # Safety
///
/// `xyz` is NULL or points to `len` writable floats.
#[no_mangle]
pub unsafe extern "C" fn sw_surface_write_forces(
    surface: *const SwSurface,
    xyz: *mut f32,
    len: usize,
) -> SwStatus {
    write_components(surface, xyz, len, Surface::forces)
}

/// Sets the uniform acceleration on every free node (gravity, wind), world units per
/// second², as `SwParams::acceleration_*` sets it at creation (`sw_surface_params` reads it
/// back). A component that is not finite is `SW_ERROR_INVALID_ARGUMENT` and changes
/// nothing.
#[no_mangle]
pub extern "C" fn sw_surface_set_acceleration(
    surface: *mut SwSurface,
    ax: f32,
    ay: f32,
    az: f32,
) -> SwStatus {
    handle::call(surface, |w| Ok(w.surface.set_acceleration([ax, ay, az])?))
}
