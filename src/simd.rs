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
//! were 30% of the step's instructions. Their callers state the `k < count` argument in
//! a `// SAFETY:` line, and `tests/miri.rs` runs the kernels under Miri.
//!
//! Buffers the lane loops stream are [`Floats`]: `f32` buffers that start on a lane
//! boundary. With 64-byte lanes, a chunk load from a `Vec<f32>` (16-byte aligned by the
//! allocator) straddles two cache lines every time; aligning the buffers made the 256²
//! engine step 27% faster on one thread (native build). For the same reason a
//! neighbour one column off is not loaded one element off but shuffled out of two
//! aligned chunks ([`east`], [`west`]), with the instruction each lane type has
//! (`core::arch`: calls that need the target feature the `cfg` above them guarantees).
//! Replacing those loads made the step 10–20% faster (native). [`stream`] writes a chunk
//! with a non-temporal store, for the engine's output on grids larger than the caches.
//!
//! The crate's `unsafe` is these accessors, the intrinsics, and the engine's unchecked
//! reads and writes of its chunk-major scratch rows (`forces::simd`), whose lengths it
//! asserts once per row.

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
/// neighbour of every column of `lo`. A register shuffle or two instead of a load one
/// column off, which with 64-byte lanes straddles two cache lines.
#[inline(always)]
pub fn east(lo: Lane, hi: Lane) -> Lane {
    shift::east(lo, hi)
}

/// Lane `LANES − 1` of `lo` then lanes `..LANES − 1` of `hi`: with `lo` the chunk before
/// `hi`, the west neighbour of every column of `hi`.
#[inline(always)]
pub fn west(lo: Lane, hi: Lane) -> Lane {
    shift::west(lo, hi)
}

/// [`east`] and [`west`] for each lane type `wide` may pick: one `valignd` with AVX-512,
/// a lane-crossing permute and a byte align with AVX2, two shuffles per half with SSE2.
#[cfg(all(target_arch = "x86_64", target_feature = "avx512f"))]
mod shift {
    use super::Lane;
    use core::arch::x86_64::{_mm512_alignr_epi32, _mm512_castps_si512, _mm512_castsi512_ps};

    /// Lanes `N..` of `lo` then lanes `..N` of `hi` (one `valignd`).
    #[inline(always)]
    fn align<const N: i32>(lo: Lane, hi: Lane) -> Lane {
        // SAFETY: AVX-512F is enabled for this build (the `cfg` on this module).
        unsafe {
            let (lo, hi) = (
                _mm512_castps_si512(lo.into()),
                _mm512_castps_si512(hi.into()),
            );
            Lane::from(_mm512_castsi512_ps(_mm512_alignr_epi32::<N>(hi, lo)))
        }
    }

    #[inline(always)]
    pub fn east(lo: Lane, hi: Lane) -> Lane {
        align::<1>(lo, hi)
    }

    #[inline(always)]
    pub fn west(lo: Lane, hi: Lane) -> Lane {
        align::<15>(lo, hi)
    }
}

#[cfg(all(
    target_arch = "x86_64",
    not(target_feature = "avx512f"),
    target_feature = "avx2"
))]
mod shift {
    use super::Lane;
    use core::arch::x86_64::{
        _mm256_alignr_epi8, _mm256_castps_si256, _mm256_castsi256_ps, _mm256_permute2f128_ps,
    };

    #[inline(always)]
    pub fn east(lo: Lane, hi: Lane) -> Lane {
        // SAFETY: AVX2 is enabled for this build (the `cfg` on this module).
        unsafe {
            // `mid` = lo[4..8], hi[0..4]; each 128-bit half then shifts by one f32.
            let mid = _mm256_permute2f128_ps::<0x21>(lo.into(), hi.into());
            let (lo, mid) = (_mm256_castps_si256(lo.into()), _mm256_castps_si256(mid));
            Lane::from(_mm256_castsi256_ps(_mm256_alignr_epi8::<4>(mid, lo)))
        }
    }

    #[inline(always)]
    pub fn west(lo: Lane, hi: Lane) -> Lane {
        // SAFETY: AVX2 is enabled for this build (the `cfg` on this module).
        unsafe {
            let mid = _mm256_permute2f128_ps::<0x21>(lo.into(), hi.into());
            let (hi, mid) = (_mm256_castps_si256(hi.into()), _mm256_castps_si256(mid));
            Lane::from(_mm256_castsi256_ps(_mm256_alignr_epi8::<12>(hi, mid)))
        }
    }
}

#[cfg(all(
    target_arch = "x86_64",
    not(target_feature = "avx512f"),
    not(target_feature = "avx2"),
    not(target_feature = "avx")
))]
mod shift {
    //! `wide`'s 8-lane type here is two SSE registers, `[a, b]`.
    use super::Lane;
    use core::arch::x86_64::{__m128, _mm_shuffle_ps};
    use wide::f32x4;

    fn halves(v: Lane) -> [__m128; 2] {
        bytemuck::cast::<Lane, [f32x4; 2]>(v).map(Into::into)
    }

    fn join(h: [__m128; 2]) -> Lane {
        bytemuck::cast::<[f32x4; 2], Lane>(h.map(f32x4::from))
    }

    /// `[x1, x2, x3, y0]`.
    #[inline(always)]
    fn east4(x: __m128, y: __m128) -> __m128 {
        // SAFETY: SSE is part of the x86_64 baseline.
        unsafe {
            let t = _mm_shuffle_ps::<0b00_00_11_11>(x, y); // x3 x3 y0 y0
            _mm_shuffle_ps::<0b10_00_10_01>(x, t) // x1 x2 x3 y0
        }
    }

    /// `[x3, y0, y1, y2]`.
    #[inline(always)]
    fn west4(x: __m128, y: __m128) -> __m128 {
        // SAFETY: SSE is part of the x86_64 baseline.
        unsafe {
            let t = _mm_shuffle_ps::<0b00_00_11_11>(x, y); // x3 x3 y0 y0
            _mm_shuffle_ps::<0b10_01_10_00>(t, y) // x3 y0 y1 y2
        }
    }

    #[inline(always)]
    pub fn east(lo: Lane, hi: Lane) -> Lane {
        let ([a, b], [c, _]) = (halves(lo), halves(hi));
        join([east4(a, b), east4(b, c)])
    }

    #[inline(always)]
    pub fn west(lo: Lane, hi: Lane) -> Lane {
        let ([_, b], [c, d]) = (halves(lo), halves(hi));
        join([west4(b, c), west4(c, d)])
    }
}

#[cfg(not(any(
    all(target_arch = "x86_64", target_feature = "avx512f"),
    all(target_arch = "x86_64", target_feature = "avx2"),
    all(
        target_arch = "x86_64",
        not(target_feature = "avx2"),
        not(target_feature = "avx")
    )
)))]
mod shift {
    //! Any other target: plain lane arithmetic, left to the compiler.
    use super::{Lane, LANES};

    #[inline(always)]
    pub fn east(lo: Lane, hi: Lane) -> Lane {
        let (lo, hi) = (lo.to_array(), hi.to_array());
        Lane::new(core::array::from_fn(|i| {
            if i + 1 < LANES {
                lo[i + 1]
            } else {
                hi[0]
            }
        }))
    }

    #[inline(always)]
    pub fn west(lo: Lane, hi: Lane) -> Lane {
        let (lo, hi) = (lo.to_array(), hi.to_array());
        Lane::new(core::array::from_fn(|i| {
            if i == 0 {
                lo[LANES - 1]
            } else {
                hi[i - 1]
            }
        }))
    }
}

/// Stores `v` into chunk `k` of a view with a non-temporal store: the cache line goes to
/// memory without being read first or kept in cache. For output that the next reads will
/// not find in cache anyway; call [`stream_fence`] before another thread reads it.
///
/// # Safety
///
/// `k < view.len()`, and chunk `k` starts on a `size_of::<Lane>()` boundary.
#[inline(always)]
pub unsafe fn stream(view: &mut [[f32; LANES]], k: usize, v: Lane) {
    debug_assert!(k < view.len());
    // SAFETY: `k < view.len()`.
    let p = unsafe { view.as_mut_ptr().add(k) }.cast::<f32>();
    debug_assert!((p as usize).is_multiple_of(core::mem::size_of::<Lane>()));
    // SAFETY: `p` is valid for `LANES` floats and aligned to a whole lane.
    unsafe { nt::store(p, v) }
}

/// Makes every [`stream`] store of this thread visible before its later stores (x86's
/// `sfence`; nothing where streaming falls back to plain stores).
#[inline(always)]
pub fn stream_fence() {
    nt::fence()
}

/// Non-temporal stores: one `vmovntps` per chunk with AVX-512, 16-byte `movntps` with
/// SSE and AVX2, plain stores elsewhere (and under Miri).
#[cfg(all(target_arch = "x86_64", not(miri), target_feature = "avx512f"))]
mod nt {
    use super::Lane;
    use core::arch::x86_64::{_mm512_stream_ps, _mm_sfence};

    /// # Safety
    ///
    /// `p` is valid for a lane's floats and 64-byte aligned.
    #[inline(always)]
    pub unsafe fn store(p: *mut f32, v: Lane) {
        // SAFETY: AVX-512F is enabled for this build; the caller guarantees `p`.
        unsafe { _mm512_stream_ps(p, v.into()) }
    }

    #[inline(always)]
    pub fn fence() {
        // SAFETY: SSE is part of the x86_64 baseline.
        unsafe { _mm_sfence() }
    }
}

#[cfg(all(target_arch = "x86_64", not(miri), not(target_feature = "avx512f")))]
mod nt {
    use super::{Lane, LANES};
    use core::arch::x86_64::{_mm_loadu_ps, _mm_sfence, _mm_stream_ps};

    /// # Safety
    ///
    /// `p` is valid for a lane's floats and 16-byte aligned.
    #[inline(always)]
    pub unsafe fn store(p: *mut f32, v: Lane) {
        let a = v.to_array();
        for i in (0..LANES).step_by(4) {
            // SAFETY: SSE is part of the x86_64 baseline; `p + i` is valid for 4 floats
            // and 16-byte aligned, `a[i..i + 4]` readable.
            unsafe { _mm_stream_ps(p.add(i), _mm_loadu_ps(a.as_ptr().add(i))) }
        }
    }

    #[inline(always)]
    pub fn fence() {
        // SAFETY: SSE is part of the x86_64 baseline.
        unsafe { _mm_sfence() }
    }
}

#[cfg(not(all(target_arch = "x86_64", not(miri))))]
mod nt {
    use super::{Lane, LANES};

    /// # Safety
    ///
    /// `p` is valid for a lane's floats.
    #[inline(always)]
    pub unsafe fn store(p: *mut f32, v: Lane) {
        // SAFETY: the caller guarantees `p`.
        unsafe { p.cast::<[f32; LANES]>().write_unaligned(v.to_array()) }
    }

    #[inline(always)]
    pub fn fence() {}
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn east_and_west_shift_by_one_column() {
        let lo = Lane::new(core::array::from_fn(|i| i as f32));
        let hi = Lane::new(core::array::from_fn(|i| (LANES + i) as f32));
        let e = east(lo, hi).to_array();
        let w = west(lo, hi).to_array();
        for i in 0..LANES {
            assert_eq!(e[i], (i + 1) as f32, "east lane {i}");
            assert_eq!(w[i], (LANES + i) as f32 - 1.0, "west lane {i}");
        }
    }
}
