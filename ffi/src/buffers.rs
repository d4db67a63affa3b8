//! What a renderer uploads each frame: node positions and velocities, normals, refracted
//! bottom texture coordinates, packed vertices, and the view-dependent LOD index buffer
//! with its patches' levels.

use crate::handle::{self, SwSurface, Water};
use crate::params::{
    c_lod_params, finite_eye, refraction_params, rust_lod_params, SwBool, SwLodParams, SwRefraction,
};
use crate::ptr::{
    copy_list_into, in_slice, input, optional, out_array, out_buffer, out_groups, read_sized_into,
};
use crate::status::{guard, Outcome, SwStatus};
use springwater::buffers::{fill_frame, Vertex, VertexBuffers};
use springwater::mesh::{compute_normals, LodMesh, Normals};
use springwater::Surface;
use std::borrow::Cow;

/// One node's packed vertex: 8 floats, 32 bytes (position at byte 0, normal at 12, the
/// refracted bottom texture coordinate at 24). The layout of the library's `Vertex`.
#[repr(C)]
#[derive(Debug, Clone, Copy, Default, PartialEq)]
pub struct SwVertex {
    /// Position in the water's local space (y up).
    pub position: [f32; 3],
    /// Unit normal.
    pub normal: [f32; 3],
    /// Bottom texture coordinate seen through the surface.
    pub uv: [f32; 2],
}

const _: () = {
    assert!(std::mem::size_of::<SwVertex>() == std::mem::size_of::<Vertex>());
    assert!(std::mem::align_of::<SwVertex>() == std::mem::align_of::<Vertex>());
    assert!(std::mem::offset_of!(SwVertex, normal) == std::mem::offset_of!(Vertex, normal));
    assert!(std::mem::offset_of!(SwVertex, uv) == std::mem::offset_of!(Vertex, uv));
};

/// Writes every node's position, interleaved `x, y, z`, row-major (node `(col, row)` at
/// `3·(row·cols + col)`). `len` is in floats and must be at least `3 · nodes`.
///
/// # Safety
///
/// `xyz` is NULL or points to `len` writable floats.
#[no_mangle]
pub unsafe extern "C" fn sw_surface_write_positions(
    surface: *const SwSurface,
    xyz: *mut f32,
    len: usize,
) -> SwStatus {
    write_triples(surface, xyz, len, |w, out| {
        Ok(w.surface.mesh_view().write_positions(out)?)
    })
}

/// Writes every node's velocity, interleaved `x, y, z`, row-major, as the lattice holds it:
/// world units per unit of *model time* (like `sw_surface_add_velocity`; multiply by
/// `time_scale` for per second, as `sw_surface_velocity_at` gives it). `len` is in floats
/// and must be at least `3 · nodes`.
///
/// # Safety
///
/// `xyz` is NULL or points to `len` writable floats.
#[no_mangle]
pub unsafe extern "C" fn sw_surface_write_velocities(
    surface: *const SwSurface,
    xyz: *mut f32,
    len: usize,
) -> SwStatus {
    write_components(surface, xyz, len, Surface::velocities)
}

/// Computes every node's unit normal and writes them interleaved `x, y, z`, row-major.
/// `len` is in floats and must be at least `3 · nodes`.
///
/// # Safety
///
/// `xyz` is NULL or points to `len` writable floats.
#[no_mangle]
pub unsafe extern "C" fn sw_surface_write_normals(
    surface: *mut SwSurface,
    xyz: *mut f32,
    len: usize,
) -> SwStatus {
    write_triples(surface, xyz, len, |w, out| {
        compute_normals(&w.surface.mesh_view(), &mut w.normals);
        let Normals { x, y, z } = &w.normals;
        for (o, ((x, y), z)) in out.iter_mut().zip(x.iter().zip(y).zip(z)) {
            *o = [*x, *y, *z];
        }
        Ok(())
    })
}

/// Computes every node's bottom texture coordinate seen through the surface from the eye
/// (Snell refraction onto the bottom plane; the texture spans the grid's rest footprint)
/// and writes them interleaved `u, v`, row-major. `len` is in floats and must be at least
/// `2 · nodes`.
///
/// # Safety
///
/// `refraction` is NULL or valid; `uv` is NULL or points to `len` writable floats.
#[no_mangle]
pub unsafe extern "C" fn sw_surface_write_refraction_uvs(
    surface: *mut SwSurface,
    refraction: *const SwRefraction,
    uv: *mut f32,
    len: usize,
) -> SwStatus {
    fill_from_eye(surface, refraction, |n| {
        Ok(VertexBuffers {
            uvs: Some(out_groups(uv, len, n, "uv")?),
            ..Default::default()
        })
    })
}

/// Computes normals and refraction coordinates and writes one packed `SwVertex` per node
/// (position, normal, uv), row-major, in one pass: the vertex buffer a renderer uploads.
/// `len` is in vertices and must be at least the node count.
///
/// # Safety
///
/// `refraction` is NULL or valid; `vertices` is NULL or points to `len` writable vertices.
#[no_mangle]
pub unsafe extern "C" fn sw_surface_write_vertices(
    surface: *mut SwSurface,
    refraction: *const SwRefraction,
    vertices: *mut SwVertex,
    len: usize,
) -> SwStatus {
    // `SwVertex` has `Vertex`'s layout (checked at compile time above).
    let vertices = vertices.cast::<Vertex>();
    fill_from_eye(surface, refraction, |n| {
        Ok(VertexBuffers {
            vertices: Some(out_buffer(vertices, len, n, "vertices")?),
            ..Default::default()
        })
    })
}

/// Replaces the LOD parameters (the next `sw_surface_update_lod` rebuilds the index
/// buffer with them).
///
/// # Safety
///
/// `params` is NULL or a valid pointer.
#[no_mangle]
pub unsafe extern "C" fn sw_surface_set_lod_params(
    surface: *mut SwSurface,
    params: *const SwLodParams,
) -> SwStatus {
    guard(|| {
        let lod = LodMesh::new(rust_lod_params(&input(params, "params")?))?;
        handle::with(surface, |w| {
            w.lod = lod;
            Ok(())
        })
    })
}

/// Updates the view-dependent LOD index buffer for an eye at `(eye_x, eye_y, eye_z)` in
/// the water's local space: patches get coarser with distance, neighbours differ by at
/// most one level and are stitched (no cracks). Writes 1 to `changed` (optional) if the
/// index buffer was rebuilt (upload it again), 0 if the previous one still holds.
///
/// # Safety
///
/// `changed` is NULL or a valid pointer.
#[no_mangle]
pub unsafe extern "C" fn sw_surface_update_lod(
    surface: *mut SwSurface,
    eye_x: f32,
    eye_y: f32,
    eye_z: f32,
    changed: *mut SwBool,
) -> SwStatus {
    guard(|| {
        let eye = finite_eye(eye_x, eye_y, eye_z)?;
        let changed = optional(changed, "changed")?;
        handle::with(surface, |w| {
            let rebuilt = w.lod.update(&w.surface.mesh_view(), eye);
            if let Some(out) = changed {
                *out = rebuilt as SwBool;
            }
            Ok(())
        })
    })
}

/// Copies the LOD index buffer (triangles as 3 node indices each, counter-clockwise seen
/// from +y) to `indices` and writes its length, in indices, to `count`. With `indices`
/// NULL only `count` is written (ask the size first, Box2D style); a `len` smaller than
/// the buffer is `SW_ERROR_BUFFER_TOO_SMALL`, with `count` still written. Before the first
/// `sw_surface_update_lod` the buffer is empty.
///
/// # Safety
///
/// `indices` is NULL or points to `len` writable `uint32_t`; `count` is NULL or valid.
#[no_mangle]
pub unsafe extern "C" fn sw_surface_lod_indices(
    surface: *const SwSurface,
    indices: *mut u32,
    len: usize,
    count: *mut usize,
) -> SwStatus {
    copy_list_into(surface, (indices, len, "indices"), (count, "count"), |w| {
        Cow::Borrowed(w.lod.indices())
    })
}

/// Writes the LOD parameters the surface's index buffer is built with to `out`, whose
/// `struct_size` must be `sizeof(SwLodParams)` (start it from `sw_lod_params_default()`):
/// the defaults, or what `sw_surface_set_lod_params` set.
///
/// # Safety
///
/// `out` is NULL or points to a writable struct whose `struct_size` (its first field) is
/// initialised.
#[no_mangle]
pub unsafe extern "C" fn sw_surface_lod_params(
    surface: *const SwSurface,
    out: *mut SwLodParams,
) -> SwStatus {
    read_sized_into(surface, out, |w| Ok(c_lod_params(w.lod.params())))
}

/// Writes the LOD mesh's patches `[across, down]` to `out[0..2]`:
/// `ceil((cols − 1) / patch_cells)` and `ceil((rows − 1) / patch_cells)` once the mesh is
/// built, `[0, 0]` before the first `sw_surface_update_lod` or `sw_surface_set_lod_levels`
/// (and after `sw_surface_set_lod_params`).
///
/// # Safety
///
/// `out` is NULL or points to 2 writable `size_t`.
#[no_mangle]
pub unsafe extern "C" fn sw_surface_lod_patch_grid(
    surface: *const SwSurface,
    out: *mut usize,
) -> SwStatus {
    guard(|| {
        let out = out_array(out, "out")?;
        *out = handle::with(surface, |w| Ok(w.lod.patch_grid()))?;
        Ok(())
    })
}

/// Copies the level of each patch (0 is full detail), row-major over
/// `sw_surface_lod_patch_grid`, to `levels` and writes their number to `count`. With
/// `levels` NULL only `count` is written; a `len` smaller than the number of patches is
/// `SW_ERROR_BUFFER_TOO_SMALL`, with `count` still written.
///
/// # Safety
///
/// `levels` is NULL or points to `len` writable bytes; `count` is NULL or valid.
#[no_mangle]
pub unsafe extern "C" fn sw_surface_lod_patch_levels(
    surface: *const SwSurface,
    levels: *mut u8,
    len: usize,
    count: *mut usize,
) -> SwStatus {
    copy_list_into(surface, (levels, len, "levels"), (count, "count"), |w| {
        Cow::Borrowed(w.lod.patch_levels())
    })
}

/// Copies the LOD level of each triangle of the index buffer (one per triangle, in its
/// order: for colouring a wireframe) to `levels` and writes their number to `count`. With
/// `levels` NULL only `count` is written; a `len` smaller than the number of triangles is
/// `SW_ERROR_BUFFER_TOO_SMALL`, with `count` still written.
///
/// # Safety
///
/// `levels` is NULL or points to `len` writable bytes; `count` is NULL or valid.
#[no_mangle]
pub unsafe extern "C" fn sw_surface_lod_triangle_levels(
    surface: *const SwSurface,
    levels: *mut u8,
    len: usize,
    count: *mut usize,
) -> SwStatus {
    copy_list_into(surface, (levels, len, "levels"), (count, "count"), |w| {
        Cow::Borrowed(w.lod.triangle_levels())
    })
}

/// Builds the LOD index buffer from levels the caller chose, one per patch, row-major
/// (for a renderer with its own error metric, or to force full detail), instead of from an
/// eye: `levels[0..len]` with `len` exactly the number of patches,
/// `ceil((cols − 1) / patch_cells) · ceil((rows − 1) / patch_cells)`; another length is
/// `SW_ERROR_BUFFER_TOO_SMALL` and changes nothing. Levels past the last are taken as the
/// last, then neighbours are kept within one level and stitched as `sw_surface_update_lod`
/// does, whose hysteresis then starts from them. Writes 1 to `changed` (optional) if the
/// index buffer was rebuilt, 0 if it still holds.
///
/// # Safety
///
/// `levels` is NULL or points to `len` bytes; `changed` is NULL or a valid pointer.
#[no_mangle]
pub unsafe extern "C" fn sw_surface_set_lod_levels(
    surface: *mut SwSurface,
    levels: *const u8,
    len: usize,
    changed: *mut SwBool,
) -> SwStatus {
    guard(|| {
        let levels = in_slice(levels, len, "levels")?;
        let changed = optional(changed, "changed")?;
        handle::with(surface, |w| {
            let rebuilt = w.lod.set_levels(&w.surface.mesh_view(), levels)?;
            if let Some(out) = changed {
                *out = rebuilt as SwBool;
            }
            Ok(())
        })
    })
}

/// The body of the calls that fill render buffers as seen from the eye in `refraction`:
/// `buffers` gives the caller's buffers for the surface's node count.
fn fill_from_eye<'a>(
    surface: *const SwSurface,
    refraction: *const SwRefraction,
    buffers: impl FnOnce(usize) -> Outcome<VertexBuffers<'a>>,
) -> SwStatus {
    guard(|| {
        let (eye, params) = refraction_params(input(refraction, "refraction")?)?;
        handle::with(surface, |w| {
            let buffers = buffers(w.surface.node_count())?;
            Ok(fill_frame(&w.surface.mesh_view(), eye, &params, buffers)?)
        })
    })
}

/// The body of the calls that write a per-node vector the library keeps as three
/// component slices (`[x, y, z]`, one value per node each) to the `len` floats at `xyz`,
/// interleaved.
pub(crate) fn write_components(
    surface: *const SwSurface,
    xyz: *mut f32,
    len: usize,
    read: impl FnOnce(&Surface) -> [&[f32]; 3],
) -> SwStatus {
    write_triples(surface, xyz, len, |w, out| {
        let [x, y, z] = read(&w.surface);
        for (o, ((x, y), z)) in out.iter_mut().zip(x.iter().zip(y).zip(z)) {
            *o = [*x, *y, *z];
        }
        Ok(())
    })
}

/// The body of the calls that write one `[x, y, z]` per node to the `len` floats at `xyz`.
fn write_triples(
    surface: *const SwSurface,
    xyz: *mut f32,
    len: usize,
    write: impl FnOnce(&mut Water, &mut [[f32; 3]]) -> Outcome,
) -> SwStatus {
    handle::call(surface, |w| {
        let out = out_groups(xyz, len, w.surface.node_count(), "xyz")?;
        write(w, out)
    })
}
