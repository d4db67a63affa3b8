//! SSE2, part of every x86-64 CPU: eight `f32` lanes in two 128-bit registers (a
//! [`Pair`] of `__m128` halves, which keeps the out-of-order core busy); masks are
//! all-ones lanes. SSE2 has no blend, so a select is and, and-not, or.

use super::halves::{Half, Pair};
use super::SimdLevel;
use core::arch::x86_64::*;

/// Eight `f32` lanes in two `__m128`, low half first.
pub(crate) type F32x8 = Pair<__m128>;

/// Runs one intrinsic expression. SSE and SSE2 are part of the x86_64 baseline, so every
/// intrinsic here is available on every CPU the crate runs on.
macro_rules! sse {
    ($e:expr) => {
        // SAFETY: SSE2 is part of the x86_64 baseline.
        unsafe { $e }
    };
}

// SAFETY: `__m128` is 16 bytes of plain data: no padding, every bit pattern valid.
unsafe impl Half for __m128 {
    /// All-ones lanes.
    type Mask = __m128;

    const LEVEL: SimdLevel = SimdLevel::Sse2;

    #[inline(always)]
    fn splat(x: f32) -> Self {
        sse!(_mm_set1_ps(x))
    }

    #[inline(always)]
    fn add(self, o: Self) -> Self {
        sse!(_mm_add_ps(self, o))
    }

    #[inline(always)]
    fn sub(self, o: Self) -> Self {
        sse!(_mm_sub_ps(self, o))
    }

    #[inline(always)]
    fn mul(self, o: Self) -> Self {
        sse!(_mm_mul_ps(self, o))
    }

    #[inline(always)]
    fn div(self, o: Self) -> Self {
        sse!(_mm_div_ps(self, o))
    }

    #[inline(always)]
    fn neg(self) -> Self {
        sse!(_mm_xor_ps(self, _mm_set1_ps(-0.0)))
    }

    #[inline(always)]
    fn sqrt(self) -> Self {
        sse!(_mm_sqrt_ps(self))
    }

    #[inline(always)]
    fn abs(self) -> Self {
        sse!(_mm_andnot_ps(_mm_set1_ps(-0.0), self))
    }

    #[inline(always)]
    fn max(self, o: Self) -> Self {
        sse!(_mm_max_ps(self, o))
    }

    #[inline(always)]
    fn min(self, o: Self) -> Self {
        sse!(_mm_min_ps(self, o))
    }

    #[inline(always)]
    fn gt(self, o: Self) -> Self {
        sse!(_mm_cmpgt_ps(self, o))
    }

    #[inline(always)]
    fn lt(self, o: Self) -> Self {
        sse!(_mm_cmplt_ps(self, o))
    }

    #[inline(always)]
    fn ge(self, o: Self) -> Self {
        sse!(_mm_cmpge_ps(self, o))
    }

    /// SSE2 has no blend: and, and-not, or.
    #[inline(always)]
    fn select(m: Self, a: Self, b: Self) -> Self {
        sse!(_mm_or_ps(_mm_and_ps(m, a), _mm_andnot_ps(m, b)))
    }

    #[inline(always)]
    fn mask_and(a: Self, b: Self) -> Self {
        sse!(_mm_and_ps(a, b))
    }

    #[inline(always)]
    fn mask_not(m: Self) -> Self {
        sse!(_mm_xor_ps(m, Self::all_lanes()))
    }

    #[inline(always)]
    fn all_lanes() -> Self {
        sse!(_mm_castsi128_ps(_mm_set1_epi32(-1)))
    }

    #[inline(always)]
    fn lanes_below(first: u32, count: u32) -> Self {
        let f = first as f32;
        let index = sse!(_mm_setr_ps(f, f + 1.0, f + 2.0, f + 3.0));
        index.lt(Self::splat(count as f32))
    }

    #[inline(always)]
    fn all(m: Self) -> bool {
        sse!(_mm_movemask_ps(m)) == 0xf
    }

    #[inline(always)]
    fn any_nan(self) -> bool {
        sse!(_mm_movemask_ps(_mm_cmpunord_ps(self, self))) != 0
    }

    /// `[x1, x2, x3, y0]`.
    #[inline(always)]
    fn east(x: Self, y: Self) -> Self {
        sse!({
            let t = _mm_shuffle_ps::<0b00_00_11_11>(x, y); // x3 x3 y0 y0
            _mm_shuffle_ps::<0b10_00_10_01>(x, t) // x1 x2 x3 y0
        })
    }

    /// `[x3, y0, y1, y2]`.
    #[inline(always)]
    fn west(x: Self, y: Self) -> Self {
        sse!({
            let t = _mm_shuffle_ps::<0b00_00_11_11>(x, y); // x3 x3 y0 y0
            _mm_shuffle_ps::<0b10_01_10_00>(t, y) // x3 y0 y1 y2
        })
    }

    #[inline(always)]
    unsafe fn load(p: *const f32) -> Self {
        // SAFETY: the caller guarantees `p` is readable for 4 floats.
        unsafe { _mm_loadu_ps(p) }
    }

    #[inline(always)]
    unsafe fn store(p: *mut f32, v: Self) {
        // SAFETY: the caller guarantees `p` is writable for 4 floats.
        unsafe { _mm_storeu_ps(p, v) }
    }

    #[inline(always)]
    unsafe fn stream(p: *mut f32, v: Self) {
        // SAFETY: the caller guarantees `p` is writable for 4 floats and 16-byte aligned.
        unsafe { _mm_stream_ps(p, v) }
    }

    #[inline(always)]
    fn fence() {
        sse!(_mm_sfence())
    }
}
