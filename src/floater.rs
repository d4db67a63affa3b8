//! Floating bodies: spheres and boxes that ride the waves and make them, two-way.
//!
//! A [`Floater`] is a rigid body that translates (it does not rotate) on a [`Surface`]
//! (added with [`Surface::add_floater`]); the surface steps its bodies with every step and
//! substep, and keeps them in snapshots. Lengths are world units, masses the lattice's mass
//! units, and time is **seconds** of the game's clock: velocities are world units per
//! second, gravity world units per second², the drag rate per second, forces mass × world
//! units per second² (see `docs/units.md`). A body's state is stored in those units and its
//! step runs in them, `Δt = dt / time_scale` seconds for a step of model time `dt`
//! ([`Params::time_scale`](crate::Params::time_scale)); only where a body meets the lattice
//! are its numbers converted (next section).
//!
//! # The model, per step of `Δt` seconds
//!
//! **Columns.** The body's footprint is cut into vertical columns at most one grid cell
//! wide: a square lattice over the box's footprint, or over the sphere's disc keeping the
//! columns whose centre lies inside it. Bodies are at most [`MAX_CELLS`] cells across. A column at `(x, z)` spans the
//! body's thickness there, from `y − L/2` to `y + L/2` (`L = 2·sqrt(R² − ρ²)` for a
//! sphere, `ρ` the column's distance from the centre; the box's height for a box). Column
//! areas are scaled so that the columns' volume is exactly the body's.
//!
//! **What each column feels**, from the water under its centre (the surface's bilinear
//! [`height_at`](Surface::height_at) `η` and [`velocity_at`](Surface::velocity_at) `w`):
//!
//! * submerged length `s = clamp(η − (y − L/2), 0, L)`;
//! * buoyancy `ρ_w g s a` upwards (Archimedes; `ρ_w` and `g` from [`Buoyancy`]);
//! * drag `κ (w − v)` with `κ = k ρ_w s a`: the body's [`Floater::drag`] rate `k` times the
//!   mass of water the column displaces, pulling the body towards the water's velocity.
//!   Horizontal water velocity carries the body along.
//!
//! **Integration.** Buoyancy and drag are stiff for light bodies (a ping-pong ball on a
//! wave), so the body's velocity is updated linearly implicitly: with `K = ρ_w g a` for
//! each column cut by the waterline,
//!
//! ```text
//! M v' = M v + Δt (F_push − M g ŷ + Σ [ρ_w g s a − K Δt v'_y] ŷ + Σ κ (w − v'))
//! ```
//!
//! which is solved for `v'` directly (the horizontal and vertical parts separate), so
//! any mass, size and drag is stable for the body; then `x ← x + Δt v'` (symplectic
//! Euler, like the water). The force of each column, `f`, is the bracket evaluated at
//! `v'`, so that `M (v' − v) = Δt (Σ f + F_push − M g ŷ)` to rounding.
//!
//! **Two-way.** Each column pushes `−f` into the water at its own point with
//! [`Surface::add_force_at`], for the same step: what the water gets is exactly minus what
//! the body gets (to the rounding of the bilinear spread and of the change of units: the
//! lattice counts forces per unit of model time², so `−f` goes in divided by
//! `time_scale²`, and the water velocity `w` a column reads is the lattice's times
//! `time_scale`). A body at rest dents the
//! surface by its weight; a moving one pushes a travelling dent, which is what leaves a
//! wake. Columns over no water (outside the patch) see calm water at rest height `y = 0`
//! with zero velocity and push nothing back: the patch is taken to sit in open water.
//!
//! **The water's stability.** To the water, a column is a spring of stiffness `ρ_w g a` and
//! a damper `κ` on the nodes under it, which the explicit step must carry:
//! [`Surface::critical_dt`] adds `ρ_w g h² / time_scale²` (the waterline's stiffness in the
//! lattice's units) to the lattice's largest node stiffness while
//! bodies float (a body whose buoyancy would push the timestep past the limit is refused),
//! and each column's `κ` is capped at half of what the damped limit leaves the four nodes
//! under it (`m b_lim − γ`, see the `absorb` module). Deep, draggy bodies in an absorbing
//! frame therefore drag less there. Bodies stacked on the same cells add their columns up
//! and can exceed the budget; the step then reports [`Error::NonFinite`] like any other
//! blow-up.
//!
//! Not modelled: rotation, added mass, bodies touching each other or the pool's walls.

use crate::error::{Error, Result};
use crate::params;
#[cfg(doc)]
use crate::Surface;
use glam::Vec3;

/// The shape of a [`Floater`] (`#[non_exhaustive]`: a shape may come).
#[derive(Debug, Clone, Copy, PartialEq)]
#[cfg_attr(feature = "serde", derive(serde::Serialize, serde::Deserialize))]
#[non_exhaustive]
pub enum Shape {
    /// A ball of `radius` world units.
    Sphere {
        /// Radius, world units (> 0).
        radius: f32,
    },
    /// A box aligned with the water's axes (bodies do not rotate).
    Box {
        /// Half the box's size along x, y and z, world units (each > 0).
        half_extents: Vec3,
    },
}

impl Shape {
    /// Volume in cubic world units.
    pub fn volume(&self) -> f32 {
        match *self {
            Shape::Sphere { radius } => 4.0 / 3.0 * std::f32::consts::PI * radius.powi(3),
            Shape::Box { half_extents: e } => 8.0 * e.x * e.y * e.z,
        }
    }

    /// Half the body's height: how far it reaches above and below its centre.
    pub fn half_height(&self) -> f32 {
        match *self {
            Shape::Sphere { radius } => radius,
            Shape::Box { half_extents } => half_extents.y,
        }
    }
}

/// A floating body. Plain data: build one, hand it to [`Surface::add_floater`], read it
/// back with [`Surface::floater`].
///
/// ```
/// use springwater::{Floater, Params, Surface};
///
/// let mut water = Surface::new(Params::with_size(64, 64))?;
/// // A ball of radius 2 at half the water's density, dropped from just above calm water.
/// let mut ball = Floater::sphere(2.0, 1.0, [32.0, 1.0, 32.0]);
/// ball.mass = 0.5 * water.buoyancy().density * ball.shape.volume();
/// let id = water.add_floater(ball)?;
/// water.step_n(1500)?;                             // 25 s at the defaults
/// let ball = water.floater(id)?;
/// assert!(ball.position.y.abs() < 0.3);             // about half under
/// assert!(ball.velocity.length() < 0.024);          // at rest (world units per second)
/// # Ok::<(), springwater::Error>(())
/// ```
///
/// `#[non_exhaustive]` (a field may come): outside the crate, start from
/// [`Floater::sphere`] or [`Floater::cuboid`] and assign the fields to change.
#[derive(Debug, Clone, Copy, PartialEq)]
#[cfg_attr(feature = "serde", derive(serde::Serialize, serde::Deserialize))]
#[non_exhaustive]
pub struct Floater {
    /// Sphere or box.
    pub shape: Shape,
    /// Mass, in the lattice's mass units (> 0; a node has [`Params::mass`](crate::Params::mass)).
    pub mass: f32,
    /// Drag rate `k`, per second (≥ 0, at most 1e8): the drag is `k` times the mass of the
    /// displaced water times the velocity relative to the water (default
    /// [`Floater::DEFAULT_DRAG`], 6 per second).
    pub drag: f32,
    /// Centre, world units in the water's local space (the calm surface is `y = 0`).
    pub position: Vec3,
    /// Velocity, world units per second (components at most 1e11; default zero).
    pub velocity: Vec3,
    /// External force (engine, wind, a player's push) for the next step only, cleared by
    /// it; [`Surface::push_floater`] adds to it. Mass units × world units per second²
    /// (default zero).
    pub push: Vec3,
    /// Read only: the force the water exerted on the body during its last step (buoyancy
    /// and drag, without gravity and push), mass units × world units per second². The
    /// water got exactly minus this (in the lattice's units, divided by `time_scale²`).
    pub water_force: Vec3,
}

impl Floater {
    /// Default drag rate `k`: 6 per second (0.25 per unit of model time at the default
    /// time scale of 24).
    pub const DEFAULT_DRAG: f32 = 6.0;

    /// A sphere of `radius` and `mass` centred at `position`, at rest.
    pub fn sphere(radius: f32, mass: f32, position: impl Into<Vec3>) -> Self {
        Self::new(Shape::Sphere { radius }, mass, position.into())
    }

    /// A box of `half_extents` and `mass` centred at `position`, at rest.
    pub fn cuboid(half_extents: impl Into<Vec3>, mass: f32, position: impl Into<Vec3>) -> Self {
        let half_extents = half_extents.into();
        Self::new(Shape::Box { half_extents }, mass, position.into())
    }

    fn new(shape: Shape, mass: f32, position: Vec3) -> Self {
        Self {
            shape,
            mass,
            drag: Self::DEFAULT_DRAG,
            position,
            velocity: Vec3::ZERO,
            push: Vec3::ZERO,
            water_force: Vec3::ZERO,
        }
    }

    /// Checks every field: an error names the first that is out of range.
    pub fn validate(&self) -> Result<()> {
        let size = |name, v: f32| {
            params::positive(name, v)?;
            if v > MAX_SIZE {
                return Err(Error::InvalidParam {
                    name,
                    value: v as f64,
                    expected: "at most 1e9 world units",
                });
            }
            Ok(())
        };
        match self.shape {
            Shape::Sphere { radius } => size("floater radius", radius)?,
            Shape::Box { half_extents: e } => {
                for v in e.to_array() {
                    size("floater half extent", v)?;
                }
            }
        }
        let volume = self.shape.volume();
        if volume.is_nan() || volume < f32::MIN_POSITIVE {
            return Err(Error::InvalidParam {
                name: "floater volume",
                value: volume as f64,
                expected: "at least 1.2e-38 (smaller bodies underflow)",
            });
        }
        params::positive("floater mass", self.mass)?;
        if !(1.0 / self.mass).is_finite() {
            return Err(Error::InvalidParam {
                name: "floater mass",
                value: self.mass as f64,
                expected: "at least 1.2e-38 (the reciprocal must be finite)",
            });
        }
        params::non_negative("floater drag", self.drag)?;
        bounded(
            "floater drag",
            self.drag,
            MAX_DRAG,
            "at most 1e8 per second",
        )?;
        for (name, v, max, expected) in [
            (
                "floater position",
                self.position,
                params::MAX_EXTENT as f32,
                "components within the largest grid extent, 1e15",
            ),
            (
                "floater velocity",
                self.velocity,
                MAX_SPEED,
                "components of at most 1e11 (world units per second)",
            ),
            ("floater push", self.push, f32::MAX, "finite components"),
            (
                "floater water force",
                self.water_force,
                f32::MAX,
                "finite components",
            ),
        ] {
            for c in v.to_array() {
                params::finite(name, c)?;
                bounded(name, c.abs(), max, expected)?;
            }
        }
        Ok(())
    }
}

/// Largest radius or half extent a floater may have, world units.
const MAX_SIZE: f32 = 1e9;
/// Largest speed component, world units per second.
const MAX_SPEED: f32 = 1e11;
/// Largest drag rate, per second.
const MAX_DRAG: f32 = 1e8;
/// Largest gravity, world units per second².
const MAX_GRAVITY: f32 = 1e9;

/// `v ≤ max`, else an error saying `expected`.
fn bounded(name: &'static str, v: f32, max: f32, expected: &'static str) -> Result<()> {
    if v <= max {
        Ok(())
    } else {
        Err(Error::InvalidParam {
            name,
            value: v as f64,
            expected,
        })
    }
}

/// The world the bodies float in: gravity and the water's density, for every body of a
/// surface ([`Surface::set_buoyancy`]).
#[derive(Debug, Clone, Copy, PartialEq)]
#[cfg_attr(feature = "serde", derive(serde::Serialize, serde::Deserialize))]
pub struct Buoyancy {
    /// Gravity pulling bodies down (−y), world units per second² (≥ 0, at most 1e9;
    /// default 57.6: a ball of radius 2 half under bobs with a period of about one second.
    /// It is 0.1 per unit of model time² at the default time scale of 24; with metres as
    /// world units, Earth's is 9.81).
    pub gravity: f32,
    /// Density of the water, mass units per cubic world unit (≥ 0; default 1: the seed's
    /// node mass 4 per cell is a layer 4 cells deep).
    pub density: f32,
}

impl Default for Buoyancy {
    fn default() -> Self {
        Self {
            gravity: 57.6,
            density: 1.0,
        }
    }
}

impl Buoyancy {
    /// Checks both fields: finite, ≥ 0, gravity at most 1e9 and density at most 1e6.
    pub fn validate(&self) -> Result<()> {
        params::non_negative("gravity", self.gravity)?;
        bounded(
            "gravity",
            self.gravity,
            MAX_GRAVITY,
            "at most 1e9 world units per second²",
        )?;
        params::non_negative("water density", self.density)?;
        bounded("water density", self.density, 1e6, "at most 1e6")
    }

    /// The stiffness `ρ_w g h²` a column of one cell adds to the nodes under it, in the
    /// lattice's units (force per unit of model time² per world unit): divided by
    /// `time_scale²`, since `g` is per second².
    pub(crate) fn node_stiffness(&self, spacing: f32, time_scale: f32) -> f32 {
        self.density * self.gravity * spacing * spacing / (time_scale * time_scale)
    }
}

/// A stable name for a floater of one surface; never reused by that surface (also not
/// after the floater is removed). Its number is for crossing boundaries (a C handle, a
/// save game): [`FloaterId::to_raw`] and back with [`FloaterId::from_raw`].
#[derive(Debug, Clone, Copy, PartialEq, Eq, PartialOrd, Ord, Hash)]
#[cfg_attr(feature = "serde", derive(serde::Serialize, serde::Deserialize))]
pub struct FloaterId(pub(crate) u64);

impl FloaterId {
    /// The id whose number is `raw` (from [`FloaterId::to_raw`]). Any number makes an id;
    /// a surface that never gave it answers [`Error::NoSuchFloater`].
    pub const fn from_raw(raw: u64) -> Self {
        Self(raw)
    }

    /// The id's number: the surface's ids count up from 0 in the order floaters were added.
    pub const fn to_raw(self) -> u64 {
        self.0
    }
}

impl From<FloaterId> for u64 {
    fn from(id: FloaterId) -> u64 {
        id.0
    }
}

/// One vertical column of a body: offset of its centre from the body's, area, length.
#[derive(Debug, Clone, Copy, PartialEq)]
pub(crate) struct Column {
    pub dx: f32,
    pub dz: f32,
    pub area: f32,
    pub length: f32,
}

/// Most columns per side of a body's footprint: columns stay at most one cell wide for
/// bodies up to [`MAX_CELLS`] cells across.
const MAX_COLUMNS: usize = 64;

/// The widest footprint a body may have, in cells of the grid it floats on
/// ([`Surface::add_floater`] refuses wider ones): a column wider than a cell would push a
/// whole cell's buoyancy and drag into one node, which the water's timestep cannot carry.
pub const MAX_CELLS: f32 = MAX_COLUMNS as f32;

/// Checks that `shape` is at most [`MAX_CELLS`] cells of `spacing` across in x and z.
pub(crate) fn check_footprint(shape: &Shape, spacing: f32) -> Result<()> {
    let (x, z) = match *shape {
        Shape::Sphere { radius } => (radius, radius),
        Shape::Box { half_extents: e } => (e.x, e.z),
    };
    let widest = 2.0 * x.max(z);
    if widest <= MAX_CELLS * spacing {
        Ok(())
    } else {
        Err(Error::InvalidParam {
            name: "floater size",
            value: widest as f64,
            expected: "a footprint at most 64 grid cells across (in x and z)",
        })
    }
}

/// The columns of `shape` for a grid of `spacing`, about one cell wide each.
pub(crate) fn columns(shape: &Shape, spacing: f32, out: &mut Vec<Column>) {
    out.clear();
    let per_side = |extent: f32| ((2.0 * extent / spacing).ceil() as usize).clamp(1, MAX_COLUMNS);
    match *shape {
        Shape::Box { half_extents: e } => {
            let (nx, nz) = (per_side(e.x), per_side(e.z));
            let (sx, sz) = (2.0 * e.x / nx as f32, 2.0 * e.z / nz as f32);
            for j in 0..nz {
                for i in 0..nx {
                    out.push(Column {
                        dx: -e.x + sx * (i as f32 + 0.5),
                        dz: -e.z + sz * (j as f32 + 0.5),
                        area: sx * sz,
                        length: 2.0 * e.y,
                    });
                }
            }
        }
        Shape::Sphere { radius: r } => {
            let n = per_side(r);
            let s = 2.0 * r / n as f32;
            for j in 0..n {
                for i in 0..n {
                    let (dx, dz) = (-r + s * (i as f32 + 0.5), -r + s * (j as f32 + 0.5));
                    let rho2 = dx * dx + dz * dz;
                    if rho2 < r * r {
                        let length = 2.0 * (r * r - rho2).sqrt();
                        out.push(Column {
                            dx,
                            dz,
                            area: s * s,
                            length,
                        });
                    }
                }
            }
            // n = 1 keeps the centre; n ≥ 2 always keeps the columns nearest the centre.
            let volume: f32 = out.iter().map(|c| c.area * c.length).sum();
            let scale = shape.volume() / volume;
            for c in out.iter_mut() {
                c.area *= scale;
            }
        }
    }
}

/// What one column of a body found under it and does this step.
#[derive(Debug, Clone, Copy, Default)]
pub(crate) struct ColumnForce {
    /// World point the column pushes into the water at, if there is water under it.
    pub at: Option<[f32; 2]>,
    /// Buoyancy `ρ g s a` (up).
    pub lift: f32,
    /// Waterline stiffness `ρ g a` when the waterline cuts the column, else 0.
    pub stiffness: f32,
    /// Drag coefficient `κ`.
    pub drag: f32,
    /// Water velocity under the column.
    pub flow: Vec3,
}

/// The body's implicit velocity update (see the module docs) and each column's force at
/// it. Returns `v'` and fills `forces` (parallel to `columns`). Everything in seconds:
/// `gravity` is the body's gravity magnitude (per second²), `dt` the step in seconds, the
/// columns' drag and flow per second.
pub(crate) fn solve(
    body: &Floater,
    columns: &[ColumnForce],
    gravity: f32,
    dt: f32,
    forces: &mut Vec<Vec3>,
) -> Vec3 {
    let m = body.mass;
    let (mut lift, mut k, mut kappa, mut kappa_w) = (0.0f32, 0.0f32, 0.0f32, Vec3::ZERO);
    for c in columns {
        lift += c.lift;
        k += c.stiffness;
        kappa += c.drag;
        kappa_w += c.drag * c.flow;
    }
    let base = m * body.velocity + dt * (body.push + kappa_w);
    let horizontal = m + dt * kappa;
    let vertical = horizontal + dt * dt * k;
    let v = Vec3::new(
        base.x / horizontal,
        (base.y + dt * (lift - m * gravity)) / vertical,
        base.z / horizontal,
    );
    forces.clear();
    forces.extend(
        columns
            .iter()
            .map(|c| Vec3::new(0.0, c.lift - c.stiffness * dt * v.y, 0.0) + c.drag * (c.flow - v)),
    );
    v
}
