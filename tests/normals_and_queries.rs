//! Per-node normals (against planes, the scalar twin and the triangle winding) and the
//! point queries game code calls (height, normal, velocity at any world (x, z)).

use glam::Vec3;
use proptest::prelude::*;
use springwater::internals::compute_normals_scalar;
use springwater::mesh::{compute_normals, Normals};
use springwater::MeshView;
use springwater::{Error, Grid, Params, Surface};

fn rest(cols: usize, rows: usize, h: f32) -> [Vec<f32>; 3] {
    let grid = Grid::new(cols, rows);
    let mut p = [Vec::new(), vec![0.0; grid.node_count()], Vec::new()];
    for i in 0..grid.node_count() {
        let (c, r) = grid.coords(i);
        p[0].push(c as f32 * h);
        p[2].push(r as f32 * h);
    }
    p
}

fn normals_of(cols: usize, rows: usize, h: f32, p: &[Vec<f32>; 3]) -> Normals {
    let view = MeshView::new(Grid::new(cols, rows), h, &p[0], &p[1], &p[2]).unwrap();
    let mut n = Normals::new();
    compute_normals(&view, &mut n);
    n
}

#[test]
fn flat_water_points_straight_up() {
    let p = rest(37, 5, 0.25);
    let n = normals_of(37, 5, 0.25, &p);
    assert_eq!(n.len(), 37 * 5);
    for i in 0..n.len() {
        assert_eq!(n.get(i), Vec3::Y, "node {i}");
    }
}

#[test]
fn a_collapsed_surface_still_gives_unit_normals() {
    let (cols, rows) = (20, 3);
    let p = [
        vec![1.0; cols * rows],
        vec![2.0; cols * rows],
        vec![3.0; cols * rows],
    ];
    let n = normals_of(cols, rows, 1.0, &p);
    for i in 0..n.len() {
        assert_eq!(n.get(i), Vec3::Y, "node {i}");
    }
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(96))]

    /// On a tilted plane y = a·x + b·z every node, border included, has the plane's normal.
    #[test]
    fn a_plane_has_its_normal_everywhere(
        (cols, rows) in (2usize..50, 2usize..12),
        a in -3.0f32..3.0,
        b in -3.0f32..3.0,
        h in 0.1f32..4.0,
    ) {
        let mut p = rest(cols, rows, h);
        p[1] = p[0].iter().zip(&p[2]).map(|(x, z)| a * x + b * z).collect();
        let n = normals_of(cols, rows, h, &p);
        let expected = Vec3::new(-a, 1.0, -b).normalize();
        for i in 0..n.len() {
            prop_assert!((n.get(i) - expected).length() < 1e-5, "node {}: {} vs {}", i, n.get(i), expected);
        }
    }

    /// The lane kernel and the scalar twin agree bitwise on any surface.
    #[test]
    fn lanes_match_the_scalar_twin(
        (cols, rows) in (2usize..70, 2usize..6),
        vals in prop::collection::vec(-2.0f32..2.0, 8..40),
    ) {
        let mut p = rest(cols, rows, 1.0);
        for i in 0..cols * rows {
            p[0][i] += 0.2 * vals[i % vals.len()];
            p[1][i] = vals[(3 * i + 1) % vals.len()];
            p[2][i] -= 0.2 * vals[(7 * i + 2) % vals.len()];
        }
        let lanes = normals_of(cols, rows, 1.0, &p);
        let view = MeshView::new(Grid::new(cols, rows), 1.0, &p[0], &p[1], &p[2]).unwrap();
        let mut scalar = Normals::new();
        compute_normals_scalar(&view, &mut scalar);
        for i in 0..cols * rows {
            prop_assert_eq!(lanes.x[i].to_bits(), scalar.x[i].to_bits(), "x at node {}", i);
            prop_assert_eq!(lanes.y[i].to_bits(), scalar.y[i].to_bits(), "y at node {}", i);
            prop_assert_eq!(lanes.z[i].to_bits(), scalar.z[i].to_bits(), "z at node {}", i);
            let len = lanes.get(i).length();
            prop_assert!((len - 1.0).abs() < 1e-5, "unit length at node {}: {}", i, len);
        }
    }
}

#[test]
fn normals_lean_away_from_a_crest_and_match_the_triangle_winding() {
    let mut water = Surface::new(Params::with_size(41, 41)).unwrap();
    water.drop_at(20.0, 20.0, 2.0, 4.0).unwrap();
    let view = water.mesh_view();
    let mut n = Normals::new();
    compute_normals(&view, &mut n);
    let g = water.grid();
    assert!(n.get(g.index(23, 20)).x > 0.1, "east slope leans east");
    assert!(n.get(g.index(17, 20)).x < -0.1, "west slope leans west");
    assert!(n.get(g.index(20, 23)).z > 0.1, "south slope leans +z");
    assert!(n.get(g.index(20, 17)).z < -0.1, "north slope leans -z");
    // The face normal of the counter-clockwise triangle (c,r), (c,r+1), (c+1,r) points the
    // same way as the node normal.
    for (c, r) in [(18, 18), (22, 19), (20, 20), (5, 30)] {
        let (a, b, d) = (
            view.position(g.index(c, r)),
            view.position(g.index(c, r + 1)),
            view.position(g.index(c + 1, r)),
        );
        let face = (b - a).cross(d - a).normalize();
        assert!(face.y > 0.0);
        assert!(face.dot(n.get(g.index(c, r))) > 0.9, "cell ({c}, {r})");
    }
}

/// A surface with waves and velocities, spacing 0.5.
fn busy() -> Surface {
    let mut p = Params::with_size(37, 23);
    p.spacing = 0.5;
    let mut water = Surface::new(p).unwrap();
    water.drop_at(12.0, 10.0, 1.0, 3.0).unwrap();
    water.drop_at(25.0, 15.0, -0.8, 2.5).unwrap();
    for _ in 0..15 {
        water.step().unwrap();
    }
    water
}

#[test]
fn queries_at_nodes_return_the_node_values() {
    let water = busy();
    let g = water.grid();
    let h = water.params().spacing;
    let [_, y, _] = water.positions();
    let [vx, vy, vz] = water.velocities();
    let view = water.mesh_view();
    for i in (0..g.node_count()).step_by(7).chain([g.node_count() - 1]) {
        let (c, r) = g.coords(i);
        let (x, z) = (c as f32 * h, r as f32 * h);
        assert!(
            (water.height_at(x, z).unwrap() - y[i]).abs() < 1e-6,
            "node {i}"
        );
        // Per second: the lattice's velocity (per unit of model time) times the time scale.
        let v = water.velocity_at(x, z).unwrap();
        let per_second = Vec3::new(vx[i], vy[i], vz[i]) * water.params().time_scale;
        assert!((v - per_second).length() < 1e-5, "node {i}");
        let n = water.normal_at(x, z).unwrap();
        assert!((n - view.node_normal(c, r)).length() < 1e-6, "node {i}");
    }
    assert!(
        water.velocities()[1].iter().any(|v| v.abs() > 1e-3),
        "the test surface moves"
    );
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(64))]

    /// Between nodes: the bilinear blend of the cell's four corners, computed here in f64.
    #[test]
    fn queries_interpolate_bilinearly(fx in 0.0f32..=1.0, fz in 0.0f32..=1.0) {
        let water = busy();
        let g = water.grid();
        let h = water.params().spacing;
        let (x, z) = (fx * (g.cols - 1) as f32 * h, fz * (g.rows - 1) as f32 * h);
        let (col, row) = ((x / h) as f64, (z / h) as f64);
        let c = (col.floor() as usize).min(g.cols - 2);
        let r = (row.floor() as usize).min(g.rows - 2);
        let (tx, tz) = (col - c as f64, row - r as f64);
        let blend = |s: &[f32]| {
            let v = |c: usize, r: usize| s[g.index(c, r)] as f64;
            (1.0 - tx) * (1.0 - tz) * v(c, r) + tx * (1.0 - tz) * v(c + 1, r)
                + (1.0 - tx) * tz * v(c, r + 1) + tx * tz * v(c + 1, r + 1)
        };
        let height = water.height_at(x, z).unwrap() as f64;
        prop_assert!((height - blend(water.positions()[1])).abs() < 1e-5);
        let vel = water.velocity_at(x, z).unwrap();
        let scale = water.params().time_scale as f64;
        for (k, got) in [vel.x, vel.y, vel.z].into_iter().enumerate() {
            prop_assert!((got as f64 - scale * blend(water.velocities()[k])).abs() < 1e-4);
        }
        let n = water.normal_at(x, z).unwrap();
        prop_assert!((n.length() - 1.0).abs() < 1e-5 && n.y > 0.0);
        // Batched queries give the same answers.
        let mut hs = Vec::new();
        water.heights_at(&[[x, z], [0.0, 0.0]], &mut hs).unwrap();
        prop_assert_eq!(hs[0], height as f32);
        let mut ns = Vec::new();
        water.normals_at(&[[x, z]], &mut ns).unwrap();
        prop_assert_eq!(ns[0], n);
        let mut vs = Vec::new();
        water.velocities_at(&[[x, z]], &mut vs).unwrap();
        prop_assert_eq!(vs[0], vel);
        // So does the per-point batch, which answers every point it can.
        let mut each = Vec::new();
        water.samples_at(&[[x, z], [-1.0, z], [x, f32::NAN]], &mut each);
        let one = each[0].expect("inside the footprint");
        prop_assert_eq!((one.height, one.normal, one.velocity), (height as f32, n, vel));
        prop_assert_eq!(water.sample_at(x, z).unwrap(), one);
        prop_assert!(each[1].is_none() && each[2].is_none());
    }
}

#[test]
fn a_midpoint_is_the_average_of_its_two_nodes() {
    let water = busy();
    let g = water.grid();
    let [_, y, _] = water.positions();
    let (a, b) = (y[g.index(12, 10)], y[g.index(13, 10)]);
    let mid = water.height_at(12.5 * 0.5, 10.0 * 0.5).unwrap();
    assert!((mid - (a + b) / 2.0).abs() < 1e-6);
    assert!(a != b, "the test needs a slope here");
}

#[test]
fn points_outside_or_not_finite_are_refused_and_batches_are_all_or_nothing() {
    let water = busy();
    let (w, l) = (36.0 * 0.5, 22.0 * 0.5);
    assert!(water.contains(0.0, 0.0) && water.contains(w, l));
    for (x, z) in [
        (-0.01, 1.0),
        (w + 0.01, 1.0),
        (1.0, -1.0),
        (1.0, l + 1.0),
        (f32::NAN, 1.0),
        (1.0, f32::INFINITY),
    ] {
        assert!(!water.contains(x, z));
        assert!(water.height_at(x, z).is_err(), "({x}, {z})");
        assert!(water.normal_at(x, z).is_err());
        assert!(water.velocity_at(x, z).is_err());
    }
    assert!(matches!(
        water.height_at(100.0, 1.0),
        Err(Error::OutsideGrid { .. })
    ));
    let mut out = vec![42.0];
    assert!(water
        .heights_at(&[[1.0, 1.0], [1.0, 99.0]], &mut out)
        .is_err());
    assert_eq!(out, vec![42.0], "nothing written on error");
    water.heights_at(&[[1.0, 1.0], [w, l]], &mut out).unwrap();
    assert_eq!(out.len(), 2);

    // Point by point: the points off the water are None, the others answered, in order.
    let points = [
        [1.0, 1.0],
        [1.0, 99.0],
        [f32::NAN, 0.0],
        [w, l],
        [-0.01, 1.0],
    ];
    let mut each = vec![None; 9];
    water.samples_at(&points, &mut each);
    assert_eq!(each.len(), points.len());
    let found: Vec<bool> = each.iter().map(Option::is_some).collect();
    assert_eq!(found, [true, false, false, true, false]);
    assert_eq!(each[3].unwrap().height, water.height_at(w, l).unwrap());
    assert!(water.sample_at(1.0, 99.0).is_err());
}
