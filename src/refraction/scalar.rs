//! The scalar twins of the refraction lane code: the oracle the SIMD path is tested
//! against (unstable, reached through `springwater::internals`).

use super::{check_normals, eye_scale, resize, Refractor, MAX_TRAVEL};
use crate::mesh::Normals;
use crate::refraction::{Refraction, RefractionParams};
use crate::view::MeshView;
use crate::Result;
use glam::Vec3;

/// The scalar twin of [`refract`](super::refract): one [`refract_node`] per node, same checks, same
/// results.
#[cfg_attr(not(feature = "internals"), allow(dead_code))]
pub fn refract_scalar(
    view: &MeshView<'_>,
    normals: &Normals,
    eye: Vec3,
    params: &RefractionParams,
    out: &mut Refraction,
) -> Result<()> {
    Refractor::new(view, eye, params)?;
    check_normals(view, normals)?;
    let n = view.grid().node_count();
    resize(out, n);
    let extent = view.extent();
    for i in 0..n {
        let [u, v, f] = refract_node(view.position(i), normals.get(i), eye, params, extent);
        (out.u[i], out.v[i], out.fresnel[i]) = (u, v, f);
    }
    Ok(())
}

/// `[u, v, fresnel]` for one node at `p` with normal `n`, the bottom texture spanning
/// `extent` (see `MeshView::extent`). The scalar twin of the lane code in [`refract`](super::refract).
pub fn refract_node(
    p: Vec3,
    n: Vec3,
    eye: Vec3,
    params: &RefractionParams,
    extent: [f32; 2],
) -> [f32; 3] {
    let eta = 1.0 / params.ior;
    let (scale, es) = eye_scale(eye);
    // The view vector D = σ(P − E), not normalised: with L = |D|, cosi = c/L and the
    // refracted direction is T/L (see the `refraction` module docs), so the hit needs no division by L.
    let (dx, dy, dz) = (p.x * scale - es.x, p.y * scale - es.y, p.z * scale - es.z);
    let l2 = dx * dx + dy * dy + dz * dz;
    let c = -(n.x * dx + n.y * dy + n.z * dz);
    let q = l2 - eta * eta * (l2 - c * c);
    let f = eta * c - q.max(0.0).sqrt();
    let (tx, ty, tz) = (eta * dx + f * n.x, eta * dy + f * n.y, eta * dz + f * n.z);
    let s = (-params.depth - p.y) / ty;
    let (ox, oz) = (s * tx, s * tz);
    let front = c > 0.0;
    let valid = front && ty < 0.0 && s >= 0.0 && ox.abs() < MAX_TRAVEL && oz.abs() < MAX_TRAVEL;
    let (hx, hz) = if valid {
        (p.x + ox, p.z + oz)
    } else {
        (p.x, p.z)
    };
    let cosi = c / l2.max(f32::MIN_POSITIVE).sqrt();

    let r0 = params.r0();
    let c_in = (-cosi).min(1.0);
    let sin2t = params.ior * params.ior * (1.0 - c_in * c_in);
    let c_back = (1.0 - sin2t).max(0.0).sqrt();
    let c = if front { cosi.min(1.0) } else { c_back };
    let m = 1.0 - c;
    let m2 = m * m;
    let r = r0 + (1.0 - r0) * (m2 * m2 * m);
    let r = if !front && sin2t >= 1.0 { 1.0 } else { r };
    [hx * (1.0 / extent[0]), hz * (1.0 / extent[1]), r]
}
