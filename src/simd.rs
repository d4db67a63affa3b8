//! The one place that names the SIMD lane type.
//!
//! `wide` chooses instructions at build time: with AVX-512 enabled
//! (`-C target-cpu=native` on this machine) a lane holds 16 `f32`, otherwise 8
//! (AVX2 with `+avx2`, two SSE registers in a default x86-64 build). The rest of the
//! crate says [`Lane`] and [`LANES`].
//!
//! Loads and stores go through slices of exactly `LANES` elements, so they are
//! bounds-checked once per chunk and need no `unsafe`.

#[cfg(target_feature = "avx512f")]
mod pick {
    /// A vector of `f32` lanes.
    pub type Lane = wide::f32x16;
}
#[cfg(not(target_feature = "avx512f"))]
mod pick {
    /// A vector of `f32` lanes.
    pub type Lane = wide::f32x8;
}
pub use pick::Lane;

/// Number of `f32` in a [`Lane`].
pub const LANES: usize = core::mem::size_of::<Lane>() / 4;

/// Loads `LANES` values starting at `at`.
#[inline(always)]
pub fn load(s: &[f32], at: usize) -> Lane {
    let chunk: &[f32; LANES] = s[at..at + LANES].try_into().unwrap();
    Lane::new(*chunk)
}

/// Stores all lanes at `at`.
#[inline(always)]
pub fn store(s: &mut [f32], at: usize, v: Lane) {
    let chunk: &mut [f32; LANES] = (&mut s[at..at + LANES]).try_into().unwrap();
    *chunk = v.to_array();
}

/// Stores the first `count` lanes at `at` (`count <= LANES`): the tail of a row.
#[inline(always)]
pub fn store_first(s: &mut [f32], at: usize, v: Lane, count: usize) {
    if count == LANES {
        store(s, at, v);
    } else {
        s[at..at + count].copy_from_slice(&v.to_array()[..count]);
    }
}

/// Adds `v` to the `LANES` values at `at`.
#[inline(always)]
pub fn add_to(s: &mut [f32], at: usize, v: Lane) {
    let old = load(s, at);
    store(s, at, old + v);
}

/// Subtracts `v` from the `LANES` values at `at`.
#[inline(always)]
pub fn sub_from(s: &mut [f32], at: usize, v: Lane) {
    let old = load(s, at);
    store(s, at, old - v);
}

/// A mask lane: all-ones where `lane index < count`.
#[inline(always)]
pub fn first_lanes(count: usize) -> Lane {
    let mut m = [0.0f32; LANES];
    for (i, v) in m.iter_mut().enumerate() {
        *v = if i < count {
            f32::from_bits(u32::MAX)
        } else {
            0.0
        };
    }
    Lane::new(m)
}

/// Rounds `n` up to a multiple of `LANES`.
pub const fn round_up(n: usize) -> usize {
    n.div_ceil(LANES) * LANES
}
