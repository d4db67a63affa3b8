//! WebAssembly SIMD128: four `f32` lanes in one `v128` ([`Single`]); masks are all-ones
//! lanes of a `v128`. (NEON and SSE2 hold eight lanes in two registers; on wasm the pairs
//! were slower and twice the code: a JIT allocates the registers, and the row kernel's
//! values in pairs spilled where four lanes fit a host's sixteen vector registers,
//! `docs/performance.md`.)
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

use super::halves::{Half, Single};
use super::SimdLevel;
use core::arch::wasm32::*;

/// Four `f32` lanes in one `v128`.
pub(crate) type F32x4 = Single<v128>;

// SAFETY: `v128` is 16 bytes of plain data: no padding, every bit pattern valid.
unsafe impl Half for v128 {
    /// All-ones lanes.
    type Mask = v128;

    const LEVEL: SimdLevel = SimdLevel::Simd128;

    #[inline(always)]
    fn splat(x: f32) -> Self {
        f32x4_splat(x)
    }

    #[inline(always)]
    fn add(self, o: Self) -> Self {
        f32x4_add(self, o)
    }

    #[inline(always)]
    fn sub(self, o: Self) -> Self {
        f32x4_sub(self, o)
    }

    #[inline(always)]
    fn mul(self, o: Self) -> Self {
        f32x4_mul(self, o)
    }

    #[inline(always)]
    fn div(self, o: Self) -> Self {
        f32x4_div(self, o)
    }

    #[inline(always)]
    fn neg(self) -> Self {
        f32x4_neg(self)
    }

    #[inline(always)]
    fn sqrt(self) -> Self {
        f32x4_sqrt(self)
    }

    #[inline(always)]
    fn abs(self) -> Self {
        f32x4_abs(self)
    }

    #[inline(always)]
    fn gt(self, o: Self) -> Self {
        f32x4_gt(self, o)
    }

    #[inline(always)]
    fn lt(self, o: Self) -> Self {
        f32x4_lt(self, o)
    }

    #[inline(always)]
    fn ge(self, o: Self) -> Self {
        f32x4_ge(self, o)
    }

    #[inline(always)]
    fn select(m: Self, a: Self, b: Self) -> Self {
        v128_bitselect(a, b, m)
    }

    #[inline(always)]
    fn mask_and(a: Self, b: Self) -> Self {
        v128_and(a, b)
    }

    #[inline(always)]
    fn mask_not(m: Self) -> Self {
        v128_xor(m, Self::all_lanes())
    }

    #[inline(always)]
    fn all_lanes() -> Self {
        u32x4_splat(u32::MAX)
    }

    #[inline(always)]
    fn lanes_below(first: u32, count: u32) -> Self {
        let index = u32x4(first, first + 1, first + 2, first + 3);
        u32x4_lt(index, u32x4_splat(count))
    }

    #[inline(always)]
    fn all(m: Self) -> bool {
        u32x4_all_true(m)
    }

    #[inline(always)]
    fn any_nan(self) -> bool {
        // A lane differs from itself only if it is NaN.
        v128_any_true(f32x4_ne(self, self))
    }

    #[inline(always)]
    fn east(a: Self, b: Self) -> Self {
        i32x4_shuffle::<1, 2, 3, 4>(a, b)
    }

    #[inline(always)]
    fn west(a: Self, b: Self) -> Self {
        i32x4_shuffle::<3, 4, 5, 6>(a, b)
    }

    #[inline(always)]
    unsafe fn load(p: *const f32) -> Self {
        // SAFETY: the caller guarantees `p` is readable for 4 floats; `v128_load` takes
        // any alignment.
        unsafe { v128_load(p.cast()) }
    }

    #[inline(always)]
    unsafe fn store(p: *mut f32, v: Self) {
        // SAFETY: the caller guarantees `p` is writable for 4 floats.
        unsafe { v128_store(p.cast(), v) }
    }

    #[inline(always)]
    unsafe fn stream(p: *mut f32, v: Self) {
        // Plain stores: wasm has no non-temporal store.
        // SAFETY: as `store`.
        unsafe { Self::store(p, v) }
    }

    #[inline(always)]
    fn fence() {}
}
