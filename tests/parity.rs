//! The engine against the scalar reference.
//!
//! Tolerance: **zero**. Both steps evaluate the same expression per spring and per node
//! (see `forces::scalar::node_force`) without FMA, so they must agree bit for bit for
//! every grid size, parameter set, pinned mask, drop, force and band height.

mod common;

use common::{state_bits, Rng};
use proptest::prelude::*;
use springwater::internals::Tuning;
use springwater::{Boundary, Family, Params, SimdLevel, SpringId, Surface};

#[derive(Debug, Clone)]
struct Case {
    params: Params,
    drops: Vec<(f32, f32, f32, f32)>,
    pins: Vec<(usize, bool)>,
    /// Springs given their own rest length and coefficient (switching their family from
    /// the shared summary to the per-spring tables in the engine).
    edits: Vec<(Family, usize, f32, f32)>,
    force_seed: Option<u32>,
    band_rows: usize,
}

fn case() -> impl Strategy<Value = Case> {
    (
        2usize..70,
        2usize..50,
        (
            1.0f32..8.0,
            1.0f32..12.0,
            0.0f32..0.3,
            0.0f32..=1.0,
            0.5f32..2.0,
        ),
        any::<bool>(),
        0.05f32..0.99,
        prop::collection::vec((0.0f32..1.0, 0.0f32..1.0, -1.0f32..1.0, 1.0f32..4.0), 0..4),
        prop::collection::vec((any::<prop::sample::Index>(), any::<bool>()), 0..8),
        prop::option::of(any::<u32>()),
        1usize..20,
        prop::collection::vec(
            (
                0usize..4,
                any::<prop::sample::Index>(),
                0.0f32..1.5,
                0.2f32..1.0,
            ),
            0..6,
        ),
    )
        .prop_map(
            |(
                cols,
                rows,
                (mass, stiffness, viscosity, rest_ratio, spacing),
                free,
                dt_frac,
                drops,
                pins,
                force_seed,
                band_rows,
                edits,
            )| {
                let mut params = Params::with_size(cols, rows)
                    .with_mass(mass)
                    .with_stiffness(stiffness)
                    .with_viscosity(viscosity)
                    .with_rest_ratio(rest_ratio)
                    .with_spacing(spacing)
                    .with_boundary(if free {
                        Boundary::Free
                    } else {
                        Boundary::Pinned
                    });
                params.dt = params.critical_dt() * dt_frac;
                let drops = drops
                    .into_iter()
                    .map(|(c, r, h, rad)| (c * cols as f32, r * rows as f32, h * rad, rad))
                    .collect();
                let pins = pins
                    .into_iter()
                    .map(|(i, p)| (i.index(cols * rows), p))
                    .collect();
                // Coefficients at most the global one keep dt below the critical timestep.
                let edits = edits
                    .into_iter()
                    .map(|(f, i, rest, c)| {
                        let origin = i.index(cols * rows);
                        (Family::ALL[f], origin, rest * spacing, c * stiffness)
                    })
                    .collect();
                Case {
                    params,
                    drops,
                    pins,
                    edits,
                    force_seed: force_seed.map(|s| s | 1),
                    band_rows,
                }
            },
        )
}

fn build(case: &Case) -> Surface {
    let mut s = common::new_surface(case.params).expect("valid by construction");
    s.set_band_rows(case.band_rows);
    for &(c, r, h, rad) in &case.drops {
        s.drop_at(c, r, h, rad).unwrap();
    }
    for &(i, p) in &case.pins {
        s.set_pinned(i, p).unwrap();
    }
    for &(family, origin, rest, coef) in &case.edits {
        // Springs that do not exist (E from the last column, …) are refused: skip them.
        let _ = s.set_spring(
            SpringId { family, origin },
            springwater::Spring {
                rest,
                stiffness: coef,
            },
        );
    }
    s
}

/// External forces from `seed`: on every node for half the seeds, on three nodes for the
/// other half (the engine then reads the force buffers only on their rows).
fn add_forces(s: &mut Surface, seed: Option<u32>) {
    if let Some(seed) = seed {
        let mut rng = Rng(seed);
        let n = s.node_count();
        if seed & 2 == 0 {
            let f: Vec<Vec<f32>> = (0..3)
                .map(|_| (0..n).map(|_| rng.next()).collect())
                .collect();
            s.set_forces([&f[0], &f[1], &f[2]]).unwrap();
        } else {
            for _ in 0..3 {
                let node = ((rng.next() + 0.5) * n as f32) as usize % n;
                let f = [rng.next(), rng.next(), rng.next()];
                s.add_force(node, f).unwrap();
            }
        }
    }
}

proptest! {
    #![proptest_config(ProptestConfig { cases: 96, ..ProptestConfig::default() })]

    #[test]
    fn engine_matches_reference_bitwise(case in case()) {
        let mut engine = build(&case);
        let mut reference = engine.clone();
        reference.set_simd_level(SimdLevel::Scalar);
        for step in 0..40 {
            if step % 10 == 0 {
                add_forces(&mut engine, case.force_seed);
                add_forces(&mut reference, case.force_seed);
            }
            let a = engine.step();
            let b = reference.step();
            prop_assert_eq!(&a, &b);
            prop_assert!(state_bits(&engine) == state_bits(&reference), "states differ after step {}", step);
            if a.is_err() {
                break;
            }
        }
    }
}

proptest! {
    #![proptest_config(ProptestConfig { cases: 64, ..ProptestConfig::default() })]

    /// Several steps per pass: every level of the wavefront, the rows handed from colour 0
    /// to colour 1 and the forces applied in a pass's first step only.
    #[test]
    fn passes_of_several_steps_match_the_reference_bitwise(
        case in case(),
        pass_steps in 1usize..=8,
        chunks in prop::collection::vec(1u64..20, 1..4),
    ) {
        let mut engine = build(&case);
        engine.set_pass_steps(pass_steps);
        let mut reference = engine.clone();
        reference.set_simd_level(SimdLevel::Scalar);
        for n in chunks {
            add_forces(&mut engine, case.force_seed);
            add_forces(&mut reference, case.force_seed);
            let a = engine.step_n(n);
            let mut b = Ok(());
            for _ in 0..n {
                b = reference.step();
                if b.is_err() {
                    break;
                }
            }
            prop_assert_eq!(&a, &b);
            prop_assert_eq!(engine.steps(), reference.steps());
            prop_assert!(state_bits(&engine) == state_bits(&reference), "states differ after {} steps", engine.steps());
            if a.is_err() {
                break;
            }
        }
    }
}

#[test]
fn band_height_does_not_change_a_bit() {
    let mut params = Params::with_size(47, 61);
    params.viscosity = 0.0;
    let runs: Vec<Vec<u32>> = [1, 2, 3, 8, 61, 100]
        .into_iter()
        .map(|h| {
            let mut s = common::new_surface(params).unwrap();
            s.set_band_rows(h);
            s.drop_at(20.0, 30.0, 1.5, 2.0).unwrap();
            for _ in 0..100 {
                s.step().unwrap();
            }
            state_bits(&s)
        })
        .collect();
    assert!(runs.windows(2).all(|w| w[0] == w[1]));
}

/// A pass whose later step blows up: the steps before it stay applied, the error names
/// the same step and node as single steps do, and the state is the same bits.
#[test]
fn a_failing_pass_stops_at_the_same_step_as_single_steps() {
    let mut p = Params::with_size(24, 40);
    p.viscosity = 0.0;
    p.dt = p.linear_dt_limit() * 1.05;
    let mut single = Surface::new_without_dt_check(p).unwrap();
    single.set_simd_level(springwater::SimdLevel::from_env().unwrap());
    let mut rng = Rng(7);
    for i in 0..single.node_count() {
        single
            .add_velocity(i, [rng.next() * 1e-3, rng.next() * 1e-3, rng.next() * 1e-3])
            .unwrap();
    }
    let mut passes = single.clone();
    passes.set_pass_steps(8);
    let err_single = (0..10_000)
        .find_map(|_| single.step().err())
        .expect("unstable above the linear limit");
    let err_passes = passes
        .step_n(10_000)
        .expect_err("unstable above the linear limit");
    assert_eq!(err_single, err_passes);
    assert_eq!(single.steps(), passes.steps());
    assert!(
        !single.steps().is_multiple_of(8),
        "the failure should fall inside a pass: step {}",
        single.steps()
    );
    assert!(state_bits(&single) == state_bits(&passes));
}

/// A grid large enough for the engine to write its back buffers with non-temporal stores
/// (2¹⁹ nodes, rows of whole chunks), in single steps and in passes, against the
/// reference; and a row width that is not a whole number of chunks, which never streams.
#[test]
fn large_grids_written_with_streaming_stores_match_the_reference() {
    for (cols, rows) in [(1024, 512), (1023, 513)] {
        let mut engine = common::new_surface(Params::with_size(cols, rows)).unwrap();
        engine.drop_at(300.0, 200.0, 2.0, 6.0).unwrap();
        engine.drop_at(900.0, 400.0, -1.5, 4.0).unwrap();
        engine.add_force(7 * cols + 9, [0.3, -0.2, 0.1]).unwrap();
        let mut reference = engine.clone();
        reference.set_simd_level(SimdLevel::Scalar);
        engine.step().unwrap();
        engine.step_n(8).unwrap();
        for _ in 0..9 {
            reference.step().unwrap();
        }
        assert!(
            state_bits(&engine) == state_bits(&reference),
            "{cols}x{rows}"
        );
    }
}
