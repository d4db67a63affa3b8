//! What a WebAssembly host needs beside the C ABI (compiled only for `wasm32`; not in the
//! header): memory it can write into before a call, and the library's disturbances (rain,
//! wakes) as handles, since a JavaScript caller cannot hand Rust a `Disturbance`. The npm
//! package in `web/` calls these; everything else it calls is the C ABI itself.
//!
//! Buffers are kept in a table keyed by their address, so freeing one the library did not
//! hand out (or freeing twice) is a no-op instead of undefined behaviour, and no `unsafe`
//! code is needed here.

use crate::disturb::{rain, rain_rate, Disturb};
use crate::handle::{self, SwSurface};
use crate::params::finite_positive;
use crate::ptr::{in_slice, out_ref};
use crate::status::{guard, Failure, SwStatus};
use springwater::disturb::Wake;
use std::cell::RefCell;
use std::collections::HashMap;

thread_local! {
    static BUFFERS: RefCell<HashMap<usize, Box<[u64]>>> = RefCell::new(HashMap::new());
    static DISTURBANCES: RefCell<(u32, HashMap<u32, Disturb>)> = RefCell::new((0, HashMap::new()));
}

/// Allocates `bytes` bytes (rounded up to 8, zeroed, aligned to 8) and returns their
/// address, or NULL for 0 bytes or when memory cannot grow.
#[no_mangle]
pub extern "C" fn sw_wasm_alloc(bytes: usize) -> *mut u8 {
    if bytes == 0 {
        return std::ptr::null_mut();
    }
    let words = bytes.div_ceil(8);
    let mut storage = Vec::new();
    if storage.try_reserve_exact(words).is_err() {
        return std::ptr::null_mut();
    }
    storage.resize(words, 0u64);
    let mut buffer = storage.into_boxed_slice();
    let address = buffer.as_mut_ptr().cast::<u8>();
    BUFFERS.with(|b| b.borrow_mut().insert(address as usize, buffer));
    address
}

/// Frees a buffer `sw_wasm_alloc` returned. NULL, and any other address, are no-ops.
#[no_mangle]
pub extern "C" fn sw_wasm_free(address: *mut u8) {
    BUFFERS.with(|b| b.borrow_mut().remove(&(address as usize)));
}

fn keep(d: Disturb) -> u32 {
    DISTURBANCES.with(|t| {
        let mut t = t.borrow_mut();
        t.0 += 1;
        let id = t.0;
        t.1.insert(id, d);
        id
    })
}

/// Rain (`springwater::disturb::Rain`) of `rate` drops per second (finite, at least 0)
/// from `seed`, drop radii from `radius_min` to `radius_max` world units (finite, > 0,
/// ordered) and depth `depth` of the radius (in (0, 1]). Writes its id to `out`.
///
/// # Safety
///
/// `out` is NULL or a valid pointer.
#[no_mangle]
pub unsafe extern "C" fn sw_wasm_rain_create(
    rate: f32,
    seed: u64,
    radius_min: f32,
    radius_max: f32,
    depth: f32,
    out: *mut u32,
) -> SwStatus {
    guard(|| {
        let out = out_ref(out, "out")?;
        *out = keep(Disturb::Rain(rain(
            rate, seed, radius_min, radius_max, depth,
        )?));
        Ok(())
    })
}

/// Sets the rate of rain `id` (finite, at least 0; 0 stops it).
#[no_mangle]
pub extern "C" fn sw_wasm_rain_set_rate(id: u32, rate: f32) -> SwStatus {
    guard(|| {
        rain_rate(rate)?;
        DISTURBANCES.with(|t| match t.borrow_mut().1.get_mut(&id) {
            Some(Disturb::Rain(rain)) => {
                rain.rate = rate;
                Ok(())
            }
            _ => Err(Failure::invalid(format!("{id} is not a live rain"))),
        })
    })
}

/// A wake (`springwater::disturb::Wake`) along the closed path of `corners` points
/// (`xz`: x, z pairs, world units), moving at `speed` world units per second, with
/// footprint `radius` and peak pressure `strength` (all finite, > 0). Writes its id to
/// `out`.
///
/// # Safety
///
/// `xz` holds `2 · corners` floats; `out` is NULL or a valid pointer.
#[no_mangle]
pub unsafe extern "C" fn sw_wasm_wake_create(
    xz: *const f32,
    corners: usize,
    speed: f32,
    radius: f32,
    strength: f32,
    out: *mut u32,
) -> SwStatus {
    guard(|| {
        let out = out_ref(out, "out")?;
        let len = corners
            .checked_mul(2)
            .ok_or_else(|| Failure::invalid("too many corners"))?;
        let points = in_slice(xz, len, "xz")?;
        finite_positive("wake speed", speed)?;
        finite_positive("wake radius", radius)?;
        finite_positive("wake strength", strength)?;
        let path = points.chunks_exact(2).map(|p| [p[0], p[1]]).collect();
        let mut wake = Wake::new(path)?;
        wake.speed = speed;
        wake.radius = radius;
        wake.strength = strength;
        *out = keep(Disturb::Wake(wake));
        Ok(())
    })
}

/// Forgets rain or wake `id`. An id not live is a no-op.
#[no_mangle]
pub extern "C" fn sw_wasm_disturbance_destroy(id: u32) {
    DISTURBANCES.with(|t| t.borrow_mut().1.remove(&id));
}

/// `sw_surface_advance` with the disturbances `ids` (`count` distinct live ids) applied
/// before every substep (`Surface::advance_with`). Writes the steps taken to `substeps`
/// (optional).
///
/// # Safety
///
/// `ids` holds `count` ids; `substeps` is NULL or a valid pointer.
#[no_mangle]
pub unsafe extern "C" fn sw_wasm_advance_with(
    surface: *mut SwSurface,
    frame_time: f32,
    ids: *const u32,
    count: usize,
    substeps: *mut u32,
) -> SwStatus {
    guard(|| {
        let ids = in_slice(ids, count, "ids")?;
        let substeps = crate::ptr::optional(substeps, "substeps")?;
        // Take the disturbances out of the table for the call, and put them back after.
        let mut taken: Vec<(u32, Disturb)> = Vec::with_capacity(ids.len());
        let missing = DISTURBANCES.with(|t| {
            let mut t = t.borrow_mut();
            for &id in ids {
                match t.1.remove(&id) {
                    Some(d) => taken.push((id, d)),
                    None => return Some(id),
                }
            }
            None
        });
        let result = match missing {
            Some(id) => Err(Failure::invalid(format!(
                "disturbance {id} is not live (never made, destroyed, or listed twice)"
            ))),
            None => handle::with(surface, |w| {
                let mut list: Vec<&mut Disturb> = taken.iter_mut().map(|(_, d)| d).collect();
                let taken = w.surface.advance_with(frame_time, &mut list[..])?;
                if let Some(out) = substeps {
                    *out = taken as u32;
                }
                Ok(())
            }),
        };
        DISTURBANCES.with(|t| t.borrow_mut().1.extend(taken));
        result
    })
}
