//! Rollback as netcode runs it: save every frame into reused buffers, restore an earlier
//! frame, simulate the same inputs again, and compare state hashes with a straight run,
//! frame by frame, on every SIMD level and thread count. And what the hash covers: every
//! input that decides the future changes it; how the surface is stored or run does not.
//!
//! The golden hashes are the same constants on every target CI runs (x86-64 at every
//! level, AArch64 under qemu, wasm32 under Node's WASI).

mod common;

use glam::Vec3;
use springwater::{Floater, FloaterId, Params, SimdLevel, Snapshot, Surface};

/// Frames of the straight run.
const FRAMES: usize = 300;
/// A rollback every `PERIOD`th frame…
const PERIOD: usize = 8;
/// …of this many frames.
const DEPTH: usize = 7;

/// XXH3-64 state hash after the straight run of [`pool`] and [`FRAMES`] frames of
/// [`play`], and after [`water_only`]: the same on every level, thread count and target.
const GOLDEN_POOL: u64 = 0x71f6_0318_3884_23e0;
const GOLDEN_WATER: u64 = 0x3de9_fb3f_6657_cd7f;

/// A pinned pool with a heavier patch, a ball and a box floating on it (whose waterlines
/// stiffen the water: half the default timestep, two steps a frame).
fn pool() -> (Surface, [FloaterId; 2]) {
    let mut p = Params::with_size(48, 40);
    p.dt = 0.2;
    let mut s = Surface::new(p).unwrap();
    for i in [20 * 48 + 30, 20 * 48 + 31] {
        s.set_mass(i, 1.5).unwrap();
    }
    let density = s.buoyancy().density;
    let mut ball = Floater::sphere(1.5, 1.0, [14.0, 0.0, 12.0]);
    ball.mass = 0.5 * density * ball.shape.volume();
    let mut crate_ = Floater::cuboid([1.2, 0.6, 0.9], 1.0, [32.0, 0.0, 26.0]);
    crate_.mass = 0.4 * density * crate_.shape.volume();
    let ids = [s.add_floater(ball).unwrap(), s.add_floater(crate_).unwrap()];
    (s, ids)
}

/// The players' inputs of `frame`, a pure function of it (so a resimulated frame gets
/// the same): drops now and then, a push on the ball, a paddle's force left pending for
/// the next frame.
fn play(s: &mut Surface, [ball, crate_]: [FloaterId; 2], frame: usize) {
    let mut rng = common::Rng((frame as u32).wrapping_mul(0x9e37_79b9) | 1);
    let (a, b, c) = (rng.next(), rng.next(), rng.next());
    if frame.is_multiple_of(5) {
        // Drops within the stable regime: |height| well below the radius.
        s.drop_at(24.0 + 36.0 * a, 20.0 + 30.0 * b, 0.4 * c, 2.0)
            .unwrap();
    }
    s.push_floater(ball, [40.0 * a, 0.0, 40.0 * b]).unwrap();
    s.advance(1.0 / 60.0).unwrap();
    // Pending through the save at the start of the next frame.
    s.add_force_at(10.0 + 20.0 * (a + 0.5), 30.0, [0.0, 0.5 * c, 0.0])
        .unwrap();
    s.push_floater(crate_, [0.0, 0.0, 30.0 * c]).unwrap();
}

/// The state hash at the start of every frame and at the end, without rollback.
fn straight(level: SimdLevel) -> Vec<u64> {
    let (mut s, ids) = pool();
    s.set_simd_level(level);
    let mut hashes = Vec::with_capacity(FRAMES + 1);
    for frame in 0..FRAMES {
        hashes.push(s.state_hash());
        play(&mut s, ids, frame);
    }
    hashes.push(s.state_hash());
    hashes
}

/// The same frames, saving each frame's start into a ring of reused buffers and rolling
/// back [`DEPTH`] frames after every [`PERIOD`]th: restore, then simulate them again.
/// Asserts every hash, first and second time, against `expected`; returns how many
/// frames were simulated again.
fn with_rollback(s: &mut Surface, ids: [FloaterId; 2], expected: &[u64], what: &str) -> usize {
    let mut ring: Vec<Vec<u8>> = vec![Vec::new(); DEPTH + 1];
    let mut again = 0;
    for frame in 0..FRAMES {
        s.save_into(&mut ring[frame % (DEPTH + 1)]);
        assert_eq!(s.state_hash(), expected[frame], "{what}: frame {frame}");
        play(s, ids, frame);
        if frame % PERIOD == PERIOD - 1 {
            let first = frame + 1 - DEPTH;
            s.restore(&ring[first % (DEPTH + 1)]).unwrap();
            for redo in first..=frame {
                assert_eq!(
                    s.state_hash(),
                    expected[redo],
                    "{what}: frame {redo} simulated again after frame {frame}"
                );
                s.save_into(&mut ring[redo % (DEPTH + 1)]);
                play(s, ids, redo);
                again += 1;
            }
        }
    }
    assert_eq!(s.state_hash(), expected[FRAMES], "{what}: the end");
    again
}

#[test]
fn rollback_gives_the_straight_runs_hashes_on_every_level_and_thread_count() {
    let expected = straight(SimdLevel::Scalar);
    assert_eq!(
        expected[FRAMES], GOLDEN_POOL,
        "the straight run's last hash: {:#018x}",
        expected[FRAMES]
    );
    // Not trivially equal: the state moved frame after frame.
    let distinct: std::collections::HashSet<_> = expected.iter().collect();
    assert_eq!(distinct.len(), expected.len());
    for level in SimdLevel::ALL {
        for threads in [1, 2] {
            let (mut s, ids) = pool();
            s.set_simd_level(level);
            #[cfg(feature = "parallel")]
            {
                let pool = rayon::ThreadPoolBuilder::new().num_threads(threads);
                s.set_thread_pool(Some(std::sync::Arc::new(pool.build().unwrap())));
            }
            let what = format!("{level} ({:?}) on {threads} threads", s.simd_level());
            let again = with_rollback(&mut s, ids, &expected, &what);
            assert_eq!(again, FRAMES / PERIOD * DEPTH);
        }
    }
}

#[test]
fn every_level_hashes_a_straight_run_alike() {
    let reference = straight(SimdLevel::Scalar);
    for level in SimdLevel::ALL.into_iter().filter(|l| l.is_available()) {
        assert!(straight(level) == reference, "{level}");
    }
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
        136..152,
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
    for frame in 0..30 {
        play(&mut s, ids, frame);
        s.save_into(&mut saved);
        assert_eq!((saved.capacity(), saved.as_ptr()), (capacity, at));
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
