//! The lattice's stability law, in one place: the critical timestep of the bounds a
//! surface has reached, and the damping a timestep leaves room for.
//!
//! Symplectic Euler with the explicit damping `−γv` keeps a mode of angular frequency `ω`
//! bounded while `ω²Δt² + 2bΔt < 4` (`b = γ/m`; the Jury conditions, see the
//! [`Params`](crate::Params) docs). While no spring is compressed below half its rest
//! length, each of a node's eight springs adds at most `c` in every direction, so
//! `ω² ≤ (12c + k)/m`, `k` the stiffness floating bodies' waterlines add to a node. The
//! law is then applied to the worst node the surface can have: its smallest mass, largest
//! spring coefficient and largest viscosity, as ever set ([`Stability`]).
//!
//! * The **critical timestep** is the positive root of `ω²Δt² + 2bΔt = 4`.
//! * The **damping room** of a timestep is the rate `b_lim = (4 − ω²Δt²) / (2Δt)` it
//!   leaves: what an absorbing frame (the `absorb` module) and the floating bodies' drag
//!   (the bodies' coupling) may add without making the step unstable.

use crate::error::{Error, Result};

/// The bounds behind the critical timestep: the smallest node mass, the largest spring
/// coefficient and the largest viscosity a surface has ever had. They only move towards
/// less room: an edit that would take the timestep past the limit is refused before they
/// move.
#[derive(Debug, Clone, Copy, PartialEq)]
pub(crate) struct Stability {
    pub min_mass: f32,
    pub max_stiffness: f32,
    pub max_viscosity: f32,
}

impl Stability {
    /// From `[min_mass, max_stiffness, max_viscosity]` (as a snapshot stores them).
    pub fn from_bounds([min_mass, max_stiffness, max_viscosity]: [f32; 3]) -> Self {
        Self {
            min_mass,
            max_stiffness,
            max_viscosity,
        }
    }

    /// `[min_mass, max_stiffness, max_viscosity]`.
    pub fn bounds(&self) -> [f32; 3] {
        [self.min_mass, self.max_stiffness, self.max_viscosity]
    }

    /// These bounds with a node of mass `mass` too.
    pub fn with_mass(self, mass: f32) -> Self {
        Self {
            min_mass: self.min_mass.min(mass),
            ..self
        }
    }

    /// These bounds with a spring of coefficient `stiffness` too.
    pub fn with_stiffness(self, stiffness: f32) -> Self {
        Self {
            max_stiffness: self.max_stiffness.max(stiffness),
            ..self
        }
    }

    /// These bounds with a node of viscosity `viscosity` too.
    pub fn with_viscosity(self, viscosity: f32) -> Self {
        Self {
            max_viscosity: self.max_viscosity.max(viscosity),
            ..self
        }
    }

    /// The critical timestep with `extra` stiffness (force per length) on every node
    /// besides its springs': `sqrt(m / (3c))` with neither viscosity nor extra, else the
    /// positive root of `((12c + extra)/m) Δt² + 2(γ/m) Δt = 4`.
    pub fn critical_dt(&self, extra: f32) -> f32 {
        let Self {
            min_mass,
            max_stiffness,
            max_viscosity,
        } = *self;
        if max_viscosity == 0.0 && extra == 0.0 {
            return (min_mass / (3.0 * max_stiffness)).sqrt();
        }
        let a = (12.0 * max_stiffness as f64 + extra as f64) / min_mass as f64;
        if max_viscosity == 0.0 {
            return (4.0 / a).sqrt() as f32;
        }
        let b = max_viscosity as f64 / min_mass as f64;
        // (sqrt(b² + 4a) − b) / a, written without cancellation as 4 / (sqrt(b² + 4a) + b).
        (4.0 / ((b * b + 4.0 * a).sqrt() + b)) as f32
    }

    /// Refuses `dt` at or past [`Stability::critical_dt`] with `extra`.
    pub fn admit(&self, dt: f32, extra: f32) -> Result<()> {
        check_dt(dt, self.critical_dt(extra))
    }

    /// The damping rate per unit of model time a step of `dt` leaves room for at the
    /// stiffest node with `extra` stiffness: `b_lim = (4 − ω²Δt²) / (2Δt)`, at least 0, in
    /// `f32` (the floating bodies' drag is capped by it).
    pub fn damping_room(&self, dt: f32, extra: f32) -> f32 {
        let omega2 = (12.0 * self.max_stiffness + extra) / self.min_mass;
        ((4.0 - omega2 * dt * dt) / (2.0 * dt)).max(0.0)
    }
}

/// The damping room `b_lim = (4 − ω²Δt²) / (2Δt)` for `omega2 = ω²`, in `f64` (the
/// absorbing frame's peak is sized from it).
pub(crate) fn damping_limit(omega2: f64, dt: f64) -> f64 {
    (4.0 - omega2 * dt * dt) / (2.0 * dt)
}

/// Refuses `dt` at or past `critical`, suggesting a timestep a little below it.
pub(crate) fn check_dt(dt: f32, critical: f32) -> Result<()> {
    if dt < critical {
        Ok(())
    } else {
        Err(Error::TimestepTooLarge {
            dt,
            critical,
            suggest: 0.95 * critical,
        })
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The seed's lattice: m 4, c 7, γ 0.05.
    fn seed() -> Stability {
        Stability::from_bounds([4.0, 7.0, 0.05])
    }

    #[test]
    fn the_critical_timestep_is_the_root_of_the_law() {
        let s = seed();
        let dt = s.critical_dt(0.0) as f64;
        let (omega2, b) = (12.0 * 7.0 / 4.0, 0.05 / 4.0);
        assert!((omega2 * dt * dt + 2.0 * b * dt - 4.0).abs() < 1e-5);
        assert!((dt - 0.4358).abs() < 1e-4);
        // Without viscosity: sqrt(m / 3c); extra stiffness lowers it.
        let undamped = Stability::from_bounds([4.0, 7.0, 0.0]);
        assert_eq!(undamped.critical_dt(0.0), (4.0f32 / 21.0).sqrt());
        assert!(s.critical_dt(10.0) < s.critical_dt(0.0));
        assert!(s.admit(0.4, 0.0).is_ok() && s.admit(0.44, 0.0).is_err());
    }

    #[test]
    fn bounds_only_move_towards_less_room() {
        let s = seed()
            .with_mass(8.0)
            .with_stiffness(1.0)
            .with_viscosity(0.01);
        assert_eq!(s, seed());
        let s = seed()
            .with_mass(2.0)
            .with_stiffness(9.0)
            .with_viscosity(0.5);
        assert_eq!(s.bounds(), [2.0, 9.0, 0.5]);
        assert!(s.critical_dt(0.0) < seed().critical_dt(0.0));
    }

    #[test]
    fn the_damping_room_leaves_the_step_at_its_limit() {
        // 0.8 per unit of model time for the seed at Δt 0.4 (γ < 3.2 at m 4).
        assert!((damping_limit(12.0 * 7.0 / 4.0, 0.4) - 0.8).abs() < 1e-12);
        assert!((seed().damping_room(0.4, 0.0) - 0.8).abs() < 1e-6);
        // Past the undamped limit there is no room left.
        assert_eq!(seed().damping_room(0.5, 0.0), 0.0);
    }
}
