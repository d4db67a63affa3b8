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

use super::access::{
    each_chunk, BackRow, Chunk, ChunkWork, EitherValues, FrontRow, NodeViews, RowPair, RowViews,
    Shared, Sink, Source, SpringValues, Tables,
};
use super::scratch::{Group, Row, RowForces};
use super::StepConfig;
use crate::grid::Family;
use crate::simd::{Task, Vector};
use crate::springs::Springs;
use crate::state::NodeTable;

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
    /// The last layer goes to the back buffers with non-temporal stores (see
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

    /// Row `r` of the front buffers (layer 0).
    #[inline(always)]
    pub fn front(&self, r: usize) -> FrontRow<'a, V> {
        FrontRow::new(self.pos, self.vel, r * self.cols, self.chunks())
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

/// Where the rows of the layer a row is advanced from live.
pub(super) enum Layer<'a, V> {
    /// Layer 0: the front buffers.
    Front,
    /// A layer in flight: row `r` in slot `r % 2` of its ring.
    Ring(&'a [Row<V>; 2]),
}

impl<V> Clone for Layer<'_, V> {
    fn clone(&self) -> Self {
        *self
    }
}

impl<V> Copy for Layer<'_, V> {}

/// Where a row's new values go.
pub(super) enum RowOut<'a, V> {
    /// The back buffers' row: x, y, z, vx, vy, vz, `cols` values each.
    Back([&'a mut [f32]; 6]),
    /// A ring row.
    Ring(&'a mut Row<V>),
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

/// Evaluates the S, SE and SW springs from row `r` of layer `from` down to row r+1 (zero
/// on the last row) into `out`: what row r sends to the next row. Only for the row just
/// above a band's rows; [`advance_row`] does this for its own rows on the way. Inlined into
/// the band, inside the level's instruction set, like [`advance_row`].
#[inline(always)]
pub(super) fn down_springs<V: Vector>(
    inp: &Inputs<V>,
    r: usize,
    from: Layer<V>,
    out: &mut RowForces<V>,
) {
    if r + 1 == inp.rows {
        out.zero_down();
        return;
    }
    match from {
        Layer::Front => springs_down(inp, r, inp.front(r), inp.front(r + 1), out),
        Layer::Ring(ring) => {
            let (here, down) = (
                ring[r % 2].groups(inp.cols),
                ring[(r + 1) % 2].groups(inp.cols),
            );
            springs_down(inp, r, here, down, out)
        }
    }
}

/// [`down_springs`] from row `here` to row `down`. Its springs come from the tables if
/// the springs have them, else the shared values: one copy of the loop for both, with a
/// branch per chunk ([`EitherValues`]). This runs once per band and layer, and a second
/// copy of the loop, as [`RowKernel::advance`] has, added a quarter to the crate's compile
/// time for no measurable speed.
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
        (Some(t), _) => EitherValues::Tables(Tables::new(t, r * inp.cols, chunks)),
        (None, Some(shared)) => EitherValues::Shared(Shared::new(shared)),
        (None, None) => unreachable!("springs that differ have tables"),
    };
    let rows = RowPair::new(chunks, here, down, &springs);
    let edges = Edges::<V>::new(inp.cols);
    let groups = out.groups_mut(inp.cols);
    for (k, group) in groups[1..=chunks].iter_mut().enumerate() {
        let at = rows.around(k);
        let (h0, d0) = (at.here, at.below);
        // Each spring from the end its force is kept for (see `RowKernel::chunk`).
        let ends = [
            (h0, d0),
            (h0, east3(d0, at.below_east)),
            (d0, east3(h0, at.here_east)),
        ];
        for (i, fam) in [Family::S, Family::SE, Family::SW].into_iter().enumerate() {
            let (coef, rest) = rows.spring(fam, k);
            let f = spring_force(ends[i].0, ends[i].1, coef, rest);
            group[i] = edges.only_springs(fam, k, chunks, true, f);
        }
    }
}

/// Advances row `r` one layer: evaluates its four springs (E inside the row, S, SE, SW
/// down to row r+1, none on the last row), sums each node's force with the springs
/// arriving from row r−1 (`prev`, evaluated one row earlier), integrates from layer
/// `from` into `dst`, and leaves the S, SE and SW forces in `next` for row r+1. Returns
/// `false` if a new value is not finite. The row's external forces ([`Inputs::ext_of_row`])
/// are added when advancing from [`Layer::Front`]: a pass applies them in its first step.
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
    from: Layer<V>,
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
        Layer::Front => {
            let (h, d) = (inp.front(r), inp.front(below));
            let kernel = RowKernel::new(inp, r, h, d, has_down, arriving);
            kernel.advance(sent, dst)
        }
        Layer::Ring(ring) => {
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
            kernel: k,
            springs,
            sent,
            dst,
        } = self;
        let cols = k.inp.cols;
        match dst {
            RowOut::Back(b) => k.run_into(&springs, sent, BackRow::new(b, cols, k.inp.stream)),
            RowOut::Ring(row) => k.run_into(&springs, sent, row.groups_mut(cols)),
        }
    }
}

/// What one row's advance reads (see [`advance_row`]), before [`RowRun`] makes its views.
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
    /// The row's node values and what row r−1 sent down.
    nodes: NodeViews<'a, V>,
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
        let (base, chunks) = (r * inp.cols, inp.chunks());
        let ext = if S::EXTERNAL { inp.ext_of_row(r) } else { None };
        RowKernel {
            inp,
            chunks,
            has_down,
            odd_start: (base / V::LANES) % 2 == 1,
            h,
            d,
            base,
            nodes: NodeViews::new(
                chunks,
                inp.inv_mass.row(r),
                inp.viscosity.row(r),
                ext,
                base,
                arriving,
            ),
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
                springs: Tables::new(
                    self.inp
                        .springs
                        .tables()
                        .expect("springs that differ have tables"),
                    self.base,
                    self.chunks,
                ),
                sent,
                dst,
            }),
        }
    }

    /// Runs every chunk of the row (see [`advance_row`]) and writes the new values into
    /// `dst`, each spring's coefficient and rest length taken from `springs`, and what the
    /// row sends down into `sent`.
    #[inline(always)]
    fn run_into<P: SpringValues<V>>(
        &self,
        springs: &P,
        sent: &mut [Group<V>],
        mut dst: impl Sink<V>,
    ) -> bool {
        let pair = RowPair::new(self.chunks, self.h, self.d, springs);
        let mut views = RowViews::new(pair, &self.nodes, sent);
        let mut work = Work {
            kernel: self,
            c: Consts::<V>::new(self),
            // The forces the chunk before sends east (zero before column 0: no node there).
            west: [V::zero(); 3],
            finite: V::zero(),
        };
        let new = each_chunk(
            &mut views,
            &mut work,
            &mut dst,
            self.has_down,
            self.odd_start,
        );
        let real = work.c.edges.tail[Family::S as usize];
        if dst.put_last(self.chunks - 1, new, real) {
            work.fold(&new);
        } else {
            // A partial chunk: only the row's own lanes are written and checked.
            for x in &new[..3] {
                work.finite += V::keep(real, *x * V::zero());
            }
        }
        !work.finite.any_nan()
    }

    /// Family `fam`'s spring force on the `from` end of its springs in chunk `k`'s lanes,
    /// the other end at `to`; with `EDGE`, only in the lanes that hold such a spring.
    ///
    /// Inlined always in release builds. In builds with debug assertions it is only
    /// offered for inlining, as is [`RowKernel::chunk`]: unoptimised, every inlined copy
    /// keeps its own stack slots, and the layer entry that inlined them all needed 2–3 MB
    /// of stack, more than a thread of rayon's pool has.
    #[cfg_attr(not(debug_assertions), inline(always))]
    #[cfg_attr(debug_assertions, inline)]
    fn spring<const EDGE: bool, P: SpringValues<V>>(
        &self,
        c: &Consts<V>,
        at: &Chunk<'_, '_, '_, V, S, P>,
        fam: Family,
        from: [V; 3],
        to: [V; 3],
    ) -> [V; 3] {
        let (coef, rest) = at.spring(fam);
        let f = spring_force(from, to, coef, rest);
        if EDGE {
            c.edges
                .only_springs(fam, at.index(), at.chunks(), self.has_down, f)
        } else {
            f
        }
    }

    /// Chunk `k`: its springs, its new positions and velocities `[x, y, z, vx, vy, vz]`.
    ///
    /// Each lane `i` evaluates four springs: E (node i to i+1), S (to the node below),
    /// SE (to the node below i+1), and the SW spring that leaves node i+1 for the node
    /// below i, evaluated from its lower end. Its S, SE and SW forces go down to row r+1
    /// ([`Chunk::exchange`]; S and SE as forces on this row's nodes, SW on the row
    /// below's). A node's force is then the sum of
    /// [`scalar::node_force`](super::super::scalar::node_force): its own E, S and SE
    /// springs, the north neighbour's S spring and the SW spring leaving the north-east
    /// neighbour, all in its own lane, minus what the lane to its west sends east — that
    /// lane's E and SW forces and its north neighbour's SE — summed there and moved one
    /// lane with a single shuffle per axis. `west` carries that sum from chunk `k − 1` to
    /// chunk `k`. With `EDGE` false the chunk is not the last and has a row below: every
    /// lane holds a spring of every family.
    ///
    /// (Inlined as [`RowKernel::spring`] is.)
    #[cfg_attr(not(debug_assertions), inline(always))]
    #[cfg_attr(debug_assertions, inline)]
    fn chunk<const EDGE: bool, P: SpringValues<V>>(
        &self,
        c: &Consts<V>,
        mut at: Chunk<'_, '_, '_, V, S, P>,
        west: &mut [V; 3],
    ) -> [V; 6] {
        // The neighbours are read here, or each where first used (`Vector::READ_AHEAD`;
        // the zeros are never used).
        let ahead = V::READ_AHEAD;
        let (h0, here_east, d0, below_east) = if ahead {
            (at.here(), at.here_east(), at.below(), at.below_east())
        } else {
            (at.here(), [V::zero(); 3], [V::zero(); 3], [V::zero(); 3])
        };
        let h_east = east3(h0, if ahead { here_east } else { at.here_east() });
        let e = self.spring::<EDGE, P>(c, &at, Family::E, h0, h_east);
        let d0 = if ahead { d0 } else { at.below() };
        let s = self.spring::<EDGE, P>(c, &at, Family::S, h0, d0);
        // Shifted only here: made with `h_east`, its lanes stayed live across the E and S
        // springs, and SSE2's pairs of registers spilled more (`docs/performance.md`).
        let d_east = east3(d0, if ahead { below_east } else { at.below_east() });
        let se = self.spring::<EDGE, P>(c, &at, Family::SE, h0, d_east);
        let sw = self.spring::<EDGE, P>(c, &at, Family::SW, d0, h_east);
        let node = at.exchange(s, se, sw);
        let (inv_mass, viscosity, north) = (node.inv_mass, node.viscosity, node.north);
        let free = inv_mass.gt(V::zero());
        let mut new = [V::zero(); 6];
        for axis in 0..3 {
            // What this lane sends east, and what arrives from the west.
            let east_bound = (e[axis] + sw[axis]) + north[1][axis];
            let from_west = V::west(west[axis], east_bound);
            // Same expression as `scalar::node_force`.
            let mut force =
                (((e[axis] + s[axis]) + se[axis]) + (north[2][axis] - north[0][axis])) - from_west;
            if S::EXTERNAL {
                if let Some(ext) = at.ext(axis) {
                    force += ext;
                }
            }
            let v = at.vel()[axis];
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

/// A row's run through its chunks ([`each_chunk`]): the kernel, its constants, and what
/// goes from chunk to chunk.
struct Work<'k, 'a, 'b, V: Vector, S> {
    kernel: &'k RowKernel<'a, 'b, V, S>,
    c: Consts<V>,
    /// What the chunk before sends east ([`RowKernel::chunk`]).
    west: [V; 3],
    /// The finiteness check of the chunks stored so far ([`Work::stored`]).
    finite: V,
}

impl<V: Vector, S: Source<V>, P: SpringValues<V>> ChunkWork<V, S, P> for Work<'_, '_, '_, V, S> {
    #[inline(always)]
    fn chunk<const EDGE: bool>(&mut self, at: Chunk<'_, '_, '_, V, S, P>) -> [V; 6] {
        self.kernel.chunk::<EDGE, P>(&self.c, at, &mut self.west)
    }

    #[inline(always)]
    fn stored(&mut self, new: &[V; 6]) {
        self.fold(new);
    }
}

impl<V: Vector, S> Work<'_, '_, '_, V, S> {
    /// Folds a stored chunk's positions into the finiteness check: `x·0` is 0 for finite
    /// x and NaN otherwise, and x' is non-finite whenever v' is.
    #[inline(always)]
    fn fold(&mut self, new: &[V; 6]) {
        self.finite += new[0] * V::zero();
        self.finite += new[1] * V::zero();
        self.finite += new[2] * V::zero();
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
