//! [`Surface`]: the water surface a game owns, steps and reads. One file per concern:
//!
//! | file | owns |
//! |---|---|
//! | `mod.rs` | the state a surface holds, construction, accessors, where its steps run |
//! | `step.rs` | the one stepping path every step goes through |
//! | `clock.rs` | the game's clock: frames of seconds into whole steps (`advance`) |
//! | `edit.rs` | drops, forces, pins, per-node values and springs between steps |
//! | `query.rs` | heights, normals and velocities at a point; forces at a point |
//! | `bodies/` | the bodies' subsystem: floating bodies, the coupled step, the water column under them, their section of a snapshot |
//! | `window.rs` | the moving window and the floating origin |
//! | `snapshot/` | snapshots: the whole state as bytes and back, `save_into`, `state_hash` |
//! | `bytes.rs` | little-endian fields the snapshot's sections share (a sink, a reader) |
//! | `tuning.rs` | the engine's schedule knobs for tests and benchmarks (`internals`) |

pub(crate) mod bodies;
mod bytes;
mod clock;
mod disturbance;
mod edit;
pub(crate) mod query;
pub use query::WaterSample;
pub(crate) mod snapshot;
mod step;
#[cfg(feature = "internals")]
pub(crate) mod tuning;
pub mod window;

pub use clock::Overflow;
pub use disturbance::Disturbance;
pub use window::{FarField, MAX_ORIGIN_CELLS};

use crate::error::Result;
use crate::forces;
use crate::forces::engine::Workspace;
use crate::grid::Grid;
use crate::jobs::{Host, JobSystem, Runner};
use crate::params::Params;
use crate::simd::SimdLevel;
use crate::springs::Springs;
use crate::stability::Stability;
use crate::state::State;
use crate::view::MeshView;
use std::sync::Arc;

/// One spring's parameters, as [`Surface::spring`] reads and [`Surface::set_spring`]
/// writes them. Named fields, so the two numbers cannot be swapped silently.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Spring {
    /// Rest length `L0` in world units (≥ 0).
    pub rest: f32,
    /// Coefficient `c` (> 0): the force per unit of stretch.
    pub stiffness: f32,
}

/// Kinetic and spring potential energy of the surface (computed in `f64`).
#[derive(Debug, Clone, Copy, PartialEq, Default)]
pub struct Energy {
    /// `Σ ½ m |v|²` over free nodes.
    pub kinetic: f64,
    /// `Σ ½ c (L − L0)²` over all springs.
    pub potential: f64,
}

impl Energy {
    /// Kinetic plus potential.
    pub fn total(&self) -> f64 {
        self.kinetic + self.potential
    }
}

/// A mass-spring water surface: structure-of-arrays state, spring tables, colour batches.
///
/// ```
/// use springwater::{Params, Surface};
///
/// let mut water = Surface::new(Params::with_size(64, 48))?;
/// water.drop_at(32.0, 24.0, 1.5, 3.0)?;       // a drop in the middle
/// water.advance(1.0 / 60.0)?;                 // one 60 Hz frame: seconds in
/// let [_x, y, _z] = water.positions();
/// assert!(y.iter().any(|&h| h != 0.0));
/// # Ok::<(), springwater::Error>(())
/// ```
#[derive(Debug, Clone)]
pub struct Surface {
    params: Params,
    /// The nodes, their springs and the stability bounds they have reached.
    lattice: Lattice,
    /// The engine's buffers and schedule (band height, steps per pass).
    workspace: Workspace,
    /// The scalar reference's buffers, for the reference level.
    reference: forces::scalar::Scratch,
    /// The instruction set the engine runs.
    simd: SimdLevel,
    steps: u64,
    time: f64,
    /// The accumulator of [`Surface::advance`] and its cap.
    clock: clock::Clock,
    /// The host's threads the engine steps on; `None`: rayon's global pool.
    host: Option<Host>,
    /// Floating bodies, their world and the water column under them.
    bodies: bodies::BodySet,
    /// Where the moving window is, and what a shift must move (see [`window`]).
    window: window::Placement,
}

/// The lattice a surface steps: the nodes' state (with the external forces waiting for
/// the next step, [`crate::state::External`]), the spring tables, and the stability
/// bounds they have reached ([`Stability`]: the smallest node mass, largest spring
/// coefficient and largest viscosity ever set, which set `critical_dt`).
#[derive(Debug, Clone)]
struct Lattice {
    state: State,
    springs: Springs,
    stability: Stability,
}

/// The node state for the unit tests of `state.rs` (the fields are private to `surface/`).
#[cfg(test)]
impl Surface {
    pub(crate) fn state_ref(&self) -> &State {
        &self.lattice.state
    }

    pub(crate) fn state_mut(&mut self) -> &mut State {
        &mut self.lattice.state
    }
}

impl Surface {
    /// Most steps one [`Surface::advance`] call may be allowed to take
    /// ([`Surface::set_step_cap`]), and most substeps of [`Surface::advance_variable`].
    pub const MAX_SUBSTEPS: usize = 10_000;

    /// A flat surface at rest with the given parameters, validated.
    ///
    /// The engine runs the widest SIMD level the CPU has ([`SimdLevel::detect`]);
    /// [`Surface::set_simd_level`] chooses another. The library never reads the process
    /// environment: `SPRINGWATER_SIMD` is the command line's and the tests' way to force a
    /// level ([`SimdLevel::from_env`] reads it for a host that wants the same).
    pub fn new(params: Params) -> Result<Self> {
        params.validate()?;
        Ok(Self::build(params))
    }

    /// Like [`Surface::new`] but without the critical-timestep check: for experiments
    /// that probe the stability limit on purpose (such a surface may well blow up; its
    /// steps then return [`Error::NonFinite`](crate::Error::NonFinite)). Every other field
    /// is still validated, and nothing here is `unsafe`.
    pub fn new_without_dt_check(params: Params) -> Result<Self> {
        params.validate_except_dt()?;
        Ok(Self::build(params))
    }

    /// The SIMD level the engine runs. Every level gives the same results, bit for bit.
    pub fn simd_level(&self) -> SimdLevel {
        self.simd
    }

    /// Runs the engine at `level`, clamped to what the CPU has, and returns the level it
    /// will run. [`SimdLevel::Scalar`] runs the scalar reference loops. Results do not
    /// change by a bit; only the speed does.
    pub fn set_simd_level(&mut self, level: SimdLevel) -> SimdLevel {
        self.simd = level.clamped();
        self.simd
    }

    fn build(params: Params) -> Self {
        let (state, springs) = (State::new(&params), Springs::new(&params));
        let max_viscosity = state
            .viscosity
            .iter()
            .fold(params.viscosity, |a, &b| a.max(b));
        let bounds = [params.mass, params.stiffness, max_viscosity];
        Self::from_parts(params, state, springs, bounds, (0, 0.0))
    }

    /// A surface from validated parts (used by [`Surface::new`] and the snapshot loader).
    /// `bounds` is `[min_mass, max_stiffness, max_viscosity]`, `progress` is `(steps, time)`.
    /// The engine's scratch buffers are rebuilt: they are not state.
    pub(crate) fn from_parts(
        params: Params,
        state: State,
        springs: Springs,
        bounds: [f32; 3],
        progress: (u64, f64),
    ) -> Self {
        Self {
            workspace: Workspace::new(None),
            reference: Default::default(),
            simd: SimdLevel::detect(),
            lattice: Lattice {
                state,
                springs,
                stability: Stability::from_bounds(bounds),
            },
            steps: progress.0,
            time: progress.1,
            clock: Default::default(),
            params,
            host: None,
            bodies: Default::default(),
            window: Default::default(),
        }
    }

    /// The parameters the surface was built with.
    pub fn params(&self) -> &Params {
        &self.params
    }

    /// The grid shape.
    pub fn grid(&self) -> Grid {
        self.lattice.state.grid
    }

    /// Number of nodes, `cols × rows` (C: `sw_surface_node_count`).
    pub fn node_count(&self) -> usize {
        self.lattice.state.len()
    }

    /// Number of nodes.
    #[deprecated(
        since = "0.2.0",
        note = "use `node_count`, the one name for the node count"
    )]
    pub fn len(&self) -> usize {
        self.node_count()
    }

    /// Always false: a surface has at least 2×2 nodes.
    #[deprecated(
        since = "0.2.0",
        note = "a surface is never empty (at least 2×2 nodes)"
    )]
    pub fn is_empty(&self) -> bool {
        false
    }

    /// Steps taken so far.
    pub fn steps(&self) -> u64 {
        self.steps
    }

    /// Seconds of the game's clock simulated so far: [`Surface::model_time`] divided by
    /// `params().time_scale` (1 after 60 steps of the default `dt` 0.4 at the default time
    /// scale of 24).
    pub fn time(&self) -> f64 {
        self.time / self.params.time_scale as f64
    }

    /// Model time simulated so far, in the lattice's own time unit: the sum of the steps'
    /// `dt` (what the snapshot stores; [`Surface::time`] is the same in seconds).
    pub fn model_time(&self) -> f64 {
        self.time
    }

    /// The largest safe timestep for the current tables: `sqrt(min m / (3 max c))`, a little
    /// less with viscosity (see [`Params`]).
    ///
    /// While bodies float ([`Surface::add_floater`]) their waterlines stiffen the nodes
    /// under them, and the limit includes that (see [`crate::floater`]).
    pub fn critical_dt(&self) -> f32 {
        self.lattice.stability.critical_dt(self.floater_stiffness())
    }

    /// Refuses `params().dt` for `stability`, the bounds an edit would give the surface,
    /// with its bodies' waterlines.
    fn admit_bounds(&self, stability: Stability) -> Result<()> {
        stability.admit(self.params.dt, self.floater_stiffness())
    }

    /// Positions `[x, y, z]`, one value per node, row-major.
    pub fn positions(&self) -> [&[f32]; 3] {
        let n = self.node_count();
        [
            &self.lattice.state.pos[0][..n],
            &self.lattice.state.pos[1][..n],
            &self.lattice.state.pos[2][..n],
        ]
    }

    /// Velocities `[vx, vy, vz]`, one value per node, row-major: the lattice's own state,
    /// in world units per unit of *model time* (borrowed, not converted; multiply by
    /// `params().time_scale` for per second, or read [`Surface::velocity_at`], which does).
    pub fn velocities(&self) -> [&[f32]; 3] {
        let n = self.node_count();
        [
            &self.lattice.state.vel[0][..n],
            &self.lattice.state.vel[1][..n],
            &self.lattice.state.vel[2][..n],
        ]
    }

    /// Runs the engine's steps on `pool`, the host's rayon thread pool, instead of rayon's
    /// global pool (`None` goes back to it). Every stepping call ([`Surface::step`],
    /// [`Surface::step_n`], [`Surface::advance`], [`Surface::advance_with`]) then runs its
    /// colour batches on that pool's threads; disturbances and the caller's code between
    /// substeps stay on the calling thread. Results are bitwise the same on any pool and
    /// any number of threads. Clones of the surface share the pool.
    ///
    /// The render-side stages ([`crate::mesh`], [`crate::refraction`],
    /// [`crate::buffers`]) on this surface's [`Surface::mesh_view`] run on the same pool.
    ///
    /// ```
    /// use std::sync::Arc;
    /// use springwater::{Params, Surface};
    ///
    /// let pool = Arc::new(rayon::ThreadPoolBuilder::new().num_threads(2).build().unwrap());
    /// let mut water = Surface::new(Params::with_size(64, 64))?;
    /// water.set_thread_pool(Some(pool.clone()));
    /// water.drop_at(32.0, 32.0, 1.0, 3.0)?;
    /// water.advance(1.0 / 60.0)?;                      // on the host's two threads
    /// assert!(water.thread_pool().is_some());
    /// # Ok::<(), springwater::Error>(())
    /// ```
    ///
    /// Setting a pool replaces a job system set with [`Surface::set_job_system`].
    #[cfg(feature = "parallel")]
    pub fn set_thread_pool(&mut self, pool: Option<Arc<rayon::ThreadPool>>) {
        self.host = pool.map(Host::Pool);
    }

    /// The host's thread pool set with [`Surface::set_thread_pool`], if any.
    #[cfg(feature = "parallel")]
    pub fn thread_pool(&self) -> Option<&Arc<rayon::ThreadPool>> {
        match &self.host {
            Some(Host::Pool(pool)) => Some(pool),
            _ => None,
        }
    }

    /// Runs the engine's colour batches through `jobs`, the host's own job system (an
    /// engine's worker threads, Bevy's task pools, a C engine's scheduler), instead of
    /// rayon (`None` goes back to rayon's global pool). Each pass of the engine hands it
    /// two batches of independent tasks, one per colour, from the thread that called the
    /// stepping method; see [`JobSystem`]. Results are bitwise the same as on rayon's
    /// pool, whatever threads and order the job system uses. Clones of the surface share
    /// the job system; setting one replaces a pool set with `set_thread_pool`.
    ///
    /// The render-side stages ([`crate::mesh`], [`crate::refraction`],
    /// [`crate::buffers`]) on this surface's [`Surface::mesh_view`] run their parts through
    /// the same job system.
    ///
    /// If the job system returns without running every task it was given, the step fails
    /// with [`Error::JobSystem`](crate::Error::JobSystem) and the surface is unchanged (a render-side stage runs
    /// the skipped parts itself, on the calling thread).
    pub fn set_job_system(&mut self, jobs: Option<Arc<dyn JobSystem>>) {
        self.host = jobs.map(Host::Jobs);
    }

    /// The host's job system set with [`Surface::set_job_system`], if any.
    pub fn job_system(&self) -> Option<&Arc<dyn JobSystem>> {
        match &self.host {
            Some(Host::Jobs(jobs)) => Some(jobs),
            _ => None,
        }
    }

    /// A borrowed view of the positions and grid shape for the render-side stages.
    pub fn mesh_view(&self) -> MeshView<'_> {
        let [x, y, z] = self.positions();
        MeshView::new(self.grid(), self.params.spacing, x, y, z)
            .expect("the surface's own buffers match its grid")
            .with_simd_level(self.simd)
            .with_runner(Runner::of(self.host.as_ref()))
            .with_origin(self.origin())
    }

    /// Kinetic plus spring potential energy, a diagnostic (`O(nodes)`).
    pub fn energy(&self) -> Energy {
        let s = &self.lattice.state;
        let n = self.node_count();
        let mut kinetic = 0.0;
        for i in (0..n).filter(|&i| !s.pinned[i]) {
            let v2: f64 = (0..3).map(|k| (s.vel[k][i] as f64).powi(2)).sum();
            kinetic += 0.5 * s.mass.get(i) as f64 * v2;
        }
        let mut potential = 0.0;
        for (id, j) in self.grid().springs() {
            let i = id.origin;
            let l = (0..3)
                .map(|k| (s.pos[k][j] as f64 - s.pos[k][i] as f64).powi(2))
                .sum::<f64>()
                .sqrt();
            let (coef, rest) = self.lattice.springs.get(id.family, i);
            let stretch = l - rest as f64;
            potential += 0.5 * coef as f64 * stretch * stretch;
        }
        Energy { kinetic, potential }
    }
}
