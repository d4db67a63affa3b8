//! `restore` and `Surface::from_bytes` of arbitrary bytes into a live surface that has
//! floating bodies: either both refuse and the live surface is bitwise unchanged (its
//! snapshot bytes and state hash), or both accept and the restored surface equals a fresh
//! load of the same bytes: the same bytes and hash, and the same bits after two more steps,
//! failed steps included (so no cache of the old bodies, such as a hull's wet mesh kept for
//! a body's place in the list, outlives the restore). `Surface::load` reads one snapshot
//! from a stream: it takes exactly what `from_bytes` takes of the bytes it reads.
//!
//! The bytes are raw, or a snapshot with fuzzer-chosen edits (XOR masks, a cut, a repaired
//! checksum so that the damage reaches the content checks) of either the live surface at an
//! earlier frame (a rollback: restored in place) or another surface, with its own bodies,
//! of the same or another size (in place, or replacing the surface).

#![no_main]

mod common;

use arbitrary::Arbitrary;
use common::{hulls, state, Edits};
use glam::{Quat, Vec3};
use libfuzzer_sys::fuzz_target;
use springwater::{Floater, Params, Surface};

#[derive(Debug, Arbitrary)]
struct Input {
    live: World,
    source: Source,
}

/// A small pool with bodies, stepped a few times.
#[derive(Debug, Arbitrary)]
struct World {
    cols: u8,
    rows: u8,
    bodies: Vec<Body>,
    steps: u8,
    /// A `body_forces` call whose reaction waits in the water column.
    foreign: bool,
}

#[derive(Debug, Arbitrary)]
struct Body {
    /// 0 ball, 1 box, else one of `common::hulls` (shared between bodies through one `Arc`).
    shape: u8,
    at: [u8; 2],
    turn: [i8; 4],
    spin: [i8; 3],
}

#[derive(Debug, Arbitrary)]
enum Source {
    Raw(Vec<u8>),
    /// The live surface as it was before its steps.
    Rollback(Edits),
    Other(World, Edits),
}

impl World {
    /// The surface before and after its steps.
    fn build(&self) -> (Vec<u8>, Surface) {
        let (cols, rows) = (self.cols as usize % 6 + 4, self.rows as usize % 6 + 4);
        let mut s = Surface::new(Params::with_size(cols, rows).with_dt(0.2)).expect("valid");
        let hulls = hulls();
        let density = s.buoyancy().density;
        for b in self.bodies.iter().take(3) {
            let at = [
                (b.at[0] as usize % cols) as f32,
                0.0,
                (b.at[1] as usize % rows) as f32,
            ];
            let mut f = match b.shape % 3 {
                0 => Floater::sphere(0.4, 1.0, at),
                1 => Floater::cuboid([0.5, 0.25, 0.3], 1.0, at),
                _ => Floater::with_hull(hulls[b.shape as usize % 3].clone(), 1.0, at),
            };
            f.mass = 0.5 * density * f.shape.volume();
            let q = Quat::from_array(b.turn.map(|v| v as f32));
            if q.length_squared() > 0.0 {
                f.orientation = q.normalize();
            }
            f.angular_velocity = Vec3::from_array(b.spin.map(|v| v as f32 / 32.0));
            let _ = s.add_floater(f);
        }
        let _ = s.drop_at(cols as f32 / 2.0, rows as f32 / 2.0, 0.5, 1.5);
        let start = s.to_bytes();
        for _ in 0..self.steps % 4 {
            if s.step().is_err() {
                break;
            }
        }
        if self.foreign {
            let probe = Floater::sphere(0.5, 0.25 * density, [1.5, 0.0, 1.5]);
            let _ = s.body_forces(&probe, 1.0 / 60.0);
        }
        (start, s)
    }
}

fuzz_target!(|input: Input| {
    let (start, mut live) = input.live.build();
    let bytes = match &input.source {
        Source::Raw(b) => b.clone(),
        Source::Rollback(edits) => {
            let mut b = start;
            edits.apply(&mut b);
            b
        }
        Source::Other(world, edits) => {
            let mut b = world.build().1.to_bytes();
            edits.apply(&mut b);
            b
        }
    };
    let before = state(&live);
    let restored = live.restore(&bytes);
    let fresh = Surface::from_bytes(&bytes);
    // `load` reads one snapshot from a stream and stops at its end: bytes after it are
    // not its business. What it read must be what `from_bytes` takes.
    let mut rest = &bytes[..];
    match Surface::load(&mut rest) {
        Ok(loaded) => {
            let read = &bytes[..bytes.len() - rest.len()];
            let again = Surface::from_bytes(read).expect("load and from_bytes disagree");
            assert!(
                state(&loaded) == state(&again),
                "load differs from from_bytes"
            );
        }
        Err(_) => assert!(fresh.is_err(), "from_bytes took what load refused"),
    }
    match (restored, fresh) {
        (Err(_), Err(_)) => {
            assert!(
                state(&live) == before,
                "a refused restore changed the surface"
            );
        }
        (Ok(()), Ok(mut fresh)) => {
            assert!(
                state(&live) == state(&fresh),
                "restored differs from a fresh load"
            );
            // Saving into a used buffer gives what a fresh save gives.
            let mut saved = before.0;
            live.save_into(&mut saved);
            assert!(saved == fresh.to_bytes());
            for _ in 0..2 {
                let (a, b) = (live.step(), fresh.step());
                assert_eq!(a.is_ok(), b.is_ok(), "{a:?} {b:?}");
                assert!(
                    state(&live) == state(&fresh),
                    "restored and fresh surfaces step apart"
                );
                if a.is_err() {
                    break;
                }
                common::check_finite(&live);
            }
        }
        (r, f) => panic!(
            "restore {:?} and from_bytes {:?} disagree",
            r.err(),
            f.err()
        ),
    }
});
