//! [`Surface`]: the water surface a game owns, steps and reads — all of it here: the
//! state and stepping (this file), the point queries and forces at a point ([`query`]),
//! and snapshots ([`snapshot`]).

mod clock;
mod disturbance;
mod floaters;
pub(crate) mod query;
pub use query::WaterSample;
pub(crate) mod snapshot;
pub mod window;

pub use clock::Overflow;
pub use disturbance::Disturbance;
use window::rest_coordinate;
pub use window::{FarField, MAX_ORIGIN_CELLS};

use crate::error::{same_length, Error, Result};
use crate::forces::engine::{PassEnd, Workspace};
use crate::forces::{self, StepConfig};
use crate::grid::{Grid, SpringId};
use crate::jobs::{Host, JobSystem, Runner};
use crate::params::{self, Params};
use crate::simd::SimdLevel;
use crate::springs::Springs;
use crate::state::{NodeValues, State};
use crate::view::MeshView;
use std::sync::Arc;

/// Which implementation of the step to run: the engine at the surface's SIMD level, or
/// the scalar reference (what [`SimdLevel::Scalar`] runs).
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub(crate) enum Stepper {
    /// Colour-partitioned bands, SIMD lanes, the host's threads.
    Engine,
    /// The plain scalar loops the engine is tested against.
    Reference,
}

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
    pub(crate) state: State,
    pub(crate) springs: Springs,
    workspace: Workspace,
    reference: forces::scalar::Scratch,
    /// The instruction set the engine runs.
    pub(crate) simd: SimdLevel,
    /// Smallest node mass, largest spring coefficient and largest viscosity ever set: they
    /// set `critical_dt`.
    pub(crate) min_mass: f32,
    pub(crate) max_stiffness: f32,
    pub(crate) max_viscosity: f32,
    steps: u64,
    time: f64,
    /// The accumulator of [`Surface::advance`] and its cap.
    pub(crate) clock: clock::Clock,
    /// The host's threads the engine steps on; `None`: rayon's global pool.
    pub(crate) host: Option<Host>,
    /// Floating bodies and their world.
    pub(crate) floaters: floaters::Floaters,
    /// Whole cells the window has travelled, `[cols, rows]` (see [`window`]).
    pub(crate) window_origin: [i64; 2],
    /// Whether a per-node mass, viscosity or pin may differ from its place's default (a
    /// shift then moves them; see [`window`]).
    pub(crate) window_custom: bool,
}

impl Surface {
    /// Most steps one [`Surface::advance`] call may be allowed to take
    /// ([`Surface::set_step_cap`]), and most substeps of [`Surface::advance_variable`].
    pub const MAX_SUBSTEPS: usize = 10_000;

    /// A flat surface at rest with the given parameters, validated.
    ///
    /// The engine runs the widest SIMD level the CPU has, or the one `SPRINGWATER_SIMD`
    /// names (see [`SimdLevel::from_env`]; an unknown name is an error).
    pub fn new(params: Params) -> Result<Self> {
        params.validate()?;
        Self::build(params).with_env_simd()
    }

    /// Like [`Surface::new`] but without the critical-timestep check: for experiments
    /// that probe the stability limit on purpose (such a surface may well blow up; its
    /// steps then return [`Error::NonFinite`]). Every other field is still validated, and
    /// nothing here is `unsafe`.
    pub fn new_without_dt_check(params: Params) -> Result<Self> {
        params.validate_except_dt()?;
        Self::build(params).with_env_simd()
    }

    pub(crate) fn with_env_simd(mut self) -> Result<Self> {
        self.simd = SimdLevel::from_env()?;
        Ok(self)
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
        let [min_mass, max_stiffness, max_viscosity] = bounds;
        Self {
            workspace: Workspace::new(None),
            reference: Default::default(),
            simd: SimdLevel::detect(),
            state,
            springs,
            min_mass,
            max_stiffness,
            max_viscosity,
            steps: progress.0,
            time: progress.1,
            clock: Default::default(),
            params,
            host: None,
            floaters: Default::default(),
            window_origin: [0, 0],
            window_custom: false,
        }
    }

    /// Fixes the band height (colour granularity) of the engine instead of
    /// `band_rows`. Results do not change by a bit; for benchmarks and tests.
    #[cfg(feature = "internals")]
    #[doc(hidden)]
    pub fn set_band_rows(&mut self, band_rows: usize) {
        let pass_steps = self.workspace.pass_steps;
        self.workspace = Workspace::new(Some(band_rows));
        self.workspace.pass_steps = pass_steps;
    }

    /// The parameters the surface was built with.
    pub fn params(&self) -> &Params {
        &self.params
    }

    /// The grid shape.
    pub fn grid(&self) -> Grid {
        self.state.grid
    }

    /// Number of nodes, `cols × rows` (C: `sw_surface_node_count`).
    pub fn node_count(&self) -> usize {
        self.state.len()
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
        self.limit(self.min_mass, self.max_stiffness, self.max_viscosity)
    }

    /// The critical timestep for these bounds and the surface's bodies.
    fn limit(&self, min_mass: f32, max_stiffness: f32, max_viscosity: f32) -> f32 {
        params::critical_dt_with(
            min_mass,
            max_stiffness,
            max_viscosity,
            self.floater_stiffness(),
        )
    }

    /// Positions `[x, y, z]`, one value per node, row-major.
    pub fn positions(&self) -> [&[f32]; 3] {
        let n = self.node_count();
        [
            &self.state.pos[0][..n],
            &self.state.pos[1][..n],
            &self.state.pos[2][..n],
        ]
    }

    /// Velocities `[vx, vy, vz]`, one value per node, row-major: the lattice's own state,
    /// in world units per unit of *model time* (borrowed, not converted; multiply by
    /// `params().time_scale` for per second, or read [`Surface::velocity_at`], which does).
    pub fn velocities(&self) -> [&[f32]; 3] {
        let n = self.node_count();
        [
            &self.state.vel[0][..n],
            &self.state.vel[1][..n],
            &self.state.vel[2][..n],
        ]
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

    /// Advances one step of `params().dt`, at the surface's SIMD level
    /// ([`Surface::set_simd_level`]; [`SimdLevel::Scalar`] runs the plain scalar loops the
    /// engine is tested against, with the same bits).
    ///
    /// The step is transactional: the new state is written to back buffers and checked
    /// for finiteness in the same pass; only if every value is finite are the buffers
    /// swapped (and the external force buffer cleared). Otherwise the step returns
    /// [`Error::NonFinite`] and the surface is bitwise unchanged, pending forces included
    /// ([`Surface::clear_forces`] drops them). The engine's check is one multiply and one
    /// add per lane on values already in registers, the swap two pointer swaps, the memory
    /// cost the back buffers (24 bytes per node). Measured against a build without the
    /// check, the difference was below this machine's run-to-run noise (a few percent at
    /// most; docs/reliability.md has the numbers).
    pub fn step(&mut self) -> Result<()> {
        self.step_dt(self.params.dt, Stepper::Engine)
    }

    /// Advances `n` steps of `params().dt` with the engine, several per pass over memory
    /// (see `src/forces/engine/`). Bitwise the same as `n` calls of [`Surface::step`], and as
    /// transactional per step: if a step would make the state non-finite, the steps before
    /// it stay applied, that one is not, and its error is returned.
    pub fn step_n(&mut self, n: u64) -> Result<()> {
        self.run_steps(n, self.params.dt)
    }

    /// Fixes how many steps one engine pass takes (`1..=8`, clamped; default 4). Results
    /// do not change by a bit; for benchmarks and tests.
    #[cfg(feature = "internals")]
    #[doc(hidden)]
    pub fn set_pass_steps(&mut self, steps: usize) {
        self.workspace.pass_steps = steps.clamp(1, forces::engine::MAX_PASS_STEPS);
    }

    fn config(&self, dt: f32) -> StepConfig {
        // The acceleration is per second², the lattice's per unit of model time²:
        // divided by `time_scale²` (a normal number, see `Params::validate`). `+ 0.0`
        // turns a −0 acceleration into +0, which keeps a zero force's sign from reaching
        // the state (see `forces::engine`).
        let ts2 = self.params.time_scale * self.params.time_scale;
        StepConfig {
            dt,
            accel: self.params.acceleration.map(|a| a / ts2 + 0.0),
        }
    }

    fn step_dt(&mut self, dt: f32, stepper: Stepper) -> Result<()> {
        if !self.floaters.bodies.is_empty() {
            return self.floating_step(dt, stepper);
        }
        self.water_step(dt, stepper)
    }

    /// One step of the water alone.
    pub(crate) fn water_step(&mut self, dt: f32, stepper: Stepper) -> Result<()> {
        match stepper {
            Stepper::Engine => self.water_steps(1, dt),
            Stepper::Reference => {
                let cfg = self.config(dt);
                match forces::scalar::step(&mut self.state, &self.springs, &mut self.reference, cfg)
                {
                    Ok(()) => {
                        self.commit(1, dt);
                        Ok(())
                    }
                    Err(node) => Err(self.non_finite(node)),
                }
            }
        }
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
    /// with [`Error::JobSystem`] and the surface is unchanged (a render-side stage runs
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

    /// `n` engine steps of the water and its bodies: with bodies one coupled step at a
    /// time, without them [`Surface::water_steps`].
    fn run_steps(&mut self, n: u64, dt: f32) -> Result<()> {
        if !self.floaters.bodies.is_empty() {
            // Bodies read the water between steps: one step at a time.
            for _ in 0..n {
                self.step_dt(dt, Stepper::Engine)?;
            }
            return Ok(());
        }
        self.water_steps(n, dt)
    }

    /// `n` engine steps of the water alone, on the host's threads if they are set (see
    /// [`Surface::set_thread_pool`], [`Surface::set_job_system`]), else where the caller is.
    fn water_steps(&mut self, n: u64, dt: f32) -> Result<()> {
        match self.host.clone() {
            #[cfg(feature = "parallel")]
            Some(Host::Pool(pool)) if pool.current_thread_index().is_none() => {
                pool.install(|| self.engine_steps_on(n, dt, Runner::Here))
            }
            Some(Host::Jobs(jobs)) => self.engine_steps_on(n, dt, Runner::Jobs(&*jobs)),
            _ => self.engine_steps_on(n, dt, Runner::Here),
        }
    }

    /// `n` engine steps, in passes of up to `pass_steps`, each colour run by `runner`. A
    /// pass that fails is redone one step at a time, so the error names the exact step
    /// and node.
    fn engine_steps_on(&mut self, n: u64, dt: f32, runner: Runner<'_>) -> Result<()> {
        if self.simd == SimdLevel::Scalar {
            for _ in 0..n {
                self.water_step(dt, Stepper::Reference)?;
            }
            return Ok(());
        }
        let cfg = self.config(dt);
        let mut left = n;
        while left > 0 {
            let k = left.min(self.workspace.pass_steps as u64) as usize;
            let (state, springs, ws) = (&mut self.state, &self.springs, &mut self.workspace);
            match forces::engine::pass(state, springs, ws, cfg, k, self.simd, runner) {
                PassEnd::Done => self.commit(k, dt),
                PassEnd::Incomplete => return Err(Error::JobSystem),
                PassEnd::NonFinite if k > 1 => {
                    for _ in 0..k {
                        self.engine_steps_on(1, dt, runner)?;
                    }
                }
                PassEnd::NonFinite => {
                    let node = self.state.first_non_finite_next().unwrap_or(0);
                    return Err(self.non_finite(node));
                }
            }
            left -= k as u64;
        }
        Ok(())
    }

    /// Makes `k` steps written to the back buffers the state.
    fn commit(&mut self, k: usize, dt: f32) {
        self.state.swap();
        self.state.clear_ext();
        self.steps += k as u64;
        for _ in 0..k {
            self.time += dt as f64;
        }
    }

    fn non_finite(&self, node: usize) -> Error {
        Error::NonFinite {
            step: self.steps,
            node,
        }
    }

    /// Advances the water by one frame of a game's clock, `frame_seconds` seconds long, in
    /// whole steps of `params().dt`: the frame's time (times `params().time_scale`) goes
    /// into an accumulator of model time (kept in `f64`, part of the state and of
    /// snapshots), and every whole step it holds is taken (a step is due 10⁻⁴ of a step
    /// early, so that the rounding of `f32` frame lengths never costs one). Returns the number of steps taken: 0 when the frame was shorter than what
    /// the accumulator lacked for the next step, 1 for a 60 Hz frame at the defaults.
    ///
    /// The state depends on the total time passed, not on how it was cut into frames:
    /// 60 frames of 1/60 s, jittered frames or 59.94 Hz frames that add up to the same
    /// second give the same bits. [`Surface::interpolation`] is the fraction of a step the
    /// game's clock is past the water's. A frame that owes more than the cap
    /// ([`Surface::set_step_cap`], [`Surface::DEFAULT_MAX_STEPS`]) takes the cap's steps and
    /// drops the rest, or carries it into the next calls ([`Overflow`]);
    /// [`Surface::dropped_seconds`] and [`Surface::owed_seconds`] say which.
    ///
    /// A negative or non-finite frame is refused with nothing changed. A failing step stops
    /// the frame there and returns its error: the earlier steps stay applied, the failing
    /// one is not, and the frame's time is spent (if no step was taken, nothing changed,
    /// the accumulator included). See [`Surface::advance_with`]
    /// to disturb the water before every step.
    ///
    /// ```
    /// use springwater::{Params, Surface};
    ///
    /// let mut water = Surface::new(Params::with_size(32, 32))?;
    /// let frames = [0.016, 0.0173, 0.0167, 0.0167];     // a jittery display
    /// let steps: usize = frames.iter().map(|&f| water.advance(f)).sum::<Result<_, _>>()?;
    /// assert_eq!(steps, 4);                               // 0.0667 s: four steps of 1/60 s
    /// assert!((0.0..1.0).contains(&water.interpolation()));
    /// # Ok::<(), springwater::Error>(())
    /// ```
    pub fn advance(&mut self, frame_seconds: f32) -> Result<usize> {
        let (clock, before) = (self.clock, self.steps);
        let steps = self.tick(frame_seconds)?;
        // Nothing reads the water between these steps: the engine takes several per pass.
        let result = self.run_steps(steps as u64, self.params.dt);
        self.settle(clock, before, steps, result)
    }

    /// [`Surface::advance`] with `disturbance` applied before every step, with the step's
    /// length in seconds, `params().dt / params().time_scale`: rain, wakes, buoyancy,
    /// anything implementing
    /// [`Disturbance`] (tuples, slices and `&mut` of disturbances are disturbances too).
    /// A failing disturbance or step stops the frame there and returns its error.
    ///
    /// ```
    /// use springwater::disturb::{Rain, Wake};
    /// use springwater::{Params, Surface};
    ///
    /// let mut water = Surface::new(Params::with_size(64, 64))?;
    /// let mut rain = Rain::new(48.0, 1);                  // 48 drops a second
    /// let mut boat = Wake::circle(&water, 16.0);
    /// for _frame in 0..60 {
    ///     water.advance_with(1.0 / 60.0, &mut (&mut rain, &mut boat))?;
    /// }
    /// assert!(rain.fallen() > 20);                        // one second
    /// # Ok::<(), springwater::Error>(())
    /// ```
    pub fn advance_with<D: Disturbance + ?Sized>(
        &mut self,
        frame_seconds: f32,
        disturbance: &mut D,
    ) -> Result<usize> {
        let (clock, before) = (self.clock, self.steps);
        let steps = self.tick(frame_seconds)?;
        let dt = self.params.dt;
        let seconds = dt / self.params.time_scale;
        let result = (0..steps).try_for_each(|_| {
            disturbance.apply(self, seconds)?;
            self.run_steps(1, dt)
        });
        self.settle(clock, before, steps, result)
    }

    /// Ends a clocked frame of `steps` steps begun with `clock` at step count `before`. If
    /// a step failed before any was taken the clock is put back, so the call changed
    /// nothing; after some steps the frame's time is spent, the failed steps with it.
    fn settle(
        &mut self,
        clock: clock::Clock,
        before: u64,
        steps: usize,
        result: Result<()>,
    ) -> Result<usize> {
        match result {
            Ok(()) => Ok(steps),
            Err(e) => {
                if self.steps == before {
                    self.clock = clock;
                }
                Err(e)
            }
        }
    }

    /// The frame split of earlier versions, for callers who ask for it by name: advances
    /// by `frame_seconds` in [`Surface::split_frame`]'s equal substeps of *variable*
    /// length (never longer than `dt`), so that every frame ends exactly on the game's
    /// clock, at the price of results that depend on the frame times and of a second full
    /// step whenever a frame is a hair longer than `dt`. It ignores and keeps the
    /// accumulator of [`Surface::advance`]. Refuses frames of more than
    /// [`Surface::MAX_SUBSTEPS`] steps.
    pub fn advance_variable(&mut self, frame_seconds: f32) -> Result<usize> {
        let (substeps, dt) = self.split_model_frame(frame_seconds)?;
        self.run_steps(substeps as u64, dt)?;
        Ok(substeps)
    }

    /// How [`Surface::advance_variable`] cuts a frame of `frame_seconds`: the number of equal
    /// substeps and their length in seconds, never longer than one step of `params().dt`.
    ///
    /// A frame whose model time is within a relative 10⁻⁵ of a whole number of timesteps
    /// takes that number (the sliver left over is dropped), so that a 60 Hz frame at the
    /// default time scale is one step of `dt`, not two steps of `dt / 2` because
    /// `(1/60) × 24` rounds a little above 0.4 in `f32`.
    pub fn split_frame(&self, frame_seconds: f32) -> Result<(usize, f32)> {
        let (substeps, dt) = self.split_model_frame(frame_seconds)?;
        Ok((substeps, dt / self.params.time_scale))
    }

    /// [`Surface::split_frame`] with the substep's length in model time, never longer than
    /// `params().dt` (not even by a rounding error).
    fn split_model_frame(&self, frame_seconds: f32) -> Result<(usize, f32)> {
        params::non_negative("frame seconds", frame_seconds)?;
        let dt = self.params.dt;
        let model = frame_seconds as f64 * self.params.time_scale as f64;
        let substeps = (model / dt as f64 * (1.0 - 1e-5)).ceil();
        if substeps > Self::MAX_SUBSTEPS as f64 {
            return Err(Error::InvalidParam {
                name: "frame seconds",
                value: frame_seconds as f64,
                expected:
                    "a frame of at most 10000 timesteps (frame seconds × time_scale ≤ 10000 dt)",
            });
        }
        let substeps = substeps as usize;
        let sub = if substeps == 0 {
            0.0
        } else {
            ((model / substeps as f64) as f32).min(dt)
        };
        Ok((substeps, sub))
    }

    /// Drops a disturbance: adds `height · exp(−d²/radius²)` to y of every free node, `d`
    /// the distance from the node's rest position `(col·h, row·h)` to the point `(x, z)`.
    ///
    /// Everything is in world units: `x`, `z` in the water's local space (any finite point,
    /// also outside the footprint), `height` and `radius` in the same length unit as
    /// `params().spacing`. Drops with `|height| ≤ radius` and a radius of at least one cell
    /// keep the lattice in the regime where `critical_dt` guarantees stability.
    /// On error nothing changes.
    pub fn drop_at(&mut self, x: f32, z: f32, height: f32, radius: f32) -> Result<()> {
        params::finite("drop x", x)?;
        params::finite("drop z", z)?;
        params::finite("drop height", height)?;
        params::positive("drop radius", radius)?;
        let grid = self.grid();
        let h = self.params.spacing;
        let [oc, or] = self.window_origin;
        let inv_r2 = 1.0 / (radius * radius);
        // `d2 * inv_r2` is 0 × ∞ = NaN at the centre when radius² underflows: the weight
        // there is 1 by definition.
        let lift = |y: &[f32], i: usize| {
            let (c, r) = grid.coords(i);
            // Rest place in the water frame.
            let (rx, rz) = (rest_coordinate(c, oc, h), rest_coordinate(r, or, h));
            let d2 = (rx - x).powi(2) + (rz - z).powi(2);
            let w = if d2 == 0.0 { 1.0 } else { (-d2 * inv_r2).exp() };
            y[i] + height * w
        };
        // Past `CUT` radii the weight `exp(−d²/r²)` is below e⁻¹²⁰, which is 0 in f32, so
        // only the nodes of the square around the centre need the exponential; the rest
        // get `y + height · 0`, which leaves y as it is except that it turns a −0 into +0
        // when `height ≥ 0` (kept, so the result is the formula's to the bit).
        const CUT: f32 = 10.954_452; // sqrt(120)
        let span = |centre: f32, n: usize, origin: i64| {
            let reach = CUT * radius / h;
            let centre = centre - origin as f32 * h;
            let lo = ((centre / h - reach).floor().max(0.0) as usize).min(n);
            let hi = ((centre / h + reach).ceil().clamp(0.0, n as f32) as usize + 1).min(n);
            lo..hi
        };
        let (cols, rows) = (span(x, grid.cols, oc), span(z, grid.rows, or));
        let near = |i: usize| {
            let (c, r) = grid.coords(i);
            cols.contains(&c) && rows.contains(&r)
        };
        let box_nodes = || {
            rows.clone()
                .flat_map(|r| cols.clone().map(move |c| r * grid.cols + c))
        };
        // Check first, then write: a drop that would overflow a height changes nothing
        // (outside the square the heights do not change, and the state is finite).
        let pinned = &self.state.pinned;
        if box_nodes().any(|i| !pinned[i] && !lift(&self.state.pos[1], i).is_finite()) {
            return Err(Error::InvalidParam {
                name: "drop height",
                value: height as f64,
                expected: "small enough that every node's height stays finite",
            });
        }
        for i in box_nodes() {
            if !self.state.pinned[i] {
                self.state.pos[1][i] = lift(&self.state.pos[1], i);
            }
        }
        if height >= 0.0 {
            let y = &mut self.state.pos[1];
            for i in 0..grid.node_count() {
                if y[i] == 0.0 && !pinned[i] && !near(i) {
                    y[i] += 0.0;
                }
            }
        }
        Ok(())
    }

    /// Adds `force` to node `node` for the next step only (buoyancy, a paddle, a wake), in
    /// the lattice's force units (mass units × world units per unit of model time², the
    /// units of its springs; a force in seconds' units divided by `time_scale²`, see
    /// `docs/units.md`).
    pub fn add_force(&mut self, node: usize, force: [f32; 3]) -> Result<()> {
        self.check_node(node)?;
        for f in force {
            params::finite("force", f)?;
        }
        let sum: [f32; 3] = std::array::from_fn(|k| self.state.ext[k][node] + force[k]);
        for f in sum {
            params::finite("accumulated force", f)?;
        }
        for (k, f) in sum.into_iter().enumerate() {
            self.state.ext[k][node] = f;
        }
        self.state.touch_ext(node);
        Ok(())
    }

    /// Discards the pending external forces (for example after a step refused them).
    pub fn clear_forces(&mut self) {
        self.state.touch_all_ext();
        self.state.clear_ext();
    }

    /// Adds a velocity change `dv` to a free node now (an impulse divided by its mass), in
    /// world units per unit of model time like [`Surface::velocities`].
    pub fn add_velocity(&mut self, node: usize, dv: [f32; 3]) -> Result<()> {
        self.check_node(node)?;
        for v in dv {
            params::finite("velocity", v)?;
        }
        let sum: [f32; 3] = std::array::from_fn(|k| self.state.vel[k][node] + dv[k]);
        for v in sum {
            params::finite("resulting velocity", v)?;
        }
        if !self.state.pinned[node] {
            for (k, v) in sum.into_iter().enumerate() {
                self.state.vel[k][node] = v;
            }
        }
        Ok(())
    }

    /// Replaces the external force buffer for the next step with `[fx, fy, fz]`, one
    /// value per node, in the lattice's force units (as [`Surface::add_force`]). Every
    /// value must be finite; on error nothing changes.
    pub fn set_forces(&mut self, force: [&[f32]; 3]) -> Result<()> {
        let n = self.node_count();
        for c in force {
            same_length("force buffer", c.len(), n)?;
            if let Some(&bad) = c.iter().find(|v| !v.is_finite()) {
                return Err(Error::InvalidParam {
                    name: "force",
                    value: bad as f64,
                    expected: "finite values",
                });
            }
        }
        for (dst, src) in self.state.ext.iter_mut().zip(force) {
            dst[..n].copy_from_slice(src);
        }
        self.state.touch_all_ext();
        Ok(())
    }

    /// Pending external forces `[fx, fy, fz]` for the next step, in the lattice's force
    /// units (as [`Surface::add_force`]).
    pub fn forces(&self) -> [&[f32]; 3] {
        let n = self.node_count();
        [
            &self.state.ext[0][..n],
            &self.state.ext[1][..n],
            &self.state.ext[2][..n],
        ]
    }

    /// Sets the uniform acceleration applied to every free node (gravity, wind), in world
    /// units per second² ([`Params::acceleration`]).
    pub fn set_acceleration(&mut self, accel: [f32; 3]) -> Result<()> {
        for a in accel {
            params::finite("acceleration", a)?;
        }
        self.params.acceleration = accel;
        Ok(())
    }

    /// Pins (`true`) or frees a node. Pinning zeroes its velocity.
    pub fn set_pinned(&mut self, node: usize, pinned: bool) -> Result<()> {
        self.check_node(node)?;
        self.state.pinned[node] = pinned;
        self.window_custom = true;
        if pinned {
            for v in &mut self.state.vel {
                v[node] = 0.0;
            }
        }
        let inv_mass = if pinned {
            0.0
        } else {
            1.0 / self.state.mass.get(node)
        };
        self.state.inv_mass.set(node, inv_mass);
        Ok(())
    }

    /// Whether a node is pinned.
    pub fn is_pinned(&self, node: usize) -> Result<bool> {
        self.check_node(node)?;
        Ok(self.state.pinned[node])
    }

    /// Sets a node's mass. Refused if it would put `params().dt` at or past the critical
    /// timestep (the bound uses the smallest mass ever set).
    pub fn set_mass(&mut self, node: usize, mass: f32) -> Result<()> {
        self.check_node(node)?;
        params::positive("mass", mass)?;
        if !(1.0 / mass).is_finite() {
            return Err(Error::InvalidParam {
                name: "mass",
                value: mass as f64,
                expected: "at least 1.2e-38 (the reciprocal must be finite)",
            });
        }
        let min_mass = self.min_mass.min(mass);
        params::check_dt(
            self.params.dt,
            self.limit(min_mass, self.max_stiffness, self.max_viscosity),
        )?;
        self.min_mass = min_mass;
        self.state.mass.set(node, mass);
        self.window_custom = true;
        if !self.state.pinned[node] {
            self.state.inv_mass.set(node, 1.0 / mass);
        }
        Ok(())
    }

    /// Sets a node's viscosity `γ` (≥ 0). Refused if it would put `params().dt` at or past
    /// the critical timestep (explicit damping has a limit too; the bound uses the largest
    /// viscosity ever set).
    pub fn set_viscosity(&mut self, node: usize, viscosity: f32) -> Result<()> {
        self.check_node(node)?;
        params::non_negative("viscosity", viscosity)?;
        let max_viscosity = self.max_viscosity.max(viscosity);
        params::check_dt(
            self.params.dt,
            self.limit(self.min_mass, self.max_stiffness, max_viscosity),
        )?;
        self.max_viscosity = max_viscosity;
        self.state.viscosity.set(node, viscosity);
        self.window_custom = true;
        Ok(())
    }

    /// Node masses, row-major. Uniform masses are not stored per node: the view reads
    /// them where they are (see [`NodeValues`]).
    pub fn masses(&self) -> NodeValues<'_> {
        NodeValues::new(&self.state.mass)
    }

    /// Node viscosities `γ`, row-major, the absorbing frame's ramp included. Stored per
    /// node only once a node differs from its default (see [`NodeValues`]).
    pub fn viscosities(&self) -> NodeValues<'_> {
        NodeValues::new(&self.state.viscosity)
    }

    /// Pinned flags.
    pub fn pinned(&self) -> &[bool] {
        &self.state.pinned
    }

    /// A spring's rest length and coefficient; `None` if the grid has no such spring.
    pub fn spring(&self, id: SpringId) -> Option<Spring> {
        (id.origin < self.node_count() && self.grid().spring_end(id.family, id.origin).is_some())
            .then(|| {
                let (stiffness, rest) = self.springs.get(id.family, id.origin);
                Spring { rest, stiffness }
            })
    }

    /// Sets a spring's rest length (≥ 0) and coefficient (> 0). Refused, with nothing
    /// changed, if the spring does not exist or the coefficient would put `params().dt` at
    /// or past the critical timestep.
    ///
    /// ```
    /// use springwater::{Family, Params, Spring, SpringId, Surface};
    ///
    /// let mut water = Surface::new(Params::with_size(8, 8))?;
    /// let id = SpringId { family: Family::E, origin: 9 };
    /// assert_eq!(water.spring(id), Some(Spring { rest: 0.5, stiffness: 7.0 }));
    /// water.set_spring(id, Spring { rest: 0.8, stiffness: 5.0 })?;
    /// assert_eq!(water.spring(id).unwrap().stiffness, 5.0);
    /// # Ok::<(), springwater::Error>(())
    /// ```
    pub fn set_spring(&mut self, id: SpringId, spring: Spring) -> Result<()> {
        let Spring {
            rest,
            stiffness: coef,
        } = spring;
        self.check_node(id.origin)?;
        if self.grid().spring_end(id.family, id.origin).is_none() {
            return Err(Error::OutOfRange {
                what: "spring origin",
                index: id.origin,
                len: self.node_count(),
            });
        }
        params::non_negative("rest length", rest)?;
        params::positive("stiffness", coef)?;
        let max_stiffness = self.max_stiffness.max(coef);
        params::check_dt(
            self.params.dt,
            self.limit(self.min_mass, max_stiffness, self.max_viscosity),
        )?;
        self.max_stiffness = max_stiffness;
        self.springs.set(id, rest, coef);
        Ok(())
    }

    /// The colour batches the engine uses on the current thread pool: bands of rows, even
    /// bands colour 0, odd bands colour 1 (see [`crate::springs`]), as they stand at the
    /// start of a pass (the tiling says how they lean through its steps).
    #[cfg(feature = "internals")]
    #[doc(hidden)]
    pub fn bands(&self) -> impl Iterator<Item = crate::springs::Band> {
        let workers = Runner::of(self.host.as_ref()).workers();
        let tiling = self
            .workspace
            .tiling(self.params.rows, self.workspace.pass_steps, workers);
        crate::springs::bands(self.params.rows, tiling.band_rows)
    }

    /// Kinetic plus spring potential energy, a diagnostic (`O(nodes)`).
    pub fn energy(&self) -> Energy {
        let s = &self.state;
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
            let (coef, rest) = self.springs.get(id.family, i);
            let stretch = l - rest as f64;
            potential += 0.5 * coef as f64 * stretch * stretch;
        }
        Energy { kinetic, potential }
    }

    fn check_node(&self, node: usize) -> Result<()> {
        if node < self.node_count() {
            Ok(())
        } else {
            Err(Error::OutOfRange {
                what: "node",
                index: node,
                len: self.node_count(),
            })
        }
    }
}
