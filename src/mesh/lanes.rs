//! Safe lane loops over the render-side stages' per-node arrays.
//!
//! A stage's lane loop reads and writes its arrays a chunk of `V::LANES` nodes at a time.
//! Zipped [`chunks_exact`](slice::chunks_exact) iterators over arrays cut to the same
//! whole number of chunks give every chunk without an index, so there is no bounds check
//! left in the loop for the compiler to prove, and each chunk is exactly `V::LANES` floats
//! long, so its load and store are one full vector (no zero-filled or truncated lanes).
//! The iterators yield plain slices, which the compiler inlines into the loop; the loads
//! and stores happen in the loop body, compiled for the kernel's instruction set.

use std::iter::Zip;
use std::slice::{ChunksExact, ChunksExactMut};

use crate::simd::Vector;

/// A chunk of each of three arrays: `((x, y), z)`, as [`Xyz`] yields them.
pub(crate) type Chunk3<'a> = ((&'a [f32], &'a [f32]), &'a [f32]);

/// A chunk of each of three output arrays, as [`xyz_chunks_mut`] yields them.
pub(crate) type Chunk3Mut<'a> = ((&'a mut [f32], &'a mut [f32]), &'a mut [f32]);

/// The chunks of three arrays, side by side.
pub(crate) type Xyz<'a> =
    Zip<Zip<ChunksExact<'a, f32>, ChunksExact<'a, f32>>, ChunksExact<'a, f32>>;

/// The chunks of three output arrays, side by side.
pub(crate) type XyzMut<'a> =
    Zip<Zip<ChunksExactMut<'a, f32>, ChunksExactMut<'a, f32>>, ChunksExactMut<'a, f32>>;

/// Three arrays (x, y, z), `V::LANES` nodes at a time: the whole chunks of the `len` nodes
/// from node `from`, `len` a multiple of `V::LANES`. Panics if an array is shorter.
#[inline(always)]
pub(crate) fn xyz_chunks<V: Vector>(s: [&[f32]; 3], from: usize, len: usize) -> Xyz<'_> {
    let [x, y, z] = s.map(|s| s[from..from + len].chunks_exact(V::LANES));
    x.zip(y).zip(z)
}

/// Three output arrays, `V::LANES` nodes at a time, as [`xyz_chunks`].
#[inline(always)]
pub(crate) fn xyz_chunks_mut<V: Vector>(s: [&mut [f32]; 3], from: usize, len: usize) -> XyzMut<'_> {
    let [x, y, z] = s.map(|s| s[from..from + len].chunks_exact_mut(V::LANES));
    x.zip(y).zip(z)
}

/// The vectors of one chunk of [`xyz_chunks`] (unaligned loads).
#[inline(always)]
pub(crate) fn load<V: Vector>(((x, y), z): Chunk3<'_>) -> [V; 3] {
    [load1(x), load1(y), load1(z)]
}

/// Writes one vector to each array of a chunk of [`xyz_chunks_mut`].
#[inline(always)]
pub(crate) fn store<V: Vector>(((x, y), z): Chunk3Mut<'_>, v: [V; 3]) {
    let [vx, vy, vz] = v;
    vx.write_to(x);
    vy.write_to(y);
    vz.write_to(z);
}

/// The vector of one chunk of exactly `V::LANES` floats: its bytes, read unaligned.
#[inline(always)]
fn load1<V: Vector>(chunk: &[f32]) -> V {
    // A vector is its lanes and nothing else, so a chunk's bytes are exactly one vector's
    // and the length check of the read is decided at compile time.
    const { assert!(std::mem::size_of::<V>() == 4 * V::LANES) };
    bytemuck::pod_read_unaligned(bytemuck::cast_slice(chunk))
}
