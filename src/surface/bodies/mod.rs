//! The bodies' subsystem of a [`Surface`]: the floating bodies, their world, and the water
//! column under them (the model is explained in [`crate::floater`]).
//!
//! | file | owns |
//! |---|---|
//! | `mod.rs` | the bodies' data ([`BodySet`]: each body's [`Record`] with the mesh the water presses on) and the public calls that add, read and push them |
//! | `coupling.rs` | the coupled step: the water under each body, the bodies' steps, their reactions; [`Surface::body_forces`] |
//! | `column.rs` | the water column: what of the bodies' push the lattice gets, and what it carries to the bottom |
//! | `section.rs` | the bodies' section of a snapshot: their records, hull meshes and column entries as bytes and back |

mod column;
mod coupling;
pub(crate) mod section;

pub(crate) use column::{Column, Entry};

use super::Surface;
use crate::body::{math, Hull};
use crate::error::{Error, Result};
use crate::floater::{self, Buoyancy, Floater, FloaterId, Shape};
use crate::params;
pub(crate) use coupling::Coupling;
use glam::Vec3;
use std::sync::Arc;

/// One floating body of a surface: its id, its state, and the mesh the water presses on
/// (what [`floater::wet_mesh`] gives for its shape, made when the body comes or its shape
/// changes, and kept through a restore that leaves the shape as it was).
#[derive(Debug, Clone)]
pub(crate) struct Record {
    id: FloaterId,
    body: Floater,
    mesh: Option<Arc<Hull>>,
}

/// The bodies of one surface, their world, the water column under them, and the scratch
/// of the coupled step.
#[derive(Debug, Clone, Default)]
pub(crate) struct BodySet {
    /// Bodies in the order they were added (ids increase along it).
    records: Vec<Record>,
    /// The bodies a restore decoded, before it keeps them.
    restored: Vec<(FloaterId, Floater)>,
    /// Their meshes (parallel to `restored`).
    restored_meshes: Vec<Option<Arc<Hull>>>,
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
        self.records.is_empty() && self.column.is_empty()
    }

    /// The bodies, in the order they were added.
    pub fn records(&self) -> &[Record] {
        &self.records
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

    /// Takes a checked snapshot's bodies, world and column (a new surface's, of grid
    /// spacing `spacing`); refused, with nothing changed, if a body's mesh cannot be made.
    pub fn load(
        &mut self,
        bodies: Vec<(FloaterId, Floater)>,
        next_id: u64,
        buoyancy: Buoyancy,
        column: Vec<Entry>,
        spacing: f32,
    ) -> Result<()> {
        let records = bodies
            .into_iter()
            .map(|(id, body)| {
                let mesh = floater::wet_mesh(&body.shape, spacing)?;
                Ok(Record { id, body, mesh })
            })
            .collect::<Result<_>>()?;
        self.records = records;
        self.set_world(next_id, buoyancy);
        self.column.set_entries(column);
        Ok(())
    }

    /// Takes a snapshot's next id and buoyancy (checked).
    pub fn set_world(&mut self, next_id: u64, buoyancy: Buoyancy) {
        self.next_id = next_id;
        self.buoyancy = buoyancy;
    }

    /// A restore in place, begun: the current bodies, which lend their hull meshes to the
    /// restored ones; the list to decode the restored bodies into; the column's spare list
    /// to decode its entries into. [`BodySet::finish_restore`] keeps them or drops them.
    pub fn restoring(&mut self) -> (&[Record], &mut Vec<(FloaterId, Floater)>, &mut Vec<Entry>) {
        self.restored.clear();
        (&self.records, &mut self.restored, self.column.spare())
    }

    /// The meshes of the bodies a restore decoded (checked bodies), on a grid of
    /// `spacing`: body `k` keeps the mesh of the current body `k` if its shape is the same
    /// (a rollback makes none), else gets its own. Refused, with the current bodies
    /// unchanged, if one cannot be made.
    pub fn mesh_restored(&mut self, spacing: f32) -> Result<()> {
        self.restored_meshes.clear();
        for (k, (_, body)) in self.restored.iter().enumerate() {
            let kept = match self.records.get(k) {
                Some(was) if same(&was.body.shape, &body.shape) => was.mesh.clone(),
                _ => floater::wet_mesh(&body.shape, spacing)?,
            };
            self.restored_meshes.push(kept);
        }
        Ok(())
    }

    /// Ends a restore begun with [`BodySet::restoring`]: the restored bodies (meshed by
    /// [`BodySet::mesh_restored`]) replace the current ones if `keep`, else they are
    /// dropped. Keeping reuses the list's capacity.
    pub fn finish_restore(&mut self, keep: bool) {
        if keep {
            let meshes = self.restored_meshes.drain(..);
            let restored = self.restored.drain(..).zip(meshes);
            self.records.clear();
            self.records
                .extend(restored.map(|((id, body), mesh)| Record { id, body, mesh }));
            self.column.take_spare();
        }
        self.restored.clear();
        self.restored_meshes.clear();
    }

    /// Forgets the reactions of [`Surface::body_forces`] waiting for the next step.
    pub fn drop_pending(&mut self) {
        self.column.drop_pending();
    }

    /// The window moved: the column's loads move with their water (`to` gives a node's
    /// new index, `None` for nodes that left).
    pub fn shift(&mut self, to: impl Fn(usize) -> Option<usize>) {
        self.column.shift(to);
    }

    /// The water's frame moved by `(dx, dz)` world units (a rebase): every body moves
    /// back by it.
    pub fn rebase(&mut self, dx: f64, dz: f64) {
        for Record { body, .. } in &mut self.records {
            body.position.x = (body.position.x as f64 - dx) as f32;
            body.position.z = (body.position.z as f64 - dz) as f32;
        }
    }

    fn index(&self, id: FloaterId) -> Result<usize> {
        self.records
            .binary_search_by_key(&id, |r| r.id)
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
        let mesh = floater::wet_mesh(&body.shape, self.params.spacing)?;
        let id = FloaterId(self.bodies.next_id);
        self.bodies.next_id = id.0.checked_add(1).ok_or(Error::InvalidParam {
            name: "floater id",
            value: id.0 as f64,
            expected: "fewer than 2^64 − 1 floaters ever added to one surface",
        })?;
        self.bodies.records.push(Record { id, body, mesh });
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
        body.orientation = math::normalised(body.orientation.as_dquat()).as_quat();
        Ok(body)
    }

    /// Removes a body and returns it.
    pub fn remove_floater(&mut self, id: FloaterId) -> Result<Floater> {
        let k = self.bodies.index(id)?;
        Ok(self.bodies.records.remove(k).body)
    }

    /// A body's current state.
    pub fn floater(&self, id: FloaterId) -> Result<&Floater> {
        let k = self.bodies.index(id)?;
        Ok(&self.bodies.records[k].body)
    }

    /// Replaces a body's state (teleport it, turn it, change its mass or shape); its
    /// read-only [`Floater::water_force`] and [`Floater::water_torque`] are kept.
    /// Validated like [`Surface::add_floater`]; on error nothing changes.
    pub fn set_floater(&mut self, id: FloaterId, body: Floater) -> Result<()> {
        let k = self.bodies.index(id)?;
        let old = &self.bodies.records[k].body;
        let body = self.admit(body, old.water_force, old.water_torque)?;
        let record = &mut self.bodies.records[k];
        if !same(&body.shape, &record.body.shape) {
            record.mesh = floater::wet_mesh(&body.shape, self.params.spacing)?;
        }
        record.body = body;
        Ok(())
    }

    /// Every body with its id, in the order they were added.
    pub fn floaters(&self) -> impl ExactSizeIterator<Item = (FloaterId, &Floater)> {
        self.bodies.records.iter().map(|r| (r.id, &r.body))
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
        let offset = at - self.bodies.records[k].body.position;
        self.push_wrench(id, force, offset.cross(force))
    }

    /// Adds `torque` about a body's centre of mass (world axes; mass units × world units²
    /// per second²) for the next step only. On error nothing changes.
    pub fn push_floater_torque(&mut self, id: FloaterId, torque: impl Into<Vec3>) -> Result<()> {
        self.push_wrench(id, Vec3::ZERO, torque.into())
    }

    fn push_wrench(&mut self, id: FloaterId, force: Vec3, torque: Vec3) -> Result<()> {
        let k = self.bodies.index(id)?;
        let body = &self.bodies.records[k].body;
        let push = body.push + force;
        let push_torque = body.push_torque + torque;
        for c in force.to_array().into_iter().chain(push.to_array()) {
            params::finite("floater push", c)?;
        }
        for c in torque.to_array().into_iter().chain(push_torque.to_array()) {
            params::finite("floater push torque", c)?;
        }
        let body = &mut self.bodies.records[k].body;
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
        if !self.bodies.records.is_empty() {
            self.admit_with(buoyancy)?;
        }
        self.bodies.buoyancy = buoyancy;
        Ok(())
    }

    /// Refuses `params().dt` for the current tables with bodies floating in `buoyancy`.
    fn admit_with(&self, buoyancy: Buoyancy) -> Result<()> {
        let extra = buoyancy.node_stiffness(self.params.spacing, self.params.time_scale);
        self.lattice.stability.admit(self.params.dt, extra)
    }

    /// The waterline stiffness the bodies add to a node (0 without bodies).
    pub(crate) fn floater_stiffness(&self) -> f32 {
        if self.bodies.records.is_empty() {
            0.0
        } else {
            self.bodies
                .buoyancy
                .node_stiffness(self.params.spacing, self.params.time_scale)
        }
    }
}

/// Whether two shapes are the same (a hull shared through one `Arc` without comparing
/// its triangles).
fn same(a: &Shape, b: &Shape) -> bool {
    match (a, b) {
        (Shape::Hull(a), Shape::Hull(b)) => Arc::ptr_eq(a, b) || a == b,
        _ => a == b,
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::{Params, Surface};

    /// Every body's mesh is its shape's, after each way the list changes.
    fn meshes_fit(s: &Surface) {
        let set = &s.bodies;
        assert!(set.restored.is_empty() && set.restored_meshes.is_empty());
        for r in &set.records {
            let want = floater::wet_mesh(&r.body.shape, s.params.spacing).unwrap();
            assert_eq!(r.mesh.as_deref(), want.as_deref(), "{:?}", r.body.shape);
        }
    }

    #[test]
    fn each_body_keeps_the_mesh_of_its_shape() {
        let mut s = Surface::new(Params::with_size(48, 48)).unwrap();
        let ball = s
            .add_floater(Floater::sphere(0.5, 0.1, [10.0, 0.0, 10.0]))
            .unwrap();
        let boxy = s.add_floater(Floater::cuboid([1.0, 0.5, 1.0], 0.5, [20.0, 0.0, 20.0]));
        let boxy = boxy.unwrap();
        s.add_floater(Floater::sphere(3.0, 40.0, [30.0, 0.0, 30.0]))
            .unwrap();
        meshes_fit(&s);
        // A small ball is a cap under the plane: no mesh.
        assert!(s.bodies.records[0].mesh.is_none() && s.bodies.records[2].mesh.is_some());
        let saved = s.to_bytes();
        s.remove_floater(ball).unwrap();
        let mut wide = s.floater(boxy).unwrap().clone();
        wide.shape = Shape::Box {
            half_extents: Vec3::new(3.0, 0.5, 3.0),
        };
        s.set_floater(boxy, wide).unwrap();
        meshes_fit(&s);
        s.step_n(3).unwrap();
        // A rollback to three bodies of other shapes in other places.
        s.restore(&saved).unwrap();
        meshes_fit(&s);
        assert_eq!(s.to_bytes(), saved);
        // A restore that is refused leaves the bodies and their meshes as they were.
        let mut bad = saved.clone();
        let last = bad.len() - 1;
        bad[last] ^= 1;
        assert!(s.restore(&bad).is_err());
        meshes_fit(&s);
        let loaded = Surface::from_bytes(&saved).unwrap();
        meshes_fit(&loaded);
    }

    #[test]
    fn clearing_the_forces_drops_the_reactions_of_body_forces_too() {
        let mut touched = Surface::new(Params::with_size(32, 32)).unwrap();
        touched.drop_at(16.0, 16.0, 1.0, 2.0).unwrap();
        let mut calm = touched.clone();
        let ball = Floater::sphere(2.0, 10.0, [10.0, 0.0, 10.0]);
        touched.body_forces(&ball, 1.0 / 60.0).unwrap();
        assert!(!touched.bodies.column.is_empty());
        touched.clear_forces();
        calm.clear_forces();
        assert!(touched.bodies.column.is_empty());
        touched.step_n(5).unwrap();
        calm.step_n(5).unwrap();
        assert_eq!(touched.state_hash(), calm.state_hash());
    }
}
