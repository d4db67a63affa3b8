//! The hull mesh: validation, and its volume, centroid and inertia by the divergence
//! theorem.
//!
//! # Mass properties from the surface alone
//!
//! Take any point `o` (here the centre of the mesh's bounding box, so that the numbers
//! stay small) and join it to every triangle `(a, b, c)` of a closed, outward-wound mesh:
//! the tetrahedra `(o, a, b, c)` cover the inside once, with signed volumes
//! `det / 6`, `det = a·(b × c)` (positions relative to `o`); the parts of tetrahedra that
//! reach outside the body, where the surface folds back, cancel against tetrahedra of
//! opposite sign. This is the divergence theorem applied face by face, and it needs
//! nothing but the triangles. Per tetrahedron, with `s = a + b + c`:
//!
//! * volume `det / 6`;
//! * first moment `∫ r dV = det · s / 24` (its centroid `s / 4` times its volume);
//! * second moment `∫ r rᵀ dV = det · (a aᵀ + b bᵀ + c cᵀ + s sᵀ) / 120` (the canonical
//!   tetrahedron's `∫ r rᵀ` is `(I + 1 1ᵀ) / 120`, mapped by the matrix `[a b c]`).
//!
//! The sums give the volume `V`, the centroid `c̄ = ∫ r dV / V` and, moved to the centroid,
//! `C = ∫ r rᵀ dV − V c̄ c̄ᵀ`. For a mass `m` of uniform density `ρ = m / V` the inertia
//! tensor about the centroid is `ρ (tr(C) I − C)`.
//!
//! Everything is accumulated in `f64` with `+`, `−`, `×` and `÷` only (no fused
//! multiply-add, no library functions), so every platform gets the same bits.

use crate::error::{Error, Result};
use glam::{DVec3, Mat3, Vec3};

/// A closed triangle mesh used as a rigid body's hull, validated, with its mass properties.
///
/// Vertices are in the body's frame (world units); triangles list three vertex indices
/// each, counter-clockwise seen from outside (the right-hand normal points out of the
/// body). What [`Hull::new`] requires, each refused with its own [`Error::InvalidHull`]
/// message:
///
/// * from [`MIN_TRIANGLES`](Self::MIN_TRIANGLES) (4, a tetrahedron) to
///   [`MAX_TRIANGLES`](Self::MAX_TRIANGLES) (65,536) triangles, at most three vertices per
///   triangle;
/// * finite vertex coordinates, each at most [`MAX_COORDINATE`](Self::MAX_COORDINATE)
///   (1e9) in size;
/// * indices in range, no triangle using a vertex twice or with zero area;
/// * closed: every edge is shared by exactly two triangles that run along it in opposite
///   directions (an oriented surface without holes; several separate parts are fine).
///   Vertices at exactly the same position count as one, so a game mesh split at its
///   texture seams is closed if its positions are;
/// * wound outward: the enclosed volume is positive, and not vanishingly small against the
///   mesh's size (at least 1e-6 of the cube of its bounding box's largest side) nor in
///   itself (at least 1.2e-38 cubic units, the smallest normal `f32`);
/// * a positive definite inertia (a mesh that turns inside out in places can pass the
///   other tests and fail this one).
///
/// Self-intersections are not looked for (that costs far more than the rest): a mesh that
/// passes through itself counts the overlap twice or not at all.
///
/// ```
/// use springwater::body::Hull;
///
/// let boat = Hull::cuboid([2.0, 0.5, 1.0])?;               // 12 triangles
/// assert_eq!(boat.triangles().len(), 12);
/// assert_eq!(boat.volume(), 8.0);
/// let inertia = boat.inertia(8.0);                            // mass 8, about the centroid
/// assert!((inertia.x_axis.x - 8.0 * (0.25 + 1.0) / 3.0).abs() < 1e-6);
/// # Ok::<(), springwater::Error>(())
/// ```
///
/// With the `serde` feature a hull is written as its `vertices` and `triangles`, and read
/// back through [`Hull::new`], so a damaged or edited file cannot make an invalid hull.
#[derive(Debug, Clone, PartialEq)]
#[cfg_attr(
    feature = "serde",
    derive(serde::Serialize, serde::Deserialize),
    serde(into = "HullMesh", try_from = "HullMesh")
)]
pub struct Hull {
    vertices: Vec<[f32; 3]>,
    triangles: Vec<[u32; 3]>,
    volume: f64,
    /// The centroid in the body frame.
    centroid: DVec3,
    /// `∫ (r − c̄)(r − c̄)ᵀ dV`, entries xx, yy, zz, xy, yz, zx.
    covariance: [f64; 6],
    /// The bounding box's largest side: the scale of the mesh.
    extent: f64,
}

impl Hull {
    /// The fewest triangles a closed mesh can have (a tetrahedron).
    pub const MIN_TRIANGLES: usize = 4;
    /// The most triangles a hull may have: 2¹⁶. A hull's buoyancy costs time in proportion
    /// to its triangles, every body, every step; this many is already some thirty times
    /// the 2,000-triangle boat of the benchmarks. A hull for buoyancy is a simplified
    /// proxy of the rendered boat, as a collision mesh is.
    pub const MAX_TRIANGLES: usize = 1 << 16;
    /// The largest coordinate a vertex may have, in world units (1e9, as for the other
    /// floating bodies' sizes).
    pub const MAX_COORDINATE: f32 = 1e9;

    /// Validates a mesh (see the type's docs for what is required) and computes its mass
    /// properties.
    pub fn new(vertices: &[[f32; 3]], triangles: &[[u32; 3]]) -> Result<Self> {
        check_sizes(vertices.len(), triangles.len())?;
        check_vertices(vertices)?;
        check_triangles(vertices, triangles)?;
        check_closed(vertices, triangles)?;
        let props = MassSums::of(vertices, triangles);
        let hull = props.into_hull(vertices, triangles)?;
        Ok(hull)
    }

    /// The surface of a closed hull cut into smaller triangles, each on its own (a cut
    /// triangle's edge may meet a neighbour's corner: the surface is closed only to
    /// rounding, so the closedness test is skipped); the other checks and the mass
    /// properties as for [`Hull::new`].
    pub(crate) fn cut_surface(vertices: &[[f32; 3]], triangles: &[[u32; 3]]) -> Result<Self> {
        check_vertices(vertices)?;
        check_triangles(vertices, triangles)?;
        MassSums::of(vertices, triangles).into_hull(vertices, triangles)
    }

    /// A box of `half_extents` centred on the origin: 8 vertices, 12 triangles.
    pub fn cuboid(half_extents: impl Into<Vec3>) -> Result<Self> {
        let e = half_extents.into();
        let vertices: Vec<[f32; 3]> = (0..8)
            .map(|i| {
                let pick = |bit: u32, v: f32| if i & bit == 0 { -v } else { v };
                [pick(1, e.x), pick(2, e.y), pick(4, e.z)]
            })
            .collect();
        // Each face as a quad, counter-clockwise from outside; vertex i has x from bit 0,
        // y from bit 1 and z from bit 2.
        let quads = [
            [0, 4, 6, 2], // −x
            [1, 3, 7, 5], // +x
            [0, 1, 5, 4], // −y
            [2, 6, 7, 3], // +y
            [0, 2, 3, 1], // −z
            [4, 5, 7, 6], // +z
        ];
        let triangles: Vec<[u32; 3]> = quads
            .iter()
            .flat_map(|&[a, b, c, d]| [[a, b, c], [a, c, d]])
            .collect();
        Self::new(&vertices, &triangles)
    }

    /// The same mesh moved so that its centroid (the centre of mass at uniform density)
    /// is at the origin of the body frame, to rounding of the `f32` coordinates.
    pub fn centred(&self) -> Result<Self> {
        let c = self.centroid;
        let moved: Vec<[f32; 3]> = self
            .vertices
            .iter()
            .map(|v| {
                [
                    (v[0] as f64 - c.x) as f32,
                    (v[1] as f64 - c.y) as f32,
                    (v[2] as f64 - c.z) as f32,
                ]
            })
            .collect();
        Self::new(&moved, &self.triangles)
    }

    /// The vertices, body frame, as given.
    pub fn vertices(&self) -> &[[f32; 3]] {
        &self.vertices
    }

    /// The triangles, as given.
    pub fn triangles(&self) -> &[[u32; 3]] {
        &self.triangles
    }

    /// The enclosed volume, cubic world units.
    pub fn volume(&self) -> f32 {
        self.volume as f32
    }

    /// The centroid of the enclosed volume, body frame: the centre of mass at uniform
    /// density.
    pub fn centroid(&self) -> Vec3 {
        self.centroid.as_vec3()
    }

    /// The inertia tensor about the centroid, in the body's axes, for `mass` spread evenly
    /// through the volume (mass × world units²). Symmetric; its diagonal holds the moments
    /// about the x, y and z axes through the centroid.
    pub fn inertia(&self, mass: f32) -> Mat3 {
        let rho = mass as f64 / self.volume;
        let [xx, yy, zz, xy, yz, zx] = self.covariance;
        let trace = xx + yy + zz;
        let col = |a: f64, b: f64, c: f64| Vec3::new(a as f32, b as f32, c as f32);
        Mat3::from_cols(
            col(rho * (trace - xx), -rho * xy, -rho * zx),
            col(-rho * xy, rho * (trace - yy), -rho * yz),
            col(-rho * zx, -rho * yz, rho * (trace - zz)),
        )
    }

    /// The enclosed volume in `f64`.
    pub(crate) fn volume_f64(&self) -> f64 {
        self.volume
    }

    /// The largest side of the mesh's bounding box, world units.
    pub(super) fn extent(&self) -> f64 {
        self.extent
    }

    /// The mesh as Wavefront OBJ text: a comment line per entry of `comments`, one `v`
    /// line per vertex (shortest round-trip form of each `f32`), one `f` line per triangle
    /// (1-based indices, counter-clockwise from outside, as OBJ expects).
    pub fn to_obj(&self, comments: &[&str]) -> String {
        let mut out = String::new();
        for c in comments {
            out.push_str(&format!("# {c}\n"));
        }
        for [x, y, z] in &self.vertices {
            out.push_str(&format!("v {x} {y} {z}\n"));
        }
        for [a, b, c] in &self.triangles {
            out.push_str(&format!("f {} {} {}\n", a + 1, b + 1, c + 1));
        }
        out
    }
}

/// What serde writes and reads of a hull: the mesh, validated again on reading.
#[cfg(feature = "serde")]
#[derive(serde::Serialize, serde::Deserialize)]
struct HullMesh {
    vertices: Vec<[f32; 3]>,
    triangles: Vec<[u32; 3]>,
}

#[cfg(feature = "serde")]
impl From<Hull> for HullMesh {
    fn from(hull: Hull) -> Self {
        Self {
            vertices: hull.vertices,
            triangles: hull.triangles,
        }
    }
}

#[cfg(feature = "serde")]
impl TryFrom<HullMesh> for Hull {
    type Error = Error;

    fn try_from(mesh: HullMesh) -> Result<Self> {
        Hull::new(&mesh.vertices, &mesh.triangles)
    }
}

fn refuse<T>(message: String) -> Result<T> {
    Err(Error::InvalidHull(message))
}

fn check_sizes(vertices: usize, triangles: usize) -> Result<()> {
    if !(Hull::MIN_TRIANGLES..=Hull::MAX_TRIANGLES).contains(&triangles) {
        return refuse(format!(
            "{triangles} triangles; a hull has 4 (a tetrahedron) to 65536: use a simplified \
             mesh for buoyancy, as for collisions"
        ));
    }
    if vertices > 3 * triangles {
        return refuse(format!(
            "{vertices} vertices for {triangles} triangles; a closed mesh uses at most three \
             per triangle: drop the unused ones"
        ));
    }
    Ok(())
}

fn check_vertices(vertices: &[[f32; 3]]) -> Result<()> {
    for (i, v) in vertices.iter().enumerate() {
        let [x, y, z] = *v;
        if !v.iter().all(|c| c.is_finite()) {
            return refuse(format!(
                "vertex {i} is ({x}, {y}, {z}): coordinates must be finite"
            ));
        }
        if !v.iter().all(|c| c.abs() <= Hull::MAX_COORDINATE) {
            return refuse(format!(
                "vertex {i} is ({x}, {y}, {z}): coordinates must be at most 1e9 in size"
            ));
        }
    }
    Ok(())
}

fn check_triangles(vertices: &[[f32; 3]], triangles: &[[u32; 3]]) -> Result<()> {
    let n = vertices.len();
    for (t, &[a, b, c]) in triangles.iter().enumerate() {
        for i in [a, b, c] {
            if i as usize >= n {
                return refuse(format!(
                    "triangle {t} refers to vertex {i}, but there are {n} vertices"
                ));
            }
        }
        if a == b || b == c || c == a {
            return refuse(format!(
                "triangle {t} ({a}, {b}, {c}) uses a vertex twice: remove it"
            ));
        }
        let p = |i: u32| DVec3::from(vertices[i as usize].map(f64::from));
        // Differences and products of f32 values are exact in f64: zero means collinear.
        if (p(b) - p(a)).cross(p(c) - p(a)) == DVec3::ZERO {
            return refuse(format!(
                "triangle {t} ({a}, {b}, {c}) has zero area (its corners are collinear): \
                 remove it"
            ));
        }
    }
    Ok(())
}

/// Every directed edge appears once, and so does its reverse. Vertices at the same
/// position are one vertex here.
fn check_closed(vertices: &[[f32; 3]], triangles: &[[u32; 3]]) -> Result<()> {
    let weld = welded(vertices);
    let mut edges: Vec<(u32, u32, u32)> = Vec::with_capacity(3 * triangles.len());
    for (t, tri) in triangles.iter().enumerate() {
        for k in 0..3 {
            let (a, b) = (tri[k], tri[(k + 1) % 3]);
            edges.push((weld[a as usize], weld[b as usize], t as u32));
        }
    }
    edges.sort_unstable();
    for pair in edges.windows(2) {
        let ((a, b, t1), (a2, b2, t2)) = (pair[0], pair[1]);
        if (a, b) == (a2, b2) {
            return refuse(format!(
                "triangles {t1} and {t2} both run from vertex {a} to vertex {b}: either their \
                 windings disagree (reverse one so that all are counter-clockwise seen from \
                 outside) or more than two triangles meet at that edge"
            ));
        }
    }
    for &(a, b, t) in &edges {
        if edges.binary_search_by(|e| (e.0, e.1).cmp(&(b, a))).is_err() {
            return refuse(format!(
                "the edge from vertex {a} to vertex {b} of triangle {t} has no triangle on its \
                 other side: the mesh is open; close the hole (vertices are joined only where \
                 their positions are exactly equal)"
            ));
        }
    }
    Ok(())
}

/// For each vertex, the smallest index of a vertex at exactly the same position (−0 and
/// +0 are the same coordinate).
fn welded(vertices: &[[f32; 3]]) -> Vec<u32> {
    let key = |i: u32| vertices[i as usize].map(|c| (c + 0.0).to_bits());
    let mut order: Vec<u32> = (0..vertices.len() as u32).collect();
    order.sort_unstable_by_key(|&i| (key(i), i));
    let mut weld = vec![0; vertices.len()];
    let mut first = 0;
    for (k, &i) in order.iter().enumerate() {
        if k == 0 || key(i) != key(order[k - 1]) {
            first = i;
        }
        weld[i as usize] = first;
    }
    weld
}

/// The tetrahedron sums of the module docs, relative to `origin`.
struct MassSums {
    origin: DVec3,
    extent: f64,
    /// Σ det (six times the volume).
    det: f64,
    /// Σ det · s (24 times the first moment).
    first: DVec3,
    /// Σ det · (a aᵀ + b bᵀ + c cᵀ + s sᵀ) (120 times the second moment): xx, yy, zz, xy,
    /// yz, zx.
    second: [f64; 6],
}

impl MassSums {
    fn of(vertices: &[[f32; 3]], triangles: &[[u32; 3]]) -> Self {
        let mut lo = DVec3::splat(f64::INFINITY);
        let mut hi = DVec3::splat(f64::NEG_INFINITY);
        for v in vertices {
            let p = DVec3::from(v.map(f64::from));
            lo = pick(lo, p, |a, b| a < b);
            hi = pick(hi, p, |a, b| a > b);
        }
        let origin = (lo + hi) * 0.5;
        let size = hi - lo;
        let extent = if size.x > size.y { size.x } else { size.y };
        let extent = if size.z > extent { size.z } else { extent };
        let mut sums = Self {
            origin,
            extent,
            det: 0.0,
            first: DVec3::ZERO,
            second: [0.0; 6],
        };
        let rel = |i: u32| DVec3::from(vertices[i as usize].map(f64::from)) - origin;
        for &[a, b, c] in triangles {
            let (a, b, c) = (rel(a), rel(b), rel(c));
            let det = a.dot(b.cross(c));
            let s = a + b + c;
            sums.det += det;
            sums.first += s * det;
            let outer = |u: DVec3| {
                [
                    u.x * u.x,
                    u.y * u.y,
                    u.z * u.z,
                    u.x * u.y,
                    u.y * u.z,
                    u.z * u.x,
                ]
            };
            let (oa, ob, oc, os) = (outer(a), outer(b), outer(c), outer(s));
            for k in 0..6 {
                sums.second[k] += det * (oa[k] + ob[k] + oc[k] + os[k]);
            }
        }
        sums
    }

    fn into_hull(self, vertices: &[[f32; 3]], triangles: &[[u32; 3]]) -> Result<Hull> {
        let volume = self.det / 6.0;
        if volume < 0.0 {
            return refuse(format!(
                "the mesh is inside out (enclosed volume {}): its triangles wind clockwise \
                 seen from outside; reverse each triangle's vertex order",
                volume as f32
            ));
        }
        let floor = 1e-6 * self.extent * self.extent * self.extent;
        if volume <= floor {
            return refuse(format!(
                "the mesh encloses almost no volume ({} against a bounding box {} wide): it \
                 is flat or folded onto itself",
                volume as f32, self.extent as f32
            ));
        }
        // The volume is handed out in f32 (`Hull::volume`, a body's displacement): a mesh
        // enclosing less than the smallest normal f32 would float with no volume at all.
        if (volume as f32) < f32::MIN_POSITIVE {
            return refuse(format!(
                "the mesh encloses {volume:e} cubic units, less than the smallest normal f32 \
                 (1.2e-38): scale it up"
            ));
        }
        let c = self.first / (24.0 * volume);
        let m = self.second.map(|v| v / 120.0);
        // The parallel axis theorem for the covariance: subtract V c̄ c̄ᵀ.
        let covariance = [
            m[0] - volume * c.x * c.x,
            m[1] - volume * c.y * c.y,
            m[2] - volume * c.z * c.z,
            m[3] - volume * c.x * c.y,
            m[4] - volume * c.y * c.z,
            m[5] - volume * c.z * c.x,
        ];
        let [xx, yy, zz, xy, yz, zx] = covariance;
        // Sylvester's criterion: the leading minors of a positive definite matrix are
        // positive.
        let minor2 = xx * yy - xy * xy;
        let det = xx * (yy * zz - yz * yz) - xy * (xy * zz - yz * zx) + zx * (xy * yz - yy * zx);
        if !(xx > 0.0 && minor2 > 0.0 && det > 0.0) {
            return refuse(
                "the mesh's inertia is not positive definite: parts of it are turned inside \
                 out (wound clockwise) while the whole encloses a positive volume; make every \
                 part counter-clockwise seen from outside"
                    .to_string(),
            );
        }
        Ok(Hull {
            vertices: vertices.to_vec(),
            triangles: triangles.to_vec(),
            volume,
            centroid: self.origin + c,
            covariance,
            extent: self.extent,
        })
    }
}

/// Per component, `b` where `better(b, a)`, else `a` (a comparison, never `min`/`max`,
/// whose zeros differ between platforms).
fn pick(a: DVec3, b: DVec3, better: impl Fn(f64, f64) -> bool) -> DVec3 {
    let one = |a: f64, b: f64| if better(b, a) { b } else { a };
    DVec3::new(one(a.x, b.x), one(a.y, b.y), one(a.z, b.z))
}
