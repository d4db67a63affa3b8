//! The one stepping path. Every way of moving the water in time — [`Surface::step`],
//! [`Surface::step_n`], the clock's [`Surface::advance`] family — ends in
//! [`Surface::run`], which goes down one road:
//!
//! ```text
//! run(n, dt) ── bodies? ──yes──▶ n × floating_step, one step at a time:
//!     │                            prepare the bodies, apply their reactions
//!     no                           (bodies/), then ────────────────┐
//!     │                                                            ▼
//!     └────────────────────────────────────────────────▶ water(n, dt)
//!                                  on the host's threads (pool, job system or here)
//!                                                                 ▼
//!                                  water_on(n, dt, runner): the scalar reference, or
//!                                  the engine's passes of up to `pass_steps` steps
//!                                                                 ▼
//!                                  commit(k): swap the back buffers, count the steps
//!                                  (with bodies: then commit the bodies, or undo
//!                                  their reactions if the water's step failed)
//! ```
//!
//! A step is transactional wherever it runs: the new state goes to back buffers, is checked
//! for finiteness in the same pass, and becomes the state only if every value is finite.

use super::Surface;
use crate::error::{Error, Result};
use crate::forces::engine::PassEnd;
use crate::forces::{self, StepConfig};
use crate::jobs::{Host, Runner};
use crate::simd::SimdLevel;

impl Surface {
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
        self.run(1, self.params.dt)
    }

    /// Advances `n` steps of `params().dt` with the engine, several per pass over memory
    /// (see `src/forces/engine/`). Bitwise the same as `n` calls of [`Surface::step`], and as
    /// transactional per step: if a step would make the state non-finite, the steps before
    /// it stay applied, that one is not, and its error is returned.
    pub fn step_n(&mut self, n: u64) -> Result<()> {
        self.run(n, self.params.dt)
    }

    /// `n` steps of model time `dt` of the water and its bodies. With bodies, one coupled
    /// step at a time (they read the water between steps); without, the engine takes
    /// several per pass.
    pub(crate) fn run(&mut self, n: u64, dt: f32) -> Result<()> {
        if self.bodies.is_idle() {
            return self.water(n, dt);
        }
        (0..n).try_for_each(|_| self.floating_step(dt))
    }

    /// One step of model time `dt` with the bodies, in four stages (the bodies' side of each
    /// is in `bodies/coupling.rs`):
    ///
    /// 1. **prepare the bodies**: each reads the water under it and takes its implicit step,
    ///    in parallel; its reactions become shares of the nodes under it;
    /// 2. **apply the reactions**: the water column turns the shares into what the water
    ///    gets, added to the external forces all or nothing;
    /// 3. **advance the lattice** one step with those forces;
    /// 4. **commit or undo**: if the water's step succeeded, the bodies take their new
    ///    poses and the column its share; otherwise the forces and the column go back to
    ///    what they were, and the surface is unchanged, bodies included.
    fn floating_step(&mut self, dt: f32) -> Result<()> {
        let mut c = self.bodies.take_scratch();
        let stepped = self
            .prepare_bodies(dt, &mut c)
            .and_then(|()| self.apply_reactions(&c))
            .and_then(|()| {
                self.water(1, dt)
                    .inspect_err(|_| self.lattice.state.ext.undo())
            });
        match stepped {
            Ok(()) => self.commit_bodies(dt, &mut c),
            Err(_) => self.discard_bodies(),
        }
        self.bodies.keep_scratch(c);
        stepped
    }

    /// `n` steps of the water alone, on the host's threads if they are set (see
    /// [`Surface::set_thread_pool`], [`Surface::set_job_system`]), else where the caller is.
    pub(crate) fn water(&mut self, n: u64, dt: f32) -> Result<()> {
        match self.host.clone() {
            #[cfg(feature = "parallel")]
            Some(Host::Pool(pool)) if pool.current_thread_index().is_none() => {
                pool.install(|| self.water_on(n, dt, Runner::Here))
            }
            Some(Host::Jobs(jobs)) => self.water_on(n, dt, Runner::Jobs(&*jobs)),
            _ => self.water_on(n, dt, Runner::Here),
        }
    }

    /// `n` steps of the water, each colour run by `runner`: the scalar reference one step
    /// at a time at [`SimdLevel::Scalar`], else the engine in passes of up to
    /// `pass_steps`. A pass that fails is redone one step at a time, so the error names the
    /// exact step and node.
    fn water_on(&mut self, n: u64, dt: f32, runner: Runner<'_>) -> Result<()> {
        let cfg = self.config(dt);
        let mut left = n;
        while left > 0 {
            if self.simd == SimdLevel::Scalar {
                let (state, springs) = (&mut self.lattice.state, &self.lattice.springs);
                forces::scalar::step(state, springs, &mut self.reference, cfg)
                    .map_err(|node| self.non_finite(node))?;
                self.commit(1, dt);
                left -= 1;
                continue;
            }
            let k = left.min(self.workspace.pass_steps as u64) as usize;
            let (state, springs, ws) = (
                &mut self.lattice.state,
                &self.lattice.springs,
                &mut self.workspace,
            );
            match forces::engine::pass(state, springs, ws, cfg, k, self.simd, runner) {
                PassEnd::Done => self.commit(k, dt),
                PassEnd::Incomplete => return Err(Error::JobSystem),
                PassEnd::NonFinite if k > 1 => {
                    for _ in 0..k {
                        self.water_on(1, dt, runner)?;
                    }
                }
                PassEnd::NonFinite => {
                    let node = self.lattice.state.first_non_finite_next().unwrap_or(0);
                    return Err(self.non_finite(node));
                }
            }
            left -= k as u64;
        }
        Ok(())
    }

    /// The step's constants for a step of model time `dt`.
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

    /// Makes `k` steps written to the back buffers the state.
    fn commit(&mut self, k: usize, dt: f32) {
        self.lattice.state.swap();
        self.lattice.state.ext.clear();
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
}
