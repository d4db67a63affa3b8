//! The one place that names the SIMD lane type.
//!
//! `wide` chooses instructions at build time: with AVX-512 enabled
//! (`-C target-cpu=native` on this machine) a lane holds 16 `f32`, otherwise 8
//! (AVX2 with `+avx2`, two SSE registers in a default x86-64 build). The rest of the
//! crate says [`Lane`] and [`LANES`].
//!
//! Lane loops see their data through *chunk views* ([`lanes`], [`lanes_mut`]): a slice
//! of `[f32; LANES]` arrays starting at any element, cut to exactly the number of chunks
//! the loop runs over. The length check happens once, when the view is made. Inside the
//! loop, [`get`] and [`put`] access chunk `k < count` without a bounds check: measured
//! with callgrind on the 256² step, the checks the compiler could not remove on its own
//! were 30% of the step's instructions. These two functions are the crate's only
//! `unsafe`; their callers state the `k < count` argument in a `// SAFETY:` line, and
//! `tests/miri.rs` runs the kernels under Miri.

#[cfg(target_feature = "avx512f")]
mod pick {
    /// A vector of `f32` lanes.
    pub type Lane = wide::f32x16;
}
#[cfg(not(target_feature = "avx512f"))]
mod pick {
    /// A vector of `f32` lanes.
    pub type Lane = wide::f32x8;
}
pub use pick::Lane;

/// Number of `f32` in a [`Lane`].
pub const LANES: usize = core::mem::size_of::<Lane>() / 4;

/// `count` lane-sized chunks of `s` from element `start` on: chunk `k` is
/// `s[start + k·LANES ..][..LANES]`. Panics if `s` is shorter than that.
#[inline(always)]
pub fn lanes(s: &[f32], start: usize, count: usize) -> &[[f32; LANES]] {
    &s[start..].as_chunks::<LANES>().0[..count]
}

/// Mutable [`lanes`].
#[inline(always)]
pub fn lanes_mut(s: &mut [f32], start: usize, count: usize) -> &mut [[f32; LANES]] {
    &mut s[start..].as_chunks_mut::<LANES>().0[..count]
}

/// Chunk `k` of a view, without a bounds check.
///
/// # Safety
///
/// `k < view.len()`.
#[inline(always)]
pub unsafe fn get(view: &[[f32; LANES]], k: usize) -> Lane {
    debug_assert!(k < view.len());
    // SAFETY: the caller guarantees `k < view.len()`.
    Lane::new(unsafe { *view.get_unchecked(k) })
}

/// Stores `v` into chunk `k` of a view, without a bounds check.
///
/// # Safety
///
/// `k < view.len()`.
#[inline(always)]
pub unsafe fn put(view: &mut [[f32; LANES]], k: usize, v: Lane) {
    debug_assert!(k < view.len());
    // SAFETY: the caller guarantees `k < view.len()`.
    unsafe { *view.get_unchecked_mut(k) = v.to_array() };
}

/// A mask lane: all-ones where `lane index < count`.
#[inline(always)]
pub fn first_lanes(count: usize) -> Lane {
    let mut m = [0.0f32; LANES];
    for (i, v) in m.iter_mut().enumerate() {
        *v = if i < count {
            f32::from_bits(u32::MAX)
        } else {
            0.0
        };
    }
    Lane::new(m)
}

/// Rounds `n` up to a multiple of `LANES`.
pub const fn round_up(n: usize) -> usize {
    n.div_ceil(LANES) * LANES
}
