//! Snapshots: the complete state of a [`Surface`] saved and restored bitwise (the format
//! is documented on [`Snapshot`]), and the rollback a multiplayer game runs on them: a hash
//! of the state ([`Surface::state_hash`]), saving into a reused buffer
//! ([`Surface::save_into`]) and restoring in place ([`Surface::restore`]).
//!
//! How it is built: the encoder is written once (`stream.rs`), a sequence of fields sent
//! to a sink that is a byte buffer for saving and a hasher for `state_hash`; the reader
//! (`read.rs`) checks the framing every version shares and reads the sections the
//! versions are built from, borrowing the bytes; the bodies' section (the bodies, the hull
//! meshes they share and the water column) is the bodies' subsystem's to write, read and
//! check (`surface/bodies/section.rs`), in the field vocabulary both share
//! (`surface/bytes.rs`); each format version has one decoder that upgrades what it read to
//! the next version (`versions.rs`); validation
//! (`validate.rs`) checks a snapshot's contents wherever they are, in vectors or in the
//! bytes; `restore.rs` copies a current-version snapshot back into a surface of the same
//! shape without allocating.
//!
//! # The state hash
//!
//! [`Surface::state_hash`] sends the encoder's stream to XXH3-64 and skips the fields the
//! encoder marks as records (framing and counters); its docs say what is in, what is
//! out and why. XXH3-64 over a checksum such as CRC-32: 64 bits (a desync missed with
//! odds 2⁻⁶⁴ a comparison, not 2⁻³²), and several bytes a cycle.

mod crc;
mod read;
mod restore;
mod stream;
mod validate;
mod versions;

use super::{Overflow, Surface};
use crate::error::{Error, Result};
use crate::floater::{Buoyancy, Floater, FloaterId};
use crate::grid::Grid;
use crate::params::{Boundary, Params};
use crate::simd::Floats;
use crate::springs::Springs;
use crate::stability::Stability;
use crate::state::State;
use crate::surface::bodies::Entry;
use crate::surface::bytes::bad;
use std::io::{Read, Write};
use stream::{slices, Bytes, StateHash};
use validate::Contents;

/// The first eight bytes of every snapshot.
pub(crate) const MAGIC: [u8; 8] = *b"SPRWATER";
/// The format version this build writes. It reads versions 1 to 7 (see [`Snapshot`]).
pub(crate) const VERSION: u32 = 7;
/// Bytes before the per-node arrays in versions 1 and 2.
const HEADER_V2: usize = 112;
/// Bytes before the per-node arrays in versions 3 to 5.
const HEADER_V5: usize = 136;
/// Bytes before the per-node arrays in version 6.
const HEADER_V6: usize = 152;
/// Bytes before the per-node arrays.
const HEADER: usize = 160;
/// Trailing checksum.
const CRC: usize = 4;

/// The complete state of a [`Surface`] as plain data, saved and restored bitwise.
///
/// A game saves a surface with [`Surface::save`] (or [`Surface::to_bytes`]) and gets it back
/// with [`Surface::load`], [`Surface::from_bytes`] or, into an existing surface,
/// [`Surface::restore`]. A restored surface continues **bitwise identically** to the one
/// that was saved: every buffer the step reads is stored with its exact bits. The engine's
/// per-band scratch buffers are not state (a step overwrites them before reading) and are
/// rebuilt.
///
/// Engines that serialise their own way convert to the plain-data [`Snapshot`] with
/// [`Surface::snapshot`] and back with [`Surface::from_snapshot`]; with the `serde` feature
/// it implements `Serialize` and `Deserialize`. Both paths run the same validation; the plain
/// data's arrays may be edited first (its bounds and flags follow them, see
/// [`Surface::from_snapshot`]).
///
/// # Format (version 7)
///
/// Little-endian throughout; `n = cols × rows`, `f` floating bodies, `h` hull meshes in
/// `m` bytes, `k` entries of the water column. Per-node arrays hold exactly `n` values (no SIMD padding); spring tables are
/// indexed by origin node, with `0.0` for springs that do not exist (E from the last
/// column, S from the last row, …).
///
/// | offset | size | field |
/// |---|---|---|
/// | 0 | 8 | magic `b"SPRWATER"` |
/// | 8 | 4 | format version `u32` (7; versions 1 to 6 are read too) |
/// | 12 | 4 | flags `u32`: bit 0 = external forces pending; other bits 0 |
/// | 16 | 8 | total length in bytes `u64`, checksum included |
/// | 24 | 8, 8 | `cols`, `rows` as `u64` |
/// | 40 | 6 × 4 | `spacing`, `mass`, `stiffness`, `viscosity`, `dt`, `rest_ratio` (`f32`) |
/// | 64 | 4 | boundary `u32`: 0 = pinned, 1 = free, 2 = absorbing |
/// | 68 | 3 × 4 | uniform acceleration x, y, z (`f32`, world units per second²) |
/// | 80 | 8 | steps taken `u64` |
/// | 88 | 8 | model time `f64` |
/// | 96 | 3 × 4 | `min_mass`, `max_stiffness`, `max_viscosity` (`f32`): the bounds behind `critical_dt` |
/// | 108 | 4 | `time_scale` (`f32`, model time per second); reserved and 0 in version 1, read as the default |
/// | 112 | 4 | absorbing frame width `u32` (0 unless the boundary is absorbing) |
/// | 116 | 4 | floating bodies `f` (`u32`) |
/// | 120 | 8 | the id the next added body gets (`u64`) |
/// | 128 | 2 × 4 | buoyancy: gravity (world units per second²), water density (`f32`) |
/// | 136 | 8 | hull meshes `h` (`u64`) |
/// | 144 | 8 | the hull section's length in bytes `m` (`u64`) |
/// | 152 | 8 | entries of the water column `k` (`u64`) |
/// | 160 | 9 × 4n | positions x, y, z; velocities x, y, z; pending forces x, y, z (the lattice's units, model time) |
/// | | 2 × 4n | mass, viscosity per node |
/// | | n | pinned per node, `u8` 0 or 1 |
/// | | 8 × 4n | rest length then stiffness, for families E, S, SE, SW |
/// | | 176 f | the bodies, ids increasing (table below) |
/// | | m | the hull section: the `h` meshes, each its vertex count `v` and triangle count `t` (`u32`), `v` vertices (three `f32`, the body's frame), `t` triangles (three `u32` vertex indices, counter-clockwise seen from outside); `m = Σ (8 + 12 v + 12 t)` |
/// | | 32 k | the water column under the bodies, nodes increasing: each its node (`u64`), the load it carries, the load waiting for the next step (three `f32` each, the lattice's force units) |
/// | end − 44 | 2 × 8 | the window's origin in cells, columns then rows (`i64`, [`Surface::origin_cells`]) |
/// | end − 28 | 8 | model time [`Surface::advance`] owes and has not stepped (`f64`) |
/// | end − 20 | 4, 4 | the step cap `u32` and what happens past it `u32`: 0 = drop, 1 = carry ([`Surface::set_step_cap`]) |
/// | end − 12 | 8 | seconds the cap has dropped so far (`f64`) |
/// | end − 4 | 4 | CRC-32 (IEEE) of every byte before it |
///
/// Each body, in seconds and world units as [`Floater`] has them (`f32` but where said):
///
/// | offset | size | field |
/// |---|---|---|
/// | 0 | 8 | id `u64` |
/// | 8 | 4 | shape `u32`: 0 = sphere, 1 = box, 2 = hull |
/// | 12 | 3 × 4 | size: (radius, 0, 0), the half extents, or (0, 0, 0) for a hull |
/// | 24 | 2 × 4 | mass, drag (per second) |
/// | 32 | 3 × 4 | position |
/// | 44 | 3 × 4 | velocity |
/// | 56 | 3 × 4 | push (mass × world units per second²) |
/// | 68 | 3 × 4 | water force |
/// | 80 | 4 × 4 | orientation x, y, z, w (body to world) |
/// | 96 | 3 × 4 | angular velocity (radians per second, world axes) |
/// | 108 | 3 × 4 | push torque |
/// | 120 | 3 × 4 | water torque |
/// | 132 | 4 | hull index `u32` into the hull section (0 for the other shapes) |
/// | 136 | 4 | inertia flag `u32`: 0 = the shape's at uniform density, 1 = the tensor that follows |
/// | 140 | 9 × 4 | inertia tensor, column by column (zeros without the flag) |
///
/// The inertia keeps all nine entries, not the six of a symmetric tensor: validation
/// accepts a tensor symmetric to rounding, which six entries would not give back bit for
/// bit.
///
/// A hull mesh is stored once however many bodies hold it (bodies sharing one
/// `Arc<Hull>`, or meshes with the same bits), in the order the bodies first use it: a
/// body's index is at most one more than the largest before it, every stored mesh is
/// used, and no two have the same bits. Loading passes each mesh through [`Hull::new`](crate::body::Hull::new) and gives
/// the bodies that name one mesh one `Arc`; [`Surface::restore`] reuses the surface's own
/// `Arc` where it has the stored bits.
///
/// The total is `204 + 77 n + 176 f + m + 32 k` bytes. Version 5 has a header of 136 bytes
/// (without the hull section's count and length), bodies of 80 bytes (the first 80 above,
/// spheres and boxes) and no hull section: its bodies load upright (the identity
/// orientation), not spinning, with no torque pushed or felt and the shape's inertia.
/// Version 4 has version 5's layout with the acceleration, gravity and bodies in model
/// time (velocities per unit of model time, drag per unit, accelerations and forces per
/// unit²): loading converts them to seconds with the stored `time_scale` (the
/// acceleration to the per-second² value that converts back to the stored bits where one
/// exists, as for zero and about 9 in 10 other values, else one rounding off; water
/// without bodies then continues bit for bit, bodies to rounding). Version 3 has no
/// origin and no clock either (read as `[0, 0]`, a window that never moved, and a fresh
/// clock). Versions 1 and 2 end the header at offset 112 (no bodies, no absorbing
/// boundary; version 1 has no `time_scale` either: such snapshots get the default).
///
/// Loading refuses, with [`Error::Snapshot`] and a message that says what is wrong: a
/// wrong magic or version, a total length that disagrees with `cols × rows`, the body
/// count and the hull section's length or with the bytes present, a checksum mismatch,
/// parameters that [`Params::validate`] refuses, non-finite values, masses or stiffnesses
/// out of range, pinned nodes that move, springs outside the grid, bounds that do not
/// cover the tables, bodies that [`Floater::validate`] refuses or whose ids are not
/// increasing, unknown shape codes or flags, hull meshes whose counts disagree with the
/// section's length, hull indices out of range or out of order, meshes no body uses or
/// stored twice, and meshes [`Hull::new`](crate::body::Hull::new) refuses. Lengths are checked against the
/// bytes actually present before anything is allocated, so a lying length or count costs
/// nothing. A refused snapshot changes nothing.
///
/// # As plain data
///
/// One value per node (no padding). Produced by [`Surface::snapshot`], turned back into a
/// surface by [`Surface::from_snapshot`], which validates everything. With the `serde`
/// feature it can be serialised in any format serde supports.
#[derive(Debug, Clone, PartialEq)]
#[cfg_attr(feature = "serde", derive(serde::Serialize, serde::Deserialize))]
#[non_exhaustive]
pub struct Snapshot {
    /// The parameters the surface was built with (acceleration as currently set).
    pub params: Params,
    /// Steps taken.
    pub steps: u64,
    /// Model time simulated ([`Surface::model_time`]; [`Surface::time`] is it in seconds).
    /// (Serialised data of earlier versions, whose bodies, gravity and acceleration were in
    /// model time, has `time` instead and is refused rather than read in the wrong units.)
    pub model_time: f64,
    // Derived state the surface keeps beside the arrays, private so that it cannot be set
    // against them (the binary format and serde carry it; loading checks it).
    /// Smallest node mass ever set: with `max_stiffness` it sets `critical_dt`.
    pub(crate) min_mass: f32,
    /// Largest spring stiffness ever set.
    pub(crate) max_stiffness: f32,
    /// Largest viscosity ever set.
    pub(crate) max_viscosity: f32,
    /// Whether `forces` is applied by the next step.
    pub(crate) forces_pending: bool,
    /// Positions `[x, y, z]`.
    pub positions: [Vec<f32>; 3],
    /// Velocities `[vx, vy, vz]`, the lattice's: world units per unit of model time
    /// ([`Surface::velocities`]).
    pub velocities: [Vec<f32>; 3],
    /// External forces for the next step `[fx, fy, fz]`, in the lattice's force units
    /// ([`Surface::forces`]).
    pub forces: [Vec<f32>; 3],
    /// Node masses.
    pub mass: Vec<f32>,
    /// Node viscosities.
    pub viscosity: Vec<f32>,
    /// Pinned flags.
    pub pinned: Vec<bool>,
    /// Rest lengths per family (E, S, SE, SW), indexed by origin node.
    pub rest: [Vec<f32>; 4],
    /// Spring stiffness `c` per family (E, S, SE, SW), indexed by origin node (the
    /// [`Spring::stiffness`](crate::Spring::stiffness) of each spring).
    #[cfg_attr(feature = "serde", serde(alias = "coef"))]
    pub stiffness: [Vec<f32>; 4],
    /// Floating bodies with their ids, ids increasing; their state in seconds, as
    /// [`Surface::floater`] reads it.
    #[cfg_attr(feature = "serde", serde(default))]
    pub floaters: Vec<(FloaterId, Floater)>,
    /// The id the next added body gets (above every id in `floaters`).
    #[cfg_attr(feature = "serde", serde(default))]
    pub(crate) next_floater_id: u64,
    /// Gravity (per second²) and water density for the bodies.
    #[cfg_attr(feature = "serde", serde(default))]
    pub buoyancy: Buoyancy,
    /// Whole cells the window has travelled, `[cols, rows]` ([`Surface::origin_cells`]).
    #[cfg_attr(feature = "serde", serde(default))]
    pub origin_cells: [i64; 2],
    /// Model time [`Surface::advance`] owes and has not stepped (the fixed-step clock's
    /// accumulator: a fraction of a step, more while [`Overflow::Carry`] catches up).
    #[cfg_attr(feature = "serde", serde(default))]
    pub owed_time: f64,
    /// Most steps one [`Surface::advance`] takes, and what happens past it
    /// ([`Surface::set_step_cap`]).
    #[cfg_attr(feature = "serde", serde(default = "default_step_cap"))]
    pub step_cap: (u32, Overflow),
    /// Seconds of the game's clock the cap has dropped so far.
    #[cfg_attr(feature = "serde", serde(default))]
    pub dropped_seconds: f64,
    /// The water column under the bodies: the nodes that carry or await a load, sorted
    /// by node (see the `column` module of the bodies' subsystem).
    #[cfg_attr(feature = "serde", serde(default))]
    pub(crate) column: Vec<Entry>,
}

#[cfg(feature = "serde")]
fn default_step_cap() -> (u32, Overflow) {
    (Surface::DEFAULT_MAX_STEPS, Overflow::Drop)
}

/// The absorbing frame's width as stored (0 for the other boundaries), if it fits a `u32`.
fn frame_width(boundary: Boundary) -> Option<u32> {
    match boundary {
        Boundary::Absorbing { width } => u32::try_from(width).ok(),
        _ => Some(0),
    }
}

/// The model's six `f32` parameters in the format's order (offsets 40 to 64).
fn model(p: &Params) -> [f32; 6] {
    [
        p.spacing,
        p.mass,
        p.stiffness,
        p.viscosity,
        p.dt,
        p.rest_ratio,
    ]
}

/// Every field of a snapshot but the arrays and the bodies.
#[derive(Debug, Clone, Copy)]
pub(crate) struct Scalars {
    pub params: Params,
    pub steps: u64,
    pub model_time: f64,
    /// `[min_mass, max_stiffness, max_viscosity]`.
    pub bounds: [f32; 3],
    pub forces_pending: bool,
    pub next_floater_id: u64,
    pub buoyancy: Buoyancy,
    pub origin_cells: [i64; 2],
    pub owed_time: f64,
    pub step_cap: (u32, Overflow),
    pub dropped_seconds: f64,
}

impl Snapshot {
    /// The first eight bytes of every binary snapshot.
    pub const MAGIC: [u8; 8] = MAGIC;
    /// The binary format version this build writes. It reads this one and versions 1 to 6
    /// (version 1 had no `time_scale`, version 3 no window origin: such snapshots get the
    /// default and `[0, 0]`; versions up to 4 kept bodies and accelerations in model time,
    /// converted to seconds on loading; bodies of versions up to 5 did not rotate and load
    /// upright and not spinning; versions up to 6 had no water column and load with an
    /// empty one).
    pub const VERSION: u32 = VERSION;

    /// Encodes the snapshot in the binary format of the module docs.
    ///
    /// Only the array lengths are checked here (every array must hold `cols × rows`
    /// values, or the bytes would not say what the arrays hold); the contents are
    /// validated when the bytes are loaded. [`Surface::to_bytes`] cannot fail.
    pub fn to_bytes(&self) -> Result<Vec<u8>> {
        let n = self.params.cols.checked_mul(self.params.rows);
        let arrays = self
            .positions
            .iter()
            .chain(&self.velocities)
            .chain(&self.forces);
        let arrays = arrays
            .chain([&self.mass, &self.viscosity])
            .chain(&self.rest)
            .chain(&self.stiffness);
        let mut lengths = arrays.map(Vec::len).chain([self.pinned.len()]);
        match n {
            Some(n)
                if lengths.all(|len| len == n)
                    && u32::try_from(self.floaters.len()).is_ok()
                    && frame_width(self.params.boundary).is_some() =>
            {
                Ok(self.encode())
            }
            _ => Err(bad(format!(
                "cannot encode: the arrays do not all hold one value per node of a {}x{} grid, or the frame width or floater count does not fit 32 bits",
                self.params.cols, self.params.rows
            ))),
        }
    }

    /// [`Snapshot::to_bytes`] for a snapshot whose arrays are known to be consistent.
    pub(crate) fn encode(&self) -> Vec<u8> {
        let mut bytes = Vec::new();
        encode_into(&self.fields(), &mut bytes);
        bytes
    }

    /// Decodes a snapshot from exactly `bytes` (no trailing data), checking the magic, the
    /// version, the lengths and the checksum. The contents are validated when the snapshot
    /// becomes a surface ([`Surface::from_snapshot`]).
    pub fn from_bytes(bytes: &[u8]) -> Result<Self> {
        let (version, r) = read::framing(bytes)?;
        versions::decode(version, r)
    }

    /// Widens the derived state to what the arrays hold: the mass, stiffness and viscosity
    /// bounds to cover every node and spring, forces pending when any is stored, the next
    /// floater id above every body's. (Non-finite values are left for validation.)
    fn cover_the_arrays(&mut self) {
        self.min_mass = self.mass.iter().fold(self.min_mass, |a, &m| a.min(m));
        self.max_viscosity = self
            .viscosity
            .iter()
            .fold(self.max_viscosity, |a, &g| a.max(g));
        self.max_stiffness = self
            .stiffness
            .iter()
            .flatten()
            .fold(self.max_stiffness, |a, &c| a.max(c));
        self.forces_pending |= self.forces.iter().flatten().any(|f| f.to_bits() != 0);
        if let Some(last) = self.floaters.iter().map(|(id, _)| id.0).max() {
            self.next_floater_id = self.next_floater_id.max(last.saturating_add(1));
        }
    }

    /// Checks every invariant a surface relies on. See [`Surface::from_snapshot`].
    pub fn validate(&self) -> Result<()> {
        let scalars = self.scalars();
        Contents {
            scalars: &scalars,
            positions: slices(&self.positions),
            velocities: slices(&self.velocities),
            forces: slices(&self.forces),
            mass: &self.mass[..],
            viscosity: &self.viscosity[..],
            pinned: &self.pinned[..],
            rest: std::array::from_fn(|f| &self.rest[f][..]),
            stiffness: std::array::from_fn(|f| &self.stiffness[f][..]),
            bodies: &self.floaters,
            column: &self.column,
        }
        .validate()
    }

    /// Every field but the arrays and the bodies.
    fn scalars(&self) -> Scalars {
        Scalars {
            params: self.params,
            steps: self.steps,
            model_time: self.model_time,
            bounds: [self.min_mass, self.max_stiffness, self.max_viscosity],
            forces_pending: self.forces_pending,
            next_floater_id: self.next_floater_id,
            buoyancy: self.buoyancy,
            origin_cells: self.origin_cells,
            owed_time: self.owed_time,
            step_cap: self.step_cap,
            dropped_seconds: self.dropped_seconds,
        }
    }
}

/// Clears `out` and fills it with the binary format of `fields`, checksum included,
/// reserving the whole length first (so a buffer large enough is not reallocated).
fn encode_into(fields: &stream::Fields<'_>, out: &mut Vec<u8>) {
    out.clear();
    out.reserve(fields.encoded_len());
    let mut bytes = Bytes {
        out,
        crc: crc::Hasher::new(),
    };
    fields.encode(&mut bytes);
    let crc = bytes.crc.finalize();
    out.extend_from_slice(&crc.to_le_bytes());
    debug_assert_eq!(out.len(), fields.encoded_len());
}

impl Surface {
    /// The complete state as plain data: what [`Surface::to_bytes`] stores, decoded.
    pub fn snapshot(&self) -> Snapshot {
        Snapshot::from_bytes(&self.to_bytes()).expect("a surface's own bytes decode")
    }

    /// A surface from a snapshot, after checking every invariant the engine relies on
    /// (see the [`Snapshot`] docs). Errors are [`Error::Snapshot`].
    ///
    /// The snapshot's public arrays may have been edited: its private derived state (the
    /// bounds behind `critical_dt`, whether forces are pending, the next floater id) is
    /// first widened to cover them, so an edit is judged on its values (a lighter node
    /// must still leave the timestep below the critical one) rather than refused for
    /// disagreeing with state the caller cannot set. The binary format is checked as
    /// stored ([`Surface::from_bytes`]).
    pub fn from_snapshot(mut snap: Snapshot) -> Result<Surface> {
        snap.cover_the_arrays();
        Surface::from_checked(snap)
    }

    /// [`Surface::from_snapshot`] without widening the derived state.
    fn from_checked(snap: Snapshot) -> Result<Surface> {
        snap.validate()?;
        let p = snap.params;
        let n = p.cols * p.rows;
        let mut state = State::new(&p);
        let fill3 = |dst: &mut [Floats; 3], src: &[Vec<f32>; 3]| {
            for (d, s) in dst.iter_mut().zip(src) {
                d[..n].copy_from_slice(s);
            }
        };
        fill3(&mut state.pos, &snap.positions);
        fill3(&mut state.next_pos, &snap.positions);
        fill3(&mut state.vel, &snap.velocities);
        state
            .ext
            .load(snap.forces_pending, |ext| fill3(ext, &snap.forces));
        // Arrays that hold the defaults load as the defaults' few rows (see `NodeTable`).
        state.mass.assign(|i| snap.mass[i]);
        state.viscosity.assign(|i| snap.viscosity[i]);
        state.pinned.copy_from_slice(&snap.pinned);
        state.refresh_inv_mass();
        // The engine reads a family's shared (c, L0) while all its springs agree: derived
        // from the tables, so recomputed rather than stored (and no tables kept then).
        let springs = Springs::from_tables(
            Grid::new(p.cols, p.rows),
            std::array::from_fn(|f| snap.rest[f].as_slice()),
            std::array::from_fn(|f| snap.stiffness[f].as_slice()),
        );
        let scalars = snap.scalars();
        let mut surface = Surface::from_parts(p, state, springs, scalars.bounds, (0, 0.0));
        surface.take_scalars(&scalars);
        let (next_id, buoyancy) = (snap.next_floater_id, snap.buoyancy);
        let spacing = surface.params.spacing;
        surface
            .bodies
            .load(snap.floaters, next_id, buoyancy, snap.column, spacing)?;
        Ok(surface)
    }

    /// Takes every field of a snapshot but the arrays and the bodies.
    fn take_scalars(&mut self, s: &Scalars) {
        self.params = s.params;
        self.steps = s.steps;
        self.time = s.model_time;
        self.lattice.stability = Stability::from_bounds(s.bounds);
        self.bodies.set_world(s.next_floater_id, s.buoyancy);
        // Per-node values may differ from their places' defaults (see `window`).
        self.window.load(s.origin_cells);
        self.clock.owed = s.owed_time;
        (self.clock.max_steps, self.clock.overflow) = s.step_cap;
        self.clock.dropped = s.dropped_seconds;
    }

    /// The snapshot in the binary format of the [`Snapshot`] docs, in a new vector
    /// ([`Surface::save_into`] reuses one).
    pub fn to_bytes(&self) -> Vec<u8> {
        let mut bytes = Vec::new();
        self.save_into(&mut bytes);
        bytes
    }

    /// Clears `out` and fills it with [`Surface::to_bytes`]: the binary format of the
    /// [`Snapshot`] docs, version and checksum included, read straight from the surface's
    /// buffers. `out` keeps its capacity: once it has held a save of this surface, saving
    /// again allocates nothing. For rollback, with [`Surface::restore`]:
    ///
    /// ```
    /// use springwater::{Params, Surface};
    ///
    /// let mut water = Surface::new(Params::with_size(64, 64))?;
    /// let mut saved = Vec::new();
    /// water.save_into(&mut saved);               // frame 0
    /// water.drop_at(32.0, 32.0, 1.0, 3.0)?;      // an input that arrived late…
    /// water.advance(1.0 / 60.0)?;
    /// let hash = water.state_hash();
    /// water.restore(&saved)?;                    // …roll back and simulate again
    /// water.drop_at(32.0, 32.0, 1.0, 3.0)?;
    /// water.advance(1.0 / 60.0)?;
    /// assert_eq!(water.state_hash(), hash);
    /// # Ok::<(), springwater::Error>(())
    /// ```
    ///
    /// The checksum costs a fraction of the copy (`docs/performance.md`), so rollback
    /// buffers and files share one format: a save from memory can be written to disk or
    /// sent to a peer that joins, and [`Surface::restore`] refuses one that was damaged.
    pub fn save_into(&self, out: &mut Vec<u8>) {
        encode_into(&self.fields(), out);
    }

    /// A 64-bit hash of everything that decides the surface's future: positions,
    /// velocities, pending forces, per-node masses, viscosities and pins, the springs, the
    /// bodies (shape and hull mesh, mass and inertia, pose, velocity and angular velocity,
    /// pushes and their torques, the water's last force and torque), the parameters and
    /// the acceleration, the bounds behind
    /// [`Surface::critical_dt`], the window's origin and the clock's carried time and cap;
    /// not the counters that only report (steps taken, [`Surface::time`],
    /// [`Surface::dropped_seconds`]), nor how the surface is stored or run (capacities,
    /// padding, caches, whether bodies with one hull mesh share its `Arc`, the thread
    /// pool, the SIMD level).
    ///
    /// Equal states hash equal on every SIMD level, thread count and platform, so peers of
    /// a multiplayer game compare hashes to detect a desync. The hash is XXH3-64 (the
    /// `xxhash-rust` crate: pure Rust, the same output on every platform) over the fields
    /// [`Surface::to_bytes`] saves, less the framing (magic, version, length, checksum)
    /// and the three counters: not cryptographic, and it needs not be (peers look for
    /// their own bugs, not an attacker's); two different states collide with odds about
    /// 2⁻⁶⁴, so a game comparing one hash a frame at 60 Hz for a year misses a desync with
    /// odds around 10⁻¹⁰; and it costs about two steps of the engine on two threads
    /// (`docs/performance.md`). The hash is that of this crate version's format: peers must
    /// run the same version.
    ///
    /// The counters are left out because nothing in the step reads them: two peers whose
    /// water is the same hash the same even if one of them loaded its state from a save
    /// with other counters. The clock's carried time, which decides when the next step
    /// falls, is in.
    pub fn state_hash(&self) -> u64 {
        let mut hash = StateHash(xxhash_rust::xxh3::Xxh3::new());
        self.fields().encode(&mut hash);
        hash.0.digest()
    }

    /// Writes [`Surface::to_bytes`] to `w`.
    pub fn save(&self, mut w: impl Write) -> Result<()> {
        w.write_all(&self.to_bytes())
            .and_then(|()| w.flush())
            .map_err(|e| Error::Io {
                action: "write",
                source: e.into(),
            })
    }

    /// A surface from a binary snapshot: exactly the bytes [`Surface::to_bytes`] wrote.
    pub fn from_bytes(bytes: &[u8]) -> Result<Surface> {
        Surface::from_checked(Snapshot::from_bytes(bytes)?)
    }

    /// Reads one snapshot from `r` (exactly its bytes; data after it stays unread).
    ///
    /// Reading grows the buffer as bytes arrive, so a header announcing a huge grid over a
    /// short stream fails with "truncated" instead of allocating.
    pub fn load(mut r: impl Read) -> Result<Surface> {
        let io = |e: std::io::Error| Error::Io {
            action: "read",
            source: e.into(),
        };
        let mut bytes = Vec::with_capacity(HEADER);
        // Reads on up to `len` bytes in all.
        let mut upto = |bytes: &mut Vec<u8>, len: usize| {
            let more = len.saturating_sub(bytes.len()) as u64;
            (&mut r).take(more).read_to_end(bytes).map_err(io)
        };
        // Every version's header is at least as long as versions 1 and 2's.
        upto(&mut bytes, HEADER_V2)?;
        let version = bytes
            .get(8..12)
            .map_or(0, |v| u32::from_le_bytes(v.try_into().expect("4 bytes")));
        upto(&mut bytes, read::header_len(version))?;
        let total = read::check_header(&bytes)?;
        upto(&mut bytes, total)?;
        Surface::from_bytes(&bytes)
    }

    /// Replaces this surface's state with a binary snapshot (exactly its bytes, as
    /// [`Surface::from_bytes`] reads them). On error `self` is unchanged.
    ///
    /// A snapshot of this format version for a surface of the same size and model (the
    /// parameters but the acceleration) is checked where it lies and copied into the
    /// surface's buffers: nothing is allocated (a per-node table, a spring table or a
    /// body list the surface has never needed may be allocated once). A stored hull mesh
    /// with the bits of one the surface's bodies hold is that body's `Arc`, neither
    /// validated nor allocated again; another is validated and allocated. Any other snapshot
    /// replaces the surface as [`Surface::from_bytes`] would. Either way, where and how
    /// the engine runs (the host's threads, the SIMD level) are settings of this surface,
    /// not state: they stay.
    pub fn restore(&mut self, bytes: &[u8]) -> Result<()> {
        if self.restore_in_place(bytes)? {
            return Ok(());
        }
        let restored = Surface::from_bytes(bytes)?;
        let (host, simd) = (self.host.take(), self.simd);
        *self = restored;
        self.host = host;
        self.simd = simd;
        Ok(())
    }
}
