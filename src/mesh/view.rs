//! [`MeshView`]: a zero-copy view of the surface for renderers.

use crate::error::{Error, Result};
use crate::grid::Grid;

/// A borrowed view of a surface's positions and grid shape: no copy.
///
/// Index buffers built from it index the full node array (row-major), so a renderer can
/// upload `x`, `y`, `z` as they are.
#[derive(Debug, Clone, Copy)]
pub struct MeshView<'a> {
    grid: Grid,
    spacing: f32,
    x: &'a [f32],
    y: &'a [f32],
    z: &'a [f32],
}

impl<'a> MeshView<'a> {
    /// A view of `x`, `y`, `z` (one value per node, row-major) on `grid` with rest
    /// spacing `spacing`. The slices must have `grid.len()` elements and the grid at
    /// least 2×2 nodes.
    pub fn new(grid: Grid, spacing: f32, x: &'a [f32], y: &'a [f32], z: &'a [f32]) -> Result<Self> {
        if grid.cols < 2 || grid.rows < 2 {
            return Err(Error::GridTooSmall {
                cols: grid.cols,
                rows: grid.rows,
            });
        }
        crate::params::positive("spacing", spacing)?;
        for (what, s) in [("x", x), ("y", y), ("z", z)] {
            if s.len() != grid.len() {
                return Err(Error::LengthMismatch {
                    what,
                    got: s.len(),
                    expected: grid.len(),
                });
            }
        }
        Ok(Self {
            grid,
            spacing,
            x,
            y,
            z,
        })
    }

    /// The grid shape.
    pub fn grid(&self) -> Grid {
        self.grid
    }

    /// Nodes per row.
    pub fn cols(&self) -> usize {
        self.grid.cols
    }

    /// Rows of nodes.
    pub fn rows(&self) -> usize {
        self.grid.rows
    }

    /// Rest spacing `h`.
    pub fn spacing(&self) -> f32 {
        self.spacing
    }

    /// The rest footprint's size in world units, `[(cols−1)·h, (rows−1)·h]`: the water
    /// spans `[0, width] × [0, length]` in x and z at rest, and the bottom texture of
    /// [`crate::refraction`] spans the same rectangle.
    pub fn extent(&self) -> [f32; 2] {
        let h = self.spacing;
        [(self.cols() - 1) as f32 * h, (self.rows() - 1) as f32 * h]
    }

    /// Copies the positions into `out` interleaved, `[x, y, z]` per node, row-major (what
    /// a vertex buffer of positions takes). `out` must hold one element per node; on error
    /// nothing is written. [`crate::buffers::interleave`] fills normals, texture
    /// coordinates and packed vertices in the same pass.
    pub fn write_positions(&self, out: &mut [[f32; 3]]) -> Result<()> {
        if out.len() != self.grid.len() {
            return Err(Error::LengthMismatch {
                what: "position buffer",
                got: out.len(),
                expected: self.grid.len(),
            });
        }
        for (o, ((x, y), z)) in out.iter_mut().zip(self.x.iter().zip(self.y).zip(self.z)) {
            *o = [*x, *y, *z];
        }
        Ok(())
    }

    /// x of every node.
    pub fn x(&self) -> &'a [f32] {
        self.x
    }

    /// y (height) of every node.
    pub fn y(&self) -> &'a [f32] {
        self.y
    }

    /// z of every node.
    pub fn z(&self) -> &'a [f32] {
        self.z
    }

    /// Position of node `i`.
    pub fn position(&self, i: usize) -> glam::Vec3 {
        glam::Vec3::new(self.x[i], self.y[i], self.z[i])
    }
}
