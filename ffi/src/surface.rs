//! A surface's life: create it from parameters, destroy it, read its parameters and size,
//! and move it on (the fixed-step clock, frames cut into variable substeps, whole steps,
//! drops).

use crate::handle::{self, SwSurface, Water};
use crate::params::{c_params, rust_params, SwParams};
use crate::ptr::{input, optional, out_ref, read_into, read_sized_into};
use crate::status::{guard, Failure, Outcome, SwStatus};
use springwater::{Overflow, Surface};

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
        let params = input(params, "params")?;
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
    read_sized_into(surface, out, |w| Ok(c_params(w.surface.params())))
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
        frame(surface, substeps, |s| s.advance(frame_time))
    })
}

/// Advances the water by one frame of `frame_time` seconds (finite, at least 0) in equal
/// substeps of *variable* length, never longer than `dt` (`sw_surface_split_frame` says how
/// many and how long): every frame ends exactly on the caller's clock, at the price of
/// results that depend on how the time is cut into frames. It leaves
/// `sw_surface_advance`'s accumulator as it is. A frame of more than 10000 steps is
/// `SW_ERROR_INVALID_ARGUMENT` and changes nothing. Writes the number of substeps to
/// `substeps` (optional, may be NULL). A failing step stops the frame there, earlier
/// steps stay applied.
///
/// # Safety
///
/// `substeps` is NULL or a valid pointer.
#[no_mangle]
pub unsafe extern "C" fn sw_surface_advance_variable(
    surface: *mut SwSurface,
    frame_time: f32,
    substeps: *mut u32,
) -> SwStatus {
    guard(|| {
        let substeps = optional(substeps, "substeps")?;
        frame(surface, substeps, |s| s.advance_variable(frame_time))
    })
}

/// The body of the frame calls (`sw_surface_advance`, `_advance_variable`,
/// `_advance_with`): one frame of `advance` on the surface, the steps it took written to
/// `substeps` if given.
pub(crate) fn frame(
    surface: *mut SwSurface,
    substeps: Option<&mut u32>,
    advance: impl FnOnce(&mut Surface) -> springwater::Result<usize>,
) -> Outcome<()> {
    handle::with(surface, |w| {
        let taken = advance(&mut w.surface)?;
        if let Some(out) = substeps {
            *out = taken as u32;
        }
        Ok(())
    })
}

/// How `sw_surface_advance_variable` would cut a frame of `frame_time` seconds, without
/// taking it: the number of equal substeps to `substeps` and the length of each, in
/// seconds of the caller's clock, to `substep_seconds` (never longer than one step of
/// `dt`). Either may be NULL. A frame of more than 10000 steps, or a `frame_time` not
/// finite and at least 0, is `SW_ERROR_INVALID_ARGUMENT`, and nothing is written.
///
/// # Safety
///
/// `substeps` and `substep_seconds` are NULL or valid pointers.
#[no_mangle]
pub unsafe extern "C" fn sw_surface_split_frame(
    surface: *const SwSurface,
    frame_time: f32,
    substeps: *mut u32,
    substep_seconds: *mut f32,
) -> SwStatus {
    guard(|| {
        let count_out = optional(substeps, "substeps")?;
        let seconds_out = optional(substep_seconds, "substep_seconds")?;
        let (count, seconds) = handle::with(surface, |w| Ok(w.surface.split_frame(frame_time)?))?;
        if let Some(out) = count_out {
            *out = count as u32;
        }
        if let Some(out) = seconds_out {
            *out = seconds;
        }
        Ok(())
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

/// Writes the cap on steps per `sw_surface_advance` call to `max_steps` and what happens
/// past it to `carry` (0 drops the owed steps, 1 carries them), as
/// `sw_surface_set_step_cap` takes them. Either may be NULL.
///
/// # Safety
///
/// `max_steps` and `carry` are NULL or valid pointers.
#[no_mangle]
pub unsafe extern "C" fn sw_surface_step_cap(
    surface: *const SwSurface,
    max_steps: *mut u32,
    carry: *mut i32,
) -> SwStatus {
    guard(|| {
        let (max_out, carry_out) = (optional(max_steps, "max_steps")?, optional(carry, "carry")?);
        let (max, overflow) = handle::with(surface, |w| Ok(w.surface.step_cap()))?;
        if let Some(out) = max_out {
            *out = max;
        }
        if let Some(out) = carry_out {
            *out = match overflow {
                Overflow::Carry => 1,
                _ => 0,
            };
        }
        Ok(())
    })
}

/// Writes the steps taken so far to `out`.
///
/// # Safety
///
/// `out` is NULL or a valid pointer.
#[no_mangle]
pub unsafe extern "C" fn sw_surface_steps(surface: *const SwSurface, out: *mut u64) -> SwStatus {
    read_into(surface, out, |w| Ok(w.surface.steps()))
}

/// Writes the seconds of the caller's clock simulated so far to `out`: the model time
/// (`sw_surface_model_time`) divided by `time_scale`.
///
/// # Safety
///
/// `out` is NULL or a valid pointer.
#[no_mangle]
pub unsafe extern "C" fn sw_surface_time(surface: *const SwSurface, out: *mut f64) -> SwStatus {
    read_into(surface, out, |w| Ok(w.surface.time()))
}

/// Writes the model time simulated so far to `out`, in the lattice's own unit: the sum of
/// the steps' `dt`.
///
/// # Safety
///
/// `out` is NULL or a valid pointer.
#[no_mangle]
pub unsafe extern "C" fn sw_surface_model_time(
    surface: *const SwSurface,
    out: *mut f64,
) -> SwStatus {
    read_into(surface, out, |w| Ok(w.surface.model_time()))
}

/// Writes to `out` the seconds of the caller's clock that `sw_surface_advance` owes and
/// has not stepped yet: under one step normally, more while a carried cap catches up.
///
/// # Safety
///
/// `out` is NULL or a valid pointer.
#[no_mangle]
pub unsafe extern "C" fn sw_surface_owed_seconds(
    surface: *const SwSurface,
    out: *mut f64,
) -> SwStatus {
    read_into(surface, out, |w| Ok(w.surface.owed_seconds()))
}

/// Writes to `out` the seconds of the caller's clock the step cap has dropped so far: how
/// far the water is behind the seconds passed to `sw_surface_advance`.
///
/// # Safety
///
/// `out` is NULL or a valid pointer.
#[no_mangle]
pub unsafe extern "C" fn sw_surface_dropped_seconds(
    surface: *const SwSurface,
    out: *mut f64,
) -> SwStatus {
    read_into(surface, out, |w| Ok(w.surface.dropped_seconds()))
}

/// Writes to `out` the largest safe timestep for the surface's current tables (and the
/// bodies floating on it): the bound `dt` must stay under.
///
/// # Safety
///
/// `out` is NULL or a valid pointer.
#[no_mangle]
pub unsafe extern "C" fn sw_surface_critical_dt(
    surface: *const SwSurface,
    out: *mut f32,
) -> SwStatus {
    read_into(surface, out, |w| Ok(w.surface.critical_dt()))
}

/// Advances `steps` steps of the model's timestep, several per pass over memory (bitwise
/// the same as one at a time). Stops at a failing step; the steps before it stay applied.
#[no_mangle]
pub extern "C" fn sw_surface_step(surface: *mut SwSurface, steps: u32) -> SwStatus {
    handle::call(surface, |w| Ok(w.surface.step_n(steps as u64)?))
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
    handle::call(surface, |w| Ok(w.surface.drop_at(x, z, height, radius)?))
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
