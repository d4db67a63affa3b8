//! The floating bodies of a [`Surface`]: adding, reading and pushing them, and the coupled
//! step that moves them with the water (the model is explained in [`crate::floater`]).

use super::Surface;
use crate::body::rigid::{self, Piece, World};
use crate::body::{Hull, HullScratch};
use crate::error::{Error, Result};
use crate::floater::{self, BodyForces, Buoyancy, Floater, FloaterId};
use crate::params;
use glam::{DVec3, Vec3};
use std::sync::Arc;

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
    /// Each body's shape and the mesh the water presses on (parallel to the bodies; a
    /// body whose shape changed, or a restored one, gets its mesh again).
    meshes: Vec<(floater::Shape, Arc<Hull>)>,
    /// Meshes of the bodies [`Surface::body_forces`] was asked about, newest last.
    foreign: Vec<(floater::Shape, Arc<Hull>)>,
    hull: HullScratch,
    pieces: Vec<Piece>,
    /// The forces a body feels and where (the water gets minus each).
    forces: Vec<(DVec3, DVec3)>,
    /// Each body after the step, until it commits.
    moved: Vec<Floater>,
    /// External forces of the nodes the reactions touched, before they did.
    log: Vec<(usize, [f32; 3])>,
}

/// How many meshes of bodies another engine owns are kept.
const FOREIGN_MESHES: usize = 16;

impl Floaters {
    fn index(&self, id: FloaterId) -> Result<usize> {
        self.bodies
            .binary_search_by_key(&id, |&(id, _)| id)
            .map_err(|_| Error::NoSuchFloater(id.0))
    }
}

/// # Floating bodies
///
/// Rigid balls, boxes and hulls that float on the water, pitch and roll with it, are
/// carried and lifted by it, and push back into it (see [`crate::floater`] for the model).
/// They step with every step and substep of the surface, in the order they were added, and
/// are part of snapshots.
impl Surface {
    /// Adds a floating body and returns its id. Refused (nothing changes) when a field is
    /// out of range ([`Floater::validate`]), the body is more than
    /// [`MAX_CELLS`](crate::floater::MAX_CELLS) cells across, or the water under the
    /// bodies would need a smaller timestep than `params().dt` ([`Surface::critical_dt`]).
    /// The orientation is stored normalised.
    pub fn add_floater(&mut self, body: Floater) -> Result<FloaterId> {
        let body = self.admit(body, Vec3::ZERO, Vec3::ZERO)?;
        params::check_dt(self.params.dt, self.limit_with(self.floaters.buoyancy))?;
        let mesh = floater::wet_mesh(&body.shape, self.params.spacing)?;
        let id = FloaterId(self.floaters.next_id);
        self.floaters.next_id = id.0.checked_add(1).ok_or(Error::InvalidParam {
            name: "floater id",
            value: id.0 as f64,
            expected: "fewer than 2^64 − 1 floaters ever added to one surface",
        })?;
        let k = self.floaters.bodies.len();
        self.floaters.scratch.meshes.truncate(k);
        if self.floaters.scratch.meshes.len() == k {
            self.floaters
                .scratch
                .meshes
                .push((body.shape.clone(), mesh));
        }
        self.floaters.bodies.push((id, body));
        Ok(id)
    }

    /// `body` validated and fit for this surface, with its read-only fields set and its
    /// orientation normalised.
    fn admit(&self, body: Floater, force: Vec3, torque: Vec3) -> Result<Floater> {
        let mut body = Floater {
            water_force: force,
            water_torque: torque,
            ..body
        };
        body.validate()?;
        floater::check_footprint(&body.shape, self.params.spacing)?;
        body.orientation = rigid::normalised(body.orientation.as_dquat()).as_quat();
        Ok(body)
    }

    /// Removes a body and returns it.
    pub fn remove_floater(&mut self, id: FloaterId) -> Result<Floater> {
        let k = self.floaters.index(id)?;
        let meshes = &mut self.floaters.scratch.meshes;
        if k < meshes.len() {
            meshes.remove(k);
        }
        Ok(self.floaters.bodies.remove(k).1)
    }

    /// A body's current state.
    pub fn floater(&self, id: FloaterId) -> Result<&Floater> {
        let k = self.floaters.index(id)?;
        Ok(&self.floaters.bodies[k].1)
    }

    /// Replaces a body's state (teleport it, turn it, change its mass or shape); its
    /// read-only [`Floater::water_force`] and [`Floater::water_torque`] are kept.
    /// Validated like [`Surface::add_floater`]; on error nothing changes.
    pub fn set_floater(&mut self, id: FloaterId, body: Floater) -> Result<()> {
        let k = self.floaters.index(id)?;
        let old = &self.floaters.bodies[k].1;
        let body = self.admit(body, old.water_force, old.water_torque)?;
        if body.shape != self.floaters.bodies[k].1.shape {
            let mesh = floater::wet_mesh(&body.shape, self.params.spacing)?;
            if let Some(slot) = self.floaters.scratch.meshes.get_mut(k) {
                *slot = (body.shape.clone(), mesh);
            }
        }
        self.floaters.bodies[k].1 = body;
        Ok(())
    }

    /// Every body with its id, in the order they were added.
    pub fn floaters(&self) -> impl ExactSizeIterator<Item = (FloaterId, &Floater)> {
        self.floaters.bodies.iter().map(|(id, f)| (*id, f))
    }

    /// Adds `force` through a body's centre of mass (mass units × world units per second²,
    /// like every force on a body) for the next step only: an engine, the wind, a player's
    /// push. On error nothing changes.
    pub fn push_floater(&mut self, id: FloaterId, force: impl Into<Vec3>) -> Result<()> {
        self.push_floater_at_offset(id, force.into(), Vec3::ZERO)
    }

    /// Adds `force` acting at the world point `at` to a body for the next step only: the
    /// force through its centre of mass and the torque `(at − position) × force` (a push
    /// on the bow turns the boat). On error nothing changes.
    pub fn push_floater_at(
        &mut self,
        id: FloaterId,
        force: impl Into<Vec3>,
        at: impl Into<Vec3>,
    ) -> Result<()> {
        let at = at.into();
        for c in at.to_array() {
            params::finite("push point", c)?;
        }
        let k = self.floaters.index(id)?;
        let offset = at - self.floaters.bodies[k].1.position;
        self.push_floater_at_offset(id, force.into(), offset)
    }

    fn push_floater_at_offset(&mut self, id: FloaterId, force: Vec3, offset: Vec3) -> Result<()> {
        let k = self.floaters.index(id)?;
        let body = &self.floaters.bodies[k].1;
        let torque = offset.cross(force);
        let push = body.push + force;
        let push_torque = body.push_torque + torque;
        for c in force.to_array().into_iter().chain(push.to_array()) {
            params::finite("floater push", c)?;
        }
        for c in torque.to_array().into_iter().chain(push_torque.to_array()) {
            params::finite("floater push torque", c)?;
        }
        let body = &mut self.floaters.bodies[k].1;
        body.push = push;
        body.push_torque = push_torque;
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
        let mut scratch = std::mem::take(&mut self.floaters.scratch);
        let coupled = self
            .logged(&mut scratch, |water, scratch| water.couple(dt, scratch))
            .and_then(|()| self.water(1, dt));
        if coupled.is_ok() {
            for ((_, body), moved) in self.floaters.bodies.iter_mut().zip(scratch.moved.drain(..)) {
                *body = moved;
            }
        } else {
            self.undo(&scratch);
        }
        self.floaters.scratch = scratch;
        coupled
    }

    /// Runs `push` (which pushes reactions into the water, logged in `scratch.log`) and
    /// undoes its pushes if it fails.
    fn logged(
        &mut self,
        scratch: &mut Scratch,
        push: impl FnOnce(&mut Self, &mut Scratch) -> Result<()>,
    ) -> Result<()> {
        scratch.log.clear();
        let pending = self.state.ext_pending;
        let listed = self.state.ext_nodes.as_ref().map(Vec::len);
        let out = push(self, scratch);
        if out.is_err() {
            self.undo(scratch);
            self.state.ext_pending = pending;
            // The list of pushed nodes goes back too, unless the reactions overflowed it;
            // `None` (clear every force) is then still correct.
            if let (Some(len), Some(nodes)) = (listed, &mut self.state.ext_nodes) {
                nodes.truncate(len);
            }
        }
        out
    }

    /// Gives the nodes in `scratch.log` their old forces back, newest first, so every
    /// touched node gets its old bits.
    fn undo(&mut self, scratch: &Scratch) {
        for &(i, f) in scratch.log.iter().rev() {
            for (c, v) in f.into_iter().enumerate() {
                self.state.ext[c][i] = v;
            }
        }
    }

    /// Makes every body's mesh match its shape (after a restore or a change of shape).
    fn fit_meshes(&self, scratch: &mut Scratch) -> Result<()> {
        let bodies = &self.floaters.bodies;
        scratch.meshes.truncate(bodies.len());
        for (k, (_, body)) in bodies.iter().enumerate() {
            match scratch.meshes.get(k) {
                Some((shape, _)) if *shape == body.shape => {}
                _ => {
                    let mesh = floater::wet_mesh(&body.shape, self.params.spacing)?;
                    let entry = (body.shape.clone(), mesh);
                    if k < scratch.meshes.len() {
                        scratch.meshes[k] = entry;
                    } else {
                        scratch.meshes.push(entry);
                    }
                }
            }
        }
        Ok(())
    }

    /// Solves every body's step (kept in `scratch.moved`) and pushes the reactions into
    /// the external forces (logged). `dt` is model time; the bodies step `dt / time_scale`
    /// seconds.
    fn couple(&mut self, dt: f32, scratch: &mut Scratch) -> Result<()> {
        self.fit_meshes(scratch)?;
        let seconds = dt / self.params.time_scale;
        let room = self.damping_room(dt);
        scratch.moved.clear();
        for k in 0..self.floaters.bodies.len() {
            let (id, ref body) = self.floaters.bodies[k];
            let mesh = Arc::clone(&scratch.meshes[k].1);
            let fail = |_| Error::FloaterNonFinite {
                step: self.steps(),
                floater: id.0,
            };
            let moved = self
                .hull_forces(body, &mesh, seconds, room, scratch)
                .map_err(fail)?;
            // The body must stay a valid body (finite, and within the ranges a snapshot
            // accepts), or the step is refused.
            let moved = Floater {
                position: moved.position.as_vec3(),
                orientation: moved.orientation.as_quat(),
                velocity: moved.velocity.as_vec3(),
                angular_velocity: moved.angular_velocity.as_vec3(),
                push: Vec3::ZERO,
                push_torque: Vec3::ZERO,
                water_force: moved.force.as_vec3(),
                water_torque: moved.torque.as_vec3(),
                ..body.clone()
            };
            moved.validate().map_err(fail)?;
            self.push_reactions(1.0, scratch)
                .map_err(|_| Error::FloaterNonFinite {
                    step: self.steps(),
                    floater: id.0,
                })?;
            scratch.moved.push(moved);
        }
        Ok(())
    }

    /// The damping rate per unit of model time the water's step has room for at the
    /// stiffest node with the waterline springs (`b_lim`, see the `absorb` module).
    fn damping_room(&self, dt: f32) -> f32 {
        let omega2 = (12.0 * self.max_stiffness + self.floater_stiffness()) / self.min_mass;
        ((4.0 - omega2 * dt * dt) / (2.0 * dt)).max(0.0)
    }

    /// The water's pieces on `body` (pose, velocities) pressing on `mesh`, and the body's
    /// implicit step over `seconds` (see [`crate::body`]'s `rigid` module). Leaves the
    /// forces the body feels, and where, in `scratch.forces`.
    fn hull_forces(
        &self,
        body: &Floater,
        mesh: &Hull,
        seconds: f32,
        room_rate: f32,
        scratch: &mut Scratch,
    ) -> Result<rigid::Moved> {
        let Buoyancy { gravity, density } = self.floaters.buoyancy;
        let rho_g = density as f64 * gravity as f64;
        let scale = self.params.time_scale;
        let h = self.params.spacing as f64;
        let pieces = &mut scratch.pieces;
        pieces.clear();
        let pressure = mesh.pressed(
            body.position,
            body.orientation,
            rho_g,
            |x, z| self.height_or_calm(x, z),
            &mut scratch.hull,
            |point, force, area| {
                pieces.push(Piece {
                    point,
                    force,
                    area,
                    flow: DVec3::ZERO,
                })
            },
        )?;
        // The water's velocity under each piece (per second), and the damping room the
        // water's step leaves under the body, per second.
        let mut room = f64::INFINITY;
        let mut seen = 0.0;
        for p in pieces.iter_mut() {
            if let Some((_, flow, r)) =
                self.water_under(p.point.x as f32, p.point.z as f32, room_rate)
            {
                p.flow = (flow * scale).as_dvec3();
                room = room.min(r.max(0.0) as f64 * scale as f64);
            }
            let f = p.force.length();
            if f > 0.0 {
                seen += p.area * p.force.y.abs() / f;
            }
        }
        // The body's drag rate, capped at half of what that room allows over the cells it
        // covers (its waterplane, or half its wet area seen from above when under).
        let cells = pressure.plane.area.max(0.5 * seen) / (h * h);
        let drag = body.drag as f64 * density as f64 * pressure.volume;
        let world = World {
            rho_g,
            gravity: gravity as f64,
            dt: seconds as f64,
            drag_rate: drag.min(0.5 * room * cells.max(1.0)),
        };
        Ok(rigid::step(
            &body.rigid(),
            pieces,
            &pressure.plane,
            world,
            &mut scratch.forces,
        ))
    }

    /// Pushes minus every force in `scratch.forces`, times `factor`, into the water at its
    /// point (logged), converted to the lattice's units; points off the patch push nothing.
    fn push_reactions(&mut self, factor: f64, scratch: &mut Scratch) -> Result<()> {
        // The lattice's forces are per unit of model time²: a body's force in seconds goes
        // in divided by `time_scale²`.
        let to_lattice = (self.params.time_scale as f64).powi(2);
        for &(point, force) in &scratch.forces {
            let (x, z) = (point.x as f32, point.z as f32);
            if self.height_at(x, z).is_err() {
                continue;
            }
            let reaction = (-force * (factor / to_lattice)).as_vec3().to_array();
            self.add_force_at_logged(x, z, reaction, Some(&mut scratch.log))?;
        }
        Ok(())
    }

    /// The water's height at world `(x, z)`, or the calm surface's (0) off the patch.
    fn height_or_calm(&self, x: f32, z: f32) -> f32 {
        self.height_at(x, z).unwrap_or(0.0)
    }

    /// The water's force and torque on a body another physics engine owns, over the
    /// engine's coming tick of `seconds`: for the body's shape, mass, inertia, drag, pose
    /// and velocities (`body`; its `push`, `push_torque` and read-only fields are ignored),
    /// as [`BodyForces`] in the world frame, the torque about `body.position` (the centre
    /// of mass). The water gets the opposite of both, spread where each part of the hull
    /// meets it, in its next step (the whole tick's impulse, so call this once per tick).
    ///
    /// The forces are those of the surface's own bodies (see [`crate::floater`]): buoyancy
    /// and drag on the wet part of the hull, taken implicitly over the tick for the
    /// velocities the body will have at its end under them and gravity. An engine that
    /// applies them with an explicit step of the same `seconds` and the same mass and
    /// inertia therefore gets the stable step of a built-in body, however light the body
    /// is: keep `seconds` equal to the engine's tick, and `gravity` of
    /// [`Surface::buoyancy`] equal to the engine's.
    ///
    /// Refused (nothing changes): an invalid body ([`Floater::validate`]), one more than
    /// [`MAX_CELLS`](crate::floater::MAX_CELLS) cells across, `seconds` not finite and
    /// positive or above one second, or reactions the water cannot hold.
    ///
    /// ```
    /// use springwater::{Floater, Params, Surface};
    ///
    /// let mut water = Surface::new(Params::with_size(64, 64))?;
    /// // A box 4 × 2 × 4 of half the water's density, floating at its draft of 1.
    /// let density = water.buoyancy().density;
    /// let boat = Floater::cuboid([2.0, 1.0, 2.0], 0.5 * density * 32.0, [32.0, 0.0, 32.0]);
    /// let push = water.body_forces(&boat, 1.0 / 60.0)?;
    /// let weight = boat.mass * water.buoyancy().gravity;
    /// assert!((push.force.y - weight).abs() < 0.02 * weight);   // it floats
    /// assert!(push.torque.length() < 1e-3 * weight);
    /// # Ok::<(), springwater::Error>(())
    /// ```
    pub fn body_forces(&mut self, body: &Floater, seconds: f32) -> Result<BodyForces> {
        if !(seconds.is_finite() && seconds > 0.0 && seconds <= 1.0) {
            return Err(Error::InvalidParam {
                name: "body tick",
                value: seconds as f64,
                expected: "seconds, finite, above 0 and at most 1",
            });
        }
        let body = Floater {
            push: Vec3::ZERO,
            push_torque: Vec3::ZERO,
            ..self.admit(body.clone(), Vec3::ZERO, Vec3::ZERO)?
        };
        let mut scratch = std::mem::take(&mut self.floaters.scratch);
        let out = self.foreign_forces(&body, seconds, &mut scratch);
        self.floaters.scratch = scratch;
        out
    }

    fn foreign_forces(
        &mut self,
        body: &Floater,
        seconds: f32,
        scratch: &mut Scratch,
    ) -> Result<BodyForces> {
        let mesh = match scratch.foreign.iter().position(|(s, _)| *s == body.shape) {
            Some(k) => {
                let entry = scratch.foreign.remove(k);
                let mesh = Arc::clone(&entry.1);
                scratch.foreign.push(entry);
                mesh
            }
            None => {
                let mesh = floater::wet_mesh(&body.shape, self.params.spacing)?;
                if scratch.foreign.len() == FOREIGN_MESHES {
                    scratch.foreign.remove(0);
                }
                scratch
                    .foreign
                    .push((body.shape.clone(), Arc::clone(&mesh)));
                mesh
            }
        };
        let room = self.damping_room(self.params.dt);
        let moved = self.hull_forces(body, &mesh, seconds, room, scratch)?;
        let (force, torque) = (moved.force.as_vec3(), moved.torque.as_vec3());
        if !(force.is_finite() && torque.is_finite()) {
            return Err(Error::InvalidParam {
                name: "body forces",
                value: moved.force.length(),
                expected: "finite in f32: the body is too large, deep or dense",
            });
        }
        // The water steps `dt / time_scale` seconds at a time: the tick's impulse goes into
        // its next step.
        let step_seconds = (self.params.dt / self.params.time_scale) as f64;
        let factor = seconds as f64 / step_seconds;
        self.logged(scratch, |water, scratch| {
            water.push_reactions(factor, scratch)
        })?;
        Ok(BodyForces { force, torque })
    }
}
