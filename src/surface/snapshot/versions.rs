//! One decoder per format version, each reading its own layout and upgrading what it read
//! to the next version, until the current one.
//!
//! | version | adds | upgrade to the next |
//! |---|---|---|
//! | 1 | the header (112 bytes) with a reserved word at offset 108, the node arrays | the reserved word must be 0; the default time scale |
//! | 2 | the time scale at offset 108 | no bodies, no absorbing frame, the default buoyancy |
//! | 3 | the frame width, bodies and buoyancy (header of 136 bytes), the bodies after the arrays | the window's origin `[0, 0]`, a fresh clock |
//! | 4 | the window's origin and the clock before the checksum | the acceleration, buoyancy and bodies from model time to seconds |
//! | 5 | (the layout of 4, in seconds) | bodies upright, not spinning, not twisted, with their shape's inertia |
//! | 6 | rigid bodies (orientation, angular velocity, torques, inertia; 176 bytes each), hull meshes after them (header of 152 bytes) | an empty water column |
//! | 7 | the water column under the bodies (its entry count at offset 152, header of 160 bytes; its entries after the hull meshes) | (current) |
//!
//! Each step is written once, so a snapshot of version 1 passes every upgrade in turn and
//! a new version adds one decoder and one upgrade.

use super::read::{self, Head, Layout, Nodes, Tail, World};
use super::{bad, Snapshot};
use crate::error::Result;
use crate::floater::{Buoyancy, Floater, FloaterId};
use crate::params::Params;
use crate::surface::bodies::section::{Bodies, ColumnBytes};
use crate::surface::bytes::Reader;
use glam::{Quat, Vec3};

/// Decodes the bytes after the version field (`r`) of a snapshot of `version`, whose
/// framing has been checked, into the current version's plain data.
pub(super) fn decode(version: u32, mut r: Reader<'_>) -> Result<Snapshot> {
    let r = &mut r;
    let snapshot = match version {
        1 => v5_to_6(v4_to_5(v3_to_4(v2_to_3(v1_to_2(v1(r)?)?)?))?),
        2 => v5_to_6(v4_to_5(v3_to_4(v2_to_3(v2(r)?)?))?),
        3 => v5_to_6(v4_to_5(v3_to_4(v3(r)?))?),
        4 => v5_to_6(v4_to_5(Layout::read(r, 4)?)?),
        5 => v5_to_6(v5(r)?),
        6 => v6(r)?,
        _ => v7(r)?,
    };
    debug_assert!(r.at_end(), "version {version} read to its end");
    Ok(snapshot)
}

/// What versions 1 and 2 store.
struct V2<'a> {
    head: Head,
    nodes: Nodes<'a>,
}

/// What version 3 stores.
struct V3<'a> {
    head: Head,
    world: World,
    nodes: Nodes<'a>,
    bodies: Bodies<'a>,
}

/// Version 1: version 2's layout, with a reserved word where the time scale is.
fn v1<'a>(r: &mut Reader<'a>) -> Result<V2<'a>> {
    v2(r)
}

fn v1_to_2(v1: V2<'_>) -> Result<V2<'_>> {
    let mut v2 = v1;
    if v2.head.params.time_scale.to_bits() != 0 {
        return Err(bad(
            "the reserved header field of a version 1 snapshot is not 0: written by an incompatible writer",
        ));
    }
    v2.head.params.time_scale = Params::default().time_scale;
    Ok(v2)
}

/// Version 2: the header of 112 bytes and the node arrays.
fn v2<'a>(r: &mut Reader<'a>) -> Result<V2<'a>> {
    let head = read::head(r);
    let n = head.params.cols * head.params.rows; // bounded by check_header
    let nodes = read::nodes(r, n)?;
    Ok(V2 { head, nodes })
}

fn v2_to_3(v2: V2<'_>) -> Result<V3<'_>> {
    if v2.head.boundary == 2 {
        return Err(read::unknown_boundary(2));
    }
    let world = World {
        width: 0,
        bodies: 0,
        next_id: 0,
        buoyancy: Buoyancy::default(),
        hulls: 0,
        hull_bytes: 0,
        column: 0,
    };
    Ok(V3 {
        head: v2.head,
        world,
        nodes: v2.nodes,
        bodies: Bodies::NONE,
    })
}

/// Version 3: the world after the header, the bodies after the arrays.
fn v3<'a>(r: &mut Reader<'a>) -> Result<V3<'a>> {
    let head = read::head(r);
    let world = read::world(r, 3);
    let n = head.params.cols * head.params.rows;
    let nodes = read::nodes(r, n)?;
    let bodies = read::bodies(r, &world, 3);
    Ok(V3 {
        head,
        world,
        nodes,
        bodies,
    })
}

fn v3_to_4(v3: V3<'_>) -> Layout<'_> {
    Layout {
        head: v3.head,
        world: v3.world,
        nodes: v3.nodes,
        bodies: v3.bodies,
        column: ColumnBytes::NONE,
        tail: Tail::FRESH,
    }
}

// Version 4 is read by `Layout::read`: version 3 and the tail.

/// Version 4's layout in model time, converted to seconds.
fn v4_to_5(v4: Layout<'_>) -> Result<Snapshot> {
    let snap = v4.to_snapshot()?;
    let (params, floaters, buoyancy) = in_seconds(snap.params, snap.floaters, snap.buoyancy);
    Ok(Snapshot {
        params,
        floaters,
        buoyancy,
        ..snap
    })
}

/// Version 5: version 4's layout in seconds.
fn v5(r: &mut Reader<'_>) -> Result<Snapshot> {
    Layout::read(r, 5)?.to_snapshot()
}

/// Version 5's bodies only translated: they are upright and not spinning, no torque is
/// pending or was felt, and their mass is spread evenly (the shape's inertia).
fn v5_to_6(mut snap: Snapshot) -> Snapshot {
    for (_, body) in &mut snap.floaters {
        body.orientation = Quat::IDENTITY;
        body.angular_velocity = Vec3::ZERO;
        body.push_torque = Vec3::ZERO;
        body.water_torque = Vec3::ZERO;
        body.inertia = None;
    }
    snap
}

/// Version 6: rigid bodies and their hull meshes. Upgraded to 7 with an empty water
/// column (a body resting in it then loads the water at first, and the column takes the
/// load up over a few seconds).
fn v6(r: &mut Reader<'_>) -> Result<Snapshot> {
    Layout::read(r, 6)?.to_snapshot()
}

/// Version 7, the current one: the water column under the bodies.
fn v7(r: &mut Reader<'_>) -> Result<Snapshot> {
    Layout::read(r, 7)?.to_snapshot()
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
