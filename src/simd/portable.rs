//! Plain `f32` arrays as a [`Vector`]: the lanes for targets without a SIMD level here,
//! and for Miri, which checks the kernels' unchecked accesses. Each operation is the same
//! IEEE operation per lane as the intrinsics of the other levels, so it gives their bits.

use super::{SimdLevel, Task, Vector};

/// Eight `f32` lanes in an array.
#[derive(Debug, Clone, Copy, bytemuck::Pod, bytemuck::Zeroable)]
#[repr(C, align(32))]
pub(crate) struct F32x8([f32; 8]);

/// A lane mask of [`F32x8`].
#[derive(Debug, Clone, Copy)]
pub(crate) struct Mask8([bool; 8]);

impl F32x8 {
    #[inline(always)]
    fn map(self, f: impl Fn(f32) -> f32) -> Self {
        Self(self.0.map(f))
    }

    #[inline(always)]
    fn zip(self, o: Self, f: impl Fn(f32, f32) -> f32) -> Self {
        Self(core::array::from_fn(|i| f(self.0[i], o.0[i])))
    }

    #[inline(always)]
    fn test(self, o: Self, f: impl Fn(f32, f32) -> bool) -> Mask8 {
        Mask8(core::array::from_fn(|i| f(self.0[i], o.0[i])))
    }
}

operators!(F32x8, |a, b| {
    add: a.zip(b, |x, y| x + y),
    sub: a.zip(b, |x, y| x - y),
    mul: a.zip(b, |x, y| x * y),
    div: a.zip(b, |x, y| x / y),
    neg: a.map(|x| -x),
});

impl core::ops::BitAnd for Mask8 {
    type Output = Self;
    #[inline(always)]
    fn bitand(self, o: Self) -> Self {
        Self(core::array::from_fn(|i| self.0[i] & o.0[i]))
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
        // Each lane differs from the all-on mask's.
        let on = F32x8::all_lanes().0;
        Self(core::array::from_fn(|i| self.0[i] != on[i]))
    }
}

impl Vector for F32x8 {
    const LANES: usize = 8;
    // Each neighbour read next to its use (see `Vector::READ_AHEAD`).
    const READ_AHEAD: bool = false;
    type Mask = Mask8;

    #[inline(always)]
    fn splat(x: f32) -> Self {
        Self([x; 8])
    }

    #[inline(always)]
    fn sqrt(self) -> Self {
        self.map(f32::sqrt)
    }

    #[inline(always)]
    fn abs(self) -> Self {
        self.map(f32::abs)
    }

    #[inline(always)]
    fn gt(self, o: Self) -> Mask8 {
        self.test(o, |x, y| x > y)
    }

    #[inline(always)]
    fn lt(self, o: Self) -> Mask8 {
        self.test(o, |x, y| x < y)
    }

    #[inline(always)]
    fn ge(self, o: Self) -> Mask8 {
        self.test(o, |x, y| x >= y)
    }

    #[inline(always)]
    fn select(m: Mask8, a: Self, b: Self) -> Self {
        // On AArch64, LLVM turns `if x < 0.0 { x } else { 0.0 }` into `fminnm`, which gives
        // −0 for −0 where every other level gives +0. Hiding the mask from the optimiser
        // keeps this a select; NEON, not this level, is the one AArch64 runs for speed.
        #[cfg(target_arch = "aarch64")]
        let m = core::hint::black_box(m);
        Self(core::array::from_fn(
            |i| if m.0[i] { a.0[i] } else { b.0[i] },
        ))
    }

    #[inline(always)]
    fn all_lanes() -> Mask8 {
        Mask8([true; 8])
    }

    #[inline(always)]
    fn first_lanes(count: usize) -> Mask8 {
        Mask8(core::array::from_fn(|i| i < count))
    }

    #[inline(always)]
    fn all(m: Mask8) -> bool {
        m.0.iter().all(|&b| b)
    }

    #[inline(always)]
    fn any_nan(self) -> bool {
        self.0.iter().any(|x| x.is_nan())
    }

    #[inline(always)]
    fn east(lo: Self, hi: Self) -> Self {
        Self(core::array::from_fn(|i| {
            if i < 7 {
                lo.0[i + 1]
            } else {
                hi.0[0]
            }
        }))
    }

    #[inline(always)]
    fn west(lo: Self, hi: Self) -> Self {
        Self(core::array::from_fn(|i| {
            if i == 0 {
                lo.0[7]
            } else {
                hi.0[i - 1]
            }
        }))
    }

    #[inline(always)]
    unsafe fn load(p: *const f32) -> Self {
        // SAFETY: the caller guarantees `p` is readable for 8 floats.
        Self(unsafe { p.cast::<[f32; 8]>().read_unaligned() })
    }

    #[inline(always)]
    unsafe fn store(p: *mut f32, v: Self) {
        // SAFETY: the caller guarantees `p` is writable for 8 floats.
        unsafe { p.cast::<[f32; 8]>().write_unaligned(v.0) }
    }

    const LEVEL: SimdLevel = SimdLevel::Portable;

    #[inline(always)]
    fn enter<T: Task<Self>>(task: T) -> T::Output {
        super::baseline_entry(task)
    }
}

/// One `f32` lane: the portable level's vector type in a `wasm32` build without
/// `+simd128`. Eight lanes of plain `f32` there are eight copies of every scalar
/// operation, a kernel eight times the code of one lane, with more values live than a
/// JIT keeps in registers; one lane is the same operations in the same order per node
/// (`docs/performance.md`).
#[derive(Debug, Clone, Copy, bytemuck::Pod, bytemuck::Zeroable)]
#[repr(transparent)]
#[cfg_attr(
    not(all(target_arch = "wasm32", not(target_feature = "simd128"))),
    allow(dead_code)
)]
pub(crate) struct F32x1(f32);

/// A lane mask of [`F32x1`].
#[derive(Debug, Clone, Copy)]
#[cfg_attr(
    not(all(target_arch = "wasm32", not(target_feature = "simd128"))),
    allow(dead_code)
)]
pub(crate) struct Mask1(bool);

operators!(F32x1, |a, b| {
    add: F32x1(a.0 + b.0),
    sub: F32x1(a.0 - b.0),
    mul: F32x1(a.0 * b.0),
    div: F32x1(a.0 / b.0),
    neg: F32x1(-a.0),
});

impl core::ops::BitAnd for Mask1 {
    type Output = Self;
    #[inline(always)]
    fn bitand(self, o: Self) -> Self {
        Self(self.0 & o.0)
    }
}

impl core::ops::BitAndAssign for Mask1 {
    #[inline(always)]
    fn bitand_assign(&mut self, o: Self) {
        *self = *self & o;
    }
}

impl core::ops::Not for Mask1 {
    type Output = Self;
    #[inline(always)]
    fn not(self) -> Self {
        Self(!self.0)
    }
}

impl Vector for F32x1 {
    const LANES: usize = 1;
    const READ_AHEAD: bool = false;
    type Mask = Mask1;

    #[inline(always)]
    fn splat(x: f32) -> Self {
        Self(x)
    }

    #[inline(always)]
    fn sqrt(self) -> Self {
        Self(self.0.sqrt())
    }

    #[inline(always)]
    fn abs(self) -> Self {
        Self(self.0.abs())
    }

    #[inline(always)]
    fn gt(self, o: Self) -> Mask1 {
        Mask1(self.0 > o.0)
    }

    #[inline(always)]
    fn lt(self, o: Self) -> Mask1 {
        Mask1(self.0 < o.0)
    }

    #[inline(always)]
    fn ge(self, o: Self) -> Mask1 {
        Mask1(self.0 >= o.0)
    }

    #[inline(always)]
    fn select(m: Mask1, a: Self, b: Self) -> Self {
        // As `F32x8::select`.
        #[cfg(target_arch = "aarch64")]
        let m = core::hint::black_box(m);
        if m.0 {
            a
        } else {
            b
        }
    }

    #[inline(always)]
    fn all_lanes() -> Mask1 {
        Mask1(true)
    }

    #[inline(always)]
    fn first_lanes(count: usize) -> Mask1 {
        Mask1(count > 0)
    }

    #[inline(always)]
    fn all(m: Mask1) -> bool {
        m.0
    }

    #[inline(always)]
    fn any_nan(self) -> bool {
        self.0.is_nan()
    }

    #[inline(always)]
    fn east(_: Self, hi: Self) -> Self {
        hi
    }

    #[inline(always)]
    fn west(lo: Self, _: Self) -> Self {
        lo
    }

    #[inline(always)]
    unsafe fn load(p: *const f32) -> Self {
        // SAFETY: the caller guarantees `p` is readable for 1 float (any alignment).
        Self(unsafe { p.read_unaligned() })
    }

    #[inline(always)]
    unsafe fn store(p: *mut f32, v: Self) {
        // SAFETY: the caller guarantees `p` is writable for 1 float.
        unsafe { p.write_unaligned(v.0) }
    }

    const LEVEL: SimdLevel = SimdLevel::Portable;

    #[inline(always)]
    fn enter<T: Task<Self>>(task: T) -> T::Output {
        super::baseline_entry(task)
    }
}
