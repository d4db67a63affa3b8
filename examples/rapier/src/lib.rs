//! Rapier rigid bodies floating on springwater's water, without Bevy: the coupling a game
//! copies, over springwater's public API (`src/main.rs` runs it, `tests/rapier.rs` holds it
//! to theory).
//!
//! Rapier owns the body: its collider, mass, inertia, collisions and integration. Once per
//! 60 Hz tick the water is asked for its force and torque on the body
//! (`Surface::body_forces`), Rapier applies them through its step, and the water takes the
//! reaction in its own step, so the box makes waves. Rapier's world is the water's local
//! space (the calm surface at `y = 0`, the lattice from the origin along +x and +z) and
//! Rapier's gravity is the water's.
//!
//! Rapier 0.36 does its maths with glam 0.33 and springwater with glam 0.32: the two
//! meet through plain arrays (`to_array` / `from_array`, quaternions as `[x, y, z, w]`,
//! matrices column by column).
//!
//! This crate is an example, not published: it lives in its own crate so that only it
//! builds Rapier.

use rapier3d::math::{Pose, Vector};
use rapier3d::prelude::{PhysicsWorld, RigidBody, RigidBodyHandle};
use springwater::body::Hull;
use springwater::glam::{Mat3, Quat, Vec3};
use springwater::{BodyForces, Floater, Surface};
use std::sync::Arc;

/// The engine's tick: 60 Hz, Rapier's default.
pub const TICK: f32 = 1.0 / 60.0;

/// A Rapier vector in springwater's glam.
pub fn vec3(v: Vector) -> Vec3 {
    Vec3::from_array(v.to_array())
}

/// A springwater vector in Rapier's glam.
pub fn vector(v: Vec3) -> Vector {
    Vector::from_array(v.to_array())
}

/// A Rapier world for `water`: its gravity, stepped at [`TICK`].
pub fn world_for(water: &Surface) -> PhysicsWorld {
    let mut world = PhysicsWorld::new();
    world.gravity = Vector::new(0.0, -water.buoyancy().gravity, 0.0);
    world.integration_parameters.dt = TICK;
    world
}

/// A Rapier body the water floats: its handle and its collider's shape as the water sees
/// it, in the body's axes about Rapier's centre of mass (the shape does not change, so it
/// is built once; the mass, inertia, pose and velocities are read every tick).
pub struct Floating {
    pub handle: RigidBodyHandle,
    shape: Floater,
}

impl Floating {
    /// The body `handle` of `world`, which must have one collider: a cuboid (a box) or a
    /// convex polyhedron (a hull). Rapier's centre of mass is where its colliders'
    /// densities put it, not necessarily the body's origin, and the collider may sit
    /// anywhere on the body: the water's shape is the collider moved into the frame
    /// centred on that centre of mass.
    pub fn new(world: &mut PhysicsWorld, handle: RigidBodyHandle) -> Result<Self, String> {
        let body = world.bodies.get_mut(handle).ok_or("no such body")?;
        // Rapier sums the colliders' mass properties at its next step: sum them now.
        body.recompute_mass_properties_from_colliders(&world.colliders);
        let body = &world.bodies[handle];
        let &[collider] = body.colliders() else {
            return Err("a floating body needs exactly one collider".into());
        };
        let collider = &world.colliders[collider];
        let com = body.local_center_of_mass();
        let placed = collider
            .position_wrt_parent()
            .copied()
            .unwrap_or(Pose::IDENTITY);
        let geometry = collider.shape();
        let centred = placed.rotation == Pose::IDENTITY.rotation && placed.translation == com;
        let shape = match (geometry.as_cuboid(), centred) {
            (Some(cuboid), true) => {
                Floater::cuboid(vec3(cuboid.half_extents), body.mass(), Vec3::ZERO)
            }
            _ => {
                let (points, triangles) = if let Some(cuboid) = geometry.as_cuboid() {
                    cuboid.to_trimesh()
                } else if let Some(polyhedron) = geometry.as_convex_polyhedron() {
                    polyhedron.to_trimesh()
                } else {
                    return Err("only cuboid and convex polyhedron colliders float".into());
                };
                let vertices: Vec<[f32; 3]> = points
                    .iter()
                    .map(|&p| (placed.transform_point(p) - com).to_array())
                    .collect();
                let hull = Hull::new(&vertices, &triangles).map_err(|e| e.to_string())?;
                Floater::with_hull(Arc::new(hull), body.mass(), Vec3::ZERO)
            }
        };
        Ok(Self { handle, shape })
    }

    /// The body as the water sees it now: the shape with Rapier's mass and inertia, its
    /// centre of mass, rotation and velocities (Rapier's linear velocity is the centre of
    /// mass's, its angular velocity is in the world's axes, as the water's).
    pub fn floater(&self, world: &PhysicsWorld) -> Floater {
        let body = &world.bodies[self.handle];
        let local = &body.mass_properties().local_mprops;
        // Rapier keeps the inertia as principal moments and axes (in the body's axes, about
        // the centre of mass, as the water's); rebuilt, the matrix is symmetric only to
        // rounding, and the water checks symmetry to 1e-6 of its size: symmetrise it.
        let inertia = Mat3::from_cols_array(&local.reconstruct_inertia_matrix().to_cols_array());
        let mut floater = self.shape.clone();
        floater.mass = body.mass();
        floater.inertia = Some(0.5 * (inertia + inertia.transpose()));
        floater.position = vec3(body.center_of_mass());
        floater.orientation = Quat::from_array(body.rotation().to_array());
        floater.velocity = vec3(body.linvel());
        floater.angular_velocity = vec3(body.angvel());
        floater
    }
}

/// The water's force and torque on each body for the coming tick, replacing the ones
/// Rapier applied in the last tick (Rapier keeps user forces until they are reset). A game
/// adds its own forces (engines, wind) after this, then steps Rapier and the water.
pub fn push_water(
    world: &mut PhysicsWorld,
    water: &mut Surface,
    bodies: &[Floating],
) -> springwater::Result<()> {
    for floating in bodies {
        let push = water.body_forces(&floating.floater(world), TICK)?;
        apply(&mut world.bodies[floating.handle], push);
    }
    Ok(())
}

/// Makes `push` the user force and torque Rapier applies to `body` in its next step.
pub fn apply(body: &mut RigidBody, push: BodyForces) {
    body.reset_forces(false);
    body.reset_torques(false);
    body.add_force(vector(push.force), true);
    body.add_torque(vector(push.torque), true);
}

/// One tick: the water's forces, Rapier's step, then the water's step with the bodies'
/// reactions.
pub fn tick(
    world: &mut PhysicsWorld,
    water: &mut Surface,
    bodies: &[Floating],
) -> springwater::Result<()> {
    push_water(world, water, bodies)?;
    world.step();
    water.advance(TICK)?;
    Ok(())
}

/// The angle in degrees between a rotation's up axis and the world's.
pub fn heel(rotation: Quat) -> f32 {
    (rotation * Vec3::Y).y.clamp(-1.0, 1.0).acos().to_degrees()
}
