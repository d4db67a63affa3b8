//! The schedule: which band integrates which rows at which layer, in which colour, on
//! which thread.
//!
//! Which band integrates which row at which layer is [`Tiling`]: the cut between two
//! bands leans one row per layer into the even band. Colour 0 (even bands) runs first, in
//! parallel: each needs only its own rows. It also hands over, at each layer below the
//! last, its first two and last two rows ([`super::Handoff`]). Colour 1 (odd bands) runs
//! second, in parallel: it reads those rows wherever it needs a row at a layer that it
//! did not integrate itself.
//!
//! Bands of one colour write disjoint rows, so each task takes `&mut` slices of its own
//! rows of the back buffer and of its own handoff slots, claimed from [`Bands`] (the
//! engine's access module, which states why no two tasks hold the same value). No
//! atomics on the state, no locks. Each colour's bands are one batch of independent tasks
//! for a [`Runner`]: rayon's pool, or the host's job system ([`crate::JobSystem`]). A
//! step allocates nothing: handoffs live in the [`Workspace`], and each worker thread
//! keeps its rings from pass to pass ([`take_scratch`]).
//!
//! Within a band, a pass is a wavefront over rows and layers ([`band`]): as soon as row
//! `r` of layer `l−1` exists, row `r−1` of layer `l` can be integrated, because a row only
//! needs the rows beside it.

use super::access::{Bands, Handoffs, Rows};
use super::row::{advance_row, down_springs, Inputs, Layer, RowOut};
use super::scratch::{put_scratch, take_scratch, Scratch};
use super::tiling::Tiling;
use super::{StepConfig, Workspace, MAX_PASS_STEPS, STREAM_MIN_NODES};
use crate::jobs::Runner;
use crate::simd::{Task, Vector};
use crate::springs::Springs;
use crate::state::State;
use std::ops::Range;
use std::sync::atomic::{AtomicBool, Ordering};

/// How a pass ended.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub(crate) enum PassEnd {
    /// Every new value is finite: the back buffers hold the state after the pass.
    Done,
    /// Some new value, at some layer, is not finite.
    NonFinite,
    /// The job system returned without running every band.
    Incomplete,
}

/// One engine pass of `layers` steps (`1..=MAX_PASS_STEPS`) from the front into the back
/// buffers with vector type `V`, each colour's bands run by `runner`.
pub(super) fn pass_with<V: Vector>(
    state: &mut State,
    springs: &Springs,
    ws: &mut Workspace,
    cfg: StepConfig,
    layers: usize,
    runner: Runner<'_>,
) -> PassEnd {
    debug_assert!((1..=MAX_PASS_STEPS).contains(&layers));
    let grid = state.grid;
    let (cols, rows, n) = (grid.cols, grid.rows, grid.node_count());
    let (t, handoffs, claims) = ws.prepare::<V>(cols, rows, layers, runner.workers());
    // Rows without forces skip them, which relies on an acceleration that is never −0.
    debug_assert!(cfg.accel.iter().all(|a| a.to_bits() != (-0.0f32).to_bits()));
    let (ext, ext_rows) = state.ext.for_step(cols, rows);
    let inp = Inputs::<V>::new(
        cols,
        rows,
        [&state.pos[0], &state.pos[1], &state.pos[2]],
        [&state.vel[0], &state.vel[1], &state.vel[2]],
        &state.inv_mass,
        &state.viscosity,
        ext,
        ext_rows,
        springs,
        cfg,
        n >= STREAM_MIN_NODES,
    );
    let mut parts = Bands::new(
        t,
        cols,
        &mut state.next_pos,
        &mut state.next_vel,
        handoffs,
        claims,
    );
    // Colour 0 (even bands) writes the handoff slots on both of its cuts; colour 1 (odd
    // bands) reads them.
    let Some(even_ok) = run_colour(runner, &mut parts, 0, &inp, &t) else {
        return PassEnd::Incomplete;
    };
    match run_colour(runner, &mut parts, 1, &inp, &t) {
        None => PassEnd::Incomplete,
        Some(true) if even_ok => PassEnd::Done,
        Some(_) => PassEnd::NonFinite,
    }
}

/// Runs the bands of `colour` (`colour, colour + 2, …`) through `runner`, each at most
/// once. Returns whether every band's new values are finite, or `None` if some band did
/// not run.
fn run_colour<V: Vector>(
    runner: Runner<'_>,
    parts: &mut Bands<V>,
    colour: usize,
    inp: &Inputs<V>,
    t: &Tiling,
) -> Option<bool> {
    let colour = parts.colour(colour);
    let ok = AtomicBool::new(true);
    runner.run(colour.tasks(), &|i| {
        if let Some(mut own) = colour.claim(i) {
            if !band(inp, t, own.band, own.handoffs, &mut own.rows) {
                ok.store(false, Ordering::Relaxed);
            }
        }
    });
    colour.all_claimed().then(|| ok.into_inner())
}

/// Band `b`'s part of a pass: a wavefront over rows and layers. Layer `l` handles row `r`
/// at time `r + l − 1`, after layer `l−1` has produced rows `r` and `r+1` (earlier in the
/// same time, or before). Handling a row means, in order: taking it from a handoff if it
/// is a row of another band that the next layer needs (odd bands); evaluating its springs
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
        let last = t.layers;
        let odd = matches!(handoffs, Handoffs::Take(..));
        // Per layer `l` (1..=last): the band's own rows, and the rows it handles — its
        // own, the row above them, and for an odd band below the last layer the two rows
        // beyond each cut that the next layer borrows.
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
                // The rows of layer `l − 1`.
                let from = if l == 1 {
                    Layer::Front
                } else {
                    Layer::Ring(&lower[l - 1])
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
