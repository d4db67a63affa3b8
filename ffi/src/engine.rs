//! A surface's energy (a diagnostic), and the SIMD level its engine runs: every level
//! gives the same bits, only the speed differs.

use crate::handle::{self, SwSurface};
use crate::params::{simd_code, simd_level, SwSimdLevel};
use crate::ptr::{optional, read_into};
use crate::status::{guard, SwStatus};

/// Kinetic and spring potential energy (a diagnostic).
#[repr(C)]
#[derive(Debug, Clone, Copy, Default)]
pub struct SwEnergy {
    /// Sum of ½ m |v|² over free nodes.
    pub kinetic: f64,
    /// Sum of ½ c (L − L0)² over all springs.
    pub potential: f64,
    /// Kinetic plus potential.
    pub total: f64,
}

/// Writes the kinetic and spring potential energy to `out`.
///
/// # Safety
///
/// `out` is NULL or a valid pointer.
#[no_mangle]
pub unsafe extern "C" fn sw_surface_energy(
    surface: *const SwSurface,
    out: *mut SwEnergy,
) -> SwStatus {
    read_into(surface, out, |w| {
        let e = w.surface.energy();
        Ok(SwEnergy {
            kinetic: e.kinetic,
            potential: e.potential,
            total: e.total(),
        })
    })
}

/// Writes the SIMD level the surface runs to `out`.
///
/// # Safety
///
/// `out` is NULL or a valid pointer.
#[no_mangle]
pub unsafe extern "C" fn sw_surface_simd_level(
    surface: *const SwSurface,
    out: *mut SwSimdLevel,
) -> SwStatus {
    read_into(surface, out, |w| Ok(simd_code(w.surface.simd_level())))
}

/// Runs the surface at `level`, clamped to what the CPU has, and writes the level it will
/// run to `ran` (optional). Results do not change by a bit; only the speed does.
///
/// # Safety
///
/// `ran` is NULL or a valid pointer.
#[no_mangle]
pub unsafe extern "C" fn sw_surface_set_simd_level(
    surface: *mut SwSurface,
    level: SwSimdLevel,
    ran: *mut SwSimdLevel,
) -> SwStatus {
    guard(|| {
        let level = simd_level(level)?;
        let ran = optional(ran, "ran")?;
        handle::with(surface, |w| {
            let level = w.surface.set_simd_level(level);
            if let Some(out) = ran {
                *out = simd_code(level);
            }
            Ok(())
        })
    })
}
