//! Floating bodies: rigid balls, boxes and hulls that pitch, roll and ride the waves, and
//! make them, two-way.
//!
//! A [`Floater`] is a rigid body with six degrees of freedom on a [`Surface`] (added with
//! [`Surface::add_floater`]): a position and an orientation (a unit quaternion, body to
//! world), a velocity and an angular velocity. The surface steps its bodies with every
//! step and substep, and keeps them in snapshots. A body another physics engine owns (Avian,
//! Rapier, Jolt, a game's own) asks the water for its force and torque instead:
//! [`Surface::body_forces`].
//!
//! Lengths are world units, masses the lattice's mass units, and time is **seconds** of
//! the game's clock: velocities are world units per second, angular velocities radians per
//! second (world axes), gravity world units per second², the drag rate per second, forces
//! mass × world units per second², torques that times world units (see `docs/units.md`).
//! A body's step runs in those units, `Δt = dt / time_scale` seconds for a step of model
//! time `dt` ([`Params::time_scale`](crate::Params::time_scale)).
//!
//! # The model, in short
//!
//! (The [`body`](crate::body) module computes it and explains every formula.)
//!
//! * **Shape.** A sphere, a box, or any closed triangle mesh ([`Hull`]), in the body's
//!   frame with the centre of mass at the origin. On a surface each shape is cut into
//!   triangles at most about a grid cell across (the volume kept exactly).
//! * **Small bodies.** A ball or a box whose farthest point is at most 1.75 cells from
//!   its centre (a cube of side 2) meets the water as one plane, sampled at its centre (height and slope): the
//!   plane's pressure in closed form through the centre of buoyancy, the drag there, the
//!   same implicit step and the same equal and opposite reaction, for a fraction of the
//!   cost (the `small` module of [`body`](crate::body)).
//! * **Buoyancy** is the water's pressure `ρ g d` on each triangle below the water's
//!   surface, clipped where the waterline crosses it (Kerner's model): a force and a
//!   torque about the centre of mass. In still water this is Archimedes' law exactly, at
//!   any heel, so a body floats at the draft its displacement predicts and rights itself
//!   or capsizes as its metacentric height says (`GM = KB + BM − KG`).
//! * **Drag** pulls every wet triangle towards the water's velocity there, with the rate
//!   [`Floater::drag`] `k` times the mass of water the body displaces, shared out by wet
//!   area, mostly along the triangle's normal (form drag) and a little along its face
//!   (skin drag): it slows both the body's motion and its spin relative to the water, and
//!   a hull far more sideways than along its length (its keel).
//! * **Integration.** Buoyancy and drag are stiff for a light body (a ping-pong ball on a
//!   wave, a wide raft), so both are taken implicitly for the new velocity and angular
//!   velocity (one 6 × 6 linear solve per body and step, with the waterplane's heave,
//!   roll and pitch stiffness), which is stable for any mass, size and drag; the position
//!   and orientation then move with the new velocities (symplectic Euler, like the water),
//!   and the orientation is renormalised every step.
//! * **Two-way.** Every wet triangle pushes minus its force onto the nodes under its own
//!   point (the bilinear weights of [`Surface::add_force_at`]), for the same step, through
//!   the water column: the lattice gets what changes of that push, and the column carries
//!   the steady rest to the bottom (`W = R − C`, `C ← C + a W`; `docs/floating.md` and the
//!   `column` module of the bodies' subsystem state it exactly). A body resting on calm
//!   water leaves it flat and stays where it is; one dropped in, bobbing, rolling or moving
//!   on makes waves. Water outside the patch is taken as calm at height 0 and gets nothing
//!   back.
//! * **The water's stability.** To the water, a body is a spring of stiffness `ρ_w g h²`
//!   per cell under its waterline and a damper: [`Surface::critical_dt`] counts the spring
//!   while bodies float (a body whose buoyancy would push the timestep past the limit is
//!   refused), and a body's drag is capped at half of the damping the water's timestep has
//!   room for under it (see the `absorb` module), so deep, draggy bodies in an absorbing
//!   frame drag less there. Bodies stacked on the same cells add up and can exceed the
//!   budget; the step then reports [`Error::NonFinite`] like any other blow-up.
//!
//! Not modelled: added mass, slamming, bodies touching each other or the pool's walls
//! (a physics engine that owns the bodies does that: [`Surface::body_forces`]).

use crate::body::math::{self, outer};
use crate::body::rigid::Rigid;
use crate::body::{tessellate, Hull};
use crate::error::{Error, Result};
use crate::params;
#[cfg(doc)]
use crate::Surface;
use glam::{DMat3, DVec3, Mat3, Quat, Vec3};
use std::sync::Arc;

/// The shape of a [`Floater`], in the body's frame (`#[non_exhaustive]`: a shape may come).
#[derive(Debug, Clone, PartialEq)]
#[cfg_attr(feature = "serde", derive(serde::Serialize, serde::Deserialize))]
#[non_exhaustive]
pub enum Shape {
    /// A ball of `radius` world units.
    Sphere {
        /// Radius, world units (> 0).
        radius: f32,
    },
    /// A box with its faces along the body's axes.
    Box {
        /// Half the box's size along the body's x, y and z, world units (each > 0).
        half_extents: Vec3,
    },
    /// A closed triangle mesh (a boat's hull), validated; the body frame's origin is the
    /// centre of mass. Shared: many boats of one hull hold one mesh.
    Hull(Arc<Hull>),
}

impl Shape {
    /// Volume in cubic world units.
    pub fn volume(&self) -> f32 {
        match self {
            Shape::Sphere { radius } => 4.0 / 3.0 * std::f32::consts::PI * radius.powi(3),
            Shape::Box { half_extents: e } => 8.0 * e.x * e.y * e.z,
            Shape::Hull(hull) => hull.volume(),
        }
    }

    /// The distance from the body's origin to its farthest point, world units: the radius
    /// of a ball that holds the body in any orientation.
    pub fn bounding_radius(&self) -> f32 {
        match self {
            Shape::Sphere { radius } => *radius,
            Shape::Box { half_extents } => half_extents.length(),
            Shape::Hull(hull) => hull
                .vertices()
                .iter()
                .map(|v| Vec3::from(*v).length())
                .fold(0.0, f32::max),
        }
    }

    /// The inertia tensor about the body's origin, in the body's axes, for `mass` spread
    /// evenly through the volume (mass × world units²). For a hull whose centroid is not
    /// at the origin (a boat ballasted low), the uniform hull's inertia moved to the origin
    /// (parallel axes).
    pub fn inertia(&self, mass: f32) -> Mat3 {
        let m = mass as f64;
        match self {
            Shape::Sphere { radius } => {
                let r = *radius as f64;
                Mat3::from_diagonal(Vec3::splat((0.4 * m * r * r) as f32))
            }
            Shape::Box { half_extents: e } => {
                let [x, y, z] = e.to_array().map(|v| v as f64 * v as f64);
                Mat3::from_diagonal((DVec3::new(y + z, z + x, x + y) * (m / 3.0)).as_vec3())
            }
            Shape::Hull(hull) => {
                let d = hull.centroid().as_dvec3();
                let about_centroid = hull.inertia(mass).as_dmat3();
                let shift = (DMat3::IDENTITY * d.length_squared() - outer(d, d)) * m;
                (about_centroid + shift).as_mat3()
            }
        }
    }
}

/// The widest a ball or box may be, in cells of the water, to meet the water as a plane
/// (the `small` module of [`crate::body`]): its bounding radius at most 1.75 cells, so a
/// ball at most 3.5 cells across and a cube of side 2 (its corners √3 cells out) do.
const SMALL_CELLS: f32 = 1.75;

impl Shape {
    /// Whether the shape meets the water of grid spacing `spacing` as one plane (the
    /// `small` module of [`crate::body`]): a ball or a box at most [`SMALL_CELLS`] cells
    /// from its centre to its farthest point. Hulls never do.
    pub(crate) fn is_small(&self, spacing: f32) -> bool {
        let most = SMALL_CELLS * spacing;
        match self {
            Shape::Sphere { radius } => *radius <= most,
            Shape::Box { half_extents } => half_extents.length_squared() <= most * most,
            Shape::Hull(_) => false,
        }
    }
}

/// The mesh the water presses on for `shape` on a grid of `spacing`, the one place that
/// decides it: none for a small ball (its cap under the plane is computed in closed form),
/// a small box's 12 triangles (clipped at the plane exactly), else the shape cut into
/// triangles at most about a cell across (the `tessellate` module of [`crate::body`]).
pub(crate) fn wet_mesh(shape: &Shape, spacing: f32) -> Result<Option<Arc<Hull>>> {
    let cell = spacing as f64;
    let small = shape.is_small(spacing);
    let mesh = match shape {
        Shape::Sphere { .. } if small => return Ok(None),
        Shape::Box { half_extents } if small => Hull::cuboid(half_extents.to_array()).map(Arc::new),
        Shape::Sphere { radius } => tessellate::sphere(*radius as f64, cell).map(Arc::new),
        Shape::Box { half_extents } => {
            tessellate::cuboid(half_extents.as_dvec3(), cell).map(Arc::new)
        }
        Shape::Hull(hull) => tessellate::cut(hull, spacing),
    };
    mesh.map(Some)
}

/// What a step changes of a body: its pose, its velocities and the water's force and
/// torque on it, in the body's `f32` fields.
#[derive(Debug, Clone, Copy)]
pub(crate) struct Motion {
    pub position: Vec3,
    pub orientation: Quat,
    pub velocity: Vec3,
    pub angular_velocity: Vec3,
    pub water_force: Vec3,
    pub water_torque: Vec3,
}

impl Motion {
    /// Whether every field is within what [`Floater::validate`] accepts (a NaN is not):
    /// one comparison per component.
    pub fn in_range(&self) -> bool {
        let [x, y, z, w] = self.orientation.to_array().map(f64::from);
        let norm = x * x + y * y + z * z + w * w;
        within(self.position, params::MAX_EXTENT as f32)
            && within(self.velocity, MAX_SPEED)
            && within(self.angular_velocity, MAX_SPIN)
            && within(self.water_force, f32::MAX)
            && within(self.water_torque, f32::MAX)
            && (norm - 1.0) * (norm - 1.0) <= 1e-6
    }
}

/// Whether every component of `v` is at most `max` in size (a NaN is not).
fn within(v: Vec3, max: f32) -> bool {
    v.abs().cmple(Vec3::splat(max)).all()
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
/// [`Floater::sphere`], [`Floater::cuboid`] or [`Floater::hull`] and assign the fields to
/// change.
#[derive(Debug, Clone, PartialEq)]
#[cfg_attr(feature = "serde", derive(serde::Serialize, serde::Deserialize))]
#[non_exhaustive]
pub struct Floater {
    /// Sphere, box or hull mesh, in the body's frame (origin at the centre of mass).
    pub shape: Shape,
    /// Mass, in the lattice's mass units (> 0; a node has [`Params::mass`](crate::Params::mass)).
    pub mass: f32,
    /// The inertia tensor about the centre of mass in the body's axes (mass × world
    /// units²), or `None` (the default) for the shape's at uniform density
    /// ([`Shape::inertia`]). Set one for a body whose mass is not spread evenly; it must be
    /// symmetric and positive definite, with each principal moment at most the sum of the
    /// other two (as every real body's is).
    pub inertia: Option<Mat3>,
    /// Drag rate `k`, per second (≥ 0, at most 1e8): the drag is `k` times the mass of the
    /// displaced water times the velocity relative to the water (default
    /// [`Floater::DEFAULT_DRAG`], 6 per second).
    pub drag: f32,
    /// Centre of mass, world units in the water's local space (the calm surface is `y = 0`).
    pub position: Vec3,
    /// Orientation, body to world: a unit quaternion (its squared norm within 1e-3 of 1;
    /// the surface keeps it normalised). Default identity.
    pub orientation: Quat,
    /// Velocity of the centre of mass, world units per second (components at most 1e11;
    /// default zero).
    pub velocity: Vec3,
    /// Angular velocity, radians per second about the world's axes (components at most
    /// 1e6; default zero).
    pub angular_velocity: Vec3,
    /// External force through the centre of mass (engine, wind, a player's push) for the
    /// next step only, cleared by it; [`Surface::push_floater`] adds to it. Mass units ×
    /// world units per second² (default zero).
    pub push: Vec3,
    /// External torque about the centre of mass (world axes) for the next step only,
    /// cleared by it; [`Surface::push_floater_at`] adds to it (default zero).
    pub push_torque: Vec3,
    /// Read only: the force the water exerted on the body during its last step (buoyancy
    /// and drag, without gravity and push). The water got exactly minus this.
    pub water_force: Vec3,
    /// Read only: the torque about the centre of mass the water exerted on the body during
    /// its last step. The water got exactly minus this.
    pub water_torque: Vec3,
}

impl Floater {
    /// Default drag rate `k`: 6 per second (0.25 per unit of model time at the default
    /// time scale of 24).
    pub const DEFAULT_DRAG: f32 = 6.0;

    /// A sphere of `radius` and `mass` centred at `position`, at rest.
    pub fn sphere(radius: f32, mass: f32, position: impl Into<Vec3>) -> Self {
        Self::with_shape(Shape::Sphere { radius }, mass, position)
    }

    /// A box of `half_extents` and `mass` centred at `position`, at rest, upright.
    pub fn cuboid(half_extents: impl Into<Vec3>, mass: f32, position: impl Into<Vec3>) -> Self {
        let half_extents = half_extents.into();
        Self::with_shape(Shape::Box { half_extents }, mass, position)
    }

    /// A body whose hull is the closed mesh `vertices`, `triangles` (counter-clockwise
    /// seen from outside, in the body's frame with the centre of mass at the origin), of
    /// `mass`, with its origin at `position`, at rest, upright. Refused with
    /// [`Error::InvalidHull`] when the mesh is not a valid hull ([`Hull::new`] says what is
    /// required).
    pub fn hull(
        vertices: &[[f32; 3]],
        triangles: &[[u32; 3]],
        mass: f32,
        position: impl Into<Vec3>,
    ) -> Result<Self> {
        let hull = Hull::new(vertices, triangles)?;
        Ok(Self::with_hull(Arc::new(hull), mass, position))
    }

    /// [`Floater::hull`] with a hull already validated, shared with other bodies.
    pub fn with_hull(hull: Arc<Hull>, mass: f32, position: impl Into<Vec3>) -> Self {
        Self::with_shape(Shape::Hull(hull), mass, position)
    }

    /// A body of any `shape` and `mass` at `position`, at rest, upright, with the default
    /// drag and the shape's inertia: what [`Floater::sphere`], [`Floater::cuboid`] and
    /// [`Floater::with_hull`] build, for a caller that holds a [`Shape`] (a face that
    /// decodes one, or a body copied with another shape).
    pub fn with_shape(shape: Shape, mass: f32, position: impl Into<Vec3>) -> Self {
        Self {
            shape,
            mass,
            inertia: None,
            drag: Self::DEFAULT_DRAG,
            position: position.into(),
            orientation: Quat::IDENTITY,
            velocity: Vec3::ZERO,
            angular_velocity: Vec3::ZERO,
            push: Vec3::ZERO,
            push_torque: Vec3::ZERO,
            water_force: Vec3::ZERO,
            water_torque: Vec3::ZERO,
        }
    }

    /// The inertia tensor in use: [`Floater::inertia`] if set, else the shape's at uniform
    /// density (body axes, about the centre of mass).
    pub fn inertia_tensor(&self) -> Mat3 {
        self.inertia
            .unwrap_or_else(|| self.shape.inertia(self.mass))
    }

    /// The body's state for the rigid step, in `f64`.
    pub(crate) fn rigid(&self) -> Rigid {
        Rigid {
            mass: self.mass as f64,
            inertia: self.inertia_tensor().as_dmat3(),
            position: self.position.as_dvec3(),
            orientation: self.orientation.as_dquat(),
            velocity: self.velocity.as_dvec3(),
            angular_velocity: self.angular_velocity.as_dvec3(),
            push: self.push.as_dvec3(),
            push_torque: self.push_torque.as_dvec3(),
        }
    }

    /// The world velocity of the body's point at world `point`: `v + ω × (point − x)`.
    pub fn velocity_at(&self, point: impl Into<Vec3>) -> Vec3 {
        self.velocity + self.angular_velocity.cross(point.into() - self.position)
    }

    /// Checks every field: an error names the first that is out of range.
    pub fn validate(&self) -> Result<()> {
        let size = |name, v: f32| {
            params::positive(name, v)?;
            bounded(name, v, MAX_SIZE, "at most 1e9 world units")
        };
        match &self.shape {
            Shape::Sphere { radius } => size("floater radius", *radius)?,
            Shape::Box { half_extents: e } => {
                for v in e.to_array() {
                    size("floater half extent", v)?;
                }
            }
            // A hull was validated when it was made; its coordinates are at most 1e9.
            Shape::Hull(_) => {}
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
        check_inertia(self.inertia_tensor())?;
        params::non_negative("floater drag", self.drag)?;
        bounded(
            "floater drag",
            self.drag,
            MAX_DRAG,
            "at most 1e8 per second",
        )?;
        self.validate_motion()
    }

    /// Takes the pose, velocities and water's force and torque a step gave, its push
    /// spent.
    pub(crate) fn take_motion(&mut self, m: &Motion) {
        self.position = m.position;
        self.orientation = m.orientation;
        self.velocity = m.velocity;
        self.angular_velocity = m.angular_velocity;
        self.water_force = m.water_force;
        self.water_torque = m.water_torque;
        self.push = Vec3::ZERO;
        self.push_torque = Vec3::ZERO;
    }

    /// The part of [`Floater::validate`] a step changes: orientation, position,
    /// velocities, pushes and the water's force and torque.
    pub(crate) fn validate_motion(&self) -> Result<()> {
        // Nearly every step's body is in range: one comparison per component says so
        // (a NaN fails it), and only a body that fails looks for the field to name.
        let motion = Motion {
            position: self.position,
            orientation: self.orientation,
            velocity: self.velocity,
            angular_velocity: self.angular_velocity,
            water_force: self.water_force,
            water_torque: self.water_torque,
        };
        if motion.in_range() && within(self.push, f32::MAX) && within(self.push_torque, f32::MAX) {
            return Ok(());
        }
        math::check_unit(
            self.orientation,
            "floater orientation",
            "floater orientation's squared norm",
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
            (
                "floater angular velocity",
                self.angular_velocity,
                MAX_SPIN,
                "components of at most 1e6 (radians per second)",
            ),
            ("floater push", self.push, f32::MAX, "finite components"),
            (
                "floater push torque",
                self.push_torque,
                f32::MAX,
                "finite components",
            ),
            (
                "floater water force",
                self.water_force,
                f32::MAX,
                "finite components",
            ),
            (
                "floater water torque",
                self.water_torque,
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

/// The water's push on a body another physics engine owns, over one tick
/// ([`Surface::body_forces`]): world frame, mass units × world units per second², the
/// torque about the body's centre of mass. Apply both for the tick (Avian's
/// `ExternalForce` and `ExternalTorque`, Rapier's `add_force` and `add_torque`).
#[derive(Debug, Clone, Copy, PartialEq, Default)]
#[cfg_attr(feature = "serde", derive(serde::Serialize, serde::Deserialize))]
pub struct BodyForces {
    /// The force through the centre of mass (buoyancy and drag; gravity is the engine's).
    pub force: Vec3,
    /// The torque about the centre of mass.
    pub torque: Vec3,
}

/// A physical inertia tensor: finite, symmetric (to 1e-6 of its size), positive
/// definite, and each principal moment at most the sum of the other two: the second
/// moment of the mass, `tr(I)/2 · 1 − I`, is positive semidefinite.
fn check_inertia(inertia: Mat3) -> Result<()> {
    let invalid = |value: f64, expected| {
        Err(Error::InvalidParam {
            name: "floater inertia",
            value,
            expected,
        })
    };
    let i = inertia.as_dmat3();
    let a = i.to_cols_array();
    if a.iter().any(|v| !v.is_finite()) {
        return invalid(f64::NAN, "finite entries");
    }
    let size = a.iter().fold(0.0f64, |m, v| m.max(v.abs()));
    let asym = (i - i.transpose()).to_cols_array();
    if asym.iter().any(|v| v.abs() > 1e-6 * size) {
        return invalid(size, "a symmetric tensor");
    }
    let i = (i + i.transpose()) * 0.5;
    let trace = i.x_axis.x + i.y_axis.y + i.z_axis.z;
    let second = DMat3::IDENTITY * (0.5 * trace) - i;
    let tolerance = 1e-6 * size;
    if !positive_definite(i, 0.0) || size < f64::from(f32::MIN_POSITIVE) {
        return invalid(size, "a positive definite tensor");
    }
    if !positive_definite(second, -tolerance) {
        return invalid(
            size,
            "principal moments each at most the sum of the other two",
        );
    }
    Ok(())
}

/// Sylvester's criterion: every leading minor above `floor` (≥ for a semidefinite test).
fn positive_definite(m: DMat3, floor: f64) -> bool {
    let (a, b, c) = (m.x_axis, m.y_axis, m.z_axis);
    let minor1 = a.x;
    let minor2 = a.x * b.y - a.y * b.x;
    let minor3 = m.determinant();
    let scale = a.x.abs().max(b.y.abs()).max(c.z.abs());
    if floor < 0.0 {
        minor1 >= floor && minor2 >= floor * scale && minor3 >= floor * scale * scale
    } else {
        minor1 > 0.0 && minor2 > 0.0 && minor3 > 0.0
    }
}

/// Largest radius or half extent a floater may have, world units.
const MAX_SIZE: f32 = 1e9;
/// Largest speed component, world units per second.
const MAX_SPEED: f32 = 1e11;
/// Largest angular velocity component, radians per second.
const MAX_SPIN: f32 = 1e6;
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

/// The widest a body may be, in cells of the grid it floats on ([`Surface::add_floater`]
/// refuses larger ones): a body is at most this many cells across in any orientation (twice
/// its [`Shape::bounding_radius`]), which bounds the triangles it is cut into.
pub const MAX_CELLS: f32 = 64.0;

/// Checks that `shape` is at most [`MAX_CELLS`] cells of `spacing` across.
pub(crate) fn check_footprint(shape: &Shape, spacing: f32) -> Result<()> {
    let widest = 2.0 * shape.bounding_radius();
    if widest <= MAX_CELLS * spacing {
        Ok(())
    } else {
        Err(Error::InvalidParam {
            name: "floater size",
            value: widest as f64,
            expected: "at most 64 grid cells across (twice the bounding radius)",
        })
    }
}
