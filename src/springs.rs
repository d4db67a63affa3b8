//! Per-spring tables and the colour batches that let threads add forces without conflicts.
//!
//! # Spring tables
//!
//! Each family ([`Family`]) has a rest-length and a coefficient buffer indexed by the
//! spring's origin node, padded like the node buffers. A spring that does not exist
//! (E from the last column, S from the last row, …) has coefficient and rest length 0, so
//! it contributes exactly nothing and lane code needs no special case for it.
//!
//! # Colours
//!
//! A spring touches two nodes, and two threads adding into one node's force at once would
//! race. The springs are therefore cut into *bands*: band `b` owns every spring whose
//! origin lies in rows `[b·H, (b+1)·H)`, and so touches rows `b·H ..= (b+1)·H`. Even bands
//! are colour 0, odd bands colour 1. Two bands of one colour are at least one band apart,
//! so they touch disjoint node sets and run in parallel with no atomics and no locks;
//! inside a band, rows are processed in order with SIMD across columns.
//!
//! Why bands rather than single springs by family and parity (8 colours)? A colour pass
//! over single springs is a full sweep over memory, so 8 colours read the state 8 times
//! per step; a band streams its rows once and keeps the forces of the two rows in flight
//! in cache.
//!
//! The band height trades per-band overhead (each band parks and restores one row of
//! forces, about 1/height of its work) against load balance (each colour needs a few
//! bands per thread). `springwater bench --band-rows H` measures it: on 256² with 2
//! threads (native build) 16 rows gave 7.5·10⁸ node updates/s, 32 rows 7.5·10⁸, 64 rows
//! 5.9·10⁸ (2 bands a colour) and 128 rows 4.1·10⁸; heights below 8 lost 10% or more in
//! earlier runs. So the engine picks, per step, [`band_rows`]`(rows, threads)`: about 4
//! bands per thread, clamped to 8..=64 rows. The choice never changes a bit of the result
//! (the per-node arithmetic does not depend on it), so it may follow the thread count.

use crate::grid::{Family, Grid, SpringId};
use crate::params::Params;
use crate::state::padded_len;
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

/// Rest length and coefficient of every spring, one buffer per family.
///
/// The tables are the truth. Beside them each family keeps a summary: the one
/// `(coefficient, rest length)` pair all its springs share, while they do. The engine then
/// reads those two numbers instead of the two tables, which saves 32 of the ~100 bytes a
/// step moves per node; the first [`Springs::set`] that breaks the agreement switches the
/// family to its tables. The scalar reference always reads the tables, so the parity tests
/// check the summaries too.
#[derive(Debug, Clone)]
pub(crate) struct Springs {
    /// Rest length `L0` per family, indexed by origin node.
    pub rest: [crate::simd::Floats; 4],
    /// Coefficient `c` per family, indexed by origin node.
    pub coef: [crate::simd::Floats; 4],
    /// `(c, L0)` shared by every spring of a family, if they all agree.
    uniform: [Option<(f32, f32)>; 4],
}

impl Springs {
    /// Uniform springs: coefficient `c`, rest length `rest_ratio ×` initial length.
    pub fn new(params: &Params) -> Self {
        let grid = Grid::new(params.cols, params.rows);
        let len = padded_len(grid.len());
        let mut rest: [crate::simd::Floats; 4] =
            std::array::from_fn(|_| crate::simd::Floats::zeros(len));
        let mut coef: [crate::simd::Floats; 4] =
            std::array::from_fn(|_| crate::simd::Floats::zeros(len));
        for (id, _) in grid.springs() {
            let f = id.family as usize;
            rest[f][id.origin] = params.rest_ratio * id.family.initial_length() * params.spacing;
            coef[f][id.origin] = params.stiffness;
        }
        let mut springs = Self {
            rest,
            coef,
            uniform: [None; 4],
        };
        springs.refresh(grid);
        springs
    }

    /// Sets one spring's rest length and coefficient.
    pub fn set(&mut self, id: SpringId, rest: f32, coef: f32) {
        let f = id.family as usize;
        self.rest[f][id.origin] = rest;
        self.coef[f][id.origin] = coef;
        if self.uniform[f]
            .is_some_and(|u| u.0.to_bits() != coef.to_bits() || u.1.to_bits() != rest.to_bits())
        {
            self.uniform[f] = None;
        }
    }

    /// Recomputes the per-family summaries after the tables were written wholesale.
    pub fn refresh(&mut self, grid: Grid) {
        for family in Family::ALL {
            let f = family as usize;
            let mut existing = (0..grid.len())
                .filter(|&i| grid.spring_end(family, i).is_some())
                .map(|i| (self.coef[f][i].to_bits(), self.rest[f][i].to_bits()));
            let first = existing.next();
            self.uniform[f] = first
                .filter(|&u| existing.all(|v| v == u))
                .map(|(c, r)| (f32::from_bits(c), f32::from_bits(r)));
        }
    }

    /// The `(coefficient, rest length)` every spring of `family` shares, if they all agree.
    pub fn uniform(&self, family: usize) -> Option<(f32, f32)> {
        self.uniform[family]
    }
}

/// One batch of springs: a band of rows, with its colour.
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct Band {
    /// 0 for even bands, 1 for odd ones.
    pub colour: usize,
    /// The rows whose springs (by origin) belong to this band.
    pub rows: Range<usize>,
}

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

/// The bands of a grid with `rows` rows, `band_rows` rows each (the last may be shorter).
pub fn bands(rows: usize, band_rows: usize) -> impl Iterator<Item = Band> {
    let band_rows = band_rows.max(1);
    (0..rows.div_ceil(band_rows)).map(move |b| Band {
        colour: b % 2,
        rows: b * band_rows..((b + 1) * band_rows).min(rows),
    })
}
