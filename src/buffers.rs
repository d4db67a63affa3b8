//! Renderer-ready vertex data: the per-node arrays interleaved into caller-owned buffers a
//! GPU upload takes as they are (Bevy's mesh attributes, a wgpu or Vulkan vertex buffer).
//!
//! The simulation and the render-side stages keep structure-of-arrays slices (`x`, `y`,
//! `z` in [`MeshView`], [`Normals`], [`Refraction`]), which is what their SIMD loops want.
//! [`interleave`] turns them, in one pass over the nodes, into any of:
//!
//! * positions `[[f32; 3]]`, normals `[[f32; 3]]`, refraction texture coordinates
//!   `[[f32; 2]]`;
//! * packed [`Vertex`]es (`#[repr(C)]`, [`bytemuck::Pod`]: `bytemuck::cast_slice` gives the
//!   bytes), 32 bytes each: position, normal, uv.
//!
//! [`fill_frame`] goes from the positions to those buffers directly: it computes the
//! normals and refraction coordinates block by block in a small per-thread scratch and
//! writes each block out while it is in cache, for a renderer that only uploads vertices.
//!
//! Every buffer is the caller's, one element per node in row-major order (the order the
//! LOD index buffer indexes), and is checked before anything is written: a buffer of the
//! wrong length is an error and no buffer is touched. The values are copied bit for bit.
//!
//! ```
//! use springwater::buffers::{interleave, Vertex, VertexBuffers};
//! use springwater::refraction::{normals_and_refraction, Refraction, RefractionParams};
//! use springwater::mesh::Normals;
//! use springwater::{Params, Surface};
//!
//! let mut water = Surface::new(Params::with_size(65, 49))?;
//! water.drop_at(32.0, 24.0, 1.0, 3.0)?;
//! let (mut normals, mut uv) = (Normals::new(), Refraction::default());
//! let mut vertices = vec![Vertex::default(); water.node_count()];       // kept between frames
//! let mut positions = vec![[0.0f32; 3]; water.node_count()];
//!
//! water.advance(1.0 / 60.0)?;
//! let view = water.mesh_view();
//! let eye = glam::Vec3::new(32.0, 20.0, -10.0);
//! normals_and_refraction(&view, eye, &RefractionParams::default(), &mut normals, &mut uv)?;
//! interleave(&view, &normals, &uv, VertexBuffers {
//!     vertices: Some(&mut vertices),
//!     positions: Some(&mut positions),
//!     ..Default::default()
//! })?;
//! let bytes: &[u8] = bytemuck::cast_slice(&vertices);               // upload these
//! assert_eq!(bytes.len(), 32 * water.node_count());
//! assert_eq!(positions[24 * 65 + 32][1], view.y()[24 * 65 + 32]);
//! # Ok::<(), springwater::Error>(())
//! ```

use std::ops::Range;

use crate::error::{same_length, Result};
use crate::jobs::{for_each_part, Runner, Split};
use crate::mesh::Normals;
use crate::refraction::{Refraction, RefractionParams, Refractor};
use crate::view::MeshView;

/// One node's vertex, packed for a GPU vertex buffer: 8 `f32`, 32 bytes, no padding.
///
/// Attribute offsets: position 0, normal 12, uv 24 (bytes).
#[repr(C)]
#[derive(Debug, Clone, Copy, Default, PartialEq, bytemuck::Pod, bytemuck::Zeroable)]
pub struct Vertex {
    /// Position in the water's local space (y up).
    pub position: [f32; 3],
    /// Unit normal.
    pub normal: [f32; 3],
    /// Bottom texture coordinate through the surface ([`Refraction`]'s `u`, `v`).
    pub uv: [f32; 2],
}

/// The buffers [`interleave`] fills; `None` skips one. Each given buffer must hold exactly
/// one element per node.
#[derive(Debug, Default)]
pub struct VertexBuffers<'a> {
    /// Positions `[x, y, z]`.
    pub positions: Option<&'a mut [[f32; 3]]>,
    /// Normals `[x, y, z]`.
    pub normals: Option<&'a mut [[f32; 3]]>,
    /// Refraction texture coordinates `[u, v]`.
    pub uvs: Option<&'a mut [[f32; 2]]>,
    /// Packed vertices.
    pub vertices: Option<&'a mut [Vertex]>,
}

/// Nodes per task when the work is split over threads, and per block of the pass.
const BLOCK: usize = 4096;

/// Fills every buffer of `out` from `view`'s positions, `normals` and `uv`, one element
/// per node, in one pass (see the [module docs](self)). `normals` and `uv` must be this
/// view's (one value per node: run the stages on it first).
///
/// Errors, with nothing written: [`Error::LengthMismatch`](crate::Error::LengthMismatch)
/// when `normals`, `uv` or a buffer does not hold one element per node.
pub fn interleave(
    view: &MeshView<'_>,
    normals: &Normals,
    uv: &Refraction,
    out: VertexBuffers<'_>,
) -> Result<()> {
    let n = view.grid().node_count();
    for c in [&normals.x, &normals.y, &normals.z] {
        same_length("normals", c.len(), n)?;
    }
    for c in [&uv.u, &uv.v] {
        same_length("refraction coordinates", c.len(), n)?;
    }
    check(n, &out)?;
    let src = Source {
        p: [view.x(), view.y(), view.z()],
        n: [&normals.x, &normals.y, &normals.z],
        uv: [&uv.u, &uv.v],
    };
    fill_blocks(view.runner(), src, out);
    Ok(())
}

/// The render-side stages straight into the vertex buffers, in one pass: each task
/// computes the normals and refraction coordinates of a block of rows into its thread's
/// scratch (24 bytes per node of the block, reused from call to call), then writes that
/// block of `out`. The same bits as [`normals_and_refraction`](crate::refraction::normals_and_refraction)
/// followed by [`interleave`], without the two structure-of-arrays results ever going to
/// memory: what a renderer that uploads vertices needs, at little more than the cost of
/// the stages (docs/performance.md has the figures). Call the two functions instead when
/// you want the [`Normals`] and [`Refraction`] slices as well.
///
/// ```
/// use springwater::buffers::{fill_frame, Vertex, VertexBuffers};
/// use springwater::refraction::RefractionParams;
/// use springwater::{Params, Surface};
///
/// let mut water = Surface::new(Params::with_size(65, 49))?;
/// water.drop_at(32.0, 24.0, 1.0, 3.0)?;
/// let mut vertices = vec![Vertex::default(); water.node_count()];     // kept between frames
/// water.advance(1.0 / 60.0)?;
/// let eye = glam::Vec3::new(32.0, 20.0, -10.0);
/// fill_frame(&water.mesh_view(), eye, &RefractionParams::default(),
///     VertexBuffers { vertices: Some(&mut vertices), ..Default::default() })?;
/// let n = water.normal_at(32.0, 24.0).expect("on the surface");
/// assert!((vertices[24 * 65 + 32].normal[1] - n.y).abs() < 1e-5);
/// # Ok::<(), springwater::Error>(())
/// ```
///
/// Errors, with nothing written: those of
/// [`refract`](crate::refraction::refract) for the eye and `params`, and
/// [`Error::LengthMismatch`](crate::Error::LengthMismatch) when a buffer of `out` does not
/// hold one element per node.
pub fn fill_frame(
    view: &MeshView<'_>,
    eye: glam::Vec3,
    params: &RefractionParams,
    out: VertexBuffers<'_>,
) -> Result<()> {
    let k = Refractor::new(view, eye, params)?;
    let (n, cols) = (view.grid().node_count(), view.cols());
    check(n, &out)?;
    let rows_per_block = (FRAME_BLOCK / cols).max(1);
    for_each_part(
        view.runner(),
        n,
        rows_per_block * cols,
        BLOCK,
        out,
        &|nodes, out| {
            with_scratch(nodes.len(), |[nx, ny, nz, u, v, fresnel]| {
                k.rows(view, nodes.start / cols, [nx, ny, nz], [u, v, fresnel]);
                let src = Source {
                    p: [view.x(), view.y(), view.z()].map(|c| &c[nodes.clone()]),
                    n: [&*nx, &*ny, &*nz],
                    uv: [&*u, &*v],
                };
                fill(src, out);
            })
        },
    );
    Ok(())
}

/// Nodes per block of [`fill_frame`]: whole rows, as many as fit in this many nodes, and
/// at least one. Up to rows of this length the six scratch arrays (24 KiB) stay in the
/// first-level cache between being written and being read; a longer row is one block.
const FRAME_BLOCK: usize = 1024;

/// Scratch floats a thread keeps between calls: blocks of up to 16 384 nodes (rows that
/// long). A block of a longer row gets a buffer of its own, freed after it.
const SCRATCH_KEPT: usize = 6 * 16 * FRAME_BLOCK;

thread_local! {
    /// This thread's scratch for [`fill_frame`]'s blocks, reused from call to call.
    static SCRATCH: std::cell::RefCell<Vec<f32>> = const { std::cell::RefCell::new(Vec::new()) };
}

/// Runs `f` on six scratch arrays of `len` floats each (their contents are whatever the
/// last block left: `f` writes before it reads), from this thread's kept scratch when it
/// can. A block gets a buffer of its own when it is longer than what a thread keeps, when
/// the thread's scratch is in use (a job system that runs tasks inside tasks) or already
/// gone (a task run while the thread exits).
fn with_scratch<R>(len: usize, f: impl FnOnce([&mut [f32]; 6]) -> R) -> R {
    let mut f = Some(f);
    let kept = SCRATCH.try_with(|cell| match cell.try_borrow_mut() {
        Ok(mut buf) if 6 * len <= SCRATCH_KEPT => f.take().map(|f| on_arrays(&mut buf, len, f)),
        _ => None,
    });
    match (kept, f) {
        (Ok(Some(done)), _) => done,
        (_, Some(f)) => on_arrays(&mut Vec::new(), len, f),
        (_, None) => unreachable!("`f` runs once: either on the kept scratch or here"),
    }
}

/// `f` on the first `6 × len` floats of `buf` (grown if shorter), as six arrays.
fn on_arrays<R>(buf: &mut Vec<f32>, len: usize, f: impl FnOnce([&mut [f32]; 6]) -> R) -> R {
    if buf.len() < 6 * len {
        buf.resize(6 * len, 0.0);
    }
    let mut arrays = buf[..6 * len].chunks_exact_mut(len.max(1));
    f(std::array::from_fn(|_| arrays.next().unwrap_or_default()))
}

/// `Ok` when every buffer of `out` holds one element per node of `n`.
fn check(n: usize, out: &VertexBuffers<'_>) -> Result<()> {
    if let Some(b) = &out.positions {
        same_length("position buffer", b.len(), n)?;
    }
    if let Some(b) = &out.normals {
        same_length("normal buffer", b.len(), n)?;
    }
    if let Some(b) = &out.uvs {
        same_length("uv buffer", b.len(), n)?;
    }
    if let Some(b) = &out.vertices {
        same_length("vertex buffer", b.len(), n)?;
    }
    Ok(())
}

/// The structure-of-arrays inputs, all of one length.
#[derive(Clone, Copy)]
struct Source<'a> {
    p: [&'a [f32]; 3],
    n: [&'a [f32]; 3],
    uv: [&'a [f32]; 2],
}

impl Source<'_> {
    fn len(&self) -> usize {
        self.p[0].len()
    }

    /// The nodes `r`.
    fn range(&self, r: Range<usize>) -> Self {
        Self {
            p: self.p.map(|c| &c[r.clone()]),
            n: self.n.map(|c| &c[r.clone()]),
            uv: self.uv.map(|c| &c[r.clone()]),
        }
    }
}

/// A task's nodes of every buffer.
impl Split for VertexBuffers<'_> {
    fn split(self, at: usize) -> (Self, Self) {
        let (positions, positions_rest) = self.positions.split(at);
        let (normals, normals_rest) = self.normals.split(at);
        let (uvs, uvs_rest) = self.uvs.split(at);
        let (vertices, vertices_rest) = self.vertices.split(at);
        let head = VertexBuffers {
            positions,
            normals,
            uvs,
            vertices,
        };
        let tail = VertexBuffers {
            positions: positions_rest,
            normals: normals_rest,
            uvs: uvs_rest,
            vertices: vertices_rest,
        };
        (head, tail)
    }
}

/// Every node, in tasks of whole blocks run by the view's runner, each block filled while
/// its inputs are in cache. Every element is written by the same code on any thread.
fn fill_blocks(runner: Runner<'_>, src: Source<'_>, out: VertexBuffers<'_>) {
    for_each_part(runner, src.len(), BLOCK, BLOCK, out, &|block, out| {
        fill(src.range(block), out)
    });
}

/// One block: each requested buffer in turn, while the block's inputs are in cache.
/// Zipped iterators over slices of one length: no bounds checks, and the compiler
/// vectorises the gathers into interleaved stores.
fn fill(src: Source<'_>, out: VertexBuffers<'_>) {
    let [x, y, z] = src.p;
    let [nx, ny, nz] = src.n;
    let [u, v] = src.uv;
    if let Some(o) = out.positions {
        for (o, ((x, y), z)) in o.iter_mut().zip(x.iter().zip(y).zip(z)) {
            *o = [*x, *y, *z];
        }
    }
    if let Some(o) = out.normals {
        for (o, ((x, y), z)) in o.iter_mut().zip(nx.iter().zip(ny).zip(nz)) {
            *o = [*x, *y, *z];
        }
    }
    if let Some(o) = out.uvs {
        for (o, (u, v)) in o.iter_mut().zip(u.iter().zip(v)) {
            *o = [*u, *v];
        }
    }
    if let Some(o) = out.vertices {
        vertices(src, o);
    }
}

/// Packed vertices, four nodes at a time: two 4 × 4 transposes turn the eight streams'
/// four-lane loads into the four vertices' two halves (`[x, y, z, nx]`, `[ny, nz, u, v]`).
/// The tail (fewer than four nodes) is copied one node at a time. `f32x4` here is the
/// shape of half a vertex, not the engine's lane width.
fn vertices(src: Source<'_>, out: &mut [Vertex]) {
    use wide::f32x4;
    let [x, y, z] = src.p;
    let [nx, ny, nz] = src.n;
    let [u, v] = src.uv;
    let halves: &mut [[f32; 4]] = bytemuck::cast_slice_mut(out);
    let (quads, _) = halves.as_chunks_mut::<8>();
    let m = quads.len();
    // Each stream as `m` chunks of four: indexing them below with `k < m` is in bounds by
    // construction, and the compiler drops the checks.
    let [x, y, z, nx, ny, nz, u, v] =
        [x, y, z, nx, ny, nz, u, v].map(|s| &s.as_chunks::<4>().0[..m]);
    for (k, quad) in quads.iter_mut().enumerate() {
        let load = |s: &[[f32; 4]]| f32x4::new(s[k]);
        let front = f32x4::transpose([load(x), load(y), load(z), load(nx)]);
        let back = f32x4::transpose([load(ny), load(nz), load(u), load(v)]);
        for j in 0..4 {
            quad[2 * j] = front[j].to_array();
            quad[2 * j + 1] = back[j].to_array();
        }
    }
    let done = 4 * m;
    let [x, y, z] = src.p;
    let [nx, ny, nz] = src.n;
    let [u, v] = src.uv;
    for (i, o) in out.iter_mut().enumerate().skip(done) {
        *o = Vertex {
            position: [x[i], y[i], z[i]],
            normal: [nx[i], ny[i], nz[i]],
            uv: [u[i], v[i]],
        };
    }
}
