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
//! The loop is shaped by what the step's arithmetic needs per chunk of nodes: four
//! springs (each a square root and a division), nine force lanes sent down, nine
//! arriving, six values in and six out. What the shape gains is in `docs/performance.md`:
//! the first and last chunk of a row are peeled off ([`RowKernel::run_into`]) so the
//! chunks between run with no mask, no partial store and no call; while every spring
//! family is uniform the eight shared values stay in registers; the scratch rows are
//! chunk-major, so one pointer reaches all of a chunk's lanes.
//!
//! A node's force is the same expression as in the scalar reference
//! ([`super::super::scalar::node_force`]), so the two agree bit for bit, whatever the
//! schedule and the level.

use super::scratch::{Group, Row, RowForces};
use super::StepConfig;
use crate::grid::Family;
use crate::simd::{Chunks, ChunksMut, Task, Vector};
use crate::springs::Springs;

/// Everything a band reads: front buffers and tables, shared by all tasks.
pub(super) struct Inputs<'a, V: Vector> {
    pub cols: usize,
    pub rows: usize,
    pub pos: [&'a [f32]; 3],
    pub vel: [&'a [f32]; 3],
    pub inv_mass: &'a [f32],
    pub viscosity: &'a [f32],
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
        inv_mass: &'a [f32],
        viscosity: &'a [f32],
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
    pub fn ext_of_row(&self, r: usize) -> Option<[&'a [f32]; 3]> {
        self.ext
            .filter(|_| self.ext_rows.is_none_or(|rows| rows[r]))
    }

    /// Chunks in a row.
    #[inline(always)]
    pub fn chunks(&self) -> usize {
        self.cols.div_ceil(V::LANES)
    }

    /// Row `r` of the front buffers (level 0).
    #[inline(always)]
    pub fn front(&self, r: usize) -> FrontRow<'a, V> {
        let chunks = self.chunks();
        FrontRow {
            pos: self.pos.map(|p| Chunks::new(p, r * self.cols, chunks + 1)),
            vel: self.vel.map(|v| Chunks::new(v, r * self.cols, chunks)),
        }
    }
}

/// The lane masks of the springs that exist at the edges of a row, made inside the
/// kernel's instruction set.
#[derive(Clone, Copy)]
struct Edges<V: Vector> {
    /// Per family, the lanes of the last chunk that hold a spring (no E or SE spring
    /// leaves the last column; columns past the row are off).
    tail: [V::Mask; 4],
    /// The lanes of the first chunk that hold a SW spring (none leaves column 0).
    head_sw: V::Mask,
}

impl<V: Vector> Edges<V> {
    #[inline(always)]
    fn new(cols: usize) -> Self {
        let last = cols - (cols - 1) / V::LANES * V::LANES; // columns in the last chunk
        let [all, short] = [V::first_lanes(last), V::first_lanes(last - 1)];
        Self {
            tail: [short, all, short, all],
            head_sw: !V::first_lanes(1),
        }
    }

    /// Which lanes of chunk `k` of `chunks` hold a spring of family `fam`.
    #[inline(always)]
    fn exists(&self, fam: Family, k: usize, chunks: usize) -> V::Mask {
        let mut m = if k + 1 == chunks {
            self.tail[fam as usize]
        } else {
            V::all_lanes()
        };
        if fam == Family::SW && k == 0 {
            m &= self.head_sw;
        }
        m
    }

    /// Family `fam`'s forces `f` on chunk `k`, with exactly +0 in the lanes that hold no
    /// spring: in a row's first and last chunk, and every lane of S, SE and SW when there
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
        let edge = k + 1 == chunks || (fam == Family::SW && k == 0);
        let none_below = fam != Family::E && !has_down;
        if !edge && !none_below {
            return f;
        }
        let exists = match (none_below, edge) {
            (true, _) => V::first_lanes(0),
            (false, true) => self.exists(fam, k, chunks),
            (false, false) => V::all_lanes(),
        };
        only(exists, f)
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
        let [x, y, z, vx, vy, vz] = dst.map(|d| d[..cols].split_at_mut(full * V::LANES));
        BackRow {
            whole: [x.0, y.0, z.0, vx.0, vy.0, vz.0].map(|d| ChunksMut::new(d, 0, full)),
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
            *g = V::select(real, v, V::zero());
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
    let s = V::select(l2.gt(V::zero()), coef * (l - rest) / l, V::zero());
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
    /// Family `fam`'s table for the `chunks` chunks of the row starting at node `base`.
    #[inline(always)]
    fn of(sp: &'a Springs, fam: Family, base: usize, chunks: usize) -> Self {
        Table {
            coef: Chunks::new(&sp.coef[fam as usize], base, chunks),
            rest: Chunks::new(&sp.rest[fam as usize], base, chunks),
        }
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

/// Evaluates the S, SE and SW springs from row `r` of level `from` down to row r+1 (zero
/// on the last row) into `out`: what row r sends to the next row. Only for the row just
/// above a band's rows; [`advance_row`] does this for its own rows on the way.
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
        Level::Front => V::enter(DownSprings {
            inp,
            r,
            here: inp.front(r),
            down: inp.front(r + 1),
            out,
        }),
        Level::Ring(ring) => {
            let [here, down] = [r % 2, (r + 1) % 2].map(|i| ring[i].groups(inp.cols));
            V::enter(DownSprings {
                inp,
                r,
                here,
                down,
                out,
            })
        }
    }
}

/// [`down_springs`] from row `here` to row `down`.
struct DownSprings<'a, 'b, V: Vector, S> {
    inp: &'a Inputs<'b, V>,
    r: usize,
    here: S,
    down: S,
    out: &'a mut RowForces<V>,
}

impl<V: Vector, S: Source<V>> Task<V> for DownSprings<'_, '_, V, S> {
    type Output = ();

    #[inline(always)]
    fn run(self) {
        let DownSprings {
            inp,
            r,
            here,
            down,
            out,
        } = self;
        let chunks = inp.chunks();
        let edges = Edges::<V>::new(inp.cols);
        let groups = out.groups_mut(inp.cols);
        let tables = [Family::S, Family::SE, Family::SW]
            .map(|fam| Table::<V>::of(inp.springs, fam, r * inp.cols, chunks));
        for (k, group) in groups[1..=chunks].iter_mut().enumerate() {
            // SAFETY: `k < chunks`; positions are readable up to chunk `chunks`, and the
            // west chunk `k − 1` is read only for `k > 0`.
            let (h, d0, d1, d_west) = unsafe {
                // Lane 0 of chunk 0 has no SW spring (column 0): its west neighbour is
                // never used.
                let d_west = if k == 0 {
                    [V::zero(); 3]
                } else {
                    down.pos(k - 1)
                };
                (here.pos(k), down.pos(k), down.pos(k + 1), d_west)
            };
            let there = [d0, east3(d0, d1), west3(d_west, d0)];
            for (i, fam) in [Family::S, Family::SE, Family::SW].into_iter().enumerate() {
                // SAFETY: `k < chunks`, within the table views.
                let (coef, rest) = unsafe { tables[i].at(k) };
                let f = spring_force(h, there[i], coef, rest);
                group[i] = edges.only_springs(fam, k, chunks, true, f);
            }
        }
    }
}

/// Advances row `r` one level: evaluates its four springs (E inside the row, S, SE, SW
/// down to row r+1, none on the last row), sums each node's force with the springs
/// arriving from row r−1 (`prev`, evaluated one row earlier), integrates from level
/// `from` into `dst`, and leaves the S, SE and SW forces in `next` for row r+1. Returns
/// `false` if a new value is not finite.
///
/// One pass over the row's chunks: the E force of the chunk before, and the neighbour
/// chunks the shuffles need, stay in registers. The first and last chunk (and every chunk
/// of the grid's last row) mask the lanes without a spring; the chunks between them run a
/// loop with no mask, no partial store and no call, so nothing forces the compiler to
/// spill the registers it carries from chunk to chunk.
#[inline(always)]
pub(super) fn advance_row<V: Vector>(
    inp: &Inputs<V>,
    r: usize,
    from: Level<V>,
    ext: Option<[&[f32]; 3]>,
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
            let kernel = RowKernel::new(inp, r, h, d, has_down, ext, arriving);
            V::enter(AdvanceRow { kernel, sent, dst })
        }
        Level::Ring(ring) => {
            let [h, d] = [r % 2, below % 2].map(|i| ring[i].groups(inp.cols));
            let kernel = RowKernel::new(inp, r, h, d, has_down, ext, arriving);
            V::enter(AdvanceRow { kernel, sent, dst })
        }
    }
}

/// [`advance_row`]'s work, run inside the level's instruction set.
struct AdvanceRow<'a, 'b, V: Vector, S> {
    kernel: RowKernel<'a, 'b, V, S>,
    sent: &'a mut [Group<V>],
    dst: RowOut<'a, V>,
}

impl<V: Vector, S: Source<V>> Task<V> for AdvanceRow<'_, '_, V, S> {
    type Output = bool;

    #[inline(always)]
    fn run(self) -> bool {
        let AdvanceRow { kernel, sent, dst } = self;
        let cols = kernel.inp.cols;
        match (dst, kernel.uniform.is_some()) {
            (RowOut::Back(b), true) => {
                kernel.run_into::<true>(sent, BackRow::new(b, cols, kernel.inp.stream))
            }
            (RowOut::Back(b), false) => {
                kernel.run_into::<false>(sent, BackRow::new(b, cols, kernel.inp.stream))
            }
            (RowOut::Ring(row), true) => kernel.run_into::<true>(sent, row.groups_mut(cols)),
            (RowOut::Ring(row), false) => kernel.run_into::<false>(sent, row.groups_mut(cols)),
        }
    }
}

/// The chunk views one row's advance reads (see [`advance_row`]).
struct RowKernel<'a, 'b, V: Vector, S> {
    inp: &'a Inputs<'b, V>,
    chunks: usize,
    has_down: bool,
    /// The row and the row below.
    h: S,
    d: S,
    tables: [Table<'a, V>; 4],
    /// [`Inputs::uniform`].
    uniform: Option<[(f32, f32); 4]>,
    inv_mass: Chunks<'a, V>,
    viscosity: Chunks<'a, V>,
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
        ext: Option<[&'a [f32]; 3]>,
        arriving: &'a [Group<V>],
    ) -> Self {
        let chunks = inp.chunks();
        let base = r * inp.cols;
        let node = |s| Chunks::new(s, base, chunks);
        RowKernel {
            inp,
            chunks,
            has_down,
            h,
            d,
            tables: Family::ALL.map(|fam| Table::of(inp.springs, fam, base, chunks)),
            uniform: inp.uniform,
            inv_mass: node(inp.inv_mass),
            viscosity: node(inp.viscosity),
            ext: ext.map(|e| e.map(node)),
            arriving,
            dt: inp.cfg.dt,
            g: inp.cfg.accel,
        }
    }

    /// Runs every chunk of the row (see [`advance_row`]) and writes the new values into
    /// `dst`; `UNIFORM` says every family's springs share one coefficient and rest length.
    #[inline(always)]
    fn run_into<const UNIFORM: bool>(&self, sent: &mut [Group<V>], mut dst: impl Sink<V>) -> bool {
        let chunks = self.chunks;
        let full = self.inp.cols / V::LANES;
        let c = Consts::<V>::new(self);
        let mut finite = V::zero();
        // The E force of the chunk before (zero before column 0: no spring there).
        let mut e_west = [V::zero(); 3];
        let last = chunks - 1;
        if self.has_down {
            if last > 0 {
                // SAFETY: `0 < last < chunks`.
                let new = unsafe { self.chunk::<true, UNIFORM>(&c, 0, &mut e_west, sent) };
                store(&mut dst, full, 0, new, &mut finite);
            }
            // Two chunks per iteration: the out-of-order core sees two independent
            // chunks' square roots and divisions at once.
            let mut k = 1;
            while k + 1 < last {
                // SAFETY: `1 ≤ k < k + 1 < chunks`.
                let a = unsafe { self.chunk::<false, UNIFORM>(&c, k, &mut e_west, sent) };
                // SAFETY: as above.
                let b = unsafe { self.chunk::<false, UNIFORM>(&c, k + 1, &mut e_west, sent) };
                store(&mut dst, full, k, a, &mut finite);
                store(&mut dst, full, k + 1, b, &mut finite);
                k += 2;
            }
            if k < last {
                // SAFETY: `1 ≤ k < chunks`.
                let new = unsafe { self.chunk::<false, UNIFORM>(&c, k, &mut e_west, sent) };
                store(&mut dst, full, k, new, &mut finite);
            }
        } else {
            for k in 0..last {
                // SAFETY: `k < chunks`.
                let new = unsafe { self.chunk::<true, UNIFORM>(&c, k, &mut e_west, sent) };
                store(&mut dst, full, k, new, &mut finite);
            }
        }
        // SAFETY: `last < chunks`.
        let new = unsafe { self.chunk::<true, UNIFORM>(&c, last, &mut e_west, sent) };
        if last < full {
            store(&mut dst, full, last, new, &mut finite);
        } else {
            // A partial chunk: only the row's own lanes are written and checked.
            let real = c.edges.tail[Family::S as usize];
            dst.put_partial(last, new, real);
            for x in &new[..3] {
                finite += V::select(real, *x * V::zero(), V::zero());
            }
        }
        !finite.any_nan()
    }

    /// Family `fam`'s spring force on chunk `k` (at `h0`) from `there`; with `EDGE`, only
    /// in the lanes that hold such a spring.
    ///
    /// Inlined always in release builds. In builds with debug assertions it is only
    /// offered for inlining, as is [`RowKernel::chunk`]: unoptimised, every inlined copy
    /// keeps its own stack slots, and the level entry that inlined them all needed 2–3 MB
    /// of stack, more than a thread of rayon's pool has.
    #[cfg_attr(not(debug_assertions), inline(always))]
    #[cfg_attr(debug_assertions, inline)]
    fn spring<const EDGE: bool, const UNIFORM: bool>(
        &self,
        c: &Consts<V>,
        k: usize,
        fam: Family,
        h0: [V; 3],
        there: [V; 3],
    ) -> [V; 3] {
        let (coef, rest) = match c.uniform {
            Some(uniform) if UNIFORM => uniform[fam as usize],
            // SAFETY: `k < chunks` (the caller's contract), within the table views.
            _ => unsafe { self.tables[fam as usize].at(k) },
        };
        let f = spring_force(h0, there, coef, rest);
        if EDGE {
            c.edges.only_springs(fam, k, self.chunks, self.has_down, f)
        } else {
            f
        }
    }

    /// Chunk `k`: its springs, its new positions and velocities `[x, y, z, vx, vy, vz]`.
    /// Sends its S, SE and SW forces into `sent` and leaves its E force in `e_west` for
    /// chunk `k + 1`. With `EDGE` false the chunk is neither the first nor the last and
    /// has a row below: every lane holds a spring of every family.
    ///
    /// # Safety
    ///
    /// `k < chunks`, and `k ≥ 1` when `EDGE` is false. (The sources are readable up to
    /// chunk `chunks`, the node and table views hold `chunks` chunks, the arriving groups
    /// and `sent` `chunks + 2` groups, chunk `k` being group `k + 1`.)
    /// (Inlined as [`RowKernel::spring`] is.)
    #[cfg_attr(not(debug_assertions), inline(always))]
    #[cfg_attr(debug_assertions, inline)]
    unsafe fn chunk<const EDGE: bool, const UNIFORM: bool>(
        &self,
        c: &Consts<V>,
        k: usize,
        e_west: &mut [V; 3],
        sent: &mut [Group<V>],
    ) -> [V; 6] {
        let (h, d) = (self.h, self.d);
        // SAFETY: `k + 1 ≤ chunks`.
        let (h0, d0, h1, d1) = unsafe { (h.pos(k), d.pos(k), h.pos(k + 1), d.pos(k + 1)) };
        let d_west = if EDGE && k == 0 {
            [V::zero(); 3]
        } else {
            // SAFETY: `k ≥ 1` here, so `k − 1 < chunks`.
            unsafe { d.pos(k - 1) }
        };
        let e = self.spring::<EDGE, UNIFORM>(c, k, Family::E, h0, east3(h0, h1));
        let s = self.spring::<EDGE, UNIFORM>(c, k, Family::S, h0, d0);
        let se = self.spring::<EDGE, UNIFORM>(c, k, Family::SE, h0, east3(d0, d1));
        let sw = self.spring::<EDGE, UNIFORM>(c, k, Family::SW, h0, west3(d_west, d0));
        // SAFETY: `k < chunks`, within the node views.
        let (inv_mass, viscosity) = unsafe { (self.inv_mass.get(k), self.viscosity.get(k)) };
        let free = inv_mass.gt(V::zero());
        debug_assert!(k + 2 < self.arriving.len() && k + 2 < sent.len());
        // SAFETY: `k + 2 ≤ chunks + 1`, within the arriving groups and `sent`.
        let (west_n, north, east_n) = unsafe {
            *sent.get_unchecked_mut(k + 1) = [s, se, sw];
            let a = self.arriving;
            (
                a.get_unchecked(k),
                a.get_unchecked(k + 1),
                a.get_unchecked(k + 2),
            )
        };
        let mut new = [V::zero(); 6];
        for axis in 0..3 {
            // Leaving (this row's springs at this node) and arriving (the same family's
            // spring from the west, north, north-west and north-east neighbour).
            let e_w = V::west(e_west[axis], e[axis]);
            let se_nw = V::west(west_n[1][axis], north[1][axis]);
            let sw_ne = V::east(north[2][axis], east_n[2][axis]);
            // Same expression as `scalar::node_force`.
            let mut force = (e[axis] - e_w)
                + (s[axis] - north[0][axis])
                + (se[axis] - se_nw)
                + (sw[axis] - sw_ne);
            if let Some(ext) = self.ext {
                // SAFETY: `k < chunks`, within the node views.
                force += unsafe { ext[axis].get(k) };
            }
            // SAFETY: `k < chunks`.
            let v = unsafe { h.vel(k) }[axis];
            let acc = (force - viscosity * v) * inv_mass + V::select(free, c.g[axis], V::zero());
            let v1 = v + acc * c.dt;
            new[axis] = h0[axis] + v1 * c.dt;
            new[axis + 3] = v1;
        }
        // Vertical: calm water is exactly calm, as in `scalar::calm`.
        new[1] = calm(new[1], c.calm);
        new[4] = calm(new[4], c.calm);
        *e_west = e;
        new
    }
}

/// The row's constants as lanes, made once per row inside the kernel's instruction set.
struct Consts<V: Vector> {
    edges: Edges<V>,
    uniform: Option<[(V, V); 4]>,
    dt: V,
    g: [V; 3],
    calm: V,
}

impl<V: Vector> Consts<V> {
    #[inline(always)]
    fn new<S>(k: &RowKernel<'_, '_, V, S>) -> Self {
        Self {
            edges: Edges::new(k.inp.cols),
            #[allow(clippy::manual_map)] // `Option::map` would take a closure: see `splat2`
            uniform: match k.uniform {
                Some([e, s, se, sw]) => Some([splat2(e), splat2(s), splat2(se), splat2(sw)]),
                None => None,
            },
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
    V::select(x.abs().lt(limit), V::zero(), x)
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

/// [`Vector::west`] of each axis.
#[inline(always)]
fn west3<V: Vector>(lo: [V; 3], hi: [V; 3]) -> [V; 3] {
    [
        V::west(lo[0], hi[0]),
        V::west(lo[1], hi[1]),
        V::west(lo[2], hi[2]),
    ]
}

/// `f` in the lanes on in `m`, +0 elsewhere.
#[inline(always)]
fn only<V: Vector>(m: V::Mask, f: [V; 3]) -> [V; 3] {
    [
        V::select(m, f[0], V::zero()),
        V::select(m, f[1], V::zero()),
        V::select(m, f[2], V::zero()),
    ]
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
