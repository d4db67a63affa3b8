//! The ring test of the edge conditions, as numbers a plot can be made from.
//!
//! `cargo run --release --example ring_test > ring.csv` prints, every 4 steps, the energy
//! left in the middle 128 × 128 nodes of a 192 × 192 pool after a bump (height 0.05,
//! radius 4) at its centre, as a share of the bump's energy, for a pinned wall, a free
//! edge and the absorbing boundary (`step,pinned,free,absorbing`). The free edge is held
//! in-plane by a constant force against its springs' rest pull (a pre-tensioned sheet
//! with nothing holding its edge contracts); vertically it is free. Then, on stderr, the
//! reflected energy of the absorbing boundary in the four cases `tests/absorbing.rs`
//! checks, at its worst step of 300 and sampled every 4 steps. `docs/ring_plot.py ring.csv docs/ring-test.png` draws the plot.

#[path = "../tests/common/ring.rs"]
mod ring;

use ring::{energy, reflection, window, Source, HEIGHT, SAMPLE};
use springwater::{Boundary, Params, Surface};

const STEPS: usize = 600;
const MIDDLE: usize = 128;

fn main() {
    let n = MIDDLE + 2 * Boundary::ABSORBING_WIDTH;
    let edges = [Boundary::Pinned, Boundary::Free, Boundary::absorbing()];
    let mut runs: Vec<(Surface, Params)> = edges
        .iter()
        .map(|&b| {
            let p = ring::params(n, b);
            let mut s = Surface::new(p).expect("valid parameters");
            s.drop_at((n / 2) as f32, (n / 2) as f32, HEIGHT, 4.0)
                .expect("a drop inside the pool");
            (s, p)
        })
        .collect();
    let hold = edge_hold(&runs[1].0);
    let (y0, v0) = window(&runs[0].0, n, 0);
    let e0 = energy(&runs[0].1, n, &y0, &v0, 0);
    println!("step,pinned,free,absorbing");
    for step in (0..=STEPS).step_by(SAMPLE) {
        let shares: Vec<String> = runs
            .iter_mut()
            .map(|(s, p)| {
                let (y, vy) = window(s, n, 0);
                let share = energy(p, n, &y, &vy, Boundary::ABSORBING_WIDTH) / e0;
                for _ in 0..SAMPLE {
                    if p.boundary == Boundary::Free {
                        for &(node, f) in &hold {
                            s.add_force(node, f).expect("a finite force");
                        }
                    }
                    s.step().expect("a stable step");
                }
                format!("{share:.6e}")
            })
            .collect();
        println!("{step},{}", shares.join(","));
    }
    for (radius, at) in [
        (4.0, Source::Centre),
        (4.0, Source::Corner),
        (2.0, Source::Centre),
        (2.0, Source::Corner),
    ] {
        let r = reflection(n, Boundary::absorbing(), at, radius);
        eprintln!(
            "absorbing, bump radius {radius}, {at:?}: reflected {:.2e} at worst (step {}), {:.2e} sampled every {SAMPLE} steps",
            r.worst(),
            r.worst_step(),
            r.sampled(SAMPLE)
        );
    }
}

/// The in-plane force that holds each outer node of a free sheet where it is at rest:
/// minus its springs' pull, read off one step from rest (`F = m v / dt`, no damping yet).
fn edge_hold(s: &Surface) -> Vec<(usize, [f32; 3])> {
    let mut probe =
        Surface::new(s.params().with_boundary(Boundary::Free)).expect("valid parameters");
    probe.step().expect("a stable step");
    let grid = probe.grid();
    let [vx, _, vz] = probe.velocities();
    let (m, dt) = (s.params().mass, s.params().dt);
    (0..grid.node_count())
        .filter(|&i| grid.is_border(i))
        .map(|i| (i, [-m * vx[i] / dt, 0.0, -m * vz[i] / dt]))
        .collect()
}
