//! The encoder, written once: the fields of the current format in their order, sent to a
//! [`Sink`]. Saving sends them to a byte buffer ([`Bytes`]); [`Surface::state_hash`] sends
//! the same stream to a hasher ([`StateHash`]), which skips the fields marked as records. So
//! what is hashed is what is saved, less the framing and the counters, and the two cannot
//! drift apart.
//!
//! The fields come from a [`Fields`] view, which a [`Surface`] gives straight from its
//! buffers (a table kept as rows of defaults or a family's shared spring is written out
//! node by node, as the format has it) and a [`Snapshot`] from its vectors. The bodies'
//! section (the bodies, their hull meshes and the water column) is the bodies'
//! subsystem's to write ([`Section`]).

use super::read::{encoded_len, FLAG_FORCES_PENDING};
use super::validate::spring_columns;
use super::{Scalars, Snapshot, MAGIC, VERSION};
use crate::grid::{Family, Grid};
use crate::params::Boundary;
use crate::state::NodeTable;
use crate::surface::bodies::section::{BodyList, Section};
use crate::surface::bytes::{floats, Sink};
use crate::surface::{Overflow, Surface};

/// Appends every field to a buffer, the binary format, and checksums what it appends
/// while it is still in the cache (a piece at a time), for the CRC-32 at the end.
pub(super) struct Bytes<'a> {
    pub out: &'a mut Vec<u8>,
    pub crc: super::crc::Hasher,
}

impl Bytes<'_> {
    fn append(&mut self, bytes: &[u8]) {
        for piece in bytes.chunks(1 << 14) {
            self.out.extend_from_slice(piece);
            self.crc.update(piece);
        }
    }
}

impl Sink for Bytes<'_> {
    fn state(&mut self, bytes: &[u8]) {
        self.append(bytes);
    }
    fn record(&mut self, bytes: &[u8]) {
        self.append(bytes);
    }
}

/// Feeds the fields that decide the future to XXH3-64.
pub(super) struct StateHash(pub xxhash_rust::xxh3::Xxh3);

impl Sink for StateHash {
    fn state(&mut self, bytes: &[u8]) {
        self.0.update(bytes);
    }
    fn record(&mut self, _: &[u8]) {}
}

/// One per-node array as the encoder finds it.
#[derive(Clone, Copy)]
pub(super) enum Values<'a> {
    /// One value per node.
    Nodes(&'a [f32]),
    /// A node table: rows of defaults, or one value per node.
    Table(&'a NodeTable),
    /// A spring family's values: the per-spring table if there is one, else the value
    /// every spring of the family shares; zero where the grid has no spring.
    Springs {
        family: Family,
        table: Option<&'a [f32]>,
        shared: f32,
    },
}

/// Everything the format stores, borrowed.
pub(super) struct Fields<'a> {
    pub grid: Grid,
    pub scalars: Scalars,
    pub positions: [&'a [f32]; 3],
    pub velocities: [&'a [f32]; 3],
    pub forces: [&'a [f32]; 3],
    pub mass: Values<'a>,
    pub viscosity: Values<'a>,
    pub pinned: &'a [bool],
    pub rest: [Values<'a>; 4],
    pub stiffness: [Values<'a>; 4],
    /// The bodies' section: the bodies, their hull meshes, the water column.
    pub bodies: Section<'a>,
}

impl Fields<'_> {
    /// The length of the encoding, checksum included.
    pub fn encoded_len(&self) -> usize {
        let (nodes, bodies) = (self.grid.node_count(), self.bodies.bodies());
        let (_, hull_bytes) = self.bodies.hulls();
        encoded_len(VERSION, nodes, bodies, hull_bytes, self.bodies.column())
            .expect("a snapshot of an allocated surface fits in memory")
    }

    /// Sends every field but the checksum to `sink`, in the format's order.
    pub fn encode(&self, sink: &mut dyn Sink) {
        let (s, p) = (&self.scalars, &self.scalars.params);
        sink.record(&MAGIC);
        sink.record(&VERSION.to_le_bytes());
        let flags = if s.forces_pending {
            FLAG_FORCES_PENDING
        } else {
            0
        };
        sink.state(&flags.to_le_bytes());
        sink.record(&(self.encoded_len() as u64).to_le_bytes());
        sink.state(&(p.cols as u64).to_le_bytes());
        sink.state(&(p.rows as u64).to_le_bytes());
        floats(sink, &super::model(p));
        let boundary: u32 = match p.boundary {
            Boundary::Pinned => 0,
            Boundary::Free => 1,
            Boundary::Absorbing { .. } => 2,
        };
        sink.state(&boundary.to_le_bytes());
        floats(sink, &p.acceleration);
        sink.record(&s.steps.to_le_bytes());
        sink.record(&s.model_time.to_le_bytes());
        floats(sink, &s.bounds);
        floats(sink, &[p.time_scale]);
        let width = super::frame_width(p.boundary).expect("checked by to_bytes or validation");
        sink.state(&width.to_le_bytes());
        sink.state(&(self.bodies.bodies() as u32).to_le_bytes());
        sink.state(&s.next_floater_id.to_le_bytes());
        floats(sink, &[s.buoyancy.gravity, s.buoyancy.density]);
        // Framing, like the total length: both follow from the meshes, which are state
        // (and water without bodies hashes as it did before hulls were stored).
        let (hulls, hull_bytes) = self.bodies.hulls();
        sink.record(&hulls.to_le_bytes());
        sink.record(&hull_bytes.to_le_bytes());
        // Framing too: the entries are state, and water without bodies has none.
        sink.record(&self.bodies.column().to_le_bytes());
        for a in self
            .positions
            .iter()
            .chain(&self.velocities)
            .chain(&self.forces)
        {
            floats(sink, a);
        }
        self.values(sink, self.mass);
        self.values(sink, self.viscosity);
        for pins in self.pinned.chunks(1024) {
            let mut bytes = [0u8; 1024];
            for (b, &p) in bytes.iter_mut().zip(pins) {
                *b = p as u8;
            }
            sink.state(&bytes[..pins.len()]);
        }
        for f in 0..4 {
            self.values(sink, self.rest[f]);
            self.values(sink, self.stiffness[f]);
        }
        self.bodies.write(sink);
        for c in s.origin_cells {
            sink.state(&c.to_le_bytes());
        }
        sink.state(&s.owed_time.to_le_bytes());
        sink.state(&s.step_cap.0.to_le_bytes());
        let overflow: u32 = match s.step_cap.1 {
            Overflow::Drop => 0,
            Overflow::Carry => 1,
        };
        sink.state(&overflow.to_le_bytes());
        sink.record(&s.dropped_seconds.to_le_bytes());
    }

    /// One value per node of `values`, row by row.
    fn values(&self, sink: &mut dyn Sink, values: Values<'_>) {
        let cols = self.grid.cols;
        match values {
            Values::Nodes(a) => floats(sink, a),
            Values::Table(t) => (0..self.grid.rows).for_each(|r| floats(sink, &t.row(r)[..cols])),
            Values::Springs {
                family,
                table,
                shared,
            } => {
                for r in 0..self.grid.rows {
                    let inside = spring_columns(self.grid, family, r);
                    repeat(sink, 0.0, inside.start);
                    match table {
                        Some(t) => floats(sink, &t[r * cols..][inside.clone()]),
                        None => repeat(sink, shared, inside.len()),
                    }
                    repeat(sink, 0.0, cols - inside.end.max(inside.start));
                }
            }
        }
    }
}

/// `value` `count` times, little-endian.
fn repeat(sink: &mut dyn Sink, value: f32, count: usize) {
    const BLOCK: usize = 256;
    let block = [value; BLOCK];
    for start in (0..count).step_by(BLOCK) {
        floats(sink, &block[..BLOCK.min(count - start)]);
    }
}

impl Surface {
    /// A spring family's rest lengths or stiffnesses (`part` of `(stiffness, rest)`).
    fn spring_values<'a>(
        &self,
        family: Family,
        part: fn((f32, f32)) -> f32,
        table: Option<&'a [f32]>,
    ) -> Values<'a> {
        // The family's first spring gives the shared value when there is no table.
        let grid = self.grid();
        let first = (0..grid.node_count()).find(|&i| grid.spring_end(family, i).is_some());
        let shared = first.map_or(0.0, |i| part(self.lattice.springs.get(family, i)));
        Values::Springs {
            family,
            table,
            shared,
        }
    }

    /// The surface's fields as the encoder reads them, straight from its buffers.
    pub(super) fn fields(&self) -> Fields<'_> {
        let n = self.node_count();
        let s = &self.lattice.state;
        let grid = self.grid();
        let tables = self.lattice.springs.tables();
        let rest = Family::ALL.map(|f| {
            let table = tables.map(|t| &t.rest[f as usize][..n]);
            self.spring_values(f, |(_, rest)| rest, table)
        });
        let stiffness = Family::ALL.map(|f| {
            let table = tables.map(|t| &t.coef[f as usize][..n]);
            self.spring_values(f, |(coef, _)| coef, table)
        });
        Fields {
            grid,
            scalars: Scalars {
                params: self.params,
                steps: self.steps,
                model_time: self.time,
                bounds: self.lattice.stability.bounds(),
                forces_pending: s.ext.is_pending(),
                next_floater_id: self.bodies.next_id(),
                buoyancy: self.buoyancy(),
                origin_cells: self.window.origin,
                owed_time: self.clock.owed,
                step_cap: (self.clock.max_steps, self.clock.overflow),
                dropped_seconds: self.clock.dropped,
            },
            positions: cut(&s.pos, n),
            velocities: cut(&s.vel, n),
            forces: cut(s.ext.buffers(), n),
            mass: Values::Table(&s.mass),
            viscosity: Values::Table(&s.viscosity),
            pinned: &s.pinned,
            rest,
            stiffness,
            bodies: Section::of(
                BodyList::Records(self.bodies.records()),
                self.bodies.column().entries(),
            ),
        }
    }
}

impl Snapshot {
    /// The snapshot's fields as the encoder reads them (its arrays hold one value per
    /// node: checked by [`Snapshot::to_bytes`] or by validation).
    pub(super) fn fields(&self) -> Fields<'_> {
        Fields {
            grid: Grid::new(self.params.cols, self.params.rows),
            scalars: self.scalars(),
            positions: slices(&self.positions),
            velocities: slices(&self.velocities),
            forces: slices(&self.forces),
            mass: Values::Nodes(&self.mass),
            viscosity: Values::Nodes(&self.viscosity),
            pinned: &self.pinned,
            rest: std::array::from_fn(|f| Values::Nodes(&self.rest[f])),
            stiffness: std::array::from_fn(|f| Values::Nodes(&self.stiffness[f])),
            bodies: Section::of(BodyList::Pairs(&self.floaters), &self.column),
        }
    }
}

/// The first `n` values of each of three padded buffers.
fn cut(a: &[crate::simd::Floats; 3], n: usize) -> [&[f32]; 3] {
    [&a[0][..n], &a[1][..n], &a[2][..n]]
}

/// Three vectors as slices.
pub(super) fn slices(a: &[Vec<f32>; 3]) -> [&[f32]; 3] {
    [&a[0], &a[1], &a[2]]
}
