//! Per-spring tables and the colour batches that let threads add forces without conflicts.
//!
//! # Spring values
//!
//! Each family ([`Family`]) has one coefficient and rest length shared by all its springs
//! until a spring is set to values of its own; then every family gets a rest-length and a
//! coefficient buffer indexed by the spring's origin node ([`Springs`]). A spring that does
//! not exist (E from the last column, S from the last row, …) has coefficient and rest
//! length 0 in the tables. The engine does not rely on that: it sets the lanes of absent
//! springs to +0 (a zero coefficient times an infinite length would be NaN), and its
//! uniform path uses the shared values for every lane.
//!
//! # Colours
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
//! The band height trades per-band overhead (one extra row of springs per band and level,
//! about 1/height of its work, and the rows handed across the cuts) against load balance
//! (each colour needs a few bands per thread). `springwater bench --band-rows H` measures
//! it (`docs/performance.md` has the measurements). So the
//! engine picks [`band_rows`]`(rows, threads)`: about 4 bands per thread, clamped to
//! 8..=64 rows (and at least 2 rows per step of a pass). The choice never changes a bit of
//! the result (the per-node arithmetic does not depend on it), so it may follow the
//! thread count.

use crate::grid::{Family, Grid, SpringId};
use crate::params::Params;
use crate::simd::Floats;
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

/// Rest length and coefficient of every spring: one value per family while all the
/// family's springs share it, tables per family once they do not.
///
/// A new lattice's springs are uniform (one coefficient and one rest length per family),
/// and most stay so: open water, pools, every surface that never calls
/// [`Surface::set_spring`](crate::Surface::set_spring). For those the per-spring tables
/// would be 32 bytes per node that say the same eight numbers over and over, a third of
/// the surface's memory, so they are made only when a spring is first set to a value of
/// its own ([`Springs::set`]), from the shared values, and kept from then on.
///
/// Beside the tables each family keeps a summary: the one `(coefficient, rest length)`
/// pair all its springs share, while they do. While every family has one, the engine keeps
/// those eight numbers in registers instead of reading the tables, which saves 32 of the
/// ~100 bytes a step moves per node and a branch per spring; the first [`Springs::set`]
/// that breaks one family's agreement switches the engine to the tables. The scalar
/// reference reads each spring through [`Springs::get`], which returns the table's value
/// or the shared one, the same bits.
#[derive(Debug, Clone)]
pub(crate) struct Springs {
    grid: Grid,
    /// `(c, L0)` shared by every spring of a family, if they all agree.
    uniform: [Option<(f32, f32)>; 4],
    /// Each spring's values, once one spring differs from its family.
    tables: Option<Box<Tables>>,
}

/// Per-spring values, one buffer per family indexed by the spring's origin node, padded
/// like the node buffers; a spring that does not exist (E from the last column, S from
/// the last row, …) has coefficient and rest length 0.
#[derive(Debug, Clone)]
pub(crate) struct Tables {
    /// Rest length `L0` per family.
    pub rest: [Floats; 4],
    /// Coefficient `c` per family.
    pub coef: [Floats; 4],
}

impl Springs {
    /// Uniform springs: coefficient `c`, rest length `rest_ratio ×` initial length.
    pub fn new(params: &Params) -> Self {
        let grid = Grid::new(params.cols, params.rows);
        let shared = |f: Family| {
            (
                params.stiffness,
                params.rest_ratio * f.initial_length() * params.spacing,
            )
        };
        Self {
            grid,
            uniform: Family::ALL.map(|f| Some(shared(f))),
            tables: None,
        }
    }

    /// Springs from whole tables (a snapshot's): kept as shared values where every family
    /// agrees and the springs that do not exist are 0, as tables otherwise.
    pub fn from_tables(grid: Grid, rest: [&[f32]; 4], coef: [&[f32]; 4]) -> Self {
        let len = padded_len(grid.node_count());
        let table = |src: &[f32]| {
            let mut t = Floats::zeros(len);
            t[..src.len()].copy_from_slice(src);
            t
        };
        let mut springs = Self {
            grid,
            uniform: [None; 4],
            tables: Some(Box::new(Tables {
                rest: rest.map(table),
                coef: coef.map(table),
            })),
        };
        springs.refresh();
        let absent_zero = Family::ALL.into_iter().all(|f| {
            (0..grid.node_count())
                .filter(|&i| grid.spring_end(f, i).is_none())
                .all(|i| rest[f as usize][i] == 0.0 && coef[f as usize][i] == 0.0)
        });
        if springs.all_uniform().is_some() && absent_zero {
            springs.tables = None;
        }
        springs
    }

    /// `(coefficient, rest length)` of the spring of family `f` from node `origin`, which
    /// exists.
    #[inline]
    pub fn get(&self, f: Family, origin: usize) -> (f32, f32) {
        match (&self.tables, self.uniform[f as usize]) {
            (Some(t), _) => (t.coef[f as usize][origin], t.rest[f as usize][origin]),
            (None, Some(shared)) => shared,
            (None, None) => unreachable!("a family without shared values has tables"),
        }
    }

    /// The per-spring tables, if a spring was ever set to a value of its own.
    pub fn tables(&self) -> Option<&Tables> {
        self.tables.as_deref()
    }

    /// Sets one spring's rest length and coefficient.
    pub fn set(&mut self, id: SpringId, rest: f32, coef: f32) {
        let f = id.family as usize;
        let same =
            |u: (f32, f32)| u.0.to_bits() == coef.to_bits() && u.1.to_bits() == rest.to_bits();
        if self.tables.is_none() && self.uniform[f].is_some_and(same) {
            return;
        }
        let tables = self.tables_mut();
        tables.rest[f][id.origin] = rest;
        tables.coef[f][id.origin] = coef;
        if self.uniform[f].is_some_and(|u| !same(u)) {
            self.uniform[f] = None;
        }
    }

    /// The tables, made from the shared values if there are none yet.
    fn tables_mut(&mut self) -> &mut Tables {
        let (grid, uniform) = (self.grid, self.uniform);
        self.tables.get_or_insert_with(|| {
            let len = padded_len(grid.node_count());
            let mut t = Tables {
                rest: std::array::from_fn(|_| Floats::zeros(len)),
                coef: std::array::from_fn(|_| Floats::zeros(len)),
            };
            for (id, _) in grid.springs() {
                let f = id.family as usize;
                let (c, l0) = uniform[f].expect("without tables every family is uniform");
                t.rest[f][id.origin] = l0;
                t.coef[f][id.origin] = c;
            }
            Box::new(t)
        })
    }

    /// Recomputes the per-family summaries from the tables.
    fn refresh(&mut self) {
        let Some(t) = &self.tables else {
            return;
        };
        let grid = self.grid;
        for family in Family::ALL {
            let f = family as usize;
            let mut existing = (0..grid.node_count())
                .filter(|&i| grid.spring_end(family, i).is_some())
                .map(|i| (t.coef[f][i].to_bits(), t.rest[f][i].to_bits()));
            let first = existing.next();
            self.uniform[f] = first
                .filter(|&u| existing.all(|v| v == u))
                .map(|(c, r)| (f32::from_bits(c), f32::from_bits(r)));
        }
    }

    /// Moves one family's tables for a shift of the window: the spring between new nodes
    /// `i` and `j` takes the values of the spring between `source(i)` and `source(j)` when
    /// both were in the window, `default` (`(rest, coef)`) otherwise; springs that do not
    /// exist hold 0. A family whose springs all hold `default` has nothing to move.
    pub fn shift_family(
        &mut self,
        family: Family,
        grid: Grid,
        source: impl Fn(usize) -> Option<usize>,
        default: (f32, f32),
    ) {
        let f = family as usize;
        let same = |u: (f32, f32)| {
            u.0.to_bits() == default.1.to_bits() && u.1.to_bits() == default.0.to_bits()
        };
        if self.uniform[f].is_some_and(same) {
            return;
        }
        // Without tables every spring holds its family's first values, the defaults.
        let Some(t) = self.tables.as_deref_mut() else {
            return;
        };
        let n = grid.node_count();
        let (rest, coef) = (t.rest[f][..n].to_vec(), t.coef[f][..n].to_vec());
        for i in 0..n {
            let (r, c) = match grid.spring_end(family, i) {
                None => (0.0, 0.0),
                Some(j) => match (source(i), source(j)) {
                    (Some(s), Some(_)) => (rest[s], coef[s]),
                    _ => default,
                },
            };
            t.rest[f][i] = r;
            t.coef[f][i] = c;
        }
        self.refresh();
    }

    /// Every family's shared `(coefficient, rest length)`, if each family has one.
    pub fn all_uniform(&self) -> Option<[(f32, f32); 4]> {
        match self.uniform {
            [Some(e), Some(s), Some(se), Some(sw)] => Some([e, s, se, sw]),
            _ => None,
        }
    }
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

/// How one engine pass of `levels` steps cuts the rows among the bands.
///
/// A pass advances the state `levels` steps while each band streams its rows once (see
/// `src/forces/engine/`). Level `l` means the state after `l` steps. At each level every row
/// is integrated by exactly one band, and the cut between two bands leans with the level,
/// one row per step, always into the even band:
///
/// ```text
///            band 0 (even)      band 1 (odd)       band 2 (even)
/// level 0    [0, H)             [H, 2H)            [2H, 3H)
/// level l    [0, H−l)           [H−l, 2H+l)        [2H+l, 3H−l)
/// ```
///
/// So an even band (colour 0) shrinks as it climbs the levels: every row it integrates at
/// level `l` needs rows it integrated itself at level `l−1`, and the even bands run in
/// parallel first with nothing from anyone. An odd band (colour 1) grows: it runs second
/// and borrows, at each level, the two rows on either side that the even bands beside it
/// integrated and handed over. Bands of one colour never write the same row, so there are
/// no atomics and no locks; the spring between the two rows at a cut is evaluated on both
/// sides, each side applying it to its own node. The band height is at least `2·levels`,
/// so an even band never shrinks below nothing.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct Tiling {
    /// Rows of the grid.
    pub rows: usize,
    /// Rows per band at level 0 (the last band also takes the remainder).
    pub band_rows: usize,
    /// Steps one pass takes.
    pub levels: usize,
}

impl Tiling {
    /// The tiling of `rows` rows for passes of `levels` steps, with bands of at least
    /// `band_rows` rows (raised to `2·levels`).
    pub fn new(rows: usize, band_rows: usize, levels: usize) -> Self {
        let levels = levels.max(1);
        Self {
            rows,
            band_rows: band_rows.max(2 * levels),
            levels,
        }
    }

    /// Number of bands.
    pub fn bands(&self) -> usize {
        (self.rows / self.band_rows).max(1)
    }

    /// First row of band `b` at level 0 (`rows` for `b ≥ bands()`).
    pub fn band_start(&self, b: usize) -> usize {
        self.cut(b, 0)
    }

    /// Where band `b` starts at `level`: the cut between bands `b−1` and `b`.
    pub fn cut(&self, b: usize, level: usize) -> usize {
        if b == 0 {
            0
        } else if b >= self.bands() {
            self.rows
        } else if b % 2 == 1 {
            b * self.band_rows - level
        } else {
            b * self.band_rows + level
        }
    }

    /// The rows band `b` integrates at `level` (`1..=levels`).
    pub fn rows_at(&self, b: usize, level: usize) -> Range<usize> {
        self.cut(b, level)..self.cut(b + 1, level)
    }
}
