//! Snapshots: the whole state of a surface as bytes (a versioned binary format with a
//! checksum), written to a caller's buffer, restored into a surface, or loaded as a new
//! one; and the state hash peers compare. Together they are what rollback netcode needs:
//! save every frame into the same buffer, restore an earlier frame, compare hashes.

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
///
/// The surface encodes into a buffer of its own that keeps its capacity, so a game that
/// saves every frame allocates nothing after the first save.
#[no_mangle]
pub unsafe extern "C" fn sw_surface_save(
    surface: *const SwSurface,
    buf: *mut u8,
    len: usize,
    size: *mut usize,
) -> SwStatus {
    copy_list_into(surface, (buf, len, "buf"), (size, "size"), |w| {
        w.surface.save_into(&mut w.save);
        Cow::Borrowed(&w.save[..])
    })
}

/// Writes a 64-bit hash of everything that decides the surface's future (XXH3-64; see the
/// Rust `Surface::state_hash`) to `out`: equal states give equal hashes on every SIMD
/// level, thread count and platform, so peers of a multiplayer game compare it to catch a
/// desync.
///
/// # Safety
///
/// `out` is NULL or valid.
#[no_mangle]
pub unsafe extern "C" fn sw_surface_state_hash(
    surface: *const SwSurface,
    out: *mut u64,
) -> SwStatus {
    guard(|| {
        let out = out_ref(out, "out")?;
        handle::with(surface, |w| {
            *out = w.surface.state_hash();
            Ok(())
        })
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
