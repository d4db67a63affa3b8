//! The lane layer: one `f32` vector type per instruction set, chosen at run time.
//!
//! # Why runtime dispatch, and why in the crate
//!
//! A game ships one binary to every player's CPU, so it cannot be built with
//! `-C target-cpu=native`; a default x86-64 build only knows SSE2. This module lets that
//! build run the widest kernel the CPU has. [`SimdLevel::detect`] asks the CPU once
//! (`is_x86_feature_detected!`), [`Surface::set_simd_level`](crate::Surface::set_simd_level)
//! forces a level (one the CPU lacks runs the CPU's widest; the command line reads it from
//! `SPRINGWATER_SIMD=scalar|sse2|avx2|avx512|neon|simd128|portable`), and every kernel that matters
//! is compiled once per level. On AArch64 the level is NEON, which every AArch64 CPU has;
//! on wasm32 it is chosen at build time, since WebAssembly cannot ask the CPU: SIMD128 in a
//! build with `-C target-feature=+simd128`, the portable lanes without.
//!
//! * [`Vector`] is what a kernel is written against: lane arithmetic, masks, the
//!   neighbour shuffles ([`Vector::east`], [`Vector::west`]), loads, stores and
//!   non-temporal stores. Its implementations are [`avx2::F32x8`] (one YMM register),
//!   [`avx512::F32x16`] (one ZMM register, mask registers for masks), a `halves::Pair` of
//!   two 128-bit halves written once for SSE2 ([`sse2::F32x8`]) and NEON (`neon::F32x8`,
//!   on AArch64), each level's file giving its half's intrinsics, one such half alone
//!   for SIMD128 (`simd128::F32x4`, a `halves::Single`, on wasm32 with `+simd128`), and
//!   [`portable::F32x8`] (plain arrays, for other targets and Miri; one lane,
//!   [`portable::F32x1`], on wasm32 without `+simd128`). Every operation is a single IEEE operation per lane (add, subtract, multiply,
//!   divide, square root, compare, select): no fused multiply-add, no approximate
//!   reciprocal. So every level computes the same bits as the scalar reference.
//! * [`Kernel`] is a piece of work generic over the vector type (a pass of the step, a
//!   row of normals, a run of refraction). [`dispatch`] runs it with the vector type of a
//!   level, inside a function compiled with that level's `#[target_feature]`. The kernel
//!   and every lane operation are `#[inline(always)]`, so the whole loop is compiled for
//!   that instruction set, not just the calls into it.
//!
//! `wide` picks its instructions at compile time (its `f32x8` is two SSE registers in a
//! default x86-64 build), so the crate uses it only where that is enough (the four-lane
//! transposes that pack [`Vertex`](crate::buffers::Vertex)es), not here. `multiversion`
//! clones one function per target but has no notion of a vector type whose width changes
//! with the target (8 lanes with AVX2, 16 with AVX-512), which this engine's data layout
//! needs. `pulp` has exactly this shape (a `WithSimd` trait,
//! dispatched once) but its vector types and shuffles are its own, and the engine needs
//! the two neighbour shuffles and non-temporal stores per level with bit-exact semantics
//! that are simplest to state and test next to the intrinsics. Six small
//! implementations of one trait (SSE2, AVX2, AVX-512, NEON, SIMD128, portable), each next
//! to its tests, cost less than adapting either.
//!
//! # Denormals, signed zeros and NaNs on every target
//!
//! The same bits on x86-64, AArch64 and wasm32 rest on each level doing exactly what the
//! scalar reference does, including at the corners of IEEE arithmetic:
//!
//! * **Denormals** are computed, not flushed, on every target in its default floating-point
//!   environment: x86's MXCSR starts with FTZ and DAZ off, AArch64's FPCR with FZ off (and,
//!   unlike 32-bit ARM's NEON, AArch64's Advanced SIMD obeys FPCR), and WebAssembly's
//!   scalar and SIMD128 arithmetic (not the relaxed-SIMD proposal, unused here) is
//!   specified to be IEEE with gradual underflow. The engine never changes that
//!   environment, and its state stays out of the subnormal range anyway: the calm rule of
//!   [`crate::forces`] stores a new height or vertical velocity below 10⁻¹⁸ as +0, so a
//!   settling pool's positions and velocities are never subnormal, at any level
//!   (`a_settling_pool_never_goes_subnormal` in `tests/simd_levels.rs`). What is left are
//!   rare intermediate values, such as the squared vertical offset of a spring whose two
//!   heights differ by less than 10⁻¹⁹. A host that sets FTZ/DAZ (some engines do, for
//!   speed) may get its own bits there: the same-bits promise is made for the default
//!   environment.
//! * **Signed zeros** come out of each IEEE operation the same way on every target. The
//!   only place targets differ is min/max, so the lane layer has none of their
//!   instructions: [`Vector::max`] and [`Vector::min`] are a compare and a select with
//!   `maxps`/`minps`'s meaning (the second operand where the operands are equal zeros),
//!   where ARM's `fmin`/`fminnm` and wasm's `f32x4.min` order −0 below +0. Selects are
//!   bitwise blends. On AArch64, LLVM turns a select against zero whose mask is a compare
//!   of the same value (`x < 0 ? x : 0`) into `fminnm`; the portable level hides its masks
//!   from that rewrite there, and the lane test checks every level's selects, maxima and
//!   minima on signed zeros and NaNs.
//! * **NaNs** never reach the state: a step that would leave a non-finite value is refused
//!   and changes nothing (see [`Surface::step`](crate::Surface::step)). That matters for the
//!   promise too, because a NaN's sign and payload bits are not portable (x86's default NaN
//!   is negative, ARM's positive, WebAssembly's unspecified).
//!
//! # Chunk views and buffers
//!
//! Lane loops read and write through [`Chunks`] and [`ChunksMut`]: a slice cut, when the
//! view is made, to exactly the chunks of `V::LANES` floats the loop runs over. Inside
//! the loop [`Chunks::get`] and [`ChunksMut::put`] access chunk `k < len` without a
//! bounds check: measured with callgrind on the 256² step, the checks the compiler could
//! not remove on its own were 30% of the step's instructions. Their callers state the
//! `k < len` argument in a `// SAFETY:` line, and `tests/miri.rs` runs the kernels under
//! Miri.
//!
//! Buffers the lane loops stream are [`Floats`]: `f32` buffers that start on a 64-byte
//! boundary whatever the level, so that a chunk load at a multiple of the lane count never
//! straddles two cache lines (aligning the buffers made the 256² step 27% faster on one
//! thread with AVX-512) and the same state serves every level. For the same reason a
//! neighbour one column off is not loaded one element off but shuffled out of two
//! aligned chunks ([`Vector::east`], [`Vector::west`]).
//!
//! What a kernel spills is aligned too: every level entry calls [`align_frame`], so that
//! its stack frame starts on a cache line and no spilled register straddles two.

use std::ops::{Add, AddAssign, BitAnd, BitAndAssign, Div, Mul, Neg, Not, Sub};

/// Implements `+ - * /` and unary `-` for a vector type `$t`, each from one expression in
/// the operands `$a` and `$b` (`$b` unused for negation).
macro_rules! operators {
    ($t:ty, |$a:ident, $b:ident| {
        add: $add:expr, sub: $sub:expr, mul: $mul:expr, div: $div:expr, neg: $neg:expr $(,)?
    }) => {
        impl core::ops::Add for $t {
            type Output = $t;
            #[inline(always)]
            fn add(self, $b: $t) -> $t {
                let $a = self;
                $add
            }
        }
        impl core::ops::Sub for $t {
            type Output = $t;
            #[inline(always)]
            fn sub(self, $b: $t) -> $t {
                let $a = self;
                $sub
            }
        }
        impl core::ops::Mul for $t {
            type Output = $t;
            #[inline(always)]
            fn mul(self, $b: $t) -> $t {
                let $a = self;
                $mul
            }
        }
        impl core::ops::Div for $t {
            type Output = $t;
            #[inline(always)]
            fn div(self, $b: $t) -> $t {
                let $a = self;
                $div
            }
        }
        impl core::ops::Neg for $t {
            type Output = $t;
            #[inline(always)]
            fn neg(self) -> $t {
                let $a = self;
                $neg
            }
        }
        impl core::ops::AddAssign for $t {
            #[inline(always)]
            fn add_assign(&mut self, o: $t) {
                *self = *self + o;
            }
        }
    };
}

#[cfg(target_arch = "x86_64")]
pub(crate) mod avx2;
#[cfg(target_arch = "x86_64")]
pub(crate) mod avx512;
mod chunks;
#[cfg(any(
    target_arch = "x86_64",
    target_arch = "aarch64",
    all(target_arch = "wasm32", target_feature = "simd128"),
))]
mod halves;
mod level;
#[cfg(target_arch = "aarch64")]
pub(crate) mod neon;
pub(crate) mod portable;
#[cfg(all(target_arch = "wasm32", target_feature = "simd128"))]
pub(crate) mod simd128;
#[cfg(target_arch = "x86_64")]
pub(crate) mod sse2;

/// The most lanes any level has (AVX-512): buffers are padded and aligned for it.
pub const MAX_LANES: usize = 16;

pub use chunks::{round_up, Floats};
pub(crate) use chunks::{Chunks, ChunksMut};
pub use level::SimdLevel;

/// A vector of `f32` lanes: what the lane kernels are written against.
///
/// Masks are [`Vector::Mask`]: all-ones lanes of a vector for SSE2, AVX2 and SIMD128, of
/// a pair of `uint32x4_t` for NEON, a mask register for AVX-512, and `bool`s for the
/// portable lanes. Every method is `#[inline(always)]` in every implementation, so that it
/// is compiled with the instruction set of the kernel it is inlined into.
pub(crate) trait Vector:
    Copy
    + Send
    + Sync
    + bytemuck::Pod
    + std::fmt::Debug
    + Add<Output = Self>
    + Sub<Output = Self>
    + Mul<Output = Self>
    + Div<Output = Self>
    + Neg<Output = Self>
    + AddAssign
{
    /// `f32` lanes per vector.
    const LANES: usize;

    /// Whether the row kernel reads a chunk's three neighbour position triples before its
    /// springs (`true`) or each just before its first use. The values and the arithmetic
    /// are the same either way; only the machine code differs. The register levels do
    /// best reading ahead (SSE2's pairs of registers spill more otherwise); the portable
    /// lanes, plain arrays that the compiler vectorises on its own, run fewer
    /// instructions with each read next to its use (`docs/performance.md`).
    const READ_AHEAD: bool = true;

    /// Lane masks.
    type Mask: Copy + BitAnd<Output = Self::Mask> + BitAndAssign + Not<Output = Self::Mask>;

    /// Every lane `x`.
    fn splat(x: f32) -> Self;

    /// Every lane 0.
    #[inline(always)]
    fn zero() -> Self {
        Self::zeroed()
    }

    /// Every lane 1.
    #[inline(always)]
    fn one() -> Self {
        Self::splat(1.0)
    }

    /// Lanes from `a[..LANES]`, zeros past the end of a shorter `a`.
    #[cfg(test)]
    #[inline(always)]
    fn from_slice(a: &[f32]) -> Self {
        let mut l = [0.0; MAX_LANES];
        let n = a.len().min(Self::LANES);
        l[..n].copy_from_slice(&a[..n]);
        // SAFETY: `l` holds `MAX_LANES ≥ LANES` floats.
        unsafe { Self::load(l.as_ptr()) }
    }

    /// Writes the first `out.len()` (at most `LANES`) lanes to `out`.
    #[inline(always)]
    fn write_to(self, out: &mut [f32]) {
        let mut l = [0.0; MAX_LANES];
        // SAFETY: `l` holds `MAX_LANES ≥ LANES` floats.
        unsafe { Self::store(l.as_mut_ptr(), self) };
        let n = out.len();
        out.copy_from_slice(&l[..Self::LANES][..n]);
    }

    /// IEEE square root per lane.
    fn sqrt(self) -> Self;

    /// `|x|` per lane (clears the sign bit).
    fn abs(self) -> Self;

    /// Per lane `if self > other { self } else { other }`: `maxps` semantics, the second
    /// operand where either is NaN. A compare and a select unless the level has `maxps`
    /// itself (ARM's and wasm's own maxima return NaN for a NaN operand and order −0
    /// below +0).
    #[inline(always)]
    fn max(self, other: Self) -> Self {
        Self::select(self.gt(other), self, other)
    }

    /// Per lane `if self < other { self } else { other }` (`minps` semantics).
    #[inline(always)]
    fn min(self, other: Self) -> Self {
        Self::select(self.lt(other), self, other)
    }

    /// `self > other` per lane (false where either is NaN).
    fn gt(self, other: Self) -> Self::Mask;

    /// `self < other` per lane.
    fn lt(self, other: Self) -> Self::Mask;

    /// `self >= other` per lane.
    fn ge(self, other: Self) -> Self::Mask;

    /// `a` where `m`, else `b`.
    fn select(m: Self::Mask, a: Self, b: Self) -> Self;

    /// `a` where `m`, else +0: [`Vector::select`] against zero, which the kernels do
    /// for absent springs, calm lanes, pinned nodes and the lanes past a row.
    #[inline(always)]
    fn keep(m: Self::Mask, a: Self) -> Self {
        Self::select(m, a, Self::zero())
    }

    /// A mask with every lane on.
    fn all_lanes() -> Self::Mask;

    /// A mask with lanes `..count` on.
    fn first_lanes(count: usize) -> Self::Mask;

    /// Whether every lane of `m` is on.
    fn all(m: Self::Mask) -> bool;

    /// Whether any lane is NaN.
    fn any_nan(self) -> bool;

    /// Lanes `1..` of `lo` then lane 0 of `hi`: with `hi` the chunk after `lo`, the east
    /// neighbour of every column of `lo`.
    fn east(lo: Self, hi: Self) -> Self;

    /// Lane `LANES − 1` of `lo` then lanes `..LANES − 1` of `hi`: with `lo` the chunk
    /// before `hi`, the west neighbour of every column of `hi`.
    fn west(lo: Self, hi: Self) -> Self;

    /// Loads `LANES` floats from `p`.
    ///
    /// # Safety
    ///
    /// `p` is valid for reading `LANES` floats.
    unsafe fn load(p: *const f32) -> Self;

    /// Stores `LANES` floats at `p`.
    ///
    /// # Safety
    ///
    /// `p` is valid for writing `LANES` floats.
    unsafe fn store(p: *mut f32, v: Self);

    /// Stores `LANES` floats at `p` with a non-temporal store: the cache line goes to
    /// memory without being read first or kept in cache (plain stores where the level has
    /// none, and under Miri). Call [`Vector::fence`] before another thread reads them.
    ///
    /// # Safety
    ///
    /// `p` is valid for writing `LANES` floats and aligned to `size_of::<Self>()`.
    #[inline(always)]
    unsafe fn stream(p: *mut f32, v: Self) {
        // SAFETY: the caller's guarantee covers a plain store's.
        unsafe { Self::store(p, v) }
    }

    /// Makes this thread's [`Vector::stream`] stores visible before its later stores
    /// (nothing to do where they are plain stores).
    #[inline(always)]
    fn fence() {}

    /// The level whose instruction set this vector type needs.
    const LEVEL: SimdLevel;

    /// Runs `task` compiled for this vector type's instruction set: inside a function with
    /// its `#[target_feature]`, into which the task and every lane operation are inlined.
    ///
    /// The entry is never inlined, not even into another entry of the same level: a task
    /// entered inside a task (the engine's rows inside its bands) stays a function of its
    /// own, which keeps every function small enough for LLVM to compile quickly.
    ///
    /// Panics if the CPU lacks the instruction set; [`dispatch`] and the engine only name
    /// a vector type whose level they clamped to the CPU's.
    fn enter<T: Task<Self>>(task: T) -> T::Output;
}

/// Makes the level entry that calls it align its stack frame to a cache line, so that
/// the registers its kernel spills are stored and reloaded whole, never split across two
/// lines (in release builds: with debug assertions the kernel's inner functions may keep
/// frames of their own).
///
/// A 32- or 64-byte register spilled to a frame that is only 16-byte aligned straddles a
/// cache line up to one time in two (AVX2) or every time (AVX-512), and each such access
/// costs about two. LLVM realigns a frame only if it knows before register allocation that
/// the frame holds an over-aligned object: spills appear during allocation, too late to
/// reserve the frame pointer that realigning needs, and then go to unaligned slots. So
/// whether an entry's spills were aligned depended on some other over-aligned temporary
/// surviving inlining into it (`docs/performance.md`: the same AVX2 row kernel 22% slower
/// without one). A cache-line-aligned local that escapes into [`std::hint::black_box`]
/// makes every entry realign, for a few stores per call and the frame pointer. (The SSE2
/// and portable entries call it too: in a build for a wider target their vectors may be
/// compiled to wider registers.)
#[inline(always)]
pub(crate) fn align_frame() {
    #[repr(align(64))]
    struct Line {
        _bytes: [u8; 64],
    }
    // Mutable, so that it is a local of the frame rather than a promoted constant.
    std::hint::black_box(&mut Line { _bytes: [0; 64] });
}

/// The [`Vector::enter`] of a vector type with nothing to enable, whose instruction set
/// is part of its target's baseline (the portable lanes; pairs and singles of SSE2, NEON
/// or SIMD128 halves): a function of its own, as every level's entry is, with its frame
/// aligned.
#[inline(never)]
pub(crate) fn baseline_entry<V: Vector, T: Task<V>>(task: T) -> T::Output {
    debug_assert!(V::LEVEL.is_available());
    align_frame();
    task.run()
}

/// Work done with one vector type `V`, compiled for its instruction set by
/// [`Vector::enter`]. `run` is `#[inline(always)]` in every implementation.
pub(crate) trait Task<V> {
    /// What the work returns.
    type Output;

    /// Does the work.
    fn run(self) -> Self::Output;
}

/// Work written once for every vector type; [`dispatch`] runs it at a level.
pub(crate) trait Kernel {
    /// What the work returns.
    type Output;

    /// Does the work with vector type `V`. `#[inline(always)]` in every implementation,
    /// so that the body is compiled inside `V`'s `#[target_feature]` entry.
    fn run<V: Vector>(self) -> Self::Output;
}

/// A [`Kernel`] as a [`Task`] of any vector type.
struct Each<K>(K);

impl<K: Kernel, V: Vector> Task<V> for Each<K> {
    type Output = K::Output;

    #[inline(always)]
    fn run(self) -> K::Output {
        self.0.run::<V>()
    }
}

/// Runs `k` with the vector type of `level`, clamped to what the CPU has. The portable
/// lanes stand in for [`SimdLevel::Scalar`] (callers with a scalar twin run it
/// themselves) and for every level under Miri; SIMD128 stands in for both in a `wasm32`
/// build with `+simd128`.
#[inline]
pub(crate) fn dispatch<K: Kernel>(level: SimdLevel, k: K) -> K::Output {
    match level.clamped() {
        #[cfg(all(target_arch = "x86_64", not(miri)))]
        SimdLevel::Avx512 => avx512::F32x16::enter(Each(k)),
        #[cfg(all(target_arch = "x86_64", not(miri)))]
        SimdLevel::Avx2 => avx2::F32x8::enter(Each(k)),
        #[cfg(all(target_arch = "x86_64", not(miri)))]
        SimdLevel::Sse2 => sse2::F32x8::enter(Each(k)),
        #[cfg(all(target_arch = "aarch64", not(miri)))]
        SimdLevel::Neon => neon::F32x8::enter(Each(k)),
        // Every level in a `wasm32` build with `+simd128`, whose kernels are not compiled
        // for the portable lanes (`SimdLevel::is_available`).
        #[cfg(all(target_arch = "wasm32", target_feature = "simd128", not(miri)))]
        _ => simd128::F32x4::enter(Each(k)),
        // The scalar reference, the portable level, and (never reached: `clamped` returns
        // only levels of this target) the levels of other targets.
        #[cfg(all(target_arch = "wasm32", not(target_feature = "simd128"), not(miri)))]
        _ => portable::F32x1::enter(Each(k)),
        #[cfg(not(all(target_arch = "wasm32", not(miri))))]
        _ => portable::F32x8::enter(Each(k)),
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Checks one vector type's operations lane by lane against plain `f32` arithmetic.
    struct LaneOps;

    impl Kernel for LaneOps {
        type Output = ();

        #[inline(always)]
        fn run<V: Vector>(self) {
            let n = V::LANES;
            let a: Vec<f32> = (0..n).map(|i| i as f32 - 3.5).collect();
            let b: Vec<f32> = (0..n).map(|i| (n + i) as f32 * 0.25).collect();
            // Lanes a select must pass through unchanged: −0, NaN, infinities.
            let special = [
                -0.0,
                f32::NAN,
                f32::INFINITY,
                f32::NEG_INFINITY,
                0.5,
                -2.0,
                0.0,
            ];
            let c: Vec<f32> = (0..n).map(|i| special[i % special.len()]).collect();
            // The same special values against each other and zeros of both signs.
            let other = [0.0, -0.0, f32::NAN, 0.0, -0.0, f32::NAN, -0.0];
            let d: Vec<f32> = (0..n).map(|i| other[(i + 3) % other.len()]).collect();
            let (va, vb, vc) = (V::from_slice(&a), V::from_slice(&b), V::from_slice(&c));
            let vd = V::from_slice(&d);
            // `x` if `take`, else `y`, as bits. The condition goes through `black_box`: on
            // AArch64, LLVM turns `if x < 0.0 { x } else { 0.0 }` into `fminnm`, which
            // returns −0 for x = −0, so the plain expression is no oracle there.
            let pick = |take: bool, x: f32, y: f32| {
                if std::hint::black_box(take) {
                    x
                } else {
                    y
                }
            };
            let lanes = |v: V| {
                let mut o = vec![0.0; n];
                v.write_to(&mut o);
                o
            };
            let e = lanes(V::east(va, vb));
            let w = lanes(V::west(va, vb));
            for i in 0..n {
                let east = if i + 1 < n { a[i + 1] } else { b[0] };
                let west = if i == 0 { a[n - 1] } else { b[i - 1] };
                assert_eq!(e[i], east, "east lane {i}");
                assert_eq!(w[i], west, "west lane {i}");
            }
            let ops = [
                (
                    lanes(va + vb),
                    a.iter().zip(&b).map(|(x, y)| x + y).collect::<Vec<_>>(),
                ),
                (
                    lanes(va - vb),
                    a.iter().zip(&b).map(|(x, y)| x - y).collect(),
                ),
                (
                    lanes(va * vb),
                    a.iter().zip(&b).map(|(x, y)| x * y).collect(),
                ),
                (
                    lanes(va / vb),
                    a.iter().zip(&b).map(|(x, y)| x / y).collect(),
                ),
                (lanes(vb.sqrt()), b.iter().map(|x| x.sqrt()).collect()),
                (lanes(-va), a.iter().map(|x| -x).collect()),
                (lanes(va.abs()), a.iter().map(|x| x.abs()).collect()),
                (
                    lanes(V::select(va.gt(V::zero()), va, vb)),
                    a.iter()
                        .zip(&b)
                        .map(|(x, y)| if *x > 0.0 { *x } else { *y })
                        .collect(),
                ),
                (
                    lanes(V::select(V::first_lanes(3), va, vb)),
                    (0..n).map(|i| if i < 3 { a[i] } else { b[i] }).collect(),
                ),
                (
                    lanes(V::keep(vc.lt(V::zero()), vc)),
                    c.iter().map(|&x| pick(x < 0.0, x, 0.0)).collect(),
                ),
                (
                    lanes(V::keep(!vc.abs().lt(V::one()), vc)),
                    c.iter().map(|&x| pick(x.abs() < 1.0, 0.0, x)).collect(),
                ),
                (
                    lanes(V::keep(V::first_lanes(5) & !vc.lt(V::zero()), vc)),
                    (0..n)
                        .map(|i| pick(i < 5 && (c[i] >= 0.0 || c[i].is_nan()), c[i], 0.0))
                        .collect(),
                ),
                // `maxps`/`minps`: the second operand where either is NaN or both are
                // zeros, whatever their signs.
                (
                    lanes(vc.max(vd)),
                    c.iter().zip(&d).map(|(&x, &y)| pick(x > y, x, y)).collect(),
                ),
                (
                    lanes(vd.max(vc)),
                    c.iter().zip(&d).map(|(&x, &y)| pick(y > x, y, x)).collect(),
                ),
                (
                    lanes(vc.min(vd)),
                    c.iter().zip(&d).map(|(&x, &y)| pick(x < y, x, y)).collect(),
                ),
                (
                    lanes(vd.min(vc)),
                    c.iter().zip(&d).map(|(&x, &y)| pick(y < x, y, x)).collect(),
                ),
            ];
            for (k, (got, want)) in ops.iter().enumerate() {
                let (g, w): (Vec<u32>, Vec<u32>) = (
                    got.iter().map(|x| x.to_bits()).collect(),
                    want.iter().map(|x| x.to_bits()).collect(),
                );
                assert_eq!(g, w, "operation {k} on {}", core::any::type_name::<V>());
            }
            assert!(!va.any_nan());
            assert!((va / V::zero() * V::zero()).any_nan());
            assert!(V::all(V::all_lanes()) && !V::all(V::first_lanes(n - 1)));
        }
    }

    #[test]
    fn every_available_level_matches_plain_arithmetic() {
        for level in SimdLevel::ALL.into_iter().filter(|l| l.is_available()) {
            dispatch(level, LaneOps);
        }
        portable::F32x8::enter(Each(LaneOps));
        portable::F32x1::enter(Each(LaneOps));
        // One half of SSE2's or NEON's pairs on its own, as SIMD128 runs its half.
        #[cfg(all(target_arch = "x86_64", not(miri)))]
        halves::Single::<core::arch::x86_64::__m128>::enter(Each(LaneOps));
        #[cfg(all(target_arch = "aarch64", not(miri)))]
        halves::Single::<core::arch::aarch64::float32x4_t>::enter(Each(LaneOps));
    }
}
