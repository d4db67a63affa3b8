//! Four lanes in one 128-bit register: a [`Half`] on its own as a [`Vector`]. The
//! SIMD128 level's vector type on WebAssembly, where a JIT allocates the registers: the
//! row kernel's values in four lanes stay in a host CPU's sixteen vector registers where
//! eight lanes in pairs of them spill, and each kernel is half the code
//! (`docs/performance.md`).
//!
//! Every operation is its half's operation: the same IEEE operation per lane as every
//! other level, so the same bits.

use super::pair::Half;
use super::{align_frame, SimdLevel, Task, Vector};

/// Four `f32` lanes in one [`Half`].
#[derive(Debug, Clone, Copy)]
#[repr(transparent)]
pub(crate) struct Single<H>(H);

// SAFETY: one half of plain data (`Half`'s contract), transparent: no padding, every bit
// pattern valid.
unsafe impl<H: Half> bytemuck::Zeroable for Single<H> {}
// SAFETY: as above.
unsafe impl<H: Half> bytemuck::Pod for Single<H> {}

/// A lane mask of [`Single`].
#[derive(Debug, Clone, Copy)]
pub(crate) struct SingleMask<H: Half>(H::Mask);

impl<H: Half> core::ops::Add for Single<H> {
    type Output = Self;
    #[inline(always)]
    fn add(self, o: Self) -> Self {
        Single(self.0.add(o.0))
    }
}

impl<H: Half> core::ops::Sub for Single<H> {
    type Output = Self;
    #[inline(always)]
    fn sub(self, o: Self) -> Self {
        Single(self.0.sub(o.0))
    }
}

impl<H: Half> core::ops::Mul for Single<H> {
    type Output = Self;
    #[inline(always)]
    fn mul(self, o: Self) -> Self {
        Single(self.0.mul(o.0))
    }
}

impl<H: Half> core::ops::Div for Single<H> {
    type Output = Self;
    #[inline(always)]
    fn div(self, o: Self) -> Self {
        Single(self.0.div(o.0))
    }
}

impl<H: Half> core::ops::Neg for Single<H> {
    type Output = Self;
    #[inline(always)]
    fn neg(self) -> Self {
        Single(self.0.neg())
    }
}

impl<H: Half> core::ops::AddAssign for Single<H> {
    #[inline(always)]
    fn add_assign(&mut self, o: Self) {
        *self = *self + o;
    }
}

impl<H: Half> core::ops::BitAnd for SingleMask<H> {
    type Output = Self;
    #[inline(always)]
    fn bitand(self, o: Self) -> Self {
        Self(H::mask_and(self.0, o.0))
    }
}

impl<H: Half> core::ops::BitAndAssign for SingleMask<H> {
    #[inline(always)]
    fn bitand_assign(&mut self, o: Self) {
        *self = *self & o;
    }
}

impl<H: Half> core::ops::Not for SingleMask<H> {
    type Output = Self;
    #[inline(always)]
    fn not(self) -> Self {
        Self(H::mask_not(self.0))
    }
}

impl<H: Half> Vector for Single<H> {
    const LANES: usize = 4;
    type Mask = SingleMask<H>;

    #[inline(always)]
    fn splat(x: f32) -> Self {
        Self(H::splat(x))
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
    fn max(self, o: Self) -> Self {
        Self(self.0.max(o.0))
    }

    #[inline(always)]
    fn min(self, o: Self) -> Self {
        Self(self.0.min(o.0))
    }

    #[inline(always)]
    fn gt(self, o: Self) -> Self::Mask {
        SingleMask(self.0.gt(o.0))
    }

    #[inline(always)]
    fn lt(self, o: Self) -> Self::Mask {
        SingleMask(self.0.lt(o.0))
    }

    #[inline(always)]
    fn ge(self, o: Self) -> Self::Mask {
        SingleMask(self.0.ge(o.0))
    }

    #[inline(always)]
    fn select(m: Self::Mask, a: Self, b: Self) -> Self {
        Self(H::select(m.0, a.0, b.0))
    }

    #[inline(always)]
    fn all_lanes() -> Self::Mask {
        SingleMask(H::all_lanes())
    }

    #[inline(always)]
    fn first_lanes(count: usize) -> Self::Mask {
        SingleMask(H::lanes_below(0, count.min(4) as u32))
    }

    #[inline(always)]
    fn all(m: Self::Mask) -> bool {
        H::all(m.0)
    }

    #[inline(always)]
    fn any_nan(self) -> bool {
        self.0.any_nan()
    }

    #[inline(always)]
    fn east(lo: Self, hi: Self) -> Self {
        Self(H::east(lo.0, hi.0))
    }

    #[inline(always)]
    fn west(lo: Self, hi: Self) -> Self {
        Self(H::west(lo.0, hi.0))
    }

    #[inline(always)]
    unsafe fn load(p: *const f32) -> Self {
        // SAFETY: the caller guarantees `p` is readable for 4 floats.
        unsafe { Self(H::load(p)) }
    }

    #[inline(always)]
    unsafe fn store(p: *mut f32, v: Self) {
        // SAFETY: the caller guarantees `p` is writable for 4 floats.
        unsafe { H::store(p, v.0) }
    }

    #[inline(always)]
    unsafe fn stream(p: *mut f32, v: Self) {
        // SAFETY: the caller guarantees `p` is writable for 4 floats and 16-byte aligned.
        unsafe { H::stream(p, v.0) }
    }

    #[inline(always)]
    fn fence() {
        H::fence()
    }

    const LEVEL: SimdLevel = H::LEVEL;

    #[inline(always)]
    fn enter<T: Task<Self>>(task: T) -> T::Output {
        // A function of its own, as every level's entry is.
        #[inline(never)]
        fn entry<H: Half, T: Task<Single<H>>>(task: T) -> T::Output {
            debug_assert!(H::LEVEL.is_available());
            align_frame();
            task.run()
        }
        entry::<H, T>(task)
    }
}
