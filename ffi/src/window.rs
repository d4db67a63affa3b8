//! The moving window: the grid is a window onto endless water that can travel with a
//! camera or a ship (shift, follow), and the frame it speaks in can move with the host's
//! floating origin (rebase).

use crate::handle::{self, SwSurface};
use crate::ptr::{out_array, read_into};
use crate::status::{guard, SwStatus};

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
    handle::call(surface, |w| Ok(w.surface.shift(dcols, drows)?))
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
        // Checked before the window moves.
        let out = out_array(out, "out")?;
        *out = handle::with(surface, |w| Ok(w.surface.follow(x, z)?))?;
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
        let out = out_array(out, "out")?;
        *out = handle::with(surface, |w| Ok(w.surface.origin()))?;
        Ok(())
    })
}

/// The whole cells the window has travelled since the surface was made, `[cols, rows]`,
/// written to `out[0..2]`: the sum of every shift (`sw_surface_origin` is this times
/// `spacing`).
///
/// # Safety
///
/// `out` is NULL or points to 2 writable `int64_t`.
#[no_mangle]
pub unsafe extern "C" fn sw_surface_origin_cells(
    surface: *const SwSurface,
    out: *mut i64,
) -> SwStatus {
    guard(|| {
        let out = out_array(out, "out")?;
        *out = handle::with(surface, |w| Ok(w.surface.origin_cells()))?;
        Ok(())
    })
}

/// Writes to `out` half the side of `sw_surface_follow`'s dead zone, in cells: an eighth
/// of the window's shorter side, at least 1.
///
/// # Safety
///
/// `out` is NULL or a valid pointer.
#[no_mangle]
pub unsafe extern "C" fn sw_surface_follow_dead_zone(
    surface: *const SwSurface,
    out: *mut u32,
) -> SwStatus {
    read_into(surface, out, |w| Ok(w.surface.follow_dead_zone() as u32))
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
    handle::call(surface, |w| Ok(w.surface.rebase(dcols, drows)?))
}
