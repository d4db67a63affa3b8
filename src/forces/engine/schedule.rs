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
//! Bands of one colour write disjoint rows, so each task takes `&mut` slices of its own
//! rows of the back buffer and of its own handoff slots ([`Disjoint`]): band `b` owns the
//! back-buffer rows `cut(b, levels) .. cut(b + 1, levels)` (cuts never decrease, so no two
//! bands share a row) and, if it is even, the handoff slots `b` and `b + 1` (the next even
//! band's are `b + 2` and `b + 3`); [`Claims`] run each band at most once. No atomics on the
//! state, no locks. Each colour's bands are one batch of independent tasks for a
//! [`Runner`]: rayon's pool, or the host's job system ([`crate::JobSystem`]). A step
//! allocates nothing: handoffs live in the [`Workspace`], and each worker thread keeps its
//! rings from pass to pass ([`take_scratch`]).
//!
//! Within a band, a pass is a wavefront over rows and levels ([`band`]): as soon as row
//! `r` of level `l−1` exists, row `r−1` of level `l` can be integrated, because a row only
//! needs the rows beside it.

use super::row::{advance_row, down_springs, Inputs, Level, RowOut};
use super::scratch::{put_scratch, take_scratch, Scratch};
use super::{Handoff, StepConfig, Workspace, MAX_PASS_STEPS, STREAM_MIN_NODES};
use crate::jobs::{Disjoint, Runner};
use crate::simd::{Task, Vector};
use crate::springs::{Springs, Tiling};
use crate::state::{State, Xyz};
use std::ops::Range;
use std::sync::atomic::{AtomicBool, Ordering};

/// The back-buffer rows one task may write: rows `first_row ..` of x, y, z, vx, vy, vz.
struct Rows<'a> {
    first_row: usize,
    cols: usize,
    out: [&'a mut [f32]; 6],
}

impl Rows<'_> {
    /// Row `r` (held by this task), for [`advance_row`] to write.
    #[inline(always)]
    fn row(&mut self, r: usize) -> [&mut [f32]; 6] {
        let at = (r - self.first_row) * self.cols;
        let row = at..at + self.cols;
        // Written out: a closure passed to `array::map` is compiled on its own (a call per
        // row).
        let [x, y, z, vx, vy, vz] = &mut self.out;
        [
            &mut x[row.clone()],
            &mut y[row.clone()],
            &mut z[row.clone()],
            &mut vx[row.clone()],
            &mut vy[row.clone()],
            &mut vz[row],
        ]
    }
}

/// The back buffers (`next_pos`, `next_vel`), for the tasks to take their bands' rows of.
struct BackRows<'a> {
    cols: usize,
    out: [Disjoint<'a, f32>; 6],
}

impl<'a> BackRows<'a> {
    fn new(pos: &'a mut Xyz, vel: &'a mut Xyz, cols: usize, n: usize) -> Self {
        let [px, py, pz] = pos;
        let [vx, vy, vz] = vel;
        let out = [px, py, pz, vx, vy, vz].map(|b| Disjoint::new(&mut b[..n]));
        Self { cols, out }
    }

    /// The rows `rows` of every buffer.
    ///
    /// # Safety
    ///
    /// No other task may hold rows overlapping `rows` at the same time.
    unsafe fn rows(&self, rows: Range<usize>) -> Rows<'a> {
        let cols = self.cols;
        let span = rows.start * cols..rows.end * cols;
        Rows {
            first_row: rows.start,
            cols,
            // SAFETY: the caller holds these rows alone.
            out: self.out.each_ref().map(|d| unsafe { d.part(span.clone()) }),
        }
    }
}

/// One flag per band of a colour: a band runs only if it is the first to claim its flag.
/// That keeps each band's rows and handoff slots with one task even if a job system
/// calls a task twice, and tells whether every band ran.
pub(super) struct Claims(Vec<AtomicBool>);

impl Claims {
    pub fn new(bands: usize) -> Self {
        Self((0..bands).map(|_| AtomicBool::new(false)).collect())
    }

    fn reset(&mut self) {
        self.0.iter_mut().for_each(|c| *c.get_mut() = false);
    }

    /// Whether band `b` is still free (it is then claimed).
    fn claim(&self, b: usize) -> bool {
        self.0
            .get(b)
            .is_some_and(|c| !c.swap(true, Ordering::AcqRel))
    }

    /// Whether every band of `colour` has been claimed.
    fn all(&mut self, colour: usize) -> bool {
        self.0
            .iter_mut()
            .skip(colour)
            .step_by(2)
            .all(|c| *c.get_mut())
    }
}

/// How a pass ended.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub(crate) enum PassEnd {
    /// Every new value is finite: the back buffers hold the state after the pass.
    Done,
    /// Some new value, at some level, is not finite.
    NonFinite,
    /// The job system returned without running every band.
    Incomplete,
}

/// One engine pass of `levels` steps (`1..=MAX_PASS_STEPS`) from the front into the back
/// buffers with vector type `V`, each colour's bands run by `runner`.
pub(super) fn pass_with<V: Vector>(
    state: &mut State,
    springs: &Springs,
    ws: &mut Workspace,
    cfg: StepConfig,
    levels: usize,
    runner: Runner<'_>,
) -> PassEnd {
    debug_assert!((1..=MAX_PASS_STEPS).contains(&levels));
    let grid = state.grid;
    let (cols, rows, n) = (grid.cols, grid.rows, grid.node_count());
    let (t, handoffs, claims) = ws.prepare::<V>(cols, rows, levels, runner.workers());
    // Rows without forces skip them, which relies on an acceleration that is never −0.
    debug_assert!(cfg.accel.iter().all(|a| a.to_bits() != (-0.0f32).to_bits()));
    let listed = state.ext_pending && state.mark_ext_rows();
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
        listed.then_some(&state.ext_rows[..]),
        springs,
        cfg,
        n >= STREAM_MIN_NODES,
    );
    let bands = t.bands();
    let back = BackRows::new(&mut state.next_pos, &mut state.next_vel, cols, n);
    // SAFETY (both colours): a band takes only its own rows at the last level, and each
    // band runs at most once per colour (`Claims`); cuts never decrease, so the rows of
    // two bands never overlap.
    debug_assert!((0..bands).all(|b| t.cut(b, levels) <= t.cut(b + 1, levels)));

    // Colour 0: even bands, each writing the handoff slots on both of its cuts.
    let slots = Disjoint::new(&mut handoffs[..]);
    let even_ok = run_colour(runner, claims, bands, 0, &|b| {
        // SAFETY: see above.
        let mut rows = unsafe { back.rows(t.rows_at(b, levels)) };
        // SAFETY: slots `b` and `b + 1` belong to even band `b` alone (the next even band's
        // are `b + 2` and `b + 3`), and `b` runs once.
        let mine = unsafe { slots.part(b.min(slots.len())..(b + 2).min(slots.len())) };
        let mut mine = mine.iter_mut();
        let above = mine.next().filter(|_| b > 0);
        let below = mine.next();
        band(&inp, &t, b, Handoffs::Give(above, below), &mut rows)
    });
    let Some(even_ok) = even_ok else {
        return PassEnd::Incomplete;
    };

    // Colour 1: odd bands, reading what the even bands handed over.
    let handoffs = &handoffs[..];
    let odd_ok = run_colour(runner, claims, bands, 1, &|b| {
        // SAFETY: see above.
        let mut rows = unsafe { back.rows(t.rows_at(b, levels)) };
        let take = |s: usize| handoffs.get(s).filter(|_| s < bands);
        band(&inp, &t, b, Handoffs::Take(take(b), take(b + 1)), &mut rows)
    });
    match odd_ok {
        None => PassEnd::Incomplete,
        Some(true) if even_ok => PassEnd::Done,
        Some(_) => PassEnd::NonFinite,
    }
}

/// Runs `f` on the bands of `colour` (`colour, colour + 2, …`) through `runner`, each at
/// most once. Returns whether every band returned `true`, or `None` if some band did not
/// run.
fn run_colour(
    runner: Runner<'_>,
    claims: &mut Claims,
    bands: usize,
    colour: usize,
    f: &(dyn Fn(usize) -> bool + Sync),
) -> Option<bool> {
    let count = bands.saturating_sub(colour).div_ceil(2);
    claims.reset();
    let ok = AtomicBool::new(true);
    let shared: &Claims = claims;
    runner.run(count, &|i| {
        let b = colour + 2 * i;
        if b < bands && shared.claim(b) && !f(b) {
            ok.store(false, Ordering::Relaxed);
        }
    });
    claims.all(colour).then(|| ok.into_inner())
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
///
/// The whole band runs inside the SIMD level's instruction set ([`Vector::enter`]), and
/// nothing in its loop is a closure; each row's kernel is an entry of its own.
fn band<V: Vector>(
    inp: &Inputs<V>,
    t: &Tiling,
    b: usize,
    handoffs: Handoffs<V>,
    rows: &mut Rows,
) -> bool {
    V::enter(Band {
        inp,
        t,
        b,
        handoffs,
        rows,
    })
}

/// [`band`]'s work, run inside the level's instruction set.
struct Band<'a, 'b, 'c, V: Vector> {
    inp: &'a Inputs<'b, V>,
    t: &'a Tiling,
    b: usize,
    handoffs: Handoffs<'a, V>,
    rows: &'a mut Rows<'c>,
}

impl<V: Vector> Task<V> for Band<'_, '_, '_, V> {
    type Output = bool;

    #[inline(always)]
    fn run(self) -> bool {
        let Band {
            inp,
            t,
            b,
            mut handoffs,
            rows,
        } = self;
        let last = t.levels;
        let odd = matches!(handoffs, Handoffs::Take(..));
        // Per level `l` (1..=last): the band's own rows, and the rows it handles — its
        // own, the row above them, and for an odd band below the last level the two rows
        // beyond each cut that the next level borrows.
        const NONE: Range<usize> = 0..0;
        let mut own = [NONE; MAX_PASS_STEPS + 1];
        let mut handled = [NONE; MAX_PASS_STEPS + 1];
        let (mut first_time, mut end_time) = (usize::MAX, 0);
        for l in 1..=last {
            own[l] = t.rows_at(b, l);
            let borrows = odd && l < last;
            let above = if borrows { 2 } else { 1 };
            let below = if borrows && own[l].end < inp.rows {
                2
            } else {
                0
            };
            handled[l] = own[l].start.saturating_sub(above)..(own[l].end + below).min(inp.rows);
            if !handled[l].is_empty() {
                first_time = first_time.min(handled[l].start + l - 1);
                end_time = end_time.max(handled[l].end + l - 1);
            }
        }
        if first_time >= end_time {
            // Nothing to handle: only a grid without rows tiles that way.
            return true;
        }
        let mut scratch = take_scratch::<V>(inp.cols, last);
        let Scratch {
            rings, prev, cur, ..
        } = &mut *scratch;
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
                if !handled[l].contains(&r) {
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
                            let from = match (r < own_l.start, above, below) {
                                (true, Some(h), _) => Some(&h[l - 1][r + 2 - own_l.start]),
                                (false, _, Some(h)) => Some(&h[l - 1][r - own_l.end]),
                                _ => None,
                            };
                            if let Some(from) = from {
                                upper[0][r % 2].copy_from(from);
                            }
                        }
                    }
                    continue;
                }
                let dst = if l == last {
                    RowOut::Back(rows.row(r))
                } else {
                    RowOut::Ring(&mut upper[0][r % 2])
                };
                ok &= advance_row(inp, r, from, &prev[l], cur, dst);
                std::mem::swap(cur, &mut prev[l]);
                if let Handoffs::Give(above, below) = &mut handoffs {
                    if l < last {
                        let row = &upper[0][r % 2];
                        if let Some(h) = above {
                            if r < own_l.start + 2 {
                                h[l - 1][r - own_l.start].copy_from(row);
                            }
                        }
                        if let Some(h) = below {
                            if r + 2 >= own_l.end {
                                h[l - 1][r + 2 - own_l.end].copy_from(row);
                            }
                        }
                    }
                }
            }
        }
        put_scratch(scratch);
        if inp.stream {
            // The streamed rows must be visible before the pass ends and other threads
            // read them.
            V::fence();
        }
        ok
    }
}
