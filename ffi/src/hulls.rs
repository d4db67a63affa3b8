//! Hull meshes the library makes or reads (`springwater::body::Hull`, `BoatShape`): a box,
//! the procedural boat, a hull moved onto its centroid, and what a hull is (its centroid,
//! its bounding radius, its vertices and triangles, to draw it). Each maker writes a new
//! `SwHull *`, freed with `sw_hull_destroy` like one from `sw_hull_create`.

use crate::bodies::{hull_of, SwHull, HULLS};
use crate::params::finite_positive;
use crate::ptr::{input, out_array, out_buffer, out_ref, Input};
use crate::status::{guard, Outcome, SwStatus};
use springwater::body::{BoatShape, Hull};
use springwater::Shape;

/// The dimensions and resolution of the procedural boat (`sw_hull_boat`);
/// `sw_boat_shape_default()` gives the defaults. Body frame: the bow points to +x, y is
/// up, starboard is +z, the origin on the keel amidships (`sw_hull_centred` moves it onto
/// the centroid); a displacement hull with a flat transom, a sharp stem, round bilges
/// amidships that sharpen forward and a sheer that rises to the bow.
/// `4 · stations · segments + 2 · stations + 2 · segments` triangles.
#[repr(C)]
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct SwBoatShape {
    /// `sizeof(SwBoatShape)`, set by `sw_boat_shape_default()`: calls that read the struct
    /// refuse any other value (a struct not started from it, or built with a header of
    /// another version than the library's).
    pub struct_size: u32,
    /// Length overall, transom to stem, world units (> 0; default 6).
    pub length: f32,
    /// Greatest beam, world units (> 0; default 2).
    pub beam: f32,
    /// Depth from the keel to the deck amidships, world units (> 0; default 1).
    pub depth: f32,
    /// Cross-sections from the transom to the stem (2 to 1024; default 40).
    pub stations: u32,
    /// Edges per side of each cross-section (2 to 1024; default 12).
    pub segments: u32,
}

impl Input for SwBoatShape {
    const MAKER: &'static str = "sw_boat_shape_default()";
}

const _: () = assert!(std::mem::offset_of!(SwBoatShape, struct_size) == 0);

/// The library's default boat: 6 long, 2 wide, 1 deep, 40 stations of 12 edges a side
/// (2,024 triangles).
#[no_mangle]
pub extern "C" fn sw_boat_shape_default() -> SwBoatShape {
    let b = BoatShape::default();
    SwBoatShape {
        struct_size: size_of::<SwBoatShape>() as u32,
        length: b.length,
        beam: b.beam,
        depth: b.depth,
        stations: b.stations,
        segments: b.segments,
    }
}

/// Generates the boat `shape` describes and writes a new hull handle to `out`. A dimension
/// out of range is `SW_ERROR_INVALID_ARGUMENT`, named in the message, and makes nothing.
///
/// # Safety
///
/// `shape` and `out` are NULL or valid pointers.
#[no_mangle]
pub unsafe extern "C" fn sw_hull_boat(
    shape: *const SwBoatShape,
    out: *mut *mut SwHull,
) -> SwStatus {
    guard(|| {
        let s = input(shape, "shape")?;
        let out = out_ref(out, "out")?;
        let mut boat = BoatShape::default();
        boat.length = s.length;
        boat.beam = s.beam;
        boat.depth = s.depth;
        boat.stations = s.stations;
        boat.segments = s.segments;
        keep(boat.hull(), out)
    })
}

/// A box hull of half extents `(half_x, half_y, half_z)` centred on the origin (8
/// vertices, 12 triangles), written to `out` as a new handle. Each half extent must be
/// finite and above 0, and at most 1e9, or the call is `SW_ERROR_INVALID_ARGUMENT`.
///
/// # Safety
///
/// `out` is NULL or a valid pointer.
#[no_mangle]
pub unsafe extern "C" fn sw_hull_cuboid(
    half_x: f32,
    half_y: f32,
    half_z: f32,
    out: *mut *mut SwHull,
) -> SwStatus {
    guard(|| {
        let out = out_ref(out, "out")?;
        for (what, v) in [("half_x", half_x), ("half_y", half_y), ("half_z", half_z)] {
            finite_positive(what, v)?;
        }
        keep(Hull::cuboid([half_x, half_y, half_z]), out)
    })
}

/// The mesh of `hull` moved so that its centroid (the centre of mass at uniform density)
/// is at the origin of the body frame, written to `out` as a new handle; `hull` stays as
/// it is.
///
/// # Safety
///
/// `out` is NULL or a valid pointer.
#[no_mangle]
pub unsafe extern "C" fn sw_hull_centred(hull: *const SwHull, out: *mut *mut SwHull) -> SwStatus {
    guard(|| {
        let hull = hull_of(hull)?;
        let out = out_ref(out, "out")?;
        keep(hull.centred(), out)
    })
}

/// Writes the centroid of the volume `hull` encloses, body frame, world units, to
/// `out[0..3]`: the centre of mass at uniform density.
///
/// # Safety
///
/// `out` is NULL or points to 3 writable floats.
#[no_mangle]
pub unsafe extern "C" fn sw_hull_centroid(hull: *const SwHull, out: *mut f32) -> SwStatus {
    guard(|| {
        let out = out_array(out, "out")?;
        *out = hull_of(hull)?.centroid().to_array();
        Ok(())
    })
}

/// Writes to `out` the distance from the body frame's origin to the hull's farthest vertex,
/// world units: the radius of a ball that holds a body of this hull in any orientation.
///
/// # Safety
///
/// `out` is NULL or a valid pointer.
#[no_mangle]
pub unsafe extern "C" fn sw_hull_bounding_radius(hull: *const SwHull, out: *mut f32) -> SwStatus {
    guard(|| {
        let out = out_ref(out, "out")?;
        *out = Shape::Hull(hull_of(hull)?).bounding_radius();
        Ok(())
    })
}

/// Copies the hull's vertices, body frame, three floats each, to `xyz` (`len` in floats)
/// and writes their number, in vertices, to `count`: the mesh to draw a hull the library
/// made. With `xyz` NULL only `count` is written; a `len` under `3 · count` is
/// `SW_ERROR_BUFFER_TOO_SMALL`, with `count` still written.
///
/// # Safety
///
/// `xyz` is NULL or points to `len` writable floats; `count` is NULL or a valid pointer.
#[no_mangle]
pub unsafe extern "C" fn sw_hull_vertices(
    hull: *const SwHull,
    xyz: *mut f32,
    len: usize,
    count: *mut usize,
) -> SwStatus {
    guard(|| {
        let count = out_ref(count, "count")?;
        let hull = hull_of(hull)?;
        copy_triples(hull.vertices(), (xyz, len, "xyz"), count)
    })
}

/// Copies the hull's triangles, three vertex indices each, counter-clockwise seen from
/// outside, to `indices` (`len` in indices) and writes their number, in triangles, to
/// `count`. With `indices` NULL only `count` is written; a `len` under `3 · count` is
/// `SW_ERROR_BUFFER_TOO_SMALL`, with `count` still written.
///
/// # Safety
///
/// `indices` is NULL or points to `len` writable `uint32_t`; `count` is NULL or a valid
/// pointer.
#[no_mangle]
pub unsafe extern "C" fn sw_hull_triangles(
    hull: *const SwHull,
    indices: *mut u32,
    len: usize,
    count: *mut usize,
) -> SwStatus {
    guard(|| {
        let count = out_ref(count, "count")?;
        let hull = hull_of(hull)?;
        copy_triples(hull.triangles(), (indices, len, "indices"), count)
    })
}

/// Writes `list.len()` to `count` and, unless `ptr` is NULL, the list to the `len`
/// elements at `ptr`, which must hold `3 · list.len()`.
fn copy_triples<T: Copy>(
    list: &[[T; 3]],
    (ptr, len, what): (*mut T, usize, &str),
    count: &mut usize,
) -> Outcome {
    *count = list.len();
    if !ptr.is_null() {
        let out = out_buffer(ptr, len, list.len().saturating_mul(3), what)?;
        for (o, v) in out.chunks_exact_mut(3).zip(list) {
            o.copy_from_slice(v);
        }
    }
    Ok(())
}

/// Registers the hull `made` and writes its new handle to `out`.
fn keep(made: springwater::Result<Hull>, out: &mut *mut SwHull) -> Outcome {
    let hull = made?;
    *out = HULLS.insert(hull) as *mut SwHull;
    Ok(())
}
