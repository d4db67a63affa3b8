//! The engine's unchecked accesses (its access module, `forces/engine/access.rs`: the
//! front and back buffers, node and spring tables, ring rows and row forces, over the lane
//! layer's chunk views) on small grids of every width around the lane count, in single
//! steps and in a pass of three steps, with uniform and edited springs, checked against
//! the scalar reference. Small enough to run under Miri, which checks every access for
//! undefined behaviour:
//!
//! ```sh
//! cargo +nightly miri test -p springwater --no-default-features --features internals --test miri
//! ```

mod common;

use common::state_bits;
use springwater::internals::Tuning;
use springwater::{Family, Params, SimdLevel, SpringId, Surface};

#[test]
fn engine_kernels_match_the_reference_on_every_small_width() {
    let widths: Vec<usize> = if cfg!(miri) {
        vec![2, 3, 7, 8, 9, 17, 32, 33]
    } else {
        (2..=40).collect()
    };
    for cols in widths {
        for rows in [2, 3, 5] {
            let mut p = Params::with_size(cols, rows);
            p.boundary = springwater::Boundary::Free;
            let mut engine = Surface::new(p).unwrap();
            engine.set_band_rows(2);
            engine.drop_at(cols as f32 / 2.0, 1.0, 0.5, 1.0).unwrap();
            engine.add_force(0, [0.1, 0.2, 0.3]).unwrap();
            if cols % 2 == 1 {
                // One edited spring per family: the engine reads that family's tables.
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
            // One single step (front buffers to back buffers), then one pass of three
            // steps (front to ring, ring to ring, ring to back buffers).
            engine.set_pass_steps(3);
            for steps in [1, 3] {
                engine.step_n(steps).unwrap();
                for _ in 0..steps {
                    reference.step().unwrap();
                }
                assert!(
                    state_bits(&engine) == state_bits(&reference),
                    "{cols}x{rows}, {steps} steps"
                );
            }
        }
    }
}
