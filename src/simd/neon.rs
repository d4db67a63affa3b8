//! NEON (Advanced SIMD), part of every AArch64 CPU: eight `f32` lanes in two 128-bit
//! registers; masks are all-ones `u32` lanes.
//!
//! Why eight lanes and not four: the engine's rows, padding and chunk bookkeeping are laid
//! out for chunks of 8 or 16 floats, and two independent halves per operation are what
//! AArch64 cores want anyway (a Cortex-A76 or Neoverse N1 has two 128-bit FP pipes, an
//! Apple core four): the second half fills the pipe while the first waits on its latency.
//! With 32 vector registers, AArch64 holds twice the live values SSE2 does at the same
//! width, so the row kernel spills less here than in the SSE2 build.
//!
//! Every operation is one IEEE operation per lane, as on the other levels:
//! `vaddq`/`vsubq`/`vmulq`/`vdivq`/`vsqrtq` and never `vfmaq`/`vmlaq` (a fused or chained
//! multiply-add rounds once where the reference rounds twice). `max`/`min` are a compare
//! and a bitwise select, never `vmaxq`/`vminq`: those return NaN where either operand is
//! NaN and order −0 below +0, where `maxps`/`minps` (and the reference's `if a > b`) return
//! the second operand. Negation and `abs` only touch the sign bit (`fneg`, `fabs`), as the
//! x86 levels' `xor`/`andnot` do.

use super::halves::{Half, Pair};
use super::SimdLevel;
use core::arch::aarch64::*;

/// Eight `f32` lanes in two `float32x4_t`, low half first; masks are pairs of `uint32x4_t`.
pub(crate) type F32x8 = Pair<float32x4_t>;

/// Runs one intrinsic expression. NEON is part of the AArch64 baseline, so every intrinsic
/// here is available on every CPU the crate runs on.
macro_rules! neon {
    ($e:expr) => {{
        // SAFETY: NEON is part of the aarch64 baseline.
        #[allow(unused_unsafe)]
        let v = unsafe { $e };
        v
    }};
}

// SAFETY: `float32x4_t` is 16 bytes of plain data: no padding, every bit pattern valid.
unsafe impl Half for float32x4_t {
    /// All ones (true) or all zeros per `u32` lane.
    type Mask = uint32x4_t;

    const LEVEL: SimdLevel = SimdLevel::Neon;

    #[inline(always)]
    fn splat(x: f32) -> Self {
        neon!(vdupq_n_f32(x))
    }

    #[inline(always)]
    fn add(self, o: Self) -> Self {
        neon!(vaddq_f32(self, o))
    }

    #[inline(always)]
    fn sub(self, o: Self) -> Self {
        neon!(vsubq_f32(self, o))
    }

    #[inline(always)]
    fn mul(self, o: Self) -> Self {
        neon!(vmulq_f32(self, o))
    }

    #[inline(always)]
    fn div(self, o: Self) -> Self {
        neon!(vdivq_f32(self, o))
    }

    #[inline(always)]
    fn neg(self) -> Self {
        neon!(vnegq_f32(self))
    }

    #[inline(always)]
    fn sqrt(self) -> Self {
        neon!(vsqrtq_f32(self))
    }

    #[inline(always)]
    fn abs(self) -> Self {
        neon!(vabsq_f32(self))
    }

    #[inline(always)]
    fn gt(self, o: Self) -> uint32x4_t {
        neon!(vcgtq_f32(self, o))
    }

    #[inline(always)]
    fn lt(self, o: Self) -> uint32x4_t {
        neon!(vcltq_f32(self, o))
    }

    #[inline(always)]
    fn ge(self, o: Self) -> uint32x4_t {
        neon!(vcgeq_f32(self, o))
    }

    #[inline(always)]
    fn select(m: uint32x4_t, a: Self, b: Self) -> Self {
        neon!(vbslq_f32(m, a, b))
    }

    #[inline(always)]
    fn mask_and(a: uint32x4_t, b: uint32x4_t) -> uint32x4_t {
        neon!(vandq_u32(a, b))
    }

    #[inline(always)]
    fn mask_not(m: uint32x4_t) -> uint32x4_t {
        neon!(veorq_u32(m, Self::all_lanes()))
    }

    #[inline(always)]
    fn all_lanes() -> uint32x4_t {
        neon!(vdupq_n_u32(u32::MAX))
    }

    #[inline(always)]
    fn lanes_below(first: u32, count: u32) -> uint32x4_t {
        let index: [u32; 4] = [first, first + 1, first + 2, first + 3];
        // SAFETY: `index` holds 4 `u32`.
        let index = neon!(vld1q_u32(index.as_ptr()));
        neon!(vcltq_u32(index, vdupq_n_u32(count)))
    }

    /// Whether every lane is on: the smallest `u32` lane is all ones.
    #[inline(always)]
    fn all(m: uint32x4_t) -> bool {
        neon!(vminvq_u32(m)) == u32::MAX
    }

    #[inline(always)]
    fn any_nan(self) -> bool {
        // A lane equals itself unless it is NaN.
        !Self::all(neon!(vceqq_f32(self, self)))
    }

    #[inline(always)]
    fn east(a: Self, b: Self) -> Self {
        neon!(vextq_f32::<1>(a, b))
    }

    #[inline(always)]
    fn west(a: Self, b: Self) -> Self {
        neon!(vextq_f32::<3>(a, b))
    }

    #[inline(always)]
    unsafe fn load(p: *const f32) -> Self {
        // SAFETY: the caller guarantees `p` is readable for 4 floats.
        unsafe { vld1q_f32(p) }
    }

    #[inline(always)]
    unsafe fn store(p: *mut f32, v: Self) {
        // SAFETY: the caller guarantees `p` is writable for 4 floats.
        unsafe { vst1q_f32(p, v) }
    }

    #[inline(always)]
    unsafe fn stream(p: *mut f32, v: Self) {
        // Plain stores: `stnp` (a store with a non-temporal hint) has no intrinsic in
        // `core::arch::aarch64`, and without one there is nothing to fence.
        // SAFETY: as `store`.
        unsafe { Self::store(p, v) }
    }

    #[inline(always)]
    fn fence() {}
}
