//! Rapier rigid bodies floated with `Surface::body_forces`: Rapier 0.36 owns the bodies
//! (mass, inertia, collisions, its own integrator at 60 Hz), the water hands it its force
//! and torque every tick and takes the reaction (the coupling of this crate's `src/lib.rs`).
//!
//! "Water held still" is a surface whose nodes are all pinned: it stays flat at height 0,
//! so a draft can be held to the displacement theory.

use rapier3d::math::Vector;
use rapier3d::prelude::{ColliderBuilder, PhysicsWorld, RigidBodyBuilder, RigidBodyHandle};
use springwater::glam::{Quat, Vec3};
use springwater::{Floater, Params, Surface};
use springwater_rapier_example::{
    apply, heel, push_water, tick, vec3, vector, world_for, Floating, TICK,
};

/// A 48 × 48 surface at the defaults (its edges pinned), its water held still or free.
fn water(still: bool) -> Surface {
    let mut s = Surface::new(Params::with_size(48, 48)).unwrap();
    if still {
        for node in 0..48 * 48 {
            s.set_pinned(node, true).unwrap();
        }
    }
    s
}

/// Runs `seconds` of ticks, checking after each that the body is finite and not flung
/// (speed under 20 world units per second, spin under 20 radians per second).
fn run(world: &mut PhysicsWorld, water: &mut Surface, body: &Floating, seconds: f32) {
    for _ in 0..(seconds / TICK).round() as usize {
        tick(world, water, std::slice::from_ref(body)).unwrap();
        let f = body.floater(world);
        assert!(
            f.position.is_finite() && f.velocity.length() < 20.0,
            "{f:?}"
        );
        assert!(f.angular_velocity.length() < 20.0, "{f:?}");
    }
}

/// The body's heel in degrees, and its speed and spin.
fn motion(world: &PhysicsWorld, handle: RigidBodyHandle) -> (f32, f32, f32) {
    let body = &world.bodies[handle];
    let rotation = Quat::from_array(body.rotation().to_array());
    let (v, w) = (vec3(body.linvel()), vec3(body.angvel()));
    (heel(rotation), v.length(), w.length())
}

#[test]
fn a_box_at_half_the_water_density_floats_at_its_draft() {
    // The collider sits on the body 0.5 above its origin: the body's origin is the box's
    // bottom and Rapier's centre of mass is the box's centre, which the water is given.
    let mut s = water(true);
    let mut world = world_for(&s);
    let e = Vec3::new(1.5, 0.5, 1.0);
    let density = 0.5 * s.buoyancy().density;
    let (handle, _) = world.insert(
        RigidBodyBuilder::dynamic()
            .translation(Vector::new(24.0, -0.2, 24.0))
            .can_sleep(false),
        ColliderBuilder::cuboid(e.x, e.y, e.z)
            .translation(Vector::new(0.0, e.y, 0.0))
            .density(density),
    );
    let body = Floating::new(&mut world, handle).unwrap();
    // Rapier's mass and inertia are the uniform box's the water would take.
    let f = body.floater(&world);
    let mass = density * 8.0 * e.x * e.y * e.z;
    assert!(
        (f.mass - mass).abs() < 1e-5 * mass,
        "{} against {mass}",
        f.mass
    );
    let uniform = Floater::cuboid(e, mass, Vec3::ZERO).inertia_tensor();
    let rapier = f.inertia.unwrap();
    assert!(
        rapier.abs_diff_eq(uniform, 1e-5 * uniform.x_axis.x),
        "{rapier} against {uniform}"
    );

    run(&mut world, &mut s, &body, 8.0);
    let bottom = world.bodies[handle].translation().y;
    let draft = 0.5 * 2.0 * e.y;
    let (heel, speed, spin) = motion(&world, handle);
    println!(
        "draft {} against {draft}; heel {heel}°, speed {speed}, spin {spin}",
        -bottom
    );
    assert!((-bottom - draft).abs() < 0.01 * draft, "draft {}", -bottom);
    assert!(heel < 0.1 && speed < 1e-3 && spin < 1e-3);
}

#[test]
fn a_hull_heeled_15_degrees_rights_itself() {
    // A barge as a convex-hull collider: 3 long, 2 wide at the deck and 1.6 at the flat
    // bottom, 0.8 deep, its origin at the keel; half the water's density, so it floats
    // about 0.43 deep with its centre of gravity well under its metacentre. Rolled 15° about
    // its length on free water.
    let mut s = water(false);
    let mut world = world_for(&s);
    let mut points = Vec::new();
    for x in [-1.5, 1.5] {
        for (y, half_beam) in [(0.0, 0.8), (0.8, 1.0)] {
            for z in [-half_beam, half_beam] {
                points.push(Vector::new(x, y, z));
            }
        }
    }
    let (handle, _) = world.insert(
        RigidBodyBuilder::dynamic()
            .translation(Vector::new(24.0, -0.4, 24.0))
            .rotation(Vector::new(15f32.to_radians(), 0.0, 0.0))
            .can_sleep(false),
        ColliderBuilder::convex_hull(&points)
            .unwrap()
            .density(0.5 * s.buoyancy().density),
    );
    let body = Floating::new(&mut world, handle).unwrap();
    let mut heels = Vec::new();
    for _ in 0..10 {
        run(&mut world, &mut s, &body, 1.0);
        heels.push(motion(&world, handle).0);
    }
    println!("heel each second: {heels:?}");
    let (heel, speed, spin) = motion(&world, handle);
    assert!(heels[0] < 15.0, "{heels:?}");
    assert!(heel < 0.5, "{heels:?}");
    assert!(speed < 0.05 && spin < 0.05, "speed {speed}, spin {spin}");
}

/// A flat box 2 × 0.5 × 2 at a tenth of the water's density, dropped from 1 above the
/// water heeled 0.3 radians, given each tick the water's forces taken over `seconds`; after
/// 10 s, the body and the water.
fn drop_light_box(seconds: f32) -> (PhysicsWorld, Surface, Floating) {
    let mut s = water(false);
    let mut world = world_for(&s);
    let (handle, _) = world.insert(
        RigidBodyBuilder::dynamic()
            .translation(Vector::new(24.0, 1.0, 24.0))
            .rotation(Vector::new(0.0, 0.0, 0.3))
            .can_sleep(false),
        ColliderBuilder::cuboid(1.0, 0.25, 1.0).density(0.1 * s.buoyancy().density),
    );
    let body = Floating::new(&mut world, handle).unwrap();
    for _ in 0..600 {
        let push = s.body_forces(&body.floater(&world), seconds).unwrap();
        apply(&mut world.bodies[handle], push);
        world.step();
        s.advance(TICK).unwrap();
        let f = body.floater(&world);
        assert!(
            f.position.is_finite() && f.velocity.length() < 20.0,
            "{f:?}"
        );
        assert!(f.angular_velocity.length() < 20.0, "{f:?}");
    }
    (world, s, body)
}

#[test]
fn a_light_box_stays_stable_and_settles() {
    // Buoyancy is a stiff spring for this box (its heave frequency is about 34 radians per
    // second, 0.57 radians a tick) and the water's drag on it, half under, five times its
    // weight per unit of speed: Rapier's explicit step must still not pump energy into it.
    let (world, s, body) = drop_light_box(TICK);
    let f = body.floater(&world);
    let (heel, speed, spin) = motion(&world, body.handle);
    let under = s.height_at(f.position.x, f.position.z).unwrap();
    let draft = 0.1 * 2.0 * 0.25;
    let measured = under - (f.position.y - 0.25);
    println!("draft {measured} against {draft}; heel {heel}°, speed {speed}, spin {spin}");
    assert!(speed < 0.01 && spin < 0.01, "speed {speed}, spin {spin}");
    assert!(heel < 1.0, "{heel}");
    assert!((measured - draft).abs() < 0.02 * draft, "{measured}");

    // The control: the same box given the forces over a tick of 1e-4 s, nearly the forces
    // at the velocities the tick starts with (explicit forces; the water gets as little of
    // the reaction), is still bouncing.
    let (world, _, body) = drop_light_box(1e-4);
    let (heel, speed, spin) = motion(&world, body.handle);
    println!("with explicit forces after 10 s: heel {heel}°, speed {speed}, spin {spin}");
    assert!(speed > 0.5, "speed {speed}");
}

#[test]
fn a_box_pushed_against_a_dock_stays_afloat_against_it() {
    // The dock is a fixed Rapier block standing half in the water (its face at x = 21);
    // the water does not know it. A box at half the water's density is dropped beside it
    // and a steady wind of a tenth of its weight pushes it against the dock: Rapier stops
    // it there, the water keeps it at its draft.
    let mut s = water(false);
    let mut world = world_for(&s);
    let dock = world.bodies.insert(RigidBodyBuilder::fixed());
    world.colliders.insert_with_parent(
        ColliderBuilder::cuboid(3.0, 1.0, 12.0)
            .translation(Vector::new(18.0, 0.0, 24.0))
            .friction(0.0),
        dock,
        &mut world.bodies,
    );
    let face = 21.0;
    let e = Vec3::new(1.0, 0.5, 1.0);
    let (handle, _) = world.insert(
        RigidBodyBuilder::dynamic()
            .translation(Vector::new(face + e.x + 1.0, 1.0, 24.0))
            .can_sleep(false),
        ColliderBuilder::cuboid(e.x, e.y, e.z).density(0.5 * s.buoyancy().density),
    );
    let body = Floating::new(&mut world, handle).unwrap();
    let wind = Vec3::new(
        -0.1 * body.floater(&world).mass * s.buoyancy().gravity,
        0.0,
        0.0,
    );
    let draft = 0.5 * 2.0 * e.y;
    let (mut gaps, mut drafts) = (Vec::new(), Vec::new());
    for _ in 0..10 {
        for _ in 0..60 {
            push_water(&mut world, &mut s, std::slice::from_ref(&body)).unwrap();
            world.bodies[handle].add_force(vector(wind), true);
            world.step();
            s.advance(TICK).unwrap();
        }
        let f = body.floater(&world);
        let under = s.height_at(f.position.x, f.position.z).unwrap();
        // The box's face towards the dock, and the water's height on its bottom.
        gaps.push(f.position.x - e.x - face);
        drafts.push(under - (f.position.y - e.y));
    }
    let (heel, speed, spin) = motion(&world, handle);
    println!(
        "each second: gap to the dock {gaps:?}, draft {drafts:?} against {draft}; \
         heel {heel}°, speed {speed}, spin {spin}"
    );
    // Against the dock from the third second on, within Rapier's contact allowance.
    assert!(gaps[2..].iter().all(|g| g.abs() < 0.02), "{gaps:?}");
    assert!(
        drafts[2..].iter().all(|d| (d - draft).abs() < 0.03 * draft),
        "{drafts:?}"
    );
    assert!(heel < 1.0, "{heel}");
    assert!(speed < 0.01 && spin < 0.01, "speed {speed}, spin {spin}");
}
