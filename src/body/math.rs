//! The small pieces of `f64` vector algebra the bodies' physics shares: outer products and
//! cross-product matrices, rotations of quaternions, and the unit-quaternion checks. Plain
//! `+`, `−`, `×`, `÷` and `sqrt` in `glam`'s `f64` types, so the same bits on every target
//! (see the [module docs](super) on arithmetic).

use crate::error::{Error, Result};
use crate::params;
use glam::{DMat3, DQuat, DVec3, Quat};

/// `a bᵀ`.
pub(crate) fn outer(a: DVec3, b: DVec3) -> DMat3 {
    DMat3::from_cols(a * b.x, a * b.y, a * b.z)
}

/// `[a]×`, the matrix of `x ↦ a × x`.
pub(crate) fn skew(a: DVec3) -> DMat3 {
    DMat3::from_cols(
        DVec3::new(0.0, a.z, -a.y),
        DVec3::new(-a.z, 0.0, a.x),
        DVec3::new(a.y, -a.x, 0.0),
    )
}

/// The body-to-world rotation matrix of a unit quaternion.
pub(crate) fn rotation(q: DQuat) -> DMat3 {
    rotation_scaled(q, 2.0)
}

/// The matrix of `q` with its products scaled by `s` instead of 2: with `s = 2 / |q|²` it
/// is a rotation for any `q` near unit length.
pub(crate) fn rotation_scaled(q: DQuat, s: f64) -> DMat3 {
    let (x, y, z, w) = (q.x, q.y, q.z, q.w);
    let (xx, yy, zz) = (s * x * x, s * y * y, s * z * z);
    let (xy, yz, zx) = (s * x * y, s * y * z, s * z * x);
    let (wx, wy, wz) = (s * w * x, s * w * y, s * w * z);
    DMat3::from_cols(
        DVec3::new(1.0 - (yy + zz), xy + wz, zx - wy),
        DVec3::new(xy - wz, 1.0 - (xx + zz), yz + wx),
        DVec3::new(zx + wy, yz - wx, 1.0 - (xx + yy)),
    )
}

/// Checks that `q` is a unit quaternion within rounding: finite components (else an error
/// naming `name`), squared norm within 1e-3 of 1 (else naming `norm_name`). Returns the
/// squared norm.
pub(crate) fn check_unit(q: Quat, name: &'static str, norm_name: &'static str) -> Result<f64> {
    for v in q.to_array() {
        params::finite(name, v)?;
    }
    let [x, y, z, w] = q.to_array().map(f64::from);
    let n = x * x + y * y + z * z + w * w;
    // (The components are finite, so n is a number.)
    if (n - 1.0) * (n - 1.0) > 1e-6 {
        return Err(Error::InvalidParam {
            name: norm_name,
            value: n,
            expected: "1 within 1e-3: a unit quaternion (normalise it)",
        });
    }
    Ok(n)
}

/// `q / |q|` (with `sqrt`, the same bits everywhere).
pub(crate) fn normalised(q: DQuat) -> DQuat {
    let n = (q.x * q.x + q.y * q.y + q.z * q.z + q.w * q.w).sqrt();
    DQuat::from_xyzw(q.x / n, q.y / n, q.z / n, q.w / n)
}
