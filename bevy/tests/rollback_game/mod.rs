//! A small rollback game shared by the `ggrs` test, the `rollback` example and the
//! `ggrs_frame` bench: a square pool with a floating ball and two players in a bevy_ggrs
//! session (a `SyncTestSession` of two local players, or one peer of a P2P session), one
//! dropping water and one pushing the ball, their inputs a function of the frame number. Headless (`common::bare_app`: a manual clock of 1/60 s
//! per update), so that every update is one session frame.

#![allow(dead_code)] // each of the three uses part of it

#[path = "../common/mod.rs"]
mod common;

use bevy::prelude::*;
use bevy_ggrs::prelude::*;
use bevy_ggrs::{LoadWorld, LocalInputs, LocalPlayers};
use springwater_bevy::prelude::*;

/// One byte of input per player.
pub type Config = GgrsConfig<u8>;

/// Player 0 drops water on every 5th frame, somewhere else each time; player 1 pushes
/// the ball one way, then another, changing every 40 frames, with a rest in between.
/// Input 0 is "nothing".
pub fn inputs_at(frame: u32) -> [u8; 2] {
    let drop = match frame % 5 {
        0 => 1 + (frame / 5 % 200) as u8,
        _ => 0,
    };
    let push = match frame / 40 % 5 {
        4 => 0,
        way => 1 + way as u8,
    };
    [drop, push]
}

/// The `ReadInputs` system: the inputs of the next frame (it runs once per new frame,
/// never when frames are simulated again).
fn read_inputs(mut commands: Commands, players: Res<LocalPlayers>, mut frame: Local<u32>) {
    let inputs = inputs_at(*frame);
    *frame += 1;
    let local = players.0.iter().map(|&p| (p, inputs[p])).collect();
    commands.insert_resource(LocalInputs::<Config>(local));
}

/// The pool's size in nodes per side.
#[derive(Resource, Clone, Copy)]
struct Size(usize);

/// The game, in `GgrsSchedule` before the water reads its inputs.
fn play(
    inputs: Res<PlayerInputs<Config>>,
    size: Res<Size>,
    mut drops: MessageWriter<WaterDrop>,
    mut balls: Query<&mut Buoyant>,
) {
    let (drop, _) = inputs[0];
    if drop != 0 {
        let cell = (size.0 as f32 - 9.0) / 50.0;
        let x = 4.0 + cell * f32::from(drop % 50);
        let z = 4.0 + cell * 6.0 * f32::from(drop % 9);
        drops.write(WaterDrop {
            water: None,
            point: Vec3::new(x, 0.0, z),
            height: -1.0,
            radius: 3.0,
        });
    }
    let (push, _) = inputs[1];
    let way = match push {
        1 => Vec3::X,
        2 => Vec3::Z,
        3 => Vec3::NEG_X,
        4 => Vec3::NEG_Z,
        _ => Vec3::ZERO,
    };
    for mut ball in &mut balls {
        ball.force = way * ball.mass * 40.0;
    }
}

/// What the session reported: checksum mismatches, and frames loaded (rollbacks).
#[derive(Resource, Default)]
pub struct Counts {
    pub mismatches: usize,
    pub loads: usize,
}

/// A sync test of the two local players with `check_distance` (0: no saves, no
/// rollbacks).
pub fn sync_test(check_distance: usize) -> Session<Config> {
    let session = SessionBuilder::<Config>::new()
        .with_num_players(2)
        .expect("two players")
        .with_check_distance(check_distance)
        .add_player(PlayerType::Local, 0)
        .expect("player 0")
        .add_player(PlayerType::Local, 1)
        .expect("player 1")
        .start_synctest_session()
        .expect("a sync test session");
    Session::SyncTest(session)
}

/// The game on a `size` × `size` pool in `session`, the water added by `water`
/// (`SpringwaterPlugin::default().with_rollback()`).
pub fn app(size: usize, session: Session<Config>, water: impl FnOnce(&mut App)) -> App {
    let mut app = common::bare_app();
    app.add_plugins(GgrsPlugin::<Config>::default())
        .insert_resource(session)
        .insert_resource(Size(size))
        .add_systems(ReadInputs, read_inputs)
        .add_systems(GgrsSchedule, play.before(WaterSystems::SyncInputs))
        .init_resource::<Counts>()
        .add_systems(LoadWorld, |mut counts: ResMut<Counts>| counts.loads += 1)
        .add_observer(|_: On<SyncTestMismatch>, mut counts: ResMut<Counts>| counts.mismatches += 1);
    water(&mut app);
    app.add_systems(
        Startup,
        move |mut commands: Commands, settings: Res<BuoyancySettings>| {
            commands.spawn(Water::with_size(size, size).with_depth(4.0));
            let middle = (size - 1) as f32 * 0.5;
            commands.spawn((
                Buoyant::sphere(3.0, 0.5, &settings),
                Transform::from_xyz(middle, 0.0, middle),
            ));
        },
    );
    app
}
