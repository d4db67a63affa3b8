//! Eight lanes as two four-lane halves: the vector type of the levels built from 128-bit
//! registers (SSE2, NEON, SIMD128), written once over a [`Half`] that each level's file
//! implements with its intrinsics.
//!
//! Every operation of [`Pair`] is its half's operation on the low half, then on the high
//! half: the same IEEE operation per lane as a level with one wide register, so the same
//! bits. Two independent halves per operation also keep the core busy: the second half's
//! operation issues while the first waits on its latency.

use super::{align_frame, SimdLevel, Task, Vector};

/// Four `f32` lanes in one register, with what [`Pair`] needs of them. Every method is
/// `#[inline(always)]` in every implementation, as [`Vector`]'s are.
///
/// # Safety
///
/// `Self` is 16 bytes of plain data: no padding, every bit pattern valid (so that a
/// [`Pair`] of them is [`bytemuck::Pod`]).
pub(crate) unsafe trait Half: Copy + Send + Sync + std::fmt::Debug + 'static {
    /// A lane mask of four lanes.
    type Mask: Copy + std::fmt::Debug;

    /// The level whose instruction set the half needs.
    const LEVEL: SimdLevel;

    fn splat(x: f32) -> Self;
    fn add(self, o: Self) -> Self;
    fn sub(self, o: Self) -> Self;
    fn mul(self, o: Self) -> Self;
    fn div(self, o: Self) -> Self;
    /// Flips the sign bit.
    fn neg(self) -> Self;
    fn sqrt(self) -> Self;
    /// Clears the sign bit.
    fn abs(self) -> Self;
    /// [`Vector::max`] per lane, `maxps` semantics: `self` where `self > o`, else `o`
    /// (also where either is NaN). A compare and a select unless the level has `maxps`
    /// itself: ARM's and wasm's own maxima return NaN for a NaN operand and order −0
    /// below +0.
    #[inline(always)]
    fn max(self, o: Self) -> Self {
        Self::select(self.gt(o), self, o)
    }
    /// [`Vector::min`] per lane, `minps` semantics: `self` where `self < o`, else `o`.
    #[inline(always)]
    fn min(self, o: Self) -> Self {
        Self::select(self.lt(o), self, o)
    }
    fn gt(self, o: Self) -> Self::Mask;
    fn lt(self, o: Self) -> Self::Mask;
    fn ge(self, o: Self) -> Self::Mask;
    /// `a` where `m`, else `b`: a bitwise blend.
    fn select(m: Self::Mask, a: Self, b: Self) -> Self;
    fn mask_and(a: Self::Mask, b: Self::Mask) -> Self::Mask;
    /// Every bit of `m` flipped.
    fn mask_not(m: Self::Mask) -> Self::Mask;
    fn all_lanes() -> Self::Mask;
    /// Lane `i` on where `first + i < count` (`count ≤ 8`).
    fn lanes_below(first: u32, count: u32) -> Self::Mask;
    /// Whether every lane of `m` is on.
    fn all(m: Self::Mask) -> bool;
    /// Whether any lane is NaN.
    fn any_nan(self) -> bool;
    /// `[a1, a2, a3, b0]`.
    fn east(a: Self, b: Self) -> Self;
    /// `[a3, b0, b1, b2]`.
    fn west(a: Self, b: Self) -> Self;

    /// Loads four floats from `p`.
    ///
    /// # Safety
    ///
    /// `p` is valid for reading four floats.
    unsafe fn load(p: *const f32) -> Self;

    /// Stores four floats at `p`.
    ///
    /// # Safety
    ///
    /// `p` is valid for writing four floats.
    unsafe fn store(p: *mut f32, v: Self);

    /// Stores four floats at `p` with a non-temporal store (a plain one where the level
    /// has none).
    ///
    /// # Safety
    ///
    /// `p` is valid for writing four floats and aligned to 16 bytes.
    unsafe fn stream(p: *mut f32, v: Self);

    /// [`Vector::fence`].
    fn fence();
}

/// Eight `f32` lanes in two [`Half`]s, low half first.
#[derive(Debug, Clone, Copy)]
#[repr(C)]
pub(crate) struct Pair<H>([H; 2]);

// SAFETY: two halves of plain data (`Half`'s contract) in a `repr(C)` array: no padding,
// every bit pattern valid.
unsafe impl<H: Half> bytemuck::Zeroable for Pair<H> {}
// SAFETY: as above.
unsafe impl<H: Half> bytemuck::Pod for Pair<H> {}

/// A lane mask of [`Pair`]: one mask per half.
#[derive(Debug, Clone, Copy)]
pub(crate) struct PairMask<H: Half>([H::Mask; 2]);

impl<H: Half> Pair<H> {
    /// `f` on each pair of halves (a half's method: the halves' instruction sets are
    /// part of their targets' baselines, so nothing is lost where it is compiled).
    #[inline(always)]
    fn zip(self, o: Self, f: impl Fn(H, H) -> H) -> Self {
        Self([f(self.0[0], o.0[0]), f(self.0[1], o.0[1])])
    }

    /// The comparison `f` on each pair of halves.
    #[inline(always)]
    fn test(self, o: Self, f: impl Fn(H, H) -> H::Mask) -> PairMask<H> {
        PairMask([f(self.0[0], o.0[0]), f(self.0[1], o.0[1])])
    }
}

impl<H: Half> core::ops::Add for Pair<H> {
    type Output = Self;
    #[inline(always)]
    fn add(self, o: Self) -> Self {
        self.zip(o, H::add)
    }
}

impl<H: Half> core::ops::Sub for Pair<H> {
    type Output = Self;
    #[inline(always)]
    fn sub(self, o: Self) -> Self {
        self.zip(o, H::sub)
    }
}

impl<H: Half> core::ops::Mul for Pair<H> {
    type Output = Self;
    #[inline(always)]
    fn mul(self, o: Self) -> Self {
        self.zip(o, H::mul)
    }
}

impl<H: Half> core::ops::Div for Pair<H> {
    type Output = Self;
    #[inline(always)]
    fn div(self, o: Self) -> Self {
        self.zip(o, H::div)
    }
}

impl<H: Half> core::ops::Neg for Pair<H> {
    type Output = Self;
    #[inline(always)]
    fn neg(self) -> Self {
        Self([self.0[0].neg(), self.0[1].neg()])
    }
}

impl<H: Half> core::ops::AddAssign for Pair<H> {
    #[inline(always)]
    fn add_assign(&mut self, o: Self) {
        *self = *self + o;
    }
}

impl<H: Half> core::ops::BitAnd for PairMask<H> {
    type Output = Self;
    #[inline(always)]
    fn bitand(self, o: Self) -> Self {
        Self([
            H::mask_and(self.0[0], o.0[0]),
            H::mask_and(self.0[1], o.0[1]),
        ])
    }
}

impl<H: Half> core::ops::BitAndAssign for PairMask<H> {
    #[inline(always)]
    fn bitand_assign(&mut self, o: Self) {
        *self = *self & o;
    }
}

impl<H: Half> core::ops::Not for PairMask<H> {
    type Output = Self;
    #[inline(always)]
    fn not(self) -> Self {
        Self([H::mask_not(self.0[0]), H::mask_not(self.0[1])])
    }
}

impl<H: Half> Vector for Pair<H> {
    const LANES: usize = 8;
    type Mask = PairMask<H>;

    #[inline(always)]
    fn splat(x: f32) -> Self {
        let h = H::splat(x);
        Self([h, h])
    }

    #[inline(always)]
    fn sqrt(self) -> Self {
        Self([self.0[0].sqrt(), self.0[1].sqrt()])
    }

    #[inline(always)]
    fn abs(self) -> Self {
        Self([self.0[0].abs(), self.0[1].abs()])
    }

    #[inline(always)]
    fn max(self, o: Self) -> Self {
        self.zip(o, H::max)
    }

    #[inline(always)]
    fn min(self, o: Self) -> Self {
        self.zip(o, H::min)
    }

    #[inline(always)]
    fn gt(self, o: Self) -> Self::Mask {
        self.test(o, H::gt)
    }

    #[inline(always)]
    fn lt(self, o: Self) -> Self::Mask {
        self.test(o, H::lt)
    }

    #[inline(always)]
    fn ge(self, o: Self) -> Self::Mask {
        self.test(o, H::ge)
    }

    #[inline(always)]
    fn select(m: Self::Mask, a: Self, b: Self) -> Self {
        Self([
            H::select(m.0[0], a.0[0], b.0[0]),
            H::select(m.0[1], a.0[1], b.0[1]),
        ])
    }

    #[inline(always)]
    fn all_lanes() -> Self::Mask {
        let h = H::all_lanes();
        PairMask([h, h])
    }

    #[inline(always)]
    fn first_lanes(count: usize) -> Self::Mask {
        let n = count.min(8) as u32;
        PairMask([H::lanes_below(0, n), H::lanes_below(4, n)])
    }

    #[inline(always)]
    fn all(m: Self::Mask) -> bool {
        H::all(H::mask_and(m.0[0], m.0[1]))
    }

    #[inline(always)]
    fn any_nan(self) -> bool {
        self.0[0].any_nan() | self.0[1].any_nan()
    }

    #[inline(always)]
    fn east(lo: Self, hi: Self) -> Self {
        let ([a, b], [c, _]) = (lo.0, hi.0);
        Self([H::east(a, b), H::east(b, c)])
    }

    #[inline(always)]
    fn west(lo: Self, hi: Self) -> Self {
        let ([_, b], [c, d]) = (lo.0, hi.0);
        Self([H::west(b, c), H::west(c, d)])
    }

    #[inline(always)]
    unsafe fn load(p: *const f32) -> Self {
        // SAFETY: the caller guarantees `p` is readable for 8 floats.
        unsafe { Self([H::load(p), H::load(p.add(4))]) }
    }

    #[inline(always)]
    unsafe fn store(p: *mut f32, v: Self) {
        // SAFETY: the caller guarantees `p` is writable for 8 floats.
        unsafe {
            H::store(p, v.0[0]);
            H::store(p.add(4), v.0[1]);
        }
    }

    #[inline(always)]
    unsafe fn stream(p: *mut f32, v: Self) {
        // SAFETY: the caller guarantees `p` is writable for 8 floats and 32-byte aligned,
        // so each half is 16-byte aligned.
        unsafe {
            H::stream(p, v.0[0]);
            H::stream(p.add(4), v.0[1]);
        }
    }

    #[inline(always)]
    fn fence() {
        H::fence()
    }

    const LEVEL: SimdLevel = H::LEVEL;

    #[inline(always)]
    fn enter<T: Task<Self>>(task: T) -> T::Output {
        // A function of its own, as every level's entry is. (The halves' instruction sets
        // are part of their targets' baselines: nothing to enable.)
        #[inline(never)]
        fn entry<H: Half, T: Task<Pair<H>>>(task: T) -> T::Output {
            debug_assert!(H::LEVEL.is_available());
            align_frame();
            task.run()
        }
        entry::<H, T>(task)
    }
}
