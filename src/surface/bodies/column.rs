//! The water column under the bodies: it carries the steady part of their push to the
//! bottom and hands the lattice only what changes.
//!
//! # Why
//!
//! The lattice is a membrane of springs with no weight of its own: a steady load on it
//! makes a dent that reaches across the whole pool, and a body beside a dent slides down
//! into it. Bodies resting on the water would dent it by their weight, drift towards each
//! other and towards the walls, and a body would set off from rest by itself as soon as the
//! least asymmetry tipped it off its own dent. In a pool the water under a boat is a
//! column whose pressure carries the boat's weight to the bottom: the free surface beside
//! the boat stays flat, and only a change of the load (a boat bobbing, rolling, dropped in,
//! or moving on to other water) makes waves.
//!
//! # What the water gets
//!
//! Per node `i`, let `R_i` be what the bodies push into it for a step: the shares of the
//! surface's own bodies' reactions (in the order the bodies were added), after those of
//! every [`Surface::body_forces`](crate::Surface::body_forces) call since the last step;
//! and let `C_i` be the load the column carries. The step's external force on node `i` gets
//!
//! ```text
//! W_i = R_i − C_i                  (R_i = pending_i + fresh_i, summed in that order)
//! C_i ← C_i + a · W_i              once the step has succeeded,
//! a   = min(1, Δt / CARRY_SECONDS)  Δt the step in seconds
//! ```
//!
//! all in `f32`, in that order, in the lattice's force units. A steady push is carried
//! geometrically, `W` shrinking as `(1 − a)ⁿ`: within about four
//! [`CARRY_SECONDS`] it is gone from the water. A push that changes faster than that
//! reaches the water nearly whole: a body dropped in makes its splash, a bobbing or
//! rolling one its rings, a moving one loads the water ahead and unloads it behind (its
//! wake). A body taken away leaves its carried load to unload, as the water under a boat
//! lifted out springs back.
//!
//! What it gives up: the pressure of a steady load does not spread through the membrane,
//! so a heavy raft leaves the water under and beside it flat rather than dented (the body
//! sits in the water, as a real one does), and the membrane under a body moored for long
//! no longer softens its roll.
//!
//! The column is state: a list of the nodes that carry or await a load, sorted by node,
//! in snapshots and in the state hash. A node leaves the list once it has nothing waiting
//! and carries less than [`TINY`] in every component.

use crate::error::{Error, Result};

/// The time over which the column takes up a steady push, seconds: a push steady for
/// `CARRY_SECONDS` reaches the water at `1/e` of its size, and after four at 2%. A quarter
/// of a second: a resting body's weight is carried within a second, while a bob of about a
/// second (a half-sunk ball at the default gravity) still reaches the water at about 85%
/// and a moving body's load meets each node in full as it arrives there.
pub(crate) const CARRY_SECONDS: f32 = 0.25;

/// A node whose carried load is below this in every component (the lattice's force
/// units), with nothing waiting, leaves the column.
pub(crate) const TINY: f32 = 1e-12;

/// No entry for this node.
const NONE: u32 = u32::MAX;

/// The nodes under the bodies and what each carries.
#[derive(Debug, Clone, Default)]
pub(crate) struct Column {
    /// Entries sorted by node between steps.
    entries: Vec<Entry>,
    /// The entry of each node, `NONE` for nodes without one; rebuilt when it does not
    /// match the grid or the entries (empty until first used).
    slot: Vec<u32>,
    /// Entries before this step's gather: a failed step drops the ones after. Equal to
    /// the entries' count between steps (every change but a gather keeps it so).
    kept: usize,
    /// A restore decodes into this buffer, checks it, then swaps it in: a rollback
    /// reuses both lists' memory.
    spare: Vec<Entry>,
}

/// One node of the column.
#[derive(Debug, Clone, Copy, PartialEq)]
#[cfg_attr(feature = "serde", derive(serde::Serialize, serde::Deserialize))]
pub(crate) struct Entry {
    pub node: usize,
    /// The load the column carries.
    pub carried: [f32; 3],
    /// Pushes of `body_forces` waiting for the next step.
    pub pending: [f32; 3],
    /// This step's pushes of the surface's own bodies, and once [`Column::water`] has
    /// run, what the water gets, `W`, for [`Column::commit`] (zero between steps).
    #[cfg_attr(feature = "serde", serde(skip))]
    fresh: [f32; 3],
}

impl Entry {
    /// A loaded entry from a snapshot.
    pub fn stored(node: usize, carried: [f32; 3], pending: [f32; 3]) -> Self {
        Self {
            node,
            carried,
            pending,
            fresh: [0.0; 3],
        }
    }

    /// `W = (pending + fresh) − carried`: what the water gets.
    fn water(&self) -> [f32; 3] {
        std::array::from_fn(|k| (self.pending[k] + self.fresh[k]) - self.carried[k])
    }
}

/// `min(1, seconds / CARRY_SECONDS)`: the part of what the water gets that the column
/// takes up in a step of `seconds`.
pub(crate) fn rate(seconds: f32) -> f32 {
    (seconds / CARRY_SECONDS).min(1.0)
}

impl Column {
    /// Whether no node carries or awaits anything.
    pub fn is_empty(&self) -> bool {
        self.entries.is_empty()
    }

    /// The entries, sorted by node.
    pub fn entries(&self) -> &[Entry] {
        &self.entries
    }

    /// Replaces the entries (from a snapshot: sorted, nodes below the grid's count).
    pub fn set_entries(&mut self, entries: impl IntoIterator<Item = Entry>) {
        self.entries.clear();
        self.entries.extend(entries);
        self.slot.clear();
        self.kept = self.entries.len();
    }

    /// The buffer a restore decodes into before [`Column::take_spare`] swaps it in.
    pub fn spare(&mut self) -> &mut Vec<Entry> {
        &mut self.spare
    }

    /// Makes the entries decoded into [`Column::spare`] (sorted, checked) the column's.
    pub fn take_spare(&mut self) {
        std::mem::swap(&mut self.entries, &mut self.spare);
        self.slot.clear();
        self.kept = self.entries.len();
    }

    /// Moves every entry to the node `to` gives (the window moved), dropping those that
    /// left the grid.
    pub fn shift(&mut self, to: impl Fn(usize) -> Option<usize>) {
        self.entries.retain_mut(|e| match to(e.node) {
            Some(i) => {
                e.node = i;
                true
            }
            None => false,
        });
        self.entries.sort_unstable_by_key(|e| e.node);
        self.slot.clear();
        self.kept = self.entries.len();
    }

    /// Makes the slots match a grid of `nodes` and the entries, if they do not.
    fn fit_slots(&mut self, nodes: usize) {
        if self.slot.len() != nodes {
            self.slot.clear();
            self.slot.resize(nodes, NONE);
            for (k, e) in self.entries.iter().enumerate() {
                self.slot[e.node] = k as u32;
            }
        }
    }

    /// The entry of `node`, made (at the end) if it has none; the slots fit the grid
    /// ([`Column::fit_slots`]).
    #[inline]
    fn entry(&mut self, node: usize) -> &mut Entry {
        let k = match self.slot[node] {
            NONE => {
                self.slot[node] = self.entries.len() as u32;
                self.entries.push(Entry::stored(node, [0.0; 3], [0.0; 3]));
                self.entries.len() - 1
            }
            k => k as usize,
        };
        &mut self.entries[k]
    }

    /// Adds `shares` (distinct nodes) to what waits for the next step: a body another
    /// engine owns. Refused, with nothing changed, if a sum is not finite.
    pub fn hold(
        &mut self,
        shares: impl Iterator<Item = (usize, [f32; 3])> + Clone,
        nodes: usize,
    ) -> Result<()> {
        let before = self.entries.len();
        self.fit_slots(nodes);
        let mut finite = true;
        for (i, f) in shares.clone() {
            let e = self.entry(i);
            finite &= (0..3).all(|k| (e.pending[k] + f[k]).is_finite());
        }
        if !finite {
            self.drop_after(before);
            return Err(overflow());
        }
        for (i, f) in shares {
            let e = self.entry(i);
            e.pending = std::array::from_fn(|k| e.pending[k] + f[k]);
        }
        self.sort_if_grown(before);
        Ok(())
    }

    /// Starts gathering this step's pushes of the surface's own bodies on a grid of
    /// `nodes` ([`Column::gather`] each, in the bodies' order).
    pub fn begin_gather(&mut self, nodes: usize) {
        self.kept = self.entries.len();
        self.fit_slots(nodes);
    }

    /// Gathers a push `f` of the surface's own bodies into `node`.
    #[inline]
    pub fn gather(&mut self, node: usize, f: [f32; 3]) {
        let e = self.entry(node);
        e.fresh = std::array::from_fn(|k| e.fresh[k] + f[k]);
    }

    /// What the water gets this step, node by node (distinct nodes): `W` of every entry,
    /// kept in its `fresh` for [`Column::commit`] (the pushes are summed in it by then).
    pub fn water(&mut self) -> impl Iterator<Item = (usize, [f32; 3])> + '_ {
        self.entries.iter_mut().map(|e| {
            e.fresh = e.water();
            (e.node, e.fresh)
        })
    }

    /// The step succeeded: the column takes up `rate` of what the water got (`W`, which
    /// [`Column::water`] left in `fresh`), the pushes are spent, and nodes with nothing
    /// left leave.
    pub fn commit(&mut self, rate: f32) {
        let mut left = false;
        for e in &mut self.entries {
            let w = e.fresh;
            e.carried = std::array::from_fn(|k| e.carried[k] + rate * w[k]);
            e.pending = [0.0; 3];
            e.fresh = [0.0; 3];
            left |= e.carried.iter().all(|c| c.abs() < TINY);
        }
        let grown = self.entries.len() > self.kept;
        if left {
            self.drop_spent();
        }
        if grown || left {
            self.sort();
        }
        self.kept = self.entries.len();
    }

    /// Forgets the pushes waiting for the next step (the caller discarded its forces):
    /// nodes left with nothing to carry leave.
    pub fn drop_pending(&mut self) {
        for e in &mut self.entries {
            e.pending = [0.0; 3];
        }
        if self.drop_spent() {
            self.sort();
        }
        self.kept = self.entries.len();
    }

    /// Drops the entries that carry less than [`TINY`] in every component (with nothing
    /// waiting), clearing their slots; whether any went (the others' slots are then stale
    /// until [`Column::sort`]).
    fn drop_spent(&mut self) -> bool {
        let (slot, before) = (&mut self.slot, self.entries.len());
        self.entries.retain(|e| {
            let keep = e.carried.iter().any(|c| c.abs() >= TINY);
            if !keep {
                if let Some(s) = slot.get_mut(e.node) {
                    *s = NONE;
                }
            }
            keep
        });
        self.entries.len() < before
    }

    /// The step failed: this step's pushes are forgotten, the column is as it was.
    pub fn discard(&mut self) {
        self.drop_after(self.kept);
        for e in &mut self.entries {
            e.fresh = [0.0; 3];
        }
    }

    /// Drops the entries made after the first `len` (with their slots).
    fn drop_after(&mut self, len: usize) {
        for e in self.entries.drain(len..) {
            if let Some(s) = self.slot.get_mut(e.node) {
                *s = NONE;
            }
        }
    }

    /// Sorts the entries again if some were made after the first `before`.
    fn sort_if_grown(&mut self, before: usize) {
        if self.entries.len() > before {
            self.sort();
        }
        self.kept = self.entries.len();
    }

    /// Sorts the entries by node and points the slots at their new places. (A stable sort:
    /// the entries are a sorted run and a few new ones after it, which it merges in a pass
    /// rather than sorting the whole list again.)
    fn sort(&mut self) {
        self.entries.sort_by_key(|e| e.node);
        if !self.slot.is_empty() {
            for (k, e) in self.entries.iter().enumerate() {
                self.slot[e.node] = k as u32;
            }
        }
    }
}

fn overflow() -> Error {
    Error::InvalidParam {
        name: "accumulated force",
        value: f64::INFINITY,
        expected: "finite: the bodies' reactions overflow f32",
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn water(column: &mut Column, shares: &[(usize, [f32; 3])]) -> Vec<(usize, [f32; 3])> {
        column.begin_gather(16);
        for &(i, f) in shares {
            column.gather(i, f);
        }
        column.water().collect()
    }

    #[test]
    fn the_water_gets_what_changes_and_the_column_takes_up_the_rest() {
        let mut c = Column::default();
        let rate = 0.25;
        // A steady push of 1 on node 3: the water gets R − C, the column takes up a W.
        let mut carried = 0.0f32;
        for _ in 0..40 {
            let w = water(&mut c, &[(3, [0.0, -1.0, 0.0])]);
            assert_eq!(w, vec![(3, [0.0, -1.0 - carried, 0.0])]);
            c.commit(rate);
            carried += rate * (-1.0 - carried);
            assert_eq!(c.entries()[0].carried, [0.0, carried, 0.0]);
        }
        // Gone after a while, and the push stopped: the water gets −C until it is tiny.
        let mut steps = 0;
        while !c.is_empty() {
            let w = water(&mut c, &[]);
            assert_eq!(w, vec![(3, [0.0, -carried, 0.0])]);
            c.commit(rate);
            carried -= rate * carried;
            steps += 1;
            assert!(steps < 200);
        }
        assert!(carried.abs() < TINY);
    }

    #[test]
    fn pending_pushes_come_first_and_a_failed_step_changes_nothing() {
        let mut c = Column::default();
        c.hold([(5, [1.0, 2.0, 3.0])].into_iter(), 16).unwrap();
        let before = c.entries().to_vec();
        let w = water(&mut c, &[(5, [0.5, 0.5, 0.5]), (9, [0.0, 1.0, 0.0])]);
        assert_eq!(w, vec![(5, [1.5, 2.5, 3.5]), (9, [0.0, 1.0, 0.0])]);
        c.discard();
        assert_eq!(c.entries(), &before[..]);
        // Refused: nothing changes.
        assert!(c.hold([(5, [f32::MAX, 0.0, 0.0])].into_iter(), 16).is_ok());
        let kept = c.entries().to_vec();
        assert!(c.hold([(5, [f32::MAX, 0.0, 0.0])].into_iter(), 16).is_err());
        assert!(c
            .hold([(7, [0.0; 3]), (5, [f32::MAX, 0.0, 0.0])].into_iter(), 16)
            .is_err());
        assert_eq!(c.entries(), &kept[..]);
    }

    #[test]
    fn dropping_the_pending_pushes_keeps_what_is_carried() {
        let mut c = Column::default();
        water(&mut c, &[(4, [0.0, 1.0, 0.0])]);
        c.commit(0.5);
        c.hold([(4, [1.0; 3]), (8, [2.0; 3])].into_iter(), 16)
            .unwrap();
        c.drop_pending();
        // Node 8 only awaited a push: it leaves; node 4 keeps its load, nothing waits.
        assert_eq!(c.entries(), &[Entry::stored(4, [0.0, 0.5, 0.0], [0.0; 3])]);
        let w = water(&mut c, &[(8, [1.0; 3])]);
        assert_eq!(w, vec![(4, [0.0, -0.5, 0.0]), (8, [1.0; 3])]);
    }

    #[test]
    fn a_step_that_fails_before_gathering_changes_nothing_after_a_load_or_a_shift() {
        let mut c = Column::default();
        c.set_entries([(3, [1.0; 3]), (7, [2.0; 3])].map(|(n, l)| Entry::stored(n, l, [0.0; 3])));
        c.discard();
        assert_eq!(c.entries().len(), 2);
        c.shift(|i| (i > 4).then(|| i - 4));
        c.discard();
        let nodes: Vec<usize> = c.entries().iter().map(|e| e.node).collect();
        assert_eq!(nodes, [3]);
    }

    #[test]
    fn entries_stay_sorted_and_move_with_the_window() {
        let mut c = Column::default();
        water(&mut c, &[(9, [1.0; 3]), (2, [1.0; 3]), (6, [1.0; 3])]);
        c.commit(0.5);
        let nodes: Vec<usize> = c.entries().iter().map(|e| e.node).collect();
        assert_eq!(nodes, [2, 6, 9]);
        c.shift(|i| i.checked_sub(4));
        let nodes: Vec<usize> = c.entries().iter().map(|e| e.node).collect();
        assert_eq!(nodes, [2, 5]);
        let w = water(&mut c, &[(5, [1.0; 3])]);
        assert_eq!(w, vec![(2, [-0.5; 3]), (5, [0.5; 3])]);
    }
}
