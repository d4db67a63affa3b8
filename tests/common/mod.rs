//! Helpers shared by the integration tests.
#![allow(dead_code)]

use springwater::disturb::{Rain, Wake};
use springwater::{Params, Surface};

/// Every position and velocity bit of a surface, in a fixed order.
pub fn state_bits(s: &Surface) -> Vec<u32> {
    s.positions()
        .iter()
        .chain(s.velocities().iter())
        .flat_map(|c| c.iter().map(|v| v.to_bits()))
        .collect()
}

/// FNV-1a over the state bits: a short fingerprint for cross-build comparisons.
pub fn fingerprint(s: &Surface) -> u64 {
    state_bits(s)
        .iter()
        .fold(0xcbf2_9ce4_8422_2325u64, |h, &b| {
            b.to_le_bytes().iter().fold(h, |h, &byte| {
                (h ^ byte as u64).wrapping_mul(0x0100_0000_01b3)
            })
        })
}

/// Largest |displacement| of any node from its rest position `(col·h, 0, row·h)`.
pub fn max_displacement(s: &Surface) -> f32 {
    let h = s.params().spacing;
    let [x, y, z] = s.positions();
    let g = s.grid();
    (0..s.node_count())
        .map(|i| {
            let (c, r) = g.coords(i);
            (x[i] - c as f32 * h)
                .abs()
                .max(y[i].abs())
                .max((z[i] - r as f32 * h).abs())
        })
        .fold(0.0, f32::max)
}

/// A small deterministic generator for test disturbances (xorshift32).
pub struct Rng(pub u32);

impl Rng {
    /// Uniform in `[-0.5, 0.5)`.
    pub fn next(&mut self) -> f32 {
        self.0 ^= self.0 << 13;
        self.0 ^= self.0 >> 17;
        self.0 ^= self.0 << 5;
        self.0 as f32 / 4_294_967_296.0 - 0.5
    }
}

/// A 97 × 140 surface (tall enough for several bands), configured by `setup` (a host's
/// pool or job system), driven through drops, a force at a point, single steps,
/// multi-step passes and frames with rain and a wake: every stepping path.
pub fn every_stepping_path(setup: impl FnOnce(&mut Surface)) -> Surface {
    let mut s = Surface::new(Params::with_size(97, 140)).unwrap();
    setup(&mut s);
    s.drop_at(30.0, 40.0, 1.5, 3.0).unwrap();
    s.drop_at(70.0, 110.0, -1.0, 2.5).unwrap();
    s.add_force_at(48.5, 70.25, [0.3, 2.0, -0.1]).unwrap();
    for _ in 0..10 {
        s.step().unwrap();
    }
    s.step_n(37).unwrap();
    let mut rain = Rain::new(20.0, 5);
    let mut wake = Wake::circle(&s, 30.0);
    for _ in 0..20 {
        s.advance_with(1.0 / 30.0, &mut (&mut rain, &mut wake))
            .unwrap();
    }
    s
}

/// Runs `run` on a surface from `build` at every SIMD level (forced, clamped to the CPU)
/// on 1 and 2 threads, and asserts that each ends with the same snapshot bytes as the
/// scalar reference (`SimdLevel::Scalar`) on 1 thread.
pub fn same_bits_everywhere(build: impl Fn() -> Surface + Sync, run: impl Fn(&mut Surface) + Sync) {
    use springwater::SimdLevel;
    let bytes = |level: SimdLevel, threads: usize| {
        let pool = rayon::ThreadPoolBuilder::new()
            .num_threads(threads)
            .build()
            .unwrap();
        pool.install(|| {
            let mut s = build();
            s.set_simd_level(level);
            run(&mut s);
            s.to_bytes()
        })
    };
    let reference = bytes(SimdLevel::Scalar, 1);
    for level in SimdLevel::ALL {
        for threads in [1, 2] {
            assert!(
                bytes(level, threads) == reference,
                "{level:?} on {threads} threads"
            );
        }
    }
}

/// A snapshot of the current version (7) in version 6's layout, what the version 6
/// encoder wrote for the same state without a water column: the header without the
/// column's entry count (offset 152) and no column section; length and checksum fixed.
pub fn as_version_6(v7: &[u8]) -> Vec<u8> {
    assert_eq!(u32::from_le_bytes(v7[8..12].try_into().unwrap()), 7);
    let column = u64::from_le_bytes(v7[152..160].try_into().unwrap()) as usize;
    let tail = v7.len() - 44;
    let mut b = [&v7[..152], &v7[160..tail - 32 * column], &v7[tail..]].concat();
    b[8..12].copy_from_slice(&6u32.to_le_bytes());
    let len = b.len() as u64;
    b[16..24].copy_from_slice(&len.to_le_bytes());
    fix_crc(&mut b);
    b
}

/// The snapshot `current` (of a surface with `n` nodes and `bodies` bodies, none with a
/// hull) in version 5's layout, what the version 5 encoder wrote for the same state but
/// the bodies' rotation and the water column: a header of 136 bytes (without the hull
/// section's count and length), and of each body's 176 bytes the first 80 (the fields
/// before the orientation), no hull section; length and checksum fixed.
pub fn as_version_5(current: &[u8], n: usize, bodies: usize) -> Vec<u8> {
    let v6 = &as_version_6(current)[..];
    assert_eq!(v6[136..152], [0; 16], "no hull meshes");
    let at = 152 + 77 * n;
    let mut b = [&v6[..136], &v6[152..at]].concat();
    for k in 0..bodies {
        b.extend_from_slice(&v6[at + 176 * k..][..80]);
    }
    b.extend_from_slice(&v6[v6.len() - 44..]);
    b[8..12].copy_from_slice(&5u32.to_le_bytes());
    let len = b.len() as u64;
    b[16..24].copy_from_slice(&len.to_le_bytes());
    fix_crc(&mut b);
    b
}

pub fn fix_crc(b: &mut [u8]) {
    let end = b.len() - 4;
    let crc = crc32(&b[..end]);
    b[end..].copy_from_slice(&crc.to_le_bytes());
}

pub fn crc32(data: &[u8]) -> u32 {
    let mut crc = !0u32;
    for &byte in data {
        crc ^= byte as u32;
        for _ in 0..8 {
            crc = if crc & 1 != 0 {
                (crc >> 1) ^ 0xEDB8_8320
            } else {
                crc >> 1
            };
        }
    }
    !crc
}

/// [`Surface::new`] at the level `SPRINGWATER_SIMD` names, if set: how CI runs the parity,
/// determinism and golden-fingerprint tests at every level (the library itself never
/// reads the environment).
pub fn new_surface(params: Params) -> springwater::Result<Surface> {
    let mut s = Surface::new(params)?;
    s.set_simd_level(springwater::SimdLevel::from_env()?);
    Ok(s)
}
