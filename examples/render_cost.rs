//! Per-node cost of the render stages (normals, refraction, LOD rebuilds, the packed
//! vertex buffer alone and fused with the stages, `fill_frame`) against one step, as the
//! best of 30 interleaved runs: a robust ratio on a shared machine, where criterion's
//! means drift. The store floor is the machine's limit for the vertex buffer: the same
//! threads writing 32 bytes per node into the same buffer, computing nothing.
//!
//! `cargo run --release --example render_cost -- [SIZE] [THREADS]` (513, 1).

use glam::Vec3;
use springwater::buffers::{fill_frame, interleave, Vertex, VertexBuffers};
use springwater::mesh::{compute_normals, LodMesh, LodParams, Normals};
use springwater::refraction::{normals_and_refraction, refract, Refraction, RefractionParams};
use springwater::{Params, Surface};
use std::time::Instant;
fn main() {
    let n: usize = std::env::args()
        .nth(1)
        .map(|a| a.parse().unwrap())
        .unwrap_or(513);
    let threads: usize = std::env::args()
        .nth(2)
        .map(|a| a.parse().unwrap())
        .unwrap_or(1);
    let mut s = Surface::new(Params::with_size(n, n)).unwrap();
    s.drop_at(n as f32 / 2.0, n as f32 / 2.0, 1.0, 4.0).unwrap();
    for _ in 0..5 {
        s.step().unwrap();
    }
    let pool = rayon::ThreadPoolBuilder::new()
        .num_threads(threads)
        .build()
        .unwrap();
    pool.install(|| {
        let mut best = [f64::MAX; 9];
        let mut vertices = vec![Vertex::default(); n * n];
        let mut lod = LodMesh::new(LodParams::default()).unwrap();
        let mut flip = false;
        let mut nm = Normals::new();
        let mut uv = Refraction::default();
        let eye = Vec3::new(n as f32 / 2.0, 20.0, n as f32 / 2.0);
        let p = RefractionParams::default();
        for _ in 0..30 {
            let t = Instant::now();
            s.step().unwrap();
            best[0] = best[0].min(t.elapsed().as_secs_f64());
            let view = s.mesh_view();
            let t = Instant::now();
            compute_normals(&view, &mut nm);
            best[1] = best[1].min(t.elapsed().as_secs_f64());
            let t = Instant::now();
            refract(&view, &nm, eye, &p, &mut uv).unwrap();
            best[2] = best[2].min(t.elapsed().as_secs_f64());
            let t = Instant::now();
            normals_and_refraction(&view, eye, &p, &mut nm, &mut uv).unwrap();
            best[5] = best[5].min(t.elapsed().as_secs_f64());
            let t = Instant::now();
            let out = VertexBuffers {
                vertices: Some(&mut vertices),
                ..Default::default()
            };
            interleave(&view, &nm, &uv, out).unwrap();
            best[6] = best[6].min(t.elapsed().as_secs_f64());
            let t = Instant::now();
            let out = VertexBuffers {
                vertices: Some(&mut vertices),
                ..Default::default()
            };
            fill_frame(&view, eye, &p, out).unwrap();
            best[7] = best[7].min(t.elapsed().as_secs_f64());
            let t = Instant::now();
            store_floor(&mut vertices, flip as u32 as f32);
            best[8] = best[8].min(t.elapsed().as_secs_f64());
            // A rebuild: the eye moves three patches between updates.
            flip = !flip;
            let at = eye + Vec3::new(if flip { 48.0 } else { 0.0 }, 0.0, 0.0);
            let t = Instant::now();
            lod.update(&view, at);
            best[3] = best[3].min(t.elapsed().as_secs_f64());
            // A rebuild at full detail everywhere.
            let [a, d] = lod.patch_grid();
            let mut levels = vec![0u8; a * d];
            levels[0] = flip as u8;
            let t = Instant::now();
            assert!(lod.set_levels(&view, &levels).unwrap());
            best[4] = best[4].min(t.elapsed().as_secs_f64());
        }
        let nn = (n * n) as f64;
        println!(
            "{n}x{n} {threads} thread(s), best of 30, ns/node: step {:.2} normals {:.2} refract {:.2} \
             fused {:.2} lod {:.3} lod_full {:.2} vertices {:.2} fill_frame {:.2} store floor {:.2} \
             | ratios to a step: normals+refract {:.2} fused {:.2} lod {:.3} lod_full {:.2} \
             vertices {:.3} fill_frame-fused {:.3} store floor {:.3}",
            best[0] / nn * 1e9,
            best[1] / nn * 1e9,
            best[2] / nn * 1e9,
            best[5] / nn * 1e9,
            best[3] / nn * 1e9,
            best[4] / nn * 1e9,
            best[6] / nn * 1e9,
            best[7] / nn * 1e9,
            best[8] / nn * 1e9,
            (best[1] + best[2]) / best[0],
            best[5] / best[0],
            best[3] / best[0],
            best[4] / best[0],
            best[6] / best[0],
            (best[7] - best[5]) / best[0],
            best[8] / best[0],
        );
    });
}

/// Writes every vertex of `out` with one value made from `seed`, in tasks of 4096 nodes
/// on the current pool: stores and nothing else.
fn store_floor(out: &mut [Vertex], seed: f32) {
    use rayon::prelude::*;
    out.par_chunks_mut(4096).for_each(|chunk| {
        let f = std::hint::black_box(seed);
        chunk.fill(Vertex {
            position: [f, f + 1.0, f + 2.0],
            normal: [f + 3.0, f + 4.0, f + 5.0],
            uv: [f + 6.0, f + 7.0],
        });
    });
}
