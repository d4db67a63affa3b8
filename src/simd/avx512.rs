//! AVX-512F: sixteen `f32` lanes in one 512-bit register; masks live in mask registers
//! (`__mmask16`), so a select is one masked blend and a compare writes no vector.
//!
//! As with [`super::avx2`], the intrinsics are called from `#[inline(always)]` methods
//! that are only ever inlined into [`F32x16::enter`](Vector::enter)'s `#[target_feature(enable =
//! "avx512f")]` entry, which [`super::dispatch`] calls only on a CPU that has AVX-512F.

use super::{SimdLevel, Task, Vector};
use core::arch::x86_64::*;

/// Sixteen `f32` lanes in a `__m512`.
#[derive(Debug, Clone, Copy)]
#[repr(transparent)]
pub(crate) struct F32x16(__m512);

// SAFETY: `__m512` is 64 bytes of plain data: no padding, every bit pattern valid.
unsafe impl bytemuck::Zeroable for F32x16 {}
// SAFETY: as above; `F32x16` is `repr(transparent)` over it.
unsafe impl bytemuck::Pod for F32x16 {}

/// A lane mask of [`F32x16`]: bit `i` for lane `i`.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub(crate) struct Mask16(__mmask16);

/// Runs one intrinsic expression.
macro_rules! avx512 {
    ($e:expr) => {
        // SAFETY: only reached inside `F32x16::run`'s AVX-512F entry (see the module docs).
        unsafe { $e }
    };
}

/// Flips the bits of `a` where `b` has them (AVX-512F has no `xorps` on `__m512`).
#[inline(always)]
fn xor(a: __m512, b: __m512) -> __m512 {
    avx512!(_mm512_castsi512_ps(_mm512_xor_si512(
        _mm512_castps_si512(a),
        _mm512_castps_si512(b)
    )))
}

operators!(F32x16, |a, b| {
    add: F32x16(avx512!(_mm512_add_ps(a.0, b.0))),
    sub: F32x16(avx512!(_mm512_sub_ps(a.0, b.0))),
    mul: F32x16(avx512!(_mm512_mul_ps(a.0, b.0))),
    div: F32x16(avx512!(_mm512_div_ps(a.0, b.0))),
    neg: F32x16(xor(a.0, avx512!(_mm512_set1_ps(-0.0)))),
});

impl core::ops::BitAnd for Mask16 {
    type Output = Self;
    #[inline(always)]
    fn bitand(self, o: Self) -> Self {
        Self(self.0 & o.0)
    }
}

impl core::ops::BitAndAssign for Mask16 {
    #[inline(always)]
    fn bitand_assign(&mut self, o: Self) {
        self.0 &= o.0;
    }
}

impl core::ops::Not for Mask16 {
    type Output = Self;
    #[inline(always)]
    fn not(self) -> Self {
        Self(!self.0)
    }
}

impl F32x16 {
    /// `A` of `self` against `o`, per lane.
    #[inline(always)]
    fn cmp<const A: i32>(self, o: Self) -> Mask16 {
        Mask16(avx512!(_mm512_cmp_ps_mask::<A>(self.0, o.0)))
    }

    /// Lanes `N..` of `lo` then lanes `..N` of `hi` (one `valignd`).
    #[inline(always)]
    fn align<const N: i32>(lo: Self, hi: Self) -> Self {
        F32x16(avx512!({
            let (lo, hi) = (_mm512_castps_si512(lo.0), _mm512_castps_si512(hi.0));
            _mm512_castsi512_ps(_mm512_alignr_epi32::<N>(hi, lo))
        }))
    }
}

impl Vector for F32x16 {
    const LANES: usize = 16;
    type Mask = Mask16;

    #[inline(always)]
    fn splat(x: f32) -> Self {
        F32x16(avx512!(_mm512_set1_ps(x)))
    }

    #[inline(always)]
    fn sqrt(self) -> Self {
        F32x16(avx512!(_mm512_sqrt_ps(self.0)))
    }

    #[inline(always)]
    fn abs(self) -> Self {
        F32x16(avx512!(_mm512_abs_ps(self.0)))
    }

    #[inline(always)]
    fn max(self, o: Self) -> Self {
        F32x16(avx512!(_mm512_max_ps(self.0, o.0)))
    }

    #[inline(always)]
    fn min(self, o: Self) -> Self {
        F32x16(avx512!(_mm512_min_ps(self.0, o.0)))
    }

    #[inline(always)]
    fn gt(self, o: Self) -> Mask16 {
        self.cmp::<_CMP_GT_OQ>(o)
    }

    #[inline(always)]
    fn lt(self, o: Self) -> Mask16 {
        self.cmp::<_CMP_LT_OQ>(o)
    }

    #[inline(always)]
    fn ge(self, o: Self) -> Mask16 {
        self.cmp::<_CMP_GE_OQ>(o)
    }

    #[inline(always)]
    fn select(m: Mask16, a: Self, b: Self) -> Self {
        F32x16(avx512!(_mm512_mask_blend_ps(m.0, b.0, a.0)))
    }

    #[inline(always)]
    fn all_lanes() -> Mask16 {
        Mask16(u16::MAX)
    }

    #[inline(always)]
    fn first_lanes(count: usize) -> Mask16 {
        Mask16(((1u32 << count.min(16)) - 1) as u16)
    }

    #[inline(always)]
    fn all(m: Mask16) -> bool {
        m.0 == u16::MAX
    }

    #[inline(always)]
    fn any_nan(self) -> bool {
        self.cmp::<_CMP_UNORD_Q>(self).0 != 0
    }

    #[inline(always)]
    fn east(lo: Self, hi: Self) -> Self {
        Self::align::<1>(lo, hi)
    }

    #[inline(always)]
    fn west(lo: Self, hi: Self) -> Self {
        Self::align::<15>(lo, hi)
    }

    #[inline(always)]
    unsafe fn load(p: *const f32) -> Self {
        // SAFETY: the caller guarantees `p` is readable for 16 floats.
        F32x16(unsafe { _mm512_loadu_ps(p) })
    }

    #[inline(always)]
    unsafe fn store(p: *mut f32, v: Self) {
        // SAFETY: the caller guarantees `p` is writable for 16 floats.
        unsafe { _mm512_storeu_ps(p, v.0) }
    }

    #[inline(always)]
    unsafe fn stream(p: *mut f32, v: Self) {
        // SAFETY: the caller guarantees `p` is writable for 16 floats and 64-byte aligned.
        unsafe { _mm512_stream_ps(p, v.0) }
    }

    #[inline(always)]
    fn fence() {
        // SAFETY: SSE is part of the x86_64 baseline.
        unsafe { _mm_sfence() }
    }

    const LEVEL: SimdLevel = SimdLevel::Avx512;

    #[inline(always)]
    fn enter<T: Task<Self>>(task: T) -> T::Output {
        #[target_feature(enable = "avx512f")]
        #[inline(never)]
        fn entry<T: Task<F32x16>>(task: T) -> T::Output {
            super::align_frame();
            task.run()
        }
        assert!(Self::LEVEL.is_available(), "this CPU has no avx512f");
        // SAFETY: the CPU has the instruction set (checked above).
        unsafe { entry(task) }
    }
}
