//! SSE2, part of every x86-64 CPU: eight `f32` lanes in two 128-bit registers (two
//! independent halves per operation, which keeps the out-of-order core busy); masks are
//! all-ones lanes. SSE2 has no blend, so a select is and, and-not, or.

use super::{SimdLevel, Task, Vector};
use core::arch::x86_64::*;

/// Eight `f32` lanes in two `__m128`, low half first.
#[derive(Debug, Clone, Copy)]
#[repr(C)]
pub(crate) struct F32x8([__m128; 2]);

// SAFETY: two `__m128` are 32 bytes of plain data: no padding, every bit pattern valid.
unsafe impl bytemuck::Zeroable for F32x8 {}
// SAFETY: as above.
unsafe impl bytemuck::Pod for F32x8 {}

impl F32x8 {
    /// `f` on each half.
    #[inline(always)]
    fn map(self, f: impl Fn(__m128) -> __m128) -> Self {
        Self(self.0.map(f))
    }

    /// `f` on each pair of halves.
    #[inline(always)]
    fn zip(self, o: Self, f: impl Fn(__m128, __m128) -> __m128) -> Self {
        Self([f(self.0[0], o.0[0]), f(self.0[1], o.0[1])])
    }
}

/// Runs one intrinsic expression. SSE and SSE2 are part of the x86_64 baseline, so every
/// intrinsic here is available on every CPU the crate runs on.
macro_rules! sse {
    ($e:expr) => {
        // SAFETY: SSE2 is part of the x86_64 baseline.
        unsafe { $e }
    };
}

operators!(F32x8, |a, b| {
    add: a.zip(b, |x, y| sse!(_mm_add_ps(x, y))),
    sub: a.zip(b, |x, y| sse!(_mm_sub_ps(x, y))),
    mul: a.zip(b, |x, y| sse!(_mm_mul_ps(x, y))),
    div: a.zip(b, |x, y| sse!(_mm_div_ps(x, y))),
    neg: a.map(|x| sse!(_mm_xor_ps(x, _mm_set1_ps(-0.0)))),
});

impl core::ops::BitAnd for F32x8 {
    type Output = Self;
    #[inline(always)]
    fn bitand(self, o: Self) -> Self {
        self.zip(o, |x, y| sse!(_mm_and_ps(x, y)))
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
        self.zip(Self::all_lanes(), |x, y| sse!(_mm_xor_ps(x, y)))
    }
}

/// `[x1, x2, x3, y0]`.
#[inline(always)]
fn east4(x: __m128, y: __m128) -> __m128 {
    sse!({
        let t = _mm_shuffle_ps::<0b00_00_11_11>(x, y); // x3 x3 y0 y0
        _mm_shuffle_ps::<0b10_00_10_01>(x, t) // x1 x2 x3 y0
    })
}

/// `[x3, y0, y1, y2]`.
#[inline(always)]
fn west4(x: __m128, y: __m128) -> __m128 {
    sse!({
        let t = _mm_shuffle_ps::<0b00_00_11_11>(x, y); // x3 x3 y0 y0
        _mm_shuffle_ps::<0b10_01_10_00>(t, y) // x3 y0 y1 y2
    })
}

impl Vector for F32x8 {
    const LANES: usize = 8;
    type Mask = F32x8;

    #[inline(always)]
    fn splat(x: f32) -> Self {
        let h = sse!(_mm_set1_ps(x));
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
        self.map(|x| sse!(_mm_sqrt_ps(x)))
    }

    #[inline(always)]
    fn abs(self) -> Self {
        self.map(|x| sse!(_mm_andnot_ps(_mm_set1_ps(-0.0), x)))
    }

    #[inline(always)]
    fn max(self, o: Self) -> Self {
        self.zip(o, |x, y| sse!(_mm_max_ps(x, y)))
    }

    #[inline(always)]
    fn min(self, o: Self) -> Self {
        self.zip(o, |x, y| sse!(_mm_min_ps(x, y)))
    }

    #[inline(always)]
    fn gt(self, o: Self) -> Self {
        self.zip(o, |x, y| sse!(_mm_cmpgt_ps(x, y)))
    }

    #[inline(always)]
    fn lt(self, o: Self) -> Self {
        self.zip(o, |x, y| sse!(_mm_cmplt_ps(x, y)))
    }

    #[inline(always)]
    fn ge(self, o: Self) -> Self {
        self.zip(o, |x, y| sse!(_mm_cmpge_ps(x, y)))
    }

    #[inline(always)]
    fn select(m: Self, a: Self, b: Self) -> Self {
        let pick = |m: __m128, a: __m128, b: __m128| {
            sse!(_mm_or_ps(_mm_and_ps(m, a), _mm_andnot_ps(m, b)))
        };
        Self([pick(m.0[0], a.0[0], b.0[0]), pick(m.0[1], a.0[1], b.0[1])])
    }

    #[inline(always)]
    fn all_lanes() -> Self {
        let h = sse!(_mm_castsi128_ps(_mm_set1_epi32(-1)));
        Self([h, h])
    }

    #[inline(always)]
    fn first_lanes(count: usize) -> Self {
        let lo = sse!(_mm_setr_ps(0.0, 1.0, 2.0, 3.0));
        let hi = sse!(_mm_setr_ps(4.0, 5.0, 6.0, 7.0));
        Self([lo, hi]).lt(Self::splat(count.min(8) as f32))
    }

    #[inline(always)]
    fn all(m: Self) -> bool {
        sse!(_mm_movemask_ps(m.0[0]) & _mm_movemask_ps(m.0[1]) == 0xf)
    }

    #[inline(always)]
    fn any_nan(self) -> bool {
        let nan = self.zip(self, |x, y| sse!(_mm_cmpunord_ps(x, y)));
        sse!(_mm_movemask_ps(nan.0[0]) | _mm_movemask_ps(nan.0[1]) != 0)
    }

    #[inline(always)]
    fn east(lo: Self, hi: Self) -> Self {
        let ([a, b], [c, _]) = (lo.0, hi.0);
        Self([east4(a, b), east4(b, c)])
    }

    #[inline(always)]
    fn west(lo: Self, hi: Self) -> Self {
        let ([_, b], [c, d]) = (lo.0, hi.0);
        Self([west4(b, c), west4(c, d)])
    }

    #[inline(always)]
    unsafe fn load(p: *const f32) -> Self {
        // SAFETY: the caller guarantees `p` is readable for 8 floats.
        unsafe { Self([_mm_loadu_ps(p), _mm_loadu_ps(p.add(4))]) }
    }

    #[inline(always)]
    unsafe fn store(p: *mut f32, v: Self) {
        // SAFETY: the caller guarantees `p` is writable for 8 floats.
        unsafe {
            _mm_storeu_ps(p, v.0[0]);
            _mm_storeu_ps(p.add(4), v.0[1]);
        }
    }

    #[inline(always)]
    unsafe fn stream(p: *mut f32, v: Self) {
        // SAFETY: the caller guarantees `p` is writable for 8 floats and 32-byte aligned.
        unsafe {
            _mm_stream_ps(p, v.0[0]);
            _mm_stream_ps(p.add(4), v.0[1]);
        }
    }

    #[inline(always)]
    fn fence() {
        sse!(_mm_sfence())
    }

    const LEVEL: SimdLevel = SimdLevel::Sse2;

    #[inline(always)]
    fn enter<T: Task<Self>>(task: T) -> T::Output {
        // A function of its own, as the other levels' entries are.
        #[inline(never)]
        fn entry<T: Task<F32x8>>(task: T) -> T::Output {
            super::align_frame();
            task.run()
        }
        entry(task)
    }
}
