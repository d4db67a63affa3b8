//! Snapshots: the complete state of a [`Surface`] saved and restored bitwise (the format
//! is documented on [`Snapshot`]).

use super::{Overflow, Surface};
use crate::error::{Error, Result};
use crate::floater::{Buoyancy, Floater, FloaterId, Shape};
use crate::grid::{Family, Grid};
use crate::params::{self, Boundary, Params, MAX_NODES};
use crate::simd::Floats;
use crate::springs::Springs;
use crate::state::State;
use std::io::{Read, Write};

/// The first eight bytes of every snapshot.
pub(crate) const MAGIC: [u8; 8] = *b"SPRWATER";
/// The format version this build writes. It reads versions 1 to 5 (see [`Snapshot`]).
pub(crate) const VERSION: u32 = 5;
/// Bytes before the per-node arrays in versions 1 and 2.
const HEADER_V2: usize = 112;
/// Bytes before the per-node arrays.
const HEADER: usize = 136;
/// Bytes per floating body.
const PER_FLOATER: usize = 80;
/// Bytes per node: 11 `f32` arrays, 1 `u8`, 8 `f32` spring arrays.
const PER_NODE: usize = 11 * 4 + 1 + 8 * 4;
/// Trailing checksum.
const CRC: usize = 4;
/// From version 4, before the checksum: the window's origin in cells (two `i64`) and the
/// clock of `advance` (owed model time `f64`, step cap `u32`, overflow `u32`, dropped
/// seconds `f64`).
const ORIGIN: usize = 16 + 24;
const FLAG_FORCES_PENDING: u32 = 1;

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
/// # Format (version 5)
///
/// Little-endian throughout; `n = cols × rows`, `f` floating bodies. Per-node arrays hold
/// exactly `n` values (no SIMD padding); spring tables are indexed by origin node, with
/// `0.0` for springs that do not exist (E from the last column, S from the last row, …).
///
/// | offset | size | field |
/// |---|---|---|
/// | 0 | 8 | magic `b"SPRWATER"` |
/// | 8 | 4 | format version `u32` (5; versions 1 to 4 are read too) |
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
/// | 136 | 9 × 4n | positions x, y, z; velocities x, y, z; pending forces x, y, z (the lattice's units, model time) |
/// | | 2 × 4n | mass, viscosity per node |
/// | | n | pinned per node, `u8` 0 or 1 |
/// | | 8 × 4n | rest length then stiffness, for families E, S, SE, SW |
/// | | 80 f | per body: id `u64`, shape `u32` (0 = sphere, 1 = box), size (radius, 0, 0 or half extents), mass, drag (per second), position, velocity (per second), push, water force (mass × world units per second²) (`f32`) |
/// | end − 44 | 2 × 8 | the window's origin in cells, columns then rows (`i64`, [`Surface::origin_cells`]) |
/// | end − 28 | 8 | model time [`Surface::advance`] owes and has not stepped (`f64`) |
/// | end − 20 | 4, 4 | the step cap `u32` and what happens past it `u32`: 0 = drop, 1 = carry ([`Surface::set_step_cap`]) |
/// | end − 12 | 8 | seconds the cap has dropped so far (`f64`) |
/// | end − 4 | 4 | CRC-32 (IEEE) of every byte before it |
///
/// The total is `180 + 77 n + 80 f` bytes. Version 4 has the same layout with the
/// acceleration, gravity and bodies in model time (velocities per unit of model time,
/// drag per unit, accelerations and forces per unit²): loading converts them to seconds
/// with the stored `time_scale` (the acceleration to the per-second² value that converts
/// back to the stored bits where one exists, as for zero and about 9 in 10 other values,
/// else one rounding off; water without bodies then continues bit for bit, bodies to
/// rounding). Version 3 has no origin and no clock either (read as
/// `[0, 0]`, a window that never moved, and a fresh clock). Versions 1 and 2 end the header at offset 112
/// (no bodies, no absorbing boundary; version 1 has no `time_scale` either: such
/// snapshots get the default). Loading refuses, with [`Error::Snapshot`] and a message
/// that says what is wrong: a wrong magic or version, a total length that disagrees with
/// `cols × rows` or with the bytes present, a checksum mismatch, parameters that
/// [`Params::validate`] refuses, non-finite values, masses or stiffnesses out of range,
/// pinned nodes that move, springs outside the grid, bounds that do not cover the
/// tables, and bodies that [`Floater::validate`] refuses or whose ids are not increasing. Lengths are checked against the bytes actually present before anything is
/// allocated, so a lying length field costs nothing. A refused snapshot changes nothing.
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

/// Snapshot size in bytes for `nodes` nodes and `floaters` bodies in a format version's
/// layout, or `None` on overflow.
fn encoded_len(version: u32, nodes: usize, floaters: usize) -> Option<usize> {
    let header = if version < 3 { HEADER_V2 } else { HEADER };
    let origin = if version < 4 { 0 } else { ORIGIN };
    nodes
        .checked_mul(PER_NODE)?
        .checked_add(floaters.checked_mul(PER_FLOATER)?)?
        .checked_add(header + origin + CRC)
}

fn bad(msg: impl Into<String>) -> Error {
    Error::Snapshot(msg.into())
}

impl Snapshot {
    /// The first eight bytes of every binary snapshot.
    pub const MAGIC: [u8; 8] = MAGIC;
    /// The binary format version this build writes. It reads this one and versions 1 to 4
    /// (version 1 had no `time_scale`, version 3 no window origin: such snapshots get the
    /// default and `[0, 0]`; versions up to 4 kept bodies and accelerations in model time,
    /// converted to seconds on loading).
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
        let n = self.mass.len();
        let total = encoded_len(VERSION, n, self.floaters.len())
            .expect("a snapshot of an allocated surface fits in memory");
        let mut b = Vec::with_capacity(total);
        let p = &self.params;
        b.extend_from_slice(&MAGIC);
        b.extend_from_slice(&VERSION.to_le_bytes());
        let flags = if self.forces_pending {
            FLAG_FORCES_PENDING
        } else {
            0
        };
        b.extend_from_slice(&flags.to_le_bytes());
        b.extend_from_slice(&(total as u64).to_le_bytes());
        b.extend_from_slice(&(p.cols as u64).to_le_bytes());
        b.extend_from_slice(&(p.rows as u64).to_le_bytes());
        for v in [
            p.spacing,
            p.mass,
            p.stiffness,
            p.viscosity,
            p.dt,
            p.rest_ratio,
        ] {
            b.extend_from_slice(&v.to_le_bytes());
        }
        let boundary: u32 = match p.boundary {
            Boundary::Pinned => 0,
            Boundary::Free => 1,
            Boundary::Absorbing { .. } => 2,
        };
        b.extend_from_slice(&boundary.to_le_bytes());
        for v in p.acceleration {
            b.extend_from_slice(&v.to_le_bytes());
        }
        b.extend_from_slice(&self.steps.to_le_bytes());
        b.extend_from_slice(&self.model_time.to_le_bytes());
        b.extend_from_slice(&self.min_mass.to_le_bytes());
        b.extend_from_slice(&self.max_stiffness.to_le_bytes());
        b.extend_from_slice(&self.max_viscosity.to_le_bytes());
        b.extend_from_slice(&p.time_scale.to_le_bytes());
        let width = frame_width(p.boundary).expect("checked by to_bytes or by validation");
        b.extend_from_slice(&width.to_le_bytes());
        b.extend_from_slice(&(self.floaters.len() as u32).to_le_bytes());
        b.extend_from_slice(&self.next_floater_id.to_le_bytes());
        b.extend_from_slice(&self.buoyancy.gravity.to_le_bytes());
        b.extend_from_slice(&self.buoyancy.density.to_le_bytes());
        debug_assert_eq!(b.len(), HEADER);
        let arrays = self
            .positions
            .iter()
            .chain(&self.velocities)
            .chain(&self.forces);
        for a in arrays.chain([&self.mass, &self.viscosity]) {
            a.iter().for_each(|v| b.extend_from_slice(&v.to_le_bytes()));
        }
        b.extend(self.pinned.iter().map(|&p| p as u8));
        for f in 0..4 {
            for a in [&self.rest[f], &self.stiffness[f]] {
                a.iter().for_each(|v| b.extend_from_slice(&v.to_le_bytes()));
            }
        }
        for (id, body) in &self.floaters {
            b.extend_from_slice(&id.0.to_le_bytes());
            let (shape, size): (u32, [f32; 3]) = match body.shape {
                Shape::Sphere { radius } => (0, [radius, 0.0, 0.0]),
                Shape::Box { half_extents } => (1, half_extents.to_array()),
            };
            b.extend_from_slice(&shape.to_le_bytes());
            let vectors = [body.position, body.velocity, body.push, body.water_force];
            let floats = size
                .into_iter()
                .chain([body.mass, body.drag])
                .chain(vectors.iter().flat_map(|v| v.to_array()));
            floats.for_each(|v| b.extend_from_slice(&v.to_le_bytes()));
        }
        for c in self.origin_cells {
            b.extend_from_slice(&c.to_le_bytes());
        }
        b.extend_from_slice(&self.owed_time.to_le_bytes());
        b.extend_from_slice(&self.step_cap.0.to_le_bytes());
        let overflow: u32 = match self.step_cap.1 {
            Overflow::Drop => 0,
            Overflow::Carry => 1,
        };
        b.extend_from_slice(&overflow.to_le_bytes());
        b.extend_from_slice(&self.dropped_seconds.to_le_bytes());
        let crc = crc32fast::hash(&b);
        b.extend_from_slice(&crc.to_le_bytes());
        b
    }

    /// Decodes a snapshot from exactly `bytes` (no trailing data), checking the magic, the
    /// version, the lengths and the checksum. The contents are validated when the snapshot
    /// becomes a surface ([`Surface::from_snapshot`]).
    pub fn from_bytes(bytes: &[u8]) -> Result<Self> {
        let total = check_header(bytes)?;
        if bytes.len() != total {
            return Err(bad(format!(
                "the header says {total} bytes but {} are present ({})",
                bytes.len(),
                if bytes.len() < total {
                    "truncated"
                } else {
                    "trailing data"
                }
            )));
        }
        let (body, crc) = bytes.split_at(total - CRC);
        let stored = u32::from_le_bytes(crc.try_into().expect("4 bytes"));
        let actual = crc32fast::hash(body);
        if stored != actual {
            return Err(bad(format!(
                "checksum mismatch (stored {stored:08x}, computed {actual:08x}): the data is corrupted"
            )));
        }
        let mut r = Cursor { bytes: body, at: 8 };
        let version = r.u32();
        let flags = r.u32();
        let _total = r.u64();
        let cols = r.u64() as usize;
        let rows = r.u64() as usize;
        let [spacing, mass, stiffness, viscosity, dt, rest_ratio] = [(); 6].map(|_| r.f32());
        let boundary_code = r.u32();
        let acceleration = [(); 3].map(|_| r.f32());
        let params = Params {
            cols,
            rows,
            spacing,
            mass,
            stiffness,
            viscosity,
            dt,
            rest_ratio,
            boundary: Boundary::Pinned,
            acceleration,
            time_scale: Params::default().time_scale,
        };
        let steps = r.u64();
        let time = r.f64();
        let min_mass = r.f32();
        let max_stiffness = r.f32();
        let max_viscosity = r.f32();
        let time_scale = r.f32();
        let (width, floater_count, next_floater_id, buoyancy) = if version < 3 {
            (0, 0, 0, Buoyancy::default())
        } else {
            let (width, count, next) = (r.u32(), r.u32(), r.u64());
            let gravity = r.f32();
            let density = r.f32();
            (width, count, next, Buoyancy { gravity, density })
        };
        let boundary = match (boundary_code, width) {
            (0, 0) => Boundary::Pinned,
            (1, 0) => Boundary::Free,
            (2, width) if version >= 3 => Boundary::Absorbing {
                width: width as usize,
            },
            (0 | 1, width) => {
                return Err(bad(format!(
                    "a frame width of {width} is stored for a boundary without one"
                )))
            }
            (other, _) => {
                return Err(bad(format!(
                    "unknown boundary code {other} (0 = pinned, 1 = free, 2 = absorbing from version 3)"
                )))
            }
        };
        let params = Params { boundary, ..params };
        if flags & !FLAG_FORCES_PENDING != 0 {
            return Err(bad(format!(
                "unknown flags {flags:#x}: written by an incompatible writer"
            )));
        }
        let params = match version {
            1 if time_scale.to_bits() != 0 => {
                return Err(bad(
                    "the reserved header field of a version 1 snapshot is not 0: written by an incompatible writer",
                ))
            }
            1 => params,
            _ => Params { time_scale, ..params },
        };
        let n = cols * rows; // bounded by check_header
        let mut f32s = || r.f32s(n);
        let positions = [f32s(), f32s(), f32s()];
        let velocities = [f32s(), f32s(), f32s()];
        let forces = [f32s(), f32s(), f32s()];
        let mass_n = f32s();
        let viscosity_n = f32s();
        let pinned = r.take(n).to_vec();
        if let Some(i) = pinned.iter().position(|&b| b > 1) {
            return Err(bad(format!(
                "node {i}: pinned flag {} is neither 0 nor 1",
                pinned[i]
            )));
        }
        let pinned = pinned.into_iter().map(|b| b == 1).collect();
        let mut rest: [Vec<f32>; 4] = Default::default();
        let mut stiffness: [Vec<f32>; 4] = Default::default();
        for f in 0..4 {
            rest[f] = r.f32s(n);
            stiffness[f] = r.f32s(n);
        }
        let mut floaters = Vec::with_capacity(floater_count as usize);
        for _ in 0..floater_count {
            let id = FloaterId(r.u64());
            let shape = r.u32();
            let [a, b, c, mass, drag] = [(); 5].map(|_| r.f32());
            let mut vector = || glam::Vec3::from_array([(); 3].map(|_| r.f32()));
            let (position, velocity, push, water_force) = (vector(), vector(), vector(), vector());
            let shape = match (shape, b.to_bits(), c.to_bits()) {
                (0, 0, 0) => Shape::Sphere { radius: a },
                (1, ..) => Shape::Box {
                    half_extents: glam::Vec3::new(a, b, c),
                },
                (0, ..) => {
                    return Err(bad(format!(
                        "floater {}: a sphere with size fields other than (radius, 0, 0)",
                        id.0
                    )))
                }
                (other, ..) => {
                    return Err(bad(format!(
                        "floater {}: unknown shape code {other} (0 = sphere, 1 = box)",
                        id.0
                    )))
                }
            };
            floaters.push((
                id,
                Floater {
                    shape,
                    mass,
                    drag,
                    position,
                    velocity,
                    push,
                    water_force,
                },
            ));
        }
        let (origin_cells, owed_time, step_cap, dropped_seconds) = if version < 4 {
            let fresh = (Surface::DEFAULT_MAX_STEPS, Overflow::Drop);
            ([0, 0], 0.0, fresh, 0.0)
        } else {
            let origin = [(); 2].map(|_| r.u64() as i64);
            let (owed, max_steps) = (r.f64(), r.u32());
            let overflow = match r.u32() {
                0 => Overflow::Drop,
                1 => Overflow::Carry,
                other => return Err(bad(format!("step cap overflow {other} is not 0 or 1"))),
            };
            (origin, owed, (max_steps, overflow), r.f64())
        };
        debug_assert_eq!(r.at, body.len());
        let (params, floaters, buoyancy) = if version < 5 {
            in_seconds(params, floaters, buoyancy)
        } else {
            (params, floaters, buoyancy)
        };
        Ok(Self {
            params,
            steps,
            model_time: time,
            min_mass,
            max_stiffness,
            max_viscosity,
            forces_pending: flags & FLAG_FORCES_PENDING != 0,
            positions,
            velocities,
            forces,
            mass: mass_n,
            viscosity: viscosity_n,
            pinned,
            rest,
            stiffness,
            floaters,
            next_floater_id,
            buoyancy,
            origin_cells,
            owed_time,
            step_cap,
            dropped_seconds,
        })
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
        let p = &self.params;
        p.validate_except_dt()
            .map_err(|e| bad(format!("parameters: {e}")))?;
        let grid = Grid::new(p.cols, p.rows);
        let n = grid.node_count();
        let arrays = self
            .positions
            .iter()
            .chain(&self.velocities)
            .chain(&self.forces);
        let named = ["x", "y", "z", "vx", "vy", "vz", "fx", "fy", "fz"]
            .into_iter()
            .zip(arrays);
        for (what, a) in named.chain([("mass", &self.mass), ("viscosity", &self.viscosity)]) {
            if a.len() != n {
                return Err(bad(format!(
                    "{what} has {} values for a {}x{} grid",
                    a.len(),
                    p.cols,
                    p.rows
                )));
            }
            if let Some(i) = a.iter().position(|v| !v.is_finite()) {
                return Err(bad(format!(
                    "{what} of node {i} is {}, not a finite number",
                    a[i]
                )));
            }
        }
        if self.pinned.len() != n {
            return Err(bad(format!(
                "pinned has {} flags for {n} nodes",
                self.pinned.len()
            )));
        }
        for f in 0..4 {
            for (what, a) in [
                ("rest length", &self.rest[f]),
                ("stiffness", &self.stiffness[f]),
            ] {
                if a.len() != n {
                    return Err(bad(format!(
                        "{what} table {f} has {} values for {n} nodes",
                        a.len()
                    )));
                }
            }
        }
        if !self.forces_pending && self.forces.iter().flatten().any(|f| f.to_bits() != 0) {
            return Err(bad(
                "external forces are stored but not marked pending (flag bit 0)",
            ));
        }
        if !(self.model_time.is_finite() && self.model_time >= 0.0) {
            return Err(bad(format!(
                "model time {} is not a finite number >= 0",
                self.model_time
            )));
        }
        params::positive("min_mass", self.min_mass).map_err(|e| bad(e.to_string()))?;
        params::positive("max_stiffness", self.max_stiffness).map_err(|e| bad(e.to_string()))?;
        params::non_negative("max_viscosity", self.max_viscosity)
            .map_err(|e| bad(e.to_string()))?;
        for i in 0..n {
            let m = self.mass[i];
            if m < self.min_mass || !(1.0 / m).is_finite() {
                return Err(bad(format!(
                    "mass {m} of node {i} is below min_mass {} or too small to invert",
                    self.min_mass
                )));
            }
            let g = self.viscosity[i];
            if !(0.0..=self.max_viscosity).contains(&g) {
                return Err(bad(format!(
                    "viscosity {g} of node {i} is negative or above max_viscosity {}",
                    self.max_viscosity
                )));
            }
            if self.pinned[i] && self.velocities.iter().any(|v| v[i] != 0.0) {
                return Err(bad(format!("node {i} is pinned but has a velocity")));
            }
        }
        for (f, family) in crate::grid::Family::ALL.into_iter().enumerate() {
            for i in 0..n {
                let (rest, c) = (self.rest[f][i], self.stiffness[f][i]);
                if grid.spring_end(family, i).is_none() {
                    if rest.to_bits() != 0 || c.to_bits() != 0 {
                        return Err(bad(format!(
                            "spring {family:?} at node {i} lies outside the grid but is not zero"
                        )));
                    }
                } else if !(rest.is_finite() && rest >= 0.0 && c.is_finite() && c > 0.0) {
                    return Err(bad(format!(
                        "spring {family:?} at node {i}: rest length {rest} and stiffness {c} must be finite, >= 0 and > 0"
                    )));
                } else if c > self.max_stiffness {
                    return Err(bad(format!(
                        "spring {family:?} at node {i}: stiffness {c} is above max_stiffness {}",
                        self.max_stiffness
                    )));
                }
            }
        }
        self.buoyancy
            .validate()
            .map_err(|e| bad(format!("buoyancy: {e}")))?;
        let mut previous = None;
        for (id, body) in &self.floaters {
            body.validate()
                .and_then(|()| crate::floater::check_footprint(&body.shape, p.spacing))
                .map_err(|e| bad(format!("floater {}: {e}", id.0)))?;
            if previous.is_some_and(|p| p >= id.0) || id.0 >= self.next_floater_id {
                // (So the next id is above 0 and every stored id below `u64::MAX`.)
                return Err(bad(format!(
                    "floater {}: ids must increase and stay below the next id {}",
                    id.0, self.next_floater_id
                )));
            }
            previous = Some(id.0);
        }
        let (max_steps, _) = self.step_cap;
        if max_steps == 0 || max_steps as usize > Surface::MAX_SUBSTEPS {
            return Err(bad(format!(
                "step cap {max_steps} is not from 1 to {}",
                Surface::MAX_SUBSTEPS
            )));
        }
        let dt = p.dt as f64;
        if !(self.owed_time.is_finite() && self.owed_time >= -dt) {
            return Err(bad(format!(
                "owed time {} is not finite and at least −dt",
                self.owed_time
            )));
        }
        if !(self.dropped_seconds.is_finite() && self.dropped_seconds >= 0.0) {
            return Err(bad(format!(
                "dropped seconds {} are not finite and at least 0",
                self.dropped_seconds
            )));
        }
        if let Some(&o) = self
            .origin_cells
            .iter()
            .find(|o| o.unsigned_abs() > super::MAX_ORIGIN_CELLS as u64)
        {
            return Err(bad(format!(
                "window origin {o} cells is past the limit of {} cells",
                super::MAX_ORIGIN_CELLS
            )));
        }
        let extra = if self.floaters.is_empty() {
            0.0
        } else {
            self.buoyancy.node_stiffness(p.spacing, p.time_scale)
        };
        let critical =
            params::critical_dt_with(self.min_mass, self.max_stiffness, self.max_viscosity, extra);
        params::check_dt(p.dt, critical).map_err(|e| bad(e.to_string()))
    }
}

/// The acceleration, buoyancy and bodies of a snapshot of version 4 or older, stored in
/// model time, converted to seconds with its time scale `s`: velocities and the drag rate
/// times `s`, accelerations and forces times `s²`.
fn in_seconds(
    params: Params,
    mut floaters: Vec<(FloaterId, Floater)>,
    buoyancy: Buoyancy,
) -> (Params, Vec<(FloaterId, Floater)>, Buoyancy) {
    let s = params.time_scale;
    let s2 = s * s;
    for (_, body) in &mut floaters {
        body.drag *= s;
        body.velocity *= s;
        body.push *= s2;
        body.water_force *= s2;
    }
    let params = Params {
        acceleration: params.acceleration.map(|a| per_second_squared(a, s2)),
        ..params
    };
    let buoyancy = Buoyancy {
        gravity: buoyancy.gravity * s2,
        ..buoyancy
    };
    (params, floaters, buoyancy)
}

/// The acceleration per second² that the step turns back into `model` (per unit of model
/// time²) bit for bit, `a / s2`: `model × s2`, or the `f32` next to it when the rounding
/// of the product would not convert back; `model × s2` when none does.
fn per_second_squared(model: f32, s2: f32) -> f32 {
    let a = model * s2;
    [a, a.next_up(), a.next_down()]
        .into_iter()
        .find(|c| (c / s2).to_bits() == model.to_bits())
        .unwrap_or(a)
}

/// Checks magic, version and lengths; returns the total length the header announces,
/// which is consistent with `cols × rows` and at most [`MAX_NODES`] nodes.
fn check_header(bytes: &[u8]) -> Result<usize> {
    if bytes.len() < 8 && MAGIC.starts_with(bytes) {
        return Err(bad(format!(
            "truncated: {} bytes, the header alone has {HEADER}",
            bytes.len()
        )));
    }
    if bytes.len() < 8 || bytes[..8] != MAGIC {
        return Err(bad("not a springwater snapshot (wrong magic bytes)"));
    }
    if bytes.len() < 12 {
        return Err(bad(format!(
            "truncated: {} bytes, shorter than any header ({HEADER_V2} bytes or more)",
            bytes.len()
        )));
    }
    let mut r = Cursor { bytes, at: 8 };
    let version = r.u32();
    if !(1..=VERSION).contains(&version) {
        return Err(bad(format!(
            "format version {version}, this build of springwater reads versions 1 to {VERSION}"
        )));
    }
    let header = if version < 3 { HEADER_V2 } else { HEADER };
    if bytes.len() < header {
        return Err(bad(format!(
            "truncated: {} bytes, the header alone has {header}",
            bytes.len()
        )));
    }
    let _flags = r.u32();
    let total = r.u64();
    let (cols, rows) = (r.u64(), r.u64());
    let floaters = if version < 3 {
        0
    } else {
        Cursor { bytes, at: 116 }.u32() as usize
    };
    let nodes = cols.checked_mul(rows).filter(|&n| n <= MAX_NODES as u64);
    let Some(expected) = nodes.and_then(|n| encoded_len(version, n as usize, floaters)) else {
        return Err(bad(format!(
            "grid {cols}x{rows} is larger than any surface (at most {MAX_NODES} nodes)"
        )));
    };
    if total != expected as u64 {
        return Err(bad(format!(
            "inconsistent lengths: the header says {total} bytes, a {cols}x{rows} grid with {floaters} floaters needs {expected}"
        )));
    }
    Ok(expected)
}

/// A forward reader over bytes whose length has been checked already.
struct Cursor<'a> {
    bytes: &'a [u8],
    at: usize,
}

impl Cursor<'_> {
    fn take(&mut self, len: usize) -> &[u8] {
        let s = &self.bytes[self.at..self.at + len];
        self.at += len;
        s
    }
    fn u32(&mut self) -> u32 {
        u32::from_le_bytes(self.take(4).try_into().expect("4 bytes"))
    }
    fn u64(&mut self) -> u64 {
        u64::from_le_bytes(self.take(8).try_into().expect("8 bytes"))
    }
    fn f32(&mut self) -> f32 {
        f32::from_bits(self.u32())
    }
    fn f64(&mut self) -> f64 {
        f64::from_bits(self.u64())
    }
    fn f32s(&mut self, n: usize) -> Vec<f32> {
        self.take(4 * n)
            .chunks_exact(4)
            .map(|c| f32::from_le_bytes(c.try_into().expect("4 bytes")))
            .collect()
    }
}

impl Surface {
    /// The complete state as plain data.
    pub fn snapshot(&self) -> Snapshot {
        let n = self.node_count();
        let s = &self.state;
        let cut3 = |a: &[Floats; 3]| [a[0][..n].to_vec(), a[1][..n].to_vec(), a[2][..n].to_vec()];
        let grid = self.grid();
        // Every spring's value, 0 where the grid has no spring (as the format says).
        let table = |value: fn((f32, f32)) -> f32| -> [Vec<f32>; 4] {
            Family::ALL.map(|family| {
                (0..n)
                    .map(|i| match grid.spring_end(family, i) {
                        Some(_) => value(self.springs.get(family, i)),
                        None => 0.0,
                    })
                    .collect()
            })
        };
        Snapshot {
            params: *self.params(),
            steps: self.steps(),
            model_time: self.model_time(),
            min_mass: self.min_mass,
            max_stiffness: self.max_stiffness,
            max_viscosity: self.max_viscosity,
            forces_pending: s.ext_pending,
            positions: cut3(&s.pos),
            velocities: cut3(&s.vel),
            forces: cut3(&s.ext),
            mass: s.mass.to_vec(),
            viscosity: s.viscosity.to_vec(),
            pinned: s.pinned.clone(),
            rest: table(|(_, rest)| rest),
            stiffness: table(|(coef, _)| coef),
            floaters: self.floaters.bodies.clone(),
            next_floater_id: self.floaters.next_id,
            buoyancy: self.floaters.buoyancy,
            origin_cells: self.window_origin,
            owed_time: self.clock.owed,
            step_cap: (self.clock.max_steps, self.clock.overflow),
            dropped_seconds: self.clock.dropped,
        }
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
        fill3(&mut state.ext, &snap.forces);
        if snap.forces_pending {
            state.touch_all_ext();
        }
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
        let bounds = [snap.min_mass, snap.max_stiffness, snap.max_viscosity];
        let progress = (snap.steps, snap.model_time);
        let mut surface = Surface::from_parts(p, state, springs, bounds, progress);
        surface.floaters.bodies = snap.floaters;
        surface.floaters.next_id = snap.next_floater_id;
        surface.floaters.buoyancy = snap.buoyancy;
        surface.window_origin = snap.origin_cells;
        surface.clock.owed = snap.owed_time;
        (surface.clock.max_steps, surface.clock.overflow) = snap.step_cap;
        surface.clock.dropped = snap.dropped_seconds;
        surface.window_custom = true;
        Ok(surface)
    }

    /// The snapshot in the binary format of the [`Snapshot`] docs.
    pub fn to_bytes(&self) -> Vec<u8> {
        self.snapshot().encode()
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
        (&mut r)
            .take(HEADER as u64)
            .read_to_end(&mut bytes)
            .map_err(io)?;
        let total = check_header(&bytes)?;
        (&mut r)
            .take((total - HEADER) as u64)
            .read_to_end(&mut bytes)
            .map_err(io)?;
        Surface::from_bytes(&bytes)
    }

    /// Replaces this surface's state with a binary snapshot. On error `self` is unchanged.
    pub fn restore(&mut self, bytes: &[u8]) -> Result<()> {
        let restored = Surface::from_bytes(bytes)?;
        // Where and how the engine runs (the host's threads, the SIMD level) are settings
        // of this surface, not state: they stay.
        let (host, simd) = (self.host.take(), self.simd);
        *self = restored;
        self.host = host;
        self.simd = simd;
        Ok(())
    }
}
