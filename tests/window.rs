//! The moving window: shifts keep the water of the overlap bit for bit at its world place,
//! whatever the SIMD level and thread count; floaters ride through; bad input changes
//! nothing.
//!
//! "The same world cells": node `(col, row)` of a window shifted by `(dc, dr)` holds the
//! water of node `(col + dc, row + dr)` of an unshifted run. The explicit step moves
//! information one cell per step, and a drop of radius `r` changes nothing beyond about
//! `10.2 r` cells (its weight is 0 in `f32` there), so as long as neither the drop's
//! reach plus the steps taken nor anything from the window's edges (the incoming strip, the
//! absorbing frame at its new place) meets, every node of the overlap is the same
//! computation in both runs and must give the same bits.

mod common;

#[cfg(feature = "parallel")]
use std::sync::Arc;

use springwater::{Boundary, Floater, Params, SimdLevel, Spring, SpringId, Surface};

/// A 128 × 112 open-water window with an 8-cell absorbing frame and one drop in the middle
/// (radius 2: nothing beyond 21 cells of (64, 56) is disturbed).
fn open_water() -> Surface {
    let mut p = Params::with_size(128, 112);
    p.boundary = Boundary::Absorbing { width: 8 };
    let mut s = Surface::new(p).unwrap();
    s.drop_at(64.0, 56.0, 1.0, 2.0).unwrap();
    s
}

/// Every position and velocity bit of node `(c, r)`.
fn node_bits(s: &Surface, c: usize, r: usize) -> [u32; 6] {
    let i = s.grid().index(c, r);
    let [x, y, z] = s.positions();
    let [vx, vy, vz] = s.velocities();
    [x[i], y[i], z[i], vx[i], vy[i], vz[i]].map(f32::to_bits)
}

/// Asserts that node `(c, r)` of `shifted` equals node `(c + dc, r + dr)` of `reference`
/// for every node of the overlap.
fn assert_overlap_equal(shifted: &Surface, reference: &Surface, dc: i64, dr: i64, what: &str) {
    let g = shifted.grid();
    let mut compared = 0;
    for r in 0..g.rows {
        for c in 0..g.cols {
            let (sc, sr) = (c as i64 + dc, r as i64 + dr);
            if sc < 0 || sr < 0 || sc >= g.cols as i64 || sr >= g.rows as i64 {
                continue;
            }
            assert_eq!(
                node_bits(shifted, c, r),
                node_bits(reference, sc as usize, sr as usize),
                "{what}: node ({c}, {r}) differs from the unshifted run's ({sc}, {sr})"
            );
            compared += 1;
        }
    }
    assert!(compared > 0, "{what}: no overlap compared");
}

#[test]
fn a_shift_keeps_the_overlap_bit_for_bit() {
    let mut reference = open_water();
    reference.step_n(12).unwrap();
    for (dc, dr) in [(5, -3), (-9, 0), (0, 7), (1, 1), (-2, -11)] {
        let mut shifted = reference.clone();
        shifted.shift(dc, dr).unwrap();
        let h = shifted.params().spacing;
        assert_eq!(shifted.origin(), [dc as f32 * h, dr as f32 * h]);
        assert_eq!(shifted.origin_cells(), [dc as i64, dr as i64]);
        // Everything but the border ring, which the boundary pins at rest.
        let g = shifted.grid();
        for r in 1..g.rows - 1 {
            for c in 1..g.cols - 1 {
                let (sc, sr) = (c as i64 + dc as i64, r as i64 + dr as i64);
                if sc < 0 || sr < 0 || sc >= g.cols as i64 || sr >= g.rows as i64 {
                    // The incoming strip is calm: rest place, no velocity.
                    let i = g.index(c, r);
                    let [x, y, z] = shifted.positions();
                    assert_eq!([x[i], y[i], z[i]], [(sc as f32) * h, 0.0, (sr as f32) * h]);
                    assert!(shifted.velocities().iter().all(|v| v[i] == 0.0));
                    continue;
                }
                assert_eq!(
                    node_bits(&shifted, c, r),
                    node_bits(&reference, sc as usize, sr as usize),
                    "shift ({dc}, {dr}): node ({c}, {r})"
                );
            }
        }
        // World-space queries answer the same at the same world point.
        for (x, z) in [(64.0, 56.0), (60.3, 57.9), (70.25, 50.5)] {
            assert_eq!(
                shifted.height_at(x, z).unwrap().to_bits(),
                reference.height_at(x, z).unwrap().to_bits(),
                "height at ({x}, {z}) after shift ({dc}, {dr})"
            );
            assert_eq!(
                shifted.velocity_at(x, z).unwrap(),
                reference.velocity_at(x, z).unwrap()
            );
        }
    }
}

/// Steps `s` `n` times at `level` on a pool of `threads` threads (on the calling thread
/// without the `parallel` feature, as on wasm32).
fn steps_on(s: &mut Surface, n: u64, level: SimdLevel, threads: usize) {
    s.set_simd_level(level);
    #[cfg(feature = "parallel")]
    {
        let pool = rayon::ThreadPoolBuilder::new()
            .num_threads(threads)
            .build()
            .unwrap();
        s.set_thread_pool(Some(Arc::new(pool)));
    }
    #[cfg(not(feature = "parallel"))]
    let _ = threads;
    s.step_n(n).unwrap();
}

#[test]
fn steps_after_a_shift_match_an_unshifted_run_at_every_level_and_thread_count() {
    // 6 steps, shift by (6, −5), 18 more: the drop's reach (21 cells) plus 24 steps stays
    // 5 cells clear of either window's frame, so the whole overlap is the same computation.
    let mut reference = open_water();
    reference.step_n(24).unwrap();
    for level in SimdLevel::ALL {
        for threads in [1, 3] {
            let mut s = open_water();
            steps_on(&mut s, 6, level, threads);
            s.shift(6, -5).unwrap();
            steps_on(&mut s, 18, level, threads);
            assert_overlap_equal(
                &s,
                &reference,
                6,
                -5,
                &format!("{level:?}, {threads} threads"),
            );
        }
    }
}

#[test]
fn shifting_back_and_forth_equals_never_shifting() {
    let mut reference = open_water();
    reference.step_n(24).unwrap();
    let mut s = open_water();
    s.step_n(5).unwrap();
    s.shift(4, 3).unwrap();
    s.step_n(7).unwrap();
    s.shift(-7, 2).unwrap();
    s.step_n(6).unwrap();
    s.shift(3, -5).unwrap();
    assert_eq!(s.origin_cells(), [0, 0]);
    s.step_n(6).unwrap();
    let bits = |s: &Surface| -> Vec<u32> {
        s.positions()
            .into_iter()
            .chain(s.velocities())
            .flatten()
            .map(|v| v.to_bits())
            .collect()
    };
    assert!(
        bits(&s) == bits(&reference),
        "the round trip changed the water"
    );
    assert_eq!(s.energy(), reference.energy());
}

#[test]
fn floaters_ride_through_shifts_without_a_jump() {
    // A ball bobbing after a drop beside it; one window follows a point that circles it,
    // the other never moves. The ball's state and the water under it must agree to the bit
    // at every step (nothing from the moving edges reaches it in 30 steps).
    let build = || {
        let mut s = open_water();
        s.add_floater(Floater::sphere(1.5, 3.0, [60.0, 0.0, 52.0]))
            .unwrap();
        s
    };
    let (mut still, mut moving) = (build(), build());
    let mut shifted = 0;
    for k in 0..30 {
        still.step().unwrap();
        moving.step().unwrap();
        let angle = k as f32 * 0.7;
        let made = moving
            .follow(64.0 + 30.0 * angle.cos(), 56.0 + 30.0 * angle.sin())
            .unwrap();
        shifted += (made != [0, 0]) as usize;
        let (a, b) = (
            still.floaters().next().unwrap().1,
            moving.floaters().next().unwrap().1,
        );
        assert_eq!(a.position, b.position, "position at step {k}");
        assert_eq!(a.velocity, b.velocity, "velocity at step {k}");
        let p = a.position;
        assert_eq!(
            still.height_at(p.x, p.z).unwrap().to_bits(),
            moving.height_at(p.x, p.z).unwrap().to_bits()
        );
    }
    assert!(shifted >= 10, "the window moved only {shifted} times");
}

#[test]
fn follow_has_a_dead_zone_and_recentres() {
    let mut s = Surface::new(Params::with_size(65, 49)).unwrap();
    let dead = s.follow_dead_zone() as f32;
    assert_eq!(dead, 6.0);
    // Centre (32, 24): inside the dead zone nothing moves.
    for (x, z) in [(32.0, 24.0), (32.0 + dead, 24.0 - dead), (30.1, 29.9)] {
        assert_eq!(s.follow(x, z).unwrap(), [0, 0]);
    }
    assert_eq!(s.origin_cells(), [0, 0]);
    assert_eq!(s.follow(50.4, 24.0).unwrap(), [18, 0]);
    assert_eq!(s.follow(50.4, 10.0).unwrap(), [0, -14]);
    assert_eq!(s.origin(), [18.0, -14.0]);
    // The point is now within half a cell of the centre along both axes.
    let [ox, oz] = s.origin();
    assert!((ox + 32.0 - 50.4).abs() <= 0.5 && (oz + 24.0 - 10.0).abs() <= 0.5);
}

#[test]
fn parameters_and_forces_travel_with_the_water_and_the_frame_stays() {
    let mut p = Params::with_size(40, 36);
    p.boundary = Boundary::Absorbing { width: 6 };
    let fresh = Surface::new(p).unwrap();
    let mut s = Surface::new(p).unwrap();
    let g = s.grid();
    let at = |c, r| g.index(c, r);
    s.set_mass(at(20, 18), 6.0).unwrap();
    s.set_viscosity(at(21, 18), 0.3).unwrap();
    s.set_pinned(at(22, 18), true).unwrap();
    s.add_force(at(23, 18), [0.5, -1.0, 0.25]).unwrap();
    s.add_force_at(24.5, 18.0, [0.0, 2.0, 0.0]).unwrap();
    let e = SpringId {
        family: springwater::Family::E,
        origin: at(25, 18),
    };
    let custom = Spring {
        rest: 0.7,
        stiffness: 5.0,
    };
    s.set_spring(e, custom).unwrap();
    let forces_before: Vec<[f32; 3]> = (0..g.node_count())
        .map(|i| std::array::from_fn(|k| s.forces()[k][i]))
        .collect();

    s.shift(3, -2).unwrap();
    let moved = |c: usize, r: usize| at(c - 3, r + 2);
    assert_eq!(s.masses()[moved(20, 18)], 6.0);
    assert_eq!(s.viscosities()[moved(21, 18)], 0.3);
    assert!(s.pinned()[moved(22, 18)]);
    assert!(!s.pinned()[at(22, 18)]);
    let moved_spring = SpringId {
        family: springwater::Family::E,
        origin: moved(25, 18),
    };
    assert_eq!(s.spring(moved_spring), Some(custom));
    assert_ne!(s.spring(e), Some(custom));
    // Pending forces: every node's force is the one of the water now at its place.
    for r in 0..g.rows {
        for c in 0..g.cols {
            let i = at(c, r);
            let f: [f32; 3] = std::array::from_fn(|k| s.forces()[k][i]);
            let expected = match (c + 3, r.checked_sub(2)) {
                (sc, Some(sr)) if sc < g.cols => forces_before[at(sc, sr)],
                _ => [0.0; 3],
            };
            assert_eq!(f, expected, "force at ({c}, {r})");
        }
    }
    // The frame and the pinned ring stay at the window's edge.
    for i in 0..g.node_count() {
        let (c, r) = g.coords(i);
        let custom = [moved(20, 18), moved(21, 18), moved(22, 18)].contains(&i);
        if !custom {
            assert_eq!(s.masses()[i], fresh.masses()[i], "mass at ({c}, {r})");
            assert_eq!(
                s.viscosities()[i],
                fresh.viscosities()[i],
                "γ at ({c}, {r})"
            );
            assert_eq!(s.pinned()[i], fresh.pinned()[i], "pin at ({c}, {r})");
        }
    }
    // And the pending forces are applied by the next step, then cleared.
    s.step().unwrap();
    assert!(s.forces().iter().all(|f| f.iter().all(|&v| v == 0.0)));
}

#[test]
fn a_far_field_fills_the_incoming_strip() {
    let mut p = Params::with_size(32, 24);
    p.boundary = Boundary::Free;
    let mut s = Surface::new(p).unwrap();
    let swell = |x: f32, z: f32| 0.05 * (0.3 * x + 0.1 * z).sin();
    s.shift_with(0, 5, swell).unwrap();
    let g = s.grid();
    let [x, y, z] = s.positions();
    for i in 0..g.node_count() {
        let (_, r) = g.coords(i);
        let expected = if r >= g.rows - 5 {
            swell(x[i], z[i])
        } else {
            0.0
        };
        assert_eq!(y[i], expected);
    }
    assert_eq!(z[g.index(0, g.rows - 1)], (g.rows - 1 + 5) as f32);
}

#[test]
fn bad_input_changes_nothing() {
    let mut s = open_water();
    s.step_n(3).unwrap();
    s.shift(2, 2).unwrap();
    let before = s.clone();
    let same = |a: &Surface, b: &Surface| {
        a.positions() == b.positions()
            && a.velocities() == b.velocities()
            && a.origin_cells() == b.origin_cells()
    };
    for (dc, dr) in [(i32::MAX, 0), (0, i32::MIN), (16_000_000, 0)] {
        let err = s.shift(dc, dr).unwrap_err().to_string();
        assert!(err.contains("shift"), "{err}");
        assert!(same(&s, &before));
    }
    for (x, z) in [
        (f32::NAN, 0.0),
        (0.0, f32::INFINITY),
        (1e30, 0.0),
        (0.0, -1e30),
    ] {
        let err = s.follow(x, z).unwrap_err().to_string();
        assert!(err.contains("follow"), "{err}");
        assert!(same(&s, &before));
    }
    let err = s
        .shift_with(
            3,
            0,
            |x: f32, _z: f32| if x > 130.0 { f32::NAN } else { 0.0 },
        )
        .unwrap_err()
        .to_string();
    assert!(err.contains("far-field"), "{err}");
    assert!(same(&s, &before));
    for (dc, dr) in [
        (i64::MAX, 0),
        (0, i64::MIN),
        (-16_000_000, 0),
        (0, 15_728_643),
    ] {
        let err = s.rebase(dc, dr).unwrap_err().to_string();
        assert!(err.contains("rebase"), "{err}");
        assert!(same(&s, &before));
    }
    s.rebase(0, 0).unwrap();
    assert!(same(&s, &before));
    // A shift of zero is nothing; one past the grid replaces all of the water with calm.
    s.shift(0, 0).unwrap();
    assert!(same(&s, &before));
    for (dc, dr) in [(0, 500), (0, -113), (128, 0), (-500, 300)] {
        s.shift(dc, dr).unwrap();
    }
    assert_eq!(s.origin_cells(), [2 - 372, 2 + 687]);
    assert!(s.positions()[1].iter().all(|&y| y == 0.0));
    assert!(s.velocities().iter().all(|v| v.iter().all(|&v| v == 0.0)));
    s.step().unwrap();
    assert!(s.positions()[1].iter().all(|&y| y == 0.0));
}

#[test]
fn snapshots_keep_the_origin() {
    let mut s = open_water();
    s.step_n(4).unwrap();
    s.shift(-3, 9).unwrap();
    s.step_n(2).unwrap();
    let loaded = Surface::from_bytes(&s.to_bytes()).unwrap();
    assert_eq!(loaded.origin_cells(), [-3, 9]);
    assert_eq!(loaded.origin(), s.origin());
    assert_eq!(
        loaded.height_at(64.0, 56.0).unwrap(),
        s.height_at(64.0, 56.0).unwrap()
    );
    let (mut a, mut b) = (s, loaded);
    a.step_n(3).unwrap();
    b.step_n(3).unwrap();
    assert_eq!(a.to_bytes(), b.to_bytes());
    // A version 3 snapshot (no origin before the checksum) loads as a window that never
    // moved.
    let fresh = Surface::new(Params::with_size(6, 5)).unwrap().to_bytes();
    let v5 = common::as_version_5(&fresh, 30, 0);
    let mut v3 = [&v5[..v5.len() - 44], &[0u8; 4][..]].concat();
    v3[8..12].copy_from_slice(&3u32.to_le_bytes());
    let len = v3.len() as u64;
    v3[16..24].copy_from_slice(&len.to_le_bytes());
    common::fix_crc(&mut v3);
    let old = Surface::from_bytes(&v3).unwrap();
    assert_eq!(old.origin_cells(), [0, 0]);
    assert_eq!(
        old.positions(),
        Surface::from_bytes(&fresh).unwrap().positions()
    );
}

#[test]
fn a_body_left_behind_floats_on_calm_water() {
    let mut s = open_water();
    let id = s
        .add_floater(Floater::sphere(1.0, 1.5, [20.0, 0.0, 20.0]))
        .unwrap();
    s.step_n(10).unwrap();
    s.shift(60, 50).unwrap(); // the ball is now 40 cells outside the window
    assert!(!s.contains(20.0, 20.0));
    for _ in 0..200 {
        s.step().unwrap();
    }
    let b = s.floater(id).unwrap();
    assert!(
        b.position.is_finite() && b.position.y.abs() < 1.0,
        "{:?}",
        b.position
    );
    assert_eq!([b.position.x, b.position.z], [20.0, 20.0]);
    // Back in the window, it meets the water again.
    s.shift(-60, -50).unwrap();
    s.step().unwrap();
    assert!(s.floater(id).unwrap().water_force.y > 0.0);
}

#[test]
fn the_lod_follows_the_window() {
    use springwater::glam::Vec3;
    use springwater::mesh::{LodMesh, LodParams};
    let mut s = Surface::new(Params::with_size(129, 97)).unwrap();
    let eye = Vec3::new(30.0, 12.0, 70.0);
    let mut lod = LodMesh::new(LodParams::default()).unwrap();
    lod.update(&s.mesh_view(), eye);
    let before = lod.indices().to_vec();
    s.shift(40, -25).unwrap();
    assert_eq!(s.mesh_view().origin(), [40.0, -25.0]);
    // The same eye relative to the window draws the same triangles.
    let mut moved = LodMesh::new(LodParams::default()).unwrap();
    moved.update(&s.mesh_view(), eye + Vec3::new(40.0, 0.0, -25.0));
    assert_eq!(moved.indices(), &before[..]);
    // The eye where it was is now further from the window's far side: a different mesh.
    let mut stay = LodMesh::new(LodParams::default()).unwrap();
    stay.update(&s.mesh_view(), eye);
    assert_ne!(stay.indices(), &before[..]);
}

/// A calm window `cells` away from the water frame's origin, then a drop at `(64, 56)` of
/// the window, stepped 40 times.
fn far_run(cells: [i32; 2], rebase: bool) -> Surface {
    let mut p = Params::with_size(128, 112);
    p.boundary = Boundary::Absorbing { width: 8 };
    let mut s = Surface::new(p).unwrap();
    s.shift(cells[0], cells[1]).unwrap();
    if rebase {
        s.rebase(cells[0] as i64, cells[1] as i64).unwrap();
    }
    let [ox, oz] = s.origin();
    s.drop_at(ox + 64.0, oz + 56.0, 1.0, 2.0).unwrap();
    s.step_n(40).unwrap();
    s
}

#[test]
fn a_far_window_rebased_to_the_origin_steps_like_a_fresh_one() {
    let far = [100_000, -70_000];
    let near = far_run([0, 0], false);
    let rebased = far_run(far, true);
    assert_eq!(rebased.origin_cells(), [0, 0]);
    assert_eq!(rebased.positions(), near.positions());
    assert_eq!(rebased.velocities(), near.velocities());
    // Without the rebase, the same water 10^5 units out has coarse horizontal coordinates
    // (0.008 units apart), its spring forces lose digits, and its heights drift.
    let unrebased = far_run(far, false);
    let drift = (unrebased.positions()[1].iter())
        .zip(near.positions()[1])
        .map(|(a, b)| (a - b).abs())
        .fold(0.0f32, f32::max);
    assert!(
        drift > 1e-4,
        "far from the origin the heights drift by only {drift:e}"
    );
}

#[test]
fn a_rebase_moves_the_frame_and_nothing_else() {
    let mut s = open_water();
    s.add_floater(Floater::sphere(1.5, 3.0, [60.0, 0.0, 52.0]))
        .unwrap();
    s.step_n(12).unwrap();
    s.shift(5, 3).unwrap();
    let before = s.clone();
    s.rebase(40, -20).unwrap();
    assert_eq!(s.origin_cells(), [5 - 40, 3 + 20]);
    assert_eq!(s.origin(), [-35.0, 23.0]);
    assert_eq!(s.positions()[1], before.positions()[1], "heights");
    assert_eq!(s.velocities(), before.velocities(), "velocities");
    // Horizontal coordinates move by exactly (−40, +20) here: h is 1 and every value is
    // small, so re-expressing a node from its rest place rounds nothing.
    for k in [0, 2] {
        let d = if k == 0 { 40.0 } else { -20.0 };
        let (new, old) = (&s.positions()[k], &before.positions()[k]);
        for i in 0..s.node_count() {
            assert_eq!(new[i], old[i] - d, "coordinate {k} of node {i}");
        }
    }
    let (a, b) = (
        s.floaters().next().unwrap().1,
        before.floaters().next().unwrap().1,
    );
    assert_eq!(
        a.position.to_array(),
        [b.position.x - 40.0, b.position.y, b.position.z + 20.0]
    );
    assert_eq!(a.velocity, b.velocity);
    // A point near the body whose coordinates move exactly (multiples of 2^-10).
    let p = (b.position * 1024.0).round() / 1024.0;
    assert_eq!(
        s.height_at(p.x - 40.0, p.z + 20.0).unwrap().to_bits(),
        before.height_at(p.x, p.z).unwrap().to_bits()
    );
    // The window and everything in it keep working in the new frame, and back.
    s.step().unwrap();
    s.rebase(-40, 20).unwrap();
    assert_eq!(s.origin_cells(), [5, 3]);
    assert!(s.positions()[1].iter().all(|y| y.is_finite()));
}

#[test]
fn a_wake_follows_a_rebase() {
    let mut wake = springwater::disturb::Wake::new(vec![[100.0, 10.0], [140.0, 10.0]]).unwrap();
    let mut s = open_water();
    s.advance_with(0.25, &mut wake).unwrap(); // part way along its path
    let before = wake.position();
    s.rebase(40, -20).unwrap();
    wake.translate(-40.0, 20.0).unwrap();
    assert_eq!(wake.position(), [before[0] - 40.0, before[1] + 20.0]);
    assert!(wake.translate(f32::INFINITY, 0.0).is_err());
    assert_eq!(wake.position(), [before[0] - 40.0, before[1] + 20.0]);
}
