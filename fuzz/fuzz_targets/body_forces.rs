//! `Surface::body_forces` for bodies another engine owns, with arbitrary shapes, masses,
//! inertias, poses, velocities and ticks, on still or disturbed water with or without the
//! surface's own bodies: refused with the surface bitwise unchanged (its snapshot bytes and
//! state hash), or a finite force and torque whose reaction waits in the water column, equal
//! and opposite.
//!
//! # What "equal and opposite" is, checked
//!
//! The reaction does not enter the water at once: it is added to the column's pending
//! load at the nodes under the body (`internals::Tuning::water_column`) and the next step
//! takes it (`src/surface/bodies/column.rs`). The lattice's forces are per unit of model
//! time², and the tick's impulse goes into one step of `dt / time_scale` seconds, so the
//! pending loads grow by `−F · factor / time_scale²` in all, with
//! `factor = seconds / (dt / time_scale)`. Checked while every wet part can reach the
//! water (the body's bounding sphere over the grid; a part over no node pushes nothing):
//!
//! * force: `Σ Δpending · time_scale² / factor = −F`;
//! * the torque about the vertical through the centre of mass: each part's reaction is
//!   spread on its cell's four nodes with bilinear weights, which keep its `x` and `z`
//!   (`Σ w·x_node = x`), so with the nodes at their rest `x, z` the water's moment about
//!   that vertical is `−τ_y`. (The other two components need the height each part acts
//!   at, which the spread drops.)
//!
//! Both hold to the rounding of `f32` sums of terms as large as the pressure on the whole
//! hull (`ρ g depth · area`, which cancels to the buoyancy), the drag and what the
//! column already waited for: the tolerance is 1e-5 of those, plus a few of the smallest
//! subnormal `f32` per node for ticks so short that the loads are subnormal.
//!
//! A call that succeeds leaves the carried loads alone; the next step either succeeds
//! (finite) or fails with nothing changed.

#![no_main]

mod common;

use arbitrary::Arbitrary;
use common::{check_finite, hulls, log_range, state, vec3, Inertia, Num, Orientation};
use glam::{DVec3, Vec3};
use libfuzzer_sys::fuzz_target;
use springwater::internals::Tuning;
use springwater::{Floater, Params, Shape, Surface};

#[derive(Debug, Arbitrary)]
struct Input {
    cols: u8,
    rows: u8,
    boundary: u8,
    drops: Vec<(u8, u8, i8)>,
    /// The surface's own bodies (balls) and the steps taken before the calls.
    own: Vec<(u8, u8)>,
    warm: u8,
    calls: Vec<Call>,
}

#[derive(Debug, Arbitrary)]
struct Call {
    /// 0 ball, 1 box, else one of `common::hulls` (scaled by `size` when a box or ball).
    shape: u8,
    size: Size,
    mass: Mass,
    position: Position,
    velocity: [Num; 3],
    orientation: Orientation,
    angular_velocity: [Num; 3],
    inertia: Inertia,
    drag: Num,
    seconds: Tick,
    /// Pushes and read-only fields, which `body_forces` ignores.
    ignored: Option<[f32; 12]>,
    /// Step the surface after this call.
    step: bool,
}

#[derive(Debug, Arbitrary)]
enum Size {
    Cells(u8),
    Raw(f32),
}

#[derive(Debug, Arbitrary)]
enum Mass {
    /// A share (0.05 to 3) of the mass of the water its volume displaces.
    Density(u8),
    Raw(Num),
}

#[derive(Debug, Arbitrary)]
enum Position {
    /// Over the pool (or off its edge), up to four units above or below the calm surface.
    Near([i8; 3]),
    Raw([Num; 3]),
}

#[derive(Debug, Arbitrary)]
enum Tick {
    /// 1/240 s to 1 s.
    Sane(u8),
    Raw(f32),
}

fn body(c: &Call, cols: usize, rows: usize, density: f32) -> Floater {
    let size = match c.size {
        Size::Cells(b) => log_range(b, 0.02, 40.0),
        Size::Raw(v) => v,
    };
    let at = match c.position {
        Position::Near(p) => {
            let across = |v: i8, n: usize| (0.5 + v as f32 / 160.0) * (n - 1) as f32;
            Vec3::new(across(p[0], cols), p[1] as f32 / 32.0, across(p[2], rows))
        }
        Position::Raw(p) => vec3(p),
    };
    let mut f = match c.shape % 3 {
        0 => Floater::sphere(size, 1.0, at),
        1 => Floater::cuboid([size, 0.5 * size, 0.75 * size], 1.0, at),
        _ => Floater::with_hull(hulls()[c.shape as usize % 3].clone(), 1.0, at),
    };
    f.mass = match c.mass {
        Mass::Density(b) => log_range(b, 0.05, 3.0) * density * f.shape.volume(),
        Mass::Raw(m) => m.get(),
    };
    f.drag = c.drag.get();
    f.velocity = vec3(c.velocity);
    f.orientation = c.orientation.get();
    f.angular_velocity = vec3(c.angular_velocity);
    c.inertia.apply(&mut f);
    f
}

/// Area of the shape's surface (an upper bound on what the water presses on).
fn area(shape: &Shape) -> f64 {
    match shape {
        Shape::Sphere { radius } => 4.0 * std::f64::consts::PI * (*radius as f64).powi(2),
        Shape::Box { half_extents: e } => {
            let e = e.as_dvec3();
            8.0 * (e.x * e.y + e.y * e.z + e.z * e.x)
        }
        Shape::Hull(h) => {
            let v = |i: u32| DVec3::from(h.vertices()[i as usize].map(f64::from));
            let twice: f64 = h
                .triangles()
                .iter()
                .map(|&[a, b, c]| (v(b) - v(a)).cross(v(c) - v(a)).length())
                .sum();
            twice / 2.0
        }
        _ => f64::INFINITY,
    }
}

/// The pending loads per node.
fn pending(s: &Surface) -> Vec<(usize, [f32; 3], [f32; 3])> {
    s.water_column()
}

fn check_reaction(
    s: &Surface,
    before: &[(usize, [f32; 3], [f32; 3])],
    f: &Floater,
    seconds: f32,
    force: Vec3,
    torque: Vec3,
) {
    let after = pending(s);
    let at = |list: &[(usize, [f32; 3], [f32; 3])], node: usize| {
        list.binary_search_by_key(&node, |e| e.0)
            .map_or(([0.0; 3], [0.0; 3]), |k| (list[k].1, list[k].2))
    };
    // What the column carries is not the call's business.
    for &(node, carried, _) in &after {
        assert_eq!(
            carried,
            at(before, node).0,
            "body_forces changed a carried load"
        );
    }
    for &(node, ..) in before {
        assert!(
            after.binary_search_by_key(&node, |e| e.0).is_ok(),
            "lost {node}"
        );
    }
    let p = s.params();
    let ts2 = (p.time_scale as f64).powi(2);
    let factor = seconds as f64 / (p.dt as f64 / p.time_scale as f64);
    let to_body = ts2 / factor;
    let (cols, h) = (p.cols, p.spacing as f64);
    let c = f.position.as_dvec3();
    let (mut sum, mut moment, mut size) = (DVec3::ZERO, 0.0f64, 0.0f64);
    for &(node, _, now) in &after {
        let was = at(before, node).1;
        let d = DVec3::from(std::array::from_fn(|k| now[k] as f64 - was[k] as f64)) * to_body;
        sum += d;
        let (x, z) = ((node % cols) as f64 * h, (node / cols) as f64 * h);
        moment += (z - c.z) * d.x - (x - c.x) * d.z;
        let held =
            DVec3::from(now.map(f64::from)).length() + DVec3::from(was.map(f64::from)).length();
        size += held * to_body;
    }
    // The largest terms that cancel: the pressure on the whole hull at the depth of its
    // lowest point below the highest water, and the drag at the fastest point.
    let b = s.buoyancy();
    let r = f.shape.bounding_radius() as f64;
    let top = s.positions()[1].iter().fold(0.0f32, |a, &y| a.max(y.abs())) as f64;
    let depth = (f.position.y as f64).abs() + r + top;
    let speed = f.velocity.length() as f64 + f.angular_velocity.length() as f64 * r;
    let displaced = b.density as f64 * f.shape.volume() as f64;
    let scale = force.length() as f64
        + size
        + b.density as f64 * area(&f.shape) * b.gravity as f64 * depth
        + f.drag as f64 * displaced * speed;
    // A tick so short that the shares are subnormal in f32 (seconds of 1e-40 give loads
    // of 1e-41) keeps only their few bits: up to a few of the smallest subnormals per
    // node and component, in the body's units.
    let grain = after.len() as f64 * 8.0 * f32::from_bits(1) as f64 * to_body;
    let err = (sum + force.as_dvec3()).length();
    assert!(
        err <= 1e-5 * scale + grain,
        "the water waits for {sum}, the body gets {force}: off by {err:e} (scale {scale:e})"
    );
    let arm = r + 2.0 * h;
    let err = (moment + torque.y as f64).abs();
    assert!(
        err <= (1e-5 * scale + grain) * arm + 1e-5 * torque.length() as f64,
        "the water's moment about the vertical {moment}, the body's {}: off by {err:e}",
        torque.y
    );
}

fuzz_target!(|input: Input| {
    let (cols, rows) = (input.cols as usize % 19 + 6, input.rows as usize % 19 + 6);
    let p = Params::with_size(cols, rows)
        .with_boundary(common::boundary(input.boundary, cols, rows))
        .with_dt(0.2);
    let Ok(mut s) = Surface::new(p) else {
        return;
    };
    let density = s.buoyancy().density;
    for &(c, r, hgt) in input.drops.iter().take(3) {
        let (x, z) = ((c as usize % cols) as f32, (r as usize % rows) as f32);
        let _ = s.drop_at(x, z, hgt as f32 / 128.0, 1.5);
    }
    for &(c, r) in input.own.iter().take(2) {
        let (x, z) = ((c as usize % cols) as f32, (r as usize % rows) as f32);
        let _ = s.add_floater(Floater::sphere(0.6, 0.5 * density * 0.905, [x, 0.3, z]));
    }
    for _ in 0..input.warm % 4 {
        if s.step().is_err() {
            return;
        }
    }
    check_finite(&s);
    for call in input.calls.iter().take(6) {
        let f = body(call, cols, rows, density);
        let seconds = match call.seconds {
            Tick::Sane(b) => log_range(b, 1.0 / 240.0, 1.0),
            Tick::Raw(v) => v,
        };
        let before = state(&s);
        let column = pending(&s);
        let out = match call.ignored {
            None => s.body_forces(&f, seconds),
            Some(v) => {
                // The same call with the pushes and the read-only fields set to anything:
                // the same answer and the same surface as without them, but that pushes
                // must still be finite (`Floater::validate`; tests/rigid_bodies.rs
                // expects a NaN push torque refused).
                let mut clean = s.clone();
                let expected = clean.body_forces(&f, seconds);
                let junk = |k: usize| Vec3::new(v[k], v[k + 1], v[k + 2]);
                let mut g = f.clone();
                g.push = junk(0);
                g.push_torque = junk(3);
                g.water_force = junk(6);
                g.water_torque = junk(9);
                let out = s.body_forces(&g, seconds);
                if g.push.is_finite() && g.push_torque.is_finite() {
                    assert_eq!(
                        out.as_ref().ok(),
                        expected.as_ref().ok(),
                        "pushes and read-only fields changed body_forces"
                    );
                    assert!(state(&s) == state(&clean));
                } else {
                    assert!(out.is_err(), "a non-finite push was taken");
                }
                out
            }
        };
        match out {
            Err(_) => assert!(state(&s) == before, "a refused call changed the surface"),
            Ok(push) => {
                assert!(
                    push.force.is_finite() && push.torque.is_finite(),
                    "{push:?}"
                );
                check_finite(&s);
                // Checked while the whole body is over the grid (see the module docs).
                let r = f.shape.bounding_radius();
                let inside = |v: f32, n: usize| v - r >= 0.0 && v + r <= (n - 1) as f32;
                if inside(f.position.x, cols) && inside(f.position.z, rows) {
                    check_reaction(&s, &column, &f, seconds, push.force, push.torque);
                }
            }
        }
        if call.step {
            let before = state(&s);
            match s.step() {
                Ok(()) => check_finite(&s),
                Err(_) => assert!(state(&s) == before, "a failed step changed the surface"),
            }
        }
    }
});
