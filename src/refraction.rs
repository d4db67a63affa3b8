//! Refraction: which point of the bottom each node shows, and how much it reflects.
//!
//! # Method
//!
//! The pool has a flat bottom at `y = −depth` carrying a texture that spans the grid's rest
//! footprint `[0, (cols−1)h] × [0, (rows−1)h]`. For node `P` with unit normal `n` and the
//! eye at `E` (both in the water's local space):
//!
//! ```text
//! d    = normalize(P − E)                       the view ray
//! cosi = −n·d                                   > 0 when the eye is on the normal's side
//! η    = 1 / ior
//! t    = η d + (η cosi − sqrt(1 − η²(1 − cosi²))) n      Snell's law, vector form
//! s    = (−depth − P.y) / t.y                   the ray P + s t meets the bottom plane
//! uv   = ((P.x + s t.x) / ((cols−1)h), (P.z + s t.z) / ((rows−1)h))
//! ```
//!
//! UVs outside `[0, 1]` are bottom points outside the footprint (wrap or clamp the texture
//! as the scene wants).
//!
//! The code evaluates exactly this, scaled by `L = |P − E|` so that the square root and
//! division of the normalisation leave the hit's dependency chain: with `D = P − E` and
//! `c = −n·D = L·cosi`,
//!
//! ```text
//! T    = η D + (η c − sqrt(L² − η²(L² − c²))) n   = L·t
//! s'   = (−depth − P.y) / T.y                      = s / L, so P + s' T = P + s t
//! cosi = c / L                                     (for Fresnel only)
//! ```
//!
//! **When the ray does not reach the bottom**, the node's coordinate is the point of the
//! bottom texture straight below it, `(P.x / ((cols−1)h), P.z / ((rows−1)h))`, as if the
//! water were still there. That happens when
//!
//! * the eye is on the back side of the surface at that node (`cosi ≤ 0`): an eye under the
//!   water, or a node on the far slope of a steep crest;
//! * the refracted ray does not go down (`t.y ≥ 0`: a normal tilted more than the
//!   refraction angle away from vertical);
//! * the node lies below the bottom (`P.y < −depth`);
//! * the hit would land more than 10³⁰ units sideways (the ray is horizontal to within
//!   about 10⁻³⁰);
//! * the eye sits exactly on the node (`cosi` is taken as 0: seen edge-on, `R = 1`).
//!
//! View vectors are computed in units of the eye's largest coordinate when that exceeds 1
//! (`D = σP − σE`, σ = 1/max(1, |E|∞)), so any finite eye works, however far away, without
//! overflow.
//!
//! # Fresnel
//!
//! Schlick's approximation, `R = R0 + (1 − R0)(1 − cos θ)⁵` with `R0 = ((ior − 1)/(ior + 1))²`:
//! `cos θ = cosi` when the eye is above the surface (`R = R0` looking straight down, → 1 at
//! grazing). From below (`cosi < 0`) light leaves the water, so `θ` is the angle of the ray
//! transmitted into the air, `sin θt = ior·sin θi`, and beyond the critical angle
//! (`sin θt ≥ 1`) the reflection is total: `R = 1`. The two sides meet at `R = 1` for
//! `cosi = 0`. `R` is always in `[R0, 1]`.
//!
//! # Lane code
//!
//! [`refract`] runs a chunk of lanes at a time on the flat arrays, at the view's SIMD
//! level ([`MeshView::simd_level`]), and chunks of nodes in parallel with the `parallel`
//! feature. Every case above is a mask and a `select`, never a branch. Clamps against
//! constants use the lanes' `min`/`max` (`minps`/`maxps`), which agree with `f32::min`
//! and `f32::max` there (a NaN input gives the constant). `refract_node` is the scalar
//! twin, with the same operations in the same order; it computes the tail of the arrays and
//! is compared with the lane code, bitwise, in tests.

use crate::error::{same_length, Error, Result};
use crate::mesh::Normals;
use crate::mesh::{load, store, xyz_chunks, xyz_chunks_mut};
use crate::simd::Vector;
use crate::view::MeshView;
use glam::Vec3;

pub(crate) mod scalar;
pub(crate) use scalar::refract_node;

/// The bottom and the water's optics.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct RefractionParams {
    /// Depth of the flat bottom below the rest surface `y = 0`, in world units
    /// (default: `4.0`). Finite and ≥ 0.
    pub depth: f32,
    /// Index of refraction of the water relative to the air above it (default: `1.333`).
    /// Finite, from 1 to 10.
    pub ior: f32,
}

impl Default for RefractionParams {
    fn default() -> Self {
        Self {
            depth: 4.0,
            ior: 1.333,
        }
    }
}

impl RefractionParams {
    /// Checks both fields.
    pub fn validate(&self) -> Result<()> {
        if !(self.depth.is_finite() && self.depth >= 0.0) {
            return Err(Error::InvalidParam {
                name: "depth",
                value: self.depth as f64,
                expected: "a finite depth >= 0 below the rest surface (for example 4)",
            });
        }
        if !(self.ior.is_finite() && (1.0..=10.0).contains(&self.ior)) {
            return Err(Error::InvalidParam {
                name: "ior",
                value: self.ior as f64,
                expected: "an index of refraction from 1 to 10 (water: 1.333)",
            });
        }
        Ok(())
    }

    /// Schlick's `R0 = ((ior − 1)/(ior + 1))²`, the reflectance at normal incidence.
    pub fn r0(&self) -> f32 {
        let r = (self.ior - 1.0) / (self.ior + 1.0);
        r * r
    }
}

/// Per-node bottom texture coordinates and Fresnel reflectance, row-major.
///
/// Caller-owned and reused between frames: [`refract`] resizes the buffers to the node
/// count and keeps their capacity.
#[derive(Debug, Clone, Default, PartialEq)]
pub struct Refraction {
    /// Bottom texture u (x direction), 0 at `x = 0`, 1 at `x = (cols−1)h`.
    pub u: Vec<f32>,
    /// Bottom texture v (z direction), 0 at `z = 0`, 1 at `z = (rows−1)h`.
    pub v: Vec<f32>,
    /// Schlick reflectance in `[R0, 1]`: blend `reflection·R + refraction·(1 − R)`.
    pub fresnel: Vec<f32>,
}

impl Refraction {
    /// Number of nodes held.
    pub fn len(&self) -> usize {
        self.u.len()
    }

    /// True before the first [`refract`].
    pub fn is_empty(&self) -> bool {
        self.u.is_empty()
    }
}

/// Nodes per parallel task (a multiple of any lane width).
const CHUNK: usize = 4096;

/// Computes every node's bottom texture coordinate and Fresnel reflectance (see the
/// [module docs](self)) into `out`.
///
/// Errors (and leaves `out` unchanged) if `normals` does not have one normal per node
/// (call [`compute_normals`](crate::mesh::compute_normals) on the same view first), if the
/// eye is not finite or if `params` is invalid. Finite positions and normals always give
/// finite results, for any eye.
pub fn refract(
    view: &MeshView<'_>,
    normals: &Normals,
    eye: Vec3,
    params: &RefractionParams,
    out: &mut Refraction,
) -> Result<()> {
    let k = Refractor::new(view, eye, params)?;
    check_normals(view, normals)?;
    let n = view.grid().node_count();
    resize(out, n);
    crate::mesh::for_each_chunk(
        view.runner(),
        [&mut out.u, &mut out.v, &mut out.fresnel],
        CHUNK,
        |chunk, out| {
            let nodes = chunk * CHUNK..(chunk * CHUNK + out[0].len());
            let local = [
                &normals.x[nodes.clone()],
                &normals.y[nodes.clone()],
                &normals.z[nodes.clone()],
            ];
            k.chunk(view, local, nodes.start, out)
        },
    );
    Ok(())
}

/// [`compute_normals`](crate::mesh::compute_normals) and [`refract`] in one pass: each
/// parallel task computes the normals of a block of rows and refracts those nodes while
/// they are in cache. Bitwise the same results as the two calls, with one parallel region
/// instead of two. (Measured on this crate's benchmark machine it costs about the same as
/// the two calls: both kernels are bound by arithmetic, not memory.)
///
/// ```
/// use springwater::mesh::Normals;
/// use springwater::refraction::{normals_and_refraction, Refraction, RefractionParams};
/// use springwater::{Params, Surface};
///
/// let water = Surface::new(Params::with_size(64, 64))?;
/// let (mut normals, mut uv) = (Normals::new(), Refraction::default());
/// let eye = glam::Vec3::new(32.0, 20.0, -10.0);
/// normals_and_refraction(&water.mesh_view(), eye, &RefractionParams::default(), &mut normals, &mut uv)?;
/// assert_eq!((normals.len(), uv.len()), (64 * 64, 64 * 64));
/// # Ok::<(), springwater::Error>(())
/// ```
pub fn normals_and_refraction(
    view: &MeshView<'_>,
    eye: Vec3,
    params: &RefractionParams,
    normals: &mut Normals,
    out: &mut Refraction,
) -> Result<()> {
    let k = Refractor::new(view, eye, params)?;
    let (n, cols) = (view.grid().node_count(), view.cols());
    normals.resize(n);
    resize(out, n);
    let rows_per_task = (CHUNK / cols).max(1);
    let (nx, ny, nz) = (&mut normals.x, &mut normals.y, &mut normals.z);
    crate::mesh::for_each_chunk(
        view.runner(),
        [nx, ny, nz, &mut out.u, &mut out.v, &mut out.fresnel],
        rows_per_task * cols,
        |chunk, [nx, ny, nz, u, v, f]| k.rows(view, chunk * rows_per_task, [nx, ny, nz], [u, v, f]),
    );
    Ok(())
}

/// Longest ray, in world units, that still counts as reaching the bottom.
const MAX_TRAVEL: f32 = 1e30;

/// `(σ, σ·eye)` with `σ = 1 / max(1, largest |eye component|)`: view vectors are computed
/// as `σ·P − σ·E`, which cannot overflow for any finite eye, and equal `P − E` (σ = 1) for
/// every eye within a unit cube of the origin's scale.
fn eye_scale(eye: Vec3) -> (f32, Vec3) {
    let scale = 1.0 / eye.abs().max_element().max(1.0);
    (scale, eye * scale)
}

fn resize(out: &mut Refraction, n: usize) {
    for c in [&mut out.u, &mut out.v, &mut out.fresnel] {
        c.resize(n, 0.0);
    }
}

/// One normal per node of `view`, or an error naming the short buffer.
fn check_normals(view: &MeshView<'_>, normals: &Normals) -> Result<()> {
    let n = view.grid().node_count();
    for (what, s) in [
        ("normals.x", &normals.x),
        ("normals.y", &normals.y),
        ("normals.z", &normals.z),
    ] {
        same_length(what, s.len(), n)?;
    }
    Ok(())
}

/// Checked inputs and per-call constants of the lane kernel.
pub(crate) struct Refractor {
    eye: Vec3,
    params: RefractionParams,
    extent: [f32; 2],
}

impl Refractor {
    /// Checks the eye and `params`.
    pub(crate) fn new(view: &MeshView<'_>, eye: Vec3, params: &RefractionParams) -> Result<Self> {
        params.validate()?;
        for (name, c) in [("eye x", eye.x), ("eye y", eye.y), ("eye z", eye.z)] {
            crate::params::finite(name, c)?;
        }
        Ok(Self {
            eye,
            params: *params,
            extent: view.extent(),
        })
    }

    /// The whole rows from `first_row` that `normals` (one value per node) holds: their
    /// normals into `normals`, then their texture coordinates and Fresnel into `out` (same
    /// length), while the normals are in cache.
    pub(crate) fn rows(
        &self,
        view: &MeshView<'_>,
        first_row: usize,
        normals: [&mut [f32]; 3],
        out: [&mut [f32]; 3],
    ) {
        let cols = view.cols();
        let [nx, ny, nz] = normals;
        let rows = nx
            .chunks_mut(cols)
            .zip(ny.chunks_mut(cols))
            .zip(nz.chunks_mut(cols));
        for (r, ((x, y), z)) in rows.enumerate() {
            crate::mesh::normals_row(view, first_row + r, [x, y, z]);
        }
        self.chunk(view, [&*nx, &*ny, &*nz], first_row * cols, out);
    }

    /// Nodes `start .. start + out[0].len()`, whose normals are `normals` (same length):
    /// lanes, then the scalar twin for the tail.
    fn chunk<'a>(
        &self,
        view: &MeshView<'a>,
        normals: [&'a [f32]; 3],
        start: usize,
        out: [&mut [f32]; 3],
    ) {
        let [ou, ov, of] = out;
        let len = ou.len();
        let count = crate::simd::dispatch(
            view.simd_level(),
            RefractChunk {
                k: self,
                view,
                normals,
                start,
                out: [&mut *ou, &mut *ov, &mut *of],
            },
        );
        for o in count..len {
            let i = start + o;
            let [u, v, f] = refract_node(
                view.position(i),
                Vec3::new(normals[0][o], normals[1][o], normals[2][o]),
                self.eye,
                &self.params,
                self.extent,
            );
            (ou[o], ov[o], of[o]) = (u, v, f);
        }
    }
}

/// The lane part of [`Refractor::chunk`], for any vector type: the whole chunks of lanes.
/// Returns how many nodes it did.
struct RefractChunk<'k, 'a, 'o> {
    k: &'k Refractor,
    view: &'k MeshView<'a>,
    normals: [&'a [f32]; 3],
    start: usize,
    out: [&'o mut [f32]; 3],
}

impl crate::simd::Kernel for RefractChunk<'_, '_, '_> {
    type Output = usize;

    #[inline(always)]
    fn run<V: Vector>(self) -> usize {
        let RefractChunk {
            k,
            view,
            normals,
            start,
            out,
        } = self;
        let c = Consts::<V>::new(k);
        let len = out[0].len() / V::LANES * V::LANES;
        let p = xyz_chunks::<V>([view.x(), view.y(), view.z()], start, len);
        let n = xyz_chunks::<V>(normals, 0, len);
        for ((p, n), o) in p.zip(n).zip(xyz_chunks_mut::<V>(out, 0, len)) {
            store(o, refract_lanes(&c, load(p), load(n)));
        }
        len
    }
}

/// Per-call constants of the lane kernel, splatted once.
struct Consts<V> {
    scale: V,
    eye: [V; 3],
    max_travel: V,
    eta: V,
    eta2: V,
    depth: V,
    r0: V,
    ior2: V,
    inv_extent: [V; 2],
}

impl<V: Vector> Consts<V> {
    #[inline(always)]
    fn new(k: &Refractor) -> Self {
        let splat = V::splat;
        let (scale, es) = eye_scale(k.eye);
        let ior = k.params.ior;
        Self {
            scale: splat(scale),
            eye: [splat(es.x), splat(es.y), splat(es.z)],
            max_travel: splat(MAX_TRAVEL),
            eta: splat(1.0 / ior),
            eta2: splat((1.0 / ior) * (1.0 / ior)),
            depth: splat(k.params.depth),
            r0: splat(k.params.r0()),
            ior2: splat(ior * ior),
            inv_extent: [splat(1.0 / k.extent[0]), splat(1.0 / k.extent[1])],
        }
    }
}

/// `[u, v, fresnel]` for a chunk of nodes at `[px, py, pz]` with normals `[nx, ny, nz]`:
/// [`scalar::refract_node`] with masks for its branches.
#[inline(always)]
fn refract_lanes<V: Vector>(c: &Consts<V>, [px, py, pz]: [V; 3], [nx, ny, nz]: [V; 3]) -> [V; 3] {
    let (zero, one) = (V::zero(), V::one());
    let (eta, scale) = (c.eta, c.scale);
    let [ex, ey, ez] = c.eye;
    let (dx, dy, dz) = (px * scale - ex, py * scale - ey, pz * scale - ez);
    let l2 = dx * dx + dy * dy + dz * dz;
    let c_l = -(nx * dx + ny * dy + nz * dz);
    let q = l2 - c.eta2 * (l2 - c_l * c_l);
    let f = eta * c_l - q.max(zero).sqrt();
    let (tx, ty, tz) = (eta * dx + f * nx, eta * dy + f * ny, eta * dz + f * nz);
    let s = (-c.depth - py) / ty;
    let (ox, oz) = (s * tx, s * tz);
    let front = c_l.gt(zero);
    let valid =
        front & ty.lt(zero) & s.ge(zero) & ox.abs().lt(c.max_travel) & oz.abs().lt(c.max_travel);
    let (hx, hz) = (V::select(valid, px + ox, px), V::select(valid, pz + oz, pz));
    let cosi = c_l / l2.max(V::splat(f32::MIN_POSITIVE)).sqrt();

    let schlick = |cos: V| {
        let m = one - cos;
        let m2 = m * m;
        c.r0 + (one - c.r0) * (m2 * m2 * m)
    };
    let r = if V::all(front) {
        // The usual case, an eye above the water: no lane needs the transmitted angle, so
        // skip its square root. Same arithmetic as the masked path for front lanes.
        schlick(cosi.min(one))
    } else {
        let c_in = (-cosi).min(one);
        let sin2t = c.ior2 * (one - c_in * c_in);
        let c_back = (one - sin2t).max(zero).sqrt();
        let r = schlick(V::select(front, cosi.min(one), c_back));
        V::select(!front & sin2t.ge(one), one, r)
    };
    [hx * c.inv_extent[0], hz * c.inv_extent[1], r]
}
