//! Model parameters with the seed's defaults ([`Params`]; its docs explain the timestep limits).

use crate::error::{Error, Result};
use crate::stability::{check_dt, Stability};

/// What happens at the edge of the grid (`#[non_exhaustive]`: a kind of edge may come).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
#[cfg_attr(feature = "serde", derive(serde::Serialize, serde::Deserialize))]
#[non_exhaustive]
pub enum Boundary {
    /// The outer ring of nodes is pinned: a pool with walls (the default).
    #[default]
    Pinned,
    /// No node is pinned: the sheet floats freely (pin nodes by hand with
    /// [`Surface::set_pinned`](crate::Surface::set_pinned)).
    Free,
    /// Open water: waves leave the patch instead of coming back. The outer ring is pinned
    /// and the `width` rings inside it damp outgoing waves with a quadratic viscosity
    /// profile; the frame lies inside the grid, so the undamped water is the
    /// `(cols − 2·width) × (rows − 2·width)` middle. With 32 rings it sends back at most
    /// 1.2·10⁻³ of a ring wave's energy at any step of the ring tests in
    /// `docs/open-water.md`. The default width ([`Boundary::absorbing`], a width of
    /// [`Boundary::ABSORBING_WIDTH`]) fits itself to the grid: 32 rings
    /// where that leaves a middle of at least 32 nodes (grids of 98 nodes across or more),
    /// otherwise the widest frame that leaves 32 nodes, or half of what lies inside the
    /// pinned ring on grids narrower than 66 (15 rings on a 64² grid, 3 on 16²). Any other
    /// width is used as given; the grid must then be at least `2·width + 2` nodes across.
    /// The frame's damping is fitted to the timestep, so it never makes a valid timestep
    /// invalid. How it works and how it was chosen: see the crate's `absorb` module source
    /// and `docs/open-water.md`.
    Absorbing {
        /// Rings of damping inside the pinned outer ring (≥ 1).
        width: usize,
    },
}

impl Boundary {
    /// The default width of an absorbing frame: 32 rings, narrower on grids under 98 nodes
    /// across (see [`Boundary::Absorbing`]).
    pub const ABSORBING_WIDTH: usize = 32;

    /// An absorbing boundary with the default frame width, fitted to the grid (see
    /// [`Boundary::Absorbing`]).
    pub const fn absorbing() -> Self {
        Self::Absorbing {
            width: Self::ABSORBING_WIDTH,
        }
    }

    /// True when the outer ring of nodes is pinned (pinned and absorbing boundaries).
    pub fn pins_border(&self) -> bool {
        !matches!(self, Self::Free)
    }
}

/// Smallest undamped middle, in nodes across, that the default width leaves on grids of
/// 66 nodes or more.
const MIN_MIDDLE: usize = 32;

/// The default frame's width on a grid whose narrower side is `across` nodes: 32 rings, or
/// the widest frame that leaves a middle of `min(32, (across − 2) / 2)` nodes (at least 1
/// ring). `None` when no frame fits (fewer than 4 nodes across).
pub(crate) fn default_width(across: usize) -> Option<usize> {
    let inside = across.checked_sub(2)?;
    let middle = MIN_MIDDLE.min(inside / 2);
    let width = ((inside - middle) / 2).clamp(1, Boundary::ABSORBING_WIDTH);
    (2 * width + 2 <= across).then_some(width)
}

/// The frame width an absorbing boundary asking for `width` rings gets on a `cols × rows`
/// grid: [`default_width`] for the default width, `width` itself otherwise (validation
/// refuses widths that do not fit).
pub(crate) fn frame_width(width: usize, cols: usize, rows: usize) -> usize {
    if width == Boundary::ABSORBING_WIDTH {
        default_width(cols.min(rows)).unwrap_or(width)
    } else {
        width
    }
}

/// Model parameters. Plain data with the seed's defaults; [`Params::validate`] checks it.
///
/// Lengths are world units (the unit of `spacing`, the water's local space); mass is in
/// mass units. The lattice's constants `dt`, `mass`, `stiffness` and `viscosity` are in
/// *model time*, the seed's time unit, and define the model; everything else a game sets
/// or reads is in seconds of its clock ([`Params::acceleration`],
/// [`Surface::advance`](crate::Surface::advance), [`Surface::time`](crate::Surface::time),
/// velocity queries, floating bodies, the rates and speeds of [`crate::disturb`]).
/// [`Params::time_scale`] says how much model time passes per second: with the defaults,
/// 1 s is 24 units of model time, 60 steps of 0.4 (`docs/units.md` lists every quantity
/// with its unit).
///
/// # Where the timestep limits come from
///
/// Symplectic Euler is stable for a linear oscillator of angular frequency ω iff `ω Δt < 2`.
/// The stiffest mode of the lattice therefore sets the limit:
///
/// * **Linear limit at rest** ([`Params::linear_dt_limit`]). Around the flat, pre-tensioned
///   rest state a spring of coefficient `c`, stretched to length `h` with rest length
///   `r·h`, has stiffness `c` along itself and `c(1 − r)` across itself. The stiffest
///   mode is the in-plane checkerboard at wave vector (π, 0): the E spring contributes
///   `4c`, the two diagonals `2·(c/2 + c(1−r)/2)·2`, the S spring `4c(1 − r)`, which adds up
///   to `ω²max = 4c(3 − r)/m`. So small disturbances stay bounded iff
///   `Δt < sqrt(m / (c (3 − r)))` (0.478 with the defaults).
/// * **Large-wave limit** ([`Params::critical_dt`]). A stretched spring stiffens across
///   itself up to `c`, so while no spring is compressed below half its rest length each of a
///   node's 8 springs adds at most `c` in every direction and Gershgorin bounds the
///   spectrum by `ω²max ≤ 12c/m`; `Δt < sqrt(m / (3c))` (0.436 with the defaults) is
///   stable for any such state. The seed's Δt = 0.4 is 92% of it. This is the limit that
///   validation enforces.
/// * **Viscosity.** The seed integrates the damping `−γv` explicitly too. For one mode,
///   symplectic Euler maps `(x, v)` with trace `2 − ω²Δt² − bΔt` and determinant `1 − bΔt`
///   (`b = γ/m`), and the Jury conditions give stability iff `ω²Δt² + 2bΔt < 4`. With
///   `ω²max = 12c/m` the limit is the positive root `Δt = 4 / (sqrt(b² + 48c/m) + b)`, which
///   is `sqrt(m / (3c))` at `γ = 0` and 0.4358 with the defaults. Heavy damping therefore
///   lowers the limit: measured on a 32×32 grid with `m = 4`, `c = 7` at 99% of the
///   undamped limit, `γ = 6` reached NaN within 103 steps. The bound uses the largest `γ`
///   and the smallest `m`.
///
///   Drops steeper than one height per cell can fold the lattice,
///   where no timestep is safe; the engine then reports [`Error::NonFinite`] instead of
///   passing NaN on.
///
/// # Building
///
/// `Params` is `#[non_exhaustive]` (a parameter may come), so code outside the crate starts
/// from [`Params::with_size`] or [`Params::default`] and changes what it needs, with the
/// `with_*` methods or by assigning fields:
///
/// ```
/// use springwater::{Boundary, Params};
///
/// let p = Params::with_size(256, 128)
///     .with_spacing(0.5)
///     .with_viscosity(0.1)
///     .with_boundary(Boundary::absorbing());
/// assert_eq!((p.cols, p.spacing, p.mass), (256, 0.5, 4.0));
/// p.validate()?;
///
/// let mut q = Params::default();
/// q.rest_ratio = 0.6;
/// assert_eq!(q, Params::default().with_rest_ratio(0.6));
/// # Ok::<(), springwater::Error>(())
/// ```
#[derive(Debug, Clone, Copy, PartialEq)]
#[cfg_attr(feature = "serde", derive(serde::Serialize, serde::Deserialize))]
#[non_exhaustive]
pub struct Params {
    /// Nodes per row, the seed's M (default: `128`). At least 2.
    pub cols: usize,
    /// Rows of nodes, the seed's N (default: `128`). At least 2.
    pub rows: usize,
    /// Grid step `h`, distance between neighbouring nodes at rest (default: `1.0`).
    pub spacing: f32,
    /// Nodal mass `m` (default: `4.0`).
    pub mass: f32,
    /// Spring coefficient `c` of every spring, mass units per unit of model time² (default:
    /// `7.0`).
    pub stiffness: f32,
    /// Viscosity `γ`, velocity damping per node, mass units per unit of model time
    /// (default: `0.05`). Zero disables damping.
    pub viscosity: f32,
    /// Integration timestep `Δt`, in model time (default: `0.4`, 1/60 s at the default
    /// [`Params::time_scale`]). Must be below [`Params::critical_dt`].
    pub dt: f32,
    /// Rest length as a fraction of the initial length (default: `0.5`), in `[0, 1]`.
    /// Below 1 the flat surface is pre-tensioned and vertical ripples travel.
    pub rest_ratio: f32,
    /// Edge condition (default: [`Boundary::Pinned`]).
    pub boundary: Boundary,
    /// Uniform acceleration applied to every free node, `[x, y, z]`, world units per second²
    /// (default: zero). The step adds it divided by `time_scale²`.
    pub acceleration: [f32; 3],
    /// Model time units per second of the caller's clock, used by
    /// [`Surface::advance`](crate::Surface::advance) (default: `24.0`). It sets how fast the
    /// water moves on screen: ripples travel [`Params::ripple_speed`] world units per
    /// second, and [`Params::set_ripple_speed`] sets this field from a wanted speed.
    ///
    /// The default makes a 60 Hz frame one step of the seed's `dt = 0.4` (the cheapest
    /// animation that uses the seed's timestep), and ripples then cross about 39 cells per
    /// second: a 128-cell pool in about 3.3 s, which is what the `springwater render`
    /// preview shows (3 steps per frame at 20 frames per second). Must be finite and > 0,
    /// with `time_scale²` a normal `f32` (about 1.1e-19 to 1.8e19): accelerations and the
    /// forces of floating bodies are converted with it.
    #[cfg_attr(feature = "serde", serde(default = "default_time_scale"))]
    pub time_scale: f32,
}

#[cfg(feature = "serde")]
fn default_time_scale() -> f32 {
    Params::default().time_scale
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
            time_scale: 24.0,
        }
    }
}

/// Largest node count a surface accepts: 2^26 nodes (8192×8192), about 7 GiB of state,
/// so that a grid that passes validation also fits in a machine's memory instead of
/// being killed while it is allocated.
pub const MAX_NODES: usize = 1 << 26;

/// Bytes of state per node: positions and velocities double-buffered (48), external
/// forces (12), mass, 1/m and viscosity (12), the pinned flag (1) and the spring tables
/// (32). The scalar reference adds 48 more the first time it runs.
pub(crate) const BYTES_PER_NODE: u128 = 48 + 12 + 12 + 1 + 32;

impl Params {
    /// The seed's parameters on a `cols × rows` grid.
    pub fn with_size(cols: usize, rows: usize) -> Self {
        Self {
            cols,
            rows,
            ..Self::default()
        }
    }

    /// With grid step `spacing` ([`Params::spacing`]).
    #[must_use]
    pub fn with_spacing(self, spacing: f32) -> Self {
        Self { spacing, ..self }
    }

    /// With nodal mass `mass` ([`Params::mass`]).
    #[must_use]
    pub fn with_mass(self, mass: f32) -> Self {
        Self { mass, ..self }
    }

    /// With spring coefficient `stiffness` ([`Params::stiffness`]).
    #[must_use]
    pub fn with_stiffness(self, stiffness: f32) -> Self {
        Self { stiffness, ..self }
    }

    /// With viscosity `viscosity` ([`Params::viscosity`]).
    #[must_use]
    pub fn with_viscosity(self, viscosity: f32) -> Self {
        Self { viscosity, ..self }
    }

    /// With timestep `dt` ([`Params::dt`]).
    #[must_use]
    pub fn with_dt(self, dt: f32) -> Self {
        Self { dt, ..self }
    }

    /// With rest length ratio `rest_ratio` ([`Params::rest_ratio`]).
    #[must_use]
    pub fn with_rest_ratio(self, rest_ratio: f32) -> Self {
        Self { rest_ratio, ..self }
    }

    /// With edge condition `boundary` ([`Params::boundary`]).
    #[must_use]
    pub fn with_boundary(self, boundary: Boundary) -> Self {
        Self { boundary, ..self }
    }

    /// With uniform acceleration `acceleration` ([`Params::acceleration`]).
    #[must_use]
    pub fn with_acceleration(self, acceleration: [f32; 3]) -> Self {
        Self {
            acceleration,
            ..self
        }
    }

    /// With `time_scale` model time units per second ([`Params::time_scale`]).
    #[must_use]
    pub fn with_time_scale(self, time_scale: f32) -> Self {
        Self { time_scale, ..self }
    }

    /// Number of nodes, `cols × rows` (saturating: parameters are not validated yet).
    pub fn node_count(&self) -> usize {
        self.cols.saturating_mul(self.rows)
    }

    /// Number of nodes.
    #[deprecated(
        since = "0.2.0",
        note = "use `node_count`, the one name for the node count"
    )]
    pub fn nodes(&self) -> usize {
        self.node_count()
    }

    /// The guaranteed (large-wave) stability limit: `sqrt(m / (3c))` without viscosity,
    /// a little less with it (see the [`Params`] docs).
    pub fn critical_dt(&self) -> f32 {
        let stability = Stability::from_bounds([self.mass, self.stiffness, self.viscosity]);
        stability.critical_dt(0.0)
    }

    /// The linear stability limit at rest `sqrt(m / (c (3 − rest_ratio)))`: see the [`Params`] docs.
    pub fn linear_dt_limit(&self) -> f32 {
        (self.mass / (self.stiffness * (3.0 - self.rest_ratio))).sqrt()
    }

    /// Speed of small ripples in world units per **second** of the caller's clock:
    /// `time_scale · h · sqrt(3c(1 − rest_ratio)/m)` (the lattice's long-wave speed per unit
    /// of model time, see the crate docs' model section, times the time scale). About 39 with
    /// the defaults. Zero when `rest_ratio = 1` (no tension: ripples do not travel).
    pub fn ripple_speed(&self) -> f32 {
        self.time_scale * self.model_ripple_speed()
    }

    /// Ripple speed in world units per unit of model time.
    fn model_ripple_speed(&self) -> f32 {
        self.spacing * (3.0 * self.stiffness * (1.0 - self.rest_ratio) / self.mass).sqrt()
    }

    /// Sets [`Params::time_scale`] so that ripples travel `speed` world units per second.
    /// Refused (nothing changed) when `speed` is not finite and positive, or when the other
    /// parameters give ripples no speed to scale (`rest_ratio = 1`) or a time scale
    /// validation would refuse.
    ///
    /// ```
    /// use springwater::Params;
    ///
    /// let mut p = Params::with_size(256, 256);
    /// p.set_ripple_speed(128.0)?;                  // cross the pool in about 2 s
    /// assert!((p.ripple_speed() - 128.0).abs() < 1e-3);
    /// # Ok::<(), springwater::Error>(())
    /// ```
    pub fn set_ripple_speed(&mut self, speed: f32) -> Result<()> {
        positive("ripple speed", speed)?;
        let per_model_time = self.model_ripple_speed();
        let time_scale = speed / per_model_time;
        if !(per_model_time.is_finite() && per_model_time > 0.0) {
            return Err(Error::InvalidParam {
                name: "ripple speed",
                value: speed as f64,
                expected: "a speed the lattice can have: it needs rest_ratio < 1 and valid spacing, mass and stiffness",
            });
        }
        check_time_scale(time_scale)?;
        self.time_scale = time_scale;
        Ok(())
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
        let extent = self.spacing as f64 * (self.cols.max(self.rows) - 1) as f64;
        if extent > MAX_EXTENT {
            return Err(Error::InvalidParam {
                name: "spacing",
                value: self.spacing as f64,
                expected: "small enough that the grid spans at most 1e15 units (squared lengths must stay finite)",
            });
        }
        positive("mass", self.mass)?;
        if !(1.0 / self.mass).is_finite() {
            return Err(Error::InvalidParam {
                name: "mass",
                value: self.mass as f64,
                expected: "at least 1.2e-38 (the reciprocal must be finite)",
            });
        }
        positive("stiffness", self.stiffness)?;
        positive("dt", self.dt)?;
        non_negative("viscosity", self.viscosity)?;
        let r = self.rest_ratio;
        if !(r.is_finite() && (0.0..=1.0).contains(&r)) {
            return Err(Error::InvalidParam {
                name: "rest_ratio",
                value: r as f64,
                expected: "a number in [0, 1]",
            });
        }
        check_time_scale(self.time_scale)?;
        if let Boundary::Absorbing { width } = self.boundary {
            let across = self.cols.min(self.rows);
            let fitted = frame_width(width, self.cols, self.rows);
            if fitted == 0 || across < fitted.saturating_mul(2).saturating_add(2) {
                return Err(Error::InvalidParam {
                    name: "absorbing width",
                    value: width as f64,
                    expected: "at least 1 and at most (min(cols, rows) − 2) / 2: choose a narrower frame or a larger grid, or the default width, which fits itself to grids of 4 nodes across or more",
                });
            }
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

/// Checks a time scale: finite, > 0, and its square a normal `f32` (it converts
/// accelerations and forces between seconds and model time).
fn check_time_scale(time_scale: f32) -> Result<()> {
    positive("time_scale", time_scale)?;
    let square = time_scale * time_scale;
    if !square.is_normal() {
        return Err(Error::InvalidParam {
            name: "time_scale",
            value: time_scale as f64,
            expected: "a time scale whose square is a normal f32 (about 1.1e-19 to 1.8e19)",
        });
    }
    Ok(())
}

/// Largest grid extent `spacing × (max(cols, rows) − 1)` that validation accepts.
pub const MAX_EXTENT: f64 = 1e15;

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
