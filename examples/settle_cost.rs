//! The step's cost while a pool settles: a drop, then thousands of steps of calm water.
//!
//! `cargo run --release --example settle_cost [size] [steps]` (256, 40000)
//!
//! Prints, for every thousand steps, the mean time per step, how many heights and
//! velocities are subnormal, and the largest height. Heights and vertical velocities
//! below 1e-18 are stored as 0 (`src/forces/mod.rs`), so the step's cost should not
//! change as the ripples die out.

use springwater::{Params, Surface};
use std::time::Instant;

fn main() {
    let arg = |i: usize, default: usize| {
        std::env::args()
            .nth(i)
            .and_then(|a| a.parse().ok())
            .unwrap_or(default)
    };
    let (n, total) = (arg(1, 256), arg(2, 40_000));
    let mut s = Surface::new(Params::with_size(n, n)).expect("valid size");
    s.drop_at(n as f32 / 2.0, n as f32 / 2.0, 1.0, 3.0)
        .expect("drop inside");
    let batch = 1000;
    let subnormal = |b: [&[f32]; 3]| {
        b.iter()
            .flat_map(|c| c.iter())
            .filter(|x| x.is_subnormal())
            .count()
    };
    println!("steps   us/step  subnormal positions  subnormal velocities  largest |height|");
    for done in (batch..=total).step_by(batch) {
        let start = Instant::now();
        s.step_n(batch as u64).expect("stable");
        let per_step = start.elapsed().as_secs_f64() / batch as f64;
        let largest = s.positions()[1].iter().fold(0f32, |m, y| m.max(y.abs()));
        println!(
            "{done:>6} {:>8.1} {:>20} {:>21} {largest:>17e}",
            per_step * 1e6,
            subnormal(s.positions()),
            subnormal(s.velocities()),
        );
    }
}
