//! LOD and refraction on arbitrary grids, eyes, depths and surfaces.
//!
//! The LOD index buffer must be a valid, crack-free triangulation of the grid's rest
//! footprint: indices in range, no degenerate triangle, every triangle counter-clockwise
//! seen from +y, every directed edge used once, every edge either shared with a triangle
//! running it the other way or lying on the grid's border, and the triangles' areas adding
//! up to the footprint's. Normals, texture coordinates and Fresnel terms must be finite for
//! any finite surface and any eye (finite or not: a non-finite eye is an error, not NaN).

#![no_main]

use arbitrary::Arbitrary;
use glam::Vec3;
use libfuzzer_sys::fuzz_target;
use springwater::mesh::{compute_normals, LodMesh, LodParams, Normals};
use springwater::refraction::{refract, Refraction, RefractionParams};
use springwater::Grid;
use springwater::MeshView;
use std::collections::HashSet;

#[derive(Debug, Arbitrary)]
struct Input {
    cols: u8,
    rows: u8,
    spacing: u8,
    patch_log2: u8,
    levels: u8,
    first_range: f32,
    hysteresis: u8,
    /// Heights, scaled by `10^(height_scale/32 − 3)`, repeated over the grid.
    heights: Vec<i8>,
    height_scale: u8,
    /// In-plane jitter of the nodes, a fraction of a cell.
    jitter: Vec<i8>,
    eyes: Vec<[f32; 3]>,
    depth: f32,
    ior: f32,
}

fuzz_target!(|input: Input| {
    let (cols, rows) = (2 + input.cols as usize % 70, 2 + input.rows as usize % 70);
    let h = 10f32.powf(input.spacing as f32 / 64.0 - 2.0);
    let grid = Grid::new(cols, rows);
    let n = grid.node_count();
    let scale = 10f32.powf(input.height_scale as f32 / 32.0 - 3.0);
    let pick = |v: &[i8], i: usize| {
        if v.is_empty() {
            0.0
        } else {
            v[i % v.len()] as f32
        }
    };
    let (mut x, mut y, mut z) = (vec![0.0; n], vec![0.0; n], vec![0.0; n]);
    for i in 0..n {
        let (c, r) = grid.coords(i);
        x[i] = (c as f32 + pick(&input.jitter, i) / 300.0) * h;
        z[i] = (r as f32 + pick(&input.jitter, i + 7) / 300.0) * h;
        y[i] = pick(&input.heights, i) * scale;
    }
    let view = MeshView::new(grid, h, &x, &y, &z).expect("matching lengths");

    let mut normals = Normals::new();
    compute_normals(&view, &mut normals);
    for i in 0..n {
        let nv = normals.get(i);
        assert!(
            nv.is_finite() && (nv.length() - 1.0).abs() < 1e-3,
            "normal {i}: {nv}"
        );
    }

    let patch_cells = 1usize << (input.patch_log2 % 8);
    let lod_params = LodParams::default()
        .with_patch_cells(patch_cells)
        .with_first_range(input.first_range)
        .with_levels(1 + input.levels as u32 % 8)
        .with_hysteresis(input.hysteresis as f32 / 255.0);
    let mut lod = LodMesh::new(lod_params).ok();
    let bottom = RefractionParams {
        depth: input.depth,
        ior: input.ior,
    };
    let mut uv = Refraction::default();
    for &[ex, ey, ez] in input.eyes.iter().take(4) {
        let eye = Vec3::new(ex, ey, ez);
        if let Some(lod) = lod.as_mut() {
            lod.update(&view, eye);
            check_mesh(grid, lod.indices());
        }
        match refract(&view, &normals, eye, &bottom, &mut uv) {
            Ok(()) => {
                assert_eq!(uv.len(), n);
                for i in 0..n {
                    let (u, v, f) = (uv.u[i], uv.v[i], uv.fresnel[i]);
                    assert!(
                        u.is_finite() && v.is_finite() && f.is_finite(),
                        "node {i}: {u} {v} {f}"
                    );
                }
            }
            Err(_) => assert!(!eye.is_finite() || bottom.validate().is_err()),
        }
    }
});

/// A valid, crack-free, counter-clockwise triangulation of the grid's rest footprint.
fn check_mesh(grid: Grid, indices: &[u32]) {
    assert_eq!(indices.len() % 3, 0);
    let n = grid.node_count();
    let at = |i: u32| {
        assert!((i as usize) < n, "index {i} out of range");
        let (c, r) = grid.coords(i as usize);
        (c as i64, r as i64)
    };
    let mut edges = HashSet::new();
    let mut area2 = 0i64;
    for t in indices.chunks_exact(3) {
        let [a, b, c] = [t[0], t[1], t[2]];
        assert!(a != b && b != c && a != c, "degenerate triangle {t:?}");
        let (pa, pb, pc) = (at(a), at(b), at(c));
        // y of (b − a) × (c − a) with x = col, z = row: positive means CCW seen from +y.
        let cross = (pb.1 - pa.1) * (pc.0 - pa.0) - (pb.0 - pa.0) * (pc.1 - pa.1);
        assert!(
            cross > 0,
            "triangle {t:?} is not counter-clockwise seen from +y"
        );
        area2 += cross;
        for e in [(a, b), (b, c), (c, a)] {
            assert!(edges.insert(e), "directed edge {e:?} drawn twice");
        }
    }
    let (w, hgt) = (grid.cols as i64 - 1, grid.rows as i64 - 1);
    assert_eq!(
        area2,
        2 * w * hgt,
        "triangles do not cover the footprint exactly"
    );
    for &(a, b) in &edges {
        if edges.contains(&(b, a)) {
            continue;
        }
        let (pa, pb) = (at(a), at(b));
        let border = (pa.0 == pb.0 && (pa.0 == 0 || pa.0 == w))
            || (pa.1 == pb.1 && (pa.1 == 0 || pa.1 == hgt));
        assert!(
            border,
            "edge {pa:?}-{pb:?} is open inside the grid: a crack"
        );
    }
}
