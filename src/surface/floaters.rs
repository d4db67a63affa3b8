//! The floating bodies of a [`Surface`]: adding, reading and pushing them, and the coupled
//! step that moves them with the water (the model is explained in [`crate::floater`]).

use super::Surface;
use crate::error::{Error, Result};
use crate::floater::{self, Buoyancy, Column, ColumnForce, Floater, FloaterId};
use crate::params;
use glam::Vec3;

/// The bodies of one surface, their world and the scratch of the coupled step.
#[derive(Debug, Clone, Default)]
pub(crate) struct Floaters {
    /// Bodies in the order they were added (ids increase along it).
    pub bodies: Vec<(FloaterId, Floater)>,
    /// The id the next added body gets.
    pub next_id: u64,
    pub buoyancy: Buoyancy,
    scratch: Scratch,
}

/// Buffers the coupled step reuses; not state.
#[derive(Debug, Clone, Default)]
struct Scratch {
    columns: Vec<Column>,
    under: Vec<ColumnForce>,
    forces: Vec<Vec3>,
    /// Each body's `(position, velocity, water force)` after the step, until it commits.
    moved: Vec<(Vec3, Vec3, Vec3)>,
    /// External forces of the nodes the reactions touched, before they did.
    log: Vec<(usize, [f32; 3])>,
}

impl Floaters {
    fn index(&self, id: FloaterId) -> Result<usize> {
        self.bodies
            .binary_search_by_key(&id, |&(id, _)| id)
            .map_err(|_| Error::NoSuchFloater(id.0))
    }
}

/// # Floating bodies
///
/// Spheres and boxes that float on the water, are carried and lifted by it, and push back
/// into it (see [`crate::floater`] for the model). They step with every step and substep
/// of the surface, in the order they were added, and are part of snapshots.
impl Surface {
    /// Adds a floating body and returns its id. Refused (nothing changes) when a field is
    /// out of range ([`Floater::validate`]) or when the water under the bodies would need
    /// a smaller timestep than `params().dt` ([`Surface::critical_dt`]).
    pub fn add_floater(&mut self, body: Floater) -> Result<FloaterId> {
        let body = Floater {
            water_force: Vec3::ZERO,
            ..body
        };
        body.validate()?;
        floater::check_footprint(&body.shape, self.params.spacing)?;
        params::check_dt(self.params.dt, self.limit_with(self.floaters.buoyancy))?;
        let id = FloaterId(self.floaters.next_id);
        self.floaters.next_id = id.0.checked_add(1).ok_or(Error::InvalidParam {
            name: "floater id",
            value: id.0 as f64,
            expected: "fewer than 2^64 − 1 floaters ever added to one surface",
        })?;
        self.floaters.bodies.push((id, body));
        Ok(id)
    }

    /// Removes a body and returns it.
    pub fn remove_floater(&mut self, id: FloaterId) -> Result<Floater> {
        let k = self.floaters.index(id)?;
        Ok(self.floaters.bodies.remove(k).1)
    }

    /// A body's current state.
    pub fn floater(&self, id: FloaterId) -> Result<&Floater> {
        let k = self.floaters.index(id)?;
        Ok(&self.floaters.bodies[k].1)
    }

    /// Replaces a body's state (teleport it, change its mass or shape); its read-only
    /// [`Floater::water_force`] is kept. Validated like [`Surface::add_floater`]; on error
    /// nothing changes.
    pub fn set_floater(&mut self, id: FloaterId, body: Floater) -> Result<()> {
        let k = self.floaters.index(id)?;
        let body = Floater {
            water_force: self.floaters.bodies[k].1.water_force,
            ..body
        };
        body.validate()?;
        floater::check_footprint(&body.shape, self.params.spacing)?;
        self.floaters.bodies[k].1 = body;
        Ok(())
    }

    /// Every body with its id, in the order they were added.
    pub fn floaters(&self) -> impl ExactSizeIterator<Item = (FloaterId, &Floater)> {
        self.floaters.bodies.iter().map(|(id, f)| (*id, f))
    }

    /// Adds `force` (mass units × world units per second², like every force on a body) to
    /// a body for the next step only: an engine, the wind, a player's push. On error nothing
    /// changes.
    pub fn push_floater(&mut self, id: FloaterId, force: impl Into<Vec3>) -> Result<()> {
        let force = force.into();
        let k = self.floaters.index(id)?;
        let push = self.floaters.bodies[k].1.push + force;
        for c in force.to_array().into_iter().chain(push.to_array()) {
            params::finite("floater push", c)?;
        }
        self.floaters.bodies[k].1.push = push;
        Ok(())
    }

    /// Gravity (world units per second²) and water density for the bodies.
    pub fn buoyancy(&self) -> Buoyancy {
        self.floaters.buoyancy
    }

    /// Sets gravity and water density for the bodies. Refused (nothing changes) when a
    /// field is out of range, or when bodies float and the stiffer waterline would need a
    /// smaller timestep than `params().dt`.
    pub fn set_buoyancy(&mut self, buoyancy: Buoyancy) -> Result<()> {
        buoyancy.validate()?;
        if !self.floaters.bodies.is_empty() {
            params::check_dt(self.params.dt, self.limit_with(buoyancy))?;
        }
        self.floaters.buoyancy = buoyancy;
        Ok(())
    }

    /// The critical timestep of the current tables with bodies floating in `buoyancy`.
    fn limit_with(&self, buoyancy: Buoyancy) -> f32 {
        params::critical_dt_with(
            self.min_mass,
            self.max_stiffness,
            self.max_viscosity,
            buoyancy.node_stiffness(self.params.spacing, self.params.time_scale),
        )
    }

    /// The waterline stiffness the bodies add to a node (0 without bodies).
    pub(crate) fn floater_stiffness(&self) -> f32 {
        if self.floaters.bodies.is_empty() {
            0.0
        } else {
            self.floaters
                .buoyancy
                .node_stiffness(self.params.spacing, self.params.time_scale)
        }
    }

    /// One step of model time `dt` with the bodies: their reactions go into the external forces,
    /// the water takes its step, and the bodies move only if it succeeded. On any error
    /// the surface is unchanged, bodies and pending forces included.
    pub(crate) fn floating_step(&mut self, dt: f32) -> Result<()> {
        let pending = self.state.ext_pending;
        let listed = self.state.ext_nodes.as_ref().map(Vec::len);
        let mut scratch = std::mem::take(&mut self.floaters.scratch);
        scratch.log.clear();
        let coupled = self
            .couple(dt, &mut scratch)
            .and_then(|()| self.water(1, dt));
        match coupled {
            Ok(()) => {
                for ((_, body), &(position, velocity, force)) in
                    self.floaters.bodies.iter_mut().zip(&scratch.moved)
                {
                    body.position = position;
                    body.velocity = velocity;
                    body.water_force = force;
                    body.push = Vec3::ZERO;
                }
            }
            Err(_) => {
                // Undo the reactions, newest first, so every touched node gets its old bits.
                for &(i, f) in scratch.log.iter().rev() {
                    for (c, v) in f.into_iter().enumerate() {
                        self.state.ext[c][i] = v;
                    }
                }
                self.state.ext_pending = pending;
                // The list of pushed nodes goes back too, unless the reactions overflowed
                // it; `None` (clear every force) is then still correct.
                if let (Some(len), Some(nodes)) = (listed, &mut self.state.ext_nodes) {
                    nodes.truncate(len);
                }
            }
        }
        self.floaters.scratch = scratch;
        coupled
    }

    /// Reads the water under every body, solves each body's step (kept in
    /// `scratch.moved`) and pushes the reactions into the external forces (logged).
    ///
    /// The bodies live in seconds, the lattice in model time (`dt` is model time): the body
    /// steps `dt / time_scale` seconds, the water velocity it reads is the lattice's times
    /// `time_scale`, and the forces it pushes into the water are divided by `time_scale²`.
    fn couple(&mut self, dt: f32, scratch: &mut Scratch) -> Result<()> {
        let Buoyancy { gravity, density } = self.floaters.buoyancy;
        let h = self.params.spacing;
        let scale = self.params.time_scale;
        let seconds = dt / scale;
        // Damping room: `b_lim` of the stiffest node with the waterline springs (see the
        // `absorb` module), shared out as half of what it leaves the four nodes under a
        // column, per cell of area. `rate` is per unit of model time, the body's drag per
        // second: the cap is `rate × time_scale`.
        let omega2 = (12.0 * self.max_stiffness + self.floater_stiffness()) / self.min_mass;
        let rate = ((4.0 - omega2 * dt * dt) / (2.0 * dt)).max(0.0);
        scratch.moved.clear();
        for k in 0..self.floaters.bodies.len() {
            let (id, body) = self.floaters.bodies[k];
            floater::columns(&body.shape, h, &mut scratch.columns);
            scratch.under.clear();
            for col in &scratch.columns {
                let (x, z) = (body.position.x + col.dx, body.position.z + col.dz);
                let (height, flow, room, at) = match self.water_under(x, z, rate) {
                    Some((height, flow, room)) => {
                        (height, flow * scale, room.max(0.0), Some([x, z]))
                    }
                    None => (0.0, Vec3::ZERO, f32::INFINITY, None),
                };
                let bottom = body.position.y - 0.5 * col.length;
                let wet = (height - bottom).clamp(0.0, col.length);
                let cap = 0.5 * room * (col.area / (h * h)).min(1.0) * scale;
                scratch.under.push(ColumnForce {
                    at,
                    lift: density * gravity * wet * col.area,
                    stiffness: if wet > 0.0 && wet < col.length {
                        density * gravity * col.area
                    } else {
                        0.0
                    },
                    drag: (body.drag * density * wet * col.area).min(cap),
                    flow,
                });
            }
            let velocity =
                floater::solve(&body, &scratch.under, gravity, seconds, &mut scratch.forces);
            let force: Vec3 = scratch.forces.iter().sum();
            let position = body.position + seconds * velocity;
            // The body must stay a valid body (finite, and within the ranges a snapshot
            // accepts), or the step is refused.
            let moved = Floater {
                position,
                velocity,
                push: Vec3::ZERO,
                water_force: force,
                ..body
            };
            if moved.validate().is_err() {
                return Err(Error::FloaterNonFinite {
                    step: self.steps(),
                    floater: id.0,
                });
            }
            // The lattice's forces are per unit of model time²: a body's force in seconds
            // goes in divided by `time_scale²`.
            let to_lattice = scale * scale;
            for (c, f) in scratch.under.iter().zip(&scratch.forces) {
                if let Some([x, z]) = c.at {
                    let reaction = (-*f / to_lattice).to_array();
                    self.add_force_at_logged(x, z, reaction, Some(&mut scratch.log))
                        .map_err(|_| Error::FloaterNonFinite {
                            step: self.steps(),
                            floater: id.0,
                        })?;
                }
            }
            scratch.moved.push((position, velocity, force));
        }
        Ok(())
    }
}
