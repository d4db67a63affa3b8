//! Rigid bodies with arbitrary orientations (raw quaternions, unit or not, NaN included),
//! angular velocities, inertia tensors, pushes and torques, on every boundary (pinned,
//! free, absorbing): every call that changes a body is refused with the surface bitwise
//! unchanged (its snapshot bytes and state hash) or leaves a finite state; every step
//! succeeds with a finite state (the water, and the bodies with unit quaternions) or fails
//! and changes nothing, bitwise.
//!
//! Bodies are balls, boxes and hulls from a fifth of a cell to six cells across, a
//! twentieth to three times as dense as the water, near the surface of a pool of at most
//! 20 × 20 nodes at a share of the critical timestep with the bodies floating; the numbers
//! the fuzzer gives for motions and pushes are raw `f32` bits or sane values from 1e-8 to
//! 1e7 (see `common::Num`).

#![no_main]

mod common;

use arbitrary::Arbitrary;
use common::{check_finite, hulls, log_range, state, vec3, Inertia, Num, Orientation};
use libfuzzer_sys::fuzz_target;
use springwater::{Floater, FloaterId, Params, Surface};

#[derive(Debug, Arbitrary)]
struct Input {
    cols: u8,
    rows: u8,
    boundary: u8,
    /// Share of the critical timestep, 0.05 to 0.99.
    dt: u8,
    bodies: Vec<Body>,
    drops: Vec<(u8, u8, i8)>,
    ops: Vec<Op>,
}

#[derive(Debug, Arbitrary)]
struct Body {
    /// 0 ball, 1 box, else one of `common::hulls`.
    shape: u8,
    size: u8,
    density: u8,
    /// Across the pool and up to two units above or below the calm surface.
    position: [i8; 3],
    velocity: [Num; 3],
    orientation: Orientation,
    angular_velocity: [Num; 3],
    inertia: Inertia,
    drag: u8,
}

#[derive(Debug, Arbitrary)]
enum Op {
    Steps(u8),
    Push(u8, [Num; 3]),
    Torque(u8, [Num; 3]),
    PushAt(u8, [Num; 3], [Num; 3]),
    Turn(u8, Orientation),
    Spin(u8, [Num; 3]),
    Inertia(u8, Inertia),
    Move(u8, [Num; 3]),
}

fn body(b: &Body, cols: usize, rows: usize, density: f32) -> Floater {
    let size = log_range(b.size, 0.1, 3.0);
    let across = |v: i8, n: usize| (0.5 + 0.6 * v as f32 / 256.0) * (n - 1) as f32;
    let at = [
        across(b.position[0], cols),
        b.position[1] as f32 / 64.0,
        across(b.position[2], rows),
    ];
    let mut f = match b.shape % 3 {
        0 => Floater::sphere(size, 1.0, at),
        1 => Floater::cuboid([size, 0.6 * size, 0.8 * size], 1.0, at),
        _ => Floater::with_hull(hulls()[b.shape as usize % 3].clone(), 1.0, at),
    };
    f.mass = log_range(b.density, 0.05, 3.0) * density * f.shape.volume();
    f.drag = log_range(b.drag, 0.01, 1e3) - 0.01;
    f.velocity = vec3(b.velocity);
    f.orientation = b.orientation.get();
    f.angular_velocity = vec3(b.angular_velocity);
    b.inertia.apply(&mut f);
    f
}

/// Runs `call`: refused, the surface must be as it was; accepted, finite.
fn checked<T, E>(s: &mut Surface, call: impl FnOnce(&mut Surface) -> Result<T, E>) {
    let before = state(s);
    match call(s) {
        Ok(_) => check_finite(s),
        Err(_) => assert!(state(s) == before, "a refused call changed the surface"),
    }
}

fuzz_target!(|input: Input| {
    let (cols, rows) = (input.cols as usize % 15 + 6, input.rows as usize % 15 + 6);
    let base = Params::with_size(cols, rows)
        .with_boundary(common::boundary(input.boundary, cols, rows))
        .with_dt(0.2);
    let Ok(mut probe) = Surface::new(base) else {
        return;
    };
    let density = probe.buoyancy().density;
    let bodies: Vec<Floater> = input
        .bodies
        .iter()
        .take(5)
        .map(|b| body(b, cols, rows, density))
        .collect();
    // The timestep: a share of the critical one with the bodies floating.
    for f in &bodies {
        let _ = probe.add_floater(f.clone());
    }
    let share = 0.05 + 0.94 * input.dt as f32 / 255.0;
    let Ok(mut s) = Surface::new(base.with_dt(share * probe.critical_dt())) else {
        return;
    };
    for f in bodies {
        checked(&mut s, |s| s.add_floater(f));
    }
    for &(c, r, h) in input.drops.iter().take(4) {
        let (x, z) = ((c as usize % cols) as f32, (r as usize % rows) as f32);
        checked(&mut s, |s| s.drop_at(x, z, h as f32 / 128.0, 1.5));
    }
    check_finite(&s);
    let ids: Vec<FloaterId> = s.floaters().map(|(id, _)| id).collect();
    if ids.is_empty() {
        return;
    }
    let id = |k: u8| ids[k as usize % ids.len()];
    // Replaces one field of a body through `set_floater`, which validates the whole.
    let set = |s: &mut Surface, k: u8, change: &dyn Fn(&mut Floater)| {
        let mut f = s.floater(id(k)).expect("a live body").clone();
        change(&mut f);
        checked(s, |s| s.set_floater(id(k), f));
    };
    let mut steps = 0;
    for op in input.ops.iter().take(48) {
        match op {
            Op::Steps(n) => {
                for _ in 0..n % 4 + 1 {
                    steps += 1;
                    if steps > 48 {
                        return;
                    }
                    let before = state(&s);
                    match s.step() {
                        Ok(()) => check_finite(&s),
                        Err(_) => {
                            assert!(state(&s) == before, "a failed step changed the surface")
                        }
                    }
                }
            }
            Op::Push(k, f) => checked(&mut s, |s| s.push_floater(id(*k), vec3(*f))),
            Op::Torque(k, t) => checked(&mut s, |s| s.push_floater_torque(id(*k), vec3(*t))),
            Op::PushAt(k, f, at) => {
                checked(&mut s, |s| s.push_floater_at(id(*k), vec3(*f), vec3(*at)))
            }
            Op::Turn(k, q) => set(&mut s, *k, &|f| f.orientation = q.get()),
            Op::Spin(k, w) => set(&mut s, *k, &|f| f.angular_velocity = vec3(*w)),
            Op::Inertia(k, i) => set(&mut s, *k, &|f| i.apply(f)),
            Op::Move(k, v) => set(&mut s, *k, &|f| f.velocity = vec3(*v)),
        }
    }
});
