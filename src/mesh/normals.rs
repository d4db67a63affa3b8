//! Per-node normals ([`compute_normals`]; its docs give the method).

use super::{load, store, xyz_chunks, xyz_chunks_mut};
use crate::simd::{Kernel, Vector};
use crate::view::MeshView;

/// Unit normals, one per node, row-major: `x[i], y[i], z[i]` is node `i`'s normal.
///
/// Caller-owned and reused between frames: [`compute_normals`] resizes the buffers to the
/// node count and keeps their capacity.
#[derive(Debug, Clone, Default, PartialEq)]
pub struct Normals {
    /// x components.
    pub x: Vec<f32>,
    /// y components (close to 1 for a calm surface).
    pub y: Vec<f32>,
    /// z components.
    pub z: Vec<f32>,
}

impl Normals {
    /// Empty buffers (the same as `Normals::default()`).
    pub fn new() -> Self {
        Self::default()
    }

    /// Number of normals held.
    pub fn len(&self) -> usize {
        self.x.len()
    }

    /// True before the first [`compute_normals`].
    pub fn is_empty(&self) -> bool {
        self.x.is_empty()
    }

    /// Normal of node `i`.
    pub fn get(&self, i: usize) -> glam::Vec3 {
        glam::Vec3::new(self.x[i], self.y[i], self.z[i])
    }

    pub(crate) fn resize(&mut self, n: usize) {
        for c in [&mut self.x, &mut self.y, &mut self.z] {
            c.resize(n, 0.0);
        }
    }
}

/// Computes the normal of every node of `view` into `out` .
///
/// ```
/// use springwater::mesh::{compute_normals, Normals};
/// use springwater::{Params, Surface};
///
/// let water = Surface::new(Params::with_size(9, 5))?;
/// let mut normals = Normals::new();
/// compute_normals(&water.mesh_view(), &mut normals);
/// assert_eq!(normals.len(), 45);
/// assert_eq!(normals.get(20), glam::Vec3::Y);          // flat water: straight up
/// # Ok::<(), springwater::Error>(())
/// ```
///
/// # Method
///
/// For node `(col, row)` with position `P(col, row)` the two tangents are differences of
/// its neighbours' current positions (the full 3-D positions, so the lattice's sideways
/// motion is taken into account):
///
/// ```text
/// u = P(col+1, row) − P(col−1, row)     along the row (+x at rest)
/// v = P(col, row+1) − P(col, row−1)     across rows   (+z at rest)
/// n = normalize(v × u)
/// ```
///
/// At the border the missing neighbour is replaced by the node itself (a one-sided
/// difference). The cross product's direction does not depend on the tangents' lengths,
/// so central and one-sided differences mix without rescaling. `v × u` is `+y` for the flat
/// rest state, and it is the orientation of the counter-clockwise triangles of
/// [`LodMesh`](crate::mesh::LodMesh): the normal points up wherever the surface has not
/// folded over. Where the tangents are parallel or zero (a collapsed node) the normal is
/// `(0, 1, 0)`, so the output is always unit length and finite.
///
/// # Vectorisation
///
/// Rows run in parallel (rayon, with the `parallel` feature). Inside a row, interior
/// columns are computed a chunk of SIMD lanes at a time, at the view's level
/// ([`MeshView::simd_level`]): left/right neighbours are the same row loaded one element
/// earlier and later, up/down neighbours the rows above and below. The first column and
/// the tail of a row that does not fill a chunk run through [`MeshView::node_normal`], the
/// scalar twin, which performs the same operations in the same order — the two agree
/// bitwise at every level (tested).
pub fn compute_normals(view: &MeshView<'_>, out: &mut Normals) {
    out.resize(view.grid().node_count());
    let cols = view.cols();
    super::for_each_chunk(
        view.runner(),
        [&mut out.x, &mut out.y, &mut out.z],
        cols,
        |row, out| normals_row(view, row, out),
    );
}

/// The scalar twin of [`compute_normals`]: one [`MeshView::node_normal`] per node. Same results,
/// bitwise; kept as the oracle for tests and as readable documentation of the kernel.
#[cfg_attr(not(feature = "internals"), allow(dead_code))]
pub fn compute_normals_scalar(view: &MeshView<'_>, out: &mut Normals) {
    out.resize(view.grid().node_count());
    let grid = view.grid();
    for i in 0..grid.node_count() {
        let (c, r) = grid.coords(i);
        let n = view.node_normal(c, r);
        (out.x[i], out.y[i], out.z[i]) = (n.x, n.y, n.z);
    }
}

/// One row of normals: lanes over the interior columns, [`MeshView::node_normal`] for the rest.
pub(crate) fn normals_row(view: &MeshView<'_>, row: usize, out: [&mut [f32]; 3]) {
    crate::simd::dispatch(view.simd_level(), NormalsRow { view, row, out })
}

/// [`normals_row`]'s work, for any vector type.
struct NormalsRow<'v, 'a, 'o> {
    view: &'v MeshView<'a>,
    row: usize,
    out: [&'o mut [f32]; 3],
}

impl Kernel for NormalsRow<'_, '_, '_> {
    type Output = ();

    #[inline(always)]
    fn run<V: Vector>(self) {
        let NormalsRow { view, row, out } = self;
        let cols = view.cols();
        let here = row * cols;
        let up = row.saturating_sub(1) * cols;
        let down = (row + 1).min(view.rows() - 1) * cols;
        let xyz = [view.x(), view.y(), view.z()];
        let [ox, oy, oz] = out;
        // Chunk k covers columns 1 + k·LANES ..; it reads one column either side, so the
        // chunks stop before the last column.
        let count = cols.saturating_sub(2) / V::LANES;
        let len = count * V::LANES;
        let at = |from| xyz_chunks::<V>(xyz, from, len);
        let sides = at(here).zip(at(here + 2));
        let above_below = at(up + 1).zip(at(down + 1));
        let outs = xyz_chunks_mut::<V>([&mut *ox, &mut *oy, &mut *oz], 1, len);
        let (tiny, huge) = (V::splat(f32::MIN_POSITIVE), V::splat(f32::INFINITY));
        for (((l, r), (a, b)), o) in sides.zip(above_below).zip(outs) {
            let ([lx, ly, lz], [rx, ry, rz]) = (load::<V>(l), load::<V>(r));
            let ([ax, ay, az], [bx, by, bz]) = (load::<V>(a), load::<V>(b));
            let (ux, uy, uz) = (rx - lx, ry - ly, rz - lz);
            let (vx, vy, vz) = (bx - ax, by - ay, bz - az);
            let n = [vy * uz - vz * uy, vz * ux - vx * uz, vx * uy - vy * ux];
            let len2 = n[0] * n[0] + n[1] * n[1] + n[2] * n[2];
            let ok = len2.gt(tiny) & len2.lt(huge);
            let inv = V::one() / len2.sqrt();
            let fallback = [V::zero(), V::one(), V::zero()];
            let unit = |i: usize| V::select(ok, n[i] * inv, fallback[i]);
            store(o, [unit(0), unit(1), unit(2)]);
        }
        let c = 1 + count * V::LANES;
        for col in std::iter::once(0).chain(c..cols) {
            let n = view.node_normal(col, row);
            (ox[col], oy[col], oz[col]) = (n.x, n.y, n.z);
        }
    }
}
