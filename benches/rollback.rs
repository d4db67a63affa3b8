//! Criterion benches of rollback: the state hash and one step, saving into a reused
//! buffer and restoring from it, against the memory floor of the same bytes.
//!
//! `rollback/<case>/<n>x<n>` at 256² and 512², on 2 threads:
//!
//! - `step`: one engine step (what a 60 Hz frame costs at the defaults);
//! - `state_hash`: [`Surface::state_hash`];
//! - `save_into`, `restore`: one [`Surface::save_into`] into a buffer that held a save
//!   already, one [`Surface::restore`] of it (in place: same size and model);
//! - `save_restore`: both, what a rollback frame costs beside its steps;
//! - `two_copies`: the floor, two plain copies of a buffer of the save's length (into a
//!   second buffer and back), the memory traffic any save and restore must at least have;
//! - `crc32`: the checksum the format carries, over the same bytes.
//!
//! The surface is a pinned pool with two drops, some steps in. Throughput counts the
//! save's bytes (nodes for `step` and `state_hash`). Run: `cargo bench --bench rollback`.

use criterion::{criterion_group, criterion_main, BenchmarkId, Criterion, Throughput};
use springwater::{Params, Surface};
use std::hint::black_box;
use std::sync::Arc;
use std::time::Duration;

fn pool(n: usize) -> Surface {
    let mut s = Surface::new(Params::with_size(n, n)).unwrap();
    let pool = rayon::ThreadPoolBuilder::new().num_threads(2).build();
    s.set_thread_pool(Some(Arc::new(pool.unwrap())));
    let c = n as f32 / 2.0;
    s.drop_at(c, c, 1.0, 4.0).unwrap();
    s.drop_at(c / 2.0, c, -0.8, 3.0).unwrap();
    s.step_n(20).unwrap();
    s
}

fn rollback(c: &mut Criterion) {
    let mut group = c.benchmark_group("rollback");
    group
        .sample_size(30)
        .warm_up_time(Duration::from_millis(500))
        .measurement_time(Duration::from_secs(3));
    for n in [256, 512] {
        let id = format!("{n}x{n}");
        let mut s = pool(n);
        let mut saved = Vec::new();
        s.save_into(&mut saved);
        let len = saved.len();

        group.throughput(Throughput::Elements((n * n) as u64));
        group.bench_function(BenchmarkId::new("step", &id), |b| {
            b.iter(|| s.step().unwrap())
        });
        group.bench_function(BenchmarkId::new("state_hash", &id), |b| {
            b.iter(|| black_box(&s).state_hash())
        });

        group.throughput(Throughput::Bytes(len as u64));
        let (mut copy, mut back) = (saved.clone(), saved.clone());
        group.bench_function(BenchmarkId::new("two_copies", &id), |b| {
            b.iter(|| {
                copy.copy_from_slice(black_box(&saved));
                back.copy_from_slice(black_box(&copy));
            })
        });
        group.bench_function(BenchmarkId::new("crc32", &id), |b| {
            b.iter(|| crc32fast::hash(black_box(&saved)))
        });
        group.bench_function(BenchmarkId::new("save_into", &id), |b| {
            b.iter(|| black_box(&s).save_into(&mut saved))
        });
        group.bench_function(BenchmarkId::new("restore", &id), |b| {
            b.iter(|| s.restore(black_box(&saved)).unwrap())
        });
        group.bench_function(BenchmarkId::new("save_restore", &id), |b| {
            b.iter(|| {
                s.save_into(&mut saved);
                s.restore(black_box(&saved)).unwrap();
            })
        });
    }
    group.finish();
}

criterion_group!(benches, rollback);
criterion_main!(benches);
