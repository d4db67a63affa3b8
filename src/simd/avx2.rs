//! AVX2: eight `f32` lanes in one 256-bit register; masks are all-ones lanes.
//!
//! The intrinsics need AVX. They are called from `#[inline(always)]` methods without a
//! target feature of their own: they are only ever inlined into
//! [`F32x8::enter`](Vector::enter)'s `#[target_feature(enable = "avx2")]` entry, which
//! [`super::dispatch`] calls only on a CPU that has AVX2. The one AVX2 instruction, the
//! byte align of [`Vector::east`] and [`Vector::west`], is written in assembly in
//! [`align_halves`] (as an intrinsic, LLVM rewrites it with the permute before it), which
//! carries the target feature itself because its `ymm_reg` operands need it.

use super::{SimdLevel, Task, Vector};
use core::arch::x86_64::*;

/// Eight `f32` lanes in a `__m256`.
#[derive(Debug, Clone, Copy)]
#[repr(transparent)]
pub(crate) struct F32x8(__m256);

// SAFETY: `__m256` is 32 bytes of plain data: no padding, every bit pattern valid.
unsafe impl bytemuck::Zeroable for F32x8 {}
// SAFETY: as above; `F32x8` is `repr(transparent)` over it.
unsafe impl bytemuck::Pod for F32x8 {}

/// Runs one intrinsic expression.
macro_rules! avx {
    ($e:expr) => {
        // SAFETY: only reached inside `F32x8::enter`'s AVX2 entry (see the module docs).
        F32x8(unsafe { $e })
    };
}

operators!(F32x8, |a, b| {
    add: avx!(_mm256_add_ps(a.0, b.0)),
    sub: avx!(_mm256_sub_ps(a.0, b.0)),
    mul: avx!(_mm256_mul_ps(a.0, b.0)),
    div: avx!(_mm256_div_ps(a.0, b.0)),
    neg: avx!(_mm256_xor_ps(a.0, _mm256_set1_ps(-0.0))),
});

impl core::ops::BitAnd for F32x8 {
    type Output = Self;
    #[inline(always)]
    fn bitand(self, o: Self) -> Self {
        avx!(_mm256_and_ps(self.0, o.0))
    }
}

impl core::ops::BitAndAssign for F32x8 {
    #[inline(always)]
    fn bitand_assign(&mut self, o: Self) {
        *self = *self & o;
    }
}

impl core::ops::Not for F32x8 {
    type Output = Self;
    #[inline(always)]
    fn not(self) -> Self {
        avx!(_mm256_xor_ps(self.0, F32x8::all_lanes().0))
    }
}

impl Vector for F32x8 {
    const LANES: usize = 8;
    type Mask = F32x8;

    #[inline(always)]
    fn splat(x: f32) -> Self {
        avx!(_mm256_set1_ps(x))
    }

    #[inline(always)]
    fn sqrt(self) -> Self {
        avx!(_mm256_sqrt_ps(self.0))
    }

    #[inline(always)]
    fn abs(self) -> Self {
        avx!(_mm256_andnot_ps(_mm256_set1_ps(-0.0), self.0))
    }

    #[inline(always)]
    fn max(self, o: Self) -> Self {
        avx!(_mm256_max_ps(self.0, o.0))
    }

    #[inline(always)]
    fn min(self, o: Self) -> Self {
        avx!(_mm256_min_ps(self.0, o.0))
    }

    #[inline(always)]
    fn gt(self, o: Self) -> Self {
        avx!(_mm256_cmp_ps::<_CMP_GT_OQ>(self.0, o.0))
    }

    #[inline(always)]
    fn lt(self, o: Self) -> Self {
        avx!(_mm256_cmp_ps::<_CMP_LT_OQ>(self.0, o.0))
    }

    #[inline(always)]
    fn ge(self, o: Self) -> Self {
        avx!(_mm256_cmp_ps::<_CMP_GE_OQ>(self.0, o.0))
    }

    #[inline(always)]
    fn select(m: Self, a: Self, b: Self) -> Self {
        avx!(_mm256_blendv_ps(b.0, a.0, m.0))
    }

    /// One `and`, which equals the blend because every mask is all-ones or all-zero
    /// lanes (compares, [`Vector::first_lanes`], [`Vector::all_lanes`] and their `!` and
    /// `&`). (LLVM compiles a `blendv` against zero to an `and` after an integer compare
    /// that spreads the mask's sign bits again: one more vector instruction per call.)
    #[inline(always)]
    fn keep(m: Self, a: Self) -> Self {
        avx!(_mm256_and_ps(m.0, a.0))
    }

    #[inline(always)]
    fn all_lanes() -> Self {
        avx!(_mm256_castsi256_ps(_mm256_set1_epi32(-1)))
    }

    #[inline(always)]
    fn first_lanes(count: usize) -> Self {
        let index = avx!(_mm256_setr_ps(0.0, 1.0, 2.0, 3.0, 4.0, 5.0, 6.0, 7.0));
        index.lt(Self::splat(count.min(8) as f32))
    }

    #[inline(always)]
    fn all(m: Self) -> bool {
        // SAFETY: inside the AVX2 entry.
        unsafe { _mm256_movemask_ps(m.0) == 0xff }
    }

    #[inline(always)]
    fn any_nan(self) -> bool {
        // SAFETY: inside the AVX2 entry.
        unsafe { _mm256_movemask_ps(_mm256_cmp_ps::<_CMP_UNORD_Q>(self.0, self.0)) != 0 }
    }

    #[inline(always)]
    fn east(lo: Self, hi: Self) -> Self {
        // `mid` = lo[4..8], hi[0..4]; each 128-bit half of `mid:lo` then shifts by one f32.
        avx!({
            let mid = _mm256_permute2f128_ps::<0x21>(lo.0, hi.0);
            align_halves::<4>(mid, lo.0)
        })
    }

    #[inline(always)]
    fn west(lo: Self, hi: Self) -> Self {
        // Each 128-bit half of `hi:mid` shifts by three f32.
        avx!({
            let mid = _mm256_permute2f128_ps::<0x21>(lo.0, hi.0);
            align_halves::<12>(hi.0, mid)
        })
    }

    #[inline(always)]
    unsafe fn load(p: *const f32) -> Self {
        // The caller guarantees `p` is readable for 8 floats.
        avx!(_mm256_loadu_ps(p))
    }

    #[inline(always)]
    unsafe fn store(p: *mut f32, v: Self) {
        // SAFETY: the caller guarantees `p` is writable for 8 floats.
        unsafe { _mm256_storeu_ps(p, v.0) }
    }

    #[inline(always)]
    unsafe fn stream(p: *mut f32, v: Self) {
        // SAFETY: the caller guarantees `p` is writable for 8 floats and 32-byte aligned.
        unsafe { _mm256_stream_ps(p, v.0) }
    }

    #[inline(always)]
    fn fence() {
        // SAFETY: SSE is part of the x86_64 baseline.
        unsafe { _mm_sfence() }
    }

    const LEVEL: SimdLevel = SimdLevel::Avx2;

    #[inline(always)]
    fn enter<T: Task<Self>>(task: T) -> T::Output {
        #[target_feature(enable = "avx2")]
        #[inline(never)]
        fn entry<T: Task<F32x8>>(task: T) -> T::Output {
            super::align_frame();
            task.run()
        }
        assert!(Self::LEVEL.is_available(), "this CPU has no avx2");
        // SAFETY: the CPU has the instruction set (checked above).
        unsafe { entry(task) }
    }
}

/// `_mm256_alignr_epi8::<BYTES>(hi, lo)` as the one `vpalignr` it names: per 128-bit half,
/// the 32 bytes `hi:lo` shifted right by `BYTES`.
///
/// Written with the intrinsic, the permute before it and the align form one two-input
/// shuffle to LLVM, which lowers that as a permute and two `vshufps`: three shuffles per
/// lane shift instead of two, on the FP pipes the row kernel is short of. The assembly keeps
/// the two written (measured in `docs/performance.md`, "a lane shift is two shuffles
/// again").
///
/// # Safety
///
/// The CPU has AVX2.
#[target_feature(enable = "avx2")]
#[inline]
unsafe fn align_halves<const BYTES: i32>(hi: __m256, lo: __m256) -> __m256 {
    let out;
    // SAFETY: `vpalignr` reads and writes registers only, and the caller's CPU has AVX2.
    unsafe {
        core::arch::asm!(
            "vpalignr {out}, {hi}, {lo}, {bytes}",
            out = lateout(ymm_reg) out,
            hi = in(ymm_reg) hi,
            lo = in(ymm_reg) lo,
            bytes = const BYTES,
            options(pure, nomem, nostack, preserves_flags),
        )
    };
    out
}
