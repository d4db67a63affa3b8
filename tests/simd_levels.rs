//! Every SIMD level gives the same bits as the scalar reference, and golden fingerprints
//! pin those bits for each set-up.
//!
//! The fingerprints were taken from the scalar reference. A level this machine lacks
//! (AVX-512 on an AVX2-only CPU) is skipped here and checked on every machine that has
//! it: the machines this crate is built and tested on change, so the constants are what
//! ties a level run on one machine to the others.

mod common;

use common::fingerprint;
use springwater::mesh::{compute_normals, Normals};
use springwater::refraction::{refract, Refraction, RefractionParams};
use springwater::{Boundary, Family, Params, SimdLevel, Spring, SpringId, Surface};

/// One fixed set-up: a surface after its disturbances, and how many steps to run.
struct SetUp {
    name: &'static str,
    build: fn() -> Surface,
    steps: u64,
    /// FNV-1a of every position and velocity bit after `steps` steps.
    golden: u64,
}

fn pool() -> Surface {
    // Pinned walls (the default), drops, a force, default schedule.
    let mut s = common::new_surface(Params::with_size(67, 45)).unwrap();
    s.drop_at(20.0, 15.0, 1.5, 3.0).unwrap();
    s.drop_at(50.5, 30.25, -1.0, 2.0).unwrap();
    s.add_force(22 * 67 + 40, [0.3, -0.7, 0.2]).unwrap();
    s
}

fn free_sheet() -> Surface {
    // Free boundary, uniform acceleration, a different rest ratio and spacing.
    let mut p = Params::with_size(64, 40);
    p.boundary = Boundary::Free;
    p.rest_ratio = 0.3;
    p.spacing = 1.0;
    let mut s = common::new_surface(p).unwrap();
    // Per second²: 0.01 and 0.002 per unit of model time², which the step gets back exactly.
    s.set_acceleration([0.0, -0.01 * 576.0, 0.002 * 576.0])
        .unwrap();
    s.drop_at(31.0, 19.0, 2.0, 4.0).unwrap();
    s
}

fn edited_springs() -> Surface {
    // Non-uniform tables (the engine reads them instead of registers), heavier nodes,
    // more viscosity, a width that leaves a partial chunk at every level.
    let mut s = common::new_surface(Params::with_size(37, 29)).unwrap();
    for (k, family) in Family::ALL.into_iter().enumerate() {
        let origin = 10 * 37 + 5 + 3 * k;
        let spring = Spring {
            rest: 0.4,
            stiffness: 5.0 + k as f32,
        };
        s.set_spring(SpringId { family, origin }, spring).unwrap();
    }
    s.set_mass(14 * 37 + 18, 6.0).unwrap();
    s.set_viscosity(7 * 37 + 9, 0.2).unwrap();
    s.drop_at(18.0, 14.0, 1.0, 2.5).unwrap();
    s
}

const SET_UPS: [SetUp; 3] = [
    SetUp {
        name: "pinned pool",
        build: pool,
        steps: 60,
        golden: 0xb028_7dc8_3213_7c80,
    },
    SetUp {
        name: "free sheet",
        build: free_sheet,
        steps: 45,
        golden: 0x7f04_90fc_cdd0_c478,
    },
    SetUp {
        name: "edited springs",
        build: edited_springs,
        steps: 50,
        golden: 0x09d3_8c55_2830_2b2f,
    },
];

#[test]
fn the_scalar_reference_matches_the_golden_fingerprints() {
    let got: Vec<u64> = SET_UPS
        .iter()
        .map(|set_up| {
            let mut s = (set_up.build)();
            s.set_simd_level(SimdLevel::Scalar);
            for _ in 0..set_up.steps {
                s.step().unwrap();
            }
            fingerprint(&s)
        })
        .collect();
    // Every set-up's value in one message: re-taking the constants after a deliberate
    // change to the reference's arithmetic needs them all.
    let changed: Vec<String> = SET_UPS
        .iter()
        .zip(got)
        .filter(|(set_up, got)| *got != set_up.golden)
        .map(|(set_up, got)| format!("{}: got {got:#018x}", set_up.name))
        .collect();
    assert!(
        changed.is_empty(),
        "the reference's bits changed: {changed:?}"
    );
}

#[test]
fn every_available_level_matches_the_golden_fingerprints() {
    for level in SimdLevel::ALL {
        if !level.is_available() {
            eprintln!("{level}: not on this CPU, checked where it is");
            continue;
        }
        for set_up in &SET_UPS {
            let mut s = (set_up.build)();
            assert_eq!(s.set_simd_level(level), level);
            // Single steps, then passes of several steps.
            let single = set_up.steps / 3;
            for _ in 0..single {
                s.step().unwrap();
            }
            s.step_n(set_up.steps - single).unwrap();
            assert_eq!(
                fingerprint(&s),
                set_up.golden,
                "{}: level {level} differs from the reference",
                set_up.name
            );
        }
    }
}

#[test]
fn render_side_stages_give_the_same_bits_at_every_level() {
    let mut s = pool();
    s.step_n(30).unwrap();
    let eye = glam::Vec3::new(30.0, 25.0, -20.0);
    let bottom = RefractionParams {
        depth: 5.0,
        ..Default::default()
    };
    let run = |level: SimdLevel| {
        let view = s.mesh_view().with_simd_level(level);
        let (mut normals, mut uv) = (Normals::new(), Refraction::default());
        compute_normals(&view, &mut normals);
        refract(&view, &normals, eye, &bottom, &mut uv).unwrap();
        let bits = |v: &[f32]| v.iter().map(|x| x.to_bits()).collect::<Vec<_>>();
        [
            bits(&normals.x),
            bits(&normals.y),
            bits(&normals.z),
            bits(&uv.u),
            bits(&uv.v),
            bits(&uv.fresnel),
        ]
    };
    let scalar = run(SimdLevel::Scalar);
    for level in SimdLevel::ALL.into_iter().filter(|l| l.is_available()) {
        assert!(run(level) == scalar, "level {level}");
    }
}

#[test]
fn levels_clamp_to_the_cpu() {
    let mut s = pool();
    let best = SimdLevel::detect();
    assert_eq!(s.set_simd_level(SimdLevel::Avx512), best);
    assert_eq!(s.simd_level(), best);
    assert_eq!(s.mesh_view().simd_level(), best);
    assert_eq!(s.set_simd_level(SimdLevel::Scalar), SimdLevel::Scalar);
}

/// A pool left to settle never passes through subnormal heights or velocities (whose
/// arithmetic many x86 cores run a hundred times slower), at every level and in the
/// reference, with the same bits. (Its in-plane positions keep a rounding jitter of a few
/// ulps, which leaves a few heights near the calm threshold instead of exactly 0.)
#[test]
fn a_settling_pool_never_goes_subnormal() {
    let settle = |level: SimdLevel| {
        let mut p = Params::with_size(40, 36);
        p.viscosity = 0.5; // settles in thousands of steps instead of tens of thousands
        let mut s = Surface::new(p).unwrap();
        assert_eq!(s.set_simd_level(level), level);
        s.drop_at(17.0, 20.0, 1.0, 3.0).unwrap();
        for chunk in 1..=60 {
            s.step_n(100).unwrap();
            let values = s.positions().into_iter().chain(s.velocities()).flatten();
            let subnormal = values.filter(|v| v.is_subnormal()).count();
            assert_eq!(
                subnormal,
                0,
                "{level}: subnormal values after {} steps",
                100 * chunk
            );
        }
        let [_, y, _] = s.positions();
        let [_, vy, _] = s.velocities();
        let largest = y.iter().chain(vy).fold(0.0f32, |m, v| m.max(v.abs()));
        assert!(largest < 1e-16, "{level}: still moving, {largest:e}");
        fingerprint(&s)
    };
    let reference = settle(SimdLevel::Scalar);
    for level in SimdLevel::ALL.into_iter().filter(|l| l.is_available()) {
        assert_eq!(settle(level), reference, "{level}");
    }
}
