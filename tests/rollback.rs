//! Rollback as netcode runs it (the scene is `tests/common/rollback.rs`): the straight
//! run's state hashes are golden on every SIMD level, and a short run that saves every
//! frame into reused buffers, restores an earlier frame and simulates the same inputs
//! again gives the straight run's hashes frame by frame (the whole run, on every level and
//! thread count, is `tests/rollback_levels.rs`). And what the hash covers: every input
//! that decides the future changes it; how the surface is stored or run does not.
//!
//! The golden hashes are the same constants on every target CI runs (x86-64 at every
//! level, AArch64 under qemu, wasm32 under Node's WASI).

mod common;
#[path = "common/rollback.rs"]
mod scene;

use glam::Vec3;
use scene::{play, pool, straight, with_rollback, DEPTH, FRAMES, PERIOD};
use springwater::{Floater, FloaterId, Params, SimdLevel, Snapshot, Surface};

/// XXH3-64 state hash after the straight run of [`pool`] and [`FRAMES`] frames of
/// [`play`], and after [`water_only`]: the same on every level, thread count and target.
const GOLDEN_POOL: u64 = 0x87b0_a5d6_2dc2_4694;
const GOLDEN_WATER: u64 = 0x3de9_fb3f_6657_cd7f;

/// Frames of the short run with rollbacks: six of them.
const SHORT: usize = 6 * PERIOD;

#[test]
fn the_straight_run_is_golden_on_every_level() {
    let expected = straight(SimdLevel::Scalar, FRAMES);
    assert_eq!(
        expected[FRAMES], GOLDEN_POOL,
        "the straight run's last hash: {:#018x}",
        expected[FRAMES]
    );
    // Not trivially equal: the state moved frame after frame.
    let distinct: std::collections::HashSet<_> = expected.iter().collect();
    assert_eq!(distinct.len(), expected.len());
    for level in SimdLevel::ALL.into_iter().filter(|l| l.is_available()) {
        assert!(straight(level, FRAMES) == expected, "{level}");
    }
}

#[test]
fn a_short_rollback_gives_the_straight_runs_hashes() {
    let expected = straight(SimdLevel::Scalar, SHORT);
    let (mut s, ids) = pool();
    let what = format!("{:?}", s.simd_level());
    let again = with_rollback(&mut s, ids, &expected, &what);
    assert_eq!(again, SHORT / PERIOD * DEPTH);
}

/// Drops, a force and frames of `advance` on open water at `level`: no bodies, the
/// water alone.
fn water_only(level: SimdLevel) -> Surface {
    let mut s = Surface::new(Params::with_size(67, 45)).unwrap();
    s.set_simd_level(level);
    s.drop_at(20.0, 15.0, 1.5, 3.0).unwrap();
    s.drop_at(50.5, 30.25, -1.0, 2.0).unwrap();
    s.add_force(22 * 67 + 40, [0.3, -0.7, 0.2]).unwrap();
    for _ in 0..40 {
        s.advance(1.0 / 50.0).unwrap();
    }
    s
}

#[test]
fn the_hash_of_water_alone_is_golden_on_every_level() {
    for level in SimdLevel::ALL {
        let hash = water_only(level).state_hash();
        assert_eq!(hash, GOLDEN_WATER, "{level}: {hash:#018x}");
    }
}

/// The byte ranges of a saved snapshot that only frame it or keep count: magic and
/// version, total length, steps and model time, the hull section's count and length,
/// seconds dropped, checksum.
fn records(len: usize) -> [std::ops::Range<usize>; 6] {
    [
        0..12,
        16..24,
        80..96,
        136..160,
        len - 12..len - 4,
        len - 4..len,
    ]
}

#[test]
fn the_hash_is_xxh3_of_the_saved_bytes_without_the_records() {
    let (mut s, ids) = pool();
    for frame in 0..20 {
        play(&mut s, ids, frame);
    }
    let bytes = s.to_bytes();
    let skip = records(bytes.len());
    let state: Vec<u8> = (0..bytes.len())
        .filter(|i| !skip.iter().any(|r| r.contains(i)))
        .map(|i| bytes[i])
        .collect();
    assert_eq!(s.state_hash(), xxhash_rust::xxh3::xxh3_64(&state));
}

#[test]
fn saving_again_reuses_the_buffer_and_restoring_reuses_the_surface() {
    let (mut s, ids) = pool();
    let mut saved = Vec::new();
    s.save_into(&mut saved);
    let (capacity, at) = (saved.capacity(), saved.as_ptr());
    let buffers = |s: &Surface| {
        let [x, y, _] = s.positions();
        [x.as_ptr(), y.as_ptr(), s.velocities()[1].as_ptr()]
    };
    let (mut capacity, mut at) = (capacity, at);
    for frame in 0..30 {
        play(&mut s, ids, frame);
        s.save_into(&mut saved);
        // The buffer grows only when the state does (the water column under the bodies
        // holds the nodes they load); a save that fits reuses it.
        if saved.len() <= capacity {
            assert_eq!((saved.capacity(), saved.as_ptr()), (capacity, at));
        }
        (capacity, at) = (saved.capacity(), saved.as_ptr());
        assert_eq!(saved, s.to_bytes());
        // Restoring writes into the surface's own buffers (the step swaps its front and
        // back buffers, so compare right across the restore).
        let before = buffers(&s);
        s.restore(&saved).unwrap();
        assert_eq!(buffers(&s), before, "frame {frame}: restored in place");
    }
    // A buffer that was larger keeps its larger capacity.
    let mut big = Vec::with_capacity(4 * capacity);
    let at = big.as_ptr();
    s.save_into(&mut big);
    assert_eq!((big.capacity(), big.as_ptr()), (4 * capacity, at));
}

#[test]
fn restore_in_place_continues_like_a_fresh_load() {
    // Restoring into a surface whose tables, pins and bodies differ from the saved ones
    // must leave nothing of them behind.
    let (mut a, ids) = pool();
    for frame in 0..12 {
        play(&mut a, ids, frame);
    }
    let saved = a.to_bytes();
    let (mut b, _) = pool();
    b.set_mass(100, 3.0).unwrap();
    b.set_viscosity(101, 0.3).unwrap();
    b.set_pinned(200, true).unwrap();
    b.set_spring(
        springwater::SpringId {
            family: springwater::Family::S,
            origin: 300,
        },
        springwater::Spring {
            rest: 0.7,
            stiffness: 4.0,
        },
    )
    .unwrap();
    b.add_floater(Floater::sphere(1.0, 2.0, [5.0, 0.0, 5.0]))
        .unwrap();
    b.add_force(5, [1.0, 1.0, 1.0]).unwrap();
    b.restore(&saved).unwrap();
    let mut fresh = Surface::from_bytes(&saved).unwrap();
    assert_eq!(b.to_bytes(), saved);
    for frame in 12..40 {
        play(&mut b, ids, frame);
        play(&mut fresh, ids, frame);
        assert_eq!(b.to_bytes(), fresh.to_bytes(), "frame {frame}");
    }
}

/// The surface of `pool` after a few frames, edited as plain data and loaded.
fn edited(edit: impl FnOnce(&mut Snapshot)) -> Surface {
    let (mut s, ids) = pool();
    for frame in 0..6 {
        play(&mut s, ids, frame);
    }
    let mut snap = s.snapshot();
    edit(&mut snap);
    Surface::from_snapshot(snap).unwrap()
}

type SnapshotEdit = Box<dyn Fn(&mut Snapshot)>;
type SurfaceEdit = fn(&mut Surface, [FloaterId; 2]);

#[test]
fn every_input_that_decides_the_future_changes_the_hash() {
    let base = edited(|_| ()).state_hash();
    let node = 21 * 48 + 17;
    let nudge = |v: &mut f32| *v = f32::from_bits(v.to_bits() + 1);
    let edits: Vec<(&str, SnapshotEdit)> = vec![
        (
            "a position",
            Box::new(move |s| nudge(&mut s.positions[1][node])),
        ),
        (
            "a velocity",
            Box::new(move |s| s.velocities[0][node] = 1e-3),
        ),
        (
            "a pending force",
            Box::new(move |s| s.forces[2][node] = 0.25),
        ),
        ("a node's mass", Box::new(move |s| s.mass[node] = 1.25)),
        (
            "a node's viscosity",
            Box::new(move |s| s.viscosity[node] = 0.03),
        ),
        (
            "a pin",
            Box::new(move |s| {
                s.pinned[node] = true;
                (0..3).for_each(|k| s.velocities[k][node] = 0.0);
            }),
        ),
        ("a spring", Box::new(move |s| nudge(&mut s.rest[3][node]))),
        (
            "a body's position",
            Box::new(|s| s.floaters[0].1.position.x += 0.01),
        ),
        (
            "a body's push",
            Box::new(|s| s.floaters[1].1.push = Vec3::new(0.0, 1.0, 0.0)),
        ),
        (
            "the clock's carried time",
            Box::new(|s| s.owed_time += 0.01),
        ),
        ("the window's origin", Box::new(|s| s.origin_cells[0] += 1)),
        (
            "the acceleration",
            Box::new(|s| s.params.acceleration[0] = 0.5),
        ),
        (
            "the water's density",
            Box::new(|s| s.buoyancy.density *= 1.01),
        ),
        ("the step cap", Box::new(|s| s.step_cap.0 = 3)),
    ];
    for (what, edit) in edits {
        assert_ne!(edited(edit).state_hash(), base, "{what}");
    }
    // And through the API: an edit, a body added, a fraction of a step carried.
    let ids = [FloaterId::from_raw(0), FloaterId::from_raw(1)];
    let api: [(&str, SurfaceEdit); 4] = [
        ("set_mass", |s, _| s.set_mass(33, 1.1).unwrap()),
        ("push_floater", |s, ids| {
            s.push_floater(ids[0], [1.0, 0.0, 0.0]).unwrap()
        }),
        ("add_floater", |s, _| {
            s.add_floater(Floater::sphere(1.0, 2.0, [30.0, 0.0, 10.0]))
                .unwrap();
        }),
        ("a short frame", |s, _| {
            assert_eq!(s.advance(0.001).unwrap(), 0);
        }),
    ];
    for (what, edit) in api {
        let mut s = edited(|_| ());
        edit(&mut s, ids);
        assert_ne!(s.state_hash(), base, "{what}");
    }
}

#[test]
fn how_the_surface_is_stored_or_run_does_not_change_the_hash() {
    let (mut s, ids) = pool();
    for frame in 0..10 {
        play(&mut s, ids, frame);
    }
    let hash = s.state_hash();
    // Counters that only report.
    for edit in [
        |s: &mut Snapshot| s.steps += 7,
        |s: &mut Snapshot| s.model_time += 3.0,
        |s: &mut Snapshot| s.dropped_seconds += 0.5,
    ] {
        let mut snap = s.snapshot();
        edit(&mut snap);
        assert_eq!(Surface::from_snapshot(snap).unwrap().state_hash(), hash);
    }
    // A clone, a reload (tables back to rows of defaults), a level, a thread pool.
    assert_eq!(s.clone().state_hash(), hash);
    assert_eq!(
        Surface::from_bytes(&s.to_bytes()).unwrap().state_hash(),
        hash
    );
    for level in SimdLevel::ALL {
        s.set_simd_level(level);
        assert_eq!(s.state_hash(), hash, "{level}");
    }
    #[cfg(feature = "parallel")]
    {
        let pool = rayon::ThreadPoolBuilder::new().num_threads(3).build();
        s.set_thread_pool(Some(std::sync::Arc::new(pool.unwrap())));
        assert_eq!(s.state_hash(), hash);
    }
    // A spring set to another value and back keeps its per-spring table; a node's mass
    // set and back its per-node array: the same values, the same hash.
    let id = springwater::SpringId {
        family: springwater::Family::E,
        origin: 50,
    };
    let spring = s.spring(id).unwrap();
    let mass = s.masses()[60];
    let mut tables = s.clone();
    tables
        .set_spring(
            id,
            springwater::Spring {
                rest: 0.3,
                ..spring
            },
        )
        .unwrap();
    tables.set_spring(id, spring).unwrap();
    tables.set_mass(60, 2.0).unwrap();
    tables.set_mass(60, mass).unwrap();
    assert_eq!(tables.to_bytes(), s.to_bytes());
    assert_eq!(tables.state_hash(), hash);
}

#[test]
fn restore_in_place_reads_bytes_at_any_alignment() {
    // 19 × 13 nodes: the spring arrays after the one-byte pins start off a multiple of 4,
    // and a save one byte into its buffer shifts every array.
    let mut s = Surface::new(Params::with_size(19, 13)).unwrap();
    s.drop_at(9.0, 6.0, 0.5, 2.0).unwrap();
    s.step_n(5).unwrap();
    s.add_force(40, [0.1, 0.2, 0.3]).unwrap();
    let saved = s.to_bytes();
    let mut shifted = vec![0u8];
    shifted.extend_from_slice(&saved);
    let straight = {
        let mut t = s.clone();
        t.step_n(4).unwrap();
        t.to_bytes()
    };
    for bytes in [&saved[..], &shifted[1..]] {
        s.step_n(3).unwrap();
        s.restore(bytes).unwrap();
        assert_eq!(s.to_bytes(), saved);
        s.step_n(4).unwrap();
        assert_eq!(s.to_bytes(), straight);
        s.restore(bytes).unwrap();
    }
}
