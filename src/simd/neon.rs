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

use super::{SimdLevel, Task, Vector};
use core::arch::aarch64::*;

/// Eight `f32` lanes in two `float32x4_t`, low half first.
#[derive(Debug, Clone, Copy)]
#[repr(C)]
pub(crate) struct F32x8([float32x4_t; 2]);

// SAFETY: two `float32x4_t` are 32 bytes of plain data: no padding, every bit pattern
// valid.
unsafe impl bytemuck::Zeroable for F32x8 {}
// SAFETY: as above.
unsafe impl bytemuck::Pod for F32x8 {}

/// A lane mask of [`F32x8`]: all ones (true) or all zeros per `u32` lane.
#[derive(Debug, Clone, Copy)]
pub(crate) struct Mask8([uint32x4_t; 2]);

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

impl F32x8 {
    /// `f` on each half.
    #[inline(always)]
    fn map(self, f: impl Fn(float32x4_t) -> float32x4_t) -> Self {
        Self(self.0.map(f))
    }

    /// `f` on each pair of halves.
    #[inline(always)]
    fn zip(self, o: Self, f: impl Fn(float32x4_t, float32x4_t) -> float32x4_t) -> Self {
        Self([f(self.0[0], o.0[0]), f(self.0[1], o.0[1])])
    }

    /// The comparison `f` on each pair of halves.
    #[inline(always)]
    fn test(self, o: Self, f: impl Fn(float32x4_t, float32x4_t) -> uint32x4_t) -> Mask8 {
        Mask8([f(self.0[0], o.0[0]), f(self.0[1], o.0[1])])
    }
}

operators!(F32x8, |a, b| {
    add: a.zip(b, |x, y| neon!(vaddq_f32(x, y))),
    sub: a.zip(b, |x, y| neon!(vsubq_f32(x, y))),
    mul: a.zip(b, |x, y| neon!(vmulq_f32(x, y))),
    div: a.zip(b, |x, y| neon!(vdivq_f32(x, y))),
    neg: a.map(|x| neon!(vnegq_f32(x))),
});

impl core::ops::BitAnd for Mask8 {
    type Output = Self;
    #[inline(always)]
    fn bitand(self, o: Self) -> Self {
        Self([
            neon!(vandq_u32(self.0[0], o.0[0])),
            neon!(vandq_u32(self.0[1], o.0[1])),
        ])
    }
}

impl core::ops::BitAndAssign for Mask8 {
    #[inline(always)]
    fn bitand_assign(&mut self, o: Self) {
        *self = *self & o;
    }
}

impl core::ops::Not for Mask8 {
    type Output = Self;
    #[inline(always)]
    fn not(self) -> Self {
        let ones = F32x8::all_lanes().0;
        Self([
            neon!(veorq_u32(self.0[0], ones[0])),
            neon!(veorq_u32(self.0[1], ones[1])),
        ])
    }
}

/// Whether every lane of a mask half is on: its smallest `u32` lane is all ones.
#[inline(always)]
fn all4(m: uint32x4_t) -> bool {
    neon!(vminvq_u32(m)) == u32::MAX
}

impl Vector for F32x8 {
    const LANES: usize = 8;
    type Mask = Mask8;

    #[inline(always)]
    fn splat(x: f32) -> Self {
        let h = neon!(vdupq_n_f32(x));
        Self([h, h])
    }

    #[cfg(test)]
    #[inline(always)]
    fn from_slice(a: &[f32]) -> Self {
        let mut l = [0.0; 8];
        let n = a.len().min(8);
        l[..n].copy_from_slice(&a[..n]);
        // SAFETY: `l` holds 8 floats.
        unsafe { Self::load(l.as_ptr()) }
    }

    #[inline(always)]
    fn write_to(self, out: &mut [f32]) {
        let mut l = [0.0; 8];
        // SAFETY: `l` holds 8 floats.
        unsafe { Self::store(l.as_mut_ptr(), self) };
        let n = out.len();
        out.copy_from_slice(&l[..n]);
    }

    #[inline(always)]
    fn sqrt(self) -> Self {
        self.map(|x| neon!(vsqrtq_f32(x)))
    }

    #[inline(always)]
    fn abs(self) -> Self {
        self.map(|x| neon!(vabsq_f32(x)))
    }

    #[inline(always)]
    fn max(self, o: Self) -> Self {
        // `maxps`: `self` where `self > o`, else `o` (also where either is NaN).
        Self::select(self.gt(o), self, o)
    }

    #[inline(always)]
    fn min(self, o: Self) -> Self {
        // `minps`: `self` where `self < o`, else `o`.
        Self::select(self.lt(o), self, o)
    }

    #[inline(always)]
    fn gt(self, o: Self) -> Mask8 {
        self.test(o, |x, y| neon!(vcgtq_f32(x, y)))
    }

    #[inline(always)]
    fn lt(self, o: Self) -> Mask8 {
        self.test(o, |x, y| neon!(vcltq_f32(x, y)))
    }

    #[inline(always)]
    fn ge(self, o: Self) -> Mask8 {
        self.test(o, |x, y| neon!(vcgeq_f32(x, y)))
    }

    #[inline(always)]
    fn select(m: Mask8, a: Self, b: Self) -> Self {
        Self([
            neon!(vbslq_f32(m.0[0], a.0[0], b.0[0])),
            neon!(vbslq_f32(m.0[1], a.0[1], b.0[1])),
        ])
    }

    #[inline(always)]
    fn all_lanes() -> Mask8 {
        let h = neon!(vdupq_n_u32(u32::MAX));
        Mask8([h, h])
    }

    #[inline(always)]
    fn first_lanes(count: usize) -> Mask8 {
        let n = neon!(vdupq_n_u32(count.min(8) as u32));
        let lo: [u32; 4] = [0, 1, 2, 3];
        let hi: [u32; 4] = [4, 5, 6, 7];
        // SAFETY: `lo` and `hi` hold 4 `u32` each.
        let (lo, hi) = neon!((vld1q_u32(lo.as_ptr()), vld1q_u32(hi.as_ptr())));
        Mask8([neon!(vcltq_u32(lo, n)), neon!(vcltq_u32(hi, n))])
    }

    #[inline(always)]
    fn all(m: Mask8) -> bool {
        all4(neon!(vandq_u32(m.0[0], m.0[1])))
    }

    #[inline(always)]
    fn any_nan(self) -> bool {
        // A lane equals itself unless it is NaN.
        let ordered = self.test(self, |x, y| neon!(vceqq_f32(x, y)));
        !Self::all(ordered)
    }

    #[inline(always)]
    fn east(lo: Self, hi: Self) -> Self {
        let ([a, b], [c, _]) = (lo.0, hi.0);
        Self([neon!(vextq_f32::<1>(a, b)), neon!(vextq_f32::<1>(b, c))])
    }

    #[inline(always)]
    fn west(lo: Self, hi: Self) -> Self {
        let ([_, b], [c, d]) = (lo.0, hi.0);
        Self([neon!(vextq_f32::<3>(b, c)), neon!(vextq_f32::<3>(c, d))])
    }

    #[inline(always)]
    unsafe fn load(p: *const f32) -> Self {
        // SAFETY: the caller guarantees `p` is readable for 8 floats.
        unsafe { Self([vld1q_f32(p), vld1q_f32(p.add(4))]) }
    }

    #[inline(always)]
    unsafe fn store(p: *mut f32, v: Self) {
        // SAFETY: the caller guarantees `p` is writable for 8 floats.
        unsafe {
            vst1q_f32(p, v.0[0]);
            vst1q_f32(p.add(4), v.0[1]);
        }
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

    const LEVEL: SimdLevel = SimdLevel::Neon;

    #[inline(always)]
    fn enter<T: Task<Self>>(task: T) -> T::Output {
        // A function of its own, as the other levels' entries are.
        #[inline(never)]
        fn entry<T: Task<F32x8>>(task: T) -> T::Output {
            debug_assert!(F32x8::LEVEL.is_available());
            super::align_frame();
            task.run()
        }
        entry(task)
    }
}
