//! The library's disturbances from C (`springwater::disturb`): rain and wakes as handles
//! (`SwDisturbance *`), made with their settings checked, read and moved between frames,
//! and applied before every substep of a frame by `sw_surface_advance_with` (the library's
//! `Surface::advance_with`). A disturbance is not tied to a surface: one rain may fall on
//! several, one after the other.

use crate::handle::{self, Registry, SwSurface};
use crate::params::finite_positive;
use crate::ptr::{in_slice, optional, out_array, out_ref};
use crate::status::{
    guard, Failure, Outcome, SwStatus, SW_ERROR_BUSY, SW_ERROR_INTERNAL, SW_ERROR_INVALID_HANDLE,
};
use crate::surface::frame;
use springwater::disturb::{Disturbance, Rain, Wake};
use springwater::Surface;
use std::sync::{Arc, Mutex, MutexGuard, TryLockError};

/// Rain or a wake (opaque). Make one with `sw_rain_create`, `sw_wake_create` or
/// `sw_wake_circle`, free it with `sw_disturbance_destroy`.
pub struct SwDisturbance {
    _opaque: [u8; 0],
}

/// A disturbance a handle stands for.
pub(crate) enum Disturb {
    Rain(Rain),
    Wake(Wake),
}

impl Disturbance for Disturb {
    fn apply(&mut self, surface: &mut Surface, dt: f32) -> springwater::Result<()> {
        match self {
            Disturb::Rain(rain) => rain.apply(surface, dt),
            Disturb::Wake(wake) => wake.apply(surface, dt),
        }
    }
}

static DISTURBANCES: Registry<Mutex<Disturb>> = Registry::new();

/// Rain of `rate` drops per second from `seed`, drop radii from `radius_min` to
/// `radius_max` and depth `depth` of the radius, each checked first.
pub(crate) fn rain(
    rate: f32,
    seed: u64,
    radius_min: f32,
    radius_max: f32,
    depth: f32,
) -> Outcome<Rain> {
    rain_rate(rate)?;
    finite_positive("rain radius_min", radius_min)?;
    finite_positive("rain radius_max", radius_max)?;
    if radius_max < radius_min {
        return Err(Failure::invalid(format!(
            "rain radius_max {radius_max} is below radius_min {radius_min}"
        )));
    }
    if !(depth > 0.0 && depth <= 1.0) {
        return Err(Failure::invalid(format!(
            "rain depth is {depth}, expected a fraction of the radius in (0, 1]"
        )));
    }
    let mut rain = Rain::new(rate, seed);
    rain.radius = radius_min..radius_max;
    rain.depth = depth;
    Ok(rain)
}

pub(crate) fn rain_rate(rate: f32) -> Outcome {
    if rate.is_finite() && rate >= 0.0 {
        Ok(())
    } else {
        Err(Failure::invalid(format!(
            "rain rate is {rate}, expected a finite number of drops per second, at least 0"
        )))
    }
}

/// `wake` with its `speed`, `radius` and `strength` set, checked first as its steps check
/// them: any finite speed (negative goes round the path backwards) and strength (negative
/// lifts the water), a finite radius above 0.
fn wake_with(mut wake: Wake, speed: f32, radius: f32, strength: f32) -> Outcome<Wake> {
    for (what, value) in [("wake speed", speed), ("wake strength", strength)] {
        if !value.is_finite() {
            return Err(Failure::invalid(format!(
                "{what} is {value}, expected a finite number"
            )));
        }
    }
    finite_positive("wake radius", radius)?;
    wake.speed = speed;
    wake.radius = radius;
    wake.strength = strength;
    Ok(wake)
}

/// Registers `d` and writes its new handle to `out`.
fn keep(d: Disturb, out: &mut *mut SwDisturbance) {
    *out = DISTURBANCES.insert(Mutex::new(d)) as *mut SwDisturbance;
}

/// What the handle `d` stands for, if it is live.
fn entry(d: *const SwDisturbance) -> Outcome<Arc<Mutex<Disturb>>> {
    if d.is_null() {
        return Err(Failure::null("disturbance"));
    }
    DISTURBANCES.get(d as usize).ok_or_else(|| {
        Failure::new(
            SW_ERROR_INVALID_HANDLE,
            format!(
                "disturbance handle {d:p} is not a live rain or wake (never created, or \
                 destroyed)"
            ),
        )
    })
}

/// Locks a disturbance for one call: an overlapping call on it is `SW_ERROR_BUSY`.
fn lock<'a>(
    d: *const SwDisturbance,
    entry: &'a Mutex<Disturb>,
) -> Outcome<MutexGuard<'a, Disturb>> {
    match entry.try_lock() {
        Ok(guard) => Ok(guard),
        Err(TryLockError::WouldBlock) => Err(Failure::new(
            SW_ERROR_BUSY,
            format!("disturbance {d:p} is in use by another call, or listed twice in this one"),
        )),
        Err(TryLockError::Poisoned(_)) => Err(Failure::new(
            SW_ERROR_INTERNAL,
            format!("disturbance {d:p} failed internally in an earlier call; destroy it"),
        )),
    }
}

/// `f` on one live disturbance, locked for the call.
fn with<T>(d: *const SwDisturbance, f: impl FnOnce(&mut Disturb) -> Outcome<T>) -> Outcome<T> {
    let entry = entry(d)?;
    let mut guard = lock(d, &entry)?;
    f(&mut guard)
}

/// The body of the calls on one rain: `f` on it, or an error for a wake.
fn with_rain<T>(d: *const SwDisturbance, f: impl FnOnce(&mut Rain) -> Outcome<T>) -> Outcome<T> {
    with(d, |disturbance| match disturbance {
        Disturb::Rain(rain) => f(rain),
        Disturb::Wake(_) => Err(Failure::invalid(format!(
            "disturbance {d:p} is a wake, not rain"
        ))),
    })
}

/// The body of the calls on one wake: `f` on it, or an error for rain.
fn with_wake<T>(d: *const SwDisturbance, f: impl FnOnce(&mut Wake) -> Outcome<T>) -> Outcome<T> {
    with(d, |disturbance| match disturbance {
        Disturb::Wake(wake) => f(wake),
        Disturb::Rain(_) => Err(Failure::invalid(format!(
            "disturbance {d:p} is rain, not a wake"
        ))),
    })
}

/// Makes rain of `rate` drops per second (finite, at least 0; 0 is no rain) whose drops
/// fall where and when `seed` says (the same seed, the same drops, however the time is cut
/// into frames), with radii from `radius_min` to `radius_max` world units (finite, > 0,
/// ordered; the library's default is 1.5 to 3) and a depth of `depth` of the radius (in
/// (0, 1]; default 0.6), and writes its handle to `out`. Drops land anywhere on the window
/// of the surface it falls on. Refused, making nothing, when a value is out of range.
///
/// # Safety
///
/// `out` is NULL or a valid pointer.
#[no_mangle]
pub unsafe extern "C" fn sw_rain_create(
    rate: f32,
    seed: u64,
    radius_min: f32,
    radius_max: f32,
    depth: f32,
    out: *mut *mut SwDisturbance,
) -> SwStatus {
    guard(|| {
        let out = out_ref(out, "out")?;
        let rain = rain(rate, seed, radius_min, radius_max, depth)?;
        keep(Disturb::Rain(rain), out);
        Ok(())
    })
}

/// Sets the rate of rain (drops per second, finite, at least 0; 0 stops it). A wake is
/// `SW_ERROR_INVALID_ARGUMENT`.
#[no_mangle]
pub extern "C" fn sw_rain_set_rate(rain: *mut SwDisturbance, rate: f32) -> SwStatus {
    guard(|| {
        rain_rate(rate)?;
        with_rain(rain, |r| {
            r.rate = rate;
            Ok(())
        })
    })
}

/// Writes the number of drops the rain has let fall so far to `out`. A wake is
/// `SW_ERROR_INVALID_ARGUMENT`.
///
/// # Safety
///
/// `out` is NULL or a valid pointer.
#[no_mangle]
pub unsafe extern "C" fn sw_rain_fallen(rain: *const SwDisturbance, out: *mut u64) -> SwStatus {
    guard(|| {
        let out = out_ref(out, "out")?;
        *out = with_rain(rain, |r| Ok(r.fallen()))?;
        Ok(())
    })
}

/// Writes the seconds the rain has fallen so far (the substeps it was applied before) to
/// `out`. A wake is `SW_ERROR_INVALID_ARGUMENT`.
///
/// # Safety
///
/// `out` is NULL or a valid pointer.
#[no_mangle]
pub unsafe extern "C" fn sw_rain_time(rain: *const SwDisturbance, out: *mut f64) -> SwStatus {
    guard(|| {
        let out = out_ref(out, "out")?;
        *out = with_rain(rain, |r| Ok(r.time()))?;
        Ok(())
    })
}

/// Makes a wake: an object moving at `speed` world units per second along the closed path
/// of `corners` points (`xz[2k]`, `xz[2k + 1]` is corner `k`, world units in the water's
/// local space; at least two distinct finite corners), from its first corner, pressing
/// the water down under it with the pressure `strength · exp(−d² / radius²)` (lattice force
/// units per unit area) out to three `radius`. The library's defaults are a speed of 60,
/// a radius of 2.5 and a strength of 1.5. `speed` and `strength` must be finite, `radius`
/// finite and > 0. Writes its handle to `out`; refused, making nothing, when a value is
/// out of range.
///
/// # Safety
///
/// `xz` is NULL or points to `2 · corners` floats; `out` is NULL or a valid pointer.
#[no_mangle]
pub unsafe extern "C" fn sw_wake_create(
    xz: *const f32,
    corners: usize,
    speed: f32,
    radius: f32,
    strength: f32,
    out: *mut *mut SwDisturbance,
) -> SwStatus {
    guard(|| {
        let floats = corners
            .checked_mul(2)
            .ok_or_else(|| Failure::invalid("corners is too large"))?;
        let points = in_slice(xz, floats, "xz")?;
        let out = out_ref(out, "out")?;
        let path = points.chunks_exact(2).map(|p| [p[0], p[1]]).collect();
        let wake = wake_with(Wake::new(path)?, speed, radius, strength)?;
        keep(Disturb::Wake(wake), out);
        Ok(())
    })
}

/// Makes a wake going round a circle of `circle_radius` world units about the middle of
/// `surface`'s window, counter-clockwise seen from above (a 64-gon; a circle too small for
/// one is a short back-and-forth), with `speed`, `radius` and `strength` as for
/// `sw_wake_create`, and writes its handle to `out`. The surface is only read.
///
/// # Safety
///
/// `out` is NULL or a valid pointer.
#[no_mangle]
pub unsafe extern "C" fn sw_wake_circle(
    surface: *const SwSurface,
    circle_radius: f32,
    speed: f32,
    radius: f32,
    strength: f32,
    out: *mut *mut SwDisturbance,
) -> SwStatus {
    guard(|| {
        let out = out_ref(out, "out")?;
        if !circle_radius.is_finite() {
            return Err(Failure::invalid(format!(
                "circle_radius is {circle_radius}, expected a finite number"
            )));
        }
        let wake = handle::with(surface, |w| Ok(Wake::circle(&w.surface, circle_radius)))?;
        let wake = wake_with(wake, speed, radius, strength)?;
        keep(Disturb::Wake(wake), out);
        Ok(())
    })
}

/// Writes where the wake's object is now, world `[x, z]`, to `out[0..2]`. Rain is
/// `SW_ERROR_INVALID_ARGUMENT`.
///
/// # Safety
///
/// `out` is NULL or points to 2 writable floats.
#[no_mangle]
pub unsafe extern "C" fn sw_wake_position(wake: *const SwDisturbance, out: *mut f32) -> SwStatus {
    guard(|| {
        let out = out_array(out, "out")?;
        *out = with_wake(wake, |w| Ok(w.position()))?;
        Ok(())
    })
}

/// Moves the wake's whole path by `(dx, dz)` world units, keeping the object's progress
/// along it: after `sw_surface_rebase(surface, dcols, drows)` a wake follows the water
/// with `dx = −dcols · spacing`, `dz = −drows · spacing`. Refused, with nothing changed,
/// when a corner would not be finite. Rain is `SW_ERROR_INVALID_ARGUMENT`.
#[no_mangle]
pub extern "C" fn sw_wake_translate(wake: *mut SwDisturbance, dx: f32, dz: f32) -> SwStatus {
    guard(|| with_wake(wake, |w| Ok(w.translate(dx, dz)?)))
}

/// Frees rain or a wake. NULL, and a handle already destroyed, are no-ops.
#[no_mangle]
pub extern "C" fn sw_disturbance_destroy(disturbance: *mut SwDisturbance) {
    let _ = std::panic::catch_unwind(|| DISTURBANCES.remove(disturbance as usize));
}

/// `sw_surface_advance` with the `count` disturbances at `disturbances` applied, in their
/// order, before every substep: each gets the substep's length in seconds, so rain falls
/// and wakes move on the water's clock. Writes the steps taken to `substeps` (optional).
/// Every handle must be live and listed once (`SW_ERROR_INVALID_HANDLE`, `SW_ERROR_BUSY`),
/// checked before anything changes. A disturbance or step that fails stops the frame there:
/// before the first step nothing has changed, after it the earlier steps stay applied.
///
/// # Safety
///
/// `disturbances` is NULL or points to `count` handles (NULL for `count` 0); `substeps` is
/// NULL or a valid pointer.
#[no_mangle]
pub unsafe extern "C" fn sw_surface_advance_with(
    surface: *mut SwSurface,
    frame_time: f32,
    disturbances: *const *mut SwDisturbance,
    count: usize,
    substeps: *mut u32,
) -> SwStatus {
    guard(|| {
        let handles = in_slice(disturbances, count, "disturbances")?;
        let substeps = optional(substeps, "substeps")?;
        let entries = handles
            .iter()
            .map(|&d| entry(d))
            .collect::<Outcome<Vec<_>>>()?;
        let mut guards = handles
            .iter()
            .zip(&entries)
            .map(|(&d, e)| lock(d, e))
            .collect::<Outcome<Vec<_>>>()?;
        let mut list: Vec<&mut Disturb> = guards.iter_mut().map(|g| &mut **g).collect();
        frame(surface, substeps, |s| {
            s.advance_with(frame_time, &mut list[..])
        })
    })
}
