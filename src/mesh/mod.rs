//! Render-side stages that read the simulation through a borrowed [`MeshView`](crate::MeshView).
//!
//! ```text
//! Surface ──mesh_view()──▶ MeshView<'_>   (borrows x, y, z: zero copy)
//!                             ├─▶ compute_normals   → Normals        (per node)
//!                             ├─▶ LodMesh::update   → indices: &[u32] (per camera, cached)
//!                             └─▶ refract           → Refraction     (per node bottom UV, Fresnel)
//! ```
//!
//! Every stage writes into a caller-owned buffer that keeps its capacity from frame to
//! frame, and every index buffer indexes the full row-major node array, so a renderer
//! uploads the positions, normals and UVs as they are and draws the LOD triangles.
//! [`normals_and_refraction`](crate::refraction::normals_and_refraction) does the two
//! per-node stages in one pass, and [`crate::buffers`] interleaves the results for a GPU
//! upload. Game code asks the full-resolution simulation, not the mesh, for heights,
//! normals and velocities ([`Surface::height_at`](crate::Surface::height_at) and friends).
//!
//! # A frame
//!
//! ```
//! use springwater::mesh::{compute_normals, LodMesh, LodParams, Normals};
//! use springwater::refraction::{refract, Refraction, RefractionParams};
//! use springwater::{Params, Surface};
//! use glam::Vec3;
//!
//! let mut water = Surface::new(Params::with_size(129, 97))?;
//! let mut lod = LodMesh::new(LodParams::default())?;
//! let mut normals = Normals::new();
//! let mut uv = Refraction::default();
//! let bottom = RefractionParams { depth: 4.0, ..Default::default() };
//!
//! water.drop_at(64.0, 48.0, 1.0, 3.0)?;
//! for frame in 0..3 {
//!     let eye = Vec3::new(64.0, 30.0, -20.0 + frame as f32);   // the camera, in water space
//!     water.advance(1.0 / 60.0)?;                              // simulate a 60 Hz frame
//!     let view = water.mesh_view();                            // borrow, no copy
//!     compute_normals(&view, &mut normals);
//!     refract(&view, &normals, eye, &bottom, &mut uv)?;
//!     if lod.update(&view, eye) {
//!         // upload lod.indices() (u32 triangles, CCW seen from +y) only when rebuilt
//!     }
//!     // upload view.x(), view.y(), view.z(), normals.{x,y,z}, uv.{u,v}, uv.fresnel; draw
//!     assert_eq!(uv.u.len(), view.x().len());
//!     assert!(lod.indices().iter().all(|&i| (i as usize) < view.x().len()));
//! }
//! # Ok::<(), springwater::Error>(())
//! ```

mod lod;
pub(crate) mod normals;

pub use lod::{LodMesh, LodParams};
pub(crate) use normals::normals_row;
pub use normals::{compute_normals, Normals};

/// Runs `f(chunk_index, [x, y, z])` on matching chunks of `len` elements of three equally
/// long buffers: on the rayon pool with the `parallel` feature, in order without it. Each
/// chunk is computed by the same code either way, so results do not depend on threads.
pub(crate) fn for_each_chunk3<F>(out: [&mut [f32]; 3], len: usize, f: F)
where
    F: Fn(usize, [&mut [f32]; 3]) + Sync + Send,
{
    let [x, y, z] = out;
    let len = len.max(1);
    #[cfg(feature = "parallel")]
    {
        use rayon::prelude::*;
        // Keep tasks at a few thousand nodes or more.
        let min_chunks = (4096 / len).max(1);
        x.par_chunks_mut(len)
            .zip(y.par_chunks_mut(len))
            .zip(z.par_chunks_mut(len))
            .with_min_len(min_chunks)
            .enumerate()
            .for_each(|(i, ((x, y), z))| f(i, [x, y, z]));
    }
    #[cfg(not(feature = "parallel"))]
    for (i, ((x, y), z)) in x
        .chunks_mut(len)
        .zip(y.chunks_mut(len))
        .zip(z.chunks_mut(len))
        .enumerate()
    {
        f(i, [x, y, z]);
    }
}

/// [`for_each_chunk3`] over six buffers.
pub(crate) fn for_each_chunk6<F>(out: [&mut [f32]; 6], len: usize, f: F)
where
    F: Fn(usize, [&mut [f32]; 6]) + Sync + Send,
{
    let [a, b, c, d, e, g] = out;
    let len = len.max(1);
    #[cfg(feature = "parallel")]
    {
        use rayon::prelude::*;
        let min_chunks = (4096 / len).max(1);
        a.par_chunks_mut(len)
            .zip(b.par_chunks_mut(len))
            .zip(c.par_chunks_mut(len))
            .zip(d.par_chunks_mut(len))
            .zip(e.par_chunks_mut(len))
            .zip(g.par_chunks_mut(len))
            .with_min_len(min_chunks)
            .enumerate()
            .for_each(|(i, (((((a, b), c), d), e), g))| f(i, [a, b, c, d, e, g]));
    }
    #[cfg(not(feature = "parallel"))]
    for (i, (((((a, b), c), d), e), g)) in a
        .chunks_mut(len)
        .zip(b.chunks_mut(len))
        .zip(c.chunks_mut(len))
        .zip(d.chunks_mut(len))
        .zip(e.chunks_mut(len))
        .zip(g.chunks_mut(len))
        .enumerate()
    {
        f(i, [a, b, c, d, e, g]);
    }
}
