//! The bodies' subsystem of a [`Surface`]: the floating bodies, their world, and the water
//! column under them (the model is explained in [`crate::floater`]).
//!
//! | file | owns |
//! |---|---|
//! | `mod.rs` | the bodies' data ([`BodySet`]) and the public calls that add, read and push them |
//! | `coupling.rs` | the coupled step: the water under each body, the bodies' steps, their reactions; [`Surface::body_forces`] |
//! | `column.rs` | the water column: what of the bodies' push the lattice gets, and what it carries to the bottom |

mod column;
mod coupling;

pub(crate) use column::{Column, Entry};

use super::Surface;
use crate::body::rigid;
use crate::error::{Error, Result};
use crate::floater::{self, Buoyancy, Floater, FloaterId};
use crate::params;
pub(crate) use coupling::Coupling;
use glam::Vec3;

/// The bodies of one surface, their world, the water column under them, and the scratch
/// of the coupled step.
#[derive(Debug, Clone, Default)]
pub(crate) struct BodySet {
    /// Bodies in the order they were added (ids increase along it).
    bodies: Vec<(FloaterId, Floater)>,
    /// The id the next added body gets.
    next_id: u64,
    buoyancy: Buoyancy,
    /// What the water under the bodies carries and awaits (state).
    column: Column,
    /// Buffers of the coupled step (not state).
    scratch: Coupling,
}

impl BodySet {
    /// Whether a step has nothing of the bodies to do: no body, and no load carried or
    /// waiting in the column.
    pub fn is_idle(&self) -> bool {
        self.bodies.is_empty() && self.column.is_empty()
    }

    /// The bodies with their ids, in the order they were added.
    pub fn records(&self) -> &[(FloaterId, Floater)] {
        &self.bodies
    }

    /// The id the next added body gets.
    pub fn next_id(&self) -> u64 {
        self.next_id
    }

    /// The water column under the bodies.
    pub fn column(&self) -> &Column {
        &self.column
    }

    /// Lends the coupled step's buffers (see [`BodySet::keep_scratch`]): a step borrows
    /// them while it borrows the surface too.
    pub fn take_scratch(&mut self) -> Coupling {
        std::mem::take(&mut self.scratch)
    }

    /// Takes back the buffers [`BodySet::take_scratch`] lent.
    pub fn keep_scratch(&mut self, scratch: Coupling) {
        self.scratch = scratch;
    }

    /// Takes a checked snapshot's bodies, world and column (a new surface's).
    pub fn load(
        &mut self,
        bodies: Vec<(FloaterId, Floater)>,
        next_id: u64,
        buoyancy: Buoyancy,
        column: Vec<Entry>,
    ) {
        self.bodies = bodies;
        self.set_world(next_id, buoyancy);
        self.column.set_entries(column);
    }

    /// Takes a snapshot's next id and buoyancy (checked).
    pub fn set_world(&mut self, next_id: u64, buoyancy: Buoyancy) {
        self.next_id = next_id;
        self.buoyancy = buoyancy;
    }

    /// A restore in place, begun: the bodies' list, to decode the restored bodies after the
    /// first `len()` current ones, and the column's spare list to decode its entries into.
    /// [`BodySet::finish_restore`] keeps them or drops them.
    pub fn restoring(&mut self) -> (&mut Vec<(FloaterId, Floater)>, &mut Vec<Entry>) {
        (&mut self.bodies, self.column.spare())
    }

    /// Ends a restore begun with [`BodySet::restoring`] when the list held `old` bodies:
    /// the restored ones replace them if `keep`, else they are dropped.
    pub fn finish_restore(&mut self, old: usize, keep: bool) {
        if keep {
            self.bodies.drain(..old);
            self.column.take_spare();
        } else {
            self.bodies.truncate(old);
        }
    }

    /// The window moved: the column's loads move with their water (`to` gives a node's
    /// new index, `None` for nodes that left).
    pub fn shift(&mut self, to: impl Fn(usize) -> Option<usize>) {
        self.column.shift(to);
    }

    /// The water's frame moved by `(dx, dz)` world units (a rebase): every body moves
    /// back by it.
    pub fn rebase(&mut self, dx: f64, dz: f64) {
        for (_, body) in &mut self.bodies {
            body.position.x = (body.position.x as f64 - dx) as f32;
            body.position.z = (body.position.z as f64 - dz) as f32;
        }
    }

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
        self.admit_with(self.bodies.buoyancy)?;
        let mesh = coupling::wet_mesh(&body.shape, self.params.spacing)?;
        let id = FloaterId(self.bodies.next_id);
        self.bodies.next_id = id.0.checked_add(1).ok_or(Error::InvalidParam {
            name: "floater id",
            value: id.0 as f64,
            expected: "fewer than 2^64 − 1 floaters ever added to one surface",
        })?;
        let k = self.bodies.bodies.len();
        self.bodies.scratch.keep_mesh(k, &body.shape, mesh);
        self.bodies.bodies.push((id, body));
        Ok(id)
    }

    /// `body` validated and fit for this surface, with its read-only fields set and its
    /// orientation normalised.
    pub(super) fn admit(&self, body: Floater, force: Vec3, torque: Vec3) -> Result<Floater> {
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
        let k = self.bodies.index(id)?;
        self.bodies.scratch.forget_mesh(k);
        Ok(self.bodies.bodies.remove(k).1)
    }

    /// A body's current state.
    pub fn floater(&self, id: FloaterId) -> Result<&Floater> {
        let k = self.bodies.index(id)?;
        Ok(&self.bodies.bodies[k].1)
    }

    /// Replaces a body's state (teleport it, turn it, change its mass or shape); its
    /// read-only [`Floater::water_force`] and [`Floater::water_torque`] are kept.
    /// Validated like [`Surface::add_floater`]; on error nothing changes.
    pub fn set_floater(&mut self, id: FloaterId, body: Floater) -> Result<()> {
        let k = self.bodies.index(id)?;
        let old = &self.bodies.bodies[k].1;
        let body = self.admit(body, old.water_force, old.water_torque)?;
        if body.shape != self.bodies.bodies[k].1.shape {
            let mesh = coupling::wet_mesh(&body.shape, self.params.spacing)?;
            self.bodies.scratch.keep_mesh(k, &body.shape, mesh);
        }
        self.bodies.bodies[k].1 = body;
        Ok(())
    }

    /// Every body with its id, in the order they were added.
    pub fn floaters(&self) -> impl ExactSizeIterator<Item = (FloaterId, &Floater)> {
        self.bodies.bodies.iter().map(|(id, f)| (*id, f))
    }

    /// Adds `force` through a body's centre of mass (mass units × world units per second²,
    /// like every force on a body) for the next step only: an engine, the wind, a player's
    /// push. On error nothing changes.
    pub fn push_floater(&mut self, id: FloaterId, force: impl Into<Vec3>) -> Result<()> {
        self.push_wrench(id, force.into(), Vec3::ZERO)
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
        let (force, at) = (force.into(), at.into());
        for c in at.to_array() {
            params::finite("push point", c)?;
        }
        let k = self.bodies.index(id)?;
        let offset = at - self.bodies.bodies[k].1.position;
        self.push_wrench(id, force, offset.cross(force))
    }

    /// Adds `torque` about a body's centre of mass (world axes; mass units × world units²
    /// per second²) for the next step only. On error nothing changes.
    pub fn push_floater_torque(&mut self, id: FloaterId, torque: impl Into<Vec3>) -> Result<()> {
        self.push_wrench(id, Vec3::ZERO, torque.into())
    }

    fn push_wrench(&mut self, id: FloaterId, force: Vec3, torque: Vec3) -> Result<()> {
        let k = self.bodies.index(id)?;
        let body = &self.bodies.bodies[k].1;
        let push = body.push + force;
        let push_torque = body.push_torque + torque;
        for c in force.to_array().into_iter().chain(push.to_array()) {
            params::finite("floater push", c)?;
        }
        for c in torque.to_array().into_iter().chain(push_torque.to_array()) {
            params::finite("floater push torque", c)?;
        }
        let body = &mut self.bodies.bodies[k].1;
        body.push = push;
        body.push_torque = push_torque;
        Ok(())
    }

    /// Gravity (world units per second²) and water density for the bodies.
    pub fn buoyancy(&self) -> Buoyancy {
        self.bodies.buoyancy
    }

    /// Sets gravity and water density for the bodies. Refused (nothing changes) when a
    /// field is out of range, or when bodies float and the stiffer waterline would need a
    /// smaller timestep than `params().dt`.
    pub fn set_buoyancy(&mut self, buoyancy: Buoyancy) -> Result<()> {
        buoyancy.validate()?;
        if !self.bodies.bodies.is_empty() {
            self.admit_with(buoyancy)?;
        }
        self.bodies.buoyancy = buoyancy;
        Ok(())
    }

    /// Refuses `params().dt` for the current tables with bodies floating in `buoyancy`.
    fn admit_with(&self, buoyancy: Buoyancy) -> Result<()> {
        let extra = buoyancy.node_stiffness(self.params.spacing, self.params.time_scale);
        self.stability.admit(self.params.dt, extra)
    }

    /// The waterline stiffness the bodies add to a node (0 without bodies).
    pub(crate) fn floater_stiffness(&self) -> f32 {
        if self.bodies.bodies.is_empty() {
            0.0
        } else {
            self.bodies
                .buoyancy
                .node_stiffness(self.params.spacing, self.params.time_scale)
        }
    }
}
