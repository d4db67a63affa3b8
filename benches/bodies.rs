//! Floating rigid bodies: what they add to a step.
//!
//! * `bodies`: a 512² pool with 0, 100 and 1,000 bodies of the sizes a game floats (half
//!   balls of radius 1, half cubes of side 2, at half the water's density, heeled a little;
//!   all meet the water as a plane), 8 steps, on 1 and 2 threads; and `smallest`, 1,000
//!   balls of radius 0.5. The ratio to 0 bodies is the bodies' cost.
//! * `hull`: one boat of the shipped hull (2,024 triangles), 8 steps on a 128² pool, against
//!   the same pool without it.
//!
//! Every iteration starts from the same state (see `benches/step.rs` on why).

use criterion::{criterion_group, criterion_main, BenchmarkId, Criterion, Throughput};
use springwater::body::BoatShape;
use springwater::glam::{Quat, Vec3};
use springwater::{Floater, Params, Surface};
use std::sync::Arc;
use std::time::Duration;

fn pool(threads: usize) -> rayon::ThreadPool {
    rayon::ThreadPoolBuilder::new()
        .num_threads(threads)
        .build()
        .unwrap()
}

/// Times 8 steps of `s` on `pool`, every iteration from the same state.
fn eight_steps(b: &mut criterion::Bencher<'_>, pool: &rayon::ThreadPool, s: &Surface) {
    pool.install(|| {
        b.iter_batched_ref(
            || s.clone(),
            |s| s.step_n(8).unwrap(),
            criterion::BatchSize::LargeInput,
        )
    })
}

/// A 512² pool with a drop in the middle and `count` bodies on a regular grid: balls of
/// radius 1 and cubes of side 2 in turn, or with `smallest` balls of radius 0.5.
fn with_bodies(count: usize, smallest: bool) -> Surface {
    let n = 512;
    let mut s = Surface::new(Params::with_size(n, n)).unwrap();
    s.drop_at(256.0, 256.0, 1.0, 8.0).unwrap();
    let per_row = 32;
    for k in 0..count {
        let at = Vec3::new(
            8.0 + (k % per_row) as f32 * 15.5,
            0.0,
            8.0 + (k / per_row) as f32 * 15.5,
        );
        let mut body = if smallest {
            Floater::sphere(0.5, 1.0, at)
        } else if k % 2 == 0 {
            Floater::sphere(1.0, 1.0, at)
        } else {
            Floater::cuboid([1.0, 1.0, 1.0], 1.0, at)
        };
        body.mass = 0.5 * s.buoyancy().density * body.shape.volume();
        body.orientation = Quat::from_rotation_x(0.1 * (k % 5) as f32);
        s.add_floater(body).unwrap();
    }
    s
}

fn many(c: &mut Criterion) {
    let mut group = c.benchmark_group("bodies");
    group
        .sample_size(20)
        .warm_up_time(Duration::from_millis(500))
        .measurement_time(Duration::from_secs(3));
    group.throughput(Throughput::Elements(8 * 512 * 512));
    for threads in [1, 2] {
        let pool = pool(threads);
        for count in [0, 100, 1000] {
            let s = with_bodies(count, false);
            let id = BenchmarkId::new(format!("512x512_{threads}threads"), count);
            group.bench_function(id, |b| eight_steps(b, &pool, &s));
        }
        let s = with_bodies(1000, true);
        let id = BenchmarkId::new(format!("smallest_512x512_{threads}threads"), 1000);
        group.bench_function(id, |b| eight_steps(b, &pool, &s));
    }
    group.finish();
}

fn hull(c: &mut Criterion) {
    let mut group = c.benchmark_group("boat");
    group
        .sample_size(20)
        .warm_up_time(Duration::from_millis(500))
        .measurement_time(Duration::from_secs(3));
    let boat = Arc::new(BoatShape::default().hull().unwrap().centred().unwrap());
    let pool = pool(1);
    for with_boat in [false, true] {
        let mut s = Surface::new(Params::with_size(128, 128)).unwrap();
        s.drop_at(60.0, 64.0, 1.0, 6.0).unwrap();
        if with_boat {
            let mass = 0.4 * s.buoyancy().density * boat.volume();
            let mut b = Floater::with_hull(Arc::clone(&boat), mass, [64.0, 0.0, 64.0]);
            b.orientation = Quat::from_rotation_x(0.1);
            s.add_floater(b).unwrap();
        }
        let name = if with_boat { "one_boat" } else { "no_boat" };
        group.bench_function(BenchmarkId::new(name, "128x128"), |b| {
            eight_steps(b, &pool, &s)
        });
    }
    group.finish();
}

criterion_group!(benches, many, hull);
criterion_main!(benches);
