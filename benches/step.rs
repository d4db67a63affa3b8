//! Criterion benches of one simulation step, reported in nodes per second.
//!
//! `step/<kernel>/<cols>x<rows>` for the scalar reference, the engine on 1 and 2 threads
//! (single steps, and passes of 4 steps per sweep over memory), the naive array-of-structs
//! baseline and the memory-floor kernel; `band_rows/<h>` sweeps the colour granularity and
//! `pass_steps/<k>` the steps per pass; `open_water/<case>/<n>` steps a pool with a pinned
//! wall (in passes of several steps, and one step per pass as bodies need), with the
//! absorbing boundary, and with 1, 16 or 64 floating balls (2 threads, 8 steps per
//! iteration). Throughput counts node updates (nodes × steps). Run: `cargo bench --bench step` (add
//! `RUSTFLAGS="-C target-cpu=native"` for the AVX-512 build).

use criterion::{criterion_group, criterion_main, BenchmarkId, Criterion, Throughput};
use springwater::internals::{MemoryFloor, NaiveSurface, Tuning};
use springwater::{Boundary, Floater, Params, SimdLevel, Surface};
use std::hint::black_box;
use std::time::Duration;

const SIZES: [usize; 4] = [64, 256, 1024, 2048];

fn surface(n: usize) -> Surface {
    let mut s = Surface::new(Params::with_size(n, n)).unwrap();
    s.drop_at(n as f32 / 2.0, n as f32 / 2.0, 1.0, 4.0).unwrap();
    s
}

fn pool(threads: usize) -> rayon::ThreadPool {
    rayon::ThreadPoolBuilder::new()
        .num_threads(threads)
        .build()
        .unwrap()
}

fn step(c: &mut Criterion) {
    let mut group = c.benchmark_group("step");
    group
        .sample_size(10)
        .warm_up_time(Duration::from_millis(500))
        .measurement_time(Duration::from_secs(2));
    for n in SIZES {
        let id = format!("{n}x{n}");
        group.throughput(Throughput::Elements((n * n) as u64));
        let mut s = surface(n);
        s.set_simd_level(SimdLevel::Scalar);
        group.bench_function(BenchmarkId::new("reference", &id), |b| {
            b.iter(|| s.step().unwrap())
        });
        for threads in [1, 2] {
            let mut s = surface(n);
            let pool = pool(threads);
            group.bench_function(BenchmarkId::new(format!("engine_{threads}t"), &id), |b| {
                pool.install(|| b.iter(|| s.step().unwrap()))
            });
        }
        group.throughput(Throughput::Elements((4 * n * n) as u64));
        for threads in [1, 2] {
            let mut s = surface(n);
            let pool = pool(threads);
            group.bench_function(
                BenchmarkId::new(format!("engine_pass4_{threads}t"), &id),
                |b| pool.install(|| b.iter(|| s.step_n(4).unwrap())),
            );
        }
        group.throughput(Throughput::Elements((n * n) as u64));
        let mut naive = NaiveSurface::new(&Params::with_size(n, n));
        naive.drop_at(n, n as f32 / 2.0, n as f32 / 2.0, 1.0, 4.0);
        group.bench_function(BenchmarkId::new("naive_aos", &id), |b| {
            b.iter(|| naive.step())
        });
        let mut floor = MemoryFloor::new(n * n);
        let pool2 = pool(2);
        group.bench_function(BenchmarkId::new("memory_floor_2t", &id), |b| {
            pool2.install(|| b.iter(|| floor.pass(0.4, black_box(0.999))))
        });
    }
    group.finish();
}

fn band_rows(c: &mut Criterion) {
    let mut group = c.benchmark_group("band_rows");
    group
        .sample_size(10)
        .warm_up_time(Duration::from_millis(300))
        .measurement_time(Duration::from_secs(1));
    let pool = pool(2);
    for n in [256, 1024] {
        group.throughput(Throughput::Elements((n * n) as u64));
        for h in [2, 4, 8, 16, 32, 64] {
            let mut s = surface(n);
            s.set_band_rows(h);
            group.bench_function(BenchmarkId::new(format!("{n}x{n}"), h), |b| {
                pool.install(|| b.iter(|| s.step().unwrap()))
            });
        }
    }
    group.finish();
}

fn pass_steps(c: &mut Criterion) {
    let mut group = c.benchmark_group("pass_steps");
    group
        .sample_size(10)
        .warm_up_time(Duration::from_millis(300))
        .measurement_time(Duration::from_secs(2));
    let pool = pool(2);
    let n = 2048;
    group.throughput(Throughput::Elements((8 * n * n) as u64));
    for k in [1, 2, 4, 8] {
        let mut s = surface(n);
        s.set_pass_steps(k);
        group.bench_function(BenchmarkId::new(format!("{n}x{n}"), k), |b| {
            pool.install(|| b.iter(|| s.step_n(8).unwrap()))
        });
    }
    group.finish();
}

fn open_water(c: &mut Criterion) {
    let mut group = c.benchmark_group("open_water");
    group
        .sample_size(30)
        .warm_up_time(Duration::from_millis(500))
        .measurement_time(Duration::from_secs(3));
    let pool = pool(2);
    for n in [256, 1024] {
        group.throughput(Throughput::Elements((8 * n * n) as u64));
        let with = |boundary: Boundary, balls: usize| {
            let mut s = Surface::new(Params::with_size(n, n).with_boundary(boundary)).unwrap();
            s.drop_at(n as f32 / 2.0, n as f32 / 2.0, 1.0, 4.0).unwrap();
            for k in 0..balls {
                let at = [
                    40.0 + (k % 8) as f32 * 22.0,
                    0.0,
                    40.0 + (k / 8) as f32 * 22.0,
                ];
                let mut ball = Floater::sphere(2.0, 1.0, at);
                ball.mass = 0.5 * ball.shape.volume();
                s.add_floater(ball).unwrap();
            }
            s
        };
        let mut single = with(Boundary::Pinned, 0);
        single.set_pass_steps(1);
        let cases = [
            ("pinned", with(Boundary::Pinned, 0)),
            ("pinned_1step", single),
            ("absorbing", with(Boundary::absorbing(), 0)),
            ("floaters_1", with(Boundary::Pinned, 1)),
            ("floaters_16", with(Boundary::Pinned, 16)),
            ("floaters_64", with(Boundary::Pinned, 64)),
        ];
        // Every iteration starts from the same state: left to run for thousands of steps,
        // a calm pool's ripples decay into the range where their squares are subnormal,
        // and the step slows down several times (see docs/performance.md).
        for (name, s) in cases {
            group.bench_function(BenchmarkId::new(name, n), |b| {
                pool.install(|| {
                    b.iter_batched_ref(
                        || s.clone(),
                        |s| s.step_n(8).unwrap(),
                        criterion::BatchSize::LargeInput,
                    )
                })
            });
        }
    }
    group.finish();
}

criterion_group!(benches, step, band_rows, pass_steps, open_water);
criterion_main!(benches);
