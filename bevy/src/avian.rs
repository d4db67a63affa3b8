//! Buoyancy for [Avian](https://docs.rs/avian3d)'s rigid bodies (feature `avian`): an
//! [`AvianBuoyant`] on a dynamic `RigidBody` makes the water push it, and the water gets
//! the reaction (the body leaves a wake and dents the water it floats on).
//!
//! Avian owns the body: its collisions, joints, gravity and integration. Every physics
//! tick, after Avian's `PhysicsSystems::Prepare` (mass properties and poses are up to date)
//! and before `PhysicsSystems::StepSimulation`, [`apply_water_forces`] builds one of
//! springwater's floating bodies ([`springwater::Floater`]) from the body's shape, Avian's
//! computed mass, angular inertia and centre of mass, its pose and its velocities, asks
//! the water for its force and torque over the coming tick
//! ([`springwater::Surface::body_forces`], with the tick Avian is about to take), and
//! hands both to Avian's [`Forces`], which holds them over every substep of the step. The
//! forces are the implicit ones of springwater's own bodies (for the velocities the body
//! will have at the end of the tick), so Avian's explicit step with the same mass,
//! inertia and tick is stable for light bodies too. The water then steps by the same
//! fixed timestep with the reaction, after Avian's step: body and water both start the
//! tick at the same time.
//!
//! Gravity is Avian's: every tick its downward component (world −y) becomes
//! [`BuoyancySettings::gravity`](crate::BuoyancySettings), which every water uses, so
//! the water's weight of displaced water and Avian's weight of the body agree. Keep
//! Avian's gravity along −y and the waters level (no tilt in their transforms).

use std::collections::HashMap;
use std::sync::Arc;

use avian3d::prelude::{
    Collider, ComputedAngularInertia, ComputedCenterOfMass, ComputedMass, Forces, Gravity, Physics,
    PhysicsTime, ReadRigidBodyForces, RigidBody, WriteRigidBodyForces,
};
use bevy::ecs::prelude::*;
use bevy::math::{Quat, Vec3};
use bevy::time::Time;
use bevy::transform::components::GlobalTransform;
use springwater::body::Hull;
use springwater::{Buoyancy, Floater};

use crate::buoyancy::BuoyancySettings;
use crate::water::{report, Space, Water, WaterError, WaterSurface};

/// Makes the water push an Avian rigid body (on the same entity as a dynamic
/// `RigidBody`): buoyancy and drag on the wet part of its hull, every physics tick, and
/// the opposite into the water. Needs [`SpringwaterPlugin::with_avian`](crate::SpringwaterPlugin::with_avian).
///
/// The hull is the entity's own `Collider` (a cuboid, a ball, a convex hull or a closed
/// triangle mesh; not compound shapes or colliders on child entities) unless
/// [`AvianBuoyant::hull`] gives one. The mass, angular inertia and centre of mass are
/// Avian's computed ones (set them with Avian's `Mass`, `ColliderDensity`,
/// `AngularInertia`, `CenterOfMass`), so the water's implicit forces match what Avian
/// integrates. Forces are in Avian's units (mass × world units per second²): the water's
/// density is [`BuoyancySettings::density`](crate::BuoyancySettings) mass units per cubic
/// world unit, so a `ColliderDensity` of half of it floats half under.
///
/// ```no_run
/// use avian3d::prelude::*;
/// use bevy::prelude::*;
/// use springwater_bevy::prelude::*;
///
/// App::new()
///     .add_plugins((
///         DefaultPlugins,
///         PhysicsPlugins::default(),
///         SpringwaterPlugin::default().with_avian(),
///     ))
///     .add_systems(Startup, |mut commands: Commands| {
///         commands.spawn(Water::with_size(65, 65));
///         // A crate 2 × 1 × 2 at half the water's density, dropped on the water.
///         commands.spawn((
///             RigidBody::Dynamic,
///             Collider::cuboid(2.0, 1.0, 2.0),
///             ColliderDensity(0.5),
///             AvianBuoyant::default(),
///             Transform::from_xyz(32.0, 2.0, 32.0),
///         ));
///     })
///     .run();
/// ```
#[derive(Component, Debug, Clone, PartialEq)]
pub struct AvianBuoyant {
    /// A hull for the water instead of the collider's (a boat's displacement hull under a
    /// simpler collider): a closed mesh in the body's frame, the frame of Avian's
    /// `Position` and `Rotation` (not moved to the centre of mass: the plugin does that).
    /// Many bodies may share one.
    pub hull: Option<Arc<Hull>>,
    /// Drag rate per second at full immersion (≥ 0; default 6, [`Floater::DEFAULT_DRAG`]):
    /// the drag is this rate times the displaced water's mass times the velocity relative
    /// to the water.
    pub drag: f32,
    /// Read only: the world force the water exerts on the body over the current tick
    /// (buoyancy and drag; gravity is Avian's).
    pub water_force: Vec3,
    /// Read only: the world torque about the centre of mass the water exerts on the body
    /// over the current tick.
    pub water_torque: Vec3,
}

impl Default for AvianBuoyant {
    /// The collider's shape, the default drag.
    fn default() -> Self {
        Self {
            hull: None,
            drag: Floater::DEFAULT_DRAG,
            water_force: Vec3::ZERO,
            water_torque: Vec3::ZERO,
        }
    }
}

impl AvianBuoyant {
    /// The water presses on `hull` (in the body's frame) instead of the collider.
    pub fn with_hull(hull: Arc<Hull>) -> Self {
        Self {
            hull: Some(hull),
            ..Self::default()
        }
    }
}

/// What a body's hull for the water was made from: the explicit hull's or the collider
/// shape's address, and the centre of mass.
type ShapeKey = (usize, [u32; 3]);

/// Each body as springwater's floater (made with the constructor for its hull, in its
/// centre-of-mass frame; mass, pose and velocities are set every tick), kept while its
/// collider (or explicit hull) and centre of mass stay the same; `None` if it has no hull
/// the water can use (reported once).
#[derive(Resource, Debug, Default)]
pub(crate) struct AvianShapes(HashMap<Entity, (ShapeKey, Option<Floater>)>);

type AvianBody = (
    Entity,
    &'static mut AvianBuoyant,
    &'static RigidBody,
    Forces,
    &'static ComputedMass,
    &'static ComputedAngularInertia,
    &'static ComputedCenterOfMass,
    Option<&'static Collider>,
);

/// Every tick, before Avian steps: the water's force and torque on each [`AvianBuoyant`]
/// body over the tick, applied through Avian's [`Forces`]; the reactions go into the
/// water's next step. See the [module docs](self).
#[allow(clippy::too_many_arguments)]
pub(crate) fn apply_water_forces(
    time: Res<Time>,
    physics: Res<Time<Physics>>,
    gravity: Res<Gravity>,
    mut settings: ResMut<BuoyancySettings>,
    mut shapes: ResMut<AvianShapes>,
    mut bodies: Query<AvianBody>,
    mut waters: Query<(Entity, &Water, &mut WaterSurface, &GlobalTransform)>,
    mut errors: MessageWriter<WaterError>,
) {
    // Avian's tick: the schedule's clock scaled by the physics clock's relative speed.
    let seconds = time.delta_secs_f64() * physics.relative_speed_f64();
    if physics.is_paused() || seconds <= 0.0 {
        return;
    }
    let g = (-gravity.0.y).max(0.0);
    if settings.gravity != g {
        settings.gravity = g;
    }
    let buoyancy = Buoyancy {
        gravity: settings.gravity,
        density: settings.density,
    };
    for (entity, _, mut ws, _) in &mut waters {
        if ws.surface.buoyancy() != buoyancy {
            if let Err(e) = ws.surface.set_buoyancy(buoyancy) {
                report(&mut errors, entity, "buoyancy settings refused", &e);
            }
        }
    }
    shapes.0.retain(|body, _| bodies.contains(*body));
    for (body, mut buoyant, rigid, mut forces, mass, inertia, com, collider) in &mut bodies {
        if !rigid.is_dynamic() {
            continue;
        }
        let rotation: Quat = forces.rotation().0;
        let centre = forces.position().0 + rotation * com.0;
        let under = waters.iter().find(|(_, _, ws, global)| {
            let p = Space::new(global).local_point(centre);
            ws.surface.contains(p.x, p.z)
        });
        let Some(water) = under.or_else(|| waters.iter().next()).map(|w| w.0) else {
            continue;
        };
        let Ok((_, params, mut ws, global)) = waters.get_mut(water) else {
            continue;
        };
        let Some(mut floater) = body_floater(&mut shapes, body, &buoyant, collider, com.0, |e| {
            report(
                &mut errors,
                water,
                &format!("hull of avian body {body}"),
                &e,
            )
        }) else {
            continue;
        };
        let space = Space::new(global);
        let local = |v: Vec3| springwater::glam::Vec3::from_array(v.to_array());
        let turn = space.local_rotation();
        floater.mass = mass.value();
        floater.position = local(space.local_point(centre));
        floater.inertia = Some(springwater::glam::Mat3::from_cols_array(
            &inertia.tensor().to_mat3().to_cols_array(),
        ));
        floater.drag = buoyant.drag;
        let q = (turn * rotation).normalize();
        floater.orientation = springwater::glam::Quat::from_array(q.to_array());
        floater.velocity = local(space.local_vector(forces.linear_velocity()));
        floater.angular_velocity = local(turn * forces.angular_velocity());
        match ws.surface.body_forces(&floater, seconds as f32) {
            Ok(push) => {
                let back = turn.inverse();
                let force = space.world_vector(Vec3::from_array(push.force.to_array()));
                let torque = back * Vec3::from_array(push.torque.to_array());
                forces.apply_force(force);
                forces.apply_torque(torque);
                buoyant.water_force = force;
                buoyant.water_torque = torque;
            }
            Err(e) => report(
                &mut errors,
                water,
                &format!("avian body {body} refused"),
                &e,
            ),
        }
        if params.paused {
            // A paused water holds its bodies up but keeps no reactions (it would get
            // them all at once when it resumes).
            ws.surface.clear_forces();
        }
    }
}

/// `body` as a floater with its hull for the water in its centre-of-mass frame, from the
/// cache while what it was made from stays the same; `None` (reported once through
/// `refused`) if it has no hull.
fn body_floater(
    shapes: &mut AvianShapes,
    body: Entity,
    buoyant: &AvianBuoyant,
    collider: Option<&Collider>,
    com: Vec3,
    refused: impl FnOnce(String),
) -> Option<Floater> {
    let source = match (&buoyant.hull, collider) {
        (Some(hull), _) => Arc::as_ptr(hull) as *const u8 as usize,
        (None, Some(c)) => Arc::as_ptr(&c.shape_scaled().0) as *const u8 as usize,
        (None, None) => 0,
    };
    let key = (source, com.to_array().map(f32::to_bits));
    if let Some((k, shape)) = shapes.0.get(&body) {
        if *k == key {
            return shape.clone();
        }
    }
    let made = make_floater(buoyant, collider, com);
    if let Err(e) = &made {
        refused(e.clone());
    }
    let floater = made.ok();
    shapes.0.insert(body, (key, floater.clone()));
    floater
}

/// The body as a floater of mass 1 at the origin, at rest, with its hull for the water in
/// its centre-of-mass frame: springwater's constructor for the shape.
fn make_floater(
    buoyant: &AvianBuoyant,
    collider: Option<&Collider>,
    com: Vec3,
) -> Result<Floater, String> {
    let centred = com.length_squared() == 0.0;
    let origin = springwater::glam::Vec3::ZERO;
    if let Some(hull) = &buoyant.hull {
        return match centred {
            true => Ok(Floater::with_hull(Arc::clone(hull), 1.0, origin)),
            false => moved_hull(hull.vertices(), hull.triangles(), com),
        };
    }
    let Some(collider) = collider else {
        return Err("no collider and no AvianBuoyant::hull".into());
    };
    let shape = collider.shape_scaled();
    if let Some(ball) = shape.as_ball() {
        return match centred {
            true => Ok(Floater::sphere(ball.radius, 1.0, origin)),
            false => Err("a ball's centre of mass must be its centre".into()),
        };
    }
    if let Some(cuboid) = shape.as_cuboid() {
        let half = springwater::glam::Vec3::from_array(cuboid.half_extents.to_array());
        if centred {
            return Ok(Floater::cuboid(half, 1.0, origin));
        }
        let hull = Hull::cuboid(half).map_err(|e| e.to_string())?;
        return moved_hull(hull.vertices(), hull.triangles(), com);
    }
    let (vertices, triangles) = if let Some(convex) = shape.as_convex_polyhedron() {
        let (v, t) = convex.to_trimesh();
        (v.iter().map(|p| p.to_array()).collect::<Vec<_>>(), t)
    } else if let Some(mesh) = shape.as_trimesh() {
        let v = mesh.vertices().iter().map(|p| p.to_array()).collect();
        (v, mesh.indices().to_vec())
    } else {
        return Err(
            "the collider is not a cuboid, ball, convex hull or trimesh: \
                    give AvianBuoyant::hull"
                .into(),
        );
    };
    moved_hull(&vertices, &triangles, com)
}

/// A floater of mass 1 at the origin whose hull is `vertices` and `triangles` with `com`
/// moved to the origin.
fn moved_hull(vertices: &[[f32; 3]], triangles: &[[u32; 3]], com: Vec3) -> Result<Floater, String> {
    let moved: Vec<[f32; 3]> = vertices
        .iter()
        .map(|v| (Vec3::from_array(*v) - com).to_array())
        .collect();
    let origin = springwater::glam::Vec3::ZERO;
    Floater::hull(&moved, triangles, 1.0, origin).map_err(|e| e.to_string())
}
