//! Chunk views and aligned buffers: what the lane loops read and write through (see the
//! lane layer's docs, "Chunk views and buffers").

use super::{Vector, MAX_LANES};

/// `count` chunks of `V::LANES` floats of a slice, from element `start` on. The length
/// check happens once, when the view is made; [`Chunks::get`] then reads without one.
#[derive(Debug)]
pub(crate) struct Chunks<'a, V> {
    s: &'a [f32],
    _lanes: std::marker::PhantomData<V>,
}

impl<V> Clone for Chunks<'_, V> {
    fn clone(&self) -> Self {
        *self
    }
}

impl<V> Copy for Chunks<'_, V> {}

impl<'a, V: Vector> Chunks<'a, V> {
    /// Chunk `k` is `s[start + k·LANES ..][..LANES]`. Panics if `s` is shorter than that.
    #[inline(always)]
    pub fn new(s: &'a [f32], start: usize, count: usize) -> Self {
        Self {
            s: &s[start..start + count * V::LANES],
            _lanes: std::marker::PhantomData,
        }
    }

    /// Number of chunks.
    #[inline(always)]
    pub fn len(self) -> usize {
        self.s.len() / V::LANES
    }

    /// Chunk `k`, without a bounds check.
    ///
    /// # Safety
    ///
    /// `k < self.len()`.
    #[inline(always)]
    pub unsafe fn get(self, k: usize) -> V {
        debug_assert!(k < self.len());
        // SAFETY: `k < len`, so `k·LANES + LANES ≤ s.len()`.
        unsafe { V::load(self.s.as_ptr().add(k * V::LANES)) }
    }
}

/// Mutable [`Chunks`].
#[derive(Debug)]
pub(crate) struct ChunksMut<'a, V> {
    s: &'a mut [f32],
    _lanes: std::marker::PhantomData<V>,
}

impl<'a, V: Vector> ChunksMut<'a, V> {
    /// Chunk `k` is `s[start + k·LANES ..][..LANES]`. Panics if `s` is shorter than that.
    #[inline(always)]
    pub fn new(s: &'a mut [f32], start: usize, count: usize) -> Self {
        Self {
            s: &mut s[start..start + count * V::LANES],
            _lanes: std::marker::PhantomData,
        }
    }

    /// Number of chunks.
    #[inline(always)]
    pub fn len(&self) -> usize {
        self.s.len() / V::LANES
    }

    /// Stores `v` into chunk `k`, without a bounds check.
    ///
    /// # Safety
    ///
    /// `k < self.len()`.
    #[inline(always)]
    pub unsafe fn put(&mut self, k: usize, v: V) {
        debug_assert!(k < self.len());
        // SAFETY: `k < len`, so `k·LANES + LANES ≤ s.len()`.
        unsafe { V::store(self.s.as_mut_ptr().add(k * V::LANES), v) }
    }

    /// Stores `v` into chunk `k` with a non-temporal store ([`Vector::stream`]).
    ///
    /// # Safety
    ///
    /// `k < self.len()`, and chunk `k` starts on a `size_of::<V>()` boundary.
    #[inline(always)]
    pub unsafe fn stream(&mut self, k: usize, v: V) {
        debug_assert!(k < self.len());
        // SAFETY: `k < len`, so `k·LANES + LANES ≤ s.len()`.
        let p = unsafe { self.s.as_mut_ptr().add(k * V::LANES) };
        debug_assert!((p as usize).is_multiple_of(core::mem::size_of::<V>()));
        // SAFETY: `p` is valid for `LANES` floats; the caller guarantees its alignment.
        unsafe { V::stream(p, v) }
    }
}

/// Rounds `n` up to a multiple of [`MAX_LANES`].
pub const fn round_up(n: usize) -> usize {
    n.div_ceil(MAX_LANES) * MAX_LANES
}

/// 64 bytes of `f32`, aligned to 64: the unit [`Floats`] allocates in.
#[derive(Clone, Copy, Default, bytemuck::Pod, bytemuck::Zeroable)]
#[repr(C, align(64))]
struct Block([f32; MAX_LANES]);

/// A zero-initialised `f32` buffer that starts on a 64-byte boundary, so that chunk loads
/// at multiples of any level's lane count never straddle two cache lines. Dereferences to
/// `[f32]`.
#[derive(Clone, Default)]
pub struct Floats {
    blocks: Vec<Block>,
    len: usize,
}

impl Floats {
    /// `len` zeros.
    pub fn zeros(len: usize) -> Self {
        Self {
            blocks: vec![Block::default(); len.div_ceil(MAX_LANES)],
            len,
        }
    }
}

impl std::ops::Deref for Floats {
    type Target = [f32];
    #[inline(always)]
    fn deref(&self) -> &[f32] {
        &bytemuck::cast_slice(&self.blocks)[..self.len]
    }
}

impl std::ops::DerefMut for Floats {
    #[inline(always)]
    fn deref_mut(&mut self) -> &mut [f32] {
        &mut bytemuck::cast_slice_mut(&mut self.blocks)[..self.len]
    }
}

impl std::fmt::Debug for Floats {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.debug_list().entries(self.iter()).finish()
    }
}
