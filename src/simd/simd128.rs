//! WebAssembly SIMD128: eight `f32` lanes in two `v128`, as NEON and SSE2 hold them (the
//! engine's chunks are 8 or 16 floats; two independent halves keep a JIT's register
//! allocation and the host CPU's pipes busy); masks are all-ones lanes of a `v128`.
//!
//! Compiled only into a `wasm32` build made with `-C target-feature=+simd128`: wasm has no
//! run-time detection (a module that uses SIMD128 fails to validate in an engine without
//! it), so such a build always runs this level and a build without it runs the portable
//! lanes.
//!
//! Every operation is one IEEE operation per lane (`f32x4.add`, `sub`, `mul`, `div`,
//! `sqrt`); the relaxed-SIMD fused multiply-add is never used. `max`/`min` are a compare
//! and a bitwise select: `f32x4.max`/`min` return NaN where either operand is NaN and order
//! −0 below +0, where the reference returns the second operand. Negation and `abs` only
//! touch the sign bit, as the spec defines `fneg`/`fabs`.

use super::{SimdLevel, Task, Vector};
use core::arch::wasm32::*;

/// Eight `f32` lanes in two `v128`, low half first.
#[derive(Debug, Clone, Copy)]
#[repr(C)]
pub(crate) struct F32x8([v128; 2]);

// SAFETY: two `v128` are 32 bytes of plain data: no padding, every bit pattern valid.
unsafe impl bytemuck::Zeroable for F32x8 {}
// SAFETY: as above.
unsafe impl bytemuck::Pod for F32x8 {}

impl F32x8 {
    /// `f` on each half.
    #[inline(always)]
    fn map(self, f: impl Fn(v128) -> v128) -> Self {
        Self(self.0.map(f))
    }

    /// `f` on each pair of halves.
    #[inline(always)]
    fn zip(self, o: Self, f: impl Fn(v128, v128) -> v128) -> Self {
        Self([f(self.0[0], o.0[0]), f(self.0[1], o.0[1])])
    }
}

operators!(F32x8, |a, b| {
    add: a.zip(b, |x, y| f32x4_add(x, y)),
    sub: a.zip(b, |x, y| f32x4_sub(x, y)),
    mul: a.zip(b, |x, y| f32x4_mul(x, y)),
    div: a.zip(b, |x, y| f32x4_div(x, y)),
    neg: a.map(|x| f32x4_neg(x)),
});

impl core::ops::BitAnd for F32x8 {
    type Output = Self;
    #[inline(always)]
    fn bitand(self, o: Self) -> Self {
        self.zip(o, |x, y| v128_and(x, y))
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
        self.zip(Self::all_lanes(), |x, y| v128_xor(x, y))
    }
}

impl Vector for F32x8 {
    const LANES: usize = 8;
    type Mask = F32x8;

    #[inline(always)]
    fn splat(x: f32) -> Self {
        let h = f32x4_splat(x);
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
        self.map(|x| f32x4_sqrt(x))
    }

    #[inline(always)]
    fn abs(self) -> Self {
        self.map(|x| f32x4_abs(x))
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
    fn gt(self, o: Self) -> Self {
        self.zip(o, |x, y| f32x4_gt(x, y))
    }

    #[inline(always)]
    fn lt(self, o: Self) -> Self {
        self.zip(o, |x, y| f32x4_lt(x, y))
    }

    #[inline(always)]
    fn ge(self, o: Self) -> Self {
        self.zip(o, |x, y| f32x4_ge(x, y))
    }

    #[inline(always)]
    fn select(m: Self, a: Self, b: Self) -> Self {
        Self([
            v128_bitselect(a.0[0], b.0[0], m.0[0]),
            v128_bitselect(a.0[1], b.0[1], m.0[1]),
        ])
    }

    #[inline(always)]
    fn all_lanes() -> Self {
        let h = u32x4_splat(u32::MAX);
        Self([h, h])
    }

    #[inline(always)]
    fn first_lanes(count: usize) -> Self {
        let n = u32x4_splat(count.min(8) as u32);
        Self([
            u32x4_lt(u32x4(0, 1, 2, 3), n),
            u32x4_lt(u32x4(4, 5, 6, 7), n),
        ])
    }

    #[inline(always)]
    fn all(m: Self) -> bool {
        u32x4_all_true(v128_and(m.0[0], m.0[1]))
    }

    #[inline(always)]
    fn any_nan(self) -> bool {
        // A lane differs from itself only if it is NaN.
        let nan = self.zip(self, |x, y| f32x4_ne(x, y));
        v128_any_true(v128_or(nan.0[0], nan.0[1]))
    }

    #[inline(always)]
    fn east(lo: Self, hi: Self) -> Self {
        let ([a, b], [c, _]) = (lo.0, hi.0);
        Self([
            i32x4_shuffle::<1, 2, 3, 4>(a, b),
            i32x4_shuffle::<1, 2, 3, 4>(b, c),
        ])
    }

    #[inline(always)]
    fn west(lo: Self, hi: Self) -> Self {
        let ([_, b], [c, d]) = (lo.0, hi.0);
        Self([
            i32x4_shuffle::<3, 4, 5, 6>(b, c),
            i32x4_shuffle::<3, 4, 5, 6>(c, d),
        ])
    }

    #[inline(always)]
    unsafe fn load(p: *const f32) -> Self {
        // SAFETY: the caller guarantees `p` is readable for 8 floats; `v128_load` takes
        // any alignment.
        unsafe { Self([v128_load(p.cast()), v128_load(p.add(4).cast())]) }
    }

    #[inline(always)]
    unsafe fn store(p: *mut f32, v: Self) {
        // SAFETY: the caller guarantees `p` is writable for 8 floats.
        unsafe {
            v128_store(p.cast(), v.0[0]);
            v128_store(p.add(4).cast(), v.0[1]);
        }
    }

    #[inline(always)]
    unsafe fn stream(p: *mut f32, v: Self) {
        // Plain stores: wasm has no non-temporal store.
        // SAFETY: as `store`.
        unsafe { Self::store(p, v) }
    }

    #[inline(always)]
    fn fence() {}

    const LEVEL: SimdLevel = SimdLevel::Simd128;

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
