//! The engine's scratch rows: the forces a row sends down, the rows of the layers in
//! flight, and each worker thread's set of them. All are chunk-major — the lanes of one
//! chunk of columns sit together — so the row kernel reaches all of a chunk's values with
//! one pointer and constant offsets (the state itself stays structure-of-arrays).

use crate::simd::Vector;
use std::any::Any;
use std::cell::RefCell;

/// The S, SE and SW forces of one chunk, by family and axis.
pub(super) type Group<V> = [[V; 3]; 3];

/// Groups in a chunk-major scratch row of `cols` columns: its chunks and a zero group on
/// each side.
fn group_count<V: Vector>(cols: usize) -> usize {
    cols.div_ceil(V::LANES) + 2
}

/// The forces a row sends down: its S, SE and SW springs. Group `j` holds columns
/// `(j − 1)·LANES ..` as `[family − 1][axis]` lanes; groups 0 and `chunks + 1`, and the
/// lanes past the row, are zero.
#[derive(Debug, Clone)]
pub(crate) struct RowForces<V> {
    groups: Vec<Group<V>>,
}

impl<V: Vector> RowForces<V> {
    pub fn new(cols: usize) -> Self {
        Self {
            groups: vec![[[V::zero(); 3]; 3]; group_count::<V>(cols)],
        }
    }

    /// The groups, checked to be those of a row of `cols` columns: the engine's unchecked
    /// accesses rely on that length.
    pub fn groups(&self, cols: usize) -> &[Group<V>] {
        assert_eq!(self.groups.len(), group_count::<V>(cols));
        &self.groups
    }

    /// [`RowForces::groups`], mutable.
    pub fn groups_mut(&mut self, cols: usize) -> &mut [Group<V>] {
        assert_eq!(self.groups.len(), group_count::<V>(cols));
        &mut self.groups
    }

    /// Clears the forces (what a band's first row receives from above when it is the
    /// grid's first row, and what the last row sends).
    pub fn zero_down(&mut self) {
        self.groups.fill([[V::zero(); 3]; 3]);
    }
}

/// One row of positions and velocities outside the state buffers: a layer in flight, or
/// a row handed from colour 0 to colour 1. Group `j` holds columns `(j − 1)·LANES ..` as
/// `[x, y, z, vx, vy, vz]` lanes; groups 0 and `chunks + 1`, and the lanes past the row,
/// stay zero.
#[derive(Debug, Clone)]
pub(crate) struct Row<V> {
    groups: Vec<[V; 6]>,
}

impl<V: Vector> Row<V> {
    pub fn new(cols: usize) -> Self {
        Self {
            groups: vec![[V::zero(); 6]; group_count::<V>(cols)],
        }
    }

    /// The groups, checked to be those of a row of `cols` columns: the engine's unchecked
    /// accesses rely on that length.
    pub fn groups(&self, cols: usize) -> &[[V; 6]] {
        assert_eq!(self.groups.len(), group_count::<V>(cols));
        &self.groups
    }

    /// [`Row::groups`], mutable.
    pub fn groups_mut(&mut self, cols: usize) -> &mut [[V; 6]] {
        assert_eq!(self.groups.len(), group_count::<V>(cols));
        &mut self.groups
    }

    pub fn copy_from(&mut self, other: &Row<V>) {
        self.groups.copy_from_slice(&other.groups);
    }
}

/// A worker's buffers for the layers in flight, reused across bands and passes.
pub(super) struct Scratch<V> {
    cols: usize,
    /// `rings[l]`: the last two rows of layer `l` (row `r` in slot `r % 2`), for
    /// `l in 1..layers` (`rings[0]` is unused: layer 0 is the front buffer).
    pub rings: Vec<[Row<V>; 2]>,
    /// `prev[l]`: the springs of the row before the one layer `l` integrates next.
    pub prev: Vec<RowForces<V>>,
    /// The row being evaluated; swapped into `prev[l]` once its row is integrated.
    pub cur: RowForces<V>,
}

impl<V: Vector> Scratch<V> {
    fn new(cols: usize, layers: usize) -> Self {
        Self {
            cols,
            rings: (0..layers)
                .map(|_| [Row::new(cols), Row::new(cols)])
                .collect(),
            prev: (0..=layers).map(|_| RowForces::new(cols)).collect(),
            cur: RowForces::new(cols),
        }
    }
}

thread_local! {
    /// This thread's [`Scratch`], of whichever vector type it last ran.
    static SCRATCH: RefCell<Option<Box<dyn Any>>> = const { RefCell::new(None) };
}

/// Takes this thread's scratch, for `cols` columns and at least `layers` layers, out of
/// its slot (made anew if the one there is of another vector type or width, or has fewer
/// layers); give it back with [`put_scratch`]. A band that panics in between drops it,
/// and the next band makes a new one. Taking and putting back, rather than lending it to
/// a closure, keeps the band's loop in the function that entered the SIMD level: a
/// closure is compiled on its own, without the level's instruction set.
pub(super) fn take_scratch<V: Vector>(cols: usize, layers: usize) -> Box<Scratch<V>> {
    let held = SCRATCH.with(|s| s.borrow_mut().take());
    match held.map(|b| b.downcast::<Scratch<V>>()) {
        Some(Ok(s)) if s.cols == cols && s.rings.len() >= layers => s,
        _ => Box::new(Scratch::new(cols, layers)),
    }
}

/// Gives this thread's scratch back to its slot for the next band.
pub(super) fn put_scratch<V: Vector>(scratch: Box<Scratch<V>>) {
    SCRATCH.with(|s| *s.borrow_mut() = Some(scratch));
}
