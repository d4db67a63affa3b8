//! Avian's rigid bodies floating on the water (feature `avian`), headless: drafts from
//! displacement, a heeled barge righting itself, a box held against a dock, and the
//! gravity of the two engines kept equal.

mod common;

use std::sync::Arc;

use avian3d::prelude::*;
use bevy::prelude::*;
use springwater_bevy::prelude::*;
use springwater_bevy::springwater::body::{BoatShape, Hull, HullScratch};
use springwater_bevy::springwater::glam;

/// Ticks of 1/60 s: 25 seconds, long enough for a dropped body to settle.
const SETTLE: usize = 1500;

/// A headless app with Avian (its default gravity, 9.81 down) and the water on one fixed
/// clock of 60 Hz, and a 48 × 48 pool of spacing 1 from the origin.
fn app() -> (App, Entity) {
    let mut app = common::bare_app();
    app.add_plugins((
        PhysicsPlugins::default(),
        SpringwaterPlugin::default().with_avian(),
    ))
    .insert_resource(Time::<Fixed>::from_hz(60.0));
    // Avian's plugins add some of their resources when the app finishes building.
    app.finish();
    app.cleanup();
    let water = app
        .world_mut()
        .spawn(Water::with_size(49, 49).with_depth(4.0))
        .id();
    app.update();
    (app, water)
}

fn run(app: &mut App, ticks: usize) {
    for _ in 0..ticks {
        app.update();
    }
}

/// The water's height under the world point `p` (the water sits at the origin).
fn water_under(app: &App, water: Entity, p: Vec3) -> f32 {
    let ws = app.world().get::<WaterSurface>(water).unwrap();
    ws.surface().height_at(p.x, p.z).unwrap()
}

fn pose(app: &App, body: Entity) -> (Vec3, Quat) {
    let world = app.world();
    let p = world.get::<Position>(body).unwrap().0;
    let r = world.get::<Rotation>(body).unwrap().0;
    (p, r)
}

/// The angle in degrees between the body's up axis and the world's.
fn heel(rotation: Quat) -> f32 {
    (rotation * Vec3::Y).y.clamp(-1.0, 1.0).acos().to_degrees()
}

/// The shipped boat with its centroid (the centre of mass at uniform density) at the
/// origin.
fn boat() -> Arc<Hull> {
    Arc::new(BoatShape::default().hull().unwrap().centred().unwrap())
}

fn spawn_box(app: &mut App, half: Vec3, density: f32, at: Vec3) -> Entity {
    app.world_mut()
        .spawn((
            RigidBody::Dynamic,
            Collider::cuboid(2.0 * half.x, 2.0 * half.y, 2.0 * half.z),
            ColliderDensity(density),
            AvianBuoyant::default(),
            Transform::from_translation(at),
        ))
        .id()
}

#[test]
fn the_water_takes_avians_gravity() {
    let (mut app, water) = app();
    run(&mut app, 2);
    let g = app.world().resource::<Gravity>().0;
    let ws = app.world().get::<WaterSurface>(water).unwrap();
    assert_eq!(ws.surface().buoyancy().gravity, -g.y);
    assert_eq!(app.world().resource::<BuoyancySettings>().gravity, -g.y);
    app.world_mut().resource_mut::<Gravity>().0 = Vec3::new(0.0, -20.0, 0.0);
    run(&mut app, 2);
    let ws = app.world().get::<WaterSurface>(water).unwrap();
    assert_eq!(ws.surface().buoyancy().gravity, 20.0);
}

#[test]
fn a_box_and_a_ball_float_at_the_draft_their_displacement_predicts() {
    // 0.1: a light body, a stiff spring for an explicit step (the forces are implicit).
    for ratio in [0.1f32, 0.25, 0.5, 0.75] {
        let (mut app, water) = app();
        let half = Vec3::new(2.0, 1.0, 1.5);
        let boxed = spawn_box(&mut app, half, ratio, Vec3::new(16.0, 0.5, 24.0));
        let radius = 2.0;
        let ball = app
            .world_mut()
            .spawn((
                RigidBody::Dynamic,
                Collider::sphere(radius),
                ColliderDensity(ratio),
                AvianBuoyant::default(),
                Transform::from_xyz(32.0, 0.5, 24.0),
            ))
            .id();
        run(&mut app, SETTLE);

        let (p, r) = pose(&app, boxed);
        let draft = water_under(&app, water, p) - (p.y - half.y);
        let want = ratio * 2.0 * half.y;
        println!(
            "box at {ratio}: draft {draft}, predicted {want}, heel {}",
            heel(r)
        );
        assert!(
            (draft - want).abs() < 0.02 * want,
            "box {ratio}: {draft} vs {want}"
        );
        assert!(heel(r) < 1.0);
        let weight = app.world().get::<ComputedMass>(boxed).unwrap().value() * 9.81;
        let push = app.world().get::<AvianBuoyant>(boxed).unwrap().water_force;
        assert!(
            (push.y - weight).abs() < 0.02 * weight,
            "{push} vs {weight}"
        );

        // A ball's cap of height h holds π h² (3r − h) / 3: bisect for the displacement.
        let volume = ratio * 4.0 / 3.0 * std::f32::consts::PI * radius.powi(3);
        let cap = |h: f32| std::f32::consts::PI * h * h * (3.0 * radius - h) / 3.0;
        let (mut lo, mut hi) = (0.0f32, 2.0 * radius);
        for _ in 0..60 {
            let mid = 0.5 * (lo + hi);
            *(if cap(mid) < volume { &mut lo } else { &mut hi }) = mid;
        }
        let want = 0.5 * (lo + hi);
        let (p, _) = pose(&app, ball);
        let draft = water_under(&app, water, p) - (p.y - radius);
        println!("ball at {ratio}: draft {draft}, predicted {want}");
        assert!(
            (draft - want).abs() < 0.02 * want,
            "ball {ratio}: {draft} vs {want}"
        );
    }
}

#[test]
fn the_boat_displaces_its_weight_with_its_centre_of_buoyancy_under_its_centre_of_mass() {
    let (mut app, water) = app();
    let hull = boat();
    let vertices: Vec<Vec3> = hull
        .vertices()
        .iter()
        .map(|v| Vec3::from_array(*v))
        .collect();
    let ratio = 0.5;
    let body = app
        .world_mut()
        .spawn((
            RigidBody::Dynamic,
            Collider::trimesh(vertices, hull.triangles().to_vec()),
            ColliderDensity(ratio),
            AvianBuoyant::with_hull(Arc::clone(&hull)),
            Transform::from_xyz(24.0, 0.5, 24.0),
        ))
        .id();
    run(&mut app, SETTLE);

    let world = app.world();
    let mass = world.get::<ComputedMass>(body).unwrap().value();
    let com = world.get::<ComputedCenterOfMass>(body).unwrap().0;
    let (p, r) = pose(&app, body);
    let centre = p + r * com;
    let ws = world.get::<WaterSurface>(water).unwrap();
    let s = ws.surface();
    // The hull's wet volume under the water as it is now, in the body's pose.
    let glam_vec = |v: Vec3| glam::Vec3::from_array(v.to_array());
    let sub = hull
        .submerged(
            glam_vec(p),
            glam::Quat::from_array(r.to_array()),
            s.buoyancy(),
            |x, z| s.height_at(x, z).unwrap(),
            &mut HullScratch::new(),
        )
        .unwrap();
    let want = mass / s.buoyancy().density;
    println!(
        "boat: mass {mass} (hull volume {}), displaces {}, heel {}",
        hull.volume(),
        sub.volume,
        heel(r)
    );
    assert!((mass - ratio * hull.volume()).abs() < 0.01 * mass);
    assert!(
        (sub.volume - want).abs() < 0.02 * want,
        "{} vs {want}",
        sub.volume
    );
    let off =
        (Vec3::from_array(sub.centre_of_buoyancy.to_array()) - centre) * Vec3::new(1.0, 0.0, 1.0);
    println!("boat: B off G by {off}");
    assert!(off.length() < 0.02, "B off G by {off}");
}

#[test]
fn a_heeled_barge_rights_itself() {
    let (mut app, _) = app();
    let half = Vec3::new(3.0, 0.5, 2.0);
    let barge = spawn_box(&mut app, half, 0.5, Vec3::new(24.0, 0.0, 24.0));
    app.world_mut()
        .get_mut::<Transform>(barge)
        .unwrap()
        .rotate_z(15f32.to_radians());
    let mut heels = Vec::new();
    for _ in 0..10 {
        run(&mut app, 60);
        heels.push(heel(pose(&app, barge).1));
    }
    println!("heel each second: {heels:?}");
    assert!(heels.iter().all(|h| h.is_finite() && *h < 15.5));
    assert!(heels[9] < 1.0, "still heeled {}°", heels[9]);
}

#[test]
fn a_box_against_a_dock_stays_afloat() {
    let (mut app, water) = app();
    let half = Vec3::new(1.5, 1.0, 1.5);
    let boxed = spawn_box(&mut app, half, 0.5, Vec3::new(20.0, 0.0, 24.0));
    // A steady push towards the dock (wind, an engine): against the water's drag of 6 per
    // second on the displaced mass (the body's own, 9), it comes in at about 1 per second.
    app.world_mut()
        .entity_mut(boxed)
        .insert(ConstantForce::new(54.0, 0.0, 0.0));
    // A dock: a wall from x = 24 to 28, from the bottom to 2 above the water, without
    // friction (a wall with friction may hold a box pressed against it off its draft).
    let face = 24.0;
    app.world_mut().spawn((
        RigidBody::Static,
        Collider::cuboid(4.0, 6.0, 16.0),
        Friction::ZERO.with_combine_rule(CoefficientCombine::Min),
        Transform::from_xyz(face + 2.0, -1.0, 24.0),
    ));
    run(&mut app, SETTLE);

    let (p, r) = pose(&app, boxed);
    let v = app.world().get::<LinearVelocity>(boxed).unwrap().0;
    let draft = water_under(&app, water, p) - (p.y - half.y);
    println!(
        "box at the dock: {p}, draft {draft}, heel {}, velocity {v}",
        heel(r)
    );
    assert!(p.x + half.x <= face + 0.05, "through the dock: {p}");
    assert!(p.x + half.x > face - 0.5, "never reached the dock: {p}");
    assert!((draft - 1.0).abs() < 0.03, "draft {draft}");
    assert!(heel(r) < 2.0);
    assert!(v.length() < 0.05, "still moving: {v}");
}

#[test]
fn a_box_keeps_its_draft_with_avians_clock_slower_or_faster() {
    // Avian's tick is the fixed timestep times `Time<Physics>`'s relative speed, and the
    // water's forces are taken over that tick; the water itself steps by the fixed
    // timestep. Floating at rest is a balance of weight and buoyancy, whatever the tick.
    for speed in [0.5f32, 2.0] {
        let (mut app, water) = app();
        app.world_mut()
            .resource_mut::<Time<Physics>>()
            .set_relative_speed(speed);
        let half = Vec3::new(2.0, 1.0, 1.5);
        let boxed = spawn_box(&mut app, half, 0.5, Vec3::new(24.0, 0.5, 24.0));
        // The same 25 seconds of physics time at either speed.
        run(&mut app, (SETTLE as f32 / speed) as usize);

        let (p, r) = pose(&app, boxed);
        let draft = water_under(&app, water, p) - (p.y - half.y);
        let weight = app.world().get::<ComputedMass>(boxed).unwrap().value() * 9.81;
        let push = app.world().get::<AvianBuoyant>(boxed).unwrap().water_force;
        let v = app.world().get::<LinearVelocity>(boxed).unwrap().0;
        println!(
            "relative speed {speed}: draft {draft} for 1, heel {}, lift {} for {weight}, velocity {v}",
            heel(r),
            push.y
        );
        assert!((draft - 1.0).abs() < 0.02, "speed {speed}: draft {draft}");
        assert!(heel(r) < 1.0, "speed {speed}: heel {}", heel(r));
        assert!(
            (push.y - weight).abs() < 0.02 * weight,
            "speed {speed}: {push} vs {weight}"
        );
        assert!(v.length() < 0.05, "speed {speed}: still moving: {v}");
    }
}
