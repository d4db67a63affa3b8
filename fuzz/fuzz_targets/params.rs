//! Raw parameter values and CLI argument lists: an error or a valid surface, never a panic.
//!
//! The CLI's model-flag parser is compiled in from the binary's own source file, so the
//! fuzzer exercises exactly the code `springwater simulate` runs, without the library
//! having to export command-line types.

#![no_main]

#[allow(dead_code)]
#[path = "../../cli/src/args.rs"]
mod args;

use arbitrary::Arbitrary;
use libfuzzer_sys::fuzz_target;
use springwater::internals::Tuning;
use springwater::{Boundary, Params, Surface};

/// Largest surface the target builds (validation alone runs for any size).
const MAX_BUILD: usize = 1 << 12;

#[derive(Debug, Arbitrary)]
struct Input {
    cols: u32,
    rows: u32,
    spacing: f32,
    mass: f32,
    stiffness: f32,
    viscosity: f32,
    dt: f32,
    rest_ratio: f32,
    /// 0 pinned, 1 free, k ≥ 2 absorbing with a frame of k − 2 rings.
    boundary: u8,
    acceleration: [f32; 3],
    time_scale: f32,
    drop: [f32; 4],
    node: u32,
    value: f32,
    args: Vec<String>,
}

fuzz_target!(|input: Input| {
    let p = Params::with_size(input.cols as usize, input.rows as usize)
        .with_spacing(input.spacing)
        .with_mass(input.mass)
        .with_stiffness(input.stiffness)
        .with_viscosity(input.viscosity)
        .with_dt(input.dt)
        .with_rest_ratio(input.rest_ratio)
        .with_boundary(match input.boundary {
            0 => Boundary::Pinned,
            1 => Boundary::Free,
            k => Boundary::Absorbing {
                width: k as usize - 2,
            },
        })
        .with_acceleration(input.acceleration)
        .with_time_scale(input.time_scale);
    if p.validate().is_ok() && p.node_count() <= MAX_BUILD {
        let mut s = Surface::new(p).expect("validate() accepted these params");
        exercise(&mut s, &input);
    }

    // The same through the command line: every model flag, arbitrary values.
    let mut parser = lexopt::Parser::from_args(input.args.iter().map(String::as_str));
    let mut model = args::ModelArgs::default();
    loop {
        match args::next_flag(&mut parser) {
            Ok(Some(flag)) => match model.parse_flag(&flag, &mut parser) {
                Ok(true) => {}
                Ok(false) | Err(_) => return,
            },
            Ok(None) => break,
            Err(_) => return,
        }
    }
    if model.params.validate().is_ok() && model.params.node_count() <= MAX_BUILD {
        if let Ok(mut s) = model.surface() {
            exercise(&mut s, &input);
        }
    }
});

/// Every mutating entry point with the raw values: errors are fine, panics and non-finite
/// state are not.
fn exercise(s: &mut Surface, input: &Input) {
    let node = input.node as usize;
    let v = input.value;
    let [c, r, h, rad] = input.drop;
    let _ = s.drop_at(c, r, h, rad);
    let _ = s.add_force(node, [v, -v, v]);
    let _ = s.add_force_at(c, r, [v, -v, v]);
    let _ = s.add_velocity(node, [v; 3]);
    let _ = s.set_mass(node, v);
    let _ = s.set_viscosity(node, v);
    let _ = s.set_pinned(node, v > 0.0);
    let _ = s.set_acceleration(input.acceleration);
    let id = springwater::SpringId {
        family: springwater::Family::ALL[node % 4],
        origin: node / 4,
    };
    let _ = s.set_spring(
        id,
        springwater::Spring {
            rest: v,
            stiffness: input.spacing,
        },
    );
    let _ = s.advance(input.dt);
    let mut params = *s.params();
    let _ = params.set_ripple_speed(v);
    // Engine and scalar reference agree bitwise, failures included.
    let mut reference = s.clone();
    reference.set_simd_level(springwater::SimdLevel::Scalar);
    for _ in 0..4 {
        let engine = s.step();
        let scalar = reference.step();
        assert_eq!(engine, scalar);
        assert!(
            s.to_bytes() == reference.to_bytes(),
            "engine and reference differ"
        );
        if engine.is_err() {
            s.clear_forces();
            reference.clear_forces();
        }
    }
    // Several steps per pass: the same bits, and a failure at the same step.
    let _ = s.add_force(node, [v, v, -v]);
    let _ = reference.add_force(node, [v, v, -v]);
    s.set_pass_steps(input.node as usize % 8 + 1);
    let passes = s.step_n(6);
    let mut single = Ok(());
    for _ in 0..6 {
        single = reference.step();
        if single.is_err() {
            break;
        }
    }
    assert_eq!(passes, single);
    assert!(
        s.to_bytes() == reference.to_bytes(),
        "passes and reference differ"
    );
    let (qx, qz) = (input.drop[0], input.drop[1]);
    if let Ok(y) = s.height_at(qx, qz) {
        assert!(y.is_finite());
    }
    if let Ok(n) = s.normal_at(qx, qz) {
        assert!(n.is_finite());
    }
    if let Ok(v) = s.velocity_at(qx, qz) {
        assert!(v.is_finite());
    }
    for c in s.positions().iter().chain(&s.velocities()) {
        assert!(
            c.iter().all(|x| x.is_finite()),
            "non-finite state after errors-only calls"
        );
    }
}
