//! The engine step: colour-partitioned bands of rows, SIMD across columns, rayon across bands.
//!
//! # How a band streams its rows
//!
//! A band owns the springs whose origin lies in its rows (see [`crate::springs`]). For row
//! `r` it evaluates the E springs inside the row and the S, SE, SW springs down to row
//! `r+1`, adding them into two row-sized force accumulators (`cur` for row r, `next` for
//! row r+1). After that, row r has received every spring force it will get (the springs
//! from row r−1 were added when row r−1 was processed), so it is integrated at once while
//! its data is still in cache, and the accumulators rotate. Forces never make a trip to
//! main memory: a step reads positions, velocities and tables once and writes the new
//! positions and velocities once.
//!
//! # The two colours
//!
//! Only the first row of a band needs springs from outside it (from the last row of the
//! band above). The step runs in two phases:
//!
//! 1. **Colour 0, even bands, in parallel.** Every row is integrated except the band's
//!    first row, whose partial force is parked in the band's `boundary` buffer; the forces
//!    that the band's last row sends down are parked in the next (odd) band's `boundary`.
//! 2. **Colour 1, odd bands, in parallel.** The band starts its first row from the parked
//!    forces, integrates all its rows, and finally the first row of the even band below
//!    (parked forces + the ones it just sent down).
//!
//! Bands of one colour touch disjoint rows, so each task gets `&mut` slices of its own rows
//! (split with `split_at_mut`, no `unsafe`, no atomics, no locks). Every node's arithmetic
//! is fixed by the band layout, not by the schedule, so results are bitwise identical for
//! any thread count and with the `parallel` feature off. A step allocates nothing: the
//! per-band buffers live in [`Workspace`].

use super::StepConfig;
use crate::simd::{add_to, first_lanes, load, store_first, sub_from, Lane, LANES};
use crate::springs::Springs;
use crate::state::State;

/// Offset of column 0 inside a row accumulator (room for the SW spring of column 0).
const LEAD: usize = LANES;

/// Per-band scratch: two row accumulators and one parked row, each `[x, y, z]`.
#[derive(Debug, Clone)]
pub(crate) struct BandScratch {
    ring: [[Vec<f32>; 3]; 2],
    boundary: [Vec<f32>; 3],
}

/// The engine's reusable buffers: one [`BandScratch`] per band.
#[derive(Debug, Clone)]
pub(crate) struct Workspace {
    band_rows: usize,
    bands: Vec<BandScratch>,
}

impl Workspace {
    pub fn new(cols: usize, rows: usize, band_rows: usize) -> Self {
        let band_rows = band_rows.max(1);
        let len = cols + 2 * LANES + 1;
        let row = || [vec![0.0; len], vec![0.0; len], vec![0.0; len]];
        let bands = (0..rows.div_ceil(band_rows))
            .map(|_| BandScratch { ring: [row(), row()], boundary: row() })
            .collect();
        Self { band_rows, bands }
    }

    pub fn band_rows(&self) -> usize {
        self.band_rows
    }
}

/// Everything a band reads: front buffers and tables, shared by all tasks.
struct Inputs<'a> {
    cols: usize,
    rows: usize,
    pos: [&'a [f32]; 3],
    vel: [&'a [f32]; 3],
    inv_mass: &'a [f32],
    viscosity: &'a [f32],
    ext: Option<[&'a [f32]; 3]>,
    springs: &'a Springs,
    cfg: StepConfig,
    /// Lane mask of the last chunk of a row (columns past the row are off).
    tail: Lane,
}

/// The back-buffer rows one task may write: rows `first_row ..` of x, y, z, vx, vy, vz.
struct Rows<'a> {
    first_row: usize,
    cols: usize,
    out: [&'a mut [f32]; 6],
}

impl<'a> Rows<'a> {
    /// Splits off rows `[first_row, row)`; `row` is clamped to the rows held.
    fn split_at_row(self, row: usize) -> (Rows<'a>, Rows<'a>) {
        let held = self.out[0].len() / self.cols;
        let at = (row.saturating_sub(self.first_row)).min(held) * self.cols;
        let [a, b, c, d, e, f] = self.out.map(|s| s.split_at_mut(at));
        let head = Rows { first_row: self.first_row, cols: self.cols, out: [a.0, b.0, c.0, d.0, e.0, f.0] };
        let tail = Rows {
            first_row: self.first_row + at / self.cols,
            cols: self.cols,
            out: [a.1, b.1, c.1, d.1, e.1, f.1],
        };
        (head, tail)
    }
}

/// One engine step from the front into the back buffers. Returns the first non-finite
/// node, if any.
pub(crate) fn step(
    state: &mut State,
    springs: &Springs,
    ws: &mut Workspace,
    cfg: StepConfig,
) -> Result<(), usize> {
    let grid = state.grid;
    let (cols, rows, n) = (grid.cols, grid.rows, grid.len());
    let tail_count = cols - (cols - 1) / LANES * LANES;
    let inp = Inputs {
        cols,
        rows,
        pos: [&state.pos[0], &state.pos[1], &state.pos[2]],
        vel: [&state.vel[0], &state.vel[1], &state.vel[2]],
        inv_mass: &state.inv_mass,
        viscosity: &state.viscosity,
        ext: state.ext_pending.then(|| [&state.ext[0][..], &state.ext[1][..], &state.ext[2][..]]),
        springs,
        cfg,
        tail: first_lanes(tail_count),
    };
    let [px, py, pz] = &mut state.next_pos;
    let [vx, vy, vz] = &mut state.next_vel;
    let all = [&mut px[..n], &mut py[..n], &mut pz[..n], &mut vx[..n], &mut vy[..n], &mut vz[..n]];
    let h = ws.band_rows;

    // Colour 0: even bands, each with the odd band below it (whose rows it does not write
    // except through the parked buffer).
    let rows_all = Rows { first_row: 0, cols, out: all };
    let bad_even = for_each_pair(&mut ws.bands, 0, rows_all, h, &|b, pair, rows| {
        even_band(&inp, b, h, pair, rows)
    });

    // Colour 1: odd bands, each with the even band below it (whose first row it finishes).
    let [px, py, pz] = &mut state.next_pos;
    let [vx, vy, vz] = &mut state.next_vel;
    let all = [&mut px[..n], &mut py[..n], &mut pz[..n], &mut vx[..n], &mut vy[..n], &mut vz[..n]];
    let (_, rows_odd) = Rows { first_row: 0, cols, out: all }.split_at_row(h);
    let bad_odd = if ws.bands.len() > 1 {
        for_each_pair(&mut ws.bands[1..], 1, rows_odd, h, &|b, pair, rows| {
            odd_band(&inp, b, h, pair, rows)
        })
    } else {
        None
    };
    match (bad_even, bad_odd) {
        (None, None) => Ok(()),
        (a, b) => Err(a.unwrap_or(usize::MAX).min(b.unwrap_or(usize::MAX))),
    }
}

/// Runs `f` on consecutive pairs of bands (`bands[0..2]`, `bands[2..4]`, …), each with
/// the rows of its pair, splitting recursively with `rayon::join` (sequentially without
/// the `parallel` feature). Returns the smallest non-finite node reported.
fn for_each_pair<F>(
    bands: &mut [BandScratch],
    first_band: usize,
    rows: Rows<'_>,
    band_rows: usize,
    f: &F,
) -> Option<usize>
where
    F: Fn(usize, &mut [BandScratch], Rows<'_>) -> Option<usize> + Sync,
{
    if bands.len() <= 2 {
        return f(first_band, bands, rows);
    }
    let left_pairs = bands.len().div_ceil(2) / 2;
    let (bl, br) = bands.split_at_mut(2 * left_pairs);
    let (rl, rr) = rows.split_at_row((first_band + 2 * left_pairs) * band_rows);
    let (a, b) = join(
        || for_each_pair(bl, first_band, rl, band_rows, f),
        || for_each_pair(br, first_band + 2 * left_pairs, rr, band_rows, f),
    );
    match (a, b) {
        (Some(a), Some(b)) => Some(a.min(b)),
        (a, b) => a.or(b),
    }
}

#[cfg(feature = "parallel")]
fn join<A: Send, B: Send>(a: impl FnOnce() -> A + Send, b: impl FnOnce() -> B + Send) -> (A, B) {
    rayon::join(a, b)
}

#[cfg(not(feature = "parallel"))]
fn join<A, B>(a: impl FnOnce() -> A, b: impl FnOnce() -> B) -> (A, B) {
    (a(), b())
}

/// Colour 0: band `b` (even). `pair[0]` is its scratch, `pair.get(1)` the odd band below.
fn even_band(inp: &Inputs, b: usize, h: usize, pair: &mut [BandScratch], mut rows: Rows) -> Option<usize> {
    let (own, below) = pair.split_first_mut().expect("a pair holds its own band");
    let r0 = b * h;
    let r1 = ((b + 1) * h).min(inp.rows);
    let [cur, next] = &mut own.ring;
    let (mut cur, mut next) = (cur, next);
    zero(cur);
    let mut bad = None;
    for r in r0..r1 {
        zero(next);
        row_springs(inp, r, cur, next);
        if r == r0 && b > 0 {
            copy(&mut own.boundary, cur);
        } else {
            bad = bad.or(integrate_row(inp, r, cur, &mut rows));
        }
        std::mem::swap(&mut cur, &mut next);
    }
    if let Some(odd) = below.first_mut() {
        copy(&mut odd.boundary, cur);
    }
    bad
}

/// Colour 1: band `b` (odd). `pair[0]` is its scratch, `pair.get(1)` the even band below.
fn odd_band(inp: &Inputs, b: usize, h: usize, pair: &mut [BandScratch], mut rows: Rows) -> Option<usize> {
    let (own, below) = pair.split_first_mut().expect("a pair holds its own band");
    let r0 = b * h;
    let r1 = ((b + 1) * h).min(inp.rows);
    let [cur, next] = &mut own.ring;
    let (mut cur, mut next) = (cur, next);
    copy(cur, &own.boundary);
    let mut bad = None;
    for r in r0..r1 {
        zero(next);
        row_springs(inp, r, cur, next);
        bad = bad.or(integrate_row(inp, r, cur, &mut rows));
        std::mem::swap(&mut cur, &mut next);
    }
    if let Some(even) = below.first() {
        for (acc, parked) in cur.iter_mut().zip(&even.boundary) {
            for (a, p) in acc.iter_mut().zip(parked) {
                *a += *p;
            }
        }
        bad = bad.or(integrate_row(inp, r1, cur, &mut rows));
    }
    bad
}

fn zero(acc: &mut [Vec<f32>; 3]) {
    for c in acc {
        c.fill(0.0);
    }
}

fn copy(dst: &mut [Vec<f32>; 3], src: &[Vec<f32>; 3]) {
    for (d, s) in dst.iter_mut().zip(src) {
        d.copy_from_slice(s);
    }
}

/// Force on the `i` lanes from springs `i → j`: `c (L − L0) d / L`, zero where `L = 0`.
#[inline(always)]
fn spring_force(pi: [Lane; 3], pj: [Lane; 3], coef: Lane, rest: Lane) -> [Lane; 3] {
    let d = [pj[0] - pi[0], pj[1] - pi[1], pj[2] - pi[2]];
    let l2 = d[0] * d[0] + d[1] * d[1] + d[2] * d[2];
    let l = l2.sqrt();
    let s = l2.simd_gt(Lane::ZERO).select(coef * (l - rest) / l, Lane::ZERO);
    [s * d[0], s * d[1], s * d[2]]
}

#[inline(always)]
fn load3(s: [&[f32]; 3], at: usize) -> [Lane; 3] {
    [load(s[0], at), load(s[1], at), load(s[2], at)]
}

/// Adds the forces of row `r`'s springs: E into `cur`, and S, SE, SW into `cur` (origin)
/// and `next` (the other end, in row r+1).
#[inline(always)]
fn row_springs(inp: &Inputs, r: usize, cur: &mut [Vec<f32>; 3], next: &mut [Vec<f32>; 3]) {
    let cols = inp.cols;
    let base = r * cols;
    let down = base + cols;
    let has_down = r + 1 < inp.rows;
    let sp = inp.springs;
    for c0 in (0..cols).step_by(LANES) {
        let i = base + c0;
        let live = if c0 + LANES > cols { inp.tail } else { first_lanes(LANES) };
        let coef = |fam: usize| load(&sp.coef[fam], i) & live;
        let rest = |fam: usize| load(&sp.rest[fam], i);
        let pi = load3(inp.pos, i);
        let a = LEAD + c0;

        let f = spring_force(pi, load3(inp.pos, i + 1), coef(0), rest(0));
        for k in 0..3 {
            add_to(&mut cur[k], a, f[k]);
            sub_from(&mut cur[k], a + 1, f[k]);
        }
        if !has_down {
            continue;
        }
        let j = down + c0;
        let f = spring_force(pi, load3(inp.pos, j), coef(1), rest(1));
        for k in 0..3 {
            add_to(&mut cur[k], a, f[k]);
            sub_from(&mut next[k], a, f[k]);
        }
        let f = spring_force(pi, load3(inp.pos, j + 1), coef(2), rest(2));
        for k in 0..3 {
            add_to(&mut cur[k], a, f[k]);
            sub_from(&mut next[k], a + 1, f[k]);
        }
        let f = spring_force(pi, load3(inp.pos, j - 1), coef(3), rest(3));
        for k in 0..3 {
            add_to(&mut cur[k], a, f[k]);
            sub_from(&mut next[k], a - 1, f[k]);
        }
    }
}

/// Symplectic Euler for row `r` with spring forces `acc`, into the back buffers.
/// Returns the first node whose new state is not finite.
#[inline(always)]
fn integrate_row(inp: &Inputs, r: usize, acc: &[Vec<f32>; 3], rows: &mut Rows) -> Option<usize> {
    let cols = inp.cols;
    let base = r * cols;
    let out_base = (r - rows.first_row) * cols;
    let dt = Lane::splat(inp.cfg.dt);
    let g = inp.cfg.accel.map(Lane::splat);
    let mut finite = first_lanes(LANES);
    for c0 in (0..cols).step_by(LANES) {
        let i = base + c0;
        let count = (cols - c0).min(LANES);
        let inv_mass = load(inp.inv_mass, i);
        let viscosity = load(inp.viscosity, i);
        let free = inv_mass.simd_gt(Lane::ZERO);
        for k in 0..3 {
            let mut force = load(&acc[k], LEAD + c0);
            if let Some(ext) = inp.ext {
                force += load(ext[k], i);
            }
            let v = load(inp.vel[k], i);
            let x = load(inp.pos[k], i);
            let a = (force - viscosity * v) * inv_mass + free.select(g[k], Lane::ZERO);
            let v1 = v + a * dt;
            let x1 = x + v1 * dt;
            let live = if count < LANES { inp.tail } else { first_lanes(LANES) };
            finite &= (x1.is_finite() & v1.is_finite()) | !live;
            store_first(rows.out[k], out_base + c0, x1, count);
            store_first(rows.out[3 + k], out_base + c0, v1, count);
        }
    }
    if finite.all() {
        return None;
    }
    (0..cols).find_map(|c| {
        let o = out_base + c;
        (0..6).any(|k| !rows.out[k][o].is_finite()).then_some(base + c)
    })
}
