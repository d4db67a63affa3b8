//! Rollback as netcode runs it, on a pinned pool with two floating bodies: the scene, the
//! players' inputs of each frame, a straight run and the same run with rollbacks. Shared
//! by `tests/rollback.rs` (the golden hashes and a short rollback, on every target CI
//! runs) and `tests/rollback_levels.rs` (the whole run with rollbacks on every level and
//! thread count).

#![allow(dead_code)]

use crate::common::Rng;
use springwater::{Floater, FloaterId, Params, SimdLevel, Surface};

/// Frames of the straight run.
pub const FRAMES: usize = 300;
/// A rollback every `PERIOD`th frame…
pub const PERIOD: usize = 8;
/// …of this many frames.
pub const DEPTH: usize = 7;

/// A pinned pool with a heavier patch, a ball and a box floating on it (whose waterlines
/// stiffen the water: half the default timestep, two steps a frame).
pub fn pool() -> (Surface, [FloaterId; 2]) {
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
pub fn play(s: &mut Surface, [ball, crate_]: [FloaterId; 2], frame: usize) {
    let mut rng = Rng((frame as u32).wrapping_mul(0x9e37_79b9) | 1);
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

/// The state hash at the start of each of the first `frames` frames and at their end,
/// without rollback.
pub fn straight(level: SimdLevel, frames: usize) -> Vec<u64> {
    let (mut s, ids) = pool();
    s.set_simd_level(level);
    let mut hashes = Vec::with_capacity(frames + 1);
    for frame in 0..frames {
        hashes.push(s.state_hash());
        play(&mut s, ids, frame);
    }
    hashes.push(s.state_hash());
    hashes
}

/// The first `expected.len() − 1` frames, saving each frame's start into a ring of reused
/// buffers and rolling back [`DEPTH`] frames after every [`PERIOD`]th: restore, then
/// simulate them again. Asserts every hash, first and second time, against `expected`
/// (from [`straight`]); returns how many frames were simulated again.
pub fn with_rollback(s: &mut Surface, ids: [FloaterId; 2], expected: &[u64], what: &str) -> usize {
    let frames = expected.len() - 1;
    let mut ring: Vec<Vec<u8>> = vec![Vec::new(); DEPTH + 1];
    let mut again = 0;
    for frame in 0..frames {
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
    assert_eq!(s.state_hash(), expected[frames], "{what}: the end");
    again
}
