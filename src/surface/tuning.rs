//! The engine's schedule knobs for the crate's tests, benchmarks and command line
//! (`springwater::internals::Tuning`, behind the `internals` feature). A trait rather
//! than methods, so that the feature adds a module and leaves [`Surface`]'s own methods
//! as they are. None of them changes a result by a bit: only how the work is cut. One
//! reader beside them, for the tests of what the water gets from floating bodies: the
//! load the water column carries.

use super::Surface;
use crate::forces::engine::tiling::{self, Band};
use crate::forces::engine::{Workspace, MAX_PASS_STEPS};
use crate::jobs::Runner;

/// How the engine cuts a step into colour batches and passes.
pub trait Tuning {
    /// Fixes the band height (colour granularity) instead of `band_rows`'s choice.
    fn set_band_rows(&mut self, band_rows: usize);
    /// Fixes how many steps one engine pass takes (`1..=8`, clamped; default 4).
    fn set_pass_steps(&mut self, steps: usize);
    /// The colour batches the engine uses on the current thread pool: bands of rows, even
    /// bands colour 0, odd bands colour 1 (see [`tiling::Tiling`]), as they stand at the
    /// start of a pass (the tiling says how they lean through its steps).
    fn bands(&self) -> impl Iterator<Item = Band>;
    /// The water column under the bodies, node by node (sorted): the load each node
    /// carries and the load waiting for the next step from `body_forces` (the lattice's
    /// force units). The next step's external force on a node gets the bodies' push minus
    /// what it carries (see `docs/floating.md`).
    fn water_column(&self) -> Vec<(usize, [f32; 3], [f32; 3])>;
}

impl Tuning for Surface {
    fn set_band_rows(&mut self, band_rows: usize) {
        let pass_steps = self.workspace.pass_steps;
        self.workspace = Workspace::new(Some(band_rows));
        self.workspace.pass_steps = pass_steps;
    }

    fn set_pass_steps(&mut self, steps: usize) {
        self.workspace.pass_steps = steps.clamp(1, MAX_PASS_STEPS);
    }

    fn bands(&self) -> impl Iterator<Item = Band> {
        let workers = Runner::of(self.host.as_ref()).workers();
        let tiling = self
            .workspace
            .tiling(self.params.rows, self.workspace.pass_steps, workers);
        tiling::bands(self.params.rows, tiling.band_rows)
    }

    fn water_column(&self) -> Vec<(usize, [f32; 3], [f32; 3])> {
        let entries = self.bodies.column().entries();
        entries
            .iter()
            .map(|e| (e.node, e.carried, e.pending))
            .collect()
    }
}
