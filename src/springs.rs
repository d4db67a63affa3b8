//! Per-spring tables: each spring's rest length and coefficient. (The colour batches that
//! let threads add forces without conflicts are the engine's: `forces/engine/tiling.rs`.)
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

use crate::grid::{Family, Grid, SpringId};
use crate::params::Params;
use crate::simd::Floats;
use crate::state::padded_len;

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
