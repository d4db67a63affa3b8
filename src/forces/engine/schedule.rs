//! The schedule: which band integrates which rows at which level, in which colour, on
//! which thread.
//!
//! Which band integrates which row at which level is [`Tiling`]: the cut between two
//! bands leans one row per level into the even band. Colour 0 (even bands) runs first, in
//! parallel: each needs only its own rows. It also hands over, at each level below the
//! last, its first two and last two rows ([`Handoff`]). Colour 1 (odd bands) runs second,
//! in parallel: it reads those rows wherever it needs a row at a level that it did not
//! integrate itself.
//!
//! Bands of one colour write disjoint rows, so each task gets `&mut` slices of its own
//! rows of the back buffer and of its own handoff slots (split with `split_at_mut`: no
//! atomics, no locks). A step allocates nothing: handoffs live in the [`Workspace`], and
//! each worker thread keeps its rings from pass to pass ([`with_scratch`]).
//!
//! Within a band, a pass is a wavefront over rows and levels ([`band`]): as soon as row
//! `r` of level `l−1` exists, row `r−1` of level `l` can be integrated, because a row only
//! needs the rows beside it.

use super::row::{advance_row, down_springs, Inputs, Level, RowOut};
use super::scratch::{with_scratch, Scratch};
use super::{Handoff, StepConfig, Workspace, MAX_PASS_STEPS, STREAM_MIN_NODES};
use crate::simd::Vector;
use crate::springs::{Springs, Tiling};
use crate::state::{State, Xyz};
use std::ops::Range;

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

    /// Row `r` (held by this task), for [`advance_row`] to write.
    fn row(&mut self, r: usize) -> [&mut [f32]; 6] {
        let at = (r - self.first_row) * self.cols;
        let cols = self.cols;
        self.out.each_mut().map(|s| &mut s[at..at + cols])
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

/// One engine pass of `levels` steps (`1..=MAX_PASS_STEPS`) from the front into the back
/// buffers with vector type `V`. Returns `false` if any new value, at any level, is not
/// finite.
pub(super) fn pass_with<V: Vector>(
    state: &mut State,
    springs: &Springs,
    ws: &mut Workspace,
    cfg: StepConfig,
    levels: usize,
) -> bool {
    debug_assert!((1..=MAX_PASS_STEPS).contains(&levels));
    let grid = state.grid;
    let (cols, rows, n) = (grid.cols, grid.rows, grid.len());
    let (t, handoffs) = ws.prepare::<V>(cols, rows, levels);
    let inp = Inputs::<V>::new(
        cols,
        rows,
        [&state.pos[0], &state.pos[1], &state.pos[2]],
        [&state.vel[0], &state.vel[1], &state.vel[2]],
        &state.inv_mass,
        &state.viscosity,
        state
            .ext_pending
            .then(|| [&state.ext[0][..], &state.ext[1][..], &state.ext[2][..]]),
        springs,
        cfg,
        n >= STREAM_MIN_NODES,
    );
    let bands = t.bands();

    // Colour 0: even bands, each writing the handoff slots on both of its cuts.
    let ok_even = for_each_band(
        &t,
        0..bands,
        Slots {
            first: 0,
            slots: &mut handoffs[..],
        },
        back_rows(&mut state.next_pos, &mut state.next_vel, cols, n),
        &|slots: Slots<V>, b| slots.split(b),
        &|b, slots: Slots<V>, mut rows| {
            let (above, below) = slots.of_band(b);
            band(&inp, &t, b, Handoffs::Give(above, below), &mut rows)
        },
    );

    // Colour 1: odd bands, reading what the even bands handed over.
    let handoffs = &handoffs[..];
    let (_, from_band_1) =
        back_rows(&mut state.next_pos, &mut state.next_vel, cols, n).split_at_row(t.cut(1, levels));
    let ok_odd = for_each_band(
        &t,
        1..bands,
        (),
        from_band_1,
        &|(), _| ((), ()),
        &|b, (), mut rows| {
            let take = |s: usize| handoffs.get(s).filter(|_| s < bands);
            band(&inp, &t, b, Handoffs::Take(take(b), take(b + 1)), &mut rows)
        },
    );
    ok_even && ok_odd
}

/// Handoff slots `first ..` for the even bands of one task.
struct Slots<'a, V> {
    first: usize,
    slots: &'a mut [Handoff<V>],
}

impl<'a, V> Slots<'a, V> {
    /// Slots before band `b`'s and from it.
    fn split(self, b: usize) -> (Slots<'a, V>, Slots<'a, V>) {
        let at = (b - self.first).min(self.slots.len());
        let (l, r) = self.slots.split_at_mut(at);
        (
            Slots {
                first: self.first,
                slots: l,
            },
            Slots {
                first: self.first + at,
                slots: r,
            },
        )
    }

    /// The slots on band `b`'s two cuts (above, below), where there is a cut.
    fn of_band(self, b: usize) -> (Option<&'a mut Handoff<V>>, Option<&'a mut Handoff<V>>) {
        let mut it = self.slots[b - self.first..].iter_mut();
        let above = it.next().filter(|_| b > 0);
        (above, it.next())
    }
}

/// Runs `f` on the bands `bands.start, bands.start + 2, …` (one colour), splitting the
/// range, the shared part `s` and the back-buffer rows recursively with `rayon::join` (in
/// order without the `parallel` feature). Returns `false` if any band did.
fn for_each_band<S: Send>(
    t: &Tiling,
    bands: Range<usize>,
    s: S,
    rows: Rows<'_>,
    split: &(impl Fn(S, usize) -> (S, S) + Sync),
    f: &(impl Fn(usize, S, Rows<'_>) -> bool + Sync),
) -> bool {
    let count = bands.len().div_ceil(2);
    if count == 0 {
        return true;
    }
    if count == 1 {
        return f(bands.start, s, rows);
    }
    let mid = bands.start + 2 * (count / 2);
    let (sl, sr) = split(s, mid);
    let (rl, rr) = rows.split_at_row(t.cut(mid, t.levels));
    let (a, b) = join(
        || for_each_band(t, bands.start..mid, sl, rl, split, f),
        || for_each_band(t, mid..bands.end, sr, rr, split, f),
    );
    a && b
}

#[cfg(feature = "parallel")]
fn join<A: Send, B: Send>(a: impl FnOnce() -> A + Send, b: impl FnOnce() -> B + Send) -> (A, B) {
    rayon::join(a, b)
}

#[cfg(not(feature = "parallel"))]
fn join<A, B>(a: impl FnOnce() -> A, b: impl FnOnce() -> B) -> (A, B) {
    (a(), b())
}

/// A band's handoff slots on its two cuts (above, below): written by an even band, read
/// by an odd one.
enum Handoffs<'a, V> {
    Give(Option<&'a mut Handoff<V>>, Option<&'a mut Handoff<V>>),
    Take(Option<&'a Handoff<V>>, Option<&'a Handoff<V>>),
}

/// Band `b`'s part of a pass: a wavefront over rows and levels. Level `l` handles row `r`
/// at time `r + l − 1`, after level `l−1` has produced rows `r` and `r+1` (earlier in the
/// same time, or before). Handling a row means, in order: taking it from a handoff if it
/// is a row of another band that the next level needs (odd bands); evaluating its springs
/// if it is the row just above the band's rows (their S, SE, SW arrive at the first row);
/// or evaluating and integrating it if it is the band's own, then handing it over if it
/// is one of the two rows next to a cut (even bands).
fn band<V: Vector>(
    inp: &Inputs<V>,
    t: &Tiling,
    b: usize,
    mut handoffs: Handoffs<V>,
    rows: &mut Rows,
) -> bool {
    let last = t.levels;
    let own: [Range<usize>; MAX_PASS_STEPS + 1] =
        std::array::from_fn(|l| if l <= last { t.rows_at(b, l) } else { 0..0 });
    let odd = matches!(handoffs, Handoffs::Take(..));
    // Rows level `l` handles: its own, the row above them, and for an odd band below the
    // last level the two rows beyond each cut that the next level borrows.
    let handled = |l: usize| {
        let own = &own[l];
        let borrow = if odd && l < last { 2 } else { 1 };
        let below = if odd && l < last && own.end < inp.rows {
            2
        } else {
            0
        };
        own.start.saturating_sub(borrow)..(own.end + below).min(inp.rows)
    };
    let first_time = (1..=last).map(|l| handled(l).start + l - 1).min();
    let end_time = (1..=last).map(|l| handled(l).end + l - 1).max();
    let (Some(first_time), Some(end_time)) = (first_time, end_time) else {
        return true;
    };
    with_scratch::<V, _>(inp.cols, last, |s| {
        let Scratch {
            rings, prev, cur, ..
        } = s;
        for l in 1..=last {
            if own[l].start == 0 {
                prev[l].zero_down();
            }
        }
        let mut ok = true;
        for time in first_time..end_time {
            for l in 1..=last {
                let Some(r) = (time + 1).checked_sub(l) else {
                    continue;
                };
                if !handled(l).contains(&r) {
                    continue;
                }
                let (lower, upper) = rings.split_at_mut(l);
                // The rows of level `l − 1`.
                let from = if l == 1 {
                    Level::Front
                } else {
                    Level::Ring(&lower[l - 1])
                };
                let own_l = &own[l];
                if !own_l.contains(&r) {
                    if r + 1 == own_l.start {
                        // The row above the band: its springs arrive at the first row.
                        down_springs(inp, r, from, &mut prev[l]);
                    }
                    if let Handoffs::Take(above, below) = &handoffs {
                        if l < last {
                            let from = if r < own_l.start {
                                above.map(|h| &h[l - 1][r + 2 - own_l.start])
                            } else {
                                below.map(|h| &h[l - 1][r - own_l.end])
                            };
                            if let Some(from) = from {
                                upper[0][r % 2].copy_from(from);
                            }
                        }
                    }
                    continue;
                }
                let ext = if l == 1 { inp.ext } else { None };
                let dst = if l == last {
                    RowOut::Back(rows.row(r))
                } else {
                    RowOut::Ring(&mut upper[0][r % 2])
                };
                ok &= advance_row(inp, r, from, ext, &prev[l], cur, dst);
                std::mem::swap(cur, &mut prev[l]);
                if let Handoffs::Give(above, below) = &mut handoffs {
                    if l < last {
                        let row = &upper[0][r % 2];
                        if let Some(h) = above.as_deref_mut().filter(|_| r < own_l.start + 2) {
                            h[l - 1][r - own_l.start].copy_from(row);
                        }
                        if let Some(h) = below.as_deref_mut().filter(|_| r + 2 >= own_l.end) {
                            h[l - 1][r + 2 - own_l.end].copy_from(row);
                        }
                    }
                }
            }
        }
        if inp.stream {
            // The streamed rows must be visible before the pass ends and other threads
            // read them.
            V::fence();
        }
        ok
    })
}
