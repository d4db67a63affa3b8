//! The library speaks world units: drops, forces at a point, wakes, rain and queries land
//! on the same world positions whatever the spacing, and `add_force_at` is the adjoint of
//! `height_at`.
//!
//! "The same physical set-up" at spacing 1 and 0.5 means the same continuum membrane
//! sampled twice as finely: the same mass per unit area (`m ∝ h²`), the same spring
//! coefficient `c` (the wave speed `h·sqrt(3c(1 − r)/m)` is then the same in world units per
//! unit time), damping per unit mass unchanged (`γ ∝ m`), and half the timestep (the
//! critical timestep `sqrt(m/3c)` halves with `h`). Disturbances are given in world units
//! and seconds. The two runs then differ only by discretisation error, which the tests
//! bound: heights sampled at the coarse grid's nodes (points every grid has) agree within
//! 10% of the peak between spacing 1 and 1/2, and closer still between 1/2 and 1/4.

use proptest::prelude::*;
use springwater::disturb::{Disturbance, Rain, Wake};
use springwater::{Boundary, Params, Surface};

/// A 32 × 32 world-unit pool sampled with spacing `h`.
fn pool(h: f32) -> Params {
    let scale = h * h; // mass per node ∝ the cell's area
    let cells = (32.0 / h).round() as usize;
    Params::with_size(cells + 1, cells + 1)
        .with_spacing(h)
        .with_mass(4.0 * scale)
        .with_viscosity(0.05 * scale)
        .with_dt(0.4 * h)
}

/// Heights at every integer world point of the 32 × 32 pool.
fn heights(s: &Surface) -> Vec<f32> {
    let mut out = Vec::new();
    for z in 0..=32 {
        for x in 0..=32 {
            out.push(s.height_at(x as f32, z as f32).unwrap());
        }
    }
    out
}

/// Largest |a − b| relative to the largest |a|.
fn relative_difference(a: &[f32], b: &[f32]) -> f32 {
    let peak = a.iter().fold(0.0f32, |m, v| m.max(v.abs()));
    assert!(peak > 0.0, "nothing moved");
    let diff = a
        .iter()
        .zip(b)
        .fold(0.0f32, |m, (x, y)| m.max((x - y).abs()));
    diff / peak
}

/// Runs model time `time` on the pools of spacing 1, 1/2 and 1/4, calling `disturb`
/// before every step, and returns the heights at the integer world points.
fn run_all(time: f32, mut disturb: impl FnMut(&mut Surface, f32)) -> [Vec<f32>; 3] {
    [1.0, 0.5, 0.25].map(|h| {
        let mut s = Surface::new(pool(h)).unwrap();
        let dt = s.params().dt;
        let steps = (time / dt).round() as usize;
        // Disturbances are handed each step's seconds.
        let seconds = dt / s.params().time_scale;
        for _ in 0..steps {
            disturb(&mut s, seconds);
            s.step().unwrap();
        }
        assert!((s.model_time() as f32 - time).abs() < 1e-3);
        heights(&s)
    })
}

/// Spacing 1 and 1/2 agree within `tolerance` of the peak, and refining further agrees
/// better still (the difference is discretisation error, shrinking with `h`).
fn assert_converges([coarse, fine, finer]: [Vec<f32>; 3], tolerance: f32) {
    let d = relative_difference(&coarse, &fine);
    let d_fine = relative_difference(&fine, &finer);
    assert!(d < tolerance, "spacing 1 vs 1/2: relative difference {d}");
    assert!(
        d_fine < d,
        "spacing 1/2 vs 1/4 ({d_fine}) is no closer than 1 vs 1/2 ({d})"
    );
}

#[test]
fn a_drop_in_world_units_lands_on_the_same_world_point() {
    for h in [1.0, 0.5, 0.25] {
        let mut s = Surface::new(pool(h)).unwrap();
        s.drop_at(10.0, 21.0, 1.0, 3.0).unwrap();
        // The crest is the node at world (10, 21), whatever the spacing.
        let y = s.positions()[1];
        let top = (0..y.len()).max_by(|&a, &b| y[a].total_cmp(&y[b])).unwrap();
        let (col, row) = s.grid().coords(top);
        assert_eq!(
            (col as f32 * h, row as f32 * h),
            (10.0, 21.0),
            "spacing {h}"
        );
        assert_eq!(s.height_at(10.0, 21.0).unwrap(), 1.0);
        // One radius away the Gaussian is at 1/e, on every grid.
        let e = s.height_at(13.0, 21.0).unwrap();
        assert!((e - (-1.0f32).exp()).abs() < 1e-6, "spacing {h}: {e}");
    }
}

#[test]
fn a_drop_moves_the_same_way_at_spacing_1_and_half() {
    let heights = run_all(16.0, |s, _| {
        if s.steps() == 0 {
            s.drop_at(16.0, 14.0, 1.0, 4.0).unwrap();
        }
    });
    assert_converges(heights, 0.1);
}

#[test]
fn a_force_at_a_world_point_moves_the_same_way_at_spacing_1_and_half() {
    // A constant downward force at a point between nodes for 8 units of model time: the
    // same impulse on both grids, spread by `add_force_at` with the query's weights.
    let heights = run_all(8.0, |s, _| {
        s.add_force_at(15.3, 17.6, [0.0, -3.0, 0.0]).unwrap();
    });
    assert_converges(heights, 0.1);
}

#[test]
fn a_wake_moves_the_same_way_at_spacing_1_and_half() {
    let path = vec![[8.0, 8.0], [24.0, 10.0], [20.0, 24.0]];
    let mut wakes = [(); 3].map(|_| Wake::new(path.clone()).unwrap());
    let heights = run_all(12.0, |s, dt| {
        // One wake per grid, told apart by the spacing (1, 1/2, 1/4).
        let i = s.params().spacing.recip().log2().round() as usize;
        wakes[i].apply(s, dt).unwrap();
    });
    // The same model time took 30, 60 and 120 steps: the wakes are at the same place.
    for w in &wakes[1..] {
        let [a, b] = [wakes[0].position(), w.position()];
        assert!(
            (a[0] - b[0]).abs() < 1e-3 && (a[1] - b[1]).abs() < 1e-3,
            "{a:?} {b:?}"
        );
    }
    assert_converges(heights, 0.1);
}

#[test]
fn rain_falls_on_the_same_world_points_at_any_spacing() {
    let [coarse, fine] = [1.0, 0.5].map(|h| {
        let mut s = Surface::new(pool(h)).unwrap();
        let mut rain = Rain::new(12.0, 11); // drops per second, over 5/6 s
        rain.apply(&mut s, 5.0 / 6.0).unwrap();
        rain.apply(&mut s, 0.0).unwrap();
        assert!(rain.fallen() > 3);
        heights(&s)
    });
    // Only drops, no motion yet: the heights at shared points agree to rounding.
    for (a, b) in coarse.iter().zip(&fine) {
        assert!((a - b).abs() < 1e-5, "{a} vs {b}");
    }
}

/// A free surface of `cols × rows` nodes, spacing `h`, whose heights are `field`.
fn surface_with_heights(cols: usize, rows: usize, h: f32, field: &[f32]) -> Surface {
    let p = Params::with_size(cols, rows)
        .with_spacing(h)
        .with_boundary(Boundary::Free);
    let mut snap = Surface::new(p).unwrap().snapshot();
    snap.positions[1].copy_from_slice(field);
    Surface::from_snapshot(snap).unwrap()
}

proptest! {
    /// `add_force_at` is the adjoint of `height_at`: for a unit force at a point and any
    /// node field `v`, `Σ force_i · v_i` equals the field interpolated at that point.
    #[test]
    fn add_force_at_is_the_adjoint_of_height_at(
        cols in 2usize..9,
        rows in 2usize..9,
        h in 0.1f32..3.0,
        fx in 0.0f32..=1.0,
        fz in 0.0f32..=1.0,
        f in -10.0f32..10.0,
        seed in any::<u64>(),
    ) {
        let n = cols * rows;
        let mut state = seed | 1;
        let field: Vec<f32> = (0..n)
            .map(|_| {
                state ^= state << 13;
                state ^= state >> 7;
                state ^= state << 17;
                (state >> 40) as f32 / (1u64 << 24) as f32 * 4.0 - 2.0
            })
            .collect();
        let s = surface_with_heights(cols, rows, h, &field);
        let (x, z) = (fx * (cols - 1) as f32 * h, fz * (rows - 1) as f32 * h);
        let mut pushed = s.clone();
        pushed.add_force_at(x, z, [0.5 * f, f, -f]).unwrap();
        let [px, py, pz] = pushed.forces();
        let dot = |force: &[f32]| -> f64 {
            force.iter().zip(&field).map(|(&a, &b)| a as f64 * b as f64).sum()
        };
        let interpolated = s.height_at(x, z).unwrap() as f64;
        let tol = 1e-5 * (1.0 + f.abs() as f64);
        prop_assert!((dot(py) - f as f64 * interpolated).abs() < tol);
        prop_assert!((dot(px) - 0.5 * f as f64 * interpolated).abs() < tol);
        prop_assert!((dot(pz) + f as f64 * interpolated).abs() < tol);
        // The spread forces sum to the force.
        let total: f64 = py.iter().map(|&v| v as f64).sum();
        prop_assert!((total - f as f64).abs() < tol);
    }
}

#[test]
fn add_force_at_refuses_bad_input_and_changes_nothing() {
    let mut s = Surface::new(Params::with_size(9, 9)).unwrap();
    s.add_force_at(4.0, 4.0, [0.0, 1.0, 0.0]).unwrap();
    let before: Vec<Vec<f32>> = s.forces().iter().map(|c| c.to_vec()).collect();
    for (x, z, f) in [
        (f32::NAN, 1.0, [0.0; 3]),
        (1.0, f32::INFINITY, [0.0; 3]),
        (-0.01, 1.0, [0.0; 3]),
        (1.0, 8.01, [0.0; 3]),
        (1.0, 1.0, [0.0, f32::NAN, 0.0]),
        (1.0, 1.0, [f32::INFINITY, 0.0, 0.0]),
    ] {
        assert!(s.add_force_at(x, z, f).is_err(), "({x}, {z}) {f:?}");
        s.add_force_at(4.0, 4.0, [0.0, 0.0, 0.0]).unwrap();
        let now: Vec<Vec<f32>> = s.forces().iter().map(|c| c.to_vec()).collect();
        assert_eq!(now, before);
    }
    // A force that would overflow the sum on a node is refused too.
    s.add_force_at(4.0, 4.0, [0.0, f32::MAX, 0.0]).unwrap();
    let before: Vec<Vec<f32>> = s.forces().iter().map(|c| c.to_vec()).collect();
    assert!(s.add_force_at(4.0, 4.0, [0.0, f32::MAX, 0.0]).is_err());
    let now: Vec<Vec<f32>> = s.forces().iter().map(|c| c.to_vec()).collect();
    assert_eq!(now, before);
    s.clear_forces();
    s.add_force_at(4.0, 4.0, [0.0, 1.0, 0.0]).unwrap();
    // The pending force acts on the next step and is then gone.
    s.step().unwrap();
    assert!(s.positions()[1][4 * 9 + 4] > 0.0);
    assert!(s.forces()[1].iter().all(|&f| f == 0.0));
}

#[test]
fn a_frame_in_seconds_is_the_same_model_time_at_any_spacing() {
    // The same time scale on both pools: a 60 Hz frame is 0.4 units of model time, one
    // step of 0.4 on the coarse pool and two of 0.2 on the fine one, and the drop has
    // moved the same way after the same seconds.
    let [coarse, fine] = [1.0, 0.5].map(|h| {
        let mut s = Surface::new(pool(h)).unwrap();
        s.drop_at(16.0, 14.0, 1.0, 4.0).unwrap();
        let mut substeps = 0;
        for _ in 0..40 {
            substeps += s.advance(1.0 / 60.0).unwrap();
        }
        assert_eq!(substeps, (40.0 / h) as usize);
        assert!((s.model_time() - 16.0).abs() < 1e-3, "{}", s.model_time());
        assert!((s.time() - 2.0 / 3.0).abs() < 1e-4, "{}", s.time());
        heights(&s)
    });
    let d = relative_difference(&coarse, &fine);
    assert!(d < 0.1, "relative difference {d}");
}
