//! Rollback under bevy_ggrs (feature `ggrs`): a `SyncTestSession` of check distance 7
//! (every frame it loads the frame 7 back, simulates the 7 frames again and compares
//! their checksums with the first run's) with two local players, one dropping water and
//! one pushing a floating ball (`rollback_game`).

mod rollback_game;

use bevy::prelude::*;
use bevy_ggrs::prelude::*;
use rollback_game::{app, sync_test, Counts};
use springwater_bevy::prelude::*;
use springwater_bevy::rollback::WaterSnapshots;

const FRAMES: usize = 300;
const SIZE: usize = 65;

/// `SpringwaterPlugin::with_rollback`.
fn with_rollback(app: &mut App) {
    app.add_plugins(SpringwaterPlugin::default().with_rollback());
}

/// What a run ends on: the water's hash and motion, the ball's place, and the session's
/// counts.
struct End {
    hash: u64,
    kinetic: f64,
    ball: Vec3,
    mismatches: usize,
    loads: usize,
}

fn run(app: &mut App, frames: usize) -> End {
    for _ in 0..frames {
        app.update();
    }
    let world = app.world_mut();
    let water = world
        .query::<&WaterSurface>()
        .single(world)
        .expect("one water")
        .surface();
    let (hash, kinetic) = (water.state_hash(), water.energy().kinetic);
    let ball = world
        .query_filtered::<&Transform, With<Buoyant>>()
        .single(world)
        .expect("one ball")
        .translation;
    let counts = world.resource::<Counts>();
    End {
        hash,
        kinetic,
        ball,
        mismatches: counts.mismatches,
        loads: counts.loads,
    }
}

#[test]
fn a_sync_test_of_300_frames_rolling_back_7_every_frame_never_mismatches() {
    let mut synctest = app(SIZE, sync_test(7), with_rollback);
    let after_100 = run(&mut synctest, 100);
    let grown = synctest
        .world()
        .resource::<WaterSnapshots>()
        .buffers_grown();
    let end = run(&mut synctest, FRAMES - 100);
    assert_eq!(after_100.mismatches, 0, "bevy_ggrs reported a mismatch");
    assert_eq!(end.mismatches, 0, "bevy_ggrs reported a mismatch");
    // A load every frame from the 8th on: the session did roll back.
    assert!(end.loads >= FRAMES - 10, "{} loads", end.loads);

    // The same game without rollback (check distance 0: no saves, no loads) ends on the
    // same bits: simulating the frames again reproduced the straight run.
    let straight = run(&mut app(SIZE, sync_test(0), with_rollback), FRAMES);
    assert_eq!(straight.loads, 0);
    assert_eq!(end.hash, straight.hash);
    assert_eq!(end.ball.to_array(), straight.ball.to_array());

    // And the game did something: the water moves, the ball was pushed away.
    assert!(end.kinetic > 1.0, "kinetic energy {}", end.kinetic);
    let middle = (SIZE - 1) as f32 * 0.5;
    let moved = end.ball.xz().distance(Vec2::splat(middle));
    assert!(moved > 2.0, "the ball moved {moved}");

    // The saves reuse their buffers: none was allocated or grown after the first 100
    // frames, and the session keeps a bounded number of frames.
    let snapshots = synctest.world().resource::<WaterSnapshots>();
    assert_eq!(snapshots.buffers_grown(), grown);
    assert!(
        snapshots.frames() <= 9,
        "{} frames kept",
        snapshots.frames()
    );
}

/// The same session with the water stepped in `GgrsSchedule` and checksummed with its
/// state hash, but never saved nor loaded: bevy_ggrs must see the difference, or the
/// test above could not fail.
#[test]
fn a_water_that_is_not_restored_is_reported_as_a_mismatch() {
    let not_restored = |app: &mut App| {
        app.add_plugins(SpringwaterPlugin::default().in_schedule(GgrsSchedule))
            .checksum_component::<WaterSurface>(|ws| ws.surface().state_hash())
            .require_rollback::<Water>();
    };
    let end = run(&mut app(SIZE, sync_test(7), not_restored), 30);
    assert!(end.mismatches > 0, "no mismatch reported");
}
