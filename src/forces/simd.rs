//! The engine step: colour-partitioned bands of rows, SIMD across columns, rayon across bands.
//!
//! # How a band streams its rows
//!
//! A band owns the springs whose origin lies in its rows (see [`crate::springs`]). For row
//! `r` it evaluates, with lanes across columns, the E springs inside the row and the S, SE
//! and SW springs down to row `r+1`, into per-family row buffers ([`RowForces`]). Row r
//! then has everything it needs — its own springs and the ones arriving from row r−1,
//! computed one row earlier — so it is summed and integrated at once while its data is
//! still in cache, and the two row buffers rotate. Spring forces never travel to main
//! memory: a step reads positions, velocities and tables once and writes the new
//! positions and velocities once.
//!
//! A node's force is the same expression as in the scalar reference
//! ([`super::scalar::node_force`]), so the two steps agree bit for bit.
//!
//! # The two colours
//!
//! Only the first row of a band needs springs from outside it (from the last row of the
//! band above). The step runs in two phases:
//!
//! 1. **Colour 0, even bands, in parallel.** Each integrates its rows except its first,
//!    whose own spring forces it parks in the band's [`RowForces`]; it also parks the
//!    forces its last row sends down, in the next (odd) band's slot.
//! 2. **Colour 1, odd bands, in parallel.** Each starts from the forces parked for it,
//!    integrates all its rows, then the first row of the even band below (from that band's
//!    parked forces and the ones it has just sent down).
//!
//! Bands of one colour touch disjoint rows, so each task gets `&mut` slices of its own rows
//! (split with `split_at_mut`: no `unsafe`, no atomics, no locks). Every node's arithmetic
//! is fixed by the expression above, not by the schedule or the band height, so results
//! are bitwise identical for any thread count and with the `parallel` feature off. A step
//! allocates nothing: parked rows live in [`Workspace`], and each worker thread keeps its
//! two rotating row buffers from step to step.

use super::StepConfig;
use crate::simd::{first_lanes, get, lanes, lanes_mut, put, Lane, LANES};
use crate::springs::Springs;
use crate::state::{State, Xyz};
use std::cell::RefCell;

/// Offset of column 0 in a row buffer: index `LEAD − 1` is a zero "column −1".
const LEAD: usize = LANES;

/// A lane mask with every lane on.
const ALL: Lane = Lane::new([f32::from_bits(u32::MAX); LANES]);

/// Spring forces of one row, by family (E, S, SE, SW) and axis, on the row's origin nodes.
/// Column `c` is at `LEAD + c`; the columns before 0 and after the row read as zero.
#[derive(Debug, Clone)]
pub(crate) struct RowForces {
    cols: usize,
    fam: [[crate::simd::Floats; 3]; 4],
}

impl RowForces {
    fn new(cols: usize) -> Self {
        let len = LEAD + crate::simd::round_up(cols) + LANES;
        Self {
            cols,
            fam: std::array::from_fn(|_| std::array::from_fn(|_| crate::simd::Floats::zeros(len))),
        }
    }

    /// Copies the forces of the families in `families` from `other`.
    fn copy_from(&mut self, other: &RowForces, families: std::ops::Range<usize>) {
        for f in families {
            for k in 0..3 {
                self.fam[f][k].copy_from_slice(&other.fam[f][k]);
            }
        }
    }

    fn zero_down(&mut self) {
        for f in 1..4 {
            for c in &mut self.fam[f] {
                c.fill(0.0);
            }
        }
    }
}

/// The engine's reusable buffers: one parked [`RowForces`] per band.
#[derive(Debug, Clone)]
pub(crate) struct Workspace {
    /// A band height fixed by the caller, or `None` to follow [`crate::springs::band_rows`].
    fixed: Option<usize>,
    band_rows: usize,
    parked: Vec<RowForces>,
}

impl Workspace {
    pub fn new(fixed: Option<usize>) -> Self {
        Self {
            fixed: fixed.map(|h| h.max(1)),
            band_rows: 0,
            parked: Vec::new(),
        }
    }

    /// The band height for this grid and the current thread count; rebuilds the parked
    /// rows when it changes (only when the thread count does).
    fn prepare(&mut self, cols: usize, rows: usize) -> usize {
        let h = self.band_rows_for(rows);
        if h != self.band_rows
            || self.parked.first().is_some_and(|p| p.cols != cols)
            || self.parked.is_empty()
        {
            self.band_rows = h;
            self.parked = (0..rows.div_ceil(h))
                .map(|_| RowForces::new(cols))
                .collect();
        }
        h
    }

    pub fn band_rows_for(&self, rows: usize) -> usize {
        self.fixed
            .unwrap_or_else(|| crate::springs::band_rows(rows, threads()))
    }
}

#[cfg(feature = "parallel")]
fn threads() -> usize {
    rayon::current_num_threads()
}

#[cfg(not(feature = "parallel"))]
fn threads() -> usize {
    1
}

thread_local! {
    /// Each worker's two rotating row buffers (previous row, current row), reused across
    /// bands and steps; reallocated only when a wider grid comes along.
    static RING: RefCell<[RowForces; 2]> = RefCell::new([RowForces::new(0), RowForces::new(0)]);
}

/// Runs `f` with this thread's row buffers sized and zeroed for `cols` columns.
fn with_ring<T>(cols: usize, f: impl FnOnce(&mut [RowForces; 2]) -> T) -> T {
    RING.with(|ring| {
        let mut ring = ring.borrow_mut();
        if ring[0].cols != cols {
            *ring = [RowForces::new(cols), RowForces::new(cols)];
        }
        ring[0].zero_down();
        f(&mut ring)
    })
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
    /// Lane masks of the springs that exist in the last chunk of a row, per family (no E
    /// or SE spring leaves the last column; columns past the row are off).
    tail: [Lane; 4],
    /// Lane mask of the SW springs that exist in the first chunk (none leaves column 0).
    head_sw: Lane,
}

impl Inputs<'_> {
    /// Which lanes of chunk `k` hold a spring of family `fam`.
    #[inline(always)]
    fn exists(&self, fam: usize, k: usize, chunks: usize) -> Lane {
        let mut m = if k + 1 == chunks { self.tail[fam] } else { ALL };
        if fam == 3 && k == 0 {
            m &= self.head_sw;
        }
        m
    }
}

/// Where a family's coefficients and rest lengths come from for one row.
#[derive(Clone, Copy)]
enum Table<'a> {
    /// Every spring of the family shares these lanes.
    Uniform(Lane, Lane),
    /// Per-spring chunk views of the coefficient and rest-length tables.
    PerSpring(&'a [[f32; LANES]], &'a [[f32; LANES]]),
}

impl Table<'_> {
    /// `(coefficient, rest length)` of chunk `k`.
    ///
    /// # Safety
    ///
    /// For `PerSpring`, `k` is below the length of both views.
    #[inline(always)]
    unsafe fn at(self, k: usize) -> (Lane, Lane) {
        match self {
            Table::Uniform(c, r) => (c, r),
            // SAFETY: the caller guarantees `k` is in range of both views.
            Table::PerSpring(c, r) => unsafe { (get(c, k), get(r, k)) },
        }
    }
}

/// The back-buffer rows one task may write: rows `first_row ..` of x, y, z, vx, vy, vz.
struct Rows<'a> {
    first_row: usize,
    cols: usize,
    out: [&'a mut [f32]; 6],
}

impl<'a> Rows<'a> {
    /// Splits at `row` (clamped to the rows held): `(rows before, rows from)`.
    fn split_at_row(self, row: usize) -> (Rows<'a>, Rows<'a>) {
        let held = self.out[0].len() / self.cols;
        let at = row.saturating_sub(self.first_row).min(held);
        let [a, b, c, d, e, f] = self.out.map(|s| s.split_at_mut(at * self.cols));
        let head = Rows {
            first_row: self.first_row,
            cols: self.cols,
            out: [a.0, b.0, c.0, d.0, e.0, f.0],
        };
        let tail = Rows {
            first_row: self.first_row + at,
            cols: self.cols,
            out: [a.1, b.1, c.1, d.1, e.1, f.1],
        };
        (head, tail)
    }
}

/// Every row of the back buffers (`next_pos`, `next_vel`), for the tasks to split.
fn back_rows<'a>(pos: &'a mut Xyz, vel: &'a mut Xyz, cols: usize, n: usize) -> Rows<'a> {
    let [px, py, pz] = pos;
    let [vx, vy, vz] = vel;
    let out = [px, py, pz, vx, vy, vz].map(|b| &mut b[..n]);
    Rows {
        first_row: 0,
        cols,
        out,
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
    let inp = Inputs {
        cols,
        rows,
        pos: [&state.pos[0], &state.pos[1], &state.pos[2]],
        vel: [&state.vel[0], &state.vel[1], &state.vel[2]],
        inv_mass: &state.inv_mass,
        viscosity: &state.viscosity,
        ext: state
            .ext_pending
            .then(|| [&state.ext[0][..], &state.ext[1][..], &state.ext[2][..]]),
        springs,
        cfg,
        tail: {
            let last = cols - (cols - 1) / LANES * LANES; // columns in the last chunk
            let [all, short] = [first_lanes(last), first_lanes(last - 1)];
            [short, all, short, all]
        },
        head_sw: !first_lanes(1),
    };
    let h = ws.prepare(cols, rows);

    // Colour 0: even bands, each paired with the odd band below it.
    let bad_even = for_each_pair(
        &mut ws.parked,
        0,
        back_rows(&mut state.next_pos, &mut state.next_vel, cols, n),
        h,
        &|b, pair, rows| even_band(&inp, b, h, pair, rows),
    );

    // Colour 1: odd bands, each paired with the even band below it.
    let (_, from_band_1) =
        back_rows(&mut state.next_pos, &mut state.next_vel, cols, n).split_at_row(h);
    let bad_odd = match ws.parked.get_mut(1..) {
        Some(odd) if !odd.is_empty() => for_each_pair(odd, 1, from_band_1, h, &|b, pair, rows| {
            odd_band(&inp, b, h, pair, rows)
        }),
        _ => None,
    };
    match (bad_even, bad_odd) {
        (None, None) => Ok(()),
        (a, b) => Err(a.unwrap_or(usize::MAX).min(b.unwrap_or(usize::MAX))),
    }
}

/// Runs `f` on consecutive pairs of bands (`parked[0..2]`, `parked[2..4]`, …) with the
/// rows of each pair, splitting recursively with `rayon::join` (in order without the
/// `parallel` feature). Returns the smallest non-finite node reported.
fn for_each_pair<F>(
    parked: &mut [RowForces],
    first_band: usize,
    rows: Rows<'_>,
    band_rows: usize,
    f: &F,
) -> Option<usize>
where
    F: Fn(usize, &mut [RowForces], Rows<'_>) -> Option<usize> + Sync,
{
    if parked.len() <= 2 {
        return f(first_band, parked, rows);
    }
    let left = 2 * (parked.len().div_ceil(2) / 2);
    let (pl, pr) = parked.split_at_mut(left);
    let (rl, rr) = rows.split_at_row((first_band + left) * band_rows);
    let (a, b) = join(
        || for_each_pair(pl, first_band, rl, band_rows, f),
        || for_each_pair(pr, first_band + left, rr, band_rows, f),
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

/// Colour 0: band `b` (even). `pair[0]` is its parked row, `pair.get(1)` the odd band's.
fn even_band(
    inp: &Inputs,
    b: usize,
    h: usize,
    pair: &mut [RowForces],
    mut rows: Rows,
) -> Option<usize> {
    let r0 = b * h;
    let r1 = ((b + 1) * h).min(inp.rows);
    with_ring(inp.cols, |ring| {
        let [prev, cur] = ring;
        let (mut prev, mut cur) = (prev, cur);
        let mut bad = None;
        for r in r0..r1 {
            row_springs(inp, r, cur);
            if r == r0 && b > 0 {
                pair[0].copy_from(cur, 0..4); // finished by the odd band above
            } else {
                bad = bad.or(integrate_row(inp, r, cur, prev, &mut rows));
            }
            std::mem::swap(&mut prev, &mut cur);
        }
        if let Some(odd) = pair.get_mut(1) {
            odd.copy_from(prev, 1..4); // what the last row sends down
        }
        bad
    })
}

/// Colour 1: band `b` (odd). `pair[0]` is its parked row, `pair.get(1)` the even band's.
fn odd_band(
    inp: &Inputs,
    b: usize,
    h: usize,
    pair: &mut [RowForces],
    mut rows: Rows,
) -> Option<usize> {
    let r0 = b * h;
    let r1 = ((b + 1) * h).min(inp.rows);
    with_ring(inp.cols, |ring| {
        let [prev, cur] = ring;
        let (mut prev, mut cur) = (prev, cur);
        prev.copy_from(&pair[0], 1..4);
        let mut bad = None;
        for r in r0..r1 {
            row_springs(inp, r, cur);
            bad = bad.or(integrate_row(inp, r, cur, prev, &mut rows));
            std::mem::swap(&mut prev, &mut cur);
        }
        if let Some(even) = pair.get(1) {
            bad = bad.or(integrate_row(inp, r1, even, prev, &mut rows));
        }
        bad
    })
}

/// Force on the `i` lanes from springs `i → j`: `c (L − L0) d / L`, zero where `L = 0`.
#[inline(always)]
fn spring_force(pi: [Lane; 3], pj: [Lane; 3], coef: Lane, rest: Lane) -> [Lane; 3] {
    let d = [pj[0] - pi[0], pj[1] - pi[1], pj[2] - pi[2]];
    let l2 = d[0] * d[0] + d[1] * d[1] + d[2] * d[2];
    let l = l2.sqrt();
    let s = l2
        .simd_gt(Lane::ZERO)
        .select(coef * (l - rest) / l, Lane::ZERO);
    [s * d[0], s * d[1], s * d[2]]
}

/// Evaluates row `r`'s springs into `out`: E inside the row, S/SE/SW down to row r+1
/// (zero on the last row).
#[inline(always)]
fn row_springs(inp: &Inputs, r: usize, out: &mut RowForces) {
    let cols = inp.cols;
    let chunks = cols.div_ceil(LANES);
    let base = r * cols;
    let has_down = r + 1 < inp.rows;
    // Chunk views (see `crate::simd`): chunk k of `view(start)` holds the nodes
    // `start + k·LANES ..`, so `view(base + 1)` is the east neighbour of `view(base)`.
    let view = |start: usize| inp.pos.map(|p| lanes(p, start, chunks));
    let here = view(base);
    // (family, the view of each spring's other end)
    let families = [
        (0, view(base + 1)),
        (1, if has_down { view(base + cols) } else { here }),
        (
            2,
            if has_down {
                view(base + cols + 1)
            } else {
                here
            },
        ),
        (
            3,
            if has_down {
                view(base + cols - 1)
            } else {
                here
            },
        ),
    ];
    for (fam, there) in families {
        let mut out = out.fam[fam].each_mut().map(|c| lanes_mut(c, LEAD, chunks));
        if fam > 0 && !has_down {
            for c in &mut out {
                c.fill([0.0; LANES]);
            }
            continue;
        }
        let sp = inp.springs;
        let table = match sp.uniform(fam) {
            Some((c, r)) => Table::Uniform(Lane::splat(c), Lane::splat(r)),
            None => Table::PerSpring(
                lanes(&sp.coef[fam], base, chunks),
                lanes(&sp.rest[fam], base, chunks),
            ),
        };
        for k in 0..chunks {
            // SAFETY: every view above was made with exactly `chunks` chunks, and k < chunks.
            unsafe {
                let (coef, rest) = table.at(k);
                let mut f = spring_force(load3(here, k), load3(there, k), coef, rest);
                // Lanes without a spring (only in a row's first and last chunk) hold other
                // rows' nodes or padding; they get exactly +0, like the reference's absent
                // spring. A coefficient of 0 is not enough: `0 · ∞` is NaN once those
                // positions are far apart (the `params` fuzz target found a surface beyond
                // ~1e19 from the origin whose step the engine refused and the reference took).
                if k + 1 == chunks || (fam == 3 && k == 0) {
                    let exists = inp.exists(fam, k, chunks);
                    f = f.map(|c| exists.select(c, Lane::ZERO));
                }
                for (o, fk) in out.iter_mut().zip(f) {
                    put(o, k, fk);
                }
            }
        }
    }
}

/// Chunk `k` of three views.
///
/// # Safety
///
/// `k` is below the length of every view.
#[inline(always)]
unsafe fn load3(v: [&[[f32; LANES]]; 3], k: usize) -> [Lane; 3] {
    // SAFETY: the caller guarantees `k` is in range of every view.
    unsafe { [get(v[0], k), get(v[1], k), get(v[2], k)] }
}

/// Sums row `r`'s spring forces (`cur`: its own springs, `prev`: the ones arriving from
/// row r−1) and integrates the row into the back buffers. Returns the first node whose
/// new state is not finite.
#[inline(always)]
fn integrate_row(
    inp: &Inputs,
    r: usize,
    cur: &RowForces,
    prev: &RowForces,
    rows: &mut Rows,
) -> Option<usize> {
    let cols = inp.cols;
    let chunks = cols.div_ceil(LANES);
    let full = cols / LANES;
    let base = r * cols;
    let out_base = (r - rows.first_row) * cols;
    let node = |s| lanes(s, base, chunks);
    let (inv_mass, viscosity) = (node(inp.inv_mass), node(inp.viscosity));
    let dt = Lane::splat(inp.cfg.dt);
    let mut finite = Lane::ZERO;
    let (xs, vs) = rows.out.split_at_mut(3);
    for (axis, (x_out, v_out)) in xs.iter_mut().zip(vs.iter_mut()).enumerate() {
        let (pos, vel) = (node(inp.pos[axis]), node(inp.vel[axis]));
        let ext = inp.ext.map(|e| node(e[axis]));
        let g = Lane::splat(inp.cfg.accel[axis]);
        fn family(
            rf: &RowForces,
            fam: usize,
            axis: usize,
            start: usize,
            chunks: usize,
        ) -> &[[f32; LANES]] {
            lanes(&rf.fam[fam][axis], start, chunks)
        }
        let f = |rf, fam, start| family(rf, fam, axis, start, chunks);
        // Leaving (this row's springs at this node) and arriving (the same family's spring
        // from the west, north, north-west and north-east neighbour).
        let (e, e_w) = (f(cur, 0, LEAD), f(cur, 0, LEAD - 1));
        let (s, s_n) = (f(cur, 1, LEAD), f(prev, 1, LEAD));
        let (se, se_nw) = (f(cur, 2, LEAD), f(prev, 2, LEAD - 1));
        let (sw, sw_ne) = (f(cur, 3, LEAD), f(prev, 3, LEAD + 1));
        let (x_full, x_tail) = x_out[out_base..out_base + cols].split_at_mut(full * LANES);
        let (v_full, v_tail) = v_out[out_base..out_base + cols].split_at_mut(full * LANES);
        let (x_full, v_full) = (
            x_full.as_chunks_mut::<LANES>().0,
            v_full.as_chunks_mut::<LANES>().0,
        );
        for k in 0..chunks {
            // SAFETY: every view above was made with exactly `chunks` chunks, and k < chunks.
            let l = |v: &[[f32; LANES]]| unsafe { get(v, k) };
            // Same expression as `scalar::node_force`.
            let mut force =
                (l(e) - l(e_w)) + (l(s) - l(s_n)) + (l(se) - l(se_nw)) + (l(sw) - l(sw_ne));
            if let Some(ext) = ext {
                force += l(ext);
            }
            let inv_mass = l(inv_mass);
            let v = l(vel);
            let acc = (force - l(viscosity) * v) * inv_mass
                + inv_mass.simd_gt(Lane::ZERO).select(g, Lane::ZERO);
            let v1 = v + acc * dt;
            let x1 = l(pos) + v1 * dt;
            // Fused finiteness check: `x·0` is 0 for finite x and NaN otherwise, and x' is
            // non-finite whenever v' is. Lanes past the row hold other rows' values or zero
            // padding; a non-finite one there is reported when its own row is checked.
            finite += x1 * Lane::ZERO;
            if k < full {
                x_full[k] = x1.to_array();
                v_full[k] = v1.to_array();
            } else {
                x_tail.copy_from_slice(&x1.to_array()[..x_tail.len()]);
                v_tail.copy_from_slice(&v1.to_array()[..v_tail.len()]);
            }
        }
    }
    if !finite.is_nan().any() {
        return None;
    }
    (0..cols).find_map(|c| {
        (0..6)
            .any(|k| !rows.out[k][out_base + c].is_finite())
            .then_some(base + c)
    })
}
