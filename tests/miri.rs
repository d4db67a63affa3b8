//! The engine's unchecked accesses (its access module, `forces/engine/access/`: the
//! front and back buffers, node and spring tables, ring rows and row forces, over the lane
//! layer's chunk views; each band's own rows and handoff slots) on small grids of every
//! width around the lane count, in single steps and in passes of three steps, with uniform
//! and edited springs, checked against the scalar reference. Small enough to run under
//! Miri, which checks every access for undefined behaviour:
//!
//! ```sh
//! cargo +nightly miri test -p springwater --no-default-features --features internals --test miri
//! ```

mod common;

use common::state_bits;
use springwater::internals::Tuning;
use springwater::{Family, Params, SimdLevel, SpringId, Surface};

/// A `cols` × `rows` grid (bands of two rows where a single step runs, of six in a pass
/// of three steps) after one single step, then one pass of three steps (front to ring,
/// ring to ring, ring to back buffers), against the scalar reference; with one edited
/// spring per family if `edited` (the engine then reads that family's tables).
fn engine_matches_the_reference(cols: usize, rows: usize, edited: bool) {
    let mut p = Params::with_size(cols, rows);
    p.boundary = springwater::Boundary::Free;
    let mut engine = Surface::new(p).unwrap();
    engine.set_band_rows(2);
    engine.drop_at(cols as f32 / 2.0, 1.0, 0.5, 1.0).unwrap();
    engine.add_force(0, [0.1, 0.2, 0.3]).unwrap();
    if edited {
        for family in Family::ALL {
            let _ = engine.set_spring(
                SpringId { family, origin: 1 },
                springwater::Spring {
                    rest: 0.3,
                    stiffness: 6.0,
                },
            );
        }
    }
    let mut reference = engine.clone();
    reference.set_simd_level(SimdLevel::Scalar);
    engine.set_pass_steps(3);
    for steps in [1, 3] {
        engine.step_n(steps).unwrap();
        for _ in 0..steps {
            reference.step().unwrap();
        }
        assert!(
            state_bits(&engine) == state_bits(&reference),
            "{cols}x{rows}, {steps} steps, edited springs: {edited}"
        );
    }
}

#[test]
fn engine_kernels_match_the_reference_on_every_small_width() {
    // Under Miri (the portable lanes, 8 wide) the widths that give each shape of a row:
    // one partial chunk, one whole, a whole and a partial one, two whole and a partial
    // one; the accesses of a chunk are the same whatever the width. Edited tables meet a
    // whole last chunk (their SW table is read one node on) and partial ones.
    let cases: Vec<(usize, bool)> = if cfg!(miri) {
        vec![(2, false), (7, true), (8, true), (9, false), (17, true)]
    } else {
        (2..=40).flat_map(|c| [(c, false), (c, true)]).collect()
    };
    // Five rows are two bands in a single step and one in a pass (under Miri; natively
    // also two rows, every one an edge, and three).
    let rows: &[usize] = if cfg!(miri) { &[5] } else { &[2, 3, 5] };
    for (cols, edited) in cases {
        for &rows in rows {
            engine_matches_the_reference(cols, rows, edited);
        }
    }
}

#[test]
fn bands_handing_rows_over_match_the_reference() {
    // Twelve or thirteen rows are two bands in a pass of three steps: the even band hands
    // its rows at the cut over to the odd one at the two levels below the last.
    let sizes: &[(usize, usize)] = if cfg!(miri) {
        &[(2, 12)]
    } else {
        &[(2, 12), (9, 12), (9, 13), (17, 12), (33, 13)]
    };
    for &(cols, rows) in sizes {
        let mut s = Surface::new(Params::with_size(cols, rows)).unwrap();
        s.set_band_rows(2);
        s.set_pass_steps(3);
        assert_eq!(s.bands().count(), 2, "{cols}x{rows}");
        engine_matches_the_reference(cols, rows, cols % 2 == 1);
    }
}
