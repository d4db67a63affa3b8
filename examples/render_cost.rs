//! Per-node cost of the render stages against one step, as the best of 30 interleaved
//! runs: a robust ratio on a shared machine, where criterion's means drift.
//!
//! `cargo run --release --example render_cost -- [SIZE] [THREADS]` (513, 1).

use glam::Vec3;
use springwater::mesh::{compute_normals, Normals};
use springwater::refraction::{refract, Refraction, RefractionParams};
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
        let mut best = [f64::MAX; 3];
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
        }
        let nn = (n * n) as f64;
        println!("{n}x{n} {threads} thread(s), best of 30, ns/node: step {:.2} normals {:.2} refract {:.2}  (normals+refract)/step {:.2}",
            best[0] / nn * 1e9, best[1] / nn * 1e9, best[2] / nn * 1e9, (best[1] + best[2]) / best[0]);
    });
}
