//! Arbitrary bytes and mutated valid snapshots to the loader: an error, never a panic.
//!
//! Raw bytes almost never get past the magic and the checksum, so half the inputs start
//! from a valid snapshot of a small surface (half of those with floating bodies: two
//! boxes sharing one hull mesh, one turned and spinning, and a ball), flip bytes chosen by
//! the fuzzer and then (optionally) repair the checksum, which sends the damage on to the
//! content checks.
//! Whatever is accepted must be a surface that re-encodes to the same bytes (an older
//! version: to bytes that load and re-encode to themselves) and steps
//! without producing non-finite values, the engine bitwise equal to the scalar reference;
//! whatever is refused must leave `restore`'s target unchanged. A restored target (in
//! place when the size and model match) hashes and saves as the loaded surface does.

#![no_main]

mod common;

use arbitrary::{Arbitrary, Unstructured};
use common::crc32;
use glam::{Quat, Vec3};
use libfuzzer_sys::fuzz_target;
use springwater::body::Hull;
use springwater::{Floater, Params, SimdLevel, Snapshot, Surface};
use std::sync::Arc;

#[derive(Debug, Arbitrary)]
struct Edit {
    at: u16,
    xor: u8,
}

fuzz_target!(|data: &[u8]| {
    let Some((&mode, rest)) = data.split_first() else {
        return;
    };
    let bytes = if mode & 1 == 0 {
        rest.to_vec()
    } else {
        let mut u = Unstructured::new(rest);
        let cols = 2 + u.int_in_range(0..=6u8).unwrap_or(0) as usize;
        let rows = 2 + u.int_in_range(0..=6u8).unwrap_or(0) as usize;
        let mut p = Params::with_size(cols, rows);
        let bodies = mode & 8 != 0;
        if bodies {
            p.dt = 0.2; // room for the waterlines' stiffness
        }
        let mut s = Surface::new(p).expect("valid");
        let (x, z) = (cols as f32 / 2.0, rows as f32 / 2.0);
        if bodies {
            let hull = Arc::new(Hull::cuboid([0.5, 0.25, 0.4]).expect("valid hull"));
            let mut turned = Floater::with_hull(Arc::clone(&hull), 0.15, [x, 0.0, z]);
            turned.orientation = Quat::from_rotation_y(0.5);
            turned.angular_velocity = Vec3::new(0.2, 1.0, 0.0);
            let upright = Floater::with_hull(hull, 0.15, [x - 0.5, 0.0, z]);
            let ball = Floater::sphere(0.3, 0.05, [x, 0.0, z - 0.5]);
            for body in [upright, turned, ball] {
                s.add_floater(body).expect("valid body");
            }
        }
        s.drop_at(x, z, 1.0, 1.5).expect("valid drop");
        let _ = s.add_force(0, [1.0, 2.0, 3.0]);
        s.step().expect("stable");
        let mut b = s.to_bytes();
        let edits: Vec<Edit> = u.arbitrary().unwrap_or_default();
        for e in edits {
            let at = e.at as usize % b.len();
            b[at] ^= e.xor;
        }
        let cut: u16 = u.arbitrary().unwrap_or(0);
        if mode & 2 != 0 {
            b.truncate(cut as usize % (b.len() + 1));
        }
        if mode & 4 != 0 && b.len() >= 4 {
            let end = b.len() - 4;
            let crc = crc32(&b[..end]);
            b[end..].copy_from_slice(&crc.to_le_bytes());
        }
        b
    };

    let mut target = Surface::new(Params::with_size(3, 3)).expect("valid");
    let before = target.to_bytes();
    match Surface::from_bytes(&bytes) {
        Ok(mut s) => {
            // An older version is converted as it loads and re-encodes as this version;
            // this version's bytes re-encode to themselves.
            let version = u32::from_le_bytes(bytes[8..12].try_into().expect("4 bytes"));
            if version == Snapshot::VERSION {
                assert_eq!(
                    s.to_bytes(),
                    bytes,
                    "an accepted snapshot re-encodes to itself"
                );
            } else {
                let again = s.to_bytes();
                let reloaded = Surface::from_bytes(&again).expect("a re-encoded snapshot loads");
                assert_eq!(
                    reloaded.to_bytes(),
                    again,
                    "a converted snapshot re-encodes to itself"
                );
            }
            target
                .restore(&bytes)
                .expect("from_bytes accepted the same bytes");
            // Restored in place or replaced, the state is the loaded one, and saving it
            // again into a used buffer gives the bytes a fresh save gives.
            assert_eq!(target.state_hash(), s.state_hash());
            let mut saved = before.clone();
            target.save_into(&mut saved);
            assert_eq!(
                saved,
                s.to_bytes(),
                "save_into equals to_bytes after a restore"
            );
            // The engine and the scalar reference agree bitwise on any valid state, so a
            // loader that leaves a derived table stale shows up here.
            let mut reference = s.clone();
            reference.set_simd_level(SimdLevel::Scalar);
            for _ in 0..3 {
                let engine_ok = s.step().is_ok();
                let reference_ok = reference.step().is_ok();
                assert_eq!(engine_ok, reference_ok);
                assert!(
                    s.to_bytes() == reference.to_bytes(),
                    "engine and reference differ after a load"
                );
                if !engine_ok {
                    break;
                }
                for c in s.positions().iter().chain(&s.velocities()) {
                    assert!(c.iter().all(|x| x.is_finite()));
                }
            }
        }
        Err(_) => {
            assert!(target.restore(&bytes).is_err());
            assert_eq!(
                target.to_bytes(),
                before,
                "a refused restore changed the surface"
            );
            assert!(Surface::load(&bytes[..]).is_err());
        }
    }
});
