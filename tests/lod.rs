//! The LOD index buffer: a watertight, counter-clockwise, exact cover of the grid for any
//! size, patch size and eye, with 2:1 balance, caching and hysteresis.

use glam::Vec3;
use proptest::prelude::*;
use springwater::mesh::{LodMesh, LodParams};
use springwater::Grid;
use springwater::MeshView;
use std::collections::HashMap;

/// A flat grid at rest, spacing `h`.
struct Flat {
    grid: Grid,
    h: f32,
    x: Vec<f32>,
    y: Vec<f32>,
    z: Vec<f32>,
}

impl Flat {
    fn new(cols: usize, rows: usize, h: f32) -> Self {
        let grid = Grid::new(cols, rows);
        let (mut x, mut z) = (Vec::new(), Vec::new());
        for i in 0..grid.node_count() {
            let (c, r) = grid.coords(i);
            x.push(c as f32 * h);
            z.push(r as f32 * h);
        }
        Self {
            grid,
            h,
            x,
            y: vec![0.0; grid.node_count()],
            z,
        }
    }

    fn view(&self) -> MeshView<'_> {
        MeshView::new(self.grid, self.h, &self.x, &self.y, &self.z).unwrap()
    }
}

/// Checks everything that makes the index buffer a crack-free cover of the grid, and
/// returns the number of triangles. Uses only the grid coordinates of the indices.
fn check_mesh(lod: &LodMesh, grid: Grid) -> usize {
    let idx = lod.indices();
    assert_eq!(idx.len() % 3, 0, "whole triangles");
    let tris = idx.len() / 3;
    assert_eq!(lod.triangle_levels().len(), tris, "one level per triangle");
    let n = grid.node_count();
    let at = |i: u32| {
        assert!((i as usize) < n, "index {i} out of range ({n} nodes)");
        let (c, r) = grid.coords(i as usize);
        (c as i64, r as i64)
    };
    let mut area2 = 0i64;
    let mut edges: HashMap<(u32, u32), u32> = HashMap::with_capacity(idx.len());
    for t in idx.chunks_exact(3) {
        let (a, b, c) = (at(t[0]), at(t[1]), at(t[2]));
        // y of (b − a) × (c − a) with x = col, z = row: > 0 is counter-clockwise from +y.
        let up = (b.1 - a.1) * (c.0 - a.0) - (b.0 - a.0) * (c.1 - a.1);
        assert!(up != 0, "degenerate triangle {t:?}");
        assert!(up > 0, "clockwise triangle {t:?}");
        area2 += up;
        for (p, q) in [(t[0], t[1]), (t[1], t[2]), (t[2], t[0])] {
            *edges.entry((p, q)).or_insert(0) += 1;
        }
    }
    let cells = ((grid.cols - 1) * (grid.rows - 1)) as i64;
    assert_eq!(
        area2,
        2 * cells,
        "triangles cover the grid's area exactly once"
    );
    let (last_c, last_r) = (grid.cols as i64 - 1, grid.rows as i64 - 1);
    let mut border = 0i64;
    for (&(p, q), &count) in &edges {
        assert_eq!(count, 1, "directed edge {p}->{q} used {count} times");
        if edges.contains_key(&(q, p)) {
            continue;
        }
        let (a, b) = (at(p), at(q));
        let on_border = (a.0 == 0 && b.0 == 0)
            || (a.1 == 0 && b.1 == 0)
            || (a.0 == last_c && b.0 == last_c)
            || (a.1 == last_r && b.1 == last_r);
        assert!(
            on_border,
            "interior edge {a:?}->{b:?} used only once: a crack or T-junction"
        );
        border += (a.0 - b.0).abs() + (a.1 - b.1).abs();
    }
    assert_eq!(border, 2 * (last_c + last_r), "the border is closed");
    tris
}

fn check_balance(lod: &LodMesh) {
    let [across, down] = lod.patch_grid();
    let l = lod.patch_levels();
    assert_eq!(l.len(), across * down);
    for r in 0..down {
        for c in 0..across {
            let i = r * across + c;
            assert!(l[i] < lod.params().levels as u8, "level within range");
            if c + 1 < across {
                assert!(
                    l[i].abs_diff(l[i + 1]) <= 1,
                    "2:1 balance across {:?}",
                    (c, r)
                );
            }
            if r + 1 < down {
                assert!(
                    l[i].abs_diff(l[i + across]) <= 1,
                    "2:1 balance down {:?}",
                    (c, r)
                );
            }
        }
    }
}

/// The plain grid: two triangles per cell, as sets of rotation-normalised triangles.
fn full_grid(grid: Grid) -> Vec<[u32; 3]> {
    let mut out = Vec::new();
    for r in 0..grid.rows - 1 {
        for c in 0..grid.cols - 1 {
            let i = |c: usize, r: usize| grid.index(c, r) as u32;
            out.push(normalise([i(c, r), i(c, r + 1), i(c + 1, r)]));
            out.push(normalise([i(c + 1, r), i(c, r + 1), i(c + 1, r + 1)]));
        }
    }
    out.sort();
    out
}

fn normalise(t: [u32; 3]) -> [u32; 3] {
    let k = (0..3).min_by_key(|&k| t[k]).unwrap();
    [t[k], t[(k + 1) % 3], t[(k + 2) % 3]]
}

fn triangles(lod: &LodMesh) -> Vec<[u32; 3]> {
    let mut v: Vec<[u32; 3]> = lod
        .indices()
        .chunks_exact(3)
        .map(|t| normalise([t[0], t[1], t[2]]))
        .collect();
    v.sort();
    v
}

fn params_strategy() -> impl Strategy<Value = LodParams> {
    (0u32..6, 1.0f32..80.0, 0.0f32..0.5).prop_flat_map(|(k, range, hys)| {
        (1..=k + 1).prop_map(move |levels| {
            LodParams::default()
                .with_patch_cells(1 << k)
                .with_first_range(range)
                .with_levels(levels)
                .with_hysteresis(hys)
        })
    })
}

/// Eyes inside, outside, far, grazing, and exactly at a range boundary above a node.
fn eye_strategy(cols: usize, rows: usize, range: f32) -> impl Strategy<Value = Vec3> {
    let (w, d) = ((cols - 1) as f32, (rows - 1) as f32);
    prop_oneof![
        (0.0..=w, 0.1f32..50.0, 0.0..=d).prop_map(|(x, y, z)| Vec3::new(x, y, z)),
        (-2.0 * w..3.0 * w, -20.0f32..60.0, -2.0 * d..3.0 * d)
            .prop_map(|(x, y, z)| Vec3::new(x, y, z)),
        (-1e5f32..1e5, -1e5f32..1e5, -1e5f32..1e5).prop_map(|(x, y, z)| Vec3::new(x, y, z)),
        (0.0..=w, 0.0..=d).prop_map(|(x, z)| Vec3::new(x, 0.0, z)),
        (0..=cols - 1, 0..=rows - 1, 0i32..6)
            .prop_map(move |(c, r, l)| { Vec3::new(c as f32, range * 2f32.powi(l), r as f32) }),
    ]
}

fn case() -> impl Strategy<Value = (usize, usize, LodParams, Vec3)> {
    (2usize..300, 2usize..300, params_strategy())
        .prop_flat_map(|(c, r, p)| (Just(c), Just(r), Just(p), eye_strategy(c, r, p.first_range)))
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(96))]

    #[test]
    fn any_grid_any_eye_is_a_crack_free_ccw_cover((cols, rows, params, eye) in case()) {
        let flat = Flat::new(cols, rows, 1.0);
        let mut lod = LodMesh::new(params).unwrap();
        prop_assert!(lod.update(&flat.view(), eye));
        check_mesh(&lod, flat.grid);
        check_balance(&lod);
        // Same eye again: cached.
        prop_assert!(!lod.update(&flat.view(), eye));
        // A fresh mesh with the same eye builds the same buffer.
        let mut again = LodMesh::new(params).unwrap();
        again.update(&flat.view(), eye);
        prop_assert_eq!(again.indices(), lod.indices());
        prop_assert_eq!(again.triangle_levels(), lod.triangle_levels());
    }

    /// Arbitrary requested levels stress every stitching case, not only the ones distance
    /// rings produce.
    #[test]
    fn arbitrary_levels_stitch_without_cracks(
        (cols, rows, k, seed) in (2usize..200, 2usize..200, 0u32..6, any::<u64>())
    ) {
        let params = LodParams::default().with_patch_cells(1 << k).with_levels(k + 1);
        let flat = Flat::new(cols, rows, 1.0);
        let mut lod = LodMesh::new(params).unwrap();
        let p = 1usize << k;
        let n = (cols - 1).div_ceil(p) * (rows - 1).div_ceil(p);
        let mut state = seed | 1;
        let wanted: Vec<u8> = (0..n).map(|_| {
            state ^= state << 13; state ^= state >> 7; state ^= state << 17;
            (state % (k as u64 + 1)) as u8
        }).collect();
        lod.set_levels(&flat.view(), &wanted).unwrap();
        check_mesh(&lod, flat.grid);
        check_balance(&lod);
        // Balancing only ever refines.
        for (got, want) in lod.patch_levels().iter().zip(&wanted) {
            prop_assert!(got <= want);
        }
    }

    #[test]
    fn level_zero_everywhere_is_exactly_the_full_grid(
        (cols, rows, k) in (2usize..120, 2usize..120, 0u32..6)
    ) {
        let flat = Flat::new(cols, rows, 1.0);
        let mut lod = LodMesh::new(LodParams::default().with_patch_cells(1 << k).with_levels(1)).unwrap();
        lod.update(&flat.view(), Vec3::new(1e4, 1e4, 1e4));
        prop_assert!(lod.patch_levels().iter().all(|&l| l == 0));
        prop_assert_eq!(triangles(&lod), full_grid(flat.grid));
    }
}

#[test]
fn smallest_grid_is_two_triangles() {
    let flat = Flat::new(2, 2, 1.0);
    let mut lod = LodMesh::new(LodParams::default()).unwrap();
    lod.update(&flat.view(), Vec3::new(100.0, 100.0, 100.0));
    assert_eq!(check_mesh(&lod, flat.grid), 2);
}

#[test]
fn far_patches_are_coarser_and_near_ones_full() {
    let flat = Flat::new(257, 257, 1.0);
    let mut lod = LodMesh::new(LodParams::default()).unwrap();
    lod.update(&flat.view(), Vec3::new(0.0, 5.0, 0.0));
    let l = lod.patch_levels();
    let [across, _] = lod.patch_grid();
    assert_eq!(l[0], 0, "the patch under the eye has full detail");
    assert_eq!(
        *l.last().unwrap(),
        4,
        "the far corner is at the coarsest level"
    );
    assert!(l[across - 1] > l[1]);
    let tris = check_mesh(&lod, flat.grid);
    assert!(
        tris * 4 < 2 * 256 * 256,
        "far-away detail dropped: {tris} triangles"
    );
}

#[test]
fn spacing_scales_the_ranges() {
    // Same grid, spacing 2: every patch is twice as far away in world units.
    let (a, b) = (Flat::new(129, 129, 1.0), Flat::new(129, 129, 2.0));
    let mut la = LodMesh::new(LodParams::default()).unwrap();
    let mut lb = LodMesh::new(LodParams::default()).unwrap();
    la.update(&a.view(), Vec3::new(0.0, 1.0, 0.0));
    lb.update(&b.view(), Vec3::new(0.0, 1.0, 0.0));
    let (sa, sb): (u32, u32) = (
        la.patch_levels().iter().map(|&l| l as u32).sum(),
        lb.patch_levels().iter().map(|&l| l as u32).sum(),
    );
    assert!(sb > sa, "wider spacing, coarser mesh ({sb} vs {sa})");
    check_mesh(&lb, b.grid);
}

/// The patch whose footprint starts at x = 0 is at distance `y` from an eye right above
/// it; put the eye at a range boundary and jitter it.
#[test]
fn hysteresis_keeps_the_mesh_at_a_range_boundary() {
    let flat = Flat::new(65, 65, 1.0);
    let params = LodParams::default()
        .with_first_range(8.0)
        .with_hysteresis(0.1);
    let mut lod = LodMesh::new(params).unwrap();
    let at = |y: f32| Vec3::new(0.0, y, 0.0);
    lod.update(&flat.view(), at(16.0)); // exactly at the 1→2 boundary: level 2
    assert_eq!(lod.patch_levels()[0], 2);
    let built = lod.indices().to_vec();
    for y in [15.9, 16.1, 15.0, 17.0, 14.6, 16.0] {
        assert!(!lod.update(&flat.view(), at(y)), "no rebuild at y = {y}");
        assert_eq!(lod.indices(), &built[..]);
    }
    // Well past the band: it does change.
    assert!(lod.update(&flat.view(), at(14.0)));
    assert_eq!(lod.patch_levels()[0], 1);
    // And back up only beyond 16·1.1.
    assert!(!lod.update(&flat.view(), at(17.5)));
    assert!(lod.update(&flat.view(), at(17.7)));
    assert_eq!(lod.patch_levels()[0], 2);
}

#[test]
fn without_hysteresis_a_boundary_flips_the_mesh() {
    let flat = Flat::new(65, 65, 1.0);
    let params = LodParams::default()
        .with_first_range(8.0)
        .with_hysteresis(0.0);
    let mut lod = LodMesh::new(params).unwrap();
    lod.update(&flat.view(), Vec3::new(0.0, 16.0, 0.0));
    assert!(lod.update(&flat.view(), Vec3::new(0.0, 15.9, 0.0)));
    assert!(lod.update(&flat.view(), Vec3::new(0.0, 16.0, 0.0)));
}

#[test]
fn a_new_grid_shape_rebuilds() {
    let (a, b) = (Flat::new(40, 30, 1.0), Flat::new(41, 30, 1.0));
    let mut lod = LodMesh::new(LodParams::default()).unwrap();
    let eye = Vec3::new(5.0, 5.0, 5.0);
    assert!(lod.update(&a.view(), eye));
    assert!(lod.update(&b.view(), eye));
    check_mesh(&lod, b.grid);
    assert!(lod.update(&a.view(), eye));
    check_mesh(&lod, a.grid);
}

#[test]
fn a_non_finite_eye_keeps_the_mesh() {
    let flat = Flat::new(100, 60, 1.0);
    let mut lod = LodMesh::new(LodParams::default()).unwrap();
    lod.update(&flat.view(), Vec3::new(5.0, 5.0, 5.0));
    let before = lod.indices().to_vec();
    assert!(!lod.update(&flat.view(), Vec3::new(f32::NAN, 5.0, 5.0)));
    assert!(!lod.update(&flat.view(), Vec3::new(0.0, f32::INFINITY, 5.0)));
    assert_eq!(lod.indices(), &before[..]);
    let mut fresh = LodMesh::new(LodParams::default()).unwrap();
    fresh.update(&flat.view(), Vec3::NAN);
    check_mesh(&fresh, flat.grid);
}

#[test]
fn the_wave_state_does_not_matter() {
    // Levels come from the rest footprint, so a moving surface reuses the cached buffer.
    let mut flat = Flat::new(50, 50, 1.0);
    let mut lod = LodMesh::new(LodParams::default()).unwrap();
    let eye = Vec3::new(10.0, 3.0, 10.0);
    lod.update(&flat.view(), eye);
    flat.y
        .iter_mut()
        .enumerate()
        .for_each(|(i, y)| *y = (i as f32 * 0.1).sin());
    assert!(!lod.update(&flat.view(), eye));
}

#[test]
fn parameters_are_validated() {
    let ok = LodParams::default();
    assert!(ok.validate().is_ok());
    for bad in [
        ok.with_patch_cells(0),
        ok.with_patch_cells(12),
        ok.with_patch_cells(8192),
        ok.with_first_range(0.0),
        ok.with_first_range(f32::NAN),
        ok.with_levels(0),
        ok.with_levels(6),
        ok.with_hysteresis(-0.1),
        ok.with_hysteresis(1.5),
        ok.with_hysteresis(f32::INFINITY),
    ] {
        let err = LodMesh::new(bad).unwrap_err();
        assert!(!err.to_string().is_empty());
    }
    assert!(LodMesh::new(ok.with_patch_cells(1).with_levels(1)).is_ok());
    let flat = Flat::new(20, 20, 1.0);
    let mut lod = LodMesh::new(ok).unwrap();
    assert!(lod.set_levels(&flat.view(), &[0; 3]).is_err());
}

#[test]
fn level_for_distance_doubles_each_range() {
    let p = LodParams::default().with_first_range(10.0).with_levels(5);
    let cases = [
        (0.0, 0),
        (9.99, 0),
        (10.0, 1),
        (19.9, 1),
        (20.0, 2),
        (40.0, 3),
        (80.0, 4),
        (1e30, 4),
    ];
    for (d, l) in cases {
        assert_eq!(p.level_for_distance(d), l, "distance {d}");
    }
    assert_eq!(p.level_for_distance(f32::NAN), 0);
    assert_eq!(p.level_for_distance(f32::INFINITY), 4);
}

#[test]
fn set_levels_caches_caps_and_balances() {
    let flat = Flat::new(65, 33, 1.0); // 4 × 2 patches of 16 cells
    let mut lod = LodMesh::new(LodParams::default()).unwrap();
    assert!(lod
        .set_levels(&flat.view(), &[0, 0, 0, 0, 0, 0, 0, 9])
        .unwrap());
    // 9 is capped at 4, then balanced down to 1 next to its level-0 neighbours.
    assert_eq!(lod.patch_levels(), &[0, 0, 0, 0, 0, 0, 0, 1]);
    assert!(
        !lod.set_levels(&flat.view(), &[0, 0, 0, 0, 0, 0, 0, 1])
            .unwrap(),
        "same levels: cached"
    );
    assert!(lod.set_levels(&flat.view(), &[0; 8]).unwrap());
    check_mesh(&lod, flat.grid);
    // A wrong count is refused and changes nothing.
    assert!(lod.set_levels(&flat.view(), &[0; 3]).is_err());
    assert_eq!(lod.patch_levels(), &[0; 8]);
}
