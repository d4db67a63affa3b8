//! Snapshots: the whole state of a surface as bytes (a versioned binary format with a
//! checksum), written to a caller's buffer, restored into a surface, or loaded as a new
//! one.

use crate::handle::{self, SwSurface, Water};
use crate::ptr::{copy_list_into, in_slice, out_ref};
use crate::status::{guard, SwStatus};
use springwater::Surface;
use std::borrow::Cow;

/// Writes a snapshot of the whole state (a versioned binary format with a checksum) to
/// `buf` and its size in bytes to `size`. With `buf` NULL only `size` is written; a `len`
/// smaller than the snapshot is `SW_ERROR_BUFFER_TOO_SMALL`, with `size` still written.
///
/// # Safety
///
/// `buf` is NULL or points to `len` writable bytes; `size` is NULL or valid.
#[no_mangle]
pub unsafe extern "C" fn sw_surface_save(
    surface: *const SwSurface,
    buf: *mut u8,
    len: usize,
    size: *mut usize,
) -> SwStatus {
    copy_list_into(surface, (buf, len, "buf"), (size, "size"), |w| {
        Cow::Owned(w.surface.to_bytes())
    })
}

/// Replaces the surface's state with a snapshot (`len` bytes at `buf`), keeping its job
/// system, SIMD level and LOD parameters. A damaged snapshot is refused and nothing
/// changes.
///
/// # Safety
///
/// `buf` is NULL or points to `len` readable bytes.
#[no_mangle]
pub unsafe extern "C" fn sw_surface_restore(
    surface: *mut SwSurface,
    buf: *const u8,
    len: usize,
) -> SwStatus {
    guard(|| {
        let bytes = in_slice(buf, len, "buf")?;
        handle::with(surface, |w| Ok(w.surface.restore(bytes)?))
    })
}

/// Creates a surface from a snapshot (`len` bytes at `buf`) and writes its handle to
/// `out`.
///
/// # Safety
///
/// `buf` is NULL or points to `len` readable bytes; `out` is NULL or valid.
#[no_mangle]
pub unsafe extern "C" fn sw_surface_load(
    buf: *const u8,
    len: usize,
    out: *mut *mut SwSurface,
) -> SwStatus {
    guard(|| {
        let bytes = in_slice(buf, len, "buf")?;
        let out = out_ref(out, "out")?;
        let surface = Surface::from_bytes(bytes)?;
        *out = handle::insert(Water::new(surface));
        Ok(())
    })
}
