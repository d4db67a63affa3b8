//! [`MeshView`]: a zero-copy view of the surface, the one way the render-side stages
//! ([`crate::mesh`], [`crate::refraction`], [`crate::buffers`]) read the simulation.
//! The physics knows nothing of them: [`Surface::mesh_view`](crate::Surface::mesh_view)
//! hands out this view and that is all.

use crate::error::{same_length, Error, Result};
use crate::grid::Grid;
use crate::jobs::Runner;
use crate::simd::SimdLevel;

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
    simd: SimdLevel,
    /// Where the stages' parts run: the surface's host threads, else rayon's pool.
    runner: Runner<'a>,
    /// Rest place `(x, z)` of node `(0, 0)` in the frame of the positions.
    origin: [f32; 2],
}

// The view only reads the surface's buffers (its host is borrowed to hand work to):
// nothing of it is left half-changed by a panic, as for the plain slices it holds.
impl std::panic::UnwindSafe for MeshView<'_> {}
impl std::panic::RefUnwindSafe for MeshView<'_> {}

impl<'a> MeshView<'a> {
    /// A view of `x`, `y`, `z` (one value per node, row-major) on `grid` with rest
    /// spacing `spacing`. The slices must have `grid.node_count()` elements and the grid at
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
            same_length(what, s.len(), grid.node_count())?;
        }
        Ok(Self {
            grid,
            spacing,
            x,
            y,
            z,
            simd: SimdLevel::detect(),
            runner: Runner::Here,
            origin: [0.0, 0.0],
        })
    }

    /// The same view of a grid whose node `(0, 0)` rests at `(origin[0], 0, origin[1])`
    /// in the frame of the positions (a moving window: [`crate::Surface::origin`]; the
    /// surface's own [`crate::Surface::mesh_view`] sets it). The LOD measures the eye's
    /// distance to the patches' rest footprints in that frame. Default `[0, 0]`.
    pub fn with_origin(mut self, origin: [f32; 2]) -> Self {
        self.origin = origin;
        self
    }

    /// The rest place `(x, z)` of node `(0, 0)` (see [`MeshView::with_origin`]).
    pub fn origin(&self) -> [f32; 2] {
        self.origin
    }

    /// The same view, read by the render-side stages at `level` (clamped to what the CPU
    /// has). Every level gives the same results, bit for bit.
    pub fn with_simd_level(mut self, level: SimdLevel) -> Self {
        self.simd = level.clamped();
        self
    }

    /// The same view, its render-side stages ([`crate::mesh`], [`crate::refraction`],
    /// [`crate::buffers`]) handing their parts to `jobs`, the host's job system, with the
    /// same results (see [`JobSystem`](crate::JobSystem): a part the job system skips runs
    /// on the calling thread). [`Surface::mesh_view`](crate::Surface::mesh_view) already
    /// carries the surface's job system or thread pool; a view built with
    /// [`MeshView::new`] runs on the rayon pool the caller is in (`pool.install(..)` picks
    /// one; in order on the calling thread without the `parallel` feature) until given a
    /// job system here.
    pub fn with_job_system(self, jobs: &'a dyn crate::JobSystem) -> Self {
        self.with_runner(Runner::Jobs(jobs))
    }

    /// The same view, its stages' parts run by `runner` (the surface's host).
    pub(crate) fn with_runner(mut self, runner: Runner<'a>) -> Self {
        self.runner = runner;
        self
    }

    /// Where the render-side stages run their parts on this view.
    pub(crate) fn runner(&self) -> Runner<'a> {
        self.runner
    }

    /// The SIMD level the render-side stages run on this view: the widest the CPU has
    /// for a new view, the surface's for [`Surface::mesh_view`](crate::Surface::mesh_view).
    pub fn simd_level(&self) -> SimdLevel {
        self.simd
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
        same_length("position buffer", out.len(), self.grid.node_count())?;
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

    /// The normal of node `(col, row)`, computed exactly like [`compute_normals`](crate::mesh::compute_normals) does.
    ///
    /// # Panics
    ///
    /// If `col` or `row` is outside the grid.
    pub fn node_normal(&self, col: usize, row: usize) -> glam::Vec3 {
        let grid = self.grid;
        assert!(
            col < grid.cols && row < grid.rows,
            "node ({col}, {row}) is outside the grid"
        );
        let left = grid.index(col.saturating_sub(1), row);
        let right = grid.index((col + 1).min(grid.cols - 1), row);
        let up = grid.index(col, row.saturating_sub(1));
        let down = grid.index(col, (row + 1).min(grid.rows - 1));
        let (x, y, z) = (self.x, self.y, self.z);
        let u = [x[right] - x[left], y[right] - y[left], z[right] - z[left]];
        let v = [x[down] - x[up], y[down] - y[up], z[down] - z[up]];
        let n = [
            v[1] * u[2] - v[2] * u[1],
            v[2] * u[0] - v[0] * u[2],
            v[0] * u[1] - v[1] * u[0],
        ];
        let len2 = n[0] * n[0] + n[1] * n[1] + n[2] * n[2];
        if len2 > f32::MIN_POSITIVE && len2 < f32::INFINITY {
            let inv = 1.0 / len2.sqrt();
            glam::Vec3::new(n[0] * inv, n[1] * inv, n[2] * inv)
        } else {
            glam::Vec3::Y
        }
    }
}
