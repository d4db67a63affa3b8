//! Model parameters with the seed's defaults, their validation and the two timestep limits.
//!
//! # Where the timestep limits come from
//!
//! Symplectic Euler is stable for a linear oscillator of angular frequency ω iff `ω Δt < 2`.
//! The stiffest mode of the lattice therefore sets the limit:
//!
//! * **Linear limit at rest** ([`Params::linear_dt_limit`]). Around the flat, pre-tensioned
//!   rest state a spring of coefficient `c`, stretched to length `h` with rest length
//!   `r·h`, has stiffness `c` along itself and `c(1 − r)` across itself. The stiffest
//!   mode is the in-plane checkerboard at wave vector (π, 0): the E spring contributes
//!   `4c`, the two diagonals `2·(c/2 + c(1−r)/2)·2`, the S spring `4c(1 − r)`, which adds up
//!   to `ω²max = 4c(3 − r)/m`. So small disturbances stay bounded iff
//!   `Δt < sqrt(m / (c (3 − r)))` (0.478 with the defaults).
//! * **Large-wave limit** ([`Params::critical_dt`]). A stretched spring stiffens across
//!   itself up to `c`, so while no spring is compressed below half its rest length each of a
//!   node's 8 springs adds at most `c` in every direction and Gershgorin bounds the
//!   spectrum by `ω²max ≤ 12c/m`; `Δt < sqrt(m / (3c))` (0.436 with the defaults) is
//!   stable for any such state. The seed's Δt = 0.4 is 92% of it. This is the limit that
//!   validation enforces. Drops steeper than one height per cell can fold the lattice,
//!   where no timestep is safe; the engine then reports [`Error::NonFinite`] instead of
//!   passing NaN on.

use crate::error::{Error, Result};

/// What happens at the edge of the grid.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
#[cfg_attr(feature = "serde", derive(serde::Serialize, serde::Deserialize))]
pub enum Boundary {
    /// The outer ring of nodes is pinned: a pool with walls (the default).
    #[default]
    Pinned,
    /// No node is pinned: the sheet floats freely (pin nodes by hand with
    /// [`Surface::set_pinned`](crate::Surface::set_pinned)).
    Free,
}

/// Model parameters. Plain data with the seed's defaults; [`Params::validate`] checks it.
///
/// Units are the model's own: lengths in grid units of the world, time in the seed's
/// time unit, mass in mass units.
#[derive(Debug, Clone, Copy, PartialEq)]
#[cfg_attr(feature = "serde", derive(serde::Serialize, serde::Deserialize))]
pub struct Params {
    /// Nodes per row, the seed's M (default: `128`). At least 2.
    pub cols: usize,
    /// Rows of nodes, the seed's N (default: `128`). At least 2.
    pub rows: usize,
    /// Grid step `h`, distance between neighbouring nodes at rest (default: `1.0`).
    pub spacing: f32,
    /// Nodal mass `m` (default: `4.0`).
    pub mass: f32,
    /// Spring coefficient `c` of every spring (default: `7.0`).
    pub stiffness: f32,
    /// Viscosity `γ`, velocity damping per node (default: `0.05`). Zero disables damping.
    pub viscosity: f32,
    /// Integration timestep `Δt` (default: `0.4`). Must be below [`Params::critical_dt`].
    pub dt: f32,
    /// Rest length as a fraction of the initial length (default: `0.5`), in `[0, 1]`.
    /// Below 1 the flat surface is pre-tensioned and vertical ripples travel.
    pub rest_ratio: f32,
    /// Edge condition (default: [`Boundary::Pinned`]).
    pub boundary: Boundary,
    /// Uniform acceleration applied to every free node, `[x, y, z]` (default: zero).
    pub acceleration: [f32; 3],
}

impl Default for Params {
    fn default() -> Self {
        Self {
            cols: 128,
            rows: 128,
            spacing: 1.0,
            mass: 4.0,
            stiffness: 7.0,
            viscosity: 0.05,
            dt: 0.4,
            rest_ratio: 0.5,
            boundary: Boundary::Pinned,
            acceleration: [0.0; 3],
        }
    }
}

/// Largest node count a surface accepts (2^28 nodes, about 10 GiB of state).
pub const MAX_NODES: usize = 1 << 28;

/// Approximate bytes of state per node (positions and velocities double-buffered,
/// forces, per-node and per-spring tables).
pub(crate) const BYTES_PER_NODE: u128 = 4 * (12 + 3 + 2 + 8 + 1);

impl Params {
    /// The seed's parameters on a `cols × rows` grid.
    pub fn with_size(cols: usize, rows: usize) -> Self {
        Self {
            cols,
            rows,
            ..Self::default()
        }
    }

    /// Number of nodes, `cols × rows`.
    pub fn nodes(&self) -> usize {
        self.cols.saturating_mul(self.rows)
    }

    /// The guaranteed (large-wave) stability limit `sqrt(m / (3c))`: see the module docs.
    pub fn critical_dt(&self) -> f32 {
        critical_dt(self.mass, self.stiffness)
    }

    /// The linear stability limit at rest `sqrt(m / (c (3 − rest_ratio)))`: see the module docs.
    pub fn linear_dt_limit(&self) -> f32 {
        (self.mass / (self.stiffness * (3.0 - self.rest_ratio))).sqrt()
    }

    /// Checks every field, including `dt < critical_dt()`.
    pub fn validate(&self) -> Result<()> {
        self.validate_except_dt()?;
        check_dt(self.dt, self.critical_dt())
    }

    /// Checks every field except the timestep limit (`dt` must still be finite and > 0).
    pub fn validate_except_dt(&self) -> Result<()> {
        if self.cols < 2 || self.rows < 2 {
            return Err(Error::GridTooSmall {
                cols: self.cols,
                rows: self.rows,
            });
        }
        let nodes = self.cols.checked_mul(self.rows);
        if nodes.is_none_or(|n| n > MAX_NODES) {
            return Err(Error::GridTooLarge {
                cols: self.cols,
                rows: self.rows,
                bytes: (self.cols as u128) * (self.rows as u128) * BYTES_PER_NODE,
            });
        }
        positive("spacing", self.spacing)?;
        positive("mass", self.mass)?;
        positive("stiffness", self.stiffness)?;
        positive("dt", self.dt)?;
        non_negative("viscosity", self.viscosity)?;
        let r = self.rest_ratio;
        if !(r.is_finite() && (0.0..=1.0).contains(&r)) {
            return Err(Error::InvalidParam {
                name: "rest-ratio",
                value: r as f64,
                expected: "a number in [0, 1]",
            });
        }
        for a in self.acceleration {
            if !a.is_finite() {
                return Err(Error::InvalidParam {
                    name: "acceleration",
                    value: a as f64,
                    expected: "finite components",
                });
            }
        }
        Ok(())
    }
}

/// `sqrt(m / (3c))`, the large-wave limit for the smallest mass and largest coefficient.
pub(crate) fn critical_dt(min_mass: f32, max_stiffness: f32) -> f32 {
    (min_mass / (3.0 * max_stiffness)).sqrt()
}

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

pub(crate) fn positive(name: &'static str, v: f32) -> Result<()> {
    if v.is_finite() && v > 0.0 {
        Ok(())
    } else {
        Err(Error::InvalidParam {
            name,
            value: v as f64,
            expected: "a finite number > 0",
        })
    }
}

pub(crate) fn non_negative(name: &'static str, v: f32) -> Result<()> {
    if v.is_finite() && v >= 0.0 {
        Ok(())
    } else {
        Err(Error::InvalidParam {
            name,
            value: v as f64,
            expected: "a finite number >= 0",
        })
    }
}

pub(crate) fn finite(name: &'static str, v: f32) -> Result<()> {
    if v.is_finite() {
        Ok(())
    } else {
        Err(Error::InvalidParam {
            name,
            value: v as f64,
            expected: "a finite number",
        })
    }
}
