//! Reading the binary format: the framing every version shares (magic, version, lengths,
//! checksum) and the sections the versions are built from, borrowed from the bytes.
//!
//! A version's layout is a sequence of sections (see `versions.rs` for which version has
//! which): the [`Head`] at offsets 8 to 112, from version 3 the [`World`] after it, the
//! per-node arrays ([`Nodes`]), from version 3 the bodies ([`Bodies`], from version 6 with
//! their hull meshes) and from version 4 the [`Tail`]. Reading a section allocates
//! nothing: arrays are views of the bytes ([`Le`]), so a surface can be restored from them
//! in place.

use super::{bad, Scalars, Snapshot, CRC, HEADER, HEADER_V2, HEADER_V5, HEADER_V6, MAGIC, VERSION};
use crate::error::Result;
use crate::floater::Buoyancy;
use crate::params::{Boundary, Params, MAX_NODES};
use crate::surface::bodies::section::{
    Bodies, ColumnBytes, Hulls, PER_BODY, PER_COLUMN_ENTRY, PER_TRANSLATING,
};
use crate::surface::bytes::Reader;
use crate::surface::{Overflow, Surface};

/// Bytes per node: 11 `f32` arrays, 1 `u8`, 8 `f32` spring arrays.
pub(super) const PER_NODE: usize = 11 * 4 + 1 + 8 * 4;
/// From version 4, before the checksum: the window's origin in cells (two `i64`) and the
/// clock of `advance` (owed model time `f64`, step cap `u32`, overflow `u32`, dropped
/// seconds `f64`).
pub(super) const TAIL: usize = 16 + 24;
pub(super) const FLAG_FORCES_PENDING: u32 = 1;

/// Bytes before the per-node arrays in a format version's layout.
pub(super) fn header_len(version: u32) -> usize {
    match version {
        ..=2 => HEADER_V2,
        3..=5 => HEADER_V5,
        6 => HEADER_V6,
        _ => HEADER,
    }
}

/// Snapshot size in bytes for `nodes` nodes, `floaters` bodies, a hull section of
/// `hull_bytes` (0 before version 6) and `column` entries of the water column (0 before
/// version 7) in a format version's layout, or `None` on overflow.
pub(super) fn encoded_len(
    version: u32,
    nodes: usize,
    floaters: usize,
    hull_bytes: u64,
    column: u64,
) -> Option<usize> {
    let per_body = if version < 6 {
        PER_TRANSLATING
    } else {
        PER_BODY
    };
    let tail = if version < 4 { 0 } else { TAIL };
    nodes
        .checked_mul(PER_NODE)?
        .checked_add(floaters.checked_mul(per_body)?)?
        .checked_add(usize::try_from(hull_bytes).ok()?)?
        .checked_add(
            usize::try_from(column)
                .ok()?
                .checked_mul(PER_COLUMN_ENTRY)?,
        )?
        .checked_add(header_len(version) + tail + CRC)
}

/// Checks magic, version and lengths; returns the total length the header announces,
/// which is consistent with `cols × rows` (at most [`MAX_NODES`] nodes), the body count
/// and the hull section's length.
pub(super) fn check_header(bytes: &[u8]) -> Result<usize> {
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
    let mut r = Reader::at(bytes, 8);
    let version = r.u32();
    if !(1..=VERSION).contains(&version) {
        return Err(bad(format!(
            "format version {version}, this build of springwater reads versions 1 to {VERSION}"
        )));
    }
    let header = header_len(version);
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
        Reader::at(bytes, 116).u32() as usize
    };
    let hull_bytes = if version < 6 {
        0
    } else {
        Reader::at(bytes, 144).u64()
    };
    let column = if version < 7 {
        0
    } else {
        Reader::at(bytes, 152).u64()
    };
    let Some(nodes) = cols.checked_mul(rows).filter(|&n| n <= MAX_NODES as u64) else {
        return Err(bad(format!(
            "grid {cols}x{rows} is larger than any surface (at most {MAX_NODES} nodes)"
        )));
    };
    let expected = encoded_len(version, nodes as usize, floaters, hull_bytes, column);
    if expected.map(|e| e as u64) != Some(total) {
        let needs = expected.map_or("more than fits in memory".into(), |e| e.to_string());
        return Err(bad(format!(
            "inconsistent lengths: the header says {total} bytes, a {cols}x{rows} grid with {floaters} floaters, {hull_bytes} bytes of hull meshes and {column} water column entries needs {needs}"
        )));
    }
    Ok(total as usize)
}

/// Checks the framing of exactly one snapshot (magic, version, lengths, no trailing data,
/// checksum) and returns its version and a reader at the first byte after the version,
/// over the bytes before the checksum.
pub(super) fn framing(bytes: &[u8]) -> Result<(u32, Reader<'_>)> {
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
    let actual = super::crc::hash(body);
    if stored != actual {
        return Err(bad(format!(
            "checksum mismatch (stored {stored:08x}, computed {actual:08x}): the data is corrupted"
        )));
    }
    let mut r = Reader::at(body, 8);
    let version = r.u32();
    Ok((version, r))
}

/// `n` `f32` values from `r`, borrowed.
fn floats<'a>(r: &mut Reader<'a>, n: usize) -> Le<'a> {
    Le(r.take(4 * n))
}

/// `f32` values stored little-endian, borrowed from the bytes (which need no alignment).
#[derive(Debug, Clone, Copy)]
pub(crate) struct Le<'a>(pub(super) &'a [u8]);

impl Le<'_> {
    pub(super) fn to_vec(self) -> Vec<f32> {
        self.0
            .chunks_exact(4)
            .map(|c| f32::from_le_bytes(c.try_into().expect("4 bytes")))
            .collect()
    }
}

/// Offsets 8 to 112, in every version: the flags, the grid and the model, the counters and
/// the bounds. The boundary stays a code until the frame width is known (version 3 on).
pub(super) struct Head {
    pub flags: u32,
    /// The parameters with `Boundary::Pinned` and the stored time scale field.
    pub params: Params,
    pub boundary: u32,
    pub steps: u64,
    pub model_time: f64,
    pub bounds: [f32; 3],
}

pub(super) fn head(r: &mut Reader<'_>) -> Head {
    let flags = r.u32();
    let _total = r.u64();
    let cols = r.u64() as usize;
    let rows = r.u64() as usize;
    let [spacing, mass, stiffness, viscosity, dt, rest_ratio] = [(); 6].map(|_| r.f32());
    let boundary = r.u32();
    let acceleration = [(); 3].map(|_| r.f32());
    let steps = r.u64();
    let model_time = r.f64();
    let bounds = [(); 3].map(|_| r.f32());
    let time_scale = r.f32();
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
        time_scale,
    };
    Head {
        flags,
        params,
        boundary,
        steps,
        model_time,
        bounds,
    }
}

/// Offsets 112 to 136 from version 3, to 152 from version 6: the absorbing frame's width
/// and the bodies' world; from version 6 the hull section's mesh count and length.
pub(super) struct World {
    pub width: u32,
    pub bodies: u32,
    pub next_id: u64,
    pub buoyancy: Buoyancy,
    pub hulls: u64,
    pub hull_bytes: u64,
    /// Entries of the water column (from version 7).
    pub column: u64,
}

pub(super) fn world(r: &mut Reader<'_>, version: u32) -> World {
    let (width, bodies, next_id) = (r.u32(), r.u32(), r.u64());
    let gravity = r.f32();
    let density = r.f32();
    let (hulls, hull_bytes) = if version < 6 {
        (0, 0)
    } else {
        (r.u64(), r.u64())
    };
    let column = if version < 7 { 0 } else { r.u64() };
    World {
        width,
        bodies,
        next_id,
        buoyancy: Buoyancy { gravity, density },
        hulls,
        hull_bytes,
        column,
    }
}

/// The per-node arrays, in every version, borrowed.
pub(super) struct Nodes<'a> {
    pub positions: [Le<'a>; 3],
    pub velocities: [Le<'a>; 3],
    pub forces: [Le<'a>; 3],
    pub mass: Le<'a>,
    pub viscosity: Le<'a>,
    /// One byte per node, checked to be 0 or 1.
    pub pinned: &'a [u8],
    pub rest: [Le<'a>; 4],
    pub stiffness: [Le<'a>; 4],
}

pub(super) fn nodes<'a>(r: &mut Reader<'a>, n: usize) -> Result<Nodes<'a>> {
    let positions = [(); 3].map(|_| floats(r, n));
    let velocities = [(); 3].map(|_| floats(r, n));
    let forces = [(); 3].map(|_| floats(r, n));
    let mass = floats(r, n);
    let viscosity = floats(r, n);
    let pinned = r.take(n);
    if let Some(i) = pinned.iter().position(|&b| b > 1) {
        return Err(bad(format!(
            "node {i}: pinned flag {} is neither 0 nor 1",
            pinned[i]
        )));
    }
    let mut rest = [Le(&[]); 4];
    let mut stiffness = [Le(&[]); 4];
    for f in 0..4 {
        rest[f] = floats(r, n);
        stiffness[f] = floats(r, n);
    }
    Ok(Nodes {
        positions,
        velocities,
        forces,
        mass,
        viscosity,
        pinned,
        rest,
        stiffness,
    })
}

/// The bodies, from version 3, and from version 6 the hull section after them. Their
/// lengths were checked against the total length (`check_header`).
pub(super) fn bodies<'a>(r: &mut Reader<'a>, world: &World, version: u32) -> Bodies<'a> {
    let count = world.bodies as usize;
    if version < 6 {
        return Bodies::Translating(r.take(count * PER_TRANSLATING));
    }
    let records = r.take(count * PER_BODY);
    let hulls = Hulls {
        count: world.hulls,
        bytes: r.take(world.hull_bytes as usize),
    };
    Bodies::Rigid { records, hulls }
}

pub(super) fn column<'a>(r: &mut Reader<'a>, world: &World) -> ColumnBytes<'a> {
    ColumnBytes::read(r, world.column as usize)
}

/// The 40 bytes before the checksum, from version 4: the window's origin and the clock.
pub(super) struct Tail {
    pub origin: [i64; 2],
    pub owed: f64,
    pub step_cap: (u32, Overflow),
    pub dropped: f64,
}

impl Tail {
    /// What a surface that never moved its window and never ran `advance` has.
    pub const FRESH: Tail = Tail {
        origin: [0, 0],
        owed: 0.0,
        step_cap: (Surface::DEFAULT_MAX_STEPS, Overflow::Drop),
        dropped: 0.0,
    };
}

pub(super) fn tail(r: &mut Reader<'_>) -> Result<Tail> {
    let origin = [(); 2].map(|_| r.u64() as i64);
    let (owed, max_steps) = (r.f64(), r.u32());
    let overflow = match r.u32() {
        0 => Overflow::Drop,
        1 => Overflow::Carry,
        other => return Err(bad(format!("step cap overflow {other} is not 0 or 1"))),
    };
    Ok(Tail {
        origin,
        owed,
        step_cap: (max_steps, overflow),
        dropped: r.f64(),
    })
}

/// The boundary a code and a frame width stand for (the width is 0 but for `absorbing`).
pub(super) fn boundary(code: u32, width: u32) -> Result<Boundary> {
    match (code, width) {
        (0, 0) => Ok(Boundary::Pinned),
        (1, 0) => Ok(Boundary::Free),
        (2, width) => Ok(Boundary::Absorbing {
            width: width as usize,
        }),
        (0 | 1, width) => Err(bad(format!(
            "a frame width of {width} is stored for a boundary without one"
        ))),
        (other, _) => Err(unknown_boundary(other)),
    }
}

pub(super) fn unknown_boundary(code: u32) -> crate::error::Error {
    bad(format!(
        "unknown boundary code {code} (0 = pinned, 1 = free, 2 = absorbing from version 3)"
    ))
}

/// The sections of versions 4 to 6 (one layout for 4 and 5, version 4 keeping the
/// acceleration, the buoyancy and the bodies in model time; version 6 with the hull
/// section's header fields and rigid bodies), borrowed from the bytes.
pub(crate) struct Layout<'a> {
    pub head: Head,
    pub world: World,
    pub nodes: Nodes<'a>,
    pub bodies: Bodies<'a>,
    pub column: ColumnBytes<'a>,
    pub tail: Tail,
}

impl<'a> Layout<'a> {
    pub fn read(r: &mut Reader<'a>, version: u32) -> Result<Self> {
        let head = head(r);
        let world = world(r, version);
        let n = head.params.cols * head.params.rows; // bounded by check_header
        let nodes = nodes(r, n)?;
        let bodies = bodies(r, &world, version);
        let column = column(r, &world);
        let tail = tail(r)?;
        Ok(Layout {
            head,
            world,
            nodes,
            bodies,
            column,
            tail,
        })
    }

    /// Every field but the arrays and bodies, checked where the bytes alone can say.
    pub fn scalars(&self) -> Result<Scalars> {
        let (head, world, tail) = (&self.head, &self.world, &self.tail);
        let boundary = boundary(head.boundary, world.width)?;
        if head.flags & !FLAG_FORCES_PENDING != 0 {
            return Err(bad(format!(
                "unknown flags {:#x}: written by an incompatible writer",
                head.flags
            )));
        }
        Ok(Scalars {
            params: Params {
                boundary,
                ..head.params
            },
            steps: head.steps,
            model_time: head.model_time,
            bounds: head.bounds,
            forces_pending: head.flags & FLAG_FORCES_PENDING != 0,
            next_floater_id: world.next_id,
            buoyancy: world.buoyancy,
            origin_cells: tail.origin,
            owed_time: tail.owed,
            step_cap: tail.step_cap,
            dropped_seconds: tail.dropped,
        })
    }

    /// The plain data, its arrays copied out of the bytes.
    pub fn to_snapshot(&self) -> Result<Snapshot> {
        let s = self.scalars()?;
        let mut floaters = Vec::new();
        self.bodies.decode_into(&mut floaters, &[])?;
        let mut column = Vec::new();
        self.column.decode_into(&mut column);
        let n = &self.nodes;
        let vecs = |a: [Le<'_>; 3]| a.map(Le::to_vec);
        Ok(Snapshot {
            params: s.params,
            steps: s.steps,
            model_time: s.model_time,
            min_mass: s.bounds[0],
            max_stiffness: s.bounds[1],
            max_viscosity: s.bounds[2],
            forces_pending: s.forces_pending,
            positions: vecs(n.positions),
            velocities: vecs(n.velocities),
            forces: vecs(n.forces),
            mass: n.mass.to_vec(),
            viscosity: n.viscosity.to_vec(),
            pinned: n.pinned.iter().map(|&b| b == 1).collect(),
            rest: n.rest.map(Le::to_vec),
            stiffness: n.stiffness.map(Le::to_vec),
            floaters,
            next_floater_id: s.next_floater_id,
            buoyancy: s.buoyancy,
            origin_cells: s.origin_cells,
            owed_time: s.owed_time,
            step_cap: s.step_cap,
            dropped_seconds: s.dropped_seconds,
            column,
        })
    }
}
