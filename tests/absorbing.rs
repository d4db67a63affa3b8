//! The absorbing boundary: the ring test in the crate's real model (see
//! `tests/common/ring.rs` and `docs/open-water.md`), its frame, its limits and its bits.

mod common;
#[path = "common/ring.rs"]
mod ring;

use ring::{reflection, Source};
use springwater::{Boundary, Error, Params, Surface};

/// The undamped middle the ring test measures, in nodes per side.
const MIDDLE: usize = 128;

fn absorbing_grid() -> usize {
    MIDDLE + 2 * Boundary::ABSORBING_WIDTH
}

#[test]
fn a_ring_wave_leaves_through_the_absorbing_frame() {
    // Bars: reflected energy below 2e-3 of a 4-cell bump's and 5e-4 of a 2-cell one's.
    let n = absorbing_grid();
    for (radius, bar) in [(4.0, 2e-3), (2.0, 5e-4)] {
        for at in [Source::Centre, Source::Corner] {
            let r = reflection(n, Boundary::absorbing(), at, radius);
            println!("absorbing, bump width {radius}, {at:?}: reflected {r:.2e}");
            assert!(
                r < bar,
                "width {radius} at {at:?}: reflected {r:.3e}, bar {bar:.0e}"
            );
        }
    }
}

#[test]
fn a_pinned_wall_reflects_the_whole_ring() {
    let r = reflection(MIDDLE, Boundary::Pinned, Source::Centre, 4.0);
    println!("pinned wall, bump width 4, centre: reflected {r:.3}");
    assert!((0.9..1.2).contains(&r), "a wall reflected {r}");
}

#[test]
fn a_narrow_frame_reflects_more_than_the_default() {
    // The test can tell frames apart: 8 rings are measurably worse than 32.
    let narrow = Boundary::Absorbing { width: 8 };
    let r = reflection(MIDDLE + 16, narrow, Source::Centre, 4.0);
    println!("absorbing:8, bump width 4, centre: reflected {r:.2e}");
    assert!(r > 5e-3, "an 8-cell frame reflected only {r:.2e}");
}

#[test]
fn the_frame_is_inside_the_grid_pinned_at_the_ring_and_damped_quadratically() {
    let p = Params {
        boundary: Boundary::Absorbing { width: 10 },
        ..Params::with_size(40, 30)
    };
    let s = Surface::new(p).unwrap();
    assert_eq!(s.len(), 40 * 30, "the frame adds no nodes");
    let grid = s.grid();
    let g = s.viscosities();
    for (i, (&pinned, &gamma)) in s.pinned().iter().zip(g).enumerate() {
        let d = grid.edge_distance(i);
        assert_eq!(pinned, d == 0, "node {i}");
        if d >= 10 {
            assert_eq!(gamma, p.viscosity, "node {i} in the middle");
        }
    }
    // Along a row in the middle: rising towards the edge, quadratically.
    let row = 15 * 40;
    let extra = |c: usize| g[row + c] - p.viscosity;
    for c in 1..10 {
        assert!(extra(c) > extra(c + 1), "column {c}");
    }
    let ratio = extra(1) / extra(5);
    let expected = (9.0f32 / 5.0).powi(2);
    assert!((ratio - expected).abs() < 1e-3, "{ratio} vs {expected}");
    // The timestep stays valid: the largest viscosity is within the damped limit.
    assert!(s.critical_dt() > p.dt);
}

#[test]
fn the_frame_fits_any_valid_timestep() {
    // Close to the critical timestep the frame gets less damping but never makes a valid
    // timestep invalid.
    let base = Params::with_size(96, 96);
    for share in [0.5, 0.9, 0.99, 0.999] {
        let p = Params {
            dt: base.critical_dt() * share,
            boundary: Boundary::absorbing(),
            ..base
        };
        let mut s = Surface::new(p).unwrap_or_else(|e| panic!("dt share {share}: {e}"));
        assert!(s.critical_dt() > p.dt, "share {share}");
        s.drop_at(48.0, 48.0, 1.5, 3.0).unwrap();
        s.step_n(300).unwrap();
        assert!(s.energy().total().is_finite());
    }
}

#[test]
fn a_frame_too_wide_for_the_grid_is_refused() {
    for (size, width) in [(64, 32), (64, 31), (10, 0)] {
        let p = Params {
            boundary: Boundary::Absorbing { width },
            ..Params::with_size(size, size + 10)
        };
        let ok = width >= 1 && size >= 2 * width + 2;
        match Surface::new(p) {
            Ok(_) => assert!(ok, "{size} / {width} accepted"),
            Err(Error::InvalidParam { name, .. }) => {
                assert!(!ok, "{size} / {width} refused");
                assert_eq!(name, "absorbing width");
            }
            Err(e) => panic!("{e}"),
        }
    }
}

#[test]
fn absorbing_surfaces_snapshot_and_restore_bitwise() {
    let p = Params {
        boundary: Boundary::Absorbing { width: 6 },
        ..Params::with_size(30, 20)
    };
    let mut a = Surface::new(p).unwrap();
    a.drop_at(15.0, 10.0, 1.0, 2.0).unwrap();
    a.step_n(7).unwrap();
    let mut b = Surface::from_bytes(&a.to_bytes()).unwrap();
    assert_eq!(b.params().boundary, p.boundary);
    a.step_n(20).unwrap();
    b.step_n(20).unwrap();
    assert_eq!(a.to_bytes(), b.to_bytes());
}

#[test]
fn the_absorbing_boundary_gives_the_same_bits_at_every_level_and_thread_count() {
    common::same_bits_everywhere(
        || {
            let p = Params {
                boundary: Boundary::Absorbing { width: 12 },
                ..Params::with_size(70, 45)
            };
            let mut s = Surface::new(p).unwrap();
            s.drop_at(20.0, 30.0, 1.5, 3.0).unwrap();
            s
        },
        |s| {
            for _ in 0..50 {
                s.step().unwrap();
            }
            s.step_n(37).unwrap();
        },
    );
}
