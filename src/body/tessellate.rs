//! Every shape as a closed mesh of small triangles: what the water presses on.
//!
//! A floating body meets the water through the triangles of its surface (the
//! `hydrostatics` module): each wet triangle is pressed where it is, and pushes the same
//! force back into the water there. The water is a lattice of nodes a cell apart, so a
//! triangle must not be much wider than a cell: a wider one would sample the waves only at
//! its corners and push a whole face's force into the four nodes under one point, a spring
//! far stiffer than the water's timestep can carry (see `crate::floater`). So when a body
//! is put on a surface, its shape is cut into triangles at most one cell across:
//!
//! * a sphere becomes an icosahedron whose faces are cut into `n²` triangles, every new
//!   vertex pushed out onto the sphere, and the whole scaled so that its volume is the
//!   sphere's exactly (the sphere's buoyancy, not the polyhedron's);
//! * a box gets a grid of squares at most a cell wide on each face, an even number along
//!   every edge, two triangles each with their diagonals alternating (mirror-symmetric);
//! * a hull mesh has every triangle cut into `n²` (each edge into `n` equal pieces), with
//!   `n` set by its longest edge, or is used as it is when its triangles are small enough.
//!
//! Points shared by neighbouring triangles are computed once from the same corners in the
//! same order, so the mesh stays closed to the bit and [`Hull::new`] validates it.
//! Everything is computed in `f64` with `+`, `−`, `×`, `÷` and `sqrt` only, so every
//! platform gets the same mesh.

use super::Hull;
use crate::error::Result;
use glam::DVec3;
use std::collections::HashMap;
use std::sync::Arc;

/// `hull` with each triangle longer than `cell` cut into `n²`, `n` set by its own longest
/// edge, so that the triangles are at most about `cell` across (fewer cuts if the whole
/// would pass [`Hull::MAX_TRIANGLES`]); the same hull when its triangles are small enough.
/// A cut triangle's new corners may lie on a neighbour's uncut edge: the surface covers
/// the hull exactly (in still water the pressure sums are Archimedes' to rounding), and on
/// waves the two sides of such an edge may sample the water a little differently.
pub(crate) fn cut(hull: &Arc<Hull>, cell: f32) -> Result<Arc<Hull>> {
    let cell = cell as f64;
    let lengths: Vec<f64> = hull
        .triangles()
        .iter()
        .map(|t| longest_edge(&t.map(|i| corner(hull.vertices(), i))))
        .collect();
    if lengths.iter().all(|&l| l <= cell) {
        return Ok(Arc::clone(hull));
    }
    // The same bound for every triangle, lowered until the whole fits.
    let mut limit = 1024;
    let count = |limit: usize| -> usize {
        lengths
            .iter()
            .map(|&l| (pieces(l, cell, 1).min(limit)).pow(2))
            .sum()
    };
    while limit > 1 && count(limit) > Hull::MAX_TRIANGLES {
        limit -= 1;
    }
    let corners: Vec<DVec3> = hull
        .vertices()
        .iter()
        .map(|v| DVec3::from(v.map(f64::from)))
        .collect();
    let n_of = |t: usize| pieces(lengths[t], cell, 1).min(limit);
    let (vertices, triangles) = subdivide(&corners, hull.triangles(), n_of, |p| p);
    Hull::cut_surface(&vertices, &triangles).map(Arc::new)
}

/// How many pieces to cut an edge of `length` into for cells of `cell`, with `triangles`
/// triangles each cut into the square of that.
fn pieces(length: f64, cell: f64, triangles: usize) -> usize {
    let wanted = (length / cell).ceil().max(1.0);
    let most = (Hull::MAX_TRIANGLES / triangles.max(1)) as f64;
    let mut n = wanted.min(1024.0) as usize;
    while n > 1 && (n * n) as f64 > most {
        n -= 1;
    }
    n
}

fn corner(vertices: &[[f32; 3]], i: u32) -> DVec3 {
    DVec3::from(vertices[i as usize].map(f64::from))
}

fn longest_edge([a, b, c]: &[DVec3; 3]) -> f64 {
    let square = |p: DVec3, q: DVec3| (p - q).length_squared();
    square(*a, *b)
        .max(square(*b, *c))
        .max(square(*c, *a))
        .sqrt()
}

/// Cuts triangle `t` into `n(t)²`: the points `(i a + j b + k c) / n`, `i + j + k = n`, each
/// computed from its corners in the order of their indices, so that two triangles sharing
/// an edge and cut alike make the same points there; `place` maps each point (onto a
/// sphere, say).
fn subdivide(
    corners: &[DVec3],
    triangles: &[[u32; 3]],
    n_of: impl Fn(usize) -> usize,
    place: impl Fn(DVec3) -> DVec3,
) -> (Vec<[f32; 3]>, Vec<[u32; 3]>) {
    let mut index: HashMap<([(u32, u32); 3], usize), u32> = HashMap::new();
    let mut vertices = Vec::new();
    let mut point = |weights: [(u32, u32); 3], n: usize| -> u32 {
        // The key: the corners with a non-zero weight, in the order of their indices.
        let mut key = weights;
        key.sort_unstable();
        for w in &mut key {
            if w.1 == 0 {
                *w = (u32::MAX, 0);
            }
        }
        key.sort_unstable();
        *index.entry((key, n)).or_insert_with(|| {
            let mut p = DVec3::ZERO;
            for &(i, w) in key.iter().filter(|w| w.1 > 0) {
                p += corners[i as usize] * w as f64;
            }
            let p = place(p / n as f64);
            vertices.push(p.as_vec3().to_array());
            (vertices.len() - 1) as u32
        })
    };
    let mut out = Vec::new();
    for (t, &[a, b, c]) in triangles.iter().enumerate() {
        let n = n_of(t);
        let m = n as u32;
        // Row j from corner a towards c, column i towards b.
        let at = |i: u32, j: u32| [(a, m - i - j), (b, i), (c, j)];
        for j in 0..m {
            for i in 0..m - j {
                let p = point(at(i, j), n);
                let q = point(at(i + 1, j), n);
                let r = point(at(i, j + 1), n);
                out.push([p, q, r]);
                if i + j + 1 < m {
                    let s = point(at(i + 1, j + 1), n);
                    out.push([q, s, r]);
                }
            }
        }
    }
    (vertices, out)
}

/// An icosphere of `radius` with triangles about `cell` across, scaled to the sphere's
/// volume.
pub(crate) fn sphere(radius: f64, cell: f64) -> Result<Hull> {
    // The icosahedron: the corners of three golden rectangles.
    let phi = (1.0 + 5.0f64.sqrt()) / 2.0;
    let corners: Vec<DVec3> = [
        [-1.0, phi, 0.0],
        [1.0, phi, 0.0],
        [-1.0, -phi, 0.0],
        [1.0, -phi, 0.0],
        [0.0, -1.0, phi],
        [0.0, 1.0, phi],
        [0.0, -1.0, -phi],
        [0.0, 1.0, -phi],
        [phi, 0.0, -1.0],
        [phi, 0.0, 1.0],
        [-phi, 0.0, -1.0],
        [-phi, 0.0, 1.0],
    ]
    .into_iter()
    .map(|p| DVec3::from(p).normalize() * radius)
    .collect();
    let faces: [[u32; 3]; 20] = [
        [0, 11, 5],
        [0, 5, 1],
        [0, 1, 7],
        [0, 7, 10],
        [0, 10, 11],
        [1, 5, 9],
        [5, 11, 4],
        [11, 10, 2],
        [10, 7, 6],
        [7, 1, 8],
        [3, 9, 4],
        [3, 4, 2],
        [3, 2, 6],
        [3, 6, 8],
        [3, 8, 9],
        [4, 9, 5],
        [2, 4, 11],
        [6, 2, 10],
        [8, 6, 7],
        [9, 8, 1],
    ];
    let edge = (corners[0] - corners[11]).length();
    let n = pieces(edge, cell, faces.len());
    let (vertices, triangles) = subdivide(&corners, &faces, |_| n, |p| p.normalize() * radius);
    let polyhedron = Hull::new(&vertices, &triangles)?;
    // Scale by the cube root of (sphere's volume / polyhedron's), by Newton's iteration
    // (only + − × ÷: the same bits everywhere).
    let ratio =
        4.0 / 3.0 * std::f64::consts::PI * radius * radius * radius / polyhedron.volume_f64();
    let mut s = 1.0;
    for _ in 0..8 {
        s = (2.0 * s + ratio / (s * s)) / 3.0;
    }
    let scaled: Vec<[f32; 3]> = vertices
        .iter()
        .map(|v| v.map(|c| (c as f64 * s) as f32))
        .collect();
    Hull::new(&scaled, &triangles)
}

/// A box of `half` extents with a grid of squares at most `cell` wide on every face.
pub(crate) fn cuboid(half: DVec3, cell: f64) -> Result<Hull> {
    // An even count of squares along every edge, their diagonals alternating like a
    // chequerboard's: each face is then its own mirror image across both of its middle
    // lines, and opposite faces are mirror images of each other, so on still water a box
    // gets no side force and no torque (a force at each triangle's centroid moves the
    // centre of pressure with the triangles' layout).
    let count = |e: f64| 2 * ((e / cell).ceil().clamp(1.0, 128.0)) as usize;
    let (nx, ny, nz) = (count(half.x), count(half.y), count(half.z));
    // The coordinate of grid line `i` of `n` along an axis of half extent `e`: the same
    // expression on every face, so shared edges get the same bits.
    let line = |e: f64, i: usize, n: usize| -e + 2.0 * e * (i as f64 / n as f64);
    let mut vertices: Vec<[f32; 3]> = Vec::new();
    let mut triangles: Vec<[u32; 3]> = Vec::new();
    // Each face: its fixed axis and side, and the two in-face axes ordered so that
    // (u × v) points out of the box.
    let faces: [(usize, f64, usize, usize); 6] = [
        (0, -1.0, 2, 1),
        (0, 1.0, 1, 2),
        (1, -1.0, 0, 2),
        (1, 1.0, 2, 0),
        (2, -1.0, 1, 0),
        (2, 1.0, 0, 1),
    ];
    let e = half.to_array();
    let n = [nx, ny, nz];
    for (axis, side, u, v) in faces {
        let first = vertices.len() as u32;
        for j in 0..=n[v] {
            for i in 0..=n[u] {
                let mut p = [0.0f64; 3];
                p[axis] = side * e[axis];
                p[u] = line(e[u], i, n[u]);
                p[v] = line(e[v], j, n[v]);
                vertices.push(p.map(|c| c as f32));
            }
        }
        let row = n[u] as u32 + 1;
        for j in 0..n[v] as u32 {
            for i in 0..n[u] as u32 {
                let k = first + j * row + i;
                if (i + j) % 2 == 0 {
                    triangles.push([k, k + 1, k + row + 1]);
                    triangles.push([k, k + row + 1, k + row]);
                } else {
                    triangles.push([k, k + 1, k + row]);
                    triangles.push([k + 1, k + row + 1, k + row]);
                }
            }
        }
    }
    weld(&mut vertices, &mut triangles);
    Hull::new(&vertices, &triangles)
}

/// Merges vertices at exactly the same position (the faces' shared edges), so that each
/// point's water is sampled once.
fn weld(vertices: &mut Vec<[f32; 3]>, triangles: &mut [[u32; 3]]) {
    let mut first: HashMap<[u32; 3], u32> = HashMap::new();
    let mut kept: Vec<[f32; 3]> = Vec::new();
    let map: Vec<u32> = vertices
        .iter()
        .map(|v| {
            *first.entry(v.map(f32::to_bits)).or_insert_with(|| {
                kept.push(*v);
                (kept.len() - 1) as u32
            })
        })
        .collect();
    for t in triangles.iter_mut() {
        *t = t.map(|i| map[i as usize]);
    }
    *vertices = kept;
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_sphere_keeps_its_volume_and_its_triangles_stay_small() {
        for (radius, cell) in [(0.5f64, 1.0f64), (1.0, 1.0), (3.0, 1.0), (2.0, 0.25)] {
            let mesh = sphere(radius, cell).unwrap();
            let exact = 4.0 / 3.0 * std::f32::consts::PI * (radius as f32).powi(3);
            assert!(
                (mesh.volume() - exact).abs() < 1e-5 * exact,
                "{radius} {cell}"
            );
            assert!(mesh.centroid().length() < 1e-5 * radius as f32);
            let longest = longest_of(&mesh);
            assert!(longest <= 1.3 * cell, "{radius} {cell}: {longest}");
        }
    }

    #[test]
    fn a_box_is_cut_into_cells_and_keeps_its_volume() {
        let mesh = cuboid(DVec3::new(2.5, 0.5, 1.0), 1.0).unwrap();
        assert_eq!(mesh.volume(), 10.0);
        assert!(longest_of(&mesh) <= 2f64.sqrt() + 1e-9);
        // 6 × 2, 2 × 2 and 6 × 2 squares on opposite faces (even counts), two triangles each.
        assert_eq!(mesh.triangles().len(), 2 * 2 * (12 + 4 + 12));
    }

    #[test]
    fn a_hull_with_long_edges_is_cut_and_one_with_short_ones_is_kept() {
        let hull = Arc::new(Hull::cuboid([3.0, 1.0, 1.0]).unwrap());
        let cut = cut(&hull, 1.0).unwrap();
        assert!((cut.volume() - hull.volume()).abs() < 1e-5 * hull.volume());
        assert!(longest_of(&cut) <= 1.0 + 1e-9);
        let kept = super::cut(&hull, 10.0).unwrap();
        assert!(Arc::ptr_eq(&kept, &hull));
    }

    fn longest_of(mesh: &Hull) -> f64 {
        mesh.triangles()
            .iter()
            .map(|t| longest_edge(&t.map(|i| corner(mesh.vertices(), i))))
            .fold(0.0, f64::max)
    }
}
