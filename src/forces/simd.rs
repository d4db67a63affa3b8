//! The engine: colour-partitioned bands of rows, SIMD across columns, rayon across bands,
//! and several steps per pass over memory.
//!
//! # How a band streams its rows
//!
//! [`advance_row`] takes row `r` in one pass over its chunks of `LANES` columns: it
//! evaluates the chunk's E spring inside the row and its S, SE and SW springs down to row
//! r+1, adds the springs arriving from row r−1 (evaluated one row earlier and kept in a
//! [`RowForces`]), integrates, and keeps the chunk's S, SE and SW forces for row r+1.
//! Spring forces never travel to main memory. A neighbour one column off comes from
//! aligned chunks and a register shuffle ([`crate::simd::east`], [`crate::simd::west`]):
//! with 64-byte lanes a load one column off straddles two cache lines.
//!
//! The first version evaluated a whole row's springs into row buffers, then summed and
//! integrated in a second loop: at 256² it was 7% faster, at 2048² (native, 2 threads)
//! 40% slower. Cutting its rows into strips whose buffers fit in L1 made 2048² slower
//! still, so cache capacity is not the reason; the one-pass loop stores 15 chunks per
//! chunk of nodes instead of 18 and loads about 30 instead of 45, but this machine has no
//! hardware counters to say more.
//!
//! What made the loop faster since, each measured at 256² on one thread, native build:
//! - the first and last chunk of a row are peeled off ([`RowKernel::run_into`]), so the chunks
//!   between need no mask, no partial store and no `memcpy` call, around which the
//!   compiler had spilled the registers it carries from chunk to chunk (+2–5%);
//! - while every spring family is uniform, the eight shared values stay in registers
//!   instead of a branch per spring between them and the tables (+17%);
//! - the forces a row sends down are chunk-major ([`RowForces`]): a chunk's nine lanes
//!   sit together behind one pointer instead of nine (+19%). The loop otherwise carries
//!   some forty array pointers, and with sixteen general registers each one more is a
//!   reload from the stack;
//! - so are the rows of the levels in flight ([`Row`]: six lanes per chunk), read through
//!   [`Source`] and written through [`Sink`] whether the row is a ring row or a row of the
//!   state buffers, which stay structure-of-arrays (+7%).
//!
//! Replacing the square root and the division by multiplies (wrong results, timing only)
//! gained 9%: the divider is not what limits the loop.
//!
//! A node's force is the same expression as in the scalar reference
//! ([`super::scalar::node_force`]), so the two agree bit for bit, whatever the schedule.
//!
//! # Several steps per pass (levels)
//!
//! One step reads 56 B per node and writes 48 B, and on a grid larger than the caches
//! that traffic, not arithmetic, sets the speed. A pass therefore advances `levels` steps
//! while reading the state once: it runs a wavefront down the band. As soon as row `r` of
//! level `l−1` (the state after `l−1` steps) exists, row `r−1` of level `l` can be
//! integrated, because a row only needs the rows beside it. Level 0 is the front buffer,
//! the last level goes to the back buffer, and every level in between lives in a ring of
//! two rows per level ([`Scratch`]) that stays in cache. Only the last level is written
//! to memory, on large grids with non-temporal stores ([`STREAM_MIN_NODES`]).
//!
//! # The two colours
//!
//! Which band integrates which row at which level is [`crate::springs::Tiling`]: the cut
//! between two bands leans one row per level into the even band. Colour 0 (even bands)
//! runs first, in parallel: each needs only its own rows. It also hands over, at each
//! level below the last, its first two and last two rows ([`Handoff`]). Colour 1 (odd
//! bands) runs second, in parallel: it reads those rows wherever it needs a row at a level
//! that it did not integrate itself.
//!
//! Bands of one colour write disjoint rows, so each task gets `&mut` slices of its own rows
//! of the back buffer and of its own handoff slots (split with `split_at_mut`: no atomics,
//! no locks). A step allocates nothing: handoffs live in [`Workspace`], and each worker
//! thread keeps its rings from pass to pass.

use super::StepConfig;
use crate::simd::{east, first_lanes, get, lanes, put, stream, stream_fence, west, Lane, LANES};
use crate::springs::{Springs, Tiling};
use crate::state::{State, Xyz};
use std::cell::RefCell;
use std::ops::Range;

/// Most steps one pass takes.
pub const MAX_PASS_STEPS: usize = 8;

/// Steps per pass when the caller does not fix it. Measured on 2048², native build, 2
/// threads, 64-row bands: single steps gave 6.0·10⁸ node updates/s, 2 steps 9.5·10⁸, 3
/// gave 1.10·10⁹, 4 gave 1.19·10⁹, 6 gave 1.15·10⁹ and 8 gave 1.12·10⁹. Past 4 the rows
/// in flight of a 2048-column pass (a ring and a row of forces per level, about 170 KB per
/// level) outgrow the 1 MB L2.
pub const DEFAULT_PASS_STEPS: usize = 4;

/// Grids of at least this many nodes (and whole chunks per row) write the last level of a
/// pass with non-temporal stores ([`crate::simd::stream`]): the back buffers are not read
/// before the next pass, and on a grid larger than the caches that read would come from
/// memory anyway, so loading each line before writing it only costs bandwidth. Measured
/// (native, 2 threads, passes of 4 steps): 512² −0–9%, 1024² +6–11%, 2048² +8–13%. At
/// 2¹⁹ nodes the front and back state take 25 MB, near this machine's 32 MB L3.
pub const STREAM_MIN_NODES: usize = 1 << 19;

/// A lane mask with every lane on.
const ALL: Lane = Lane::new([f32::from_bits(u32::MAX); LANES]);

/// The forces a row sends down: its S, SE and SW springs, chunk-major. Group `j` holds
/// columns `(j − 1)·LANES ..` as `[family − 1][axis]` lanes; groups 0 and `chunks + 1`,
/// and the lanes past the row, are zero. One group is nine adjacent lanes, so the hot loop
/// reaches all of a chunk's with one pointer and constant offsets.
#[derive(Debug, Clone)]
pub(crate) struct RowForces {
    groups: Vec<Group>,
}

/// The S, SE and SW forces of one chunk, by family and axis.
type Group = [[Lane; 3]; 3];

/// Groups in a chunk-major scratch row of `cols` columns: its chunks and a zero group on
/// each side.
fn group_count(cols: usize) -> usize {
    cols.div_ceil(LANES) + 2
}

impl RowForces {
    fn new(cols: usize) -> Self {
        Self {
            groups: vec![[[Lane::ZERO; 3]; 3]; group_count(cols)],
        }
    }

    /// The groups, checked to be those of a row of `cols` columns: the engine's unchecked
    /// accesses rely on that length.
    fn groups(&self, cols: usize) -> &[Group] {
        assert_eq!(self.groups.len(), group_count(cols));
        &self.groups
    }

    /// [`RowForces::groups`], mutable.
    fn groups_mut(&mut self, cols: usize) -> &mut [Group] {
        assert_eq!(self.groups.len(), group_count(cols));
        &mut self.groups
    }

    /// Clears the forces (what a band's first row receives from above when it is the
    /// grid's first row, and what the last row sends).
    fn zero_down(&mut self) {
        self.groups.fill([[Lane::ZERO; 3]; 3]);
    }
}

/// One row of positions and velocities outside the state buffers: a level in flight, or
/// a row handed from colour 0 to colour 1. Chunk-major like [`RowForces`]: group `j` holds
/// columns `(j − 1)·LANES ..` as `[x, y, z, vx, vy, vz]` lanes; groups 0 and `chunks + 1`,
/// and the lanes past the row, stay zero.
#[derive(Debug, Clone)]
pub(crate) struct Row {
    groups: Vec<[Lane; 6]>,
}

impl Row {
    fn new(cols: usize) -> Self {
        Self {
            groups: vec![[Lane::ZERO; 6]; group_count(cols)],
        }
    }

    /// The groups, checked to be those of a row of `cols` columns: the engine's unchecked
    /// accesses rely on that length.
    fn groups(&self, cols: usize) -> &[[Lane; 6]] {
        assert_eq!(self.groups.len(), group_count(cols));
        &self.groups
    }

    /// [`Row::groups`], mutable.
    fn groups_mut(&mut self, cols: usize) -> &mut [[Lane; 6]] {
        assert_eq!(self.groups.len(), group_count(cols));
        &mut self.groups
    }

    fn copy_from(&mut self, other: &Row) {
        self.groups.copy_from_slice(&other.groups);
    }
}

/// Where the rows of the level a row is advanced from live.
#[derive(Clone, Copy)]
enum Level<'a> {
    /// Level 0: the front buffers.
    Front,
    /// A level in flight: row `r` in slot `r % 2` of its ring.
    Ring(&'a [Row; 2]),
}

/// Where a row's new values go.
enum RowOut<'a> {
    /// The back buffers' row: x, y, z, vx, vy, vz, `cols` values each.
    Back([&'a mut [f32]; 6]),
    /// A ring row.
    Ring(&'a mut Row),
}

/// Chunk access to a row's positions and velocities, whatever its layout; `chunks` is the
/// row's chunk count, `cols.div_ceil(LANES)`. Chunk `chunks` (one past the row) is
/// readable for positions: it holds the next row's nodes, padding or zeros (as do the
/// lanes past the row in the last chunk), which only ever meet masked-off springs.
trait Source: Copy {
    /// Positions of chunk `k`.
    ///
    /// # Safety
    ///
    /// `k ≤ chunks`.
    unsafe fn pos(self, k: usize) -> [Lane; 3];

    /// Velocities of chunk `k`.
    ///
    /// # Safety
    ///
    /// `k < chunks`.
    unsafe fn vel(self, k: usize) -> [Lane; 3];
}

/// A row of the front buffers as chunk views: positions `chunks + 1` chunks long,
/// velocities `chunks`.
#[derive(Clone, Copy)]
struct FrontRow<'a> {
    pos: [&'a [[f32; LANES]]; 3],
    vel: [&'a [[f32; LANES]]; 3],
}

impl Source for FrontRow<'_> {
    #[inline(always)]
    unsafe fn pos(self, k: usize) -> [Lane; 3] {
        // SAFETY: `k ≤ chunks`, the views hold `chunks + 1`.
        unsafe { load3(self.pos, k) }
    }

    #[inline(always)]
    unsafe fn vel(self, k: usize) -> [Lane; 3] {
        // SAFETY: `k < chunks`.
        unsafe { load3(self.vel, k) }
    }
}

/// A [`Row`]'s groups (`chunks + 2`; chunk `k` is group `k + 1`).
impl Source for &[[Lane; 6]] {
    #[inline(always)]
    unsafe fn pos(self, k: usize) -> [Lane; 3] {
        debug_assert!(k + 1 < self.len());
        // SAFETY: `k + 1 ≤ chunks + 1`.
        let g = unsafe { self.get_unchecked(k + 1) };
        [g[0], g[1], g[2]]
    }

    #[inline(always)]
    unsafe fn vel(self, k: usize) -> [Lane; 3] {
        debug_assert!(k + 2 < self.len());
        // SAFETY: `k + 1 ≤ chunks`.
        let g = unsafe { self.get_unchecked(k + 1) };
        [g[3], g[4], g[5]]
    }
}

/// Where [`RowKernel::run`] writes a row's new `[x, y, z, vx, vy, vz]`.
trait Sink {
    /// Whole chunk `k`.
    ///
    /// # Safety
    ///
    /// `k < cols / LANES`.
    unsafe fn put(&mut self, k: usize, new: [Lane; 6]);

    /// The last chunk `k`, partial: only the lanes on in `real` belong to the row.
    fn put_partial(&mut self, k: usize, new: [Lane; 6], real: Lane);
}

/// A back-buffer row: its whole chunks and the columns after them.
struct BackRow<'a> {
    whole: [&'a mut [[f32; LANES]]; 6],
    tail: [&'a mut [f32]; 6],
    /// Write the whole chunks with non-temporal stores ([`STREAM_MIN_NODES`]).
    stream: bool,
}

impl<'a> BackRow<'a> {
    fn new(dst: [&'a mut [f32]; 6], cols: usize, stream: bool) -> Self {
        let [x, y, z, vx, vy, vz] = dst.map(|d| d[..cols].split_at_mut(cols / LANES * LANES));
        BackRow {
            whole: [x.0, y.0, z.0, vx.0, vy.0, vz.0].map(|d| d.as_chunks_mut::<LANES>().0),
            tail: [x.1, y.1, z.1, vx.1, vy.1, vz.1],
            stream,
        }
    }
}

impl Sink for BackRow<'_> {
    #[inline(always)]
    unsafe fn put(&mut self, k: usize, new: [Lane; 6]) {
        for (o, v) in self.whole.iter_mut().zip(new) {
            if self.stream {
                // SAFETY: `k < cols / LANES`, the length of `whole`; with `stream` every row
                // starts on a lane boundary of its lane-aligned buffer (`Inputs::stream`).
                unsafe { stream(o, k, v) };
            } else {
                // SAFETY: `k < cols / LANES`, the length of `whole`.
                unsafe { put(o, k, v) };
            }
        }
    }

    fn put_partial(&mut self, _: usize, new: [Lane; 6], _: Lane) {
        for (t, v) in self.tail.iter_mut().zip(new) {
            t.copy_from_slice(&v.to_array()[..t.len()]);
        }
    }
}

/// A [`Row`]'s groups.
impl Sink for &mut [[Lane; 6]] {
    #[inline(always)]
    unsafe fn put(&mut self, k: usize, new: [Lane; 6]) {
        debug_assert!(k + 2 < self.len());
        // SAFETY: `k + 1 ≤ chunks`.
        unsafe { *self.get_unchecked_mut(k + 1) = new };
    }

    fn put_partial(&mut self, k: usize, new: [Lane; 6], real: Lane) {
        // The lanes past the row stay zero.
        self[k + 1] = new.map(|v| real.select(v, Lane::ZERO));
    }
}

/// What an even band hands to the odd band across one cut: for each level `1..levels`,
/// the two rows next to the cut (upper first).
pub(crate) type Handoff = Vec<[Row; 2]>;

/// The engine's reusable buffers: the tiling in use and one [`Handoff`] per cut.
#[derive(Debug, Clone)]
pub(crate) struct Workspace {
    /// A band height fixed by the caller, or `None` to follow [`crate::springs::band_rows`].
    fixed_band_rows: Option<usize>,
    /// Steps per pass.
    pub pass_steps: usize,
    tiling: Option<(Tiling, usize)>,
    /// Slot `b` holds what crosses the cut above band `b` (slot 0 is unused).
    handoffs: Vec<Handoff>,
}

impl Workspace {
    pub fn new(fixed_band_rows: Option<usize>) -> Self {
        Self {
            fixed_band_rows: fixed_band_rows.map(|h| h.max(1)),
            pass_steps: DEFAULT_PASS_STEPS,
            tiling: None,
            handoffs: Vec::new(),
        }
    }

    /// The tiling for a pass of `levels` steps; rebuilds the handoff slots when it changes.
    fn prepare(&mut self, cols: usize, rows: usize, levels: usize) -> Tiling {
        let tiling = self.tiling(rows, levels);
        if self.tiling != Some((tiling, cols)) {
            self.tiling = Some((tiling, cols));
            let slots = if tiling.bands() > 1 {
                tiling.bands()
            } else {
                0
            };
            self.handoffs = (0..slots)
                .map(|b| {
                    let levels = if b == 0 { 0 } else { levels - 1 };
                    (0..levels)
                        .map(|_| [Row::new(cols), Row::new(cols)])
                        .collect()
                })
                .collect();
        }
        tiling
    }

    /// How a pass of `levels` steps cuts `rows` rows on the current thread pool.
    pub fn tiling(&self, rows: usize, levels: usize) -> Tiling {
        let band_rows = self
            .fixed_band_rows
            .unwrap_or_else(|| crate::springs::band_rows(rows, threads()));
        Tiling::new(rows, band_rows, levels)
    }
}

#[cfg(feature = "parallel")]
fn threads() -> usize {
    rayon::current_num_threads()
}

#[cfg(not(feature = "parallel"))]
fn threads() -> usize {
    1
}

/// A worker's buffers for the levels in flight, reused across bands and passes.
struct Scratch {
    cols: usize,
    /// `rings[l]`: the last two rows of level `l` (row `r` in slot `r % 2`), for
    /// `l in 1..levels` (`rings[0]` is unused: level 0 is the front buffer).
    rings: Vec<[Row; 2]>,
    /// `prev[l]`: the springs of the row before the one level `l` integrates next.
    prev: Vec<RowForces>,
    /// The row being evaluated; swapped into `prev[l]` once its row is integrated.
    cur: RowForces,
}

impl Scratch {
    fn new(cols: usize, levels: usize) -> Self {
        Self {
            cols,
            rings: (0..levels)
                .map(|_| [Row::new(cols), Row::new(cols)])
                .collect(),
            prev: (0..=levels).map(|_| RowForces::new(cols)).collect(),
            cur: RowForces::new(cols),
        }
    }
}

thread_local! {
    static SCRATCH: RefCell<Scratch> = RefCell::new(Scratch::new(0, 0));
}

/// Runs `f` with this thread's scratch sized for `cols` columns and `levels` levels.
fn with_scratch<T>(cols: usize, levels: usize, f: impl FnOnce(&mut Scratch) -> T) -> T {
    SCRATCH.with(|s| {
        let mut s = s.borrow_mut();
        if s.cols != cols || s.rings.len() < levels {
            *s = Scratch::new(cols, levels);
        }
        f(&mut s)
    })
}

/// Everything a band reads: front buffers and tables, shared by all tasks.
struct Inputs<'a> {
    cols: usize,
    rows: usize,
    pos: [&'a [f32]; 3],
    vel: [&'a [f32]; 3],
    inv_mass: &'a [f32],
    viscosity: &'a [f32],
    /// External forces, applied in the first step of the pass only.
    ext: Option<[&'a [f32]; 3]>,
    springs: &'a Springs,
    /// Each family's shared coefficient and rest length, when every family has them
    /// (the usual case: no spring was edited). The hot loop then keeps them in registers.
    uniform: Option<[(Lane, Lane); 4]>,
    cfg: StepConfig,
    /// Lane masks of the springs that exist in the last chunk of a row, per family (no E
    /// or SE spring leaves the last column; columns past the row are off).
    tail: [Lane; 4],
    /// Lane mask of the SW springs that exist in the first chunk (none leaves column 0).
    head_sw: Lane,
    /// The last level goes to the back buffers with non-temporal stores: a grid of at
    /// least [`STREAM_MIN_NODES`] nodes whose rows are whole chunks, so that every row
    /// starts on a lane boundary.
    stream: bool,
}

impl Inputs<'_> {
    /// Which lanes of chunk `k` hold a spring of family `fam`.
    #[inline(always)]
    fn exists(&self, fam: usize, k: usize, chunks: usize) -> Lane {
        let mut m = if k + 1 == chunks { self.tail[fam] } else { ALL };
        if fam == 3 && k == 0 {
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
        fam: usize,
        k: usize,
        chunks: usize,
        has_down: bool,
        f: [Lane; 3],
    ) -> [Lane; 3] {
        let edge = k + 1 == chunks || (fam == 3 && k == 0);
        let none_below = fam > 0 && !has_down;
        if !edge && !none_below {
            return f;
        }
        let mut exists = if none_below { Lane::ZERO } else { ALL };
        if edge {
            exists &= self.exists(fam, k, chunks);
        }
        f.map(|c| exists.select(c, Lane::ZERO))
    }

    /// Row `r` of the front buffers (level 0).
    #[inline(always)]
    fn front(&self, r: usize) -> FrontRow<'_> {
        let chunks = self.cols.div_ceil(LANES);
        FrontRow {
            pos: self.pos.map(|p| lanes(p, r * self.cols, chunks + 1)),
            vel: self.vel.map(|v| lanes(v, r * self.cols, chunks)),
        }
    }
}

/// One family's coefficients and rest lengths along one row, as chunk views of its
/// tables.
#[derive(Clone, Copy)]
struct Table<'a> {
    coef: &'a [[f32; LANES]],
    rest: &'a [[f32; LANES]],
}

impl<'a> Table<'a> {
    /// Family `fam`'s table for the `chunks` chunks of the row starting at node `base`.
    #[inline(always)]
    fn of(sp: &'a Springs, fam: usize, base: usize, chunks: usize) -> Self {
        Table {
            coef: lanes(&sp.coef[fam], base, chunks),
            rest: lanes(&sp.rest[fam], base, chunks),
        }
    }

    /// `(coefficient, rest length)` of chunk `k`.
    ///
    /// # Safety
    ///
    /// `k < chunks`.
    #[inline(always)]
    unsafe fn at(self, k: usize) -> (Lane, Lane) {
        // SAFETY: the caller guarantees `k` is in range of both views.
        unsafe { (get(self.coef, k), get(self.rest, k)) }
    }
}

/// The back-buffer rows one task may write: rows `first_row ..` of x, y, z, vx, vy, vz.
struct Rows<'a> {
    first_row: usize,
    cols: usize,
    out: [&'a mut [f32]; 6],
}

impl<'a> Rows<'a> {
    /// Splits at `row` (clamped to the rows held): `(rows before, rows from)`.
    fn split_at_row(self, row: usize) -> (Rows<'a>, Rows<'a>) {
        let held = self.out[0].len() / self.cols;
        let at = row.saturating_sub(self.first_row).min(held);
        let [a, b, c, d, e, f] = self.out.map(|s| s.split_at_mut(at * self.cols));
        let head = Rows {
            first_row: self.first_row,
            cols: self.cols,
            out: [a.0, b.0, c.0, d.0, e.0, f.0],
        };
        let tail = Rows {
            first_row: self.first_row + at,
            cols: self.cols,
            out: [a.1, b.1, c.1, d.1, e.1, f.1],
        };
        (head, tail)
    }

    /// Row `r` (held by this task), for [`advance_row`] to write.
    fn row(&mut self, r: usize) -> [&mut [f32]; 6] {
        let at = (r - self.first_row) * self.cols;
        let cols = self.cols;
        self.out.each_mut().map(|s| &mut s[at..at + cols])
    }
}

/// Every row of the back buffers (`next_pos`, `next_vel`), for the tasks to split.
fn back_rows<'a>(pos: &'a mut Xyz, vel: &'a mut Xyz, cols: usize, n: usize) -> Rows<'a> {
    let [px, py, pz] = pos;
    let [vx, vy, vz] = vel;
    let out = [px, py, pz, vx, vy, vz].map(|b| &mut b[..n]);
    Rows {
        first_row: 0,
        cols,
        out,
    }
}

/// One engine pass of `levels` steps (`1..=MAX_PASS_STEPS`) from the front into the back
/// buffers. Returns `false` if any new value, at any level, is not finite.
pub(crate) fn pass(
    state: &mut State,
    springs: &Springs,
    ws: &mut Workspace,
    cfg: StepConfig,
    levels: usize,
) -> bool {
    debug_assert!((1..=MAX_PASS_STEPS).contains(&levels));
    let grid = state.grid;
    let (cols, rows, n) = (grid.cols, grid.rows, grid.len());
    let t = ws.prepare(cols, rows, levels);
    let inp = Inputs {
        cols,
        rows,
        pos: [&state.pos[0], &state.pos[1], &state.pos[2]],
        vel: [&state.vel[0], &state.vel[1], &state.vel[2]],
        inv_mass: &state.inv_mass,
        viscosity: &state.viscosity,
        ext: state
            .ext_pending
            .then(|| [&state.ext[0][..], &state.ext[1][..], &state.ext[2][..]]),
        springs,
        uniform: springs
            .all_uniform()
            .map(|u| u.map(|(c, r)| (Lane::splat(c), Lane::splat(r)))),
        cfg,
        tail: {
            let last = cols - (cols - 1) / LANES * LANES; // columns in the last chunk
            let [all, short] = [first_lanes(last), first_lanes(last - 1)];
            [short, all, short, all]
        },
        head_sw: !first_lanes(1),
        stream: n >= STREAM_MIN_NODES && cols % LANES == 0,
    };
    let bands = t.bands();

    // Colour 0: even bands, each writing the handoff slots on both of its cuts.
    let ok_even = for_each_band(
        &t,
        0..bands,
        Slots {
            first: 0,
            slots: &mut ws.handoffs,
        },
        back_rows(&mut state.next_pos, &mut state.next_vel, cols, n),
        &|slots: Slots, b| slots.split(b),
        &|b, slots: Slots, mut rows| {
            let (above, below) = slots.of_band(b);
            band(&inp, &t, b, Handoffs::Give(above, below), &mut rows)
        },
    );

    // Colour 1: odd bands, reading what the even bands handed over.
    let handoffs = &ws.handoffs[..];
    let (_, from_band_1) =
        back_rows(&mut state.next_pos, &mut state.next_vel, cols, n).split_at_row(t.cut(1, levels));
    let ok_odd = for_each_band(
        &t,
        1..bands,
        (),
        from_band_1,
        &|(), _| ((), ()),
        &|b, (), mut rows| {
            let take = |s: usize| handoffs.get(s).filter(|_| s < bands);
            band(&inp, &t, b, Handoffs::Take(take(b), take(b + 1)), &mut rows)
        },
    );
    ok_even && ok_odd
}

/// Handoff slots `first ..` for the even bands of one task.
struct Slots<'a> {
    first: usize,
    slots: &'a mut [Handoff],
}

impl<'a> Slots<'a> {
    /// Slots before band `b`'s and from it.
    fn split(self, b: usize) -> (Slots<'a>, Slots<'a>) {
        let at = (b - self.first).min(self.slots.len());
        let (l, r) = self.slots.split_at_mut(at);
        (
            Slots {
                first: self.first,
                slots: l,
            },
            Slots {
                first: self.first + at,
                slots: r,
            },
        )
    }

    /// The slots on band `b`'s two cuts (above, below), where there is a cut.
    fn of_band(self, b: usize) -> (Option<&'a mut Handoff>, Option<&'a mut Handoff>) {
        let mut it = self.slots[b - self.first..].iter_mut();
        let above = it.next().filter(|_| b > 0);
        (above, it.next())
    }
}

/// Runs `f` on the bands `bands.start, bands.start + 2, …` (one colour), splitting the
/// range, the shared part `s` and the back-buffer rows recursively with `rayon::join` (in
/// order without the `parallel` feature). Returns `false` if any band did.
fn for_each_band<S: Send>(
    t: &Tiling,
    bands: Range<usize>,
    s: S,
    rows: Rows<'_>,
    split: &(impl Fn(S, usize) -> (S, S) + Sync),
    f: &(impl Fn(usize, S, Rows<'_>) -> bool + Sync),
) -> bool {
    let count = bands.len().div_ceil(2);
    if count == 0 {
        return true;
    }
    if count == 1 {
        return f(bands.start, s, rows);
    }
    let mid = bands.start + 2 * (count / 2);
    let (sl, sr) = split(s, mid);
    let (rl, rr) = rows.split_at_row(t.cut(mid, t.levels));
    let (a, b) = join(
        || for_each_band(t, bands.start..mid, sl, rl, split, f),
        || for_each_band(t, mid..bands.end, sr, rr, split, f),
    );
    a && b
}

#[cfg(feature = "parallel")]
fn join<A: Send, B: Send>(a: impl FnOnce() -> A + Send, b: impl FnOnce() -> B + Send) -> (A, B) {
    rayon::join(a, b)
}

#[cfg(not(feature = "parallel"))]
fn join<A, B>(a: impl FnOnce() -> A, b: impl FnOnce() -> B) -> (A, B) {
    (a(), b())
}

/// A band's handoff slots on its two cuts (above, below): written by an even band, read
/// by an odd one.
enum Handoffs<'a> {
    Give(Option<&'a mut Handoff>, Option<&'a mut Handoff>),
    Take(Option<&'a Handoff>, Option<&'a Handoff>),
}

/// Band `b`'s part of a pass: a wavefront over rows and levels. Level `l` handles row `r`
/// at time `r + l − 1`, after level `l−1` has produced rows `r` and `r+1` (earlier in the
/// same time, or before). Handling a row means, in order: taking it from a handoff if it
/// is a row of another band that the next level needs (odd bands); evaluating its springs
/// if it is the row just above the band's rows (their S, SE, SW arrive at the first row);
/// or evaluating and integrating it if it is the band's own, then handing it over if it
/// is one of the two rows next to a cut (even bands).
fn band(inp: &Inputs, t: &Tiling, b: usize, mut handoffs: Handoffs, rows: &mut Rows) -> bool {
    let last = t.levels;
    let own: [Range<usize>; MAX_PASS_STEPS + 1] =
        std::array::from_fn(|l| if l <= last { t.rows_at(b, l) } else { 0..0 });
    let odd = matches!(handoffs, Handoffs::Take(..));
    // Rows level `l` handles: its own, the row above them, and for an odd band below the
    // last level the two rows beyond each cut that the next level borrows.
    let handled = |l: usize| {
        let own = &own[l];
        let borrow = if odd && l < last { 2 } else { 1 };
        let below = if odd && l < last && own.end < inp.rows {
            2
        } else {
            0
        };
        own.start.saturating_sub(borrow)..(own.end + below).min(inp.rows)
    };
    let first_time = (1..=last).map(|l| handled(l).start + l - 1).min();
    let end_time = (1..=last).map(|l| handled(l).end + l - 1).max();
    let (Some(first_time), Some(end_time)) = (first_time, end_time) else {
        return true;
    };
    with_scratch(inp.cols, last, |s| {
        let Scratch {
            rings, prev, cur, ..
        } = s;
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
                if !handled(l).contains(&r) {
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
                            let from = if r < own_l.start {
                                above.map(|h| &h[l - 1][r + 2 - own_l.start])
                            } else {
                                below.map(|h| &h[l - 1][r - own_l.end])
                            };
                            if let Some(from) = from {
                                upper[0][r % 2].copy_from(from);
                            }
                        }
                    }
                    continue;
                }
                let ext = if l == 1 { inp.ext } else { None };
                let dst = if l == last {
                    RowOut::Back(rows.row(r))
                } else {
                    RowOut::Ring(&mut upper[0][r % 2])
                };
                ok &= advance_row(inp, r, from, ext, &prev[l], cur, dst);
                std::mem::swap(cur, &mut prev[l]);
                if let Handoffs::Give(above, below) = &mut handoffs {
                    if l < last {
                        let row = &upper[0][r % 2];
                        if let Some(h) = above.as_deref_mut().filter(|_| r < own_l.start + 2) {
                            h[l - 1][r - own_l.start].copy_from(row);
                        }
                        if let Some(h) = below.as_deref_mut().filter(|_| r + 2 >= own_l.end) {
                            h[l - 1][r + 2 - own_l.end].copy_from(row);
                        }
                    }
                }
            }
        }
        if inp.stream {
            // The streamed rows must be visible before the pass ends and other threads
            // read them.
            stream_fence();
        }
        ok
    })
}

/// Force on the `i` lanes from springs `i → j`: `c (L − L0) d / L`, zero where `L = 0`.
#[inline(always)]
fn spring_force(pi: [Lane; 3], pj: [Lane; 3], coef: Lane, rest: Lane) -> [Lane; 3] {
    let d = [pj[0] - pi[0], pj[1] - pi[1], pj[2] - pi[2]];
    let l2 = d[0] * d[0] + d[1] * d[1] + d[2] * d[2];
    let l = l2.sqrt();
    let s = l2
        .simd_gt(Lane::ZERO)
        .select(coef * (l - rest) / l, Lane::ZERO);
    [s * d[0], s * d[1], s * d[2]]
}

/// Evaluates the S, SE and SW springs from row `r` of level `from` down to row r+1 (zero
/// on the last row) into `out`: what row r sends to the next row. Only for the row just
/// above a band's rows; [`advance_row`] does this for its own rows on the way.
fn down_springs(inp: &Inputs, r: usize, from: Level, out: &mut RowForces) {
    if r + 1 == inp.rows {
        out.zero_down();
        return;
    }
    match from {
        Level::Front => down_springs_from(inp, r, inp.front(r), inp.front(r + 1), out),
        Level::Ring(ring) => {
            let [here, down] = [r % 2, (r + 1) % 2].map(|i| ring[i].groups(inp.cols));
            down_springs_from(inp, r, here, down, out)
        }
    }
}

/// [`down_springs`] from row `here` to row `down`.
fn down_springs_from<S: Source>(inp: &Inputs, r: usize, here: S, down: S, out: &mut RowForces) {
    let chunks = inp.cols.div_ceil(LANES);
    let table = |fam| Table::of(inp.springs, fam, r * inp.cols, chunks);
    // `family` calls these with `k < chunks`; positions are readable up to chunk `chunks`.
    // SAFETY: `k < chunks`.
    family(inp, 1, table(1), here, out, |k| unsafe { down.pos(k) });
    // SAFETY: `k + 1 ≤ chunks`.
    family(inp, 2, table(2), here, out, |k| unsafe {
        let (a, b) = (down.pos(k), down.pos(k + 1));
        [0, 1, 2].map(|i| east(a[i], b[i]))
    });
    // SAFETY: `k − 1` (for k > 0) and `k` are below `chunks`.
    family(inp, 3, table(3), here, out, |k| unsafe {
        // Lane 0 of chunk 0 has no SW spring (column 0): its west neighbour is never used.
        let a = if k == 0 {
            [Lane::ZERO; 3]
        } else {
            down.pos(k - 1)
        };
        let b = down.pos(k);
        [0, 1, 2].map(|i| west(a[i], b[i]))
    });
}

/// One down family's springs (`fam` in 1..4) along a row: from the nodes of `h` to
/// `there(k)`, into `out`.
#[inline(always)]
fn family<S: Source>(
    inp: &Inputs,
    fam: usize,
    table: Table,
    h: S,
    out: &mut RowForces,
    there: impl Fn(usize) -> [Lane; 3],
) {
    let chunks = inp.cols.div_ceil(LANES);
    for (k, group) in out.groups[1..=chunks].iter_mut().enumerate() {
        // SAFETY: `k < chunks`.
        let f = unsafe {
            let (coef, rest) = table.at(k);
            spring_force(h.pos(k), there(k), coef, rest)
        };
        group[fam - 1] = inp.only_springs(fam, k, chunks, true, f);
    }
}

/// Chunk `k` of three views.
///
/// # Safety
///
/// `k` is below the length of every view.
#[inline(always)]
unsafe fn load3(v: [&[[f32; LANES]]; 3], k: usize) -> [Lane; 3] {
    // SAFETY: the caller guarantees `k` is in range of every view.
    unsafe { [get(v[0], k), get(v[1], k), get(v[2], k)] }
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
fn advance_row(
    inp: &Inputs,
    r: usize,
    from: Level,
    ext: Option<[&[f32]; 3]>,
    prev: &RowForces,
    next: &mut RowForces,
    dst: RowOut,
) -> bool {
    // On the last row the "row below" is the row itself: its springs are masked off.
    let has_down = r + 1 < inp.rows;
    let below = if has_down { r + 1 } else { r };
    let sent = next.groups_mut(inp.cols);
    match from {
        Level::Front => {
            let (h, d) = (inp.front(r), inp.front(below));
            RowKernel::new(inp, r, h, d, has_down, ext, prev).run(sent, dst)
        }
        Level::Ring(ring) => {
            let [h, d] = [r % 2, below % 2].map(|i| ring[i].groups(inp.cols));
            RowKernel::new(inp, r, h, d, has_down, ext, prev).run(sent, dst)
        }
    }
}

/// The chunk views one row's advance reads (see [`advance_row`]).
struct RowKernel<'a, S> {
    inp: &'a Inputs<'a>,
    chunks: usize,
    has_down: bool,
    /// The row and the row below.
    h: S,
    d: S,
    tables: [Table<'a>; 4],
    /// [`Inputs::uniform`].
    uniform: Option<[(Lane, Lane); 4]>,
    inv_mass: &'a [[f32; LANES]],
    viscosity: &'a [[f32; LANES]],
    ext: Option<[&'a [[f32; LANES]]; 3]>,
    /// What row r−1 sent down ([`RowForces`]: `chunks + 2` groups).
    arriving: &'a [Group],
    dt: Lane,
    g: [Lane; 3],
}

impl<'a, S: Source> RowKernel<'a, S> {
    #[inline(always)]
    fn new(
        inp: &'a Inputs<'a>,
        r: usize,
        h: S,
        d: S,
        has_down: bool,
        ext: Option<[&'a [f32]; 3]>,
        prev: &'a RowForces,
    ) -> Self {
        let chunks = inp.cols.div_ceil(LANES);
        let base = r * inp.cols;
        let node = |s| lanes(s, base, chunks);
        RowKernel {
            inp,
            chunks,
            has_down,
            h,
            d,
            tables: std::array::from_fn(|fam| Table::of(inp.springs, fam, base, chunks)),
            uniform: inp.uniform,
            inv_mass: node(inp.inv_mass),
            viscosity: node(inp.viscosity),
            ext: ext.map(|e| e.map(node)),
            arriving: prev.groups(inp.cols),
            dt: Lane::splat(inp.cfg.dt),
            g: inp.cfg.accel.map(Lane::splat),
        }
    }

    /// Runs the row into a back-buffer or a ring row.
    #[inline(always)]
    fn run(&self, sent: &mut [Group], dst: RowOut) -> bool {
        match (dst, self.uniform.is_some()) {
            (RowOut::Back(b), true) => self.run_into::<true>(sent, self.back_row(b)),
            (RowOut::Back(b), false) => self.run_into::<false>(sent, self.back_row(b)),
            (RowOut::Ring(row), true) => self.run_into::<true>(sent, row.groups_mut(self.inp.cols)),
            (RowOut::Ring(row), false) => {
                self.run_into::<false>(sent, row.groups_mut(self.inp.cols))
            }
        }
    }

    fn back_row<'b>(&self, dst: [&'b mut [f32]; 6]) -> BackRow<'b> {
        BackRow::new(dst, self.inp.cols, self.inp.stream)
    }

    /// Runs every chunk of the row (see [`advance_row`]) and writes the new values into
    /// `dst`; `UNIFORM` says every family's springs share one coefficient and rest length.
    #[inline(always)]
    fn run_into<const UNIFORM: bool>(&self, sent: &mut [Group], mut dst: impl Sink) -> bool {
        let chunks = self.chunks;
        let full = self.inp.cols / LANES;
        let mut finite = Lane::ZERO;
        // The E force of the chunk before (zero before column 0: no spring there).
        let mut e_west = [Lane::ZERO; 3];
        let last = chunks - 1;
        // Every chunk but the last is whole: `k < last ≤ full`.
        let mut store = |k: usize, new: [Lane; 6], finite: &mut Lane| {
            debug_assert!(k < full);
            // SAFETY: `k < full`: every caller stores a chunk before the last, or the last
            // when it is whole.
            unsafe { dst.put(k, new) };
            // Fused finiteness check: `x·0` is 0 for finite x and NaN otherwise, and x' is
            // non-finite whenever v' is.
            for x in &new[..3] {
                *finite += *x * Lane::ZERO;
            }
        };
        if self.has_down {
            if last > 0 {
                // SAFETY: `0 < last < chunks`.
                let new = unsafe { self.chunk::<true, UNIFORM>(0, &mut e_west, sent) };
                store(0, new, &mut finite);
            }
            // Two chunks per iteration: the out-of-order core sees two independent
            // chunks' square roots and divisions at once (measured +3% at 256², 1 thread).
            let mut k = 1;
            while k + 1 < last {
                // SAFETY: `1 ≤ k < k + 1 < chunks`.
                let a = unsafe { self.chunk::<false, UNIFORM>(k, &mut e_west, sent) };
                // SAFETY: as above.
                let b = unsafe { self.chunk::<false, UNIFORM>(k + 1, &mut e_west, sent) };
                store(k, a, &mut finite);
                store(k + 1, b, &mut finite);
                k += 2;
            }
            if k < last {
                // SAFETY: `1 ≤ k < chunks`.
                let new = unsafe { self.chunk::<false, UNIFORM>(k, &mut e_west, sent) };
                store(k, new, &mut finite);
            }
        } else {
            for k in 0..last {
                // SAFETY: `k < chunks`.
                let new = unsafe { self.chunk::<true, UNIFORM>(k, &mut e_west, sent) };
                store(k, new, &mut finite);
            }
        }
        // SAFETY: `last < chunks`.
        let new = unsafe { self.chunk::<true, UNIFORM>(last, &mut e_west, sent) };
        if last < full {
            store(last, new, &mut finite);
        } else {
            // A partial chunk: only the row's own lanes are written and checked.
            let real = self.inp.tail[1];
            dst.put_partial(last, new, real);
            for x in &new[..3] {
                finite += real.select(*x * Lane::ZERO, Lane::ZERO);
            }
        }
        !finite.is_nan().any()
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
    #[inline(always)]
    unsafe fn chunk<const EDGE: bool, const UNIFORM: bool>(
        &self,
        k: usize,
        e_west: &mut [Lane; 3],
        sent: &mut [Group],
    ) -> [Lane; 6] {
        let (h, d) = (self.h, self.d);
        // SAFETY: `k + 1 ≤ chunks`.
        let (h0, d0, h1, d1) = unsafe { (h.pos(k), d.pos(k), h.pos(k + 1), d.pos(k + 1)) };
        let d_west = if EDGE && k == 0 {
            [Lane::ZERO; 3]
        } else {
            // SAFETY: `k ≥ 1` here, so `k − 1 < chunks`.
            unsafe { d.pos(k - 1) }
        };
        let spring = |fam: usize, there: [Lane; 3]| {
            let (coef, rest) = match self.uniform {
                Some(uniform) if UNIFORM => uniform[fam],
                // SAFETY: `k < chunks`, within the table views.
                _ => unsafe { self.tables[fam].at(k) },
            };
            let f = spring_force(h0, there, coef, rest);
            if EDGE {
                self.inp.only_springs(fam, k, self.chunks, self.has_down, f)
            } else {
                f
            }
        };
        let e = spring(0, [0, 1, 2].map(|i| east(h0[i], h1[i])));
        let s = spring(1, d0);
        let se = spring(2, [0, 1, 2].map(|i| east(d0[i], d1[i])));
        let sw = spring(3, [0, 1, 2].map(|i| west(d_west[i], d0[i])));
        // SAFETY: `k < chunks`, within the node views.
        let (inv_mass, viscosity) = unsafe { (get(self.inv_mass, k), get(self.viscosity, k)) };
        let free = inv_mass.simd_gt(Lane::ZERO);
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
        let mut new = [Lane::ZERO; 6];
        for axis in 0..3 {
            // SAFETY: `k < chunks`, within the node views.
            let m = |v: &[[f32; LANES]]| unsafe { get(v, k) };
            // Leaving (this row's springs at this node) and arriving (the same family's
            // spring from the west, north, north-west and north-east neighbour).
            let e_w = west(e_west[axis], e[axis]);
            let se_nw = west(west_n[1][axis], north[1][axis]);
            let sw_ne = east(north[2][axis], east_n[2][axis]);
            // Same expression as `scalar::node_force`.
            let mut force = (e[axis] - e_w)
                + (s[axis] - north[0][axis])
                + (se[axis] - se_nw)
                + (sw[axis] - sw_ne);
            if let Some(ext) = self.ext {
                force += m(ext[axis]);
            }
            // SAFETY: `k < chunks`.
            let v = unsafe { h.vel(k) }[axis];
            let acc = (force - viscosity * v) * inv_mass + free.select(self.g[axis], Lane::ZERO);
            let v1 = v + acc * self.dt;
            new[axis] = h0[axis] + v1 * self.dt;
            new[axis + 3] = v1;
        }
        *e_west = e;
        new
    }
}
