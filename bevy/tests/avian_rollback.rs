//! Avian's rigid bodies under rollback (features `avian` and `ggrs`), headless: the
//! shipped boat floated by the water, pushed and turned by a player's inputs, in a
//! bevy_ggrs `SyncTestSession` of check distance 7 (every frame it loads the frame 7
//! back and simulates the 7 frames again). Every frame simulated again must end on the
//! bits its first run ended on: the water's `Surface::state_hash`, the boat's
//! `Transform`, linear and angular velocity. Avian runs in `GgrsSchedule`
//! (`PhysicsPlugins::new(GgrsSchedule)`); the plugin rolls back the water and the boat's
//! `AvianBuoyant`, the game Avian's own components (the plugin's documented contract).

mod common;

use std::collections::HashMap;
use std::sync::Arc;

use avian3d::prelude::*;
use avian3d::schedule::PhysicsSystems;
use bevy::prelude::*;
use bevy_ggrs::prelude::*;
use bevy_ggrs::{LoadWorld, LocalInputs, LocalPlayers, RollbackFrameCount};
use springwater_bevy::prelude::*;
use springwater_bevy::springwater::body::BoatShape;

type Config = GgrsConfig<u8>;

const CHECK_DISTANCE: usize = 7;
const FRAMES: usize = 150;

/// The player's input on a frame: the boat under way ahead, then turning to port, then
/// astern while turning to starboard, then drifting; 30 frames each.
fn input_at(frame: u32) -> u8 {
    (frame / 30 % 4) as u8
}

fn read_inputs(mut commands: Commands, players: Res<LocalPlayers>, mut frame: Local<u32>) {
    let input = input_at(*frame);
    *frame += 1;
    let local = players.0.iter().map(|&p| (p, input)).collect();
    commands.insert_resource(LocalInputs::<Config>(local));
}

/// The helm, before Avian's step: a push along the boat's heading and a turn, from the
/// frame's input only.
fn helm(inputs: Res<PlayerInputs<Config>>, mut boats: Query<Forces, With<AvianBuoyant>>) {
    let (input, _) = inputs[0];
    let (ahead, turn) = match input {
        0 => (12.0, 0.0),
        1 => (12.0, 1.5),
        2 => (-6.0, -1.5),
        _ => (0.0, 0.0),
    };
    for mut forces in &mut boats {
        let heading = forces.rotation().0 * Vec3::X;
        forces.apply_linear_acceleration(heading * ahead);
        forces.apply_angular_acceleration(Vec3::Y * turn);
    }
}

/// A frame's end state as bits: the water's hash, and the boat's translation, rotation,
/// linear and angular velocity.
type Bits = (u64, Vec<u32>);

/// Each frame's first run, and what the runs after a rollback found.
#[derive(Resource, Default)]
struct Record {
    first: HashMap<i32, Bits>,
    /// Frames simulated again and compared with their first run.
    compared: usize,
    /// The frames simulated again that ended elsewhere.
    differed: Vec<i32>,
    loads: usize,
}

fn bits(water: &WaterSurface, boat: (&Transform, &LinearVelocity, &AngularVelocity)) -> Bits {
    let (t, v, w) = boat;
    let floats = [
        t.translation.to_array().as_slice(),
        t.rotation.to_array().as_slice(),
        v.0.to_array().as_slice(),
        w.0.to_array().as_slice(),
    ]
    .concat();
    let hash = water.surface().state_hash();
    (hash, floats.into_iter().map(f32::to_bits).collect())
}

/// At the end of every simulated frame: the first run of a frame is kept, a later one
/// compared with it.
fn record(
    frame: Res<RollbackFrameCount>,
    mut record: ResMut<Record>,
    water: Single<&WaterSurface>,
    boat: Single<(&Transform, &LinearVelocity, &AngularVelocity), With<AvianBuoyant>>,
) {
    let now = bits(*water, *boat);
    let record = &mut *record;
    match record.first.get(&frame.0) {
        None => {
            record.first.insert(frame.0, now);
        }
        Some(first) => {
            record.compared += 1;
            if *first != now {
                record.differed.push(frame.0);
            }
        }
    }
}

/// The game: a 48 × 48 pool, the shipped boat on it, a sync test of `check_distance`;
/// `roll_back_avian`: the game registers Avian's components for rollback.
fn app(check_distance: usize, roll_back_avian: bool) -> App {
    let mut app = common::bare_app();
    let session = SessionBuilder::<Config>::new()
        .with_num_players(1)
        .expect("one player")
        .with_check_distance(check_distance)
        .add_player(PlayerType::Local, 0)
        .expect("player 0")
        .start_synctest_session()
        .expect("a sync test session");
    app.add_plugins((
        GgrsPlugin::<Config>::default(),
        PhysicsPlugins::new(GgrsSchedule),
        SpringwaterPlugin::default().with_rollback().with_avian(),
    ))
    .insert_resource(Session::SyncTest(session))
    .init_resource::<Record>()
    .add_systems(ReadInputs, read_inputs)
    .add_systems(GgrsSchedule, helm.in_set(PhysicsSystems::First))
    .add_systems(
        GgrsSchedule,
        record
            .after(PhysicsSystems::Last)
            .after(WaterSystems::Writeback),
    )
    .add_systems(LoadWorld, |mut record: ResMut<Record>| record.loads += 1);
    if roll_back_avian {
        app.rollback_component_with_copy::<Position>()
            .rollback_component_with_copy::<Rotation>()
            .rollback_component_with_copy::<LinearVelocity>()
            .rollback_component_with_copy::<AngularVelocity>()
            .rollback_component_with_copy::<Transform>();
    }
    app.finish();
    app.cleanup();
    app.world_mut()
        .spawn(Water::with_size(49, 49).with_depth(4.0));
    let hull = Arc::new(BoatShape::default().hull().unwrap().centred().unwrap());
    let vertices: Vec<Vec3> = hull.vertices().iter().map(|v| Vec3::from(*v)).collect();
    app.world_mut().spawn((
        RigidBody::Dynamic,
        Collider::trimesh(vertices, hull.triangles().to_vec()),
        ColliderDensity(0.4),
        AvianBuoyant::with_hull(Arc::clone(&hull)),
        Transform::from_xyz(24.0, 0.2, 24.0),
    ));
    app
}

/// Runs `frames` and returns the last frame's bits.
fn run(app: &mut App, frames: usize) -> Bits {
    for _ in 0..frames {
        app.update();
    }
    let world = app.world_mut();
    let mut waters = world.query::<&WaterSurface>();
    let mut boats = world
        .query_filtered::<(&Transform, &LinearVelocity, &AngularVelocity), With<AvianBuoyant>>();
    let water = waters.single(world).unwrap();
    let boat = boats.single(world).unwrap();
    bits(water, boat)
}

#[test]
fn a_boat_simulated_again_after_a_rollback_ends_every_frame_on_the_bits_of_its_first_run() {
    let mut synctest = app(CHECK_DISTANCE, true);
    let end = run(&mut synctest, FRAMES);
    let record = synctest.world().resource::<Record>();
    println!(
        "{} frames, {} loads, {} frames simulated again, differing: {:?}",
        record.first.len(),
        record.loads,
        record.compared,
        record.differed
    );
    assert!(record.loads >= FRAMES - 10, "{} loads", record.loads);
    assert!(record.compared >= (FRAMES - 10) * CHECK_DISTANCE);
    assert_eq!(record.differed, Vec::<i32>::new());

    // The same game without rollback ends on the same bits.
    let mut straight = app(0, true);
    assert_eq!(run(&mut straight, FRAMES), end);
    assert_eq!(straight.world().resource::<Record>().loads, 0);

    // And the boat went somewhere and made waves.
    let world = synctest.world_mut();
    let mut boats = world.query_filtered::<(&Transform, &LinearVelocity), With<AvianBuoyant>>();
    let mut waters = world.query::<&WaterSurface>();
    let (t, v) = boats.single(world).unwrap();
    let at = Vec2::new(t.translation.x, t.translation.z);
    let (moved, speed) = (at.distance(Vec2::splat(24.0)), v.0.length());
    let kinetic = waters.single(world).unwrap().surface().energy().kinetic;
    println!("the boat moved {moved}, speed {speed}; the water's kinetic energy {kinetic}");
    assert!(moved > 1.0 && speed > 0.1, "moved {moved}, speed {speed}");
    assert!(kinetic > 1e-6, "kinetic energy {kinetic}");
}

#[test]
fn without_avians_components_rolled_back_the_frames_simulated_again_differ() {
    // The water and the AvianBuoyant are rolled back, the boat's motion is not: every
    // frame simulated again starts the boat from where the session left it.
    let mut synctest = app(CHECK_DISTANCE, false);
    run(&mut synctest, 60);
    let record = synctest.world().resource::<Record>();
    println!(
        "{} frames simulated again, {} differing",
        record.compared,
        record.differed.len()
    );
    assert!(record.compared > 0);
    assert!(
        record.differed.len() > record.compared / 2,
        "{} of {} differ",
        record.differed.len(),
        record.compared
    );
}
