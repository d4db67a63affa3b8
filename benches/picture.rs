//! The CPU preview renderer: one whole frame (`picture/frame/{grid}_{image}`, throughput
//! in pixels) against one simulation step of the same grid (`picture/step/…`, throughput
//! in nodes), in one group so the ratios come from one run. `cargo bench --bench picture`.

use criterion::{criterion_group, criterion_main, BenchmarkId, Criterion, Throughput};
use springwater::disturb::{Disturbance, Rain};
use springwater::render::{Camera, RenderParams, Renderer, Texture};
use springwater::{Params, Surface};
use std::time::Duration;

fn picture(c: &mut Criterion) {
    let mut g = c.benchmark_group("picture");
    g.sample_size(10)
        .warm_up_time(Duration::from_millis(500))
        .measurement_time(Duration::from_secs(2));
    for (n, w, h) in [(128usize, 400u32, 300u32), (256, 800, 600)] {
        let id = format!("{n}x{n}_{w}x{h}");
        let mut water = Surface::new(Params::with_size(n, n)).unwrap();
        let mut rain = Rain::new(24.0, 1);
        for _ in 0..60 {
            let seconds = water.params().dt / water.params().time_scale;
            rain.apply(&mut water, seconds).unwrap();
            water.step().unwrap();
        }
        let camera = Camera::framing(n, n, 1.0, w, h);
        let extent = (n - 1) as f32;
        let mut renderer = Renderer::new(
            RenderParams::default(),
            Texture::pool_tiles_for(extent, extent),
        )
        .unwrap();
        g.throughput(Throughput::Elements(w as u64 * h as u64));
        g.bench_function(BenchmarkId::new("frame", &id), |b| {
            b.iter(|| {
                renderer.render(&water.mesh_view(), &camera).unwrap();
            })
        });
        g.throughput(Throughput::Elements((n * n) as u64));
        g.bench_function(BenchmarkId::new("step", &id), |b| {
            b.iter(|| water.step().unwrap())
        });
    }
    g.finish();
}

criterion_group!(benches, picture);
criterion_main!(benches);
