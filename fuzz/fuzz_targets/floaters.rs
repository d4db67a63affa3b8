//! Floating bodies of any size, mass, drag and speed, on any boundary, in any buoyancy,
//! at timesteps up to 0.99 × the critical one: adding a body either is refused or keeps
//! the state finite, and every step either succeeds with a finite state (water and
//! bodies) or fails and leaves the surface bitwise unchanged. The engine and the scalar
//! reference agree bitwise, failures included.

#![no_main]

use arbitrary::Arbitrary;
use libfuzzer_sys::fuzz_target;
use springwater::{Boundary, Buoyancy, Floater, Params, SimdLevel, Surface};

#[derive(Debug, Arbitrary)]
struct Input {
    cols: u8,
    rows: u8,
    /// 0 pinned, 1 free, else absorbing with a frame of up to a quarter of the grid.
    boundary: u8,
    /// Share of the critical timestep, 0.05 to 0.99.
    dt: u8,
    gravity: u8,
    density: u8,
    bodies: Vec<Body>,
    drops: Vec<(u8, u8, i8)>,
    pushes: Vec<(u8, [i8; 3])>,
    steps: u8,
}

#[derive(Debug, Arbitrary)]
struct Body {
    boxy: bool,
    size: [u8; 3],
    mass: u8,
    drag: u8,
    position: [i16; 3],
    velocity: [i8; 3],
    speed: u8,
}

/// `lo · (hi/lo)^(b/255)`.
fn log_range(b: u8, lo: f32, hi: f32) -> f32 {
    lo * (hi / lo).powf(b as f32 / 255.0)
}

fn finite(s: &Surface) -> bool {
    let water = s
        .positions()
        .iter()
        .chain(&s.velocities())
        .all(|a| a.iter().all(|v| v.is_finite()));
    let bodies = s.floaters().all(|(_, f)| {
        f.position.is_finite() && f.velocity.is_finite() && f.water_force.is_finite()
    });
    water && bodies
}

fuzz_target!(|input: Input| {
    let (cols, rows) = (input.cols as usize % 48 + 2, input.rows as usize % 48 + 2);
    let boundary = match input.boundary {
        0 => Boundary::Pinned,
        1 => Boundary::Free,
        k => Boundary::Absorbing {
            width: (k as usize % 16 + 1)
                .min((cols.min(rows).saturating_sub(2)) / 2)
                .max(1),
        },
    };
    let base = Params::with_size(cols, rows).with_boundary(boundary);
    if base.validate().is_err() {
        return;
    }
    let mut s = Surface::new(base).unwrap();
    // Gravity, drag and speeds per second: the ranges are 1e-4 to 1e4 per unit of model
    // time², 1e-3 to 1e6 and 1e-3 to 1e9 per unit of model time at the default time scale.
    let buoyancy = Buoyancy {
        gravity: log_range(input.gravity, 0.0576, 5.76e6),
        density: log_range(input.density, 1e-4, 1e4),
    };
    let _ = s.set_buoyancy(buoyancy);
    let bodies: Vec<Floater> = input
        .bodies
        .iter()
        .take(24)
        .map(|b| {
            let size = b.size.map(|v| log_range(v, 1e-3, 1e9));
            let at = b.position.map(|v| v as f32 * 0.01);
            let mut f = if b.boxy {
                Floater::cuboid(size, 1.0, at)
            } else {
                Floater::sphere(size[0], 1.0, at)
            };
            f.mass = log_range(b.mass, 1e-37, 1e37);
            f.drag = log_range(b.drag, 0.024, 2.4e7) - 0.024;
            let speed = log_range(b.speed, 0.024, 2.4e10);
            f.velocity = glam::Vec3::from_array(b.velocity.map(|v| v as f32 / 128.0 * speed));
            f
        })
        .collect();
    // The timestep: a share of the critical one with the bodies floating.
    for f in &bodies {
        let _ = s.add_floater(f.clone());
    }
    let share = 0.05 + 0.94 * input.dt as f32 / 255.0;
    let p = base.with_dt(share * s.critical_dt());
    let Ok(mut s) = Surface::new(p) else {
        return;
    };
    let _ = s.set_buoyancy(buoyancy);
    for f in bodies {
        let before = s.to_bytes();
        if s.add_floater(f).is_err() {
            assert!(s.to_bytes() == before, "a refused body changed the surface");
        }
    }
    for &(c, r, h) in input.drops.iter().take(8) {
        let _ = s.drop_at(
            c as f32 % cols as f32,
            r as f32 % rows as f32,
            h as f32 / 64.0,
            2.0,
        );
    }
    assert!(finite(&s));
    let mut reference = s.clone();
    reference.set_simd_level(SimdLevel::Scalar);
    let ids: Vec<_> = s.floaters().map(|(id, _)| id).collect();
    for step in 0..input.steps as usize % 64 {
        if let Some(&(k, f)) = input.pushes.get(step) {
            if let Some(&id) = ids.get(k as usize % ids.len().max(1)) {
                let force = f.map(|v| v as f32 * 10.0);
                let _ = s.push_floater(id, force);
                let _ = reference.push_floater(id, force);
            }
        }
        let before = s.to_bytes();
        let engine = s.step();
        let scalar = reference.step();
        assert_eq!(engine, scalar);
        assert!(
            s.to_bytes() == reference.to_bytes(),
            "engine and reference differ"
        );
        match engine {
            Ok(()) => assert!(finite(&s), "a successful step left a non-finite state"),
            Err(_) => {
                assert!(s.to_bytes() == before, "a failed step changed the surface");
                break;
            }
        }
    }
});
