//! The external forces waiting for the next step, and the bookkeeping that lets a step
//! read and clear only the few nodes that hold one.
//!
//! Every way a force gets in (a caller's [`add_force`](crate::Surface::add_force) or
//! [`add_force_at`](crate::Surface::add_force_at), the floating bodies' reactions, a
//! whole buffer from [`set_forces`](crate::Surface::set_forces) or a snapshot) goes through
//! [`External`], which keeps three rules:
//!
//! * **All or nothing.** [`External::add`] adds a batch of forces, each to a distinct node;
//!   if any sum is not finite, every node gets its old bits back and the batch is refused.
//! * **Undo.** The last batch can be taken back whole ([`External::undo`]), bit for bit,
//!   with the flags as they were: a coupled step whose water step fails after the bodies'
//!   reactions went in leaves the forces as they were.
//! * **Few nodes, few rows.** While fewer than a sixteenth of the nodes hold a force, they
//!   are listed: a step then reads the force buffers on their rows only
//!   ([`External::for_step`]) and clears just them. Past that, any node may hold one, and a
//!   step reads and clears the whole buffers.

use super::{zeros3, Xyz};

/// The external forces per node for the next step (see the [module docs](self)).
#[derive(Debug, Clone)]
pub(crate) struct External {
    forces: Xyz,
    /// Whether any force may be non-zero.
    pending: bool,
    /// Every node whose force may be non-zero, while few (`None`: any node may be).
    nodes: Option<Vec<usize>>,
    /// Nodes of the grid (the list's limit is a sixteenth of them).
    len: usize,
    /// One flag per row: whether the row holds a listed node ([`External::for_step`]).
    rows: Vec<bool>,
    /// The last batch's nodes and their forces before it, oldest first.
    log: Vec<(usize, [f32; 3])>,
    /// `pending` and the list's length before the last batch.
    before: (bool, Option<usize>),
    /// Whether the last batch went onto no pending force (and keeps no log).
    from_zero: bool,
}

impl External {
    /// No forces, on buffers of `padded` floats for `len` nodes.
    pub fn new(len: usize, padded: usize) -> Self {
        Self {
            forces: zeros3(padded),
            pending: false,
            nodes: Some(Vec::new()),
            len,
            rows: Vec::new(),
            log: Vec::new(),
            before: (false, Some(0)),
            from_zero: false,
        }
    }

    /// Whether any force may be non-zero.
    pub fn is_pending(&self) -> bool {
        self.pending
    }

    /// The force buffers `[x, y, z]` (padded; zero where nothing is pending).
    pub fn buffers(&self) -> &Xyz {
        &self.forces
    }

    /// The force buffers, while any force is pending.
    pub fn pending(&self) -> Option<[&[f32]; 3]> {
        let [x, y, z] = &self.forces;
        self.pending.then_some([&x[..], &y[..], &z[..]])
    }

    /// Adds each `(node, force)` of `batch` (distinct nodes), all or nothing: if a sum is
    /// not finite, every node gets its old force back and that sum is the error. The
    /// batch can be taken back by [`External::undo`] until the next one.
    ///
    /// A batch onto no pending force at all (the bodies' reactions, most steps) keeps no
    /// log: every old force was `+0`, so the nodes it listed (or, past a sixteenth of the
    /// grid, the whole buffers) are what taking it back clears.
    // Never inlined: a batch's loop is compiled with its iterator in a function of its
    // own, where the iterator's closures inline into it (inside the large coupled step
    // they may not, and each force becomes a call).
    #[inline(never)]
    pub fn add(&mut self, batch: impl IntoIterator<Item = (usize, [f32; 3])>) -> Result<(), f32> {
        self.log.clear();
        self.before = (self.pending, self.nodes.as_ref().map(Vec::len));
        let from_zero = !self.pending;
        let limit = self.len / 16;
        let [fx, fy, fz] = slices(&mut self.forces);
        let n = fx.len();
        let (mut finite, mut any) = (true, false);
        for (i, f) in batch {
            assert!(i < n, "node {i} of {n}");
            let old = [fx[i], fy[i], fz[i]];
            let sum = [old[0] + f[0], old[1] + f[1], old[2] + f[2]];
            (fx[i], fy[i], fz[i]) = (sum[0], sum[1], sum[2]);
            if !from_zero {
                self.log.push((i, old));
            } else if let Some(nodes) = &mut self.nodes {
                match nodes.len() < limit {
                    true => nodes.push(i),
                    false => self.nodes = None,
                }
            }
            any = true;
            finite &= sum[0].is_finite() & sum[1].is_finite() & sum[2].is_finite();
        }
        self.from_zero = from_zero;
        if !finite {
            let sum = match from_zero {
                true => self.touched().find(|s| !s.is_finite()),
                false => self
                    .log
                    .iter()
                    .flat_map(|&(i, _)| [fx[i], fy[i], fz[i]])
                    .find(|s| !s.is_finite()),
            };
            self.undo();
            return Err(sum.unwrap_or(f32::INFINITY));
        }
        self.pending |= any;
        if !from_zero {
            if let Some(nodes) = &mut self.nodes {
                if nodes.len() + self.log.len() <= limit {
                    nodes.extend(self.log.iter().map(|&(i, _)| i));
                } else {
                    self.nodes = None;
                }
            }
        }
        Ok(())
    }

    /// The forces a batch onto no pending force may have written: the listed nodes', or
    /// every force once the list is gone.
    fn touched(&self) -> impl Iterator<Item = f32> + '_ {
        let [fx, fy, fz] = &self.forces;
        let listed = self
            .nodes
            .iter()
            .flatten()
            .flat_map(|&i| [fx[i], fy[i], fz[i]]);
        let all = self
            .nodes
            .is_none()
            .then(|| fx.iter().chain(fy.iter()).chain(fz.iter()).copied());
        listed.chain(all.into_iter().flatten())
    }

    /// Takes the last batch of [`External::add`] back: its nodes get their old bits,
    /// newest first, and the flag and list go back to what they were (a list that
    /// overflowed stays `None`, which is still correct). A batch onto no pending force
    /// clears what it wrote (every force was `+0`), and the list is empty again.
    pub fn undo(&mut self) {
        if std::mem::take(&mut self.from_zero) {
            self.zero_written();
            return;
        }
        let [fx, fy, fz] = slices(&mut self.forces);
        for &(i, old) in self.log.iter().rev() {
            (fx[i], fy[i], fz[i]) = (old[0], old[1], old[2]);
        }
        self.log.clear();
        self.from_zero = false;
        self.pending = self.before.0;
        if let (Some(len), Some(nodes)) = (self.before.1, &mut self.nodes) {
            nodes.truncate(len);
        }
    }

    /// Replaces every node's force with `force` (finite, `len` values each, so every
    /// node is written), as a step that reads every row.
    pub fn set(&mut self, force: [&[f32]; 3]) {
        for (dst, src) in self.forces.iter_mut().zip(force) {
            dst[..src.len()].copy_from_slice(src);
        }
        self.mark_all();
    }

    /// Clears every force (after a step applied them, or to discard them).
    pub fn clear(&mut self) {
        if self.pending {
            self.zero_written();
        }
        self.log.clear();
        self.from_zero = false;
    }

    /// Sets every force that may be non-zero to `+0`: the listed nodes', or the whole
    /// buffers once the list is gone (which starts again, empty). Nothing is pending then.
    fn zero_written(&mut self) {
        match &mut self.nodes {
            Some(nodes) => {
                let [fx, fy, fz] = slices(&mut self.forces);
                for &i in nodes.iter() {
                    assert!(i < fx.len(), "node {i} of {}", fx.len());
                    (fx[i], fy[i], fz[i]) = (0.0, 0.0, 0.0);
                }
                nodes.clear();
            }
            None => {
                for c in &mut self.forces {
                    c.fill(0.0);
                }
                self.nodes = Some(Vec::new());
            }
        }
        self.pending = false;
    }

    /// Notes that any node may now hold a force (the buffers were written whole).
    fn mark_all(&mut self) {
        self.pending = true;
        self.nodes = None;
        self.log.clear();
        self.from_zero = false;
    }

    /// What a step reads, on a grid of `cols` columns and `rows` rows: the force
    /// buffers while any force is pending, and the rows whose nodes may hold one while
    /// they are listed (`None`: every row).
    pub fn for_step(&mut self, cols: usize, rows: usize) -> (Option<[&[f32]; 3]>, Option<&[bool]>) {
        if !self.pending {
            return (None, None);
        }
        if let Some(nodes) = &self.nodes {
            self.rows.clear();
            self.rows.resize(rows, false);
            for &i in nodes {
                self.rows[i / cols] = true;
            }
        }
        let [x, y, z] = &self.forces;
        let listed = self.nodes.is_some().then_some(&self.rows[..]);
        (Some([&x[..], &y[..], &z[..]]), listed)
    }

    /// The window moved: `moved` moves the buffers' values (and zeroes what came in),
    /// `to` gives each listed node's new place (`None`: it left the grid).
    pub fn shift(&mut self, moved: impl FnOnce(&mut Xyz), to: impl Fn(usize) -> Option<usize>) {
        if !self.pending {
            return;
        }
        moved(&mut self.forces);
        if let Some(nodes) = &mut self.nodes {
            let mut kept: Vec<usize> = nodes.iter().filter_map(|&i| to(i)).collect();
            kept.sort_unstable();
            kept.dedup();
            *nodes = kept;
        }
        self.log.clear();
        self.from_zero = false;
    }

    /// Loads the forces of a snapshot (`pending` as it recorded; `read` fills the three
    /// buffers' first `len` values).
    pub fn load(&mut self, pending: bool, read: impl FnOnce(&mut Xyz)) {
        // Nothing pending means every force is zero: clearing what may be pending is
        // enough before reading.
        self.clear();
        if pending {
            read(&mut self.forces);
            self.mark_all();
        }
    }
}

/// The three buffers as plain slices of one length, taken once, rather than the buffers'
/// view at every index (a bounds check a node, not one an axis).
fn slices(forces: &mut Xyz) -> [&mut [f32]; 3] {
    let [x, y, z] = forces;
    let n = x.len().min(y.len()).min(z.len());
    [&mut x[..n], &mut y[..n], &mut z[..n]]
}

#[cfg(test)]
mod tests {
    use super::*;

    fn bits(e: &External) -> Vec<u32> {
        e.buffers()
            .iter()
            .flat_map(|b| b.iter().map(|v| v.to_bits()))
            .collect()
    }

    #[test]
    fn a_batch_is_all_or_nothing_and_undone_bit_for_bit() {
        let mut e = External::new(64, 80);
        e.add([(3, [1.0, -0.0, 2.0]), (9, [f32::MAX; 3])]).unwrap();
        let before = bits(&e);
        // The second node overflows: the first is restored too.
        let err = e.add([(3, [1.0; 3]), (9, [f32::MAX; 3])]);
        assert_eq!(err, Err(f32::INFINITY));
        assert_eq!(bits(&e), before);
        e.add([(3, [0.5; 3]), (40, [1.0; 3])]).unwrap();
        assert!(e.is_pending());
        e.undo();
        assert_eq!(bits(&e), before);
        let row_of_3_and_9 = [true, true, false, false, false, false, false, false];
        assert_eq!(e.for_step(8, 8).1, Some(&row_of_3_and_9[..]));
    }

    #[test]
    fn a_batch_onto_no_force_is_refused_or_undone_to_zeros_without_a_log() {
        // Listed: 64 nodes hold a list of up to 4.
        let mut e = External::new(64, 80);
        let err = e.add([(3, [1.0, -0.0, 2.0]), (9, [f32::INFINITY; 3])]);
        assert_eq!(err, Err(f32::INFINITY));
        assert!(!e.is_pending() && bits(&e).iter().all(|&b| b == 0));
        e.add([(3, [1.0, -0.0, 2.0]), (9, [-0.0; 3])]).unwrap();
        assert!(e.log.is_empty());
        e.undo();
        assert!(!e.is_pending() && bits(&e).iter().all(|&b| b == 0));
        assert_eq!(e.for_step(8, 8), (None, None));
        // Past the list: refusing it or taking it back clears every force, and the list
        // starts again.
        let bad_last = |i| match i {
            5 => [f32::INFINITY; 3],
            _ => [1.0; 3],
        };
        let err = e.add((0..6).map(|i| (i * 9, bad_last(i))));
        assert_eq!(err, Err(f32::INFINITY));
        assert!(!e.is_pending() && bits(&e).iter().all(|&b| b == 0));
        e.add((0..6).map(|i| (i * 9, [1.0; 3]))).unwrap();
        assert_eq!(e.for_step(8, 8).1, None);
        e.undo();
        assert!(!e.is_pending() && bits(&e).iter().all(|&b| b == 0));
        e.add([(63, [1.0; 3])]).unwrap();
        let last_row = [false, false, false, false, false, false, false, true];
        assert_eq!(e.for_step(8, 8).1, Some(&last_row[..]));
    }

    #[test]
    fn past_a_sixteenth_of_the_nodes_every_row_is_read() {
        let mut e = External::new(64, 80);
        e.add((0..4).map(|i| (i * 8, [1.0; 3]))).unwrap();
        let rows = |e: &mut External| e.for_step(8, 8).1.map(|r| r.iter().filter(|&&b| b).count());
        assert_eq!(rows(&mut e), Some(4));
        e.add([(63, [1.0; 3])]).unwrap();
        assert!(e.for_step(8, 8).0.is_some());
        assert_eq!(rows(&mut e), None);
        e.clear();
        assert!(!e.is_pending());
        assert!(bits(&e).iter().all(|&b| b == 0));
        assert!(e.for_step(8, 8).0.is_none());
    }
}
