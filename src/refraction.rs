//! STAND-IN for the `mesh` branch's refraction stage, written against the agreed
//! signatures so `render` compiles before that branch lands. Deleted at the merge.

use crate::error::Result;
use crate::mesh::{MeshView, Normals};
use glam::Vec3;

/// Bottom depth and index of refraction.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct RefractionParams {
    /// Depth of the bottom below y = 0.
    pub depth: f32,
    /// Index of refraction of the water.
    pub ior: f32,
}

impl Default for RefractionParams {
    fn default() -> Self {
        Self {
            depth: 8.0,
            ior: 1.333,
        }
    }
}

/// Per-node bottom UV and Fresnel reflectance.
#[derive(Debug, Clone, Default)]
pub struct Refraction {
    /// u per node.
    pub u: Vec<f32>,
    /// v per node.
    pub v: Vec<f32>,
    /// Fresnel reflectance per node.
    pub fresnel: Vec<f32>,
}

/// Snell to the bottom plane, Schlick's Fresnel.
pub fn refract(
    view: &MeshView<'_>,
    normals: &Normals,
    eye: Vec3,
    params: &RefractionParams,
    out: &mut Refraction,
) -> Result<()> {
    let n = view.cols() * view.rows();
    out.u.resize(n, 0.0);
    out.v.resize(n, 0.0);
    out.fresnel.resize(n, 0.0);
    let eta = 1.0 / params.ior;
    let w = (view.cols() - 1) as f32 * view.spacing();
    let d_ = (view.rows() - 1) as f32 * view.spacing();
    let r0 = ((1.0 - params.ior) / (1.0 + params.ior)).powi(2);
    for i in 0..n {
        let p = view.position(i);
        let nrm = Vec3::new(normals.x[i], normals.y[i], normals.z[i]);
        let d = (p - eye).normalize_or(Vec3::NEG_Y);
        let cosi = (-nrm.dot(d)).clamp(0.0, 1.0);
        let k = (1.0 - eta * eta * (1.0 - cosi * cosi)).max(0.0);
        let t = eta * d + (eta * cosi - k.sqrt()) * nrm;
        let s = if t.y < -1e-6 {
            (-params.depth - p.y) / t.y
        } else {
            0.0
        };
        let hit = p + s.max(0.0) * t;
        out.u[i] = hit.x / w;
        out.v[i] = hit.z / d_;
        out.fresnel[i] = r0 + (1.0 - r0) * (1.0 - cosi).powi(5);
    }
    Ok(())
}
