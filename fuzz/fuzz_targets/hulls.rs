//! Hull meshes from arbitrary vertex and triangle arrays: `Hull::new` refuses the mesh
//! with an error, or makes a hull whose volume is finite and positive, whose centroid and
//! inertia are finite, and which makes the same hull again from its own arrays.
//! `Floater::hull` agrees with `Hull::new`, and a body of the hull on a small pool is
//! refused with nothing changed or steps finitely (a failed step changes nothing).
//!
//! Raw arrays are almost never closed, so most inputs start from a closed mesh (a box, an
//! octahedron, a tetrahedron) and damage it: vertices moved, triangles reversed, dropped
//! or added, the mesh split at seams (each triangle with vertices of its own, which the
//! closedness test welds back), the whole scaled from 1e-30 to 1e9 and moved.

#![no_main]

mod common;

use arbitrary::Arbitrary;
use common::{check_finite, log_range, state, Num};
use glam::DVec3;
use libfuzzer_sys::fuzz_target;
use springwater::body::Hull;
use springwater::{Floater, Params, Surface};

#[derive(Debug, Arbitrary)]
enum Input {
    Raw {
        vertices: Vec<[f32; 3]>,
        triangles: Vec<[u32; 3]>,
    },
    /// Small integer vertices times one scale, indices taken modulo the vertex count.
    Lattice {
        vertices: Vec<[i8; 3]>,
        triangles: Vec<[u8; 3]>,
        scale: Num,
    },
    Damaged(Damage),
}

#[derive(Debug, Arbitrary)]
struct Damage {
    base: u8,
    /// Vertex, and its move (up to a quarter of the base's size).
    moves: Vec<(u8, [i8; 3])>,
    /// Triangles whose winding is reversed.
    flips: Vec<u8>,
    dropped: Option<u8>,
    added: Option<[u8; 3]>,
    seams: bool,
    /// Size, from 1e-30 to 1e9.
    scale: u8,
    /// A move in sixteenths of the size, or (sometimes) any distance.
    offset: [i8; 3],
    far: Option<[Num; 3]>,
    /// Vertices set to a raw number (NaN, infinity, 1e38).
    raw: Option<(u8, [f32; 3])>,
}

/// A closed, outward-wound mesh: a box, an octahedron or a tetrahedron.
fn base(kind: u8) -> (Vec<[f32; 3]>, Vec<[u32; 3]>) {
    match kind % 3 {
        0 => {
            let h = Hull::cuboid([1.0, 0.5, 0.75]).expect("valid");
            (h.vertices().to_vec(), h.triangles().to_vec())
        }
        1 => {
            // ±x, ±y, ±z; each face counter-clockwise seen from outside.
            let v = vec![
                [1.0, 0.0, 0.0],
                [-1.0, 0.0, 0.0],
                [0.0, 1.0, 0.0],
                [0.0, -1.0, 0.0],
                [0.0, 0.0, 1.0],
                [0.0, 0.0, -1.0],
            ];
            let t = vec![
                [0, 2, 4],
                [4, 2, 1],
                [1, 2, 5],
                [5, 2, 0],
                [4, 3, 0],
                [1, 3, 4],
                [5, 3, 1],
                [0, 3, 5],
            ];
            (v, t)
        }
        _ => {
            let v = vec![
                [0.0, 0.0, 0.0],
                [1.0, 0.0, 0.0],
                [0.0, 0.0, 1.0],
                [0.0, 1.0, 0.0],
            ];
            let t = vec![[0, 1, 2], [1, 0, 3], [2, 1, 3], [0, 2, 3]];
            (v, t)
        }
    }
}

fn damaged(d: &Damage) -> (Vec<[f32; 3]>, Vec<[u32; 3]>) {
    let (mut v, mut t) = base(d.base);
    for &(k, m) in d.moves.iter().take(8) {
        let n = v.len();
        let p = &mut v[k as usize % n];
        for (c, dm) in p.iter_mut().zip(m) {
            *c += dm as f32 / 512.0;
        }
    }
    for &k in d.flips.iter().take(4) {
        let n = t.len();
        t[k as usize % n].swap(1, 2);
    }
    if let Some(k) = d.dropped {
        let n = t.len();
        t.remove(k as usize % n);
    }
    if let Some(a) = d.added {
        t.push(a.map(|i| i as u32 % v.len() as u32));
    }
    if d.seams {
        let mut split_v = Vec::new();
        for tri in &mut t {
            for i in tri.iter_mut() {
                split_v.push(v[*i as usize]);
                *i = split_v.len() as u32 - 1;
            }
        }
        v = split_v;
    }
    let scale = log_range(d.scale, 1e-30, 1e9);
    let offset = match d.far {
        Some(far) => common::vec3(far).to_array(),
        None => d.offset.map(|v| v as f32 / 16.0 * scale),
    };
    for p in &mut v {
        for k in 0..3 {
            p[k] = p[k] * scale + offset[k];
        }
    }
    if let Some((k, raw)) = d.raw {
        let n = v.len();
        v[k as usize % n] = raw;
    }
    (v, t)
}

/// What a valid hull promises: the mass properties of a solid (see the `body::hull`
/// module docs).
fn check(hull: &Hull, vertices: &[[f32; 3]], triangles: &[[u32; 3]]) {
    let volume = hull.volume();
    assert!(volume.is_finite() && volume > 0.0, "volume {volume}");
    // The volume is at least 1e-6 of the cube of the bounding box's largest side (the
    // check in `Hull::new`, in f64, up to the f32 rounding of the volume returned).
    let (mut lo, mut hi) = (DVec3::splat(f64::INFINITY), DVec3::splat(f64::NEG_INFINITY));
    for v in vertices {
        let p = DVec3::from(v.map(f64::from));
        lo = lo.min(p);
        hi = hi.max(p);
    }
    let extent = (hi - lo).max_element();
    assert!(
        volume as f64 >= 0.99e-6 * extent * extent * extent,
        "volume {volume} for a mesh {extent} across"
    );
    let c = hull.centroid();
    assert!(c.is_finite(), "centroid {c}");
    // A solid's centroid lies within its bounding box. A mesh that folds through itself
    // counts some volume twice or with the opposite sign, so this holds only loosely:
    // within one extent of the box.
    let c = c.as_dvec3();
    assert!(
        c.cmpge(lo - extent).all() && c.cmple(hi + extent).all(),
        "centroid {c} far outside the box {lo}..{hi}"
    );
    for mass in [1e-30f32, 1.0, 1e6] {
        let inertia = hull.inertia(mass);
        let m = inertia.to_cols_array();
        if mass == 1.0 || m.iter().all(|v| v.is_finite()) {
            assert!(m.iter().all(|v| v.is_finite()), "inertia {inertia}");
            // The moments about the axes are integrals of squared distances: never negative.
            let d = [inertia.x_axis.x, inertia.y_axis.y, inertia.z_axis.z];
            assert!(d.iter().all(|&v| v >= 0.0), "inertia {inertia}");
            assert_eq!(inertia, inertia.transpose(), "not symmetric");
        }
    }
    // The same arrays make the same hull; the hull keeps the arrays as given.
    assert_eq!(hull.vertices(), vertices);
    assert_eq!(hull.triangles(), triangles);
    assert!(
        Hull::new(vertices, triangles).is_ok_and(|again| again == *hull),
        "the same arrays made another hull"
    );
    // Moving the centroid to the origin: refused (the moved coordinates may round into
    // an invalid mesh) or valid.
    if let Ok(centred) = hull.centred() {
        assert!(centred.volume() > 0.0 && centred.centroid().is_finite());
    }
}

/// A body of the hull at half the water's density, floating in a small pool.
fn float(hull: &Hull) {
    let mut s = Surface::new(Params::with_size(12, 12).with_dt(0.2)).expect("valid");
    let mass = 0.5 * s.buoyancy().density * hull.volume();
    let body = Floater::hull(hull.vertices(), hull.triangles(), mass, [5.5, 0.0, 5.5])
        .expect("the same mesh as a hull");
    let before = state(&s);
    if s.add_floater(body).is_err() {
        assert!(state(&s) == before, "a refused body changed the surface");
        return;
    }
    check_finite(&s);
    for _ in 0..2 {
        let before = state(&s);
        match s.step() {
            Ok(()) => check_finite(&s),
            Err(_) => {
                assert!(state(&s) == before, "a failed step changed the surface");
                return;
            }
        }
    }
}

fuzz_target!(|input: Input| {
    let (vertices, triangles) = match &input {
        Input::Raw {
            vertices,
            triangles,
        } => (
            vertices.iter().take(192).copied().collect(),
            triangles.iter().take(64).copied().collect(),
        ),
        Input::Lattice {
            vertices,
            triangles,
            scale,
        } => {
            let scale = scale.get();
            let v: Vec<[f32; 3]> = vertices
                .iter()
                .take(64)
                .map(|p| p.map(|c| c as f32 * scale))
                .collect();
            let n = v.len().max(1) as u32;
            let t = triangles
                .iter()
                .take(64)
                .map(|t| t.map(|i| i as u32 % n))
                .collect();
            (v, t)
        }
        Input::Damaged(d) => damaged(d),
    };
    let hull = Hull::new(&vertices, &triangles);
    let body = Floater::hull(&vertices, &triangles, 1.0, [0.0; 3]);
    assert_eq!(
        hull.is_ok(),
        body.is_ok(),
        "Floater::hull and Hull::new disagree"
    );
    if let Ok(hull) = hull {
        check(&hull, &vertices, &triangles);
        float(&hull);
    }
});
