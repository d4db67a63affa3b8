//! STAND-IN for the `mesh` branch (normals and LOD), written against the agreed
//! signatures so `render` compiles before that branch lands. Deleted at the merge.
//! Not the real thing: full-resolution triangles only, central-difference normals.

use super::MeshView;
use crate::error::Result;

/// Per-node unit normals.
#[derive(Debug, Clone, Default)]
pub struct Normals {
    /// x components.
    pub x: Vec<f32>,
    /// y components.
    pub y: Vec<f32>,
    /// z components.
    pub z: Vec<f32>,
}

/// Normals by central differences of the positions.
pub fn compute_normals(view: &MeshView<'_>, out: &mut Normals) {
    let (cols, rows) = (view.cols(), view.rows());
    let n = cols * rows;
    for v in [&mut out.x, &mut out.y, &mut out.z] {
        v.resize(n, 0.0);
    }
    for r in 0..rows {
        for c in 0..cols {
            let i = r * cols + c;
            let (l, rr) = (
                r * cols + c.saturating_sub(1),
                r * cols + (c + 1).min(cols - 1),
            );
            let (u, d) = (
                r.saturating_sub(1) * cols + c,
                (r + 1).min(rows - 1) * cols + c,
            );
            let tx = view.position(rr) - view.position(l);
            let tz = view.position(d) - view.position(u);
            let nrm = tz.cross(tx).normalize_or(glam::Vec3::Y);
            out.x[i] = nrm.x;
            out.y[i] = nrm.y;
            out.z[i] = nrm.z;
        }
    }
}

/// LOD parameters (ignored by the stand-in).
#[derive(Debug, Clone, Copy, PartialEq, Default)]
pub struct LodParams {}

/// Full-resolution triangles.
#[derive(Debug, Clone, Default)]
pub struct LodMesh {
    indices: Vec<u32>,
    levels: Vec<u8>,
    patches: Vec<u8>,
}

impl LodMesh {
    /// An empty mesh.
    pub fn new(_params: LodParams) -> Result<Self> {
        Ok(Self::default())
    }

    /// Builds the full-resolution index buffer once.
    pub fn update(&mut self, view: &MeshView<'_>, _eye: glam::Vec3) -> bool {
        let (cols, rows) = (view.cols(), view.rows());
        let want = (cols - 1) * (rows - 1) * 6;
        if self.indices.len() == want {
            return false;
        }
        self.indices.clear();
        for r in 0..rows - 1 {
            for c in 0..cols - 1 {
                let a = (r * cols + c) as u32;
                let b = a + 1;
                let cc = a + cols as u32;
                let d = cc + 1;
                self.indices.extend_from_slice(&[a, cc, b, b, cc, d]);
            }
        }
        self.levels = vec![0; want / 3];
        self.patches = vec![0; 1];
        true
    }

    /// Triangle indices.
    pub fn indices(&self) -> &[u32] {
        &self.indices
    }

    /// LOD level of every triangle.
    pub fn triangle_levels(&self) -> &[u8] {
        &self.levels
    }

    /// LOD level of every patch.
    pub fn patch_levels(&self) -> &[u8] {
        &self.patches
    }
}
