//! Lanes as 128-bit halves: the vector types of the levels built from 128-bit registers
//! (SSE2, NEON, SIMD128), written once over a [`Half`] that each level's file implements
//! with its intrinsics. SSE2 and NEON run a [`Pair`], eight lanes in two halves: two
//! independent halves per operation keep an out-of-order core busy (the second half's
//! operation issues while the first waits on its latency). SIMD128 runs a [`Single`], four
//! lanes in one half: under a JIT that allocates the registers, the row kernel's values in
//! four lanes stay in a host CPU's sixteen vector registers where eight lanes in pairs of
//! them spill, and each kernel is half the code (`docs/performance.md`).
//!
//! Every operation of [`Halves`] is its half's operation on each half in turn, low half
//! first: the same IEEE operation per lane as a level with one wide register, so the same
//! bits.

// Indexed loops on purpose: see the note above `Halves`'s helpers.
#![allow(clippy::needless_range_loop)]

use super::{baseline_entry, SimdLevel, Task, Vector};

/// Four `f32` lanes in one register, with what [`Halves`] needs of them. Every method is
/// `#[inline(always)]` in every implementation, as [`Vector`]'s are.
///
/// # Safety
///
/// `Self` is 16 bytes of plain data: no padding, every bit pattern valid (so that a
/// [`Halves`] of them is [`bytemuck::Pod`]).
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
    /// Lane `i` on where `first + i < count`.
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

/// `4 N` `f32` lanes in `N` [`Half`]s, low half first.
#[derive(Debug, Clone, Copy)]
#[repr(C)]
pub(crate) struct Halves<H, const N: usize>([H; N]);

/// Eight lanes in two halves: SSE2's and NEON's vector type.
#[cfg_attr(target_arch = "wasm32", allow(dead_code))]
pub(crate) type Pair<H> = Halves<H, 2>;

/// Four lanes in one half: SIMD128's vector type (elsewhere built for the lane test
/// only).
#[cfg_attr(not(target_arch = "wasm32"), allow(dead_code))]
pub(crate) type Single<H> = Halves<H, 1>;

// SAFETY: halves of plain data (`Half`'s contract) in a `repr(C)` array: no padding, every
// bit pattern valid.
unsafe impl<H: Half, const N: usize> bytemuck::Zeroable for Halves<H, N> {}
// SAFETY: as above.
unsafe impl<H: Half, const N: usize> bytemuck::Pod for Halves<H, N> {}

/// A lane mask of [`Halves`]: one mask per half.
#[derive(Debug, Clone, Copy)]
pub(crate) struct HalvesMask<H: Half, const N: usize>([H::Mask; N]);

// The operations below are plain loops over the halves, of a constant count that the
// compiler unrolls at any optimisation level, with no helper of the standard library
// between (`array::from_fn` and iterators are functions of their own a build with a low
// inlining threshold would call).
impl<H: Half, const N: usize> Halves<H, N> {
    /// `f` on each half.
    #[inline(always)]
    fn map(self, f: impl Fn(H) -> H) -> Self {
        let mut out = self.0;
        for h in &mut out {
            *h = f(*h);
        }
        Self(out)
    }

    /// `f` on each pair of halves (a half's method: the halves' instruction sets are
    /// part of their targets' baselines, so nothing is lost where it is compiled).
    #[inline(always)]
    fn zip(self, o: Self, f: impl Fn(H, H) -> H) -> Self {
        let mut out = self.0;
        for i in 0..N {
            out[i] = f(self.0[i], o.0[i]);
        }
        Self(out)
    }

    /// The comparison `f` on each pair of halves.
    #[inline(always)]
    fn test(self, o: Self, f: impl Fn(H, H) -> H::Mask) -> HalvesMask<H, N> {
        let mut out = [H::all_lanes(); N];
        for i in 0..N {
            out[i] = f(self.0[i], o.0[i]);
        }
        HalvesMask(out)
    }
}

impl<H: Half, const N: usize> core::ops::Add for Halves<H, N> {
    type Output = Self;
    #[inline(always)]
    fn add(self, o: Self) -> Self {
        self.zip(o, H::add)
    }
}

impl<H: Half, const N: usize> core::ops::Sub for Halves<H, N> {
    type Output = Self;
    #[inline(always)]
    fn sub(self, o: Self) -> Self {
        self.zip(o, H::sub)
    }
}

impl<H: Half, const N: usize> core::ops::Mul for Halves<H, N> {
    type Output = Self;
    #[inline(always)]
    fn mul(self, o: Self) -> Self {
        self.zip(o, H::mul)
    }
}

impl<H: Half, const N: usize> core::ops::Div for Halves<H, N> {
    type Output = Self;
    #[inline(always)]
    fn div(self, o: Self) -> Self {
        self.zip(o, H::div)
    }
}

impl<H: Half, const N: usize> core::ops::Neg for Halves<H, N> {
    type Output = Self;
    #[inline(always)]
    fn neg(self) -> Self {
        self.map(H::neg)
    }
}

impl<H: Half, const N: usize> core::ops::AddAssign for Halves<H, N> {
    #[inline(always)]
    fn add_assign(&mut self, o: Self) {
        *self = *self + o;
    }
}

impl<H: Half, const N: usize> core::ops::BitAnd for HalvesMask<H, N> {
    type Output = Self;
    #[inline(always)]
    fn bitand(self, o: Self) -> Self {
        let mut out = self.0;
        for i in 0..N {
            out[i] = H::mask_and(self.0[i], o.0[i]);
        }
        Self(out)
    }
}

impl<H: Half, const N: usize> core::ops::BitAndAssign for HalvesMask<H, N> {
    #[inline(always)]
    fn bitand_assign(&mut self, o: Self) {
        *self = *self & o;
    }
}

impl<H: Half, const N: usize> core::ops::Not for HalvesMask<H, N> {
    type Output = Self;
    #[inline(always)]
    fn not(self) -> Self {
        let mut out = self.0;
        for m in &mut out {
            *m = H::mask_not(*m);
        }
        Self(out)
    }
}

impl<H: Half, const N: usize> Vector for Halves<H, N> {
    const LANES: usize = 4 * N;
    type Mask = HalvesMask<H, N>;

    #[inline(always)]
    fn splat(x: f32) -> Self {
        Self([H::splat(x); N])
    }

    #[inline(always)]
    fn sqrt(self) -> Self {
        self.map(H::sqrt)
    }

    #[inline(always)]
    fn abs(self) -> Self {
        self.map(H::abs)
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
        let mut out = a.0;
        for i in 0..N {
            out[i] = H::select(m.0[i], a.0[i], b.0[i]);
        }
        Self(out)
    }

    #[inline(always)]
    fn all_lanes() -> Self::Mask {
        HalvesMask([H::all_lanes(); N])
    }

    #[inline(always)]
    fn first_lanes(count: usize) -> Self::Mask {
        let n = count.min(Self::LANES) as u32;
        let mut out = [H::all_lanes(); N];
        for (i, m) in out.iter_mut().enumerate() {
            *m = H::lanes_below(4 * i as u32, n);
        }
        HalvesMask(out)
    }

    #[inline(always)]
    fn all(m: Self::Mask) -> bool {
        let mut every = m.0[0];
        for i in 1..N {
            every = H::mask_and(every, m.0[i]);
        }
        H::all(every)
    }

    #[inline(always)]
    fn any_nan(self) -> bool {
        let mut any = false;
        for i in 0..N {
            any |= self.0[i].any_nan();
        }
        any
    }

    #[inline(always)]
    fn east(lo: Self, hi: Self) -> Self {
        // Half `i` with the first lane of the half after it.
        let mut out = lo.0;
        for i in 0..N {
            out[i] = H::east(lo.0[i], if i + 1 < N { lo.0[i + 1] } else { hi.0[0] });
        }
        Self(out)
    }

    #[inline(always)]
    fn west(lo: Self, hi: Self) -> Self {
        // Half `i` of `hi` with the last lane of the half before it.
        let mut out = hi.0;
        for i in 0..N {
            out[i] = H::west(if i == 0 { lo.0[N - 1] } else { hi.0[i - 1] }, hi.0[i]);
        }
        Self(out)
    }

    #[inline(always)]
    unsafe fn load(p: *const f32) -> Self {
        let mut out = [H::splat(0.0); N];
        for (i, h) in out.iter_mut().enumerate() {
            // SAFETY: the caller guarantees `p` is readable for `4 N` floats.
            *h = unsafe { H::load(p.add(4 * i)) };
        }
        Self(out)
    }

    #[inline(always)]
    unsafe fn store(p: *mut f32, v: Self) {
        for i in 0..N {
            // SAFETY: the caller guarantees `p` is writable for `4 N` floats.
            unsafe { H::store(p.add(4 * i), v.0[i]) }
        }
    }

    #[inline(always)]
    unsafe fn stream(p: *mut f32, v: Self) {
        for i in 0..N {
            // SAFETY: the caller guarantees `p` is writable for `4 N` floats and aligned
            // to `16 N` bytes, so each half is 16-byte aligned.
            unsafe { H::stream(p.add(4 * i), v.0[i]) }
        }
    }

    #[inline(always)]
    fn fence() {
        H::fence()
    }

    const LEVEL: SimdLevel = H::LEVEL;

    #[inline(always)]
    fn enter<T: Task<Self>>(task: T) -> T::Output {
        baseline_entry(task)
    }
}
