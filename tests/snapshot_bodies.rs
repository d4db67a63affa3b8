//! Snapshots of rigid floating bodies: every field of a turned, spinning body back bit for
//! bit, hull meshes stored once and shared again after loading, older versions loading
//! upright and still, damaged hull sections refused without a change, rollback that
//! neither rebuilds meshes nor allocates, and a state hash that sees all of it.

mod common;

use glam::{Mat3, Quat, Vec3};
use springwater::body::{BoatShape, Hull};
use springwater::{Error, Floater, FloaterId, Params, Shape, Snapshot, Surface};
use std::alloc::{GlobalAlloc, Layout, System};
use std::cell::Cell;
use std::sync::Arc;

thread_local! {
    /// Allocations made by this thread.
    static ALLOCATIONS: Cell<usize> = const { Cell::new(0) };
}

/// Counts one allocation on this thread (none while the thread's locals are torn down).
fn count() {
    let _ = ALLOCATIONS.try_with(|n| n.set(n.get() + 1));
}

/// The system allocator, counting each thread's allocations (tests run on threads of
/// their own, so a test counts only what it does).
struct Counting;

// SAFETY: every call is forwarded unchanged to `System`, which upholds the contract.
unsafe impl GlobalAlloc for Counting {
    unsafe fn alloc(&self, layout: Layout) -> *mut u8 {
        count();
        System.alloc(layout)
    }
    unsafe fn alloc_zeroed(&self, layout: Layout) -> *mut u8 {
        count();
        System.alloc_zeroed(layout)
    }
    unsafe fn realloc(&self, ptr: *mut u8, layout: Layout, size: usize) -> *mut u8 {
        count();
        System.realloc(ptr, layout, size)
    }
    unsafe fn dealloc(&self, ptr: *mut u8, layout: Layout) {
        System.dealloc(ptr, layout)
    }
}

#[global_allocator]
static COUNTING: Counting = Counting;

/// How many allocations `f` makes on this thread.
fn allocations(f: impl FnOnce()) -> usize {
    let before = ALLOCATIONS.with(Cell::get);
    f();
    ALLOCATIONS.with(Cell::get) - before
}

/// A small boat hull (224 triangles), centred on its centroid.
fn boat_hull() -> Hull {
    let mut shape = BoatShape::default();
    (shape.stations, shape.segments) = (12, 4);
    shape.hull().unwrap().centred().unwrap()
}

/// A box hull, centred.
fn box_hull() -> Hull {
    Hull::cuboid([1.0, 0.4, 0.6]).unwrap()
}

/// The bodies of [`fleet`], in the order they were added.
struct Fleet {
    crate_: FloaterId,
    ball: FloaterId,
    boats: [FloaterId; 2],
    raft: FloaterId,
}

/// A pool with a turned, spinning box, a ball, two boats sharing one hull (the first with
/// an inertia of its own) and a raft of another hull, a few steps in, with pushes and a
/// push's torque pending.
fn fleet() -> (Surface, Fleet) {
    let mut p = Params::with_size(40, 32);
    p.dt = 0.2;
    let mut s = Surface::new(p).unwrap();
    let density = s.buoyancy().density;
    let afloat = |mut body: Floater| {
        body.mass = 0.5 * density * body.shape.volume();
        body
    };
    let mut crate_ = afloat(Floater::cuboid([1.0, 0.5, 0.75], 1.0, [8.0, 0.0, 8.0]));
    crate_.orientation = (Quat::from_rotation_y(0.4) * Quat::from_rotation_x(0.2)).normalize();
    crate_.angular_velocity = Vec3::new(0.3, 1.5, -0.2);
    let ball = afloat(Floater::sphere(1.2, 1.0, [30.0, 0.0, 8.0]));
    let hull = Arc::new(boat_hull());
    let mut first = afloat(Floater::with_hull(
        Arc::clone(&hull),
        1.0,
        [12.0, 0.0, 20.0],
    ));
    first.inertia = Some(first.shape.inertia(first.mass) * 1.25);
    let mut second = afloat(Floater::with_hull(hull, 1.0, [26.0, 0.0, 22.0]));
    second.orientation = Quat::from_rotation_y(1.0);
    let raft = afloat(Floater::with_hull(
        Arc::new(box_hull()),
        1.0,
        [33.0, 0.0, 27.0],
    ));
    let mut add = |body| s.add_floater(body).unwrap();
    let ids = Fleet {
        crate_: add(crate_),
        ball: add(ball),
        boats: [add(first), add(second)],
        raft: add(raft),
    };
    s.drop_at(20.0, 16.0, 0.5, 3.0).unwrap();
    s.step_n(15).unwrap();
    s.push_floater(ids.ball, [4.0, 0.0, -2.0]).unwrap();
    s.push_floater_at(ids.boats[0], [0.0, 0.0, 6.0], [14.0, 0.3, 20.0])
        .unwrap();
    (s, ids)
}

/// Every bit of a body: its shape (a hull's vertices and triangles), mass, inertia, drag,
/// pose, velocities, pushes and the water's force and torque.
fn bits(body: &Floater) -> Vec<u32> {
    let b = |v: f32| v.to_bits();
    let mut out = vec![b(body.mass), b(body.drag)];
    out.extend(body.orientation.to_array().map(b));
    for v in [
        body.position,
        body.velocity,
        body.angular_velocity,
        body.push,
        body.push_torque,
        body.water_force,
        body.water_torque,
    ] {
        out.extend(v.to_array().map(b));
    }
    match body.inertia {
        Some(i) => {
            out.push(1);
            out.extend(i.to_cols_array().map(b));
        }
        None => out.push(0),
    }
    match &body.shape {
        Shape::Sphere { radius } => out.extend([0, b(*radius)]),
        Shape::Box { half_extents } => {
            out.push(1);
            out.extend(half_extents.to_array().map(b));
        }
        Shape::Hull(hull) => {
            out.push(2);
            out.extend(hull.vertices().iter().flatten().map(|&v| b(v)));
            out.extend(hull.triangles().iter().flatten());
        }
        other => panic!("a shape this test does not know: {other:?}"),
    }
    out
}

/// A body's hull.
fn hull(s: &Surface, id: FloaterId) -> Arc<Hull> {
    match &s.floater(id).unwrap().shape {
        Shape::Hull(hull) => Arc::clone(hull),
        other => panic!("not a hull: {other:?}"),
    }
}

/// Where the bodies' records start: after the 160 bytes of the header and 77 per node.
fn bodies_at(s: &Surface) -> usize {
    160 + 77 * s.node_count()
}

/// Bytes a mesh takes in the hull section: its two counts, 12 per vertex and per triangle.
fn mesh_len(hull: &Hull) -> usize {
    8 + 12 * (hull.vertices().len() + hull.triangles().len())
}

#[test]
fn rigid_bodies_and_shared_hulls_come_back_bit_for_bit() {
    let (mut s, ids) = fleet();
    // The test means something: the state is turned, spinning, pushed and twisted.
    let crate_ = s.floater(ids.crate_).unwrap();
    assert!(crate_.orientation.angle_between(Quat::IDENTITY) > 0.1);
    assert!(crate_.angular_velocity.length() > 0.1);
    assert!(crate_.water_torque.length() > 0.0);
    assert!(s.floater(ids.boats[0]).unwrap().push_torque.length() > 0.0);
    assert!(s.floater(ids.boats[0]).unwrap().inertia.is_some());

    let bytes = s.to_bytes();
    // 5 bodies of 176 bytes, and two meshes: the boats' once.
    let meshes = mesh_len(&boat_hull()) + mesh_len(&box_hull());
    assert_eq!(
        bytes.len(),
        204 + 77 * s.node_count() + 176 * 5 + meshes + 32 * column_entries(&bytes)
    );

    let loaded = Surface::from_bytes(&bytes).unwrap();
    let plain = Surface::from_snapshot(s.snapshot()).unwrap();
    let read = Surface::load(&bytes[..]).unwrap();
    let mut restored = fleet().0;
    restored.step_n(4).unwrap();
    restored.restore(&bytes).unwrap();
    for (what, t) in [
        ("from_bytes", &loaded),
        ("from_snapshot", &plain),
        ("load", &read),
        ("restore", &restored),
    ] {
        assert_eq!(t.to_bytes(), bytes, "{what}");
        assert_eq!(t.floaters().len(), 5, "{what}");
        for (id, body) in s.floaters() {
            assert_eq!(bits(t.floater(id).unwrap()), bits(body), "{what}: {id:?}");
        }
        let [a, b] = ids.boats.map(|id| hull(t, id));
        assert!(Arc::ptr_eq(&a, &b), "{what}: the boats share one mesh");
        assert!(!Arc::ptr_eq(&a, &hull(t, ids.raft)), "{what}");
    }
    // The plain data shares it too.
    let snap = Snapshot::from_bytes(&bytes).unwrap();
    let boats: Vec<_> = snap.floaters[2..4]
        .iter()
        .map(|(_, body)| match &body.shape {
            Shape::Hull(hull) => Arc::clone(hull),
            other => panic!("{other:?}"),
        })
        .collect();
    assert!(Arc::ptr_eq(&boats[0], &boats[1]));
    assert_eq!(snap.to_bytes().unwrap(), bytes);

    // And a loaded surface continues as the original does.
    let mut loaded = loaded;
    s.step_n(20).unwrap();
    loaded.step_n(20).unwrap();
    assert_eq!(loaded.to_bytes(), s.to_bytes());
}

#[test]
fn rollback_reuses_the_meshes_and_allocates_nothing() {
    let (mut s, ids) = fleet();
    let boat = hull(&s, ids.boats[0]);
    let raft = hull(&s, ids.raft);
    // The counter counts.
    assert!(allocations(|| drop(std::hint::black_box(vec![1u8; 64]))) > 0);
    let mut saved = Vec::new();
    // Warm: the buffer has held a save, the body list a restore.
    s.save_into(&mut saved);
    s.step().unwrap();
    s.restore(&saved).unwrap();
    for frame in 0..4 {
        assert_eq!(allocations(|| s.save_into(&mut saved)), 0, "frame {frame}");
        s.step_n(2).unwrap();
        assert_eq!(
            allocations(|| s.restore(&saved).unwrap()),
            0,
            "frame {frame}"
        );
        assert_eq!(s.to_bytes(), saved);
        for id in ids.boats {
            assert!(Arc::ptr_eq(&hull(&s, id), &boat), "frame {frame}");
        }
        assert!(Arc::ptr_eq(&hull(&s, ids.raft), &raft), "frame {frame}");
    }

    // A body that changed its mesh since the save gets the stored one back, shared with
    // the body that still holds it; with no body holding it, a new mesh, shared again.
    let mut changed = s.floater(ids.boats[1]).unwrap().clone();
    changed.shape = Shape::Hull(Arc::new(box_hull()));
    s.set_floater(ids.boats[1], changed).unwrap();
    s.restore(&saved).unwrap();
    assert_eq!(s.to_bytes(), saved);
    assert!(Arc::ptr_eq(&hull(&s, ids.boats[1]), &boat));
    for id in ids.boats {
        s.remove_floater(id).unwrap();
    }
    s.restore(&saved).unwrap();
    assert_eq!(s.to_bytes(), saved);
    let [a, b] = ids.boats.map(|id| hull(&s, id));
    assert!(Arc::ptr_eq(&a, &b) && !Arc::ptr_eq(&a, &boat));
}

/// Reads a `u32` or the bits of an `f32` at byte `at`.
fn word(b: &[u8], at: usize) -> u32 {
    u32::from_le_bytes(b[at..at + 4].try_into().unwrap())
}

fn put(b: &mut [u8], at: usize, v: u32) {
    b[at..at + 4].copy_from_slice(&v.to_le_bytes());
}

/// A snapshot written by version 5 (before bodies rotated): water, a ball and a box,
/// pushed, stepped. It loads with every stored field as stored, read here at version 5's
/// offsets, and the bodies upright, not spinning, untwisted, of uniform density.
#[test]
fn version_5_snapshots_load_upright_and_still() {
    let v5: &[u8] = include_bytes!("fixtures/snapshot-v5-bodies.bin");
    assert_eq!(word(v5, 8), 5);
    let n = (word(v5, 24) * word(v5, 32)) as usize;
    let count = word(v5, 116) as usize;
    assert_eq!(count, 2);
    let loaded = Surface::from_bytes(v5).unwrap();
    let mut restored = fleet().0;
    restored.restore(v5).unwrap();
    for s in [&loaded, &restored] {
        assert_eq!(s.floaters().len(), count);
        for (k, (id, body)) in s.floaters().enumerate() {
            let at = 136 + 77 * n + 80 * k;
            let stored = |i: usize| word(v5, at + 12 + 4 * i);
            assert_eq!(
                id.to_raw(),
                u64::from_le_bytes(v5[at..at + 8].try_into().unwrap())
            );
            let (size, rest) = match &body.shape {
                Shape::Sphere { radius } => ([radius.to_bits(), 0, 0], word(v5, at + 8) == 0),
                Shape::Box { half_extents } => (
                    half_extents.to_array().map(f32::to_bits),
                    word(v5, at + 8) == 1,
                ),
                other => panic!("{other:?}"),
            };
            assert!(rest, "body {k}: shape code");
            assert_eq!(size, [0, 1, 2].map(stored), "body {k}");
            let fields = [body.mass, body.drag]
                .into_iter()
                .chain(
                    [body.position, body.velocity, body.push, body.water_force]
                        .into_iter()
                        .flat_map(|v| v.to_array()),
                )
                .map(f32::to_bits);
            assert!(fields.eq((3..17).map(stored)), "body {k}");
            assert_eq!(body.orientation, Quat::IDENTITY);
            assert_eq!(body.angular_velocity, Vec3::ZERO);
            assert_eq!(body.push_torque, Vec3::ZERO);
            assert_eq!(body.water_torque, Vec3::ZERO);
            assert_eq!(body.inertia, None);
        }
        assert!(s.floaters().any(|(_, b)| b.push.length() > 0.0));
        // Nothing else changed: saved again, in version 5's layout, the same bytes.
        assert_eq!(common::as_version_5(&s.to_bytes(), n, count), v5);
    }
}

/// [`fleet`]'s surface saved, with `edit` made to the bytes and the checksum fixed.
/// The water column's entry count in a snapshot's header (offset 152).
fn column_entries(b: &[u8]) -> usize {
    u64::from_le_bytes(b[152..160].try_into().unwrap()) as usize
}

/// Where the hull section ends: before the water column's entries and the 44 bytes of
/// the window's origin, the clock and the checksum.
fn hulls_end(b: &[u8]) -> usize {
    b.len() - 44 - 32 * column_entries(b)
}

fn damaged(s: &Surface, edit: &dyn Fn(&mut Vec<u8>, usize)) -> Vec<u8> {
    let mut b = s.to_bytes();
    edit(&mut b, bodies_at(s));
    common::fix_crc(&mut b);
    b
}

/// Adds `delta` to the `u32` at `at`.
fn add_u32(b: &mut [u8], at: usize, delta: i32) {
    put(b, at, word(b, at).wrapping_add_signed(delta));
}

/// Adds `delta` to the `u64` at `at`.
fn add_u64(b: &mut [u8], at: usize, delta: i64) {
    let v = u64::from_le_bytes(b[at..at + 8].try_into().unwrap());
    b[at..at + 8].copy_from_slice(&v.wrapping_add_signed(delta).to_le_bytes());
}

#[test]
fn damaged_hull_sections_are_refused_and_change_nothing() {
    let (s, ids) = fleet();
    let boat = mesh_len(&boat_hull());
    // Record offsets (the format's documentation): the hull index at 132, the inertia
    // flag at 136 and its entries at 140; a hull body's size fields at 12.
    let record = |bodies: usize, k: usize| bodies + 176 * k;
    let section = |bodies: usize| bodies + 176 * 5;
    type Edit = Box<dyn Fn(&mut Vec<u8>, usize)>;
    // Body `k`'s word at `offset` set to `value`.
    let set = |k: usize, offset: usize, value: u32| -> Edit {
        Box::new(move |b, at| put(b, record(at, k) + offset, value))
    };
    let cases: Vec<(&str, &str, Edit)> = vec![
        (
            "the section's length one vertex longer",
            "inconsistent lengths",
            Box::new(|b, _| add_u64(b, 144, 12)),
        ),
        (
            "a vertex count past the section's end",
            "need",
            Box::new(move |b, at| add_u32(b, section(at), 1000)),
        ),
        (
            "a vertex count one short",
            "hull 0",
            Box::new(move |b, at| add_u32(b, section(at), -1)),
        ),
        (
            "bytes after the last mesh, counted in both lengths",
            "after its last hull",
            Box::new(|b, _| {
                let end = hulls_end(b);
                b.splice(end..end, [0; 12]);
                add_u64(b, 144, 12);
                add_u64(b, 16, 12);
            }),
        ),
        ("an index out of range", "out of range", set(4, 132, 2)),
        (
            "an index used before its turn",
            "order bodies first use them",
            set(2, 132, 1),
        ),
        ("a mesh no body uses", "no body uses", set(4, 132, 0)),
        (
            "an open mesh (the raft's last triangle gone)",
            "open",
            Box::new(move |b, at| {
                let raft = section(at) + boat;
                add_u32(b, raft + 4, -1);
                let end = hulls_end(b);
                b.drain(end - 12..end);
                add_u64(b, 144, -12);
                add_u64(b, 16, -12);
            }),
        ),
        (
            "the boat's mesh stored again for the raft",
            "repeats hull 0",
            Box::new(move |b, at| {
                let (first, end) = (section(at), hulls_end(b));
                let copy = b[first..first + boat].to_vec();
                let longer = boat as i64 - (end - first - boat) as i64;
                b.splice(first + boat..end, copy);
                add_u64(b, 144, longer);
                add_u64(b, 16, longer);
            }),
        ),
        ("a hull index on a ball", "not a hull", set(1, 132, 1)),
        (
            "a size on a hull",
            "size fields",
            set(3, 12, 1.0f32.to_bits()),
        ),
        ("inertia flag 2", "inertia flag", set(2, 136, 2)),
        (
            "inertia entries without the flag",
            "without the inertia flag",
            set(3, 140, 1.0f32.to_bits()),
        ),
        (
            "an orientation that is not a unit quaternion",
            "orientation",
            set(0, 92, 2.0f32.to_bits()),
        ),
    ];
    let mut target = s.clone();
    target.step_n(3).unwrap();
    let before = target.to_bytes();
    let meshes = [ids.boats[0], ids.raft].map(|id| hull(&target, id));
    for (what, expected, edit) in &cases {
        let bad = damaged(&s, edit);
        let message = match Surface::from_bytes(&bad) {
            Err(Error::Snapshot(m)) => m,
            other => panic!("{what}: {other:?}"),
        };
        assert!(message.contains(expected), "{what}: {message}");
        assert!(!message.contains('\n'), "{what}: one line: {message}");
        let plain = Snapshot::from_bytes(&bad).and_then(Surface::from_snapshot);
        assert!(plain.is_err(), "{what}");
        assert!(Surface::load(&bad[..]).is_err(), "{what}");
        let err = target.restore(&bad).unwrap_err();
        assert_eq!(
            err.to_string(),
            Error::Snapshot(message).to_string(),
            "{what}"
        );
        assert_eq!(target.to_bytes(), before, "{what}: changed nothing");
        let now = [ids.boats[0], ids.raft].map(|id| hull(&target, id));
        assert!(
            now.iter().zip(&meshes).all(|(a, b)| Arc::ptr_eq(a, b)),
            "{what}"
        );
    }
    // The undamaged bytes are fine.
    target.restore(&s.to_bytes()).unwrap();
}

#[test]
fn the_hash_sees_the_rigid_fields_and_the_meshes_not_how_they_are_shared() {
    let (s, ids) = fleet();
    let base = s.state_hash();
    type Edit = Box<dyn Fn(&mut Floater)>;
    let edits: Vec<(&str, FloaterId, Edit)> = vec![
        (
            "an orientation",
            ids.crate_,
            Box::new(|b| b.orientation = (b.orientation * Quat::from_rotation_z(1e-3)).normalize()),
        ),
        (
            "an angular velocity",
            ids.ball,
            Box::new(|b| b.angular_velocity.y += 0.01),
        ),
        (
            "a push's torque",
            ids.crate_,
            Box::new(|b| b.push_torque = Vec3::new(0.0, 0.5, 0.0)),
        ),
        (
            "an inertia set",
            ids.boats[1],
            Box::new(|b| b.inertia = Some(b.shape.inertia(b.mass))),
        ),
        (
            "an inertia changed",
            ids.boats[0],
            Box::new(|b| b.inertia = b.inertia.map(|i| i * 1.01)),
        ),
        (
            "a mesh",
            ids.boats[1],
            Box::new(|b| {
                let mut wider = BoatShape::default();
                (wider.stations, wider.segments, wider.beam) = (12, 4, 2.01);
                b.shape = Shape::Hull(Arc::new(wider.hull().unwrap().centred().unwrap()));
            }),
        ),
        (
            "a box turned into the same box as a mesh",
            ids.crate_,
            Box::new(|b| b.shape = Shape::Hull(Arc::new(Hull::cuboid([1.0, 0.5, 0.75]).unwrap()))),
        ),
    ];
    for (what, id, edit) in edits {
        let mut t = s.clone();
        let mut body = t.floater(id).unwrap().clone();
        edit(&mut body);
        t.set_floater(id, body).unwrap();
        assert_ne!(t.state_hash(), base, "{what}");
        t.restore(&s.to_bytes()).unwrap();
        assert_eq!(t.state_hash(), base, "{what}: restored");
    }
    // The boats holding equal meshes of their own instead of one shared: the same state,
    // the same bytes (one mesh stored) and hash.
    let mut t = s.clone();
    let mut second = t.floater(ids.boats[1]).unwrap().clone();
    second.shape = Shape::Hull(Arc::new(boat_hull()));
    t.set_floater(ids.boats[1], second).unwrap();
    assert!(!Arc::ptr_eq(
        &hull(&t, ids.boats[0]),
        &hull(&t, ids.boats[1])
    ));
    assert_eq!(t.to_bytes(), s.to_bytes());
    assert_eq!(t.state_hash(), base);
    // Loaded, they share one again.
    let loaded = Surface::from_bytes(&t.to_bytes()).unwrap();
    assert!(Arc::ptr_eq(
        &hull(&loaded, ids.boats[0]),
        &hull(&loaded, ids.boats[1])
    ));
}

/// With the `serde` feature, the plain data of rigid bodies and their meshes goes through
/// a serde format and back to the same bytes (serde writes each body's mesh in full;
/// saving stores it once again).
#[cfg(feature = "serde")]
#[test]
fn serde_round_trip_keeps_rigid_bodies_and_meshes() {
    let (s, _) = fleet();
    let json = serde_json::to_string(&s.snapshot()).unwrap();
    let back: Snapshot = serde_json::from_str(&json).unwrap();
    let loaded = Surface::from_snapshot(back).unwrap();
    assert_eq!(loaded.to_bytes(), s.to_bytes());
    for (id, body) in s.floaters() {
        assert_eq!(bits(loaded.floater(id).unwrap()), bits(body), "{id:?}");
    }
    // A mesh edited into an invalid one is refused on reading, by the hull's validation.
    let open = json.replacen("\"triangles\":[[", "\"triangles\":[[0,0,0],[", 1);
    assert!(open != json);
    assert!(serde_json::from_str::<Snapshot>(&open).is_err());
}

/// The inertia override is stored with all nine entries: one set slightly off symmetric
/// (within what validation accepts) comes back with its own bits.
#[test]
fn an_inertia_off_symmetric_by_rounding_comes_back_bit_for_bit() {
    let (mut s, ids) = fleet();
    let mut body = s.floater(ids.crate_).unwrap().clone();
    let mut entries = body.shape.inertia(body.mass).to_cols_array();
    // Entries (0, 1) and (1, 0), a rounding apart.
    entries[3] = 0.01 * entries[0];
    entries[1] = entries[3] * (1.0 + 1e-7);
    body.inertia = Some(Mat3::from_cols_array(&entries));
    s.set_floater(ids.crate_, body.clone()).unwrap();
    let loaded = Surface::from_bytes(&s.to_bytes()).unwrap();
    let back = loaded.floater(ids.crate_).unwrap().inertia.unwrap();
    assert_eq!(
        back.to_cols_array().map(f32::to_bits),
        entries.map(f32::to_bits)
    );
    assert_ne!(entries[1].to_bits(), entries[3].to_bits());
}

/// Bodies sharing one mesh in runs and apart, after other bodies: one mesh stored, one
/// `Arc` after loading and after restoring.
#[test]
fn a_mesh_shared_in_runs_and_apart_is_stored_once() {
    let mut p = Params::with_size(40, 32);
    p.dt = 0.2;
    let mut s = Surface::new(p).unwrap();
    let mesh = Arc::new(box_hull());
    let boat = |x: f32, z: f32| Floater::with_hull(Arc::clone(&mesh), 0.4, [x, 0.0, z]);
    let bodies = [
        Floater::sphere(1.0, 1.5, [5.0, 0.0, 5.0]),
        boat(10.0, 8.0),
        boat(14.0, 8.0),
        boat(18.0, 8.0),
        Floater::cuboid([0.5, 0.5, 0.5], 0.4, [25.0, 0.0, 20.0]),
        boat(30.0, 24.0),
    ];
    let ids: Vec<FloaterId> = bodies
        .into_iter()
        .map(|b| s.add_floater(b).unwrap())
        .collect();
    s.step_n(3).unwrap();
    let bytes = s.to_bytes();
    assert_eq!(
        bytes.len(),
        204 + 77 * s.node_count() + 176 * 6 + mesh_len(&mesh) + 32 * column_entries(&bytes)
    );
    let mut restored = s.clone();
    restored.step_n(2).unwrap();
    restored.restore(&bytes).unwrap();
    for t in [Surface::from_bytes(&bytes).unwrap(), restored] {
        assert_eq!(t.to_bytes(), bytes);
        let boats: Vec<_> = [1, 2, 3, 5].map(|k| hull(&t, ids[k])).into();
        assert!(boats.iter().all(|b| Arc::ptr_eq(b, &boats[0])));
    }
}
