//! Pieces the targets share (the rigid-body ones, `hulls`, `rigid_bodies`, `body_forces`,
//! `restore_bodies`, `ffi_bodies`, and the snapshot's checksum for `snapshot`): numbers that are sometimes raw bits and sometimes sane, boundaries,
//! a few hulls, and the checks of a surface's state. Not a target of its own.

#![allow(dead_code)] // each target uses its own part

use arbitrary::Arbitrary;
use glam::{Mat3, Quat, Vec3};
use springwater::body::Hull;
use springwater::{Boundary, Floater, Surface};
use std::sync::Arc;

/// A number as the fuzzer gives it: any `f32` bit pattern (NaN, infinities, subnormals,
/// 1e38), or a sane one, `m / 64 · 10^e` with `e` from −8 to 7, which is what reaches
/// past validation.
#[derive(Debug, Clone, Copy, Arbitrary)]
pub enum Num {
    Raw(f32),
    Sane(i8, u8),
}

impl Num {
    pub fn get(self) -> f32 {
        match self {
            Num::Raw(v) => v,
            Num::Sane(m, e) => m as f32 / 64.0 * 10f32.powi(e as i32 % 16 - 8),
        }
    }
}

pub fn vec3(v: [Num; 3]) -> Vec3 {
    Vec3::from_array(v.map(Num::get))
}

/// An orientation: raw components (unit or not, NaN included), or a rotation made of small
/// integers and normalised here in `f32` (a unit quaternion to rounding, which the surface
/// normalises again).
#[derive(Debug, Clone, Copy, Arbitrary)]
pub enum Orientation {
    Raw([f32; 4]),
    Turn([i8; 4]),
}

impl Orientation {
    pub fn get(self) -> Quat {
        match self {
            Orientation::Raw(q) => Quat::from_array(q),
            Orientation::Turn(q) => {
                let q = Quat::from_array(q.map(|v| v as f32));
                if q.length_squared() == 0.0 {
                    Quat::IDENTITY
                } else {
                    q.normalize()
                }
            }
        }
    }
}

/// An inertia tensor: the shape's (the default), any nine numbers, or a diagonal one (in
/// units of the shape's own) that may break the triangle inequality of the principal
/// moments.
#[derive(Debug, Clone, Copy, Arbitrary)]
pub enum Inertia {
    Shape,
    Raw([f32; 9]),
    Diagonal([u8; 3]),
}

impl Inertia {
    pub fn apply(self, body: &mut Floater) {
        body.inertia = match self {
            Inertia::Shape => None,
            Inertia::Raw(m) => Some(Mat3::from_cols_array(&m)),
            Inertia::Diagonal(d) => {
                let own = body.shape.inertia(body.mass);
                let scale = d.map(|v| 0.25 + v as f32 / 64.0);
                Some(Mat3::from_diagonal(Vec3::new(
                    own.x_axis.x * scale[0],
                    own.y_axis.y * scale[1],
                    own.z_axis.z * scale[2],
                )))
            }
        };
    }
}

/// 0 pinned, 1 free, else absorbing with a frame that fits the grid.
pub fn boundary(k: u8, cols: usize, rows: usize) -> Boundary {
    match k % 3 {
        0 => Boundary::Pinned,
        1 => Boundary::Free,
        _ => Boundary::Absorbing {
            width: (k as usize % 6 + 1)
                .min(cols.min(rows).saturating_sub(2) / 2)
                .max(1),
        },
    }
}

/// Hulls a body may take: a box, a flat box and a tetrahedron whose centroid is off the
/// origin (so the body's origin is not its centroid).
pub fn hulls() -> [Arc<Hull>; 3] {
    let tetra = Hull::new(
        &[
            [0.6, -0.2, 0.1],
            [-0.4, -0.2, 0.5],
            [-0.3, -0.25, -0.6],
            [0.0, 0.7, 0.0],
        ],
        &[[0, 1, 2], [1, 0, 3], [2, 1, 3], [0, 2, 3]],
    )
    .expect("a valid tetrahedron");
    [
        Arc::new(Hull::cuboid([0.5, 0.3, 0.4]).expect("valid")),
        Arc::new(Hull::cuboid([1.5, 0.2, 0.8]).expect("valid")),
        Arc::new(tetra),
    ]
}

/// Every position and velocity of the water finite, and every body's fields finite with
/// a unit orientation (its squared norm within 1e-5 of 1: the surface keeps it normalised
/// in `f64` and rounds it to `f32`).
pub fn check_finite(s: &Surface) {
    for c in s.positions().iter().chain(&s.velocities()) {
        assert!(c.iter().all(|v| v.is_finite()), "non-finite water");
    }
    for (id, f) in s.floaters() {
        let fields = [
            f.position,
            f.velocity,
            f.angular_velocity,
            f.push,
            f.push_torque,
            f.water_force,
            f.water_torque,
        ];
        assert!(fields.iter().all(|v| v.is_finite()), "{id:?}: {f:?}");
        assert!(
            (f.orientation.length_squared() - 1.0).abs() < 1e-5,
            "{id:?}: orientation {:?} is not a unit quaternion",
            f.orientation
        );
    }
}

/// The surface's state as its bytes and its hash: what "nothing changed" compares.
pub fn state(s: &Surface) -> (Vec<u8>, u64) {
    (s.to_bytes(), s.state_hash())
}

/// `lo · (hi/lo)^(b/255)`, in `f64` (a range such as 1e-30 to 1e9 overflows `f32`).
pub fn log_range(b: u8, lo: f32, hi: f32) -> f32 {
    let (lo, hi) = (lo as f64, hi as f64);
    (lo * (hi / lo).powf(b as f64 / 255.0)) as f32
}

/// CRC-32 (IEEE), bitwise: the targets repair a snapshot's checksum after editing it
/// without the crate's helper, so that the edit reaches the checks behind the checksum.
pub fn crc32(data: &[u8]) -> u32 {
    let mut crc = !0u32;
    for &b in data {
        crc ^= b as u32;
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

/// Byte edits of a snapshot: XOR masks at positions, a cut, and a repaired checksum (its
/// last four bytes, little-endian).
#[derive(Debug, Arbitrary)]
pub struct Edits {
    pub xors: Vec<(u16, u8)>,
    pub cut: Option<u16>,
    pub repair: bool,
}

impl Edits {
    pub fn apply(&self, b: &mut Vec<u8>) {
        for &(at, xor) in self.xors.iter().take(16) {
            if !b.is_empty() {
                let at = at as usize % b.len();
                b[at] ^= xor;
            }
        }
        if let Some(cut) = self.cut {
            b.truncate(cut as usize % (b.len() + 1));
        }
        if self.repair && b.len() >= 4 {
            let end = b.len() - 4;
            let crc = crc32(&b[..end]);
            b[end..].copy_from_slice(&crc.to_le_bytes());
        }
    }
}
