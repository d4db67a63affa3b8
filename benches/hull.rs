//! Criterion benches of hull meshes: validation with mass properties (`hull/new`), and
//! the submerged part (`hull/submerged`) of the boat (`BoatShape`, 2,024 triangles) and
//! of a 12-triangle box, heeled 10° and floating about half under, in flat water (`flat`)
//! and on a rippled `Surface` read with `height_at` at every vertex (`surface`).
//! Throughput counts triangles. Run: `cargo bench --bench hull`.

use criterion::{criterion_group, criterion_main, BenchmarkId, Criterion, Throughput};
use springwater::body::{BoatShape, Hull, HullScratch};
use springwater::glam::{Quat, Vec3};
use springwater::{Buoyancy, Params, Surface};
use std::hint::black_box;
use std::time::Duration;

fn hull(c: &mut Criterion) {
    let mut group = c.benchmark_group("hull");
    group
        .sample_size(30)
        .warm_up_time(Duration::from_millis(500))
        .measurement_time(Duration::from_secs(2));
    let water = Buoyancy::default();
    let mut surface = Surface::new(Params::with_size(64, 64)).unwrap();
    surface.drop_at(30.0, 31.0, 0.5, 3.0).unwrap();
    surface.step_n(20).unwrap();

    let boat = BoatShape::default().hull().unwrap().centred().unwrap();
    let cube = Hull::cuboid([1.0, 0.5, 2.0]).unwrap();
    for (name, hull) in [("boat", &boat), ("box", &cube)] {
        let n = hull.triangles().len();
        let id = format!("{name}/{n}");
        group.throughput(Throughput::Elements(n as u64));
        let (vertices, triangles) = (hull.vertices().to_vec(), hull.triangles().to_vec());
        group.bench_function(BenchmarkId::new("new", &id), |b| {
            b.iter(|| Hull::new(black_box(&vertices), black_box(&triangles)).unwrap())
        });
        let heel = Quat::from_rotation_x(10f32.to_radians());
        let mut scratch = HullScratch::new();
        let at = Vec3::new(32.0, 0.0, 32.0);
        group.bench_function(BenchmarkId::new("submerged/flat", &id), |b| {
            b.iter(|| {
                hull.submerged(black_box(at), heel, water, |_, _| 0.0, &mut scratch)
                    .unwrap()
            })
        });
        let waves = |x: f32, z: f32| surface.height_at(x, z).unwrap_or(0.0);
        group.bench_function(BenchmarkId::new("submerged/surface", &id), |b| {
            b.iter(|| {
                hull.submerged(black_box(at), heel, water, waves, &mut scratch)
                    .unwrap()
            })
        });
    }
    group.finish();
}

criterion_group!(benches, hull);
criterion_main!(benches);
