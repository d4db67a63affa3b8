//! The engine's unchecked access: every read and write the row kernel makes of the state,
//! the node and spring tables and its scratch rows goes through the views of this module,
//! so that the kernel above it ([`super::row`]) is safe code, and each band's own rows of
//! the back buffers and handoff slots are handed out by [`bands`], so that the schedule
//! above it ([`super::schedule`]) is safe code too. Only this module of the engine says
//! `unsafe`.
//!
//! # Why every access is in bounds
//!
//! A row of `cols` columns is `chunks = ⌈cols / LANES⌉` chunks; chunk `k` is columns
//! `k·LANES ..`. The kernel reads chunk `k` of the row and of the row below, chunk `k + 1`
//! of both (the east neighbours), and writes chunk `k`, for every `k < chunks`. The views
//! are made once per row, and each constructor checks with `assert!` that it holds all of
//! that:
//!
//! * a source row ([`FrontRow`] or a ring row's groups) has the positions of chunks
//!   `0 ..= chunks` and the velocities of chunks `0 .. chunks` ([`RowPair::new`]). Chunk
//!   `chunks`, and the lanes past the row in the last chunk, hold the next row's nodes,
//!   padding or zeros, which only ever meet masked-off springs;
//! * the spring tables ([`Tables::new`], which reads the SW table one node on: the
//!   tables' padding past the last node covers it), the node tables and the external
//!   forces have `chunks` chunks, the arriving forces ([`NodeViews::new`]) and the sent
//!   ones ([`RowViews::new`]) `chunks + 2` groups, chunk `k` being group `k + 1`;
//! * a destination ([`Sink`]) has `whole` whole chunks, at least `chunks − 1`
//!   ([`each_chunk`] asserts it), and a back-buffer row ([`BackRow`]) streams only where
//!   every row starts on a vector boundary.
//!
//! Then the chunk index needs no check: [`each_chunk`] runs the loop over a row's chunks
//! and hands the kernel each chunk as a [`Chunk`], which only it makes and only for
//! `k < chunks`, and which reads and writes through the views it was made from. (A
//! checked load would cost a comparison per lane load — 30% of the 256² step's
//! instructions, measured with callgrind — and even one check per view and chunk kept
//! the compiler from holding the kernel's values in registers: 1–3% more instructions.)
//! [`RowPair::around`] and [`RowPair::spring`], for the springs a band evaluates above
//! its first row, check the index: they run once per band and layer.
//!
//! `tests/miri.rs` runs these paths under Miri on every width around the lane count, in
//! single steps and passes, with uniform and edited springs.

mod bands;

pub(super) use bands::{Bands, Claims, Handoffs, Rows};

use super::scratch::Group;
use crate::grid::Family;
use crate::simd::{Chunks, ChunksMut, Vector};
use crate::springs::Tables as SpringTables;

/// The unchecked reads behind [`Source`] and [`SpringValues`], callable only here.
mod raw {
    use crate::grid::Family;

    /// A row's positions and velocities by chunk, whatever its layout.
    pub trait Source<V>: Copy {
        /// Chunks of positions readable (`k < pos_chunks`).
        fn pos_chunks(self) -> usize;
        /// Chunks of velocities readable.
        fn vel_chunks(self) -> usize;
        /// # Safety
        ///
        /// `k < self.pos_chunks()`.
        unsafe fn pos(self, k: usize) -> [V; 3];
        /// # Safety
        ///
        /// `k < self.vel_chunks()`.
        unsafe fn vel(self, k: usize) -> [V; 3];
    }

    /// A row's spring coefficients and rest lengths by family and chunk.
    pub trait Springs<V> {
        /// Chunks readable (`usize::MAX` for values that are not read from memory).
        fn chunks(&self) -> usize;
        /// # Safety
        ///
        /// `k < self.chunks()`.
        unsafe fn at(&self, fam: Family, k: usize) -> (V, V);
    }
}

/// Where a row's positions and velocities live: the front buffers ([`FrontRow`]) or a
/// ring row's groups (`&[[V; 6]]`: `chunks + 2` groups, chunk `k` in group `k + 1`).
pub(super) trait Source<V>: raw::Source<V> {
    /// Rows of this kind may carry external forces. Only the front buffers do: a pass
    /// applies them in its first step. (Known when the kernel is compiled, so a ring row's
    /// kernel has no test for them.)
    const EXTERNAL: bool;
}

/// Where a row's springs take their coefficient and rest length from: the kernel is
/// compiled once for each kind.
pub(super) trait SpringValues<V>: raw::Springs<V> {}

/// A row of the front buffers as chunk views.
pub(super) struct FrontRow<'a, V> {
    pos: [Chunks<'a, V>; 3],
    vel: [Chunks<'a, V>; 3],
}

impl<V> Clone for FrontRow<'_, V> {
    fn clone(&self) -> Self {
        *self
    }
}

impl<V> Copy for FrontRow<'_, V> {}

impl<'a, V: Vector> FrontRow<'a, V> {
    /// The row of `chunks` chunks starting at node `start`: positions `chunks + 1` chunks
    /// long, velocities `chunks`. Panics if a buffer is shorter.
    #[inline(always)]
    pub fn new(pos: [&'a [f32]; 3], vel: [&'a [f32]; 3], start: usize, chunks: usize) -> Self {
        // Written out, as is every view a row advance builds: a closure passed to
        // `array::map` is compiled on its own and became calls, several per row.
        let ([x, y, z], [vx, vy, vz]) = (pos, vel);
        FrontRow {
            pos: [
                Chunks::new(x, start, chunks + 1),
                Chunks::new(y, start, chunks + 1),
                Chunks::new(z, start, chunks + 1),
            ],
            vel: [
                Chunks::new(vx, start, chunks),
                Chunks::new(vy, start, chunks),
                Chunks::new(vz, start, chunks),
            ],
        }
    }
}

impl<V: Vector> raw::Source<V> for FrontRow<'_, V> {
    #[inline(always)]
    fn pos_chunks(self) -> usize {
        let [x, y, z] = self.pos;
        x.len().min(y.len()).min(z.len())
    }

    #[inline(always)]
    fn vel_chunks(self) -> usize {
        let [x, y, z] = self.vel;
        x.len().min(y.len()).min(z.len())
    }

    #[inline(always)]
    unsafe fn pos(self, k: usize) -> [V; 3] {
        let [x, y, z] = self.pos;
        // SAFETY: `k < pos_chunks`, the shortest view's length.
        unsafe { [x.get(k), y.get(k), z.get(k)] }
    }

    #[inline(always)]
    unsafe fn vel(self, k: usize) -> [V; 3] {
        let [x, y, z] = self.vel;
        // SAFETY: `k < vel_chunks`, the shortest view's length.
        unsafe { [x.get(k), y.get(k), z.get(k)] }
    }
}

impl<V: Vector> Source<V> for FrontRow<'_, V> {
    const EXTERNAL: bool = true;
}

impl<V: Vector> raw::Source<V> for &[[V; 6]] {
    #[inline(always)]
    fn pos_chunks(self) -> usize {
        self.len().saturating_sub(1)
    }

    #[inline(always)]
    fn vel_chunks(self) -> usize {
        self.len().saturating_sub(2)
    }

    #[inline(always)]
    unsafe fn pos(self, k: usize) -> [V; 3] {
        // SAFETY: `k < len − 1`, so group `k + 1` exists.
        let g = unsafe { self.get_unchecked(k + 1) };
        [g[0], g[1], g[2]]
    }

    #[inline(always)]
    unsafe fn vel(self, k: usize) -> [V; 3] {
        // SAFETY: `k < len − 2`, so group `k + 1` exists.
        let g = unsafe { self.get_unchecked(k + 1) };
        [g[3], g[4], g[5]]
    }
}

impl<V: Vector> Source<V> for &[[V; 6]] {
    const EXTERNAL: bool = false;
}

/// One family's coefficients and rest lengths along one row.
#[derive(Clone, Copy)]
struct Table<'a, V> {
    coef: Chunks<'a, V>,
    rest: Chunks<'a, V>,
}

impl<'a, V: Vector> Table<'a, V> {
    /// Family `fam`'s table for the `chunks` chunks of the row from node `base` (one node
    /// on for SW: see [`Tables::new`]).
    #[inline(always)]
    fn of(sp: &'a SpringTables, fam: Family, base: usize, chunks: usize) -> Self {
        let (f, start) = (fam as usize, base + usize::from(fam == Family::SW));
        Table {
            coef: Chunks::new(&sp.coef[f], start, chunks),
            rest: Chunks::new(&sp.rest[f], start, chunks),
        }
    }
}

/// Each spring's own values, read from the families' tables along the row.
pub(super) struct Tables<'a, V>([Table<'a, V>; 4]);

impl<'a, V: Vector> Tables<'a, V> {
    /// The tables for the `chunks` chunks of the row starting at node `base`, in the lanes
    /// the kernel evaluates each spring in: a SW spring in the lane of its lower end, one
    /// column west of its origin, so that table is read one node on. Panics if a table is
    /// shorter (they are padded past the last node by more than a chunk).
    #[inline(always)]
    pub fn new(sp: &'a SpringTables, base: usize, chunks: usize) -> Self {
        // Written out: a closure passed to `array::map` became four calls per row.
        let [e, s, se, sw] = Family::ALL;
        Self([
            Table::of(sp, e, base, chunks),
            Table::of(sp, s, base, chunks),
            Table::of(sp, se, base, chunks),
            Table::of(sp, sw, base, chunks),
        ])
    }
}

impl<V: Vector> raw::Springs<V> for Tables<'_, V> {
    #[inline(always)]
    fn chunks(&self) -> usize {
        let mut n = usize::MAX;
        for t in &self.0 {
            n = n.min(t.coef.len()).min(t.rest.len());
        }
        n
    }

    #[inline(always)]
    unsafe fn at(&self, fam: Family, k: usize) -> (V, V) {
        let t = self.0[fam as usize];
        // SAFETY: `k < chunks`, the shortest view's length.
        unsafe { (t.coef.get(k), t.rest.get(k)) }
    }
}

impl<V: Vector> SpringValues<V> for Tables<'_, V> {}

/// Every family's springs share one coefficient and rest length: the eight values stay in
/// registers and no table is read.
pub(super) struct Shared<V>([(V, V); 4]);

impl<V: Vector> Shared<V> {
    #[inline(always)]
    pub fn new([e, s, se, sw]: [(f32, f32); 4]) -> Self {
        Self([splat2(e), splat2(s), splat2(se), splat2(sw)])
    }
}

/// `(coefficient, rest length)` as lanes. (A named `#[inline(always)]` function, never a
/// closure, where lanes are made: a closure is compiled on its own, without the level's
/// target features, and the intrinsics in it become calls.)
#[inline(always)]
fn splat2<V: Vector>((c, r): (f32, f32)) -> (V, V) {
    (V::splat(c), V::splat(r))
}

impl<V: Vector> raw::Springs<V> for Shared<V> {
    #[inline(always)]
    fn chunks(&self) -> usize {
        usize::MAX
    }

    #[inline(always)]
    unsafe fn at(&self, fam: Family, _k: usize) -> (V, V) {
        self.0[fam as usize]
    }
}

impl<V: Vector> SpringValues<V> for Shared<V> {}

/// The tables if the springs have them, else the shared values: one copy of a loop for
/// both, with a branch per chunk.
pub(super) enum EitherValues<'a, V> {
    Tables(Tables<'a, V>),
    Shared(Shared<V>),
}

impl<V: Vector> raw::Springs<V> for EitherValues<'_, V> {
    #[inline(always)]
    fn chunks(&self) -> usize {
        match self {
            Self::Tables(t) => t.chunks(),
            Self::Shared(s) => s.chunks(),
        }
    }

    #[inline(always)]
    unsafe fn at(&self, fam: Family, k: usize) -> (V, V) {
        match self {
            // SAFETY: `k < chunks`, which is this variant's.
            Self::Tables(t) => unsafe { t.at(fam, k) },
            // SAFETY: as above.
            Self::Shared(s) => unsafe { s.at(fam, k) },
        }
    }
}

impl<V: Vector> SpringValues<V> for EitherValues<'_, V> {}

/// The positions of chunks `k` and `k + 1` of a row and of the row below.
pub(super) struct Around<V> {
    pub here: [V; 3],
    pub here_east: [V; 3],
    pub below: [V; 3],
    pub below_east: [V; 3],
}

/// A row, the row below it and the row's springs, checked for `chunks` chunks.
pub(super) struct RowPair<'p, V, S, P> {
    chunks: usize,
    here: S,
    below: S,
    springs: &'p P,
    _lanes: std::marker::PhantomData<V>,
}

impl<'p, V: Vector, S: Source<V>, P: SpringValues<V>> RowPair<'p, V, S, P> {
    /// Panics unless both rows hold positions of chunks `0 ..= chunks` and velocities of
    /// chunks `0 .. chunks`, and `springs` has `chunks` chunks.
    #[inline(always)]
    pub fn new(chunks: usize, here: S, below: S, springs: &'p P) -> Self {
        assert!(here.pos_chunks() > chunks && below.pos_chunks() > chunks);
        assert!(here.vel_chunks() >= chunks && below.vel_chunks() >= chunks);
        assert!(springs.chunks() >= chunks);
        Self {
            chunks,
            here,
            below,
            springs,
            _lanes: std::marker::PhantomData,
        }
    }

    /// The positions of chunk `k` of the row, or of the row below.
    ///
    /// # Safety
    ///
    /// `k ≤ chunks`.
    #[inline(always)]
    unsafe fn pos_unchecked(&self, below: bool, k: usize) -> [V; 3] {
        debug_assert!(k <= self.chunks);
        let row = if below { self.below } else { self.here };
        // SAFETY: `k ≤ chunks < pos_chunks` (checked in `new`).
        unsafe { row.pos(k) }
    }

    /// Family `fam`'s `(coefficient, rest length)` in chunk `k`'s lanes.
    ///
    /// # Safety
    ///
    /// `k < chunks`.
    #[inline(always)]
    unsafe fn spring_unchecked(&self, fam: Family, k: usize) -> (V, V) {
        debug_assert!(k < self.chunks);
        // SAFETY: `k < chunks ≤ springs.chunks()` (checked in `new`).
        unsafe { self.springs.at(fam, k) }
    }

    /// The positions around chunk `k` ([`Around`]). Panics unless `k < chunks`.
    #[inline(always)]
    pub fn around(&self, k: usize) -> Around<V> {
        assert!(k < self.chunks);
        // SAFETY: `k < chunks`, checked above, so `k + 1 ≤ chunks`.
        unsafe {
            Around {
                here: self.pos_unchecked(false, k),
                here_east: self.pos_unchecked(false, k + 1),
                below: self.pos_unchecked(true, k),
                below_east: self.pos_unchecked(true, k + 1),
            }
        }
    }

    /// Family `fam`'s `(coefficient, rest length)` in chunk `k`'s lanes. Panics unless
    /// `k < chunks`.
    #[inline(always)]
    pub fn spring(&self, fam: Family, k: usize) -> (V, V) {
        assert!(k < self.chunks);
        // SAFETY: `k < chunks`, checked above.
        unsafe { self.spring_unchecked(fam, k) }
    }
}

/// What a row's nodes hold besides their positions and velocities, and the forces that
/// arrive from the row above: chunk views of a row, made where the row's kernel is
/// prepared, each checked for `chunks` chunks.
pub(super) struct NodeViews<'a, V> {
    chunks: usize,
    inv_mass: Chunks<'a, V>,
    viscosity: Chunks<'a, V>,
    ext: Option<[Chunks<'a, V>; 3]>,
    /// What row r−1 sent down (`chunks + 2` groups, chunk `k` in group `k + 1`).
    arriving: &'a [Group<V>],
}

impl<'a, V: Vector> NodeViews<'a, V> {
    /// The node tables' row slices (each starts at the row's first node: lanes past the
    /// row read its padding, and are discarded), the external forces from node `base` on,
    /// and the arriving forces. Panics unless every view holds `chunks` chunks and
    /// `arriving` `chunks + 2` groups.
    #[inline(always)]
    pub fn new(
        chunks: usize,
        inv_mass: &'a [f32],
        viscosity: &'a [f32],
        ext: Option<[&'a [f32]; 3]>,
        base: usize,
        arriving: &'a [Group<V>],
    ) -> Self {
        assert!(arriving.len() >= chunks + 2);
        Self {
            chunks,
            inv_mass: Chunks::new(inv_mass, 0, chunks),
            viscosity: Chunks::new(viscosity, 0, chunks),
            #[allow(clippy::manual_map)] // `Option::map` would take a closure: see `FrontRow::new`
            ext: match ext {
                Some([x, y, z]) => Some([
                    Chunks::new(x, base, chunks),
                    Chunks::new(y, base, chunks),
                    Chunks::new(z, base, chunks),
                ]),
                None => None,
            },
            arriving,
        }
    }
}

/// Everything one row advance reads and writes besides its destination, checked for one
/// chunk count: handed out a chunk at a time by [`each_chunk`].
pub(super) struct RowViews<'v, 'a, V, S, P> {
    chunks: usize,
    pair: RowPair<'v, V, S, P>,
    nodes: &'v NodeViews<'a, V>,
    /// What this row sends down (`chunks + 2` groups).
    sent: &'v mut [Group<V>],
}

impl<'v, 'a, V: Vector, S: Source<V>, P: SpringValues<V>> RowViews<'v, 'a, V, S, P> {
    /// Panics unless `pair` and `nodes` were checked for `chunks` chunks, `chunks > 0`
    /// and `sent` holds `chunks + 2` groups.
    #[inline(always)]
    pub fn new(
        pair: RowPair<'v, V, S, P>,
        nodes: &'v NodeViews<'a, V>,
        sent: &'v mut [Group<V>],
    ) -> Self {
        let chunks = pair.chunks;
        assert!(chunks > 0 && nodes.chunks == chunks && sent.len() >= chunks + 2);
        Self {
            chunks,
            pair,
            nodes,
            sent,
        }
    }
}

/// Chunk `k` of the row being advanced: made by [`each_chunk`] only for `k < chunks`, so
/// its reads and writes need no check.
pub(super) struct Chunk<'c, 'v, 'a, V, S, P> {
    k: usize,
    views: &'c mut RowViews<'v, 'a, V, S, P>,
}

/// Chunk `k`'s node values and what arrived from the row above ([`Chunk::exchange`]).
pub(super) struct NodeChunk<'c, V> {
    pub inv_mass: V,
    pub viscosity: V,
    /// The S, SE and SW forces row r−1 sent down to chunk `k`.
    pub north: &'c Group<V>,
}

impl<'a, V: Vector, S: Source<V>, P: SpringValues<V>> Chunk<'_, '_, 'a, V, S, P> {
    /// The chunk's index in its row.
    #[inline(always)]
    pub fn index(&self) -> usize {
        self.k
    }

    /// The row's chunk count.
    #[inline(always)]
    pub fn chunks(&self) -> usize {
        self.views.chunks
    }

    /// The chunk's positions in the row.
    ///
    /// (One `[V; 3]` per call, not the four as one [`Around`]: returned together, two of
    /// the row below's axes went through the stack at the portable level, 4.6 more
    /// instructions per node update there; `docs/performance.md`.)
    #[inline(always)]
    pub fn here(&self) -> [V; 3] {
        // SAFETY: `k < chunks` (`Chunk`), the count `pair` was checked for.
        unsafe { self.views.pair.pos_unchecked(false, self.k) }
    }

    /// The positions of the chunk east of this one in the row.
    #[inline(always)]
    pub fn here_east(&self) -> [V; 3] {
        // SAFETY: `k + 1 ≤ chunks`, as `k < chunks` (`Chunk`).
        unsafe { self.views.pair.pos_unchecked(false, self.k + 1) }
    }

    /// The chunk's positions in the row below.
    #[inline(always)]
    pub fn below(&self) -> [V; 3] {
        // SAFETY: as in `here`.
        unsafe { self.views.pair.pos_unchecked(true, self.k) }
    }

    /// The positions of the chunk east of this one in the row below.
    #[inline(always)]
    pub fn below_east(&self) -> [V; 3] {
        // SAFETY: as in `here_east`.
        unsafe { self.views.pair.pos_unchecked(true, self.k + 1) }
    }

    /// Family `fam`'s `(coefficient, rest length)` in the chunk's lanes.
    #[inline(always)]
    pub fn spring(&self, fam: Family) -> (V, V) {
        // SAFETY: as in `here`.
        unsafe { self.views.pair.spring_unchecked(fam, self.k) }
    }

    /// The chunk's velocities.
    #[inline(always)]
    pub fn vel(&self) -> [V; 3] {
        debug_assert!(self.k < self.views.chunks);
        // SAFETY: `k < chunks ≤ vel_chunks` (checked in `RowPair::new`).
        unsafe { self.views.pair.here.vel(self.k) }
    }

    /// Leaves `[s, se, sw]` as what the chunk sends to the row below, and gives its node
    /// values and what arrived from the row above. (Three arguments, each written in
    /// place: a `Group` argument went through the stack frame on wasm, `docs/performance.md`.)
    #[inline(always)]
    pub fn exchange(&mut self, s: [V; 3], se: [V; 3], sw: [V; 3]) -> NodeChunk<'a, V> {
        let (k, v) = (self.k, &mut *self.views);
        let arriving: &'a [Group<V>] = v.nodes.arriving;
        debug_assert!(k < v.chunks);
        // SAFETY: `k < chunks`: within the node views (`chunks` chunks) and the force
        // rows (`chunks + 2` groups), as checked in `NodeViews::new` and `RowViews::new`.
        unsafe {
            let (inv_mass, viscosity) = (v.nodes.inv_mass.get(k), v.nodes.viscosity.get(k));
            let down = v.sent.get_unchecked_mut(k + 1);
            (down[0], down[1], down[2]) = (s, se, sw);
            NodeChunk {
                inv_mass,
                viscosity,
                north: arriving.get_unchecked(k + 1),
            }
        }
    }

    /// The chunk's external forces on `axis`, if the row has any.
    #[inline(always)]
    pub fn ext(&self, axis: usize) -> Option<V> {
        #[allow(clippy::manual_map)] // `Option::map` would take a closure: see `FrontRow::new`
        match &self.views.nodes.ext {
            // SAFETY: `k < chunks`, the views' length.
            Some(ext) => Some(unsafe { ext[axis].get(self.k) }),
            None => None,
        }
    }
}

/// The work on each chunk of a row, which [`each_chunk`] runs in order.
pub(super) trait ChunkWork<V: Vector, S, P> {
    /// The chunk's new `[x, y, z, vx, vy, vz]`. With `EDGE` false the chunk is not the
    /// row's last and has a row below.
    fn chunk<const EDGE: bool>(&mut self, c: Chunk<'_, '_, '_, V, S, P>) -> [V; 6];

    /// `new`, the chunk's values, went to the destination whole.
    fn stored(&mut self, new: &[V; 6]);
}

/// The cache line the non-temporal stores fill, in bytes (x86-64).
const CACHE_LINE: usize = 64;

/// Runs `work` on every chunk of the row of `views`, in order, and stores each chunk
/// but the last into `dst`; returns the last chunk's values, unstored.
///
/// Without a row below (`has_down` false) every chunk is an edge chunk; with one, the
/// chunks before the last run with no mask, no partial store and no call, and chunks
/// narrower than a cache line go in pairs that start on a pair boundary of the buffers
/// (`odd_start`: the row starts an odd number of chunks into its buffers): the
/// non-temporal stores of a large grid's last layer then fill each line in one iteration
/// at AVX2, or its halves in two in a row at SSE2 (AVX2 at 2048²: 1.4-1.6x the speed of
/// one chunk per iteration, or of pairs that straddle lines). A chunk a line wide
/// (AVX-512) goes alone, which keeps fewer registers live, and so does every chunk on
/// WebAssembly, which has no non-temporal store (the pairs' extra code was 9–19% of the npm
/// package's modules). The order, and so the results, are the same whatever the shape.
#[inline(always)]
pub(super) fn each_chunk<V, S, P, W, D>(
    views: &mut RowViews<'_, '_, V, S, P>,
    work: &mut W,
    dst: &mut D,
    has_down: bool,
    odd_start: bool,
) -> [V; 6]
where
    V: Vector,
    S: Source<V>,
    P: SpringValues<V>,
    W: ChunkWork<V, S, P>,
    D: Sink<V>,
{
    // Every `k` below is under `last = chunks − 1` (`chunks > 0`, `RowViews::new`), and
    // `last ≤ dst.whole()` (asserted): every chunk but the last is whole.
    let last = views.chunks - 1;
    assert!(last <= dst.whole());
    macro_rules! run {
        ($edge:literal, $k:expr) => {
            work.chunk::<$edge>(Chunk {
                k: $k,
                views: &mut *views,
            })
        };
    }
    macro_rules! put {
        ($k:expr, $new:expr) => {{
            // SAFETY: `k < last ≤ dst.whole()`.
            unsafe { dst.put($k, $new) };
            work.stored(&$new);
        }};
    }
    if has_down {
        let mut k = 0;
        if V::LANES * size_of::<f32>() < CACHE_LINE && !cfg!(target_family = "wasm") {
            if odd_start && last > 0 {
                let new = run!(false, 0);
                put!(0, new);
                k = 1;
            }
            while k + 1 < last {
                let a = run!(false, k);
                let b = run!(false, k + 1);
                put!(k, a);
                put!(k + 1, b);
                k += 2;
            }
        }
        while k < last {
            let new = run!(false, k);
            put!(k, new);
            k += 1;
        }
    } else {
        for k in 0..last {
            let new = run!(true, k);
            put!(k, new);
        }
    }
    run!(true, last)
}

/// Where a row's new `[x, y, z, vx, vy, vz]` go, a chunk at a time.
pub(super) trait Sink<V: Vector> {
    /// Whole chunks in the row.
    fn whole(&self) -> usize;

    /// Stores whole chunk `k`.
    ///
    /// # Safety
    ///
    /// `k < self.whole()`.
    unsafe fn put(&mut self, k: usize, new: [V; 6]);

    /// Stores the row's last chunk `k`, whole if `k < self.whole()`, else partial: only
    /// the lanes on in `real` belong to the row. Returns whether it was whole.
    fn put_last(&mut self, k: usize, new: [V; 6], real: V::Mask) -> bool;
}

/// A back-buffer row: its whole chunks and the columns after them.
pub(super) struct BackRow<'a, V> {
    full: usize,
    whole: [ChunksMut<'a, V>; 6],
    tail: [&'a mut [f32]; 6],
    /// Write the whole chunks with non-temporal stores.
    stream: bool,
}

impl<'a, V: Vector> BackRow<'a, V> {
    /// The first `cols` values of each of `dst`, written with non-temporal stores if
    /// `stream` and every buffer's row starts on a `size_of::<V>()` boundary (plain stores
    /// otherwise). Panics if a buffer is shorter than `cols`.
    #[inline(always)]
    pub fn new(dst: [&'a mut [f32]; 6], cols: usize, stream: bool) -> Self {
        let full = cols / V::LANES;
        let mut aligned = true;
        for d in &dst {
            aligned &= (d.as_ptr() as usize).is_multiple_of(size_of::<V>());
        }
        let [x, y, z, vx, vy, vz] = dst;
        let [x, y, z, vx, vy, vz] = [
            x[..cols].split_at_mut(full * V::LANES),
            y[..cols].split_at_mut(full * V::LANES),
            z[..cols].split_at_mut(full * V::LANES),
            vx[..cols].split_at_mut(full * V::LANES),
            vy[..cols].split_at_mut(full * V::LANES),
            vz[..cols].split_at_mut(full * V::LANES),
        ];
        BackRow {
            full,
            whole: [
                ChunksMut::new(x.0, 0, full),
                ChunksMut::new(y.0, 0, full),
                ChunksMut::new(z.0, 0, full),
                ChunksMut::new(vx.0, 0, full),
                ChunksMut::new(vy.0, 0, full),
                ChunksMut::new(vz.0, 0, full),
            ],
            tail: [x.1, y.1, z.1, vx.1, vy.1, vz.1],
            stream: stream && aligned,
        }
    }
}

impl<V: Vector> Sink<V> for BackRow<'_, V> {
    #[inline(always)]
    fn whole(&self) -> usize {
        self.full
    }

    #[inline(always)]
    unsafe fn put(&mut self, k: usize, new: [V; 6]) {
        debug_assert!(k < self.full);
        for (o, v) in self.whole.iter_mut().zip(new) {
            if self.stream {
                // SAFETY: `k < full`, each view's length; with `stream` each view starts on
                // a `size_of::<V>()` boundary (checked in `new`), and so does chunk `k`.
                unsafe { o.stream(k, v) };
            } else {
                // SAFETY: `k < full`, each view's length.
                unsafe { o.put(k, v) };
            }
        }
    }

    #[inline(always)]
    fn put_last(&mut self, k: usize, new: [V; 6], _: V::Mask) -> bool {
        if k < self.full {
            // SAFETY: `k < full`, checked above.
            unsafe { self.put(k, new) };
            return true;
        }
        for (t, v) in self.tail.iter_mut().zip(new) {
            v.write_to(t);
        }
        false
    }
}

/// A ring row's groups (`chunks + 2`, chunk `k` in group `k + 1`).
impl<V: Vector> Sink<V> for &mut [[V; 6]] {
    #[inline(always)]
    fn whole(&self) -> usize {
        self.len().saturating_sub(2)
    }

    #[inline(always)]
    unsafe fn put(&mut self, k: usize, new: [V; 6]) {
        debug_assert!(k + 2 < self.len());
        // SAFETY: `k < len − 2`, so group `k + 1` exists.
        unsafe { *self.get_unchecked_mut(k + 1) = new };
    }

    #[inline(always)]
    fn put_last(&mut self, k: usize, new: [V; 6], real: V::Mask) -> bool {
        // The lanes past the row stay zero; `whole` counts the last chunk of a ring row as
        // whole whatever its width, so the mask decides here (a chunk with every lane in
        // the row is stored as it is, as the chunks before it are).
        let g = &mut self[k + 1];
        let whole = V::all(real);
        if whole {
            *g = new;
        } else {
            for (g, v) in g.iter_mut().zip(new) {
                *g = V::keep(real, v);
            }
        }
        whole
    }
}
