//! The floating bodies and the water, coupled: each step of the surface reads the water
//! under every body, steps the bodies (in parallel, each on its own), pushes their
//! reactions into the water and then steps the water; and the water's forces on a body
//! another physics engine owns ([`Surface::body_forces`]).
//!
//! The model is explained in [`crate::floater`] and computed in [`crate::body`]: the
//! `hydrostatics` module presses the water on a body's wet triangles (the `small` module
//! presses one plane of water on a small ball or box), the `rigid` module solves its
//! step. This file only gathers the water for them and hands their reactions
//! back: bodies step in parallel but their reactions go into the water one body after
//! another in the order the bodies were added, so the bits do not depend on the threads.

use super::{column, Record};
use crate::body::rigid::{self, Piece, World};
use crate::body::small::{self, Plane};
use crate::body::{Hull, HullScratch};
use crate::error::{Error, Result};
use crate::floater::{self, BodyForces, Buoyancy, Floater, Motion, Shape};
use crate::jobs::{self, Runner};
use crate::surface::query::{Spread, Waters};
use crate::surface::Surface;
use glam::{DVec3, Vec3};
use std::sync::Arc;

/// Buffers the coupled step reuses; not state.
#[derive(Debug, Clone, Default)]
pub(crate) struct Coupling {
    /// Meshes of the bodies [`Surface::body_forces`] was asked about, newest last.
    foreign: Vec<(Shape, Option<Arc<Hull>>)>,
    /// One per body: its workspace and its step's outcome.
    slots: Vec<Slot>,
    /// The workspace of [`Surface::body_forces`].
    foreign_slot: Slot,
}

/// How many meshes of bodies another engine owns are kept.
const FOREIGN_MESHES: usize = 16;

/// Bodies per task when they step in parallel.
const BODIES_PER_TASK: usize = 16;

/// One body's workspace and outcome in a step.
#[derive(Debug, Clone, Default)]
struct Slot {
    hull: HullScratch,
    pieces: Vec<Piece>,
    /// Where each piece's reaction goes into the water (parallel to `pieces`).
    spreads: Vec<Option<Spread>>,
    /// The forces the body feels and where (the water gets minus each): first one per
    /// piece, then the waterplane's.
    forces: Vec<(DVec3, DVec3)>,
    /// The water's share of the body's reactions, in the lattice's units, summed for the
    /// nodes under the body: a window of `width` nodes by rows, its first the node
    /// `first` of a grid of `cols` columns ([`Slot::shares`] reads it).
    window: Vec<Sum>,
    first: usize,
    width: usize,
    cols: usize,
    /// What the step changes of the body, or why its step failed (`None` until it steps).
    motion: Option<Result<Motion>>,
}

/// What every body's step reads: the water and the world.
struct Context<'a> {
    waters: Waters<'a>,
    buoyancy: Buoyancy,
    /// The time scale: seconds of the bodies to model time of the lattice.
    scale: f32,
    spacing: f32,
    /// The step, seconds.
    seconds: f32,
    /// The damping rate per unit of model time the water's step has room for.
    room_rate: f32,
    /// Steps the surface has taken (for errors).
    steps: u64,
}

impl Context<'_> {
    /// Body `body` pressing on `mesh` (its [`floater::wet_mesh`]): its implicit step over
    /// `seconds` (see the `rigid` module of [`crate::body`]), leaving the forces it feels
    /// in `slot.forces`. A small body meets the water as a plane ([`Context::step_small`]).
    fn step(&self, body: &Floater, mesh: Option<&Hull>, slot: &mut Slot) -> Result<rigid::Moved> {
        let mesh = match mesh {
            _ if body.shape.is_small(self.spacing) => return self.step_small(body, mesh, slot),
            Some(mesh) => mesh,
            None => return Err(no_mesh()),
        };
        let rho_g = self.rho_g();
        let h = self.spacing as f64;
        let pieces = &mut slot.pieces;
        pieces.clear();
        let waters = &self.waters;
        // A ball is the same in every orientation: its mesh stays aligned with the world's
        // axes (mirror-symmetric in x and z), so the ball's spin never turns the facets of
        // its tessellation under the water (a rolling polyhedron would walk).
        let orientation = match body.shape {
            Shape::Sphere { .. } => glam::Quat::IDENTITY,
            _ => body.orientation,
        };
        let pressure = mesh.pressed(
            body.position,
            orientation,
            rho_g,
            // Off the patch the water is calm, at height 0.
            |x, z| waters.height(x, z).unwrap_or(0.0),
            &mut slot.hull,
            |point, force, area| {
                pieces.push(Piece {
                    point,
                    force,
                    area,
                    flow: DVec3::ZERO,
                    // The pressure pushes the face inwards, against its outward normal.
                    normal: -force.normalize_or_zero(),
                })
            },
        )?;
        // The water's velocity under each piece (per second), and the damping room the
        // water's step leaves under the body, per second.
        let mut room = f64::INFINITY;
        let mut seen = 0.0;
        let mut cache = None;
        slot.spreads.clear();
        for p in pieces.iter_mut() {
            let (x, z) = (p.point.x as f32, p.point.z as f32);
            let under = waters.flow(x, z, self.room_rate, &mut cache);
            if let Some((flow, r, _)) = under {
                p.flow = (flow * self.scale).as_dvec3();
                room = room.min(r.max(0.0) as f64 * self.scale as f64);
            }
            slot.spreads.push(under.map(|u| u.2));
            let f = p.force.length();
            if f > 0.0 {
                seen += p.area * p.force.y.abs() / f;
            }
        }
        // The body's drag rate, capped at half of what that room allows over the cells it
        // covers (its waterplane, or half its wet area seen from above when under), and
        // so that a piece's form drag, `FORM` times its share, stays within it.
        let cells = pressure.plane.area.max(0.5 * seen) / (h * h);
        let cap = 0.5 * room * cells.max(1.0) / rigid::FORM;
        let world = self.world(body, pressure.volume, cap);
        Ok(rigid::step(
            &body.rigid(),
            pieces,
            &pressure.plane,
            world,
            &mut slot.forces,
        ))
    }

    /// The water's weight per volume, `ρ g`.
    fn rho_g(&self) -> f64 {
        self.buoyancy.density as f64 * self.buoyancy.gravity as f64
    }

    /// What the rigid step of `body` needs of the water: its weight per volume, gravity,
    /// the timestep, and the drag rate `k ρ V` for the displaced `volume`, at most
    /// `drag_cap` (what the water's damping room allows under the body).
    fn world(&self, body: &Floater, volume: f64, drag_cap: f64) -> World {
        let Buoyancy { gravity, density } = self.buoyancy;
        let drag = body.drag as f64 * density as f64 * volume;
        World {
            rho_g: self.rho_g(),
            gravity: gravity as f64,
            dt: self.seconds as f64,
            drag_rate: drag.min(drag_cap),
        }
    }

    /// [`Context::step`] for a small body (the `small` module of [`crate::body`]): the
    /// water sampled once, at the body's centre, as a plane; the pressure of that plane as
    /// one force at the centre of buoyancy `B`, and the drag there towards the water's
    /// velocity under `B`. `mesh` is a box's 12 triangles (a ball needs none).
    fn step_small(
        &self,
        body: &Floater,
        mesh: Option<&Hull>,
        slot: &mut Slot,
    ) -> Result<rigid::Moved> {
        let rho_g = self.rho_g();
        let c = body.position;
        // Off the patch the water is calm, at height 0.
        let (height, slope) = self.waters.plane(c.x, c.z).unwrap_or((0.0, [0.0; 2]));
        let water = Plane {
            at: [c.x as f64, c.z as f64],
            height: height as f64,
            slope: slope.map(f64::from),
        };
        let wet = match (&body.shape, mesh) {
            (&Shape::Sphere { radius }, _) => {
                small::sphere(radius as f64, c.as_dvec3(), water, rho_g)
            }
            (_, Some(mesh)) => {
                small::mesh(mesh, c, body.orientation, water, rho_g, &mut slot.hull)?
            }
            (_, None) => return Err(no_mesh()),
        };
        let b = wet.centre;
        let under = self
            .waters
            .flow(b.x as f32, b.z as f32, self.room_rate, &mut None);
        let (flow, room) = match under {
            Some((flow, room, _)) => (
                (flow * self.scale).as_dvec3(),
                room.max(0.0) as f64 * self.scale as f64,
            ),
            None => (DVec3::ZERO, f64::INFINITY),
        };
        slot.pieces.clear();
        slot.pieces.push(Piece {
            point: b,
            force: wet.force,
            area: 1.0,
            flow,
            // One point for the whole body: it drags alike in every direction.
            normal: DVec3::ZERO,
        });
        slot.spreads.clear();
        slot.spreads.push(under.map(|u| u.2));
        // The whole drag lands on the four nodes under `B`: capped at half the room of
        // one cell.
        let world = self.world(body, wet.volume, 0.5 * room);
        Ok(rigid::step(
            &body.rigid(),
            &slot.pieces,
            &wet.plane,
            world,
            &mut slot.forces,
        ))
    }

    /// Each node's share of minus every force the body of `slot` feels, times `factor`,
    /// in the lattice's units, summed node by node in `slot.window` (forces off the patch
    /// push nothing), each node's in the order of the forces. The window is the part of
    /// the grid just wide enough for the body's spreads, where a node is found by its
    /// place; the column reads the sums straight from it ([`Slot::shares`]).
    fn shares(&self, slot: &mut Slot, factor: f64) {
        let Slot {
            spreads,
            forces,
            window,
            ..
        } = slot;
        window.clear();
        // The pieces' spreads were found with the water under them; the others' now.
        for &(point, _) in forces.iter().skip(spreads.len()) {
            spreads.push(self.waters.spread(point.x as f32, point.z as f32));
        }
        // The window: the rows and columns of every spread's corners.
        let (mut lo, mut hi) = ([usize::MAX; 2], [0; 2]);
        for spread in spreads.iter().flatten() {
            let [c, r] = spread.cell;
            lo = [lo[0].min(c), lo[1].min(r)];
            hi = [hi[0].max(c + 1), hi[1].max(r + 1)];
        }
        if lo[0] > hi[0] {
            return;
        }
        let width = hi[0] - lo[0] + 1;
        let nodes = width * (hi[1] - lo[1] + 1);
        window.resize(nodes, NO_SUM);
        // The lattice's forces are per unit of model time²: a body's force in seconds goes
        // in divided by `time_scale²`.
        let scale = factor / ((self.scale as f64) * (self.scale as f64));
        for (&(_, force), spread) in forces.iter().zip(spreads.iter()) {
            let Some(Spread {
                cell: [c, r],
                weights,
            }) = *spread
            else {
                continue;
            };
            let reaction = (-force * scale).as_vec3().to_array();
            let at = (r - lo[1]) * width + (c - lo[0]);
            for (k, w) in [at, at + 1, at + width, at + width + 1]
                .into_iter()
                .zip(weights)
            {
                let add = reaction.map(|f| f * w);
                let (sum, seen) = &mut window[k];
                // A node's sum starts at −0, so its first share is taken as it is (its
                // sign of zero kept: −0 + x is x, bit for bit).
                *sum = [sum[0] + add[0], sum[1] + add[1], sum[2] + add[2]];
                *seen = true;
            }
        }
        let cols = self.waters.cols();
        (slot.first, slot.width, slot.cols) = (lo[1] * cols + lo[0], width, cols);
    }
}

impl Slot {
    /// The body's shares of the water, node by node, row by row: the nodes of the window
    /// that got any.
    fn shares(&self) -> impl Iterator<Item = (usize, [f32; 3])> + Clone + '_ {
        let (first, cols) = (self.first, self.cols);
        let rows = self.window.chunks_exact(self.width.max(1));
        rows.enumerate().flat_map(move |(r, row)| {
            let nodes = row.iter().enumerate().filter(|(_, sum)| sum.1);
            nodes.map(move |(c, &(f, _))| (first + r * cols + c, f))
        })
    }
}

/// A node's sum of shares while a body's are summed, and whether it has any.
type Sum = ([f32; 3], bool);

/// A node without shares: its sum starts at −0, the one zero that adds nothing.
const NO_SUM: Sum = ([-0.0; 3], false);

impl Surface {
    /// The coupled step's second stage: the bodies' shares (`c`, in the bodies' order) go
    /// through the column, and what the water gets is added to the external forces, all or
    /// nothing: refused, with nothing changed, if a node's force would not be finite.
    pub(crate) fn apply_reactions(&mut self, c: &Coupling) -> Result<()> {
        let n = self.node_count();
        let column = &mut self.bodies.column;
        column.begin_gather(n);
        // A share of zero (either sign: a corner of a spread with no weight, a point on a
        // cell's edge) changes no bit of the column or the forces (sums there start at +0
        // and stay off −0, and the lattice takes a zero force's sign to +0): it is left
        // out, so it makes no entry that the commit would drop again.
        for slot in &c.slots {
            slot.shares().for_each(|(node, f)| {
                if f != [0.0; 3] {
                    column.gather(node, f);
                }
            });
        }
        let water = self.bodies.column.water();
        self.lattice
            .state
            .ext
            .add(water)
            .map_err(|_| Error::InvalidParam {
                name: "accumulated force",
                value: f64::INFINITY,
                expected: "finite: the bodies' reactions overflow f32",
            })
    }

    /// The coupled step's last stage, once the water's step of model time `dt` succeeded:
    /// the bodies take their new poses and velocities, and the column takes up its share
    /// of what the water got.
    pub(crate) fn commit_bodies(&mut self, dt: f32, c: &mut Coupling) {
        for (Record { body, .. }, slot) in self.bodies.records.iter_mut().zip(&mut c.slots) {
            if let Some(Ok(motion)) = slot.motion.take() {
                body.take_motion(&motion);
            }
        }
        let seconds = dt / self.params.time_scale;
        self.bodies.column.commit(column::rate(seconds));
    }

    /// The coupled step failed: this step's pushes are forgotten (the external forces were
    /// taken back by their own undo).
    pub(crate) fn discard_bodies(&mut self) {
        self.bodies.column.discard();
    }

    fn context(&self, seconds: f32) -> Context<'_> {
        Context {
            waters: self.waters(),
            buoyancy: self.bodies.buoyancy,
            scale: self.params.time_scale,
            spacing: self.params.spacing,
            seconds,
            room_rate: self
                .lattice
                .stability
                .damping_room(self.params.dt, self.floater_stiffness()),
            steps: self.steps(),
        }
    }

    /// The coupled step's first stage: every body reads the water under it and takes its
    /// step (in parallel, into `c.slots`), and its reactions become shares of the nodes.
    /// `dt` is model time; the bodies step `dt / time_scale` seconds. Changes nothing of
    /// the surface.
    pub(crate) fn prepare_bodies(&self, dt: f32, c: &mut Coupling) -> Result<()> {
        let bodies = &self.bodies.records;
        c.slots.resize_with(bodies.len(), Slot::default);
        let cx = self.context(dt / self.params.time_scale);
        jobs::for_each_part(
            Runner::of(self.host.as_ref()),
            bodies.len(),
            1,
            BODIES_PER_TASK,
            &mut c.slots[..],
            &|range, slots: &mut [Slot]| {
                for (k, slot) in range.zip(slots) {
                    let Record { id, body, mesh } = &bodies[k];
                    let step = cx.step(body, mesh.as_deref(), slot);
                    slot.motion = Some(step.and_then(|m| {
                        let motion = motion(&m);
                        // Shape, mass, inertia and drag are the valid body's: what the
                        // step changed must be finite and in range.
                        match motion.in_range() {
                            true => Ok(motion),
                            false => Err(Error::FloaterNonFinite {
                                step: cx.steps,
                                floater: id.0,
                            }),
                        }
                    }));
                    cx.shares(slot, 1.0);
                }
            },
        );
        // The first body whose step failed, with its own error.
        match c
            .slots
            .iter()
            .find_map(|slot| slot.motion.as_ref()?.as_ref().err())
        {
            Some(e) => Err(e.clone()),
            None => Ok(()),
        }
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
        let mut c = std::mem::take(&mut self.bodies.scratch);
        let n = self.node_count();
        let out = self
            .foreign_forces(&body, seconds, &mut c)
            .and_then(|forces| {
                let shares = c.foreign_slot.shares();
                self.bodies.column.hold(shares, n).map(|()| forces)
            });
        self.bodies.scratch = c;
        out
    }

    /// The water's forces on `body` over `seconds`, its reactions' shares in `c.foreign_slot`.
    fn foreign_forces(&self, body: &Floater, seconds: f32, c: &mut Coupling) -> Result<BodyForces> {
        let mesh = match c
            .foreign
            .iter()
            .position(|(s, _)| super::same(s, &body.shape))
        {
            Some(k) => {
                let entry = c.foreign.remove(k);
                let mesh = entry.1.clone();
                c.foreign.push(entry);
                mesh
            }
            None => {
                let mesh = floater::wet_mesh(&body.shape, self.params.spacing)?;
                if c.foreign.len() == FOREIGN_MESHES {
                    c.foreign.remove(0);
                }
                c.foreign.push((body.shape.clone(), mesh.clone()));
                mesh
            }
        };
        let cx = self.context(seconds);
        let slot = &mut c.foreign_slot;
        let moved = cx.step(body, mesh.as_deref(), slot)?;
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
        cx.shares(slot, seconds as f64 / step_seconds);
        Ok(BodyForces { force, torque })
    }
}

/// A body without the mesh its shape needs (never: every body's is made with it).
fn no_mesh() -> Error {
    Error::InvalidParam {
        name: "floater mesh",
        value: 0.0,
        expected: "the mesh of the body's shape",
    }
}

/// What the step `m` changes of a body, in its `f32` fields.
fn motion(m: &rigid::Moved) -> Motion {
    Motion {
        position: m.position.as_vec3(),
        orientation: m.orientation.as_quat(),
        velocity: m.velocity.as_vec3(),
        angular_velocity: m.angular_velocity.as_vec3(),
        water_force: m.force.as_vec3(),
        water_torque: m.torque.as_vec3(),
    }
}
