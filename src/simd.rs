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
//!
//! Buffers the lane loops stream are [`Floats`]: `f32` buffers that start on a lane
//! boundary. With 64-byte lanes, a chunk load from a `Vec<f32>` (16-byte aligned by the
//! allocator) straddles two cache lines every time; aligning the buffers made the 256²
//! engine step 27% faster on one thread (native build).

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

/// A zero-initialised `f32` buffer that starts on a lane boundary (64 B with AVX-512,
/// 32 B otherwise), so that chunk loads at multiples of [`LANES`] never straddle two
/// cache lines. Dereferences to `[f32]`.
#[derive(Clone, Default)]
pub struct Floats {
    chunks: Vec<Lane>,
    len: usize,
}

impl Floats {
    /// `len` zeros.
    pub fn zeros(len: usize) -> Self {
        Self {
            chunks: vec![Lane::ZERO; len.div_ceil(LANES)],
            len,
        }
    }
}

impl std::ops::Deref for Floats {
    type Target = [f32];
    #[inline(always)]
    fn deref(&self) -> &[f32] {
        &bytemuck::cast_slice(&self.chunks)[..self.len]
    }
}

impl std::ops::DerefMut for Floats {
    #[inline(always)]
    fn deref_mut(&mut self) -> &mut [f32] {
        &mut bytemuck::cast_slice_mut(&mut self.chunks)[..self.len]
    }
}

impl std::fmt::Debug for Floats {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.debug_list().entries(self.iter()).finish()
    }
}

/// Lanes `1..` of `lo` then lane 0 of `hi`: with `hi` the chunk after `lo`, the east
/// neighbour of every column of `lo`. One register shuffle instead of a load that
/// straddles two cache lines.
#[inline(always)]
pub fn east(lo: Lane, hi: Lane) -> Lane {
    #[cfg(target_feature = "avx512f")]
    {
        use core::arch::x86_64::{_mm512_alignr_epi32, _mm512_castps_si512, _mm512_castsi512_ps};
        // SAFETY: these intrinsics only need AVX-512F, which this build enables (`cfg` above).
        unsafe {
            let (lo, hi) = (_mm512_castps_si512(lo.into()), _mm512_castps_si512(hi.into()));
            Lane::from(_mm512_castsi512_ps(_mm512_alignr_epi32::<1>(hi, lo)))
        }
    }
    #[cfg(not(target_feature = "avx512f"))]
    {
        let (lo, hi) = (lo.to_array(), hi.to_array());
        Lane::new(core::array::from_fn(|i| if i + 1 < LANES { lo[i + 1] } else { hi[0] }))
    }
}

/// Lane `LANES − 1` of `lo` then lanes `..LANES − 1` of `hi`: with `lo` the chunk before
/// `hi`, the west neighbour of every column of `hi`.
#[inline(always)]
pub fn west(lo: Lane, hi: Lane) -> Lane {
    #[cfg(target_feature = "avx512f")]
    {
        use core::arch::x86_64::{_mm512_alignr_epi32, _mm512_castps_si512, _mm512_castsi512_ps};
        // SAFETY: these intrinsics only need AVX-512F, which this build enables (`cfg` above).
        unsafe {
            let (lo, hi) = (_mm512_castps_si512(lo.into()), _mm512_castps_si512(hi.into()));
            Lane::from(_mm512_castsi512_ps(_mm512_alignr_epi32::<15>(hi, lo)))
        }
    }
    #[cfg(not(target_feature = "avx512f"))]
    {
        let (lo, hi) = (lo.to_array(), hi.to_array());
        Lane::new(core::array::from_fn(|i| if i == 0 { lo[LANES - 1] } else { hi[i - 1] }))
    }
}
