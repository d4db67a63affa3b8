//! Floating bodies, two-way: a [`Buoyant`] entity is one of springwater's floating bodies
//! ([`springwater::Floater`]) on the water under it; the plugin keeps the two in step.

use std::collections::HashMap;
use std::sync::Arc;

use bevy::ecs::prelude::*;
use bevy::math::{Mat3, Quat, Vec3};
use bevy::transform::components::{GlobalTransform, Transform};
use springwater::body::Hull;
use springwater::{Buoyancy, Floater, FloaterId, Shape};

use crate::water::{report, Space, WaterError, WaterSurface};

/// A floating rigid body: a sphere, a box or a hull mesh that pitches and rolls. Needs a
/// `Transform` on a root entity (its translation is the body's centre of mass in world
/// space, its rotation the body's orientation); the plugin moves and turns it.
///
/// The body is one of springwater's floating bodies on the water whose footprint holds it
/// when it appears: the water lifts and drags it from the height and velocity under each
/// column of its footprint and gets exactly minus that force back, every substep, so a
/// floating body dents the water and a moving one leaves a wake. The model is
/// [`springwater::floater`]'s, and so are the units, world units and seconds:
/// `velocity` in units per second, `force` and [`Buoyant::water_force`] in mass × units
/// per second², `drag` per second. They pass to the library as they are; only the water's
/// `GlobalTransform` turns them between world space and the water's local space.
///
/// A body away from every water's footprint floats on calm water at the water's rest
/// height (springwater's open-water assumption); with no water at all it stays where it is.
/// When a water's parameters change its surface starts over, and its bodies are put back
/// where their components say.
#[derive(Component, Debug, Clone, PartialEq)]
#[require(Transform)]
pub struct Buoyant {
    /// Sphere, box or hull, in the body's frame, world units (the water's local units if
    /// its transform scales).
    pub shape: Shape,
    /// Mass, in the units of [`BuoyancySettings::density`] × volume (> 0).
    pub mass: f32,
    /// The inertia tensor about the centre of mass in the body's axes (mass × world
    /// units²), or `None` (the default) for the shape's at uniform density
    /// ([`Shape::inertia`]): springwater's [`Floater::inertia`], passed as it is. Set one
    /// ([`Buoyant::with_inertia`]) for a body whose mass is not spread evenly (a boat
    /// ballasted low, a hollow ball); it must be symmetric and positive definite, with
    /// each principal moment at most the sum of the other two, or the water refuses the
    /// body (a [`WaterError`]).
    pub inertia: Option<Mat3>,
    /// Drag rate per second at full immersion (≥ 0; default 6,
    /// [`Floater::DEFAULT_DRAG`]): the drag is this rate times the displaced water's mass
    /// times the velocity relative to the water.
    pub drag: f32,
    /// World velocity, per second. Set it to throw the body.
    pub velocity: Vec3,
    /// World angular velocity, radians per second. Set it to spin the body.
    pub angular_velocity: Vec3,
    /// External world force through the centre of mass held during the next frame (game
    /// input, wind, an engine); cleared after use.
    pub force: Vec3,
    /// External world torque about the centre of mass held during the next frame; cleared
    /// after use.
    pub torque: Vec3,
    /// Read only: the world force the water exerted on the body in the last substep
    /// (buoyancy and drag).
    pub water_force: Vec3,
    /// Read only: the world torque about the centre of mass the water exerted on the body
    /// in the last substep.
    pub water_torque: Vec3,
}

impl Buoyant {
    /// A sphere of `radius` with `relative_density` (0.5: floats half under), at rest.
    pub fn sphere(radius: f32, relative_density: f32, settings: &BuoyancySettings) -> Self {
        Self::new(Shape::Sphere { radius }, relative_density, settings)
    }

    /// A box of `half_extents` with `relative_density`, at rest.
    pub fn cuboid(half_extents: Vec3, relative_density: f32, settings: &BuoyancySettings) -> Self {
        let half_extents = springwater::glam::Vec3::from_array(half_extents.to_array());
        Self::new(Shape::Box { half_extents }, relative_density, settings)
    }

    /// A body whose hull is `hull` (a closed mesh in the body's frame, the centre of mass
    /// at its origin: [`springwater::body::Hull`]; many bodies may share one) with
    /// `relative_density`, at rest.
    pub fn hull(hull: Arc<Hull>, relative_density: f32, settings: &BuoyancySettings) -> Self {
        Self::new(Shape::Hull(hull), relative_density, settings)
    }

    fn new(shape: Shape, relative_density: f32, settings: &BuoyancySettings) -> Self {
        let mass = relative_density * settings.density * shape.volume();
        Self {
            shape,
            mass,
            inertia: None,
            drag: Floater::DEFAULT_DRAG,
            velocity: Vec3::ZERO,
            angular_velocity: Vec3::ZERO,
            force: Vec3::ZERO,
            torque: Vec3::ZERO,
            water_force: Vec3::ZERO,
            water_torque: Vec3::ZERO,
        }
    }

    /// The body with `inertia` (body axes, about the centre of mass) instead of its
    /// shape's at uniform density.
    pub fn with_inertia(mut self, inertia: Mat3) -> Self {
        self.inertia = Some(inertia);
        self
    }

    /// The inertia tensor in use: [`Buoyant::inertia`] if set, else the shape's at
    /// uniform density for [`Buoyant::mass`] (springwater's [`Shape::inertia`]).
    pub fn inertia_tensor(&self) -> Mat3 {
        self.inertia
            .unwrap_or_else(|| to_bevy(self.shape.inertia(self.mass)))
    }

    /// The body in the water's local space, its centre at `centre` and turned by
    /// `rotation` (world).
    fn floater(&self, centre: Vec3, rotation: Quat, space: &Space) -> Floater {
        let local = |v: Vec3| springwater::glam::Vec3::from_array(v.to_array());
        let mut body = floater_of(&self.shape, self.mass, local(space.local_point(centre)));
        body.inertia = self
            .inertia
            .map(|m| springwater::glam::Mat3::from_cols_array(&m.to_cols_array()));
        body.drag = self.drag;
        body.velocity = local(space.local_vector(self.velocity));
        body.angular_velocity = local(space.local_rotation() * self.angular_velocity);
        let q = (space.local_rotation() * rotation).normalize();
        body.orientation = springwater::glam::Quat::from_array(q.to_array());
        body
    }
}

/// A springwater matrix as Bevy's.
fn to_bevy(m: springwater::glam::Mat3) -> Mat3 {
    Mat3::from_cols_array(&m.to_cols_array())
}

/// A floater of `shape` and `mass` at `position`, at rest: springwater's constructor
/// for any shape.
fn floater_of(shape: &Shape, mass: f32, position: springwater::glam::Vec3) -> Floater {
    Floater::with_shape(shape.clone(), mass, position)
}

/// Gravity and the water's density for every [`Buoyant`] body.
///
/// The default is springwater's [`Buoyancy::default`]: gravity 57.6 units per second²,
/// density 1. The seed's
/// lattice is fast water (ripples cross about 39 units per second), and bodies fall to
/// match. With real gravity (9.81 for metres) they float the same but, being 6 times
/// lighter for the lattice, dent it and make waves 6 times less.
#[derive(Resource, Debug, Clone, Copy, PartialEq)]
pub struct BuoyancySettings {
    /// Gravity along the water's −y, world units per second² (default 57.6).
    pub gravity: f32,
    /// Density of the water, mass per cubic world unit (default 1).
    pub density: f32,
}

impl Default for BuoyancySettings {
    fn default() -> Self {
        let Buoyancy { gravity, density } = Buoyancy::default();
        Self { gravity, density }
    }
}

/// Which water and floater each body is, and the component values the plugin last wrote
/// (so that a body the game did not touch is not converted back and forth every frame).
#[derive(Resource, Debug, Default)]
pub(crate) struct Bodies(HashMap<Entity, Link>);

#[derive(Debug, Clone)]
pub(crate) struct Link {
    water: Entity,
    id: FloaterId,
    written: Option<(Buoyant, Vec3, Quat)>,
}

impl Bodies {
    /// Forgets the bodies of `water` (its surface started over without them).
    pub(crate) fn forget_water(&mut self, water: Entity) {
        self.0.retain(|_, link| link.water != water);
    }

    /// Which water and floater `body` is, if any (saved for rollback).
    #[cfg(feature = "ggrs")]
    pub(crate) fn link(&self, body: Entity) -> Option<Link> {
        self.0.get(&body).cloned()
    }

    /// Puts back what [`Bodies::link`] said at a saved frame.
    #[cfg(feature = "ggrs")]
    pub(crate) fn set_link(&mut self, body: Entity, link: Option<Link>) {
        match link {
            Some(link) => {
                self.0.insert(body, link);
            }
            None => {
                self.0.remove(&body);
            }
        }
    }
}

/// Hands every body's state to its water (adding new bodies, putting back those a
/// restarted surface lost, removing those that are gone) before the water steps.
pub(crate) fn sync_bodies(
    settings: Res<BuoyancySettings>,
    mut registry: ResMut<Bodies>,
    bodies: Query<(Entity, &Buoyant, &Transform)>,
    mut waters: Query<(Entity, &mut WaterSurface, &GlobalTransform)>,
    mut errors: MessageWriter<WaterError>,
) {
    registry.0.retain(|&body, link| {
        let alive = bodies.contains(body);
        if !alive {
            if let Ok((_, mut ws, _)) = waters.get_mut(link.water) {
                let _ = ws.surface.remove_floater(link.id);
            }
        }
        alive
    });
    for (entity, mut ws, _) in &mut waters {
        ws.pushes.0.clear();
        let buoyancy = Buoyancy {
            gravity: settings.gravity,
            density: settings.density,
        };
        if ws.surface.buoyancy() != buoyancy {
            if let Err(e) = ws.surface.set_buoyancy(buoyancy) {
                report(&mut errors, entity, "buoyancy settings refused", &e);
            }
        }
    }
    for (body, buoyant, transform) in &bodies {
        let (centre, rotation) = (transform.translation, transform.rotation);
        let linked = registry.0.get(&body).cloned().filter(|link| {
            waters
                .get(link.water)
                .is_ok_and(|(_, ws, _)| ws.surface.floater(link.id).is_ok())
        });
        let water = match &linked {
            Some(link) => link.water,
            None => {
                let under = waters.iter().find(|(_, ws, global)| {
                    let p = Space::new(global).local_point(centre);
                    ws.surface.contains(p.x, p.z)
                });
                match under.or_else(|| waters.iter().next()) {
                    Some((water, _, _)) => water,
                    None => continue,
                }
            }
        };
        let Ok((_, mut ws, global)) = waters.get_mut(water) else {
            continue;
        };
        let space = Space::new(global);
        let floater = buoyant.floater(centre, rotation, &space);
        let untouched = |link: &Link| {
            link.written
                .as_ref()
                .is_some_and(|(b, c, r)| b == buoyant && *c == centre && *r == rotation)
        };
        let done = match &linked {
            // Untouched since the plugin wrote it: the library's state is the exact one.
            Some(link) if untouched(link) => Ok(link.id),
            Some(link) => ws.surface.set_floater(link.id, floater).map(|()| link.id),
            None => ws.surface.add_floater(floater),
        };
        match done {
            Ok(id) => {
                let written = linked.and_then(|link| link.written);
                registry.0.insert(body, Link { water, id, written });
                let local = |v: Vec3| springwater::glam::Vec3::from_array(v.to_array());
                let push = local(space.local_vector(buoyant.force));
                let twist = local(space.local_rotation() * buoyant.torque);
                ws.pushes.0.push((id, push, twist));
            }
            Err(e) => {
                registry.0.remove(&body);
                report(&mut errors, water, "buoyant body refused", &e);
            }
        }
    }
}

/// Moves every body's `Transform` and `Buoyant` to where its water left it.
pub(crate) fn write_bodies(
    mut registry: ResMut<Bodies>,
    mut bodies: Query<(Entity, &mut Buoyant, &mut Transform)>,
    waters: Query<(&WaterSurface, &GlobalTransform)>,
) {
    for (body, mut buoyant, mut transform) in &mut bodies {
        let Some(link) = registry.0.get_mut(&body) else {
            continue;
        };
        let Ok((ws, global)) = waters.get(link.water) else {
            continue;
        };
        let Ok(f) = ws.surface.floater(link.id) else {
            continue;
        };
        if ws.substeps == 0 {
            // Nothing stepped (paused, a zero frame, a failed step): the push waits.
            continue;
        }
        let space = Space::new(global);
        let world = |v: springwater::glam::Vec3| space.world_vector(Vec3::from_array(v.to_array()));
        let turn = space.local_rotation().inverse();
        let turned = |v: springwater::glam::Vec3| turn * Vec3::from_array(v.to_array());
        transform.translation = space.world_point(Vec3::from_array(f.position.to_array()));
        transform.rotation = (turn * Quat::from_array(f.orientation.to_array())).normalize();
        buoyant.velocity = world(f.velocity);
        buoyant.angular_velocity = turned(f.angular_velocity);
        buoyant.water_force = world(f.water_force);
        buoyant.water_torque = turned(f.water_torque);
        buoyant.force = Vec3::ZERO;
        buoyant.torque = Vec3::ZERO;
        link.written = Some((buoyant.clone(), transform.translation, transform.rotation));
    }
}
