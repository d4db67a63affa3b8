//! The cost of a rendered frame of a bevy_ggrs `SyncTestSession` (check distance 7) on a
//! 256 × 256 pool, against the same game without rollback (check distance 0: no saves,
//! no loads). At 60 Hz and the seed's `dt` a session frame is one step, so a sync test
//! frame is 8 steps (the new frame and 7 simulated again), 8 saves with their state
//! hashes and one restore; the plain frame is one step. The mesh is written once per
//! rendered frame in both. Then the parts, on the sync test's water: its step, state
//! hash, save and restore.
//!
//! ```sh
//! cargo bench -p springwater-bevy --features ggrs --bench ggrs_frame
//! ```

#[path = "../tests/rollback_game/mod.rs"]
mod rollback_game;

use std::time::Duration;

use bevy::app::App;
use criterion::measurement::WallTime;
use criterion::{criterion_group, criterion_main, BenchmarkGroup, BenchmarkId, Criterion};
use springwater_bevy::{SpringwaterPlugin, WaterSurface};

const SIZE: usize = 256;

fn frame(c: &mut Criterion) {
    let mut group = c.benchmark_group("ggrs_frame");
    group
        .sample_size(40)
        .measurement_time(Duration::from_secs(8));
    for (name, check_distance) in [("sync_test_7", 7), ("no_rollback", 0)] {
        let mut app = rollback_game::app(SIZE, rollback_game::sync_test(check_distance), |app| {
            app.add_plugins(SpringwaterPlugin::default().with_rollback());
        });
        // Past the first frames: the session rolls back every frame and every save
        // buffer it keeps has been allocated.
        for _ in 0..30 {
            app.update();
        }
        let id = BenchmarkId::new(name, format!("{SIZE}x{SIZE}"));
        group.bench_function(id, |b| b.iter(|| app.update()));
        let counts = app.world().resource::<rollback_game::Counts>();
        assert_eq!(counts.mismatches, 0, "bevy_ggrs reported a mismatch");
        if check_distance > 0 {
            parts(&mut group, &mut app);
        }
    }
    group.finish();
}

/// What a sync test frame is made of, on the water of that session (its surface steps on
/// Bevy's compute pool, as in the frame): one frame's step, the checksum, a save and a
/// restore.
fn parts(group: &mut BenchmarkGroup<WallTime>, app: &mut App) {
    let world = app.world_mut();
    let mut water = world.query::<&mut WaterSurface>();
    let mut water = water.single_mut(world).expect("one water");
    let surface = water.surface_mut();
    let id = |name| BenchmarkId::new(name, format!("{SIZE}x{SIZE}"));
    group.bench_function(id("state_hash"), |b| b.iter(|| surface.state_hash()));
    let mut saved = Vec::new();
    group.bench_function(id("save_into"), |b| {
        b.iter(|| surface.save_into(&mut saved))
    });
    group.bench_function(id("restore"), |b| {
        b.iter(|| surface.restore(&saved).expect("its own save"))
    });
    group.bench_function(id("step"), |b| {
        b.iter(|| surface.advance(1.0 / 60.0).expect("a step"))
    });
}

criterion_group!(benches, frame);
criterion_main!(benches);
