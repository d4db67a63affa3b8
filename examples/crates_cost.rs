//! What floating crates cost: a 512² pool with a drop and a mix of bodies laid out on a
//! grid, stepped `steps` times at one SIMD level on one thread. Run it under
//! `valgrind --tool=cachegrind --cache-sim=no` for two step counts and take the
//! difference: instructions per step, whatever the machine's load.
//!
//! `cargo run --release --example crates_cost -- MIX STEPS [LEVEL]`, MIX one of
//! `none`, `game` (500 balls of radius 1 and 500 cubes of side 2, half the water's
//! density), `game100` (50 and 50 of them), `smallest` (1,000 balls of radius 0.5), or
//! `single` (no bodies, one step per engine pass, as the water steps beside bodies),
//! `forces` (no bodies, a force at each of the 1,000 places before every step);
//! LEVEL a SIMD level's name (default avx2, the widest valgrind runs).

use springwater::glam::{Quat, Vec3};
use springwater::{Floater, Params, SimdLevel, Surface};

fn main() {
    let args: Vec<String> = std::env::args().collect();
    let mix = args.get(1).map_or("game", String::as_str);
    let steps: u64 = args.get(2).and_then(|s| s.parse().ok()).unwrap_or(10);
    let level = args.get(3).map_or("avx2", String::as_str);
    let level = SimdLevel::ALL
        .into_iter()
        .find(|l| l.to_string() == level)
        .expect("a SIMD level's name");
    let n = 512;
    let mut s = Surface::new(Params::with_size(n, n)).expect("valid size");
    s.set_simd_level(level);
    s.drop_at(256.0, 256.0, 1.0, 8.0).expect("inside");
    let (count, body): (usize, fn(usize, Vec3) -> Floater) = match mix {
        "none" | "single" | "forces" => (0, |_, at| Floater::sphere(1.0, 1.0, at)),
        "game" | "game100" => (if mix == "game" { 1000 } else { 100 }, |k, at| {
            if k % 2 == 0 {
                Floater::sphere(1.0, 1.0, at)
            } else {
                Floater::cuboid([1.0, 1.0, 1.0], 1.0, at)
            }
        }),
        "smallest" => (1000, |_, at| Floater::sphere(0.5, 1.0, at)),
        other => panic!("unknown mix {other}"),
    };
    let per_row = 32;
    for k in 0..count {
        let at = Vec3::new(
            8.0 + (k % per_row) as f32 * 15.5,
            0.0,
            8.0 + (k / per_row) as f32 * 15.5,
        );
        let mut b = body(k, at);
        b.mass = 0.5 * s.buoyancy().density * b.shape.volume();
        b.orientation = Quat::from_rotation_x(0.1 * (k % 5) as f32);
        s.add_floater(b).expect("fits");
    }
    let pool = rayon::ThreadPoolBuilder::new()
        .num_threads(1)
        .build()
        .unwrap();
    if mix == "forces" {
        pool.install(|| {
            for _ in 0..steps {
                for k in 0..1000 {
                    let (x, z) = (
                        8.3 + (k % per_row) as f32 * 15.5,
                        8.3 + (k / per_row) as f32 * 15.5,
                    );
                    s.add_force_at(x, z, [0.0, -0.01, 0.0]).expect("inside");
                }
                s.step().expect("stable");
            }
        });
    } else {
        pool.install(|| s.step_n(steps).expect("stable"));
    }
    println!("{mix}: {count} bodies, {steps} steps, {}", s.simd_level());
}
