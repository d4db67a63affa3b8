//! Each band's own rows of the back buffers and its own handoff slots, for the tasks that
//! run a colour's bands at once ([`super::super::schedule`]).
//!
//! # Why no two tasks hold the same value
//!
//! A pass's writable parts are one [`Bands`]: the back buffers and the handoff slots,
//! borrowed mutably for the pass, with one claim flag per band. [`Bands::colour`] opens a
//! colour, and [`Colour::claim`] hands band `b`'s parts to the first call that claims
//! `b`, and to no other:
//!
//! * **rows**: band `b` writes the rows `cut(b) .. cut(b + 1)` of the pass's last layer.
//!   [`Bands::new`] asserts that the cuts never decrease, so no two bands' rows overlap,
//!   and each part is checked to lie inside the buffers;
//! * **handoff slots**: only the even colour writes them, band `b` its slots `b` and
//!   `b + 1` (the next even band's are `b + 2` and `b + 3`). The odd colour only reads
//!   them, through a shared borrow;
//! * **claims**: a band's flag is set by its first claim and cleared only when the next
//!   colour opens. Opening a colour borrows the `Bands` mutably, and every part handed
//!   out borrows it for as long as the part lives: no part of one colour is alive when
//!   the flags are cleared or the next colour's parts are made. So a band's parts go to
//!   one task per colour even if a job system calls a task twice.
//!
//! The one `unsafe` here takes a part of a buffer ([`Disjoint::part`]) on that argument.

use super::super::Handoff;
use crate::forces::engine::tiling::Tiling;
use crate::jobs::Disjoint;
use crate::state::Xyz;
use std::sync::atomic::{AtomicBool, Ordering};

/// One flag per band: a band's parts go only to the task that claims its flag first.
/// That also tells whether every band of a colour ran.
pub(crate) struct Claims(Vec<AtomicBool>);

impl Claims {
    pub fn new(bands: usize) -> Self {
        Self((0..bands).map(|_| AtomicBool::new(false)).collect())
    }

    /// Whether band `b` is still free (it is then claimed).
    fn claim(&self, b: usize) -> bool {
        self.0
            .get(b)
            .is_some_and(|c| !c.swap(true, Ordering::AcqRel))
    }

    /// Whether band `b` has been claimed.
    fn claimed(&self, b: usize) -> bool {
        self.0.get(b).is_some_and(|c| c.load(Ordering::Acquire))
    }
}

/// The parts of a pass that its bands write: the back buffers (`next_pos`, `next_vel`)
/// and the handoff slots.
pub(crate) struct Bands<'a, V> {
    tiling: Tiling,
    cols: usize,
    back: [&'a mut [f32]; 6],
    slots: &'a mut [Handoff<V>],
    claims: &'a mut Claims,
}

impl<'a, V> Bands<'a, V> {
    /// The back buffers of a grid `cols` wide, cut by `tiling`, and the handoff slots
    /// (slot `b` holds what crosses the cut above band `b`). Panics if the tiling's cuts
    /// decrease anywhere, or if the buffers are shorter than the grid.
    pub fn new(
        tiling: Tiling,
        cols: usize,
        pos: &'a mut Xyz,
        vel: &'a mut Xyz,
        slots: &'a mut [Handoff<V>],
        claims: &'a mut Claims,
    ) -> Self {
        let cut = |b| tiling.cut(b, tiling.layers);
        assert!(
            (0..tiling.bands()).all(|b| cut(b) <= cut(b + 1)),
            "the bands of {tiling:?} overlap"
        );
        let n = tiling.rows * cols;
        let [px, py, pz] = pos;
        let [vx, vy, vz] = vel;
        Self {
            tiling,
            cols,
            back: [px, py, pz, vx, vy, vz].map(|b| &mut b[..n]),
            slots,
            claims,
        }
    }

    /// Colour `colour`'s bands (`colour, colour + 2, …`): the even colour (0) writes the
    /// handoff slots, the odd one (1) reads them.
    pub fn colour(&mut self, colour: usize) -> Colour<'_, V> {
        self.claims.0.iter_mut().for_each(|c| *c.get_mut() = false);
        let slots = if colour == 0 {
            Slots::Give(Disjoint::new(&mut *self.slots))
        } else {
            Slots::Take(&*self.slots)
        };
        let [x, y, z, vx, vy, vz] = &mut self.back;
        Colour {
            colour,
            tiling: self.tiling,
            cols: self.cols,
            back: [x, y, z, vx, vy, vz].map(|b| Disjoint::new(b)),
            slots,
            claims: &*self.claims,
        }
    }
}

/// The handoff slots as one colour sees them.
enum Slots<'s, V> {
    Give(Disjoint<'s, Handoff<V>>),
    Take(&'s [Handoff<V>]),
}

/// One colour's bands, each for the task that claims it first.
pub(crate) struct Colour<'s, V> {
    colour: usize,
    tiling: Tiling,
    cols: usize,
    back: [Disjoint<'s, f32>; 6],
    slots: Slots<'s, V>,
    claims: &'s Claims,
}

/// What [`Colour::claim`] hands a task: its band and that band's parts.
pub(crate) struct Claimed<'s, V> {
    pub band: usize,
    pub rows: Rows<'s>,
    pub handoffs: Handoffs<'s, V>,
}

impl<'s, V> Colour<'s, V> {
    /// How many tasks the colour has: task `i` runs band `colour + 2i`.
    pub fn tasks(&self) -> usize {
        self.tiling.bands().saturating_sub(self.colour).div_ceil(2)
    }

    /// Task `i`'s band and its parts, if no call claimed them before.
    pub fn claim(&self, i: usize) -> Option<Claimed<'s, V>> {
        let (b, bands) = (self.colour + 2 * i, self.tiling.bands());
        if b >= bands || !self.claims.claim(b) {
            return None;
        }
        let cols = self.cols;
        let rows = self.tiling.rows_at(b, self.tiling.layers);
        let span = rows.start * cols..rows.end * cols;
        // Written out: a closure passed to `array::map` is compiled on its own.
        let [x, y, z, vx, vy, vz] = &self.back;
        // SAFETY: band `b`'s own rows, which no other band's overlap (the cuts never
        // decrease: `Bands::new`), for the one call that claimed `b`.
        let out = unsafe {
            [
                x.part(span.clone()),
                y.part(span.clone()),
                z.part(span.clone()),
                vx.part(span.clone()),
                vy.part(span.clone()),
                vz.part(span),
            ]
        };
        let handoffs = match &self.slots {
            Slots::Give(slots) => {
                let mine = b.min(slots.len())..(b + 2).min(slots.len());
                // SAFETY: slots `b` and `b + 1` of even band `b` (the next even band's
                // are `b + 2` and `b + 3`), for the one call that claimed `b`.
                let mut mine = unsafe { slots.part(mine) }.iter_mut();
                let above = mine.next().filter(|_| b > 0);
                Handoffs::Give(above, mine.next())
            }
            Slots::Take(slots) => {
                let take = |s: usize| slots.get(s).filter(|_| s < bands);
                Handoffs::Take(take(b), take(b + 1))
            }
        };
        Some(Claimed {
            band: b,
            rows: Rows {
                first_row: rows.start,
                cols,
                out,
            },
            handoffs,
        })
    }

    /// Whether every band of the colour has been claimed.
    pub fn all_claimed(&self) -> bool {
        (self.colour..self.tiling.bands())
            .step_by(2)
            .all(|b| self.claims.claimed(b))
    }
}

/// The back-buffer rows one band writes: rows `first_row ..` of x, y, z, vx, vy, vz.
pub(crate) struct Rows<'a> {
    first_row: usize,
    cols: usize,
    out: [&'a mut [f32]; 6],
}

impl Rows<'_> {
    /// Row `r` (of this band), for the row kernel to write.
    #[inline(always)]
    pub fn row(&mut self, r: usize) -> [&mut [f32]; 6] {
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

/// A band's handoff slots on its two cuts (above, below): written by an even band, read
/// by an odd one.
pub(crate) enum Handoffs<'a, V> {
    Give(Option<&'a mut Handoff<V>>, Option<&'a mut Handoff<V>>),
    Take(Option<&'a Handoff<V>>, Option<&'a Handoff<V>>),
}
