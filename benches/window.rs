//! Criterion benches of the moving window: a shift of 1, 8 and 64 cells (along both axes,
//! so every row is cut) against one step of the same grid, at 512² and 1024².
//!
//! `window/<case>/<n>x<n>` with `case` = `step` (one engine step, 2 threads),
//! `shift_<k>` (one `Surface::shift(±k, ±k)`, alternating direction so the window stays
//! put on average), or `floor` (the memory floor of moving rows: six plain arrays of `n²`
//! floats each moved by one row with `copy_within`, three per thread on the same 2
//! threads, the 24 bytes per node read and written that any shift by moving rows must
//! move). The surface is open water (absorbing boundary) with a drop in the
//! middle, as a game's window would be. Throughput counts nodes. Run:
//! `cargo bench --bench window`.

use criterion::{criterion_group, criterion_main, BenchmarkId, Criterion, Throughput};
use rayon::prelude::*;
use springwater::{Boundary, Params, Surface};
use std::hint::black_box;
use std::sync::Arc;
use std::time::Duration;

fn two_threads() -> rayon::ThreadPool {
    rayon::ThreadPoolBuilder::new()
        .num_threads(2)
        .build()
        .unwrap()
}

fn open_water(n: usize) -> Surface {
    let mut p = Params::with_size(n, n);
    p.boundary = Boundary::Absorbing { width: 32 };
    let mut s = Surface::new(p).unwrap();
    s.drop_at(n as f32 / 2.0, n as f32 / 2.0, 1.0, 4.0).unwrap();
    s.set_thread_pool(Some(Arc::new(two_threads())));
    s.step_n(4).unwrap();
    s
}

fn window(c: &mut Criterion) {
    let mut group = c.benchmark_group("window");
    group
        .sample_size(20)
        .warm_up_time(Duration::from_millis(500))
        .measurement_time(Duration::from_secs(2));
    for n in [512, 1024] {
        let id = format!("{n}x{n}");
        group.throughput(Throughput::Elements((n * n) as u64));
        let mut s = open_water(n);
        group.bench_function(BenchmarkId::new("step", &id), |b| {
            b.iter(|| s.step().unwrap())
        });
        let pool = two_threads();
        let mut arrays = vec![vec![0.5f32; n * n]; 6];
        let mut sign = 1;
        group.bench_function(BenchmarkId::new("floor", &id), |b| {
            b.iter(|| {
                pool.install(|| {
                    arrays.par_iter_mut().with_max_len(3).for_each(|a| {
                        let (src, dst) = if sign > 0 { (n, 0) } else { (0, n) };
                        a.copy_within(src..src + n * n - n, dst);
                    })
                });
                sign = -sign;
            })
        });
        for k in [1, 8, 64] {
            let mut s = open_water(n);
            let mut sign = 1;
            group.bench_function(BenchmarkId::new(format!("shift_{k}"), &id), |b| {
                b.iter(|| {
                    s.shift(black_box(sign * k), black_box(sign * k)).unwrap();
                    sign = -sign;
                })
            });
        }
    }
    group.finish();
}

criterion_group!(benches, window);
criterion_main!(benches);
