//! Render-side stages against one simulation step of the same grid, in one group so the
//! ratios come from one run: `render/{stage}/{n}x{n}`, throughput in nodes.
//!
//! * `step`: one engine step (the reference cost);
//! * `normals`, `refraction`, `normals+refraction`: per-node stages for all nodes;
//! * `normals_and_refraction`: the fused pass (same results as the two calls);
//! * `lod_rebuild`: an index buffer rebuild for an eye 20 units above the water, moving
//!   between two spots three patches apart (every update rebuilds);
//! * `lod_rebuild_full`: a rebuild at full detail (level 0 everywhere: the largest buffer);
//! * `lod_cached`: an update that finds nothing changed (the usual per-frame cost);
//! * `interleave_vertices`: packed `Vertex` buffer (position, normal, uv) from the SoA
//!   slices; `interleave_all`: that plus separate position, normal and uv buffers, in the
//!   same pass (the aim is a tenth of `step` or less; it is memory-bound, so the ratio
//!   grows on grids that outgrow the caches);
//! * `fill_frame_vertices`: normals, refraction and the packed `Vertex` buffer in one pass
//!   (the same buffer as `normals_and_refraction` then `interleave_vertices`).

use criterion::{criterion_group, criterion_main, BenchmarkId, Criterion, Throughput};
use glam::Vec3;
use springwater::buffers::{fill_frame, interleave, Vertex, VertexBuffers};
use springwater::mesh::{compute_normals, LodMesh, LodParams, Normals};
use springwater::refraction::{normals_and_refraction, refract, Refraction, RefractionParams};
use springwater::{Params, Surface};
use std::hint::black_box;
use std::time::Duration;

fn surface(n: usize) -> Surface {
    let mut s = Surface::new(Params::with_size(n, n)).unwrap();
    let c = n as f32 / 2.0;
    s.drop_at(c, c, 1.0, 4.0).unwrap();
    for _ in 0..5 {
        s.step().unwrap();
    }
    s
}

fn render(c: &mut Criterion) {
    let mut g = c.benchmark_group("render");
    g.sample_size(10)
        .warm_up_time(Duration::from_millis(500))
        .measurement_time(Duration::from_secs(2));
    for n in [257usize, 513, 1025] {
        let size = format!("{n}x{n}");
        g.throughput(Throughput::Elements((n * n) as u64));
        let mut water = surface(n);
        g.bench_function(BenchmarkId::new("step", &size), |b| {
            b.iter(|| water.step().unwrap())
        });

        let water = surface(n);
        let view = water.mesh_view();
        let centre = n as f32 / 2.0;
        let eye = Vec3::new(centre, 20.0, centre);
        let optics = RefractionParams::default();
        let mut normals = Normals::new();
        let mut uv = Refraction::default();
        compute_normals(&view, &mut normals);
        g.bench_function(BenchmarkId::new("normals", &size), |b| {
            b.iter(|| compute_normals(black_box(&view), &mut normals))
        });
        g.bench_function(BenchmarkId::new("refraction", &size), |b| {
            b.iter(|| refract(black_box(&view), &normals, eye, &optics, &mut uv).unwrap())
        });
        g.bench_function(BenchmarkId::new("normals+refraction", &size), |b| {
            b.iter(|| {
                compute_normals(black_box(&view), &mut normals);
                refract(&view, &normals, eye, &optics, &mut uv).unwrap()
            })
        });

        g.bench_function(BenchmarkId::new("normals_and_refraction", &size), |b| {
            b.iter(|| {
                normals_and_refraction(black_box(&view), eye, &optics, &mut normals, &mut uv)
                    .unwrap()
            })
        });

        // The stages' outputs, whichever benches the filter ran.
        normals_and_refraction(&view, eye, &optics, &mut normals, &mut uv).unwrap();
        let mut vertices = vec![Vertex::default(); n * n];
        g.bench_function(BenchmarkId::new("interleave_vertices", &size), |b| {
            b.iter(|| {
                let out = VertexBuffers {
                    vertices: Some(&mut vertices),
                    ..Default::default()
                };
                interleave(black_box(&view), &normals, &uv, out).unwrap()
            })
        });
        let mut positions = vec![[0.0f32; 3]; n * n];
        let mut normal_buf = vec![[0.0f32; 3]; n * n];
        let mut uvs = vec![[0.0f32; 2]; n * n];
        g.bench_function(BenchmarkId::new("interleave_all", &size), |b| {
            b.iter(|| {
                let out = VertexBuffers {
                    positions: Some(&mut positions),
                    normals: Some(&mut normal_buf),
                    uvs: Some(&mut uvs),
                    vertices: Some(&mut vertices),
                };
                interleave(black_box(&view), &normals, &uv, out).unwrap()
            })
        });
        g.bench_function(BenchmarkId::new("fill_frame_vertices", &size), |b| {
            b.iter(|| {
                let out = VertexBuffers {
                    vertices: Some(&mut vertices),
                    ..Default::default()
                };
                fill_frame(black_box(&view), eye, &optics, out).unwrap()
            })
        });

        let mut lod = LodMesh::new(LodParams::default()).unwrap();
        let other = eye + Vec3::new(48.0, 0.0, 0.0);
        let mut flip = false;
        g.bench_function(BenchmarkId::new("lod_rebuild", &size), |b| {
            b.iter(|| {
                flip = !flip;
                assert!(lod.update(&view, if flip { eye } else { other }));
            })
        });
        // The patch grid exists once the mesh has seen the view (whichever benches ran).
        lod.update(&view, eye);
        let patches = lod.patch_grid();
        let all_zero = vec![0u8; patches[0] * patches[1]];
        let mut one_coarse = all_zero.clone();
        one_coarse[0] = 1;
        g.bench_function(BenchmarkId::new("lod_rebuild_full", &size), |b| {
            b.iter(|| {
                flip = !flip;
                assert!(lod
                    .set_levels(&view, if flip { &all_zero } else { &one_coarse })
                    .unwrap());
            })
        });
        lod.update(&view, eye);
        g.bench_function(BenchmarkId::new("lod_cached", &size), |b| {
            b.iter(|| assert!(!lod.update(black_box(&view), eye)))
        });
        println!(
            "{size}: {} triangles at eye {eye} (full grid {})",
            lod.triangle_count(),
            2 * (n - 1) * (n - 1)
        );
    }
    g.finish();
}

criterion_group!(benches, render);
criterion_main!(benches);
