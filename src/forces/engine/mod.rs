//! The engine: colour-partitioned bands of rows, SIMD across columns, rayon across bands,
//! and several steps per pass over memory, at the SIMD level the CPU has.
//!
//! * [`row`]: the row kernel, one row advanced one step in one pass over its chunks.
//! * [`schedule`]: bands, colours, handoffs and the wavefront over layers.
//! * [`scratch`]: the chunk-major rows the kernel reads and writes besides the state.
//!
//! # Several steps per pass (layers)
//!
//! One step reads 56 B per node and writes 48 B, and on a grid larger than the caches
//! that traffic, not arithmetic, sets the speed. A pass therefore advances `layers` steps
//! while reading the state once: layer 0 is the front buffer, the last layer goes to the
//! back buffer, and every layer in between lives in a ring of two rows per layer that
//! stays in cache. Only the last layer is written to memory, on large grids with
//! non-temporal stores ([`STREAM_MIN_NODES`]).
//!
//! # Levels of SIMD
//!
//! [`pass`] picks the vector type of the surface's [`SimdLevel`] once per pass; the
//! schedule is generic over it, and each band's loop enters the level's instruction set
//! through [`crate::simd::Vector::enter`] (a `#[target_feature]` function, once per band
//! and pass). Each row's kernel is an entry of its own, called from that loop: one
//! function holding the band and all eight of its row kernels took LLVM minutes to
//! compile. Nothing in the loop is a closure: a closure is compiled as a function of its
//! own, without the level's instruction set. Every level computes the same operations in
//! the same order, so the results do not depend on it, nor on the thread count.

mod access;
mod row;
mod schedule;
mod scratch;
pub(crate) mod tiling;

use super::StepConfig;
use crate::jobs::Runner;
use crate::simd::{Kernel, SimdLevel, Vector};
use crate::springs::Springs;
use crate::state::State;
use access::Claims;
pub(crate) use schedule::PassEnd;
use scratch::Row;
use std::any::Any;
use tiling::Tiling;

/// Most steps one pass takes.
pub const MAX_PASS_STEPS: usize = 8;

/// Steps per pass when the caller does not fix it (see `docs/performance.md`: past 4
/// the rows in flight of a 2048-column pass outgrow a 1 MB L2).
pub const DEFAULT_PASS_STEPS: usize = 4;

/// Grids of at least this many nodes (and whole chunks per row) write the last layer of a
/// pass with non-temporal stores ([`Vector::stream`]): the back buffers are not read
/// before the next pass, and on a grid larger than the caches that read would come from
/// memory anyway, so loading each line before writing it only costs bandwidth. At 2¹⁹
/// nodes the front and back state take 25 MB, near a 32 MB L3 (`docs/performance.md`).
pub const STREAM_MIN_NODES: usize = 1 << 19;

/// What an even band hands to the odd band across one cut: for each layer `1..layers`,
/// the two rows next to the cut (upper first).
pub(crate) type Handoff<V> = Vec<[Row<V>; 2]>;

/// The engine's reusable buffers: the tiling in use and one [`Handoff`] per cut.
pub(crate) struct Workspace {
    /// A band height fixed by the caller, or `None` to follow [`tiling::band_rows`].
    fixed_band_rows: Option<usize>,
    /// Steps per pass.
    pub pass_steps: usize,
    /// The tiling, columns and vector type the handoffs were made for.
    made_for: Option<(Tiling, usize, std::any::TypeId)>,
    /// `Vec<Handoff<V>>` for that vector type: slot `b` holds what crosses the cut above
    /// band `b` (slot 0 is unused).
    handoffs: Option<Box<dyn Any + Send + Sync>>,
    /// One flag per band: which bands of the running colour have been taken by a task.
    claims: Claims,
}

impl Clone for Workspace {
    /// The same schedule; the handoff buffers are made again on the first pass.
    fn clone(&self) -> Self {
        Self {
            fixed_band_rows: self.fixed_band_rows,
            pass_steps: self.pass_steps,
            made_for: None,
            handoffs: None,
            claims: Claims::new(0),
        }
    }
}

impl std::fmt::Debug for Workspace {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.debug_struct("Workspace")
            .field("fixed_band_rows", &self.fixed_band_rows)
            .field("pass_steps", &self.pass_steps)
            .finish_non_exhaustive()
    }
}

impl Workspace {
    pub fn new(fixed_band_rows: Option<usize>) -> Self {
        Self {
            fixed_band_rows: fixed_band_rows.map(|h| h.max(1)),
            pass_steps: DEFAULT_PASS_STEPS,
            made_for: None,
            handoffs: None,
            claims: Claims::new(0),
        }
    }

    /// The tiling for a pass of `layers` steps on `workers` threads, its handoff slots and
    /// band claims, made again when the tiling, the width or the vector type changes.
    fn prepare<V: Vector>(
        &mut self,
        cols: usize,
        rows: usize,
        layers: usize,
        workers: usize,
    ) -> (Tiling, &mut Vec<Handoff<V>>, &mut Claims) {
        let tiling = self.tiling(rows, layers, workers);
        let key = (tiling, cols, std::any::TypeId::of::<V>());
        if self.made_for != Some(key) || self.handoffs.is_none() {
            let slots = if tiling.bands() > 1 {
                tiling.bands()
            } else {
                0
            };
            let handoffs: Vec<Handoff<V>> = (0..slots)
                .map(|b| {
                    let layers = if b == 0 { 0 } else { layers - 1 };
                    (0..layers)
                        .map(|_| [Row::new(cols), Row::new(cols)])
                        .collect()
                })
                .collect();
            self.handoffs = Some(Box::new(handoffs));
            self.claims = Claims::new(tiling.bands());
            self.made_for = Some(key);
        }
        let handoffs = self
            .handoffs
            .as_mut()
            .and_then(|h| h.downcast_mut::<Vec<Handoff<V>>>())
            .expect("the handoffs were made for this vector type");
        (tiling, handoffs, &mut self.claims)
    }

    /// How a pass of `layers` steps cuts `rows` rows for `workers` threads.
    pub fn tiling(&self, rows: usize, layers: usize, workers: usize) -> Tiling {
        let band_rows = self
            .fixed_band_rows
            .unwrap_or_else(|| tiling::band_rows(rows, workers));
        Tiling::new(rows, band_rows, layers)
    }
}

/// One engine pass of `layers` steps (`1..=MAX_PASS_STEPS`) from the front into the back
/// buffers, with the lanes of `level` (clamped to the CPU's; the portable lanes for
/// [`SimdLevel::Scalar`], whose callers run the scalar reference instead), each colour's
/// bands run by `runner`.
pub(crate) fn pass(
    state: &mut State,
    springs: &Springs,
    ws: &mut Workspace,
    cfg: StepConfig,
    layers: usize,
    level: SimdLevel,
    runner: Runner<'_>,
) -> PassEnd {
    crate::simd::dispatch(
        level,
        Pass {
            state,
            springs,
            ws,
            cfg,
            layers,
            runner,
        },
    )
}

/// [`pass`]'s arguments, as a kernel of any vector type.
struct Pass<'a> {
    state: &'a mut State,
    springs: &'a Springs,
    ws: &'a mut Workspace,
    cfg: StepConfig,
    layers: usize,
    runner: Runner<'a>,
}

impl Kernel for Pass<'_> {
    type Output = PassEnd;

    #[inline(always)]
    fn run<V: Vector>(self) -> PassEnd {
        schedule::pass_with::<V>(
            self.state,
            self.springs,
            self.ws,
            self.cfg,
            self.layers,
            self.runner,
        )
    }
}
