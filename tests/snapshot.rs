//! Snapshots: bitwise round trips, identical continuation, and refusal of damaged data.

mod common;

use springwater::Snapshot;
const MAGIC: [u8; 8] = Snapshot::MAGIC;
const VERSION: u32 = Snapshot::VERSION;
use springwater::{Boundary, Error, Family, Params, Spring, SpringId, Surface};

/// A surface that uses every piece of state: drops, velocities, pending forces, per-node
/// mass/viscosity/pins, per-spring tables, steps taken.
fn busy_surface() -> Surface {
    let mut p = Params::with_size(19, 13);
    p.acceleration = [0.0, -5.76, 0.0]; // per second²: 0.01 per unit of model time²
    let mut s = Surface::new(p).unwrap();

    s.drop_at(9.0, 6.0, 1.5, 2.5).unwrap();
    s.drop_at(4.3, 3.7, -0.8, 1.2).unwrap();
    for _ in 0..17 {
        s.step().unwrap();
    }
    s.set_mass(40, 5.5).unwrap();
    s.set_viscosity(41, 0.2).unwrap();
    s.set_pinned(60, true).unwrap();
    s.set_pinned(0, false).unwrap();
    s.set_spring(
        SpringId {
            family: Family::SE,
            origin: 42,
        },
        Spring {
            rest: 0.9,
            stiffness: 6.0,
        },
    )
    .unwrap();
    s.add_velocity(70, [0.0, 0.3, 0.1]).unwrap();
    s.add_force(71, [0.5, -1.0, 0.25]).unwrap();
    s
}

fn run(s: &mut Surface, steps: usize) {
    for _ in 0..steps {
        s.step().unwrap();
    }
}

#[test]
fn round_trip_is_bitwise() {
    let s = busy_surface();
    let bytes = s.to_bytes();
    let back = Surface::from_bytes(&bytes).unwrap();
    assert_eq!(back.to_bytes(), bytes);
    assert_eq!(back.snapshot(), s.snapshot());
    assert_eq!(back.steps(), s.steps());
    assert_eq!(back.time().to_bits(), s.time().to_bits());
    assert_eq!(back.critical_dt().to_bits(), s.critical_dt().to_bits());
    assert_eq!(back.forces(), s.forces());
}

#[test]
fn restored_surface_continues_bitwise_identically() {
    let mut original = busy_surface();
    let mut restored = Surface::from_bytes(&original.to_bytes()).unwrap();
    run(&mut original, 200);
    run(&mut restored, 200);
    assert_eq!(original.to_bytes(), restored.to_bytes());
    // Not trivially equal: the surface moved.
    assert_ne!(original.to_bytes(), busy_surface().to_bytes());
}

#[test]
fn save_then_load_through_io() {
    let s = busy_surface();
    let mut file = Vec::new();
    s.save(&mut file).unwrap();
    file.extend_from_slice(b"trailing game data");
    let mut reader = &file[..];
    let back = Surface::load(&mut reader).unwrap();
    assert_eq!(back.to_bytes(), s.to_bytes());
    assert_eq!(
        reader, b"trailing game data",
        "load reads exactly one snapshot"
    );
}

#[test]
fn restore_replaces_state_and_refusal_changes_nothing() {
    let saved = busy_surface();
    let mut target = Surface::new(Params::with_size(5, 7)).unwrap();
    target.restore(&saved.to_bytes()).unwrap();
    assert_eq!(target.to_bytes(), saved.to_bytes());

    let mut target = Surface::new(Params::with_size(5, 7)).unwrap();
    target.drop_at(2.0, 3.0, 0.5, 1.0).unwrap();
    let before = target.to_bytes();
    let mut bad = saved.to_bytes();
    bad[500] ^= 0x40;
    let err = target.restore(&bad).unwrap_err();
    assert!(matches!(err, Error::Snapshot(_)), "{err}");
    assert!(err.to_string().contains("checksum"), "{err}");
    assert_eq!(target.to_bytes(), before);
}

fn message(bytes: &[u8]) -> String {
    match Surface::from_bytes(bytes) {
        Err(Error::Snapshot(m)) => m,
        other => panic!("expected Error::Snapshot, got {other:?}"),
    }
}

#[test]
fn truncated_snapshots_are_refused_at_every_length() {
    let bytes = Surface::new(Params::with_size(3, 2)).unwrap().to_bytes();
    for len in 0..bytes.len() {
        let m = message(&bytes[..len]);
        assert!(m.contains("truncated"), "length {len}: {m}");
        assert!(Surface::load(&bytes[..len]).is_err());
    }
}

#[test]
fn every_single_bit_flip_is_refused() {
    let bytes = Surface::new(Params::with_size(3, 2)).unwrap().to_bytes();
    for at in 0..bytes.len() {
        for bit in 0..8 {
            let mut b = bytes.clone();
            b[at] ^= 1 << bit;
            assert!(
                Surface::from_bytes(&b).is_err(),
                "flip of bit {bit} at byte {at} accepted"
            );
        }
    }
}

#[test]
fn wrong_magic_and_version_are_refused() {
    let bytes = Surface::new(Params::with_size(4, 4)).unwrap().to_bytes();
    assert_eq!(&bytes[..8], &MAGIC);
    let mut b = bytes.clone();
    b[0] = b'X';
    assert!(message(&b).contains("magic"));
    let mut b = bytes.clone();
    b[8..12].copy_from_slice(&(VERSION + 1).to_le_bytes());
    common::fix_crc(&mut b);
    let m = message(&b);
    assert!(m.contains(&format!("version {}", VERSION + 1)), "{m}");
    b[8..12].copy_from_slice(&0u32.to_le_bytes());
    common::fix_crc(&mut b);
    let m = message(&b);
    assert!(m.contains("version 0"), "{m}");
}

/// The bytes of a snapshot without bodies, frame or shift, in the layout of `version`
/// (1 or 2: the header ends at offset 112 and there is no origin before the checksum).
fn downgrade(current: &[u8], version: u32) -> Vec<u8> {
    let v6 = &common::as_version_6(current)[..];
    let mut b = [&v6[..112], &v6[152..v6.len() - 44], &[0; 4]].concat();
    b[8..12].copy_from_slice(&version.to_le_bytes());
    let len = b.len() as u64;
    b[16..24].copy_from_slice(&len.to_le_bytes());
    common::fix_crc(&mut b);
    b
}

/// A version 1 snapshot (no time scale: the field was reserved and 0) still loads, with
/// the default time scale; a version 1 snapshot with that field set is refused.
#[test]
fn version_1_snapshots_load_with_the_default_time_scale() {
    let mut s = Surface::new(Params::with_size(5, 4).with_time_scale(50.0)).unwrap();
    s.drop_at(2.0, 2.0, 0.5, 1.0).unwrap();
    s.step().unwrap();
    let v2 = downgrade(&s.to_bytes(), 2);
    let loaded = Surface::from_bytes(&v2).unwrap();
    assert_eq!(loaded.params().time_scale, 50.0);
    assert_eq!(loaded.positions(), s.positions());
    assert_eq!(
        downgrade(&loaded.to_bytes(), 2),
        v2,
        "read as version 2, written as 7"
    );
    let mut v1 = v2.clone();
    v1[8..12].copy_from_slice(&1u32.to_le_bytes());
    v1[108..112].copy_from_slice(&0u32.to_le_bytes());
    common::fix_crc(&mut v1);
    let loaded = Surface::from_bytes(&v1).unwrap();
    assert_eq!(loaded.params().time_scale, Params::default().time_scale);
    assert_eq!(loaded.positions(), s.positions());
    let mut bad = v2.clone();
    bad[8..12].copy_from_slice(&1u32.to_le_bytes());
    common::fix_crc(&mut bad);
    assert!(message(&bad).contains("reserved"));
    // A version 2 snapshot with a time scale that validation refuses is refused.
    let mut bad = v2;
    bad[108..112].copy_from_slice(&(-1.0f32).to_le_bytes());
    common::fix_crc(&mut bad);
    assert!(message(&bad).contains("time_scale"), "{}", message(&bad));
}

#[test]
fn lying_lengths_are_refused_without_allocating() {
    let bytes = Surface::new(Params::with_size(4, 4)).unwrap().to_bytes();
    // A header announcing 2^26 nodes (the most a surface may have) over a few hundred bytes:
    // refused as truncated, and the reader path does not allocate the announced size.
    let mut b = bytes.clone();
    b[24..32].copy_from_slice(&(1u64 << 13).to_le_bytes());
    b[32..40].copy_from_slice(&(1u64 << 13).to_le_bytes());
    b[16..24].copy_from_slice(&(204u64 + 77 * (1 << 26)).to_le_bytes());
    assert!(message(&b).contains("truncated"));
    assert!(Surface::load(&b[..]).is_err());
    // A floater count the bytes do not hold.
    let mut b = bytes.clone();
    b[116..120].copy_from_slice(&1u32.to_le_bytes());
    assert!(
        message(&b).contains("inconsistent lengths"),
        "{}",
        message(&b)
    );
    // cols × rows overflowing u64.
    let mut b = bytes.clone();
    b[24..32].copy_from_slice(&u64::MAX.to_le_bytes());
    assert!(message(&b).contains("larger than any surface"));
    // Total length disagreeing with cols × rows.
    let mut b = bytes.clone();
    b[16..24].copy_from_slice(&(bytes.len() as u64 + 77).to_le_bytes());
    assert!(message(&b).contains("inconsistent lengths"));
    // Trailing data after a complete snapshot.
    let mut b = bytes.clone();
    b.push(0);
    assert!(message(&b).contains("trailing"));
}

#[test]
fn invalid_contents_with_a_valid_checksum_are_refused() {
    let s = busy_surface();
    let n = s.node_count();
    let base = s.snapshot();
    type Edit = Box<dyn Fn(&mut Snapshot)>;
    let cases: Vec<(&str, Edit)> = vec![
        ("NaN position", Box::new(|s| s.positions[1][7] = f32::NAN)),
        (
            "infinite velocity",
            Box::new(|s| s.velocities[0][8] = f32::INFINITY),
        ),
        ("NaN force", Box::new(|s| s.forces[2][9] = f32::NAN)),
        ("zero mass", Box::new(|s| s.mass[10] = 0.0)),
        ("subnormal mass", Box::new(|s| s.mass[10] = 1e-40)),
        ("negative viscosity", Box::new(|s| s.viscosity[11] = -1.0)),
        (
            "viscosity above bound",
            Box::new(|s| s.viscosity[11] = 100.0),
        ),
        (
            "moving pinned node",
            Box::new(|s| {
                s.pinned[30] = true;
                s.velocities[1][30] = 0.5
            }),
        ),
        ("negative rest", Box::new(|s| s.rest[0][30] = -1.0)),
        ("zero coefficient", Box::new(|s| s.stiffness[1][30] = 0.0)),
        (
            "coef above bound",
            Box::new(|s| s.stiffness[2][30] = 7.0 * 2.0),
        ),
        (
            "spring off the grid",
            Box::new(move |s| s.stiffness[0][18] = 1.0),
        ),
        ("dt past critical", Box::new(|s| s.params.dt = 1.0)),
        ("invalid param", Box::new(|s| s.params.rest_ratio = 2.0)),
        ("negative time", Box::new(|s| s.model_time = -1.0)),
        (
            "wrong array length",
            Box::new(move |s| s.mass.truncate(n - 1)),
        ),
    ];
    for (what, edit) in cases {
        let mut snap = base.clone();
        edit(&mut snap);
        let err = Surface::from_snapshot(snap.clone()).unwrap_err();
        assert!(matches!(err, Error::Snapshot(_)), "{what}: {err}");
        if snap.mass.len() == n {
            // Through the binary format too (with a valid checksum).
            let err = Surface::from_bytes(&snap.to_bytes().unwrap()).unwrap_err();
            assert!(matches!(err, Error::Snapshot(_)), "{what}: {err}");
        }
    }
    // And the untouched snapshot is fine.
    Surface::from_snapshot(base).unwrap();
}

#[test]
fn derived_state_that_disagrees_with_the_arrays_is_refused() {
    // The bounds behind `critical_dt` and the pending-forces flag are not public fields of
    // `Snapshot`; the binary format carries them, and loading checks them.
    let s = busy_surface();
    let bytes = s.to_bytes();
    assert!(
        s.forces()[2].iter().any(|&f| f != 0.0),
        "the test needs forces"
    );
    let cases: [(&str, usize, [u8; 4]); 4] = [
        ("forces pending flag", 12, 0u32.to_le_bytes()),
        ("min_mass above a node's mass", 96, 100.0f32.to_le_bytes()),
        (
            "max_stiffness below the springs'",
            100,
            1.0f32.to_le_bytes(),
        ),
        ("max_viscosity below the nodes'", 104, 0.0f32.to_le_bytes()),
    ];
    for (what, at, value) in cases {
        let mut b = bytes.clone();
        b[at..at + 4].copy_from_slice(&value);
        common::fix_crc(&mut b);
        let err = Surface::from_bytes(&b).unwrap_err();
        assert!(matches!(err, Error::Snapshot(_)), "{what}: {err}");
    }
    Surface::from_bytes(&bytes).unwrap();
}

#[test]
fn unknown_codes_in_the_header_are_refused() {
    let bytes = Surface::new(Params::with_size(4, 4)).unwrap().to_bytes();
    let mut b = bytes.clone();
    b[64..68].copy_from_slice(&7u32.to_le_bytes()); // boundary
    common::fix_crc(&mut b);
    assert!(message(&b).contains("boundary"));
    let mut b = bytes.clone();
    b[12..16].copy_from_slice(&0x80u32.to_le_bytes()); // flags
    common::fix_crc(&mut b);
    assert!(message(&b).contains("flags"));
    let mut b = bytes;
    let pinned_at = 160 + 11 * 4 * 16;
    b[pinned_at] = 2;
    common::fix_crc(&mut b);
    assert!(message(&b).contains("pinned flag"));
}

#[test]
fn free_boundary_and_snapshot_of_fresh_surface() {
    let mut p = Params::with_size(2, 2);
    p.boundary = Boundary::Free;
    let s = Surface::new(p).unwrap();
    let bytes = s.to_bytes();
    assert_eq!(bytes.len(), 204 + 77 * 4);
    assert_eq!(Surface::from_bytes(&bytes).unwrap().to_bytes(), bytes);
}

#[test]
fn pending_forces_survive_a_snapshot() {
    let mut a = Surface::new(Params::with_size(8, 8)).unwrap();
    a.add_force(27, [0.0, 3.0, 0.0]).unwrap();
    let mut b = Surface::from_bytes(&a.to_bytes()).unwrap();
    a.step().unwrap();
    b.step().unwrap();
    assert_eq!(a.to_bytes(), b.to_bytes());
    assert!(a.positions()[1][27] > 0.0, "the force was applied");
}

/// With the `serde` feature, `Snapshot` goes through any serde format and back bitwise.
#[cfg(feature = "serde")]
#[test]
fn serde_round_trip_is_bitwise() {
    let s = busy_surface();
    let json = serde_json::to_string(&s.snapshot()).unwrap();
    let back: Snapshot = serde_json::from_str(&json).unwrap();
    let restored = Surface::from_snapshot(back).unwrap();
    assert_eq!(restored.to_bytes(), s.to_bytes());
    // Documents written when the stiffness table was called `coef` still load.
    let old = json.replacen("\"stiffness\":[[", "\"coef\":[[", 1);
    assert!(old != json);
    let back: Snapshot = serde_json::from_str(&old).unwrap();
    assert_eq!(
        Surface::from_snapshot(back).unwrap().to_bytes(),
        s.to_bytes()
    );
    // Documents of the versions that kept bodies and accelerations in model time (their
    // clock field was `time`) are refused instead of read in the wrong units.
    let model_units = json.replacen("\"model_time\":", "\"time\":", 1);
    assert!(model_units != json);
    assert!(serde_json::from_str::<Snapshot>(&model_units).is_err());
    // And the same validation applies to what comes in.
    let bad = json.replacen("\"min_mass\":", "\"min_mass\":-", 1);
    let snap: Snapshot = serde_json::from_str(&bad).unwrap();
    assert!(matches!(
        Surface::from_snapshot(snap),
        Err(Error::Snapshot(_))
    ));
}

#[test]
fn a_hand_built_inconsistent_snapshot_is_refused_by_the_encoder() {
    let mut snap = busy_surface().snapshot();
    // Same total length, so only a per-array check can tell.
    snap.positions[0].pop();
    snap.stiffness[3].push(1.0);
    assert!(matches!(snap.to_bytes(), Err(Error::Snapshot(_))));
    assert!(Surface::from_snapshot(snap).is_err());
    let mut snap = busy_surface().snapshot();
    snap.params.cols = usize::MAX;
    assert!(snap.to_bytes().is_err());
}

/// From the `snapshot` fuzz target (fuzz/regressions/snapshot/crash-d540…): the engine
/// reads one shared (c, L0) per spring family while all its springs agree, a summary
/// derived from the tables. A loader that copied the tables but kept the summary of a
/// fresh surface stepped the old coefficients. Engine and reference must agree bitwise
/// after a load, whichever families are uniform.
#[test]
fn loaded_spring_tables_reach_the_engine() {
    let mut s = Surface::new(Params::with_size(12, 9)).unwrap();
    s.drop_at(6.0, 4.0, 1.0, 2.0).unwrap();
    // Every E spring changed alike (still uniform, other values), one S spring changed.
    for origin in 0..s.node_count() {
        let id = SpringId {
            family: Family::E,
            origin,
        };
        if s.spring(id).is_some() {
            s.set_spring(
                id,
                Spring {
                    rest: 0.25,
                    stiffness: 3.0,
                },
            )
            .unwrap();
        }
    }
    s.set_spring(
        SpringId {
            family: Family::S,
            origin: 30,
        },
        Spring {
            rest: 0.7,
            stiffness: 5.0,
        },
    )
    .unwrap();
    let mut snap = s.snapshot();
    let mut engine = Surface::from_snapshot(snap.clone()).unwrap();
    let mut reference = engine.clone();
    reference.set_simd_level(springwater::SimdLevel::Scalar);
    for _ in 0..20 {
        engine.step().unwrap();
        reference.step().unwrap();
    }
    assert_eq!(engine.to_bytes(), reference.to_bytes());
    // Tables edited wholesale in the plain-data snapshot take effect too.
    snap.stiffness[1]
        .iter_mut()
        .filter(|c| **c > 0.0)
        .for_each(|c| *c = 2.0);
    let mut engine = Surface::from_snapshot(snap).unwrap();
    let mut reference = engine.clone();
    reference.set_simd_level(springwater::SimdLevel::Scalar);
    engine.step().unwrap();
    reference.step().unwrap();
    assert_eq!(engine.to_bytes(), reference.to_bytes());
}

/// A reader or writer that fails with `kind`.
struct Broken(std::io::ErrorKind);

impl std::io::Read for Broken {
    fn read(&mut self, _: &mut [u8]) -> std::io::Result<usize> {
        Err(std::io::Error::new(self.0, "the disk went away"))
    }
}

impl std::io::Write for Broken {
    fn write(&mut self, _: &[u8]) -> std::io::Result<usize> {
        Err(std::io::Error::new(self.0, "the disk went away"))
    }
    fn flush(&mut self) -> std::io::Result<()> {
        Ok(())
    }
}

#[test]
fn io_failures_keep_the_io_error_as_their_source() {
    use std::error::Error as _;
    let s = Surface::new(Params::with_size(4, 4)).unwrap();
    let write = s
        .save(Broken(std::io::ErrorKind::PermissionDenied))
        .unwrap_err();
    let read = Surface::load(Broken(std::io::ErrorKind::UnexpectedEof)).unwrap_err();
    for (err, kind, action) in [
        (write, std::io::ErrorKind::PermissionDenied, "write"),
        (read, std::io::ErrorKind::UnexpectedEof, "read"),
    ] {
        assert!(
            matches!(&err, Error::Io { action: a, source } if *a == action && source.kind() == kind),
            "{err:?}"
        );
        let io = err
            .source()
            .and_then(|e| e.downcast_ref::<springwater::IoError>())
            .expect("the I/O error is the source");
        let original = io.source().and_then(|e| e.downcast_ref::<std::io::Error>());
        assert_eq!(original.map(|e| e.kind()), Some(kind));
        assert!(err.to_string().contains("the disk went away"), "{err}");
        assert_eq!(err.clone(), err);
    }
    // Format problems have no source.
    assert!(Surface::from_bytes(b"nonsense")
        .unwrap_err()
        .source()
        .is_none());
}

#[test]
fn library_errors_do_not_speak_command_line_flags() {
    let errors = [
        Surface::new(Params::with_size(100_000, 100_000)).unwrap_err(),
        Surface::new(Params::with_size(1, 5)).unwrap_err(),
        Surface::new(Params::default().with_rest_ratio(2.0)).unwrap_err(),
        Surface::new(Params::default().with_dt(1.0)).unwrap_err(),
    ];
    for e in errors {
        let m = e.to_string();
        assert!(!m.contains("--"), "{m}");
    }
}

#[test]
fn edited_plain_data_is_judged_on_its_values() {
    // The public arrays of a `Snapshot` may be edited; the private bounds and flags follow
    // them when it becomes a surface again.
    let calm = Surface::new(Params::with_size(12, 10)).unwrap();
    let mut snap = calm.snapshot();
    snap.mass[40] = 3.8; // lighter than any mass set so far, still a safe timestep
    snap.forces[1][41] = -0.5; // a force where none was pending
    snap.viscosity[42] = 0.1; // more than any viscosity set so far
    let s = Surface::from_snapshot(snap.clone()).unwrap();
    assert_eq!(s.masses()[40], 3.8);
    assert_eq!(s.forces()[1][41], -0.5);
    assert!(s.critical_dt() < calm.critical_dt());
    // The force is applied by the next step, as a pending force is.
    let mut stepped = s;
    stepped.step().unwrap();
    assert!(stepped.velocities()[1][41] < 0.0);

    // An edit the timestep cannot take is still refused.
    snap.mass[40] = 0.5;
    let err = Surface::from_snapshot(snap).unwrap_err();
    assert!(matches!(err, Error::Snapshot(_)), "{err}");
}

/// Reads the `f32` at byte `at`.
fn f32_at(b: &[u8], at: usize) -> f32 {
    f32::from_le_bytes(b[at..at + 4].try_into().unwrap())
}

/// Writes `v` at byte `at`.
fn put_f32(b: &mut [u8], at: usize, v: f32) {
    b[at..at + 4].copy_from_slice(&v.to_le_bytes());
}

/// The same state in version 4's units: the acceleration (offset 68), gravity (128) and
/// each body's drag, velocity, push and water force in model time. Built from a current
/// snapshot of a surface with `n` nodes and `bodies` bodies at the time scale `ts`.
fn as_version_4(current: &[u8], n: usize, bodies: usize, ts: f32) -> Vec<u8> {
    let v5 = &common::as_version_5(current, n, bodies)[..];
    let mut b = v5.to_vec();
    b[8..12].copy_from_slice(&4u32.to_le_bytes());
    let ts2 = ts * ts;
    for at in [68, 72, 76, 128] {
        put_f32(&mut b, at, f32_at(v5, at) / ts2);
    }
    for k in 0..bodies {
        // id u64, shape u32, size 3 × f32, mass, then drag at +28, position at +32,
        // velocity at +44, push at +56, water force at +68.
        let body = 136 + 77 * n + 80 * k;
        put_f32(&mut b, body + 28, f32_at(v5, body + 28) / ts);
        for c in 0..3 {
            let v = body + 44 + 4 * c;
            put_f32(&mut b, v, f32_at(v5, v) / ts);
            for at in [body + 56 + 4 * c, body + 68 + 4 * c] {
                put_f32(&mut b, at, f32_at(v5, at) / ts2);
            }
        }
    }
    common::fix_crc(&mut b);
    b
}

/// Version 4 kept bodies, gravity and the acceleration in model time: such a snapshot
/// loads with them in seconds, and continues as the surface it was taken from does.
#[test]
fn version_4_snapshots_load_in_seconds() {
    use glam::Vec3;
    use springwater::{Buoyancy, Floater};
    let close = |a: Vec3, b: Vec3| (a - b).abs().max_element() <= 1e-6 * a.abs().max_element();

    // Water alone: the acceleration converts back to the bits the lattice used, so the
    // loaded surface continues bit for bit.
    let p = Params::with_size(24, 20)
        .with_boundary(Boundary::Free)
        .with_acceleration([0.3, -5.76, 1.0 / 3.0]);
    let mut water = Surface::new(p).unwrap();
    water.drop_at(12.0, 10.0, 1.0, 2.0).unwrap();
    water.step_n(7).unwrap();
    let v4 = as_version_4(&water.to_bytes(), water.node_count(), 0, p.time_scale);
    let mut old = Surface::from_bytes(&v4).unwrap();
    for (a, b) in old.params().acceleration.iter().zip(p.acceleration) {
        assert!((a - b).abs() <= 1e-6 * b.abs(), "{a} vs {b}");
    }
    water.step_n(20).unwrap();
    old.step_n(20).unwrap();
    assert_eq!(old.positions(), water.positions());
    assert_eq!(old.velocities(), water.velocities());
    assert_eq!(
        u32::from_le_bytes(old.to_bytes()[8..12].try_into().unwrap()),
        VERSION
    );

    // With bodies: their state comes back in seconds, to the rounding of the conversion.
    let mut s = Surface::new(Params::with_size(24, 20).with_time_scale(30.0)).unwrap();
    s.set_buoyancy(Buoyancy {
        gravity: 80.0,
        density: 1.2,
    })
    .unwrap();
    let mut ball = Floater::sphere(2.0, 10.0, [12.0, 1.0, 10.0]);
    ball.velocity = Vec3::new(2.4, -1.2, 0.7);
    ball.drag = 7.5;
    let a = s.add_floater(ball).unwrap();
    let b = s
        .add_floater(Floater::cuboid([1.0, 0.5, 1.5], 2.0, [6.0, 0.0, 14.0]))
        .unwrap();
    s.step_n(10).unwrap();
    s.push_floater(a, [90.0, 0.0, -45.0]).unwrap();
    let v4 = as_version_4(&s.to_bytes(), s.node_count(), 2, 30.0);
    let mut old = Surface::from_bytes(&v4).unwrap();
    assert!((old.buoyancy().gravity - 80.0).abs() < 1e-4);
    assert_eq!(old.buoyancy().density, 1.2);
    for id in [a, b] {
        let (new, was) = (s.floater(id).unwrap(), old.floater(id).unwrap());
        assert_eq!(was.position, new.position);
        assert!((was.drag - new.drag).abs() <= 1e-6 * new.drag, "{was:?}");
        for (x, y) in [
            (was.velocity, new.velocity),
            (was.push, new.push),
            (was.water_force, new.water_force),
        ] {
            assert!(close(y, x), "{x} vs {y}");
        }
    }
    // Version 4 bodies did not rotate: they load upright and not spinning. The original,
    // turned back so, continues as the loaded one does (both without the water column,
    // which snapshots before version 7 do not hold).
    let mut s = Surface::from_bytes(&common::as_version_6(&s.to_bytes())).unwrap();
    for id in [a, b] {
        let mut body = s.floater(id).unwrap().clone();
        let was = old.floater(id).unwrap();
        assert_eq!(was.orientation, glam::Quat::IDENTITY);
        assert_eq!(was.angular_velocity, Vec3::ZERO);
        body.orientation = glam::Quat::IDENTITY;
        body.angular_velocity = Vec3::ZERO;
        s.set_floater(id, body).unwrap();
    }
    s.step_n(100).unwrap();
    old.step_n(100).unwrap();
    for id in [a, b] {
        let (new, was) = (s.floater(id).unwrap(), old.floater(id).unwrap());
        assert!(
            (was.position - new.position).abs().max_element() < 1e-4,
            "{was:?} vs {new:?}"
        );
    }
    let (y_old, y_new) = (old.positions()[1], s.positions()[1]);
    let worst = y_old
        .iter()
        .zip(y_new)
        .fold(0.0f32, |w, (a, b)| w.max((a - b).abs()));
    assert!(worst < 1e-4, "{worst}");
}
