//! The row kernel: one row advanced one step in one pass over its chunks of `V::LANES`
//! columns — its springs, each node's force sum, and symplectic Euler.
//!
//! [`advance_row`] evaluates each chunk's E spring inside the row and its S, SE and SW
//! springs down to row r+1, adds the springs arriving from row r−1 (evaluated one row
//! earlier and kept in a [`RowForces`]), integrates, and keeps the chunk's S, SE and SW
//! forces for row r+1. Spring forces never travel to main memory. A neighbour one column
//! off comes from aligned chunks and a register shuffle ([`Vector::east`],
//! [`Vector::west`]).
//!
//! The shuffles are few by choice of lanes. Every spring is evaluated in the lane of its
//! western end (a SW spring from its lower end, see [`RowKernel::chunk`]), so a lane needs
//! only two neighbours one column east (in its own row and the row below), and everything
//! a lane owes its east neighbour is summed first and crosses lanes in one shuffle per
//! axis: six position shuffles and three force shuffles per chunk. (Each spring seen from
//! its origin, and each family's arrivals moved on their own, would need eighteen; an
//! AVX2 shuffle across the two 128-bit halves is two instructions, on the same ports as
//! the arithmetic.)
//!
//! The loop is shaped by what the step's arithmetic needs per chunk of nodes: four
//! springs (each a square root and a division), nine force lanes sent down, nine
//! arriving, six values in and six out. What the shape gains is in `docs/performance.md`:
//! the last chunk of a row is peeled off ([`RowKernel::run_into`]) so the chunks before
//! it run with no mask, no partial store and no call; while every spring family is
//! uniform the eight shared values stay in registers; the scratch rows are chunk-major,
//! so one pointer reaches all of a chunk's lanes.
//!
//! A node's force is the same expression as in the scalar reference
//! ([`super::super::scalar::node_force`]), so the two agree bit for bit, whatever the
//! schedule and the level.

use super::scratch::{Group, Row, RowForces};
use super::StepConfig;
use crate::grid::Family;
use crate::simd::{Chunks, ChunksMut, Task, Vector};
use crate::springs::{Springs, Tables as SpringTables};
use crate::state::NodeTable;

/// The cache line the non-temporal stores fill, in bytes (x86-64).
const CACHE_LINE: usize = 64;

/// Everything a band reads: front buffers and tables, shared by all tasks.
pub(super) struct Inputs<'a, V: Vector> {
    pub cols: usize,
    pub rows: usize,
    pub pos: [&'a [f32]; 3],
    pub vel: [&'a [f32]; 3],
    /// Read a row at a time ([`NodeTable::row`]).
    pub inv_mass: &'a NodeTable,
    pub viscosity: &'a NodeTable,
    /// External forces, applied in the first step of the pass only.
    pub ext: Option<[&'a [f32]; 3]>,
    /// The rows whose nodes may hold an external force (`None`: every row). The others
    /// skip reading `ext`: they would add +0, which changes nothing but the sign of a −0
    /// force, and that sign is lost when the integration adds the step's acceleration,
    /// which is never −0 (`Surface::config` turns a −0 into +0; pinned nodes add +0).
    pub ext_rows: Option<&'a [bool]>,
    pub springs: &'a Springs,
    /// Each family's shared coefficient and rest length, when every family has them
    /// (the usual case: no spring was edited). The hot loop then keeps them in registers.
    pub uniform: Option<[(f32, f32); 4]>,
    pub cfg: StepConfig,
    /// The last level goes to the back buffers with non-temporal stores (see
    /// [`super::STREAM_MIN_NODES`]): every row then starts on a lane boundary.
    pub stream: bool,
    _lanes: std::marker::PhantomData<V>,
}

impl<'a, V: Vector> Inputs<'a, V> {
    #[allow(clippy::too_many_arguments)]
    pub fn new(
        cols: usize,
        rows: usize,
        pos: [&'a [f32]; 3],
        vel: [&'a [f32]; 3],
        inv_mass: &'a NodeTable,
        viscosity: &'a NodeTable,
        ext: Option<[&'a [f32]; 3]>,
        ext_rows: Option<&'a [bool]>,
        springs: &'a Springs,
        cfg: StepConfig,
        stream: bool,
    ) -> Self {
        Self {
            cols,
            rows,
            pos,
            vel,
            inv_mass,
            viscosity,
            ext,
            ext_rows,
            springs,
            uniform: springs.all_uniform(),
            cfg,
            stream: stream && cols.is_multiple_of(V::LANES),
            _lanes: std::marker::PhantomData,
        }
    }

    /// The external forces row `r` adds in a pass's first step, if it may hold any.
    #[inline(always)]
    fn ext_of_row(&self, r: usize) -> Option<[&'a [f32]; 3]> {
        let listed = match self.ext_rows {
            Some(rows) => rows[r],
            None => true,
        };
        if listed {
            self.ext
        } else {
            None
        }
    }

    /// Chunks in a row.
    #[inline(always)]
    pub fn chunks(&self) -> usize {
        self.cols.div_ceil(V::LANES)
    }

    /// Row `r` of the front buffers (level 0).
    #[inline(always)]
    pub fn front(&self, r: usize) -> FrontRow<'a, V> {
        // Written out, as is every view a row advance builds: a closure passed to
        // `array::map` is compiled on its own and became calls, several per row.
        let (chunks, start) = (self.chunks(), r * self.cols);
        let ([x, y, z], [vx, vy, vz]) = (self.pos, self.vel);
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

/// The lane masks of the springs that exist at the edges of a row, made inside the
/// kernel's instruction set.
#[derive(Clone, Copy)]
struct Edges<V: Vector> {
    /// Per family, the lanes of the last chunk that hold a spring (no E or SE spring
    /// leaves the last column, and no SW spring arrives at its lower end there: the lanes
    /// of a SW spring are those of its lower end; columns past the row are off).
    tail: [V::Mask; 4],
}

impl<V: Vector> Edges<V> {
    #[inline(always)]
    fn new(cols: usize) -> Self {
        let last = cols - (cols - 1) / V::LANES * V::LANES; // columns in the last chunk
        let [all, short] = [V::first_lanes(last), V::first_lanes(last - 1)];
        Self {
            tail: [short, all, short, short],
        }
    }

    /// Family `fam`'s forces `f` on chunk `k`, with exactly +0 in the lanes that hold no
    /// spring: in a row's last chunk, and every lane of S, SE and SW when there
    /// is no row below (`has_down` false). Those lanes hold other rows' nodes or padding,
    /// and get +0 like the reference's absent spring. A coefficient of 0 is not enough:
    /// `0 · ∞` is NaN once those positions are far apart (the `params` fuzz target found a
    /// surface beyond ~1e19 from the origin whose step the engine refused and the
    /// reference took).
    #[inline(always)]
    fn only_springs(
        &self,
        fam: Family,
        k: usize,
        chunks: usize,
        has_down: bool,
        f: [V; 3],
    ) -> [V; 3] {
        let none_below = fam != Family::E && !has_down;
        if none_below {
            only(V::first_lanes(0), f)
        } else if k + 1 == chunks {
            only(self.tail[fam as usize], f)
        } else {
            f
        }
    }
}

/// Where the rows of the level a row is advanced from live.
pub(super) enum Level<'a, V> {
    /// Level 0: the front buffers.
    Front,
    /// A level in flight: row `r` in slot `r % 2` of its ring.
    Ring(&'a [Row<V>; 2]),
}

impl<V> Clone for Level<'_, V> {
    fn clone(&self) -> Self {
        *self
    }
}

impl<V> Copy for Level<'_, V> {}

/// Where a row's new values go.
pub(super) enum RowOut<'a, V> {
    /// The back buffers' row: x, y, z, vx, vy, vz, `cols` values each.
    Back([&'a mut [f32]; 6]),
    /// A ring row.
    Ring(&'a mut Row<V>),
}

/// Chunk access to a row's positions and velocities, whatever its layout; `chunks` is the
/// row's chunk count. Chunk `chunks` (one past the row) is readable for positions: it
/// holds the next row's nodes, padding or zeros (as do the lanes past the row in the last
/// chunk), which only ever meet masked-off springs.
pub(super) trait Source<V>: Copy {
    /// Rows of this kind may carry external forces. Only the front buffers do: a pass
    /// applies them in its first step. (Known when the kernel is compiled, so a ring row's
    /// kernel has no test for them.)
    const EXTERNAL: bool;

    /// Positions of chunk `k`.
    ///
    /// # Safety
    ///
    /// `k ≤ chunks`.
    unsafe fn pos(self, k: usize) -> [V; 3];

    /// Velocities of chunk `k`.
    ///
    /// # Safety
    ///
    /// `k < chunks`.
    unsafe fn vel(self, k: usize) -> [V; 3];
}

/// A row of the front buffers as chunk views: positions `chunks + 1` chunks long,
/// velocities `chunks`.
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

impl<V: Vector> Source<V> for FrontRow<'_, V> {
    const EXTERNAL: bool = true;

    #[inline(always)]
    unsafe fn pos(self, k: usize) -> [V; 3] {
        let [x, y, z] = self.pos;
        // SAFETY: `k ≤ chunks`, the views hold `chunks + 1`.
        unsafe { [x.get(k), y.get(k), z.get(k)] }
    }

    #[inline(always)]
    unsafe fn vel(self, k: usize) -> [V; 3] {
        let [x, y, z] = self.vel;
        // SAFETY: `k < chunks`.
        unsafe { [x.get(k), y.get(k), z.get(k)] }
    }
}

/// A [`Row`]'s groups (`chunks + 2`; chunk `k` is group `k + 1`).
impl<V: Vector> Source<V> for &[[V; 6]] {
    const EXTERNAL: bool = false;

    #[inline(always)]
    unsafe fn pos(self, k: usize) -> [V; 3] {
        debug_assert!(k + 1 < self.len());
        // SAFETY: `k + 1 ≤ chunks + 1`.
        let g = unsafe { self.get_unchecked(k + 1) };
        [g[0], g[1], g[2]]
    }

    #[inline(always)]
    unsafe fn vel(self, k: usize) -> [V; 3] {
        debug_assert!(k + 2 < self.len());
        // SAFETY: `k + 1 ≤ chunks`.
        let g = unsafe { self.get_unchecked(k + 1) };
        [g[3], g[4], g[5]]
    }
}

/// Where [`RowKernel::run_into`] writes a row's new `[x, y, z, vx, vy, vz]`.
trait Sink<V> {
    /// Whole chunk `k`.
    ///
    /// # Safety
    ///
    /// `k < cols / LANES`.
    unsafe fn put(&mut self, k: usize, new: [V; 6]);

    /// The last chunk `k`, partial: only the lanes on in `real` belong to the row.
    fn put_partial(&mut self, k: usize, new: [V; 6], real: V::Mask)
    where
        V: Vector;
}

/// A back-buffer row: its whole chunks and the columns after them.
struct BackRow<'a, V> {
    whole: [ChunksMut<'a, V>; 6],
    tail: [&'a mut [f32]; 6],
    /// Write the whole chunks with non-temporal stores.
    stream: bool,
}

impl<'a, V: Vector> BackRow<'a, V> {
    #[inline(always)]
    fn new(dst: [&'a mut [f32]; 6], cols: usize, stream: bool) -> Self {
        let full = cols / V::LANES;
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
            whole: [
                ChunksMut::new(x.0, 0, full),
                ChunksMut::new(y.0, 0, full),
                ChunksMut::new(z.0, 0, full),
                ChunksMut::new(vx.0, 0, full),
                ChunksMut::new(vy.0, 0, full),
                ChunksMut::new(vz.0, 0, full),
            ],
            tail: [x.1, y.1, z.1, vx.1, vy.1, vz.1],
            stream,
        }
    }
}

impl<V: Vector> Sink<V> for BackRow<'_, V> {
    #[inline(always)]
    unsafe fn put(&mut self, k: usize, new: [V; 6]) {
        for (o, v) in self.whole.iter_mut().zip(new) {
            if self.stream {
                // SAFETY: `k < cols / LANES`, the length of `whole`; with `stream` every row
                // starts on a lane boundary of its 64-byte-aligned buffer (`Inputs::stream`).
                unsafe { o.stream(k, v) };
            } else {
                // SAFETY: `k < cols / LANES`, the length of `whole`.
                unsafe { o.put(k, v) };
            }
        }
    }

    #[inline(always)]
    fn put_partial(&mut self, _: usize, new: [V; 6], _: V::Mask) {
        for (t, v) in self.tail.iter_mut().zip(new) {
            v.write_to(t);
        }
    }
}

/// A [`Row`]'s groups.
impl<V: Vector> Sink<V> for &mut [[V; 6]] {
    #[inline(always)]
    unsafe fn put(&mut self, k: usize, new: [V; 6]) {
        debug_assert!(k + 2 < self.len());
        // SAFETY: `k + 1 ≤ chunks`.
        unsafe { *self.get_unchecked_mut(k + 1) = new };
    }

    #[inline(always)]
    fn put_partial(&mut self, k: usize, new: [V; 6], real: V::Mask) {
        // The lanes past the row stay zero.
        let g = &mut self[k + 1];
        for (g, v) in g.iter_mut().zip(new) {
            *g = V::keep(real, v);
        }
    }
}

/// Force on the `i` lanes from springs `i → j`: `c (L − L0) d / L`, zero where `L = 0`
/// (the same operations as [`super::super::scalar::spring_force`]).
#[inline(always)]
fn spring_force<V: Vector>(pi: [V; 3], pj: [V; 3], coef: V, rest: V) -> [V; 3] {
    let d = [pj[0] - pi[0], pj[1] - pi[1], pj[2] - pi[2]];
    let l2 = d[0] * d[0] + d[1] * d[1] + d[2] * d[2];
    let l = l2.sqrt();
    let s = V::keep(l2.gt(V::zero()), coef * (l - rest) / l);
    [s * d[0], s * d[1], s * d[2]]
}

/// One family's coefficients and rest lengths along one row, as chunk views of its
/// tables.
struct Table<'a, V> {
    coef: Chunks<'a, V>,
    rest: Chunks<'a, V>,
}

impl<V> Clone for Table<'_, V> {
    fn clone(&self) -> Self {
        *self
    }
}

impl<V> Copy for Table<'_, V> {}

impl<'a, V: Vector> Table<'a, V> {
    /// Family `fam`'s table for the `chunks` chunks of the row starting at node `base`,
    /// in the lanes the kernel evaluates its springs in: a SW spring in the lane of its
    /// lower end, one column west of its origin, so that table is read one node on. (The
    /// tables are padded past the last node by more than a chunk.)
    #[inline(always)]
    fn of(sp: &'a SpringTables, fam: Family, base: usize, chunks: usize) -> Self {
        let start = base + usize::from(fam == Family::SW);
        Table {
            coef: Chunks::new(&sp.coef[fam as usize], start, chunks),
            rest: Chunks::new(&sp.rest[fam as usize], start, chunks),
        }
    }

    /// [`Table::of`] for every family. (Written out: a closure passed to `array::map`
    /// is compiled on its own, and became four calls per row.)
    #[inline(always)]
    fn all(sp: &'a SpringTables, base: usize, chunks: usize) -> [Self; 4] {
        let [e, s, se, sw] = Family::ALL;
        [
            Self::of(sp, e, base, chunks),
            Self::of(sp, s, base, chunks),
            Self::of(sp, se, base, chunks),
            Self::of(sp, sw, base, chunks),
        ]
    }

    /// `(coefficient, rest length)` of chunk `k`.
    ///
    /// # Safety
    ///
    /// `k < chunks`.
    #[inline(always)]
    unsafe fn at(self, k: usize) -> (V, V) {
        // SAFETY: the caller guarantees `k` is in range of both views.
        unsafe { (self.coef.get(k), self.rest.get(k)) }
    }
}

/// Where a row's springs take their coefficient and rest length from: the kernel is
/// compiled once for each kind.
trait SpringValues<V> {
    /// `(coefficient, rest length)` of family `fam`'s springs in chunk `k`'s lanes.
    ///
    /// # Safety
    ///
    /// `k < chunks` of the row.
    unsafe fn at(&self, fam: Family, k: usize) -> (V, V);
}

/// Every family's springs share one coefficient and rest length ([`Inputs::uniform`]):
/// the eight values stay in registers and no table is read.
struct Shared<V>([(V, V); 4]);

impl<V: Vector> Shared<V> {
    #[inline(always)]
    fn new([e, s, se, sw]: [(f32, f32); 4]) -> Self {
        Self([splat2(e), splat2(s), splat2(se), splat2(sw)])
    }
}

impl<V: Vector> SpringValues<V> for Shared<V> {
    #[inline(always)]
    unsafe fn at(&self, fam: Family, _k: usize) -> (V, V) {
        self.0[fam as usize]
    }
}

/// Each spring's own values, read from the families' tables along the row.
struct Tables<'a, V>([Table<'a, V>; 4]);

impl<V: Vector> SpringValues<V> for Tables<'_, V> {
    #[inline(always)]
    unsafe fn at(&self, fam: Family, k: usize) -> (V, V) {
        // SAFETY: `k < chunks` (the caller's contract), within the table views.
        unsafe { self.0[fam as usize].at(k) }
    }
}

/// Evaluates the S, SE and SW springs from row `r` of level `from` down to row r+1 (zero
/// on the last row) into `out`: what row r sends to the next row. Only for the row just
/// above a band's rows; [`advance_row`] does this for its own rows on the way. Inlined into
/// the band, inside the level's instruction set, like [`advance_row`].
#[inline(always)]
pub(super) fn down_springs<V: Vector>(
    inp: &Inputs<V>,
    r: usize,
    from: Level<V>,
    out: &mut RowForces<V>,
) {
    if r + 1 == inp.rows {
        out.zero_down();
        return;
    }
    match from {
        Level::Front => springs_down(inp, r, inp.front(r), inp.front(r + 1), out),
        Level::Ring(ring) => {
            let (here, down) = (
                ring[r % 2].groups(inp.cols),
                ring[(r + 1) % 2].groups(inp.cols),
            );
            springs_down(inp, r, here, down, out)
        }
    }
}

/// Where [`springs_down`] takes its values: the tables if the springs have them, else the
/// shared values. One copy of the loop for both, with a branch per chunk: this runs once
/// per band and level, and a second copy of the loop, as [`RowKernel::advance`] has,
/// added a quarter to the crate's compile time for no measurable speed.
enum DownValues<'a, V> {
    Tables(Tables<'a, V>),
    Shared(Shared<V>),
}

impl<V: Vector> SpringValues<V> for DownValues<'_, V> {
    #[inline(always)]
    unsafe fn at(&self, fam: Family, k: usize) -> (V, V) {
        match self {
            // SAFETY: the caller's contract, passed on.
            Self::Tables(t) => unsafe { t.at(fam, k) },
            // SAFETY: as above.
            Self::Shared(s) => unsafe { s.at(fam, k) },
        }
    }
}

/// [`down_springs`] from row `here` to row `down`.
#[inline(always)]
fn springs_down<V: Vector, S: Source<V>>(
    inp: &Inputs<V>,
    r: usize,
    here: S,
    down: S,
    out: &mut RowForces<V>,
) {
    let chunks = inp.chunks();
    let springs = match (inp.springs.tables(), inp.uniform) {
        (Some(t), _) => DownValues::Tables(Tables(Table::all(t, r * inp.cols, chunks))),
        (None, Some(shared)) => DownValues::Shared(Shared::new(shared)),
        (None, None) => unreachable!("springs that differ have tables"),
    };
    let edges = Edges::<V>::new(inp.cols);
    let groups = out.groups_mut(inp.cols);
    for (k, group) in groups[1..=chunks].iter_mut().enumerate() {
        // SAFETY: `k < chunks`; positions are readable up to chunk `chunks`.
        let (h0, h1, d0, d1) =
            unsafe { (here.pos(k), here.pos(k + 1), down.pos(k), down.pos(k + 1)) };
        // Each spring from the end its force is kept for (see `RowKernel::chunk`).
        let ends = [(h0, d0), (h0, east3(d0, d1)), (d0, east3(h0, h1))];
        for (i, fam) in [Family::S, Family::SE, Family::SW].into_iter().enumerate() {
            // SAFETY: `k < chunks` of the row.
            let (coef, rest) = unsafe { springs.at(fam, k) };
            let f = spring_force(ends[i].0, ends[i].1, coef, rest);
            group[i] = edges.only_springs(fam, k, chunks, true, f);
        }
    }
}

/// Advances row `r` one level: evaluates its four springs (E inside the row, S, SE, SW
/// down to row r+1, none on the last row), sums each node's force with the springs
/// arriving from row r−1 (`prev`, evaluated one row earlier), integrates from level
/// `from` into `dst`, and leaves the S, SE and SW forces in `next` for row r+1. Returns
/// `false` if a new value is not finite. The row's external forces ([`Inputs::ext_of_row`])
/// are added when advancing from [`Level::Front`]: a pass applies them in its first step.
///
/// One pass over the row's chunks: what the chunk before sends east, and the neighbour
/// chunks the shuffles need, stay in registers. The last chunk (and every chunk of the
/// grid's last row) masks the lanes without a spring; the chunks before it run a loop
/// with no mask, no partial store and no call, so nothing forces the compiler to spill
/// the registers it carries from chunk to chunk.
///
/// Called inside the level's instruction set (the band has entered it); the row's kernel
/// enters it again as a function of its own ([`RowRun`], one per kind of source row,
/// springs and destination), so that the band's function stays small enough to compile
/// quickly.
#[inline(always)]
pub(super) fn advance_row<V: Vector>(
    inp: &Inputs<V>,
    r: usize,
    from: Level<V>,
    prev: &RowForces<V>,
    next: &mut RowForces<V>,
    dst: RowOut<V>,
) -> bool {
    // On the last row the "row below" is the row itself: its springs are masked off.
    let has_down = r + 1 < inp.rows;
    let below = if has_down { r + 1 } else { r };
    let sent = next.groups_mut(inp.cols);
    let arriving = prev.groups(inp.cols);
    match from {
        Level::Front => {
            let (h, d) = (inp.front(r), inp.front(below));
            let kernel = RowKernel::new(inp, r, h, d, has_down, arriving);
            kernel.advance(sent, dst)
        }
        Level::Ring(ring) => {
            let (h, d) = (
                ring[r % 2].groups(inp.cols),
                ring[below % 2].groups(inp.cols),
            );
            let kernel = RowKernel::new(inp, r, h, d, has_down, arriving);
            kernel.advance(sent, dst)
        }
    }
}

/// One row's run: [`RowKernel::run_into`] for its springs and destination, entered as a
/// function of its own (see [`advance_row`]).
struct RowRun<'k, 'a, 'b, V: Vector, S, P> {
    kernel: &'k RowKernel<'a, 'b, V, S>,
    springs: P,
    sent: &'k mut [Group<V>],
    dst: RowOut<'k, V>,
}

impl<V: Vector, S: Source<V>, P: SpringValues<V>> Task<V> for RowRun<'_, '_, '_, V, S, P> {
    type Output = bool;

    #[inline(always)]
    fn run(self) -> bool {
        let RowRun {
            kernel,
            springs,
            sent,
            dst,
        } = self;
        let cols = kernel.inp.cols;
        match dst {
            RowOut::Back(b) => {
                kernel.run_into(&springs, sent, BackRow::new(b, cols, kernel.inp.stream))
            }
            RowOut::Ring(row) => kernel.run_into(&springs, sent, row.groups_mut(cols)),
        }
    }
}

/// The chunk views one row's advance reads (see [`advance_row`]).
struct RowKernel<'a, 'b, V: Vector, S> {
    inp: &'a Inputs<'b, V>,
    chunks: usize,
    has_down: bool,
    /// The row starts an odd number of chunks into its buffers, so a pair of chunks from
    /// chunk 0 would straddle a line of the back buffers (see [`RowKernel::run_into`]).
    /// It matters only for streamed rows, which start on a chunk boundary; elsewhere it
    /// changes the loop's shape, never its results.
    odd_start: bool,
    /// The row and the row below.
    h: S,
    d: S,
    /// The row's first node.
    base: usize,
    inv_mass: Chunks<'a, V>,
    viscosity: Chunks<'a, V>,
    /// The row's external forces, if its source carries them ([`Source::EXTERNAL`]) and
    /// it may hold any ([`Inputs::ext_of_row`]).
    ext: Option<[Chunks<'a, V>; 3]>,
    /// What row r−1 sent down ([`RowForces`]: `chunks + 2` groups).
    arriving: &'a [Group<V>],
    dt: f32,
    g: [f32; 3],
}

impl<'a, 'b, V: Vector, S: Source<V>> RowKernel<'a, 'b, V, S> {
    #[inline(always)]
    fn new(
        inp: &'a Inputs<'b, V>,
        r: usize,
        h: S,
        d: S,
        has_down: bool,
        arriving: &'a [Group<V>],
    ) -> Self {
        let chunks = inp.chunks();
        let base = r * inp.cols;
        let node = |s| Chunks::new(s, base, chunks);
        let ext = if S::EXTERNAL { inp.ext_of_row(r) } else { None };
        RowKernel {
            inp,
            chunks,
            has_down,
            odd_start: (base / V::LANES) % 2 == 1,
            h,
            d,
            base,
            // A table's row slice starts at the row's first node, whichever way the table
            // stores it; lanes past the row read its padding, and are discarded.
            inv_mass: Chunks::new(inp.inv_mass.row(r), 0, chunks),
            viscosity: Chunks::new(inp.viscosity.row(r), 0, chunks),
            #[allow(clippy::manual_map)] // `Option::map` would take a closure: see `front`
            ext: match ext {
                Some([x, y, z]) => Some([node(x), node(y), node(z)]),
                None => None,
            },
            arriving,
            dt: inp.cfg.dt,
            g: inp.cfg.accel,
        }
    }

    /// Runs the row into `dst` with the kernel for its springs and destination (entered
    /// as a function of its own, [`RowRun`]), and leaves what it sends down in `sent`.
    #[inline(always)]
    fn advance(&self, sent: &mut [Group<V>], dst: RowOut<V>) -> bool {
        match self.inp.uniform {
            Some(shared) => V::enter(RowRun {
                kernel: self,
                springs: Shared::new(shared),
                sent,
                dst,
            }),
            None => V::enter(RowRun {
                kernel: self,
                springs: Tables(Table::all(
                    self.inp
                        .springs
                        .tables()
                        .expect("springs that differ have tables"),
                    self.base,
                    self.chunks,
                )),
                sent,
                dst,
            }),
        }
    }

    /// Runs every chunk of the row (see [`advance_row`]) and writes the new values into
    /// `dst`, each spring's coefficient and rest length taken from `springs`.
    #[inline(always)]
    fn run_into<P: SpringValues<V>>(
        &self,
        springs: &P,
        sent: &mut [Group<V>],
        mut dst: impl Sink<V>,
    ) -> bool {
        let chunks = self.chunks;
        let full = self.inp.cols / V::LANES;
        let c = Consts::<V>::new(self);
        let mut finite = V::zero();
        // The forces the chunk before sends east (zero before column 0: no node there).
        let mut west = [V::zero(); 3];
        let last = chunks - 1;
        if self.has_down {
            let mut k = 0;
            // Chunks narrower than a cache line go in pairs that start on a pair boundary
            // of the buffers: the non-temporal stores of a large grid's last level then
            // fill each line in one iteration at AVX2, or its halves in two in a row at
            // SSE2 (AVX2 at 2048²: 1.4-1.6x the speed of one chunk per iteration, or of
            // pairs that straddle lines). A chunk a line wide (AVX-512) goes alone, which
            // keeps fewer registers live.
            if V::LANES * size_of::<f32>() < CACHE_LINE {
                if self.odd_start && last > 0 {
                    // SAFETY: `0 < last < chunks`.
                    let new = unsafe { self.chunk::<false, P>(&c, springs, 0, &mut west, sent) };
                    store(&mut dst, full, 0, new, &mut finite);
                    k = 1;
                }
                while k + 1 < last {
                    // SAFETY: `k < k + 1 < chunks`.
                    let a = unsafe { self.chunk::<false, P>(&c, springs, k, &mut west, sent) };
                    // SAFETY: as above.
                    let b = unsafe { self.chunk::<false, P>(&c, springs, k + 1, &mut west, sent) };
                    store(&mut dst, full, k, a, &mut finite);
                    store(&mut dst, full, k + 1, b, &mut finite);
                    k += 2;
                }
            }
            while k < last {
                // SAFETY: `k < chunks`.
                let new = unsafe { self.chunk::<false, P>(&c, springs, k, &mut west, sent) };
                store(&mut dst, full, k, new, &mut finite);
                k += 1;
            }
        } else {
            for k in 0..last {
                // SAFETY: `k < chunks`.
                let new = unsafe { self.chunk::<true, P>(&c, springs, k, &mut west, sent) };
                store(&mut dst, full, k, new, &mut finite);
            }
        }
        // SAFETY: `last < chunks`.
        let new = unsafe { self.chunk::<true, P>(&c, springs, last, &mut west, sent) };
        if last < full {
            store(&mut dst, full, last, new, &mut finite);
        } else {
            // A partial chunk: only the row's own lanes are written and checked.
            let real = c.edges.tail[Family::S as usize];
            dst.put_partial(last, new, real);
            for x in &new[..3] {
                finite += V::keep(real, *x * V::zero());
            }
        }
        !finite.any_nan()
    }

    /// Family `fam`'s spring force on the `from` end of its springs in chunk `k`'s lanes,
    /// the other end at `to`; with `EDGE`, only in the lanes that hold such a spring.
    ///
    /// Inlined always in release builds. In builds with debug assertions it is only
    /// offered for inlining, as is [`RowKernel::chunk`]: unoptimised, every inlined copy
    /// keeps its own stack slots, and the level entry that inlined them all needed 2–3 MB
    /// of stack, more than a thread of rayon's pool has.
    ///
    /// # Safety
    ///
    /// `k < chunks`.
    #[cfg_attr(not(debug_assertions), inline(always))]
    #[cfg_attr(debug_assertions, inline)]
    unsafe fn spring<const EDGE: bool, P: SpringValues<V>>(
        &self,
        c: &Consts<V>,
        springs: &P,
        k: usize,
        fam: Family,
        from: [V; 3],
        to: [V; 3],
    ) -> [V; 3] {
        // SAFETY: `k < chunks` (the caller's contract).
        let (coef, rest) = unsafe { springs.at(fam, k) };
        let f = spring_force(from, to, coef, rest);
        if EDGE {
            c.edges.only_springs(fam, k, self.chunks, self.has_down, f)
        } else {
            f
        }
    }

    /// Chunk `k`: its springs, its new positions and velocities `[x, y, z, vx, vy, vz]`.
    ///
    /// Each lane `i` evaluates four springs: E (node i to i+1), S (to the node below),
    /// SE (to the node below i+1), and the SW spring that leaves node i+1 for the node
    /// below i, evaluated from its lower end. Its S, SE and SW forces go into `sent` for
    /// row r+1 (S and SE as forces on this row's nodes, SW on the row below's). A node's
    /// force is then the sum of [`scalar::node_force`](super::super::scalar::node_force):
    /// its own E, S and SE springs, the north neighbour's S spring and the SW spring
    /// leaving the north-east neighbour, all in its own lane,
    /// minus what the lane to its west sends east — that lane's E and SW forces and its
    /// north neighbour's SE — summed there and moved one lane with a single shuffle per
    /// axis. `west` carries that sum from chunk `k − 1` to chunk `k`. With `EDGE` false
    /// the chunk is not the last and has a row below: every lane holds a spring of every
    /// family.
    ///
    /// # Safety
    ///
    /// `k < chunks`. (The sources are readable up to chunk `chunks`, the node and table
    /// views hold `chunks` chunks, the arriving groups and `sent` `chunks + 2` groups,
    /// chunk `k` being group `k + 1`.)
    /// (Inlined as [`RowKernel::spring`] is.)
    #[cfg_attr(not(debug_assertions), inline(always))]
    #[cfg_attr(debug_assertions, inline)]
    unsafe fn chunk<const EDGE: bool, P: SpringValues<V>>(
        &self,
        c: &Consts<V>,
        springs: &P,
        k: usize,
        west: &mut [V; 3],
        sent: &mut [Group<V>],
    ) -> [V; 6] {
        let (h, d) = (self.h, self.d);
        // SAFETY: `k + 1 ≤ chunks`.
        let (h0, d0, h1, d1) = unsafe { (h.pos(k), d.pos(k), h.pos(k + 1), d.pos(k + 1)) };
        let h_east = east3(h0, h1);
        // SAFETY: `k < chunks`.
        let (e, s, se, sw) = unsafe {
            (
                self.spring::<EDGE, P>(c, springs, k, Family::E, h0, h_east),
                self.spring::<EDGE, P>(c, springs, k, Family::S, h0, d0),
                self.spring::<EDGE, P>(c, springs, k, Family::SE, h0, east3(d0, d1)),
                self.spring::<EDGE, P>(c, springs, k, Family::SW, d0, h_east),
            )
        };
        // SAFETY: `k < chunks`, within the node views.
        let (inv_mass, viscosity) = unsafe { (self.inv_mass.get(k), self.viscosity.get(k)) };
        let free = inv_mass.gt(V::zero());
        debug_assert!(k + 1 < self.arriving.len() && k + 1 < sent.len());
        // SAFETY: `k + 1 ≤ chunks`, within the arriving groups and `sent`.
        let north = unsafe {
            *sent.get_unchecked_mut(k + 1) = [s, se, sw];
            self.arriving.get_unchecked(k + 1)
        };
        let mut new = [V::zero(); 6];
        for axis in 0..3 {
            // What this lane sends east, and what arrives from the west.
            let east_bound = (e[axis] + sw[axis]) + north[1][axis];
            let from_west = V::west(west[axis], east_bound);
            // Same expression as `scalar::node_force`.
            let mut force =
                (((e[axis] + s[axis]) + se[axis]) + (north[2][axis] - north[0][axis])) - from_west;
            if let (true, Some(ext)) = (S::EXTERNAL, self.ext) {
                // SAFETY: `k < chunks`, within the node views.
                force += unsafe { ext[axis].get(k) };
            }
            // SAFETY: `k < chunks`.
            let v = unsafe { h.vel(k) }[axis];
            let acc = (force - viscosity * v) * inv_mass + V::keep(free, c.g[axis]);
            let v1 = v + acc * c.dt;
            new[axis] = h0[axis] + v1 * c.dt;
            new[axis + 3] = v1;
            west[axis] = east_bound;
        }
        // Vertical: calm water is exactly calm, as in `scalar::calm`.
        new[1] = calm(new[1], c.calm);
        new[4] = calm(new[4], c.calm);
        new
    }
}

/// The row's constants as lanes, made once per row inside the kernel's instruction set.
struct Consts<V: Vector> {
    edges: Edges<V>,
    dt: V,
    g: [V; 3],
    calm: V,
}

impl<V: Vector> Consts<V> {
    #[inline(always)]
    fn new<S>(k: &RowKernel<'_, '_, V, S>) -> Self {
        Self {
            edges: Edges::new(k.inp.cols),
            dt: V::splat(k.dt),
            g: [V::splat(k.g[0]), V::splat(k.g[1]), V::splat(k.g[2])],
            calm: V::splat(crate::forces::CALM),
        }
    }
}

/// `(coefficient, rest length)` as lanes.
///
/// The kernel calls named `#[inline(always)]` functions, never closures: a closure is
/// compiled on its own, without the level's target features, and the intrinsics in it
/// become calls (seen as a 10× slower AVX2 step before they were taken out).
#[inline(always)]
fn splat2<V: Vector>((c, r): (f32, f32)) -> (V, V) {
    (V::splat(c), V::splat(r))
}

/// `x`, or +0 in the lanes where it is smaller in magnitude than `limit` (NaN stays):
/// [`super::super::scalar::calm`] in lanes.
#[inline(always)]
fn calm<V: Vector>(x: V, limit: V) -> V {
    V::keep(!x.abs().lt(limit), x)
}

/// [`Vector::east`] of each axis.
#[inline(always)]
fn east3<V: Vector>(lo: [V; 3], hi: [V; 3]) -> [V; 3] {
    [
        V::east(lo[0], hi[0]),
        V::east(lo[1], hi[1]),
        V::east(lo[2], hi[2]),
    ]
}

/// `f` in the lanes on in `m`, +0 elsewhere.
#[inline(always)]
fn only<V: Vector>(m: V::Mask, f: [V; 3]) -> [V; 3] {
    [V::keep(m, f[0]), V::keep(m, f[1]), V::keep(m, f[2])]
}

/// Stores chunk `k` (whole: `k < full`) of a row into `dst` and folds its positions into
/// the finiteness check: `x·0` is 0 for finite x and NaN otherwise, and x' is non-finite
/// whenever v' is.
#[inline(always)]
fn store<V: Vector>(dst: &mut impl Sink<V>, full: usize, k: usize, new: [V; 6], finite: &mut V) {
    debug_assert!(k < full);
    // SAFETY: `k < full`: every caller stores a chunk before the last, or the last when it
    // is whole.
    unsafe { dst.put(k, new) };
    *finite += new[0] * V::zero();
    *finite += new[1] * V::zero();
    *finite += new[2] * V::zero();
}
