//! The colour batches that let threads add spring forces without conflicts: bands of rows,
//! and how a pass of several steps cuts them.
//!
//! A spring touches two nodes, and two threads adding into one node's force at once would
//! race. The rows are therefore cut into *bands* of `H` rows ([`bands`]); even bands are
//! colour 0, odd bands colour 1. A band integrates its own rows and evaluates every spring
//! that ends in them, adding each spring only to its own node (a spring across a cut is
//! evaluated by both bands, each for its own end). Bands of one colour are at least one
//! band apart, so they write disjoint rows and run in parallel with no atomics and no
//! locks; inside a band, rows are processed in order with SIMD across columns. When a
//! pass advances several steps, the cuts lean with the step ([`Tiling`]) so that colour 0
//! needs nothing from colour 1 and colour 1 only what colour 0 handed over.
//!
//! Why bands rather than single springs by family and parity (8 colours)? A colour pass
//! over single springs is a full sweep over memory, so 8 colours read the state 8 times
//! per step; a band streams its rows once and keeps the forces of the rows in flight in
//! cache.
//!
//! The band height trades per-band overhead (one extra row of springs per band and layer,
//! about 1/height of its work, and the rows handed across the cuts) against load balance
//! (each colour needs a few bands per thread). `springwater bench --band-rows H` measures
//! it (`docs/performance.md` has the measurements). So the
//! engine picks [`band_rows`]`(rows, threads)`: about 4 bands per thread, clamped to
//! 8..=64 rows (and at least 2 rows per step of a pass). The choice never changes a bit of
//! the result (the per-node arithmetic does not depend on it), so it may follow the
//! thread count.

use crate::grid::{Family, Grid, SpringId};
use std::ops::Range;

/// Fewest rows per band the engine picks.
pub const MIN_BAND_ROWS: usize = 8;
/// Most rows per band the engine picks.
pub const MAX_BAND_ROWS: usize = 64;

/// The band height the engine uses for `rows` rows on `threads` threads: about 4 bands
/// (2 per colour) per thread, clamped to `MIN_BAND_ROWS..=MAX_BAND_ROWS`.
pub fn band_rows(rows: usize, threads: usize) -> usize {
    rows.div_ceil(4 * threads.max(1))
        .clamp(MIN_BAND_ROWS, MAX_BAND_ROWS)
}

/// One batch of springs: a band of rows, with its colour.
#[cfg_attr(not(feature = "internals"), allow(dead_code))]
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct Band {
    /// 0 for even bands, 1 for odd ones.
    pub colour: usize,
    /// The rows whose springs (by origin) belong to this band.
    pub rows: Range<usize>,
}

#[cfg_attr(not(feature = "internals"), allow(dead_code))]
impl Band {
    /// The springs of this band on `grid`.
    pub fn springs(&self, grid: Grid) -> impl Iterator<Item = SpringId> + '_ {
        let nodes = self.rows.start * grid.cols..self.rows.end * grid.cols;
        Family::ALL.into_iter().flat_map(move |family| {
            nodes
                .clone()
                .filter(move |&origin| grid.spring_end(family, origin).is_some())
                .map(move |origin| SpringId { family, origin })
        })
    }
}

/// The bands of a grid with `rows` rows, `band_rows` rows each; the last band also takes
/// the remainder (so it has `band_rows ..< 2·band_rows` rows), and a grid shorter than
/// `band_rows` is one band.
#[cfg_attr(not(feature = "internals"), allow(dead_code))]
pub fn bands(rows: usize, band_rows: usize) -> impl Iterator<Item = Band> {
    let tiling = Tiling::new(rows, band_rows, 1);
    (0..tiling.bands()).map(move |b| Band {
        colour: b % 2,
        rows: tiling.band_start(b)..tiling.band_start(b + 1),
    })
}

/// How one engine pass of `layers` steps cuts the rows among the bands.
///
/// A pass advances the state `layers` steps while each band streams its rows once (see
/// `src/forces/engine/`). Layer `l` means the state after `l` steps. At each layer every row
/// is integrated by exactly one band, and the cut between two bands leans with the layer,
/// one row per step, always into the even band:
///
/// ```text
///            band 0 (even)      band 1 (odd)       band 2 (even)
/// layer 0    [0, H)             [H, 2H)            [2H, 3H)
/// layer l    [0, H−l)           [H−l, 2H+l)        [2H+l, 3H−l)
/// ```
///
/// So an even band (colour 0) shrinks as it climbs the layers: every row it integrates at
/// layer `l` needs rows it integrated itself at layer `l−1`, and the even bands run in
/// parallel first with nothing from anyone. An odd band (colour 1) grows: it runs second
/// and borrows, at each layer, the two rows on either side that the even bands beside it
/// integrated and handed over. Bands of one colour never write the same row, so there are
/// no atomics and no locks; the spring between the two rows at a cut is evaluated on both
/// sides, each side applying it to its own node. The band height is at least `2·layers`,
/// so an even band never shrinks below nothing.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct Tiling {
    /// Rows of the grid.
    pub rows: usize,
    /// Rows per band at layer 0 (the last band also takes the remainder).
    pub band_rows: usize,
    /// Steps one pass takes.
    pub layers: usize,
}

impl Tiling {
    /// The tiling of `rows` rows for passes of `layers` steps, with bands of at least
    /// `band_rows` rows (raised to `2·layers`).
    pub fn new(rows: usize, band_rows: usize, layers: usize) -> Self {
        let layers = layers.max(1);
        Self {
            rows,
            band_rows: band_rows.max(2 * layers),
            layers,
        }
    }

    /// Number of bands.
    pub fn bands(&self) -> usize {
        (self.rows / self.band_rows).max(1)
    }

    /// First row of band `b` at layer 0 (`rows` for `b ≥ bands()`).
    pub fn band_start(&self, b: usize) -> usize {
        self.cut(b, 0)
    }

    /// Where band `b` starts at `layer`: the cut between bands `b−1` and `b`.
    pub fn cut(&self, b: usize, layer: usize) -> usize {
        if b == 0 {
            0
        } else if b >= self.bands() {
            self.rows
        } else if b % 2 == 1 {
            b * self.band_rows - layer
        } else {
            b * self.band_rows + layer
        }
    }

    /// The rows band `b` integrates at `layer` (`1..=layers`).
    pub fn rows_at(&self, b: usize, layer: usize) -> Range<usize> {
        self.cut(b, layer)..self.cut(b + 1, layer)
    }
}
