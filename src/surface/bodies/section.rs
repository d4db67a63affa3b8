//! The bodies' section of a snapshot: what the bodies' subsystem stores of itself, written
//! and read here, framed by the snapshot (`surface/snapshot/`), which counts it in its
//! header. In a snapshot of the current version the section is the bodies' records (176
//! bytes each), the hull meshes they refer to, and the water column's entries; versions 3
//! to 5 stored records of 80 bytes (spheres and boxes that only translate) and no meshes.
//! The encoder's half is [`Section::write`]; the reader's, [`Bodies::decode_into`] and
//! [`ColumnBytes::decode_into`]; [`check_bodies`] and [`check_column`] are what validation
//! asks of the decoded bodies and entries.
//!
//! # Shared hulls
//!
//! A hull mesh is stored once however many bodies hold it, in the order the bodies first
//! use it; each body names its mesh by its index in that order. Two bodies hold the same
//! mesh when they share the `Arc` or when their meshes have the same bits (vertices and
//! triangles, as given); a mesh stored twice is refused, so an accepted snapshot saves
//! back to its own bytes. Reading gives the bodies that name one stored mesh one `Arc`.
//! Decoding beside a surface's bodies (a restore in place) reuses the `Arc` of one of them
//! whose mesh has the stored bits, that at the same place first, so a rollback neither
//! validates nor allocates a mesh again.
//!
//! # Bounds
//!
//! The hull section's length is in the header and agrees with the total length, which
//! agrees with the bytes present; each mesh's vertex and triangle counts are checked
//! against the bytes left in the section before anything is copied out of it, and a mesh
//! that is not reused goes through [`Hull::new`]. A damaged count or index is an error,
//! never a large allocation.

use super::{Entry, Record};
use crate::body::Hull;
use crate::error::Result;
use crate::floater::{self, Buoyancy, Floater, FloaterId, Shape};
use crate::surface::bytes::{bad, floats, words, Reader, Sink};
use glam::{Mat3, Quat, Vec3};
use std::sync::Arc;

/// Bytes per body in versions 3 to 5.
pub(crate) const PER_TRANSLATING: usize = 80;
/// Where a version 6 record has its hull index: after the fields of versions 3 to 5, the
/// orientation (16 bytes), the angular velocity, push torque and water torque (12 each).
const HULL_INDEX_AT: usize = PER_TRANSLATING + 16 + 3 * 12;
/// Bytes per body from version 6: the hull index, then the inertia override (a flag and
/// nine entries).
pub(crate) const PER_BODY: usize = HULL_INDEX_AT + 4 + 40;
/// Each stored mesh starts with its vertex and triangle counts (`u32`).
const MESH_HEAD: usize = 8;
/// The shape code of a hull.
const HULL: u32 = 2;

/// Bytes of one entry of the water column, from version 7: its node (`u64`), the load it
/// carries and the load waiting (three `f32` each).
pub(crate) const PER_COLUMN_ENTRY: usize = 8 + 24;

/// A body's hull mesh, if it has one.
fn hull_of(body: &Floater) -> Option<&Arc<Hull>> {
    match &body.shape {
        Shape::Hull(hull) => Some(hull),
        _ => None,
    }
}

/// The bodies as stored, borrowed from the bytes.
#[derive(Clone, Copy)]
pub(crate) enum Bodies<'a> {
    /// Versions 3 to 5: [`PER_TRANSLATING`] bytes per body.
    Translating(&'a [u8]),
    /// Version 6: [`PER_BODY`] bytes per body, and the hull section.
    Rigid { records: &'a [u8], hulls: Hulls<'a> },
}

/// The hull section of version 6: `count` meshes, each its counts, vertices and triangles.
#[derive(Clone, Copy)]
pub(crate) struct Hulls<'a> {
    pub count: u64,
    pub bytes: &'a [u8],
}

impl Bodies<'_> {
    pub const NONE: Bodies<'static> = Bodies::Translating(&[]);

    /// Appends each body with its id to `out`, or returns the error its record gives (then
    /// `out` may hold some of them after its own: the caller drops them). The `lenders`,
    /// a surface's current bodies, lend their hull meshes (see the module docs).
    pub fn decode_into(
        self,
        out: &mut Vec<(FloaterId, Floater)>,
        lenders: &[Record],
    ) -> Result<()> {
        match self {
            Bodies::Translating(records) => {
                for record in records.chunks_exact(PER_TRANSLATING) {
                    let mut r = Reader::new(record);
                    let (id, code, size, body) = common(&mut r);
                    let shape = shape(id, code, size, false)?.expect("no hulls before version 6");
                    out.push((id, Floater { shape, ..body }));
                }
                Ok(())
            }
            Bodies::Rigid { records, hulls } => rigid(records, hulls, out, lenders),
        }
    }
}

/// The fields every version stores (the first [`PER_TRANSLATING`] bytes of a record): the
/// id, the shape code and its size fields, and the body with those fields (a placeholder
/// shape, the others at [`Floater`]'s defaults).
fn common(r: &mut Reader<'_>) -> (FloaterId, u32, [f32; 3], Floater) {
    let id = FloaterId(r.u64());
    let code = r.u32();
    let [a, b, c, mass, drag] = [(); 5].map(|_| r.f32());
    let (position, velocity, push, water_force) = (vec3(r), vec3(r), vec3(r), vec3(r));
    let mut body = Floater::sphere(1.0, mass, position);
    body.drag = drag;
    body.velocity = velocity;
    body.push = push;
    body.water_force = water_force;
    (id, code, [a, b, c], body)
}

fn vec3(r: &mut Reader<'_>) -> Vec3 {
    Vec3::from_array([(); 3].map(|_| r.f32()))
}

/// The shape a code and its size fields stand for; `None` for a hull (code 2, from
/// version 6 (`rigid`), with zero size fields), which the caller looks up.
fn shape(id: FloaterId, code: u32, [a, b, c]: [f32; 3], rigid: bool) -> Result<Option<Shape>> {
    let zero = |v: f32| v.to_bits() == 0;
    let id = id.0;
    match code {
        0 if zero(b) && zero(c) => Ok(Some(Shape::Sphere { radius: a })),
        0 => Err(bad(format!(
            "floater {id}: a sphere with size fields other than (radius, 0, 0)"
        ))),
        1 => Ok(Some(Shape::Box {
            half_extents: Vec3::new(a, b, c),
        })),
        HULL if rigid && zero(a) && zero(b) && zero(c) => Ok(None),
        HULL if rigid => Err(bad(format!(
            "floater {id}: a hull with size fields other than (0, 0, 0)"
        ))),
        other => Err(bad(format!(
            "floater {id}: unknown shape code {other} ({})",
            if rigid {
                "0 = sphere, 1 = box, 2 = hull"
            } else {
                "0 = sphere, 1 = box; hulls from version 6"
            }
        ))),
    }
}

/// A version 6 record but its shape: the body (a placeholder shape for a hull), the
/// shape if it is not a hull, and the hull index (0 for the other shapes).
fn rigid_record(record: &[u8]) -> Result<(FloaterId, Floater, Option<Shape>, u32)> {
    let mut r = Reader::new(record);
    let (id, code, size, mut body) = common(&mut r);
    let shape = shape(id, code, size, true)?;
    body.orientation = Quat::from_array([(); 4].map(|_| r.f32()));
    body.angular_velocity = vec3(&mut r);
    body.push_torque = vec3(&mut r);
    body.water_torque = vec3(&mut r);
    let hull = r.u32();
    if shape.is_some() && hull != 0 {
        return Err(bad(format!(
            "floater {}: hull index {hull} stored for a body that is not a hull",
            id.0
        )));
    }
    let flag = r.u32();
    let entries = [(); 9].map(|_| r.f32());
    body.inertia = match flag {
        1 => Some(Mat3::from_cols_array(&entries)),
        0 if entries.iter().all(|v| v.to_bits() == 0) => None,
        0 => {
            return Err(bad(format!(
                "floater {}: inertia entries stored without the inertia flag",
                id.0
            )))
        }
        other => {
            return Err(bad(format!(
                "floater {}: inertia flag {other} is not 0 or 1",
                id.0
            )))
        }
    };
    Ok((id, body, shape, hull))
}

/// Decodes version 6 records and their meshes into `out` (see [`Bodies::decode_into`]).
fn rigid(
    records: &[u8],
    hulls: Hulls<'_>,
    out: &mut Vec<(FloaterId, Floater)>,
    lenders: &[Record],
) -> Result<()> {
    let pool = out.len();
    let mut meshes = Meshes::new(hulls.bytes);
    // The last mesh looked up and its first body: bodies sharing one often come in runs.
    let mut last: Option<(u32, usize)> = None;
    for (k, record) in records.chunks_exact(PER_BODY).enumerate() {
        let (id, mut body, shape, index) = rigid_record(record)?;
        body.shape = match shape {
            Some(shape) => shape,
            None if u64::from(index) < meshes.read => {
                // Not the first body to use the mesh: the first one has it.
                let first = match last {
                    Some((i, first)) if i == index => first,
                    _ => records
                        .chunks_exact(PER_BODY)
                        .position(|r| code_and_hull(r) == (HULL, index))
                        .expect("an earlier body used the mesh"),
                };
                last = Some((index, first));
                out[pool + first].1.shape.clone()
            }
            None if u64::from(index) == meshes.read && meshes.read < hulls.count => {
                let mesh = meshes.next()?;
                if let Some(j) = meshes.earlier(&mesh) {
                    return Err(bad(format!(
                        "hull {index} repeats hull {j}: each mesh is stored once"
                    )));
                }
                Shape::Hull(match mesh.held_by(lenders, k) {
                    Some(hull) => Arc::clone(hull),
                    None => Arc::new(
                        mesh.to_hull()
                            .map_err(|e| bad(format!("hull {index} (floater {}): {e}", id.0)))?,
                    ),
                })
            }
            None if u64::from(index) < hulls.count => {
                return Err(bad(format!(
                    "floater {}: refers to hull {index} before hull {}: hulls are stored in \
                     the order bodies first use them",
                    id.0, meshes.read
                )))
            }
            None => {
                return Err(bad(format!(
                    "floater {}: hull index {index} is out of range: {} hulls are stored",
                    id.0, hulls.count
                )))
            }
        };
        out.push((id, body));
    }
    if meshes.read < hulls.count {
        return Err(bad(format!(
            "hull {} is stored but no body uses it",
            meshes.read
        )));
    }
    if !meshes.bytes.is_empty() {
        return Err(bad(format!(
            "the hull section has {} bytes after its last hull: its length is wrong",
            meshes.bytes.len()
        )));
    }
    Ok(())
}

/// The shape code and hull index of a version 6 record.
fn code_and_hull(record: &[u8]) -> (u32, u32) {
    let word = |at: usize| u32::from_le_bytes(record[at..at + 4].try_into().expect("4 bytes"));
    (word(8), word(HULL_INDEX_AT))
}

/// The hull section read from the front, one mesh at a time.
struct Meshes<'a> {
    section: &'a [u8],
    /// What is left to read.
    bytes: &'a [u8],
    /// Meshes read so far.
    read: u64,
}

impl<'a> Meshes<'a> {
    fn new(section: &'a [u8]) -> Self {
        Meshes {
            section,
            bytes: section,
            read: 0,
        }
    }

    /// The index of a mesh read before the last one that has the same bits as `mesh` (a
    /// writer stores each once: a mesh stored twice would not save back to these bytes).
    fn earlier(&self, mesh: &Mesh<'_>) -> Option<u64> {
        let before = self.section.len() - self.bytes.len();
        let mut earlier = Meshes::new(&self.section[..before]);
        (0..self.read - 1).find(|_| earlier.next().is_ok_and(|m| m == *mesh))
    }

    /// The next mesh, its counts checked against the bytes left.
    fn next(&mut self) -> Result<Mesh<'a>> {
        let index = self.read;
        let left = self.bytes.len();
        if left < MESH_HEAD {
            return Err(bad(format!(
                "hull {index}: the hull section ends ({left} bytes left) before its counts: \
                 its length is wrong"
            )));
        }
        let mut r = Reader::new(self.bytes);
        let (vertices, triangles) = (r.u32() as usize, r.u32() as usize);
        // At most 2 × 2³² × 12 bytes: no overflow in u64.
        let need = 12 * (vertices as u64 + triangles as u64);
        if need > (left - MESH_HEAD) as u64 {
            return Err(bad(format!(
                "hull {index}: {vertices} vertices and {triangles} triangles need {need} bytes, \
                 the hull section has {} left: a count or the section's length is wrong",
                left - MESH_HEAD
            )));
        }
        let (vertices, rest) = self.bytes[MESH_HEAD..].split_at(12 * vertices);
        let (triangles, rest) = rest.split_at(12 * triangles);
        self.bytes = rest;
        self.read += 1;
        Ok(Mesh {
            vertices,
            triangles,
        })
    }
}

/// One stored mesh: its vertices (three `f32` each) and triangles (three `u32` each),
/// little-endian, borrowed.
#[derive(PartialEq)]
struct Mesh<'a> {
    vertices: &'a [u8],
    triangles: &'a [u8],
}

impl Mesh<'_> {
    /// Whether `hull` has exactly these vertices and triangles, bit for bit.
    fn is(&self, hull: &Hull) -> bool {
        same_words(self.vertices, vertex_bits(hull))
            && same_words(self.triangles, bytemuck::cast_slice(hull.triangles()))
    }

    /// The hull of a body of `bodies` that is this mesh: body `k`'s if it is, else the
    /// first one's.
    fn held_by<'b>(&self, bodies: &'b [Record], k: usize) -> Option<&'b Arc<Hull>> {
        let this = |r: &'b Record| hull_of(&r.body).filter(|h| self.is(h));
        let known = bodies.get(k).and_then(this);
        known.or_else(|| bodies.iter().find_map(this))
    }

    /// The mesh validated by [`Hull::new`].
    fn to_hull(&self) -> Result<Hull> {
        let word = |c: &[u8]| u32::from_le_bytes(c.try_into().expect("4 bytes"));
        let vertices: Vec<[f32; 3]> = self
            .vertices
            .chunks_exact(12)
            .map(|v| [0, 4, 8].map(|at| f32::from_bits(word(&v[at..at + 4]))))
            .collect();
        let triangles: Vec<[u32; 3]> = self
            .triangles
            .chunks_exact(12)
            .map(|t| [0, 4, 8].map(|at| word(&t[at..at + 4])))
            .collect();
        Hull::new(&vertices, &triangles)
    }
}

/// Whether little-endian `bytes` hold exactly `words`.
fn same_words(bytes: &[u8], words: &[u32]) -> bool {
    if cfg!(target_endian = "little") {
        bytes == bytemuck::cast_slice::<u32, u8>(words)
    } else {
        bytes.len() == 4 * words.len()
            && bytes
                .chunks_exact(4)
                .zip(words)
                .all(|(b, w)| b == w.to_le_bytes())
    }
}

/// Whether two meshes are one for the format: the same `Hull`, or the same vertices (bit
/// for bit) and triangles.
fn same_hull(a: &Hull, b: &Hull) -> bool {
    std::ptr::eq(a, b) || (a.triangles() == b.triangles() && vertex_bits(a) == vertex_bits(b))
}

/// The bits of a mesh's vertex coordinates.
fn vertex_bits(hull: &Hull) -> &[u32] {
    bytemuck::cast_slice(hull.vertices())
}

/// Bytes a mesh takes in the hull section.
fn stored_len(hull: &Hull) -> u64 {
    (MESH_HEAD + 12 * (hull.vertices().len() + hull.triangles().len())) as u64
}

/// The hull meshes of a body list as the format stores them: each distinct mesh once, in
/// the order bodies first use it. Found by scanning the list (nothing is allocated): a
/// body's mesh is compared with those of the bodies before it, by pointer first, so bodies
/// sharing an `Arc` cost next to nothing.
#[derive(Clone, Copy)]
pub(crate) struct HullTable<'a> {
    bodies: BodyList<'a>,
    /// The first body with a hull: scans start there.
    start: usize,
    /// Distinct meshes.
    pub count: u64,
    /// The hull section's length in bytes.
    pub bytes: u64,
}

impl<'a> HullTable<'a> {
    fn of(bodies: BodyList<'a>) -> Self {
        let start = (0..bodies.len()).position(|k| hull_of(bodies.body(k)).is_some());
        let mut table = HullTable {
            bodies,
            start: start.unwrap_or(bodies.len()),
            count: 0,
            bytes: 0,
        };
        for hull in table.distinct() {
            table.count += 1;
            table.bytes += stored_len(hull);
        }
        table
    }

    /// The distinct meshes in the order they are stored.
    fn distinct(self) -> impl Iterator<Item = &'a Hull> {
        (self.start..self.bodies.len()).filter_map(move |i| {
            let hull = hull_of(self.bodies.body(i))?;
            (self.first_use(hull, i) == i).then_some(&**hull)
        })
    }

    /// The index in the hull section of `hull`, the mesh of a body of the list.
    fn index(self, hull: &Hull) -> u32 {
        let earlier = self.distinct().take_while(|&h| !same_hull(h, hull));
        earlier.count() as u32
    }

    /// The first body, at most `k`, whose mesh is `hull` (`k` if none before it).
    fn first_use(self, hull: &Hull, k: usize) -> usize {
        (self.start..k)
            .find(|&i| hull_of(self.bodies.body(i)).is_some_and(|h| same_hull(h, hull)))
            .unwrap_or(k)
    }
}

/// The bodies the section writes: a surface's records or a snapshot's list.
#[derive(Clone, Copy)]
pub(crate) enum BodyList<'a> {
    Records(&'a [Record]),
    Pairs(&'a [(FloaterId, Floater)]),
}

impl<'a> BodyList<'a> {
    fn len(self) -> usize {
        match self {
            BodyList::Records(r) => r.len(),
            BodyList::Pairs(p) => p.len(),
        }
    }

    fn id(self, k: usize) -> FloaterId {
        match self {
            BodyList::Records(r) => r[k].id,
            BodyList::Pairs(p) => p[k].0,
        }
    }

    fn body(self, k: usize) -> &'a Floater {
        match self {
            BodyList::Records(r) => &r[k].body,
            BodyList::Pairs(p) => &p[k].1,
        }
    }
}

/// The bodies' section as the encoder writes it, borrowed: the bodies, the distinct hull
/// meshes they hold, and the water column's entries (sorted by node).
#[derive(Clone, Copy)]
pub(crate) struct Section<'a> {
    bodies: BodyList<'a>,
    hulls: HullTable<'a>,
    column: &'a [Entry],
}

impl<'a> Section<'a> {
    /// The section of `bodies` and the water column's `column`.
    pub fn of(bodies: BodyList<'a>, column: &'a [Entry]) -> Self {
        Section {
            bodies,
            hulls: HullTable::of(bodies),
            column,
        }
    }

    /// How many bodies the section holds.
    pub fn bodies(&self) -> usize {
        self.bodies.len()
    }

    /// How many distinct hull meshes it stores, and in how many bytes.
    pub fn hulls(&self) -> (u64, u64) {
        (self.hulls.count, self.hulls.bytes)
    }

    /// How many entries of the water column it stores.
    pub fn column(&self) -> u64 {
        self.column.len() as u64
    }

    /// Sends the section to `sink`: each body's record, each distinct hull mesh (its vertex
    /// and triangle counts as `u32`, its vertices, its triangles), each entry of the
    /// column (its node as `u64`, the load it carries, the load waiting).
    pub fn write(&self, sink: &mut dyn Sink) {
        // Bodies that share a mesh usually come in runs: the last one found is tried first.
        let mut last: Option<(&Hull, u32)> = None;
        for k in 0..self.bodies.len() {
            let body = self.bodies.body(k);
            sink.state(&self.bodies.id(k).0.to_le_bytes());
            let (shape, size): (u32, [f32; 3]) = match &body.shape {
                Shape::Sphere { radius } => (0, [*radius, 0.0, 0.0]),
                Shape::Box { half_extents } => (1, half_extents.to_array()),
                Shape::Hull(_) => (HULL, [0.0; 3]),
            };
            sink.state(&shape.to_le_bytes());
            floats(sink, &size);
            floats(sink, &[body.mass, body.drag]);
            for v in [body.position, body.velocity, body.push, body.water_force] {
                floats(sink, &v.to_array());
            }
            floats(sink, &body.orientation.to_array());
            for v in [body.angular_velocity, body.push_torque, body.water_torque] {
                floats(sink, &v.to_array());
            }
            let hull = hull_of(body).map_or(0, |hull| match last {
                Some((h, index)) if std::ptr::eq(h, &**hull) => index,
                _ => {
                    let index = self.hulls.index(hull);
                    last = Some((hull, index));
                    index
                }
            });
            sink.state(&hull.to_le_bytes());
            let (flag, inertia) = match body.inertia {
                Some(i) => (1u32, i.to_cols_array()),
                None => (0, [0.0; 9]),
            };
            sink.state(&flag.to_le_bytes());
            floats(sink, &inertia);
        }
        for hull in self.hulls.distinct() {
            let (vertices, triangles) = (hull.vertices(), hull.triangles());
            words(sink, &[vertices.len() as u32, triangles.len() as u32]);
            floats(sink, bytemuck::cast_slice(vertices));
            words(sink, bytemuck::cast_slice(triangles));
        }
        for e in self.column {
            sink.state(&(e.node as u64).to_le_bytes());
            floats(sink, &e.carried);
            floats(sink, &e.pending);
        }
    }
}

/// The water column's entries, from version 7 (after the bodies), borrowed; their count
/// was checked against the total length.
#[derive(Clone, Copy)]
pub(crate) struct ColumnBytes<'a>(&'a [u8]);

impl<'a> ColumnBytes<'a> {
    /// No entries (versions before 7).
    pub const NONE: ColumnBytes<'static> = ColumnBytes(&[]);

    /// The next `entries` entries of `r`.
    pub fn read(r: &mut Reader<'a>, entries: usize) -> Self {
        ColumnBytes(r.take(entries * PER_COLUMN_ENTRY))
    }

    /// Decodes the entries into `out` (cleared first, its capacity reused).
    pub fn decode_into(self, out: &mut Vec<Entry>) {
        out.clear();
        out.extend(self.0.chunks_exact(PER_COLUMN_ENTRY).map(|e| {
            let mut r = Reader::new(e);
            let node = r.u64() as usize;
            let carried = [(); 3].map(|_| r.f32());
            let pending = [(); 3].map(|_| r.f32());
            Entry::stored(node, carried, pending)
        }));
    }
}

/// Decoded bodies a surface can take: the world is valid; each body is valid and fits a
/// lattice of `spacing`; ids increase and stay below `next_id`.
pub(crate) fn check_bodies(
    bodies: &[(FloaterId, Floater)],
    next_id: u64,
    buoyancy: Buoyancy,
    spacing: f32,
) -> Result<()> {
    buoyancy
        .validate()
        .map_err(|e| bad(format!("buoyancy: {e}")))?;
    let mut previous = None;
    for (id, body) in bodies {
        body.validate()
            .and_then(|()| floater::check_footprint(&body.shape, spacing))
            .map_err(|e| bad(format!("floater {}: {e}", id.0)))?;
        if previous.is_some_and(|p| p >= id.0) || id.0 >= next_id {
            // (So the next id is above 0 and every stored id below `u64::MAX`.)
            return Err(bad(format!(
                "floater {}: ids must increase and stay below the next id {next_id}",
                id.0
            )));
        }
        previous = Some(id.0);
    }
    Ok(())
}

/// Decoded column entries a surface of `n` nodes can take: their nodes are on the grid
/// and increase; their loads are finite.
pub(crate) fn check_column(column: &[Entry], n: usize) -> Result<()> {
    let mut last = None;
    for e in column {
        if e.node >= n || last.is_some_and(|l| l >= e.node) {
            return Err(bad(format!(
                "the water column's node {} is off the grid of {n} nodes or out of order",
                e.node
            )));
        }
        if !e.carried.iter().chain(&e.pending).all(|v| v.is_finite()) {
            return Err(bad(format!(
                "the water column's load at node {} is not finite",
                e.node
            )));
        }
        last = Some(e.node);
    }
    Ok(())
}
