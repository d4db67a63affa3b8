//! A long run for `scripts/soak.sh`: open water in the rain, a window that follows a point
//! moving across the world, and 200 floating bodies, for a fixed number of steps.
//!
//! `cargo run --release --example soak -- STEPS [REPORT_EVERY]` (REPORT_EVERY 1000)
//!
//! Every `REPORT_EVERY` steps it checks that the water and every body are finite and
//! prints `step N hash H origin X Z seconds S`; at the end `final step N hash H`. A step
//! that fails (a non-finite state) ends the run with exit code 1. Everything is
//! deterministic (the rain from its seed, the bodies from a fixed sequence, the path as a
//! function of the step), so two runs of the same step count end with the same hash.
//!
//! The window is 160 × 160 cells with an absorbing frame. The point it follows moves along
//! +x at 6 cells a second and sways ±24 cells along z (a triangle wave); the window follows
//! it by whole cells. A body the window leaves behind (within 6 cells of its trailing edge
//! or outside it) is put back, at rest and upright, the same distance from the leading
//! edge, so the 200 bodies stay in the water the whole run.

use springwater::body::Hull;
use springwater::disturb::{Disturbance, Rain};
use springwater::glam::{Quat, Vec3};
use springwater::{Boundary, Floater, FloaterId, Params, Surface};
use std::sync::Arc;
use std::time::Instant;

const SIZE: usize = 160;
const BODIES: usize = 200;

/// A small fixed sequence of numbers in `[0, 1)` (a 64-bit LCG's high bits): the bodies'
/// sizes and places.
struct Sequence(u64);

impl Sequence {
    fn next(&mut self) -> f32 {
        self.0 = self
            .0
            .wrapping_mul(6364136223846793005)
            .wrapping_add(1442695040888963407);
        (self.0 >> 40) as f32 / (1u64 << 24) as f32
    }
}

/// The point the window follows at step `n`, world units: 6 cells a second along x, a
/// triangle wave of ±24 cells along z with a period of 40 s.
fn path(n: u64, seconds_per_step: f64) -> [f32; 2] {
    let t = n as f64 * seconds_per_step;
    let centre = (SIZE - 1) as f64 / 2.0;
    let phase = (t / 40.0).fract();
    let sway = 24.0 * (4.0 * (phase - 0.5).abs() - 1.0);
    [(centre + 6.0 * t) as f32, (centre + sway) as f32]
}

fn check_finite(s: &Surface) -> Result<(), String> {
    for c in s.positions().iter().chain(&s.velocities()) {
        if !c.iter().all(|v| v.is_finite()) {
            return Err("the water is not finite".into());
        }
    }
    for (id, f) in s.floaters() {
        let all = [f.position, f.velocity, f.angular_velocity, f.water_force];
        if !all.iter().all(|v| v.is_finite()) || !f.orientation.is_finite() {
            return Err(format!("body {id:?} is not finite: {f:?}"));
        }
    }
    Ok(())
}

fn main() {
    let arg = |i: usize, default: u64| {
        std::env::args()
            .nth(i)
            .map(|a| a.parse().expect("a whole number"))
            .unwrap_or(default)
    };
    let (steps, every) = (arg(1, 10_000), arg(2, 1000).max(1));
    if let Err(e) = run(steps, every) {
        eprintln!("soak: {e}");
        std::process::exit(1);
    }
}

fn run(steps: u64, every: u64) -> Result<(), String> {
    let p = Params::with_size(SIZE, SIZE)
        .with_boundary(Boundary::Absorbing { width: 12 })
        .with_dt(0.3);
    let mut s = Surface::new(p).map_err(|e| e.to_string())?;
    let density = s.buoyancy().density;
    let hull = Arc::new(Hull::cuboid([1.2, 0.4, 0.6]).map_err(|e| e.to_string())?);
    let mut seq = Sequence(46);
    for k in 0..BODIES {
        let at = [
            8.0 + seq.next() * (SIZE - 16) as f32,
            0.0,
            8.0 + seq.next() * (SIZE - 16) as f32,
        ];
        let size = 0.5 + seq.next();
        let mut body = match k % 3 {
            0 => Floater::sphere(size, 1.0, at),
            1 => Floater::cuboid([size, 0.5 * size, 0.8 * size], 1.0, at),
            _ => Floater::with_hull(Arc::clone(&hull), 1.0, at),
        };
        body.mass = (0.3 + 0.5 * seq.next()) * density * body.shape.volume();
        body.orientation = Quat::from_rotation_y(seq.next() * 6.0);
        s.add_floater(body).map_err(|e| e.to_string())?;
    }
    let ids: Vec<FloaterId> = s.floaters().map(|(id, _)| id).collect();
    let mut rain = Rain::new(30.0, 46);
    let seconds = p.dt / p.time_scale;
    let start = Instant::now();
    for n in 1..=steps {
        rain.apply(&mut s, seconds).map_err(|e| e.to_string())?;
        s.step().map_err(|e| format!("step {n} failed: {e}"))?;
        if n % 8 == 0 {
            let [x, z] = path(n, seconds as f64);
            s.follow(x, z).map_err(|e| e.to_string())?;
            bring_back(&mut s, &ids)?;
        }
        if n % every == 0 || n == steps {
            check_finite(&s).map_err(|e| format!("step {n}: {e}"))?;
            let [ox, oz] = s.origin();
            println!(
                "step {n} hash {:016x} origin {ox} {oz} seconds {:.0}",
                s.state_hash(),
                start.elapsed().as_secs_f64()
            );
        }
    }
    println!("final step {steps} hash {:016x}", s.state_hash());
    Ok(())
}

/// Bodies the window has left behind, or is about to (within `margin` cells of an edge or
/// past it), come back at rest inside it: at the leading edge along x, at the other side
/// along z.
fn bring_back(s: &mut Surface, ids: &[FloaterId]) -> Result<(), String> {
    let [ox, oz] = s.origin();
    let far = (SIZE - 1) as f32;
    let margin = 6.0;
    for &id in ids {
        let mut f = s.floater(id).map_err(|e| e.to_string())?.clone();
        let (x, z) = (f.position.x - ox, f.position.z - oz);
        let back_x = (x < margin).then_some(far - 2.0 * margin);
        let back_z = if z < margin {
            Some(far - 2.0 * margin)
        } else {
            (z > far - margin).then_some(2.0 * margin)
        };
        if back_x.is_none() && back_z.is_none() {
            continue;
        }
        f.position = Vec3::new(ox + back_x.unwrap_or(x), 0.0, oz + back_z.unwrap_or(z));
        f.velocity = Vec3::ZERO;
        f.angular_velocity = Vec3::ZERO;
        f.orientation = Quat::IDENTITY;
        s.set_floater(id, f).map_err(|e| e.to_string())?;
    }
    Ok(())
}
