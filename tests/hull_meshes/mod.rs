//! Meshes and an independent clipper for the hull tests.
#![allow(dead_code)]

use springwater::body::Hull;
use springwater::glam::{DVec3, Quat, Vec3};

/// A sphere-like mesh of radius `r`: an octahedron whose faces are cut into `4^level`
/// triangles, vertices pushed out onto the sphere (shared, so the mesh is closed).
pub fn sphere_mesh(r: f32, level: u32) -> (Vec<[f32; 3]>, Vec<[u32; 3]>) {
    let mut vertices: Vec<DVec3> = vec![
        DVec3::X,
        DVec3::NEG_X,
        DVec3::Y,
        DVec3::NEG_Y,
        DVec3::Z,
        DVec3::NEG_Z,
    ];
    let mut triangles: Vec<[u32; 3]> = vec![
        [0, 2, 4],
        [2, 1, 4],
        [1, 3, 4],
        [3, 0, 4],
        [2, 0, 5],
        [1, 2, 5],
        [3, 1, 5],
        [0, 3, 5],
    ];
    for _ in 0..level {
        let mut midpoints = std::collections::HashMap::new();
        let mut next = Vec::new();
        for [a, b, c] in triangles {
            let mut mid = |i: u32, j: u32| {
                *midpoints.entry((i.min(j), i.max(j))).or_insert_with(|| {
                    let p = (vertices[i as usize] + vertices[j as usize]).normalize();
                    vertices.push(p);
                    vertices.len() as u32 - 1
                })
            };
            let (ab, bc, ca) = (mid(a, b), mid(b, c), mid(c, a));
            next.extend([[a, ab, ca], [ab, b, bc], [ca, bc, c], [ab, bc, ca]]);
        }
        triangles = next;
    }
    let vertices = vertices
        .iter()
        .map(|v| (*v * r as f64).as_vec3().to_array())
        .collect();
    (vertices, triangles)
}

/// The hull's triangles in world coordinates (f64) for a pose.
pub fn world_triangles(hull: &Hull, position: Vec3, orientation: Quat) -> Vec<[DVec3; 3]> {
    let q = orientation.as_dquat().normalize();
    let p = position.as_dvec3();
    let place = |i: u32| p + q * DVec3::from(hull.vertices()[i as usize].map(f64::from));
    hull.triangles().iter().map(|t| t.map(place)).collect()
}

/// Volume and centroid of the part of a convex polyhedron (its triangles) where
/// `inside(p) > 0`, for an affine `inside`: each face clipped (Sutherland–Hodgman), the cut
/// closed by a lid polygon through the cut points sorted by angle, then tetrahedra from
/// the mean of the vertices. Independent of the library's pressure integrals.
pub fn clip_convex(tris: &[[DVec3; 3]], inside: impl Fn(DVec3) -> f64) -> (f64, DVec3) {
    let mut faces: Vec<Vec<DVec3>> = Vec::new();
    let mut cuts: Vec<DVec3> = Vec::new();
    for t in tris {
        let mut poly = Vec::new();
        for k in 0..3 {
            let (a, b) = (t[k], t[(k + 1) % 3]);
            let (fa, fb) = (inside(a), inside(b));
            if fa >= 0.0 {
                poly.push(a);
                if fa == 0.0 {
                    cuts.push(a);
                }
            }
            if (fa > 0.0 && fb < 0.0) || (fa < 0.0 && fb > 0.0) {
                let p = a + (b - a) * (fa / (fa - fb));
                poly.push(p);
                cuts.push(p);
            }
        }
        if poly.len() >= 3 {
            faces.push(poly);
        }
    }
    // The lid: distinct cut points in order round their mean.
    let mut lid: Vec<DVec3> = Vec::new();
    for p in cuts {
        if lid.iter().all(|q| q.distance(p) > 1e-9) {
            lid.push(p);
        }
    }
    if lid.len() >= 3 {
        let mean = lid.iter().copied().sum::<DVec3>() / lid.len() as f64;
        let normal = (lid[0] - mean).cross(lid[1] - mean);
        let normal = if normal.length() > 1e-12 {
            normal.normalize()
        } else {
            (lid[0] - mean).cross(lid[2] - mean).normalize()
        };
        let u = (lid[0] - mean).normalize();
        let v = normal.cross(u);
        lid.sort_by(|a, b| {
            let angle = |p: &DVec3| (*p - mean).dot(v).atan2((*p - mean).dot(u));
            angle(a).total_cmp(&angle(b))
        });
        faces.push(lid);
    }
    let points: Vec<DVec3> = faces.iter().flatten().copied().collect();
    if points.is_empty() {
        return (0.0, DVec3::ZERO);
    }
    let q = points.iter().copied().sum::<DVec3>() / points.len() as f64;
    let (mut volume, mut moment) = (0.0, DVec3::ZERO);
    for f in &faces {
        for i in 1..f.len() - 1 {
            let (a, b, c) = (f[0], f[i], f[i + 1]);
            let v = ((a - q).dot((b - q).cross(c - q)) / 6.0).abs();
            volume += v;
            moment += (q + a + b + c) / 4.0 * v;
        }
    }
    if volume == 0.0 {
        return (0.0, DVec3::ZERO);
    }
    (volume, moment / volume)
}
