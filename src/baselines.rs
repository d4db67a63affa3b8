//! Comparison kernels for benchmarks: what the engine is measured against.
//!
//! * [`NaiveSurface`]: the straightforward first version anyone would write — a `Vec` of
//!   node structs and a `Vec` of springs with indices, one thread, no SIMD. Same model,
//!   same seed parameters.
//! * [`MemoryFloor`]: the least any step must do on this layout — read and write each
//!   node's position and velocity once (24 B read + 24 B written per node). Its
//!   throughput is the memory-bandwidth ceiling for a step that keeps forces in cache.

use crate::grid::Grid;
use crate::params::Params;
use crate::simd::Floats;
use glam::Vec3;

/// A node of the naive array-of-structs baseline.
#[derive(Debug, Clone, Copy)]
pub struct NaiveNode {
    /// Position.
    pub pos: Vec3,
    /// Velocity.
    pub vel: Vec3,
    /// Spring force sum of the current step.
    pub force: Vec3,
    /// Mass.
    pub mass: f32,
    /// Viscosity.
    pub viscosity: f32,
    /// Never moves.
    pub pinned: bool,
}

/// A spring of the naive baseline: two node indices and its constants.
#[derive(Debug, Clone, Copy)]
pub struct NaiveSpring {
    /// First node.
    pub i: usize,
    /// Second node.
    pub j: usize,
    /// Rest length.
    pub rest: f32,
    /// Coefficient.
    pub coef: f32,
}

/// The naive array-of-structs surface.
#[derive(Debug, Clone)]
pub struct NaiveSurface {
    /// Nodes, row-major.
    pub nodes: Vec<NaiveNode>,
    /// Every spring once.
    pub springs: Vec<NaiveSpring>,
    dt: f32,
}

impl NaiveSurface {
    /// The flat rest state for `params` (not validated: benchmark use).
    pub fn new(params: &Params) -> Self {
        let grid = Grid::new(params.cols, params.rows);
        let nodes = (0..grid.node_count())
            .map(|i| {
                let (c, r) = grid.coords(i);
                NaiveNode {
                    pos: Vec3::new(c as f32 * params.spacing, 0.0, r as f32 * params.spacing),
                    vel: Vec3::ZERO,
                    force: Vec3::ZERO,
                    mass: params.mass,
                    viscosity: params.viscosity,
                    pinned: params.boundary.pins_border() && grid.is_border(i),
                }
            })
            .collect();
        let springs = grid
            .springs()
            .map(|(id, j)| NaiveSpring {
                i: id.origin,
                j,
                rest: params.rest_ratio * id.family.initial_length() * params.spacing,
                coef: params.stiffness,
            })
            .collect();
        Self {
            nodes,
            springs,
            dt: params.dt,
        }
    }

    /// Adds a drop like [`Surface::drop_at`](crate::Surface::drop_at).
    pub fn drop_at(&mut self, cols: usize, col: f32, row: f32, height: f32, radius: f32) {
        for (i, n) in self.nodes.iter_mut().enumerate().filter(|(_, n)| !n.pinned) {
            let d2 = ((i % cols) as f32 - col).powi(2) + ((i / cols) as f32 - row).powi(2);
            n.pos.y += height * (-d2 / (radius * radius)).exp();
        }
    }

    /// One step: accumulate spring forces, then integrate every node.
    pub fn step(&mut self) {
        for n in &mut self.nodes {
            n.force = Vec3::ZERO;
        }
        for s in &self.springs {
            let d = self.nodes[s.j].pos - self.nodes[s.i].pos;
            let l = d.length();
            if l > 0.0 {
                let f = d * (s.coef * (l - s.rest) / l);
                self.nodes[s.i].force += f;
                self.nodes[s.j].force -= f;
            }
        }
        for n in &mut self.nodes {
            if !n.pinned {
                let a = (n.force - n.viscosity * n.vel) / n.mass;
                n.vel += a * self.dt;
                n.pos += n.vel * self.dt;
            }
        }
    }
}

/// Positions and velocities only, streamed once per pass.
#[derive(Debug, Clone)]
pub struct MemoryFloor {
    pos: [Floats; 3],
    vel: [Floats; 3],
}

impl MemoryFloor {
    /// Buffers for `nodes` nodes.
    pub fn new(nodes: usize) -> Self {
        let v = || {
            let mut b = Floats::zeros(nodes);
            b.fill(0.5);
            b
        };
        Self {
            pos: [v(), v(), v()],
            vel: [v(), v(), v()],
        }
    }

    /// One pass: `v ← v·k; x ← x + v·dt` for every node and component (reads and writes
    /// 48 B per node), on the current rayon pool when `parallel` is on.
    pub fn pass(&mut self, dt: f32, k: f32) {
        for (x, v) in self.pos.iter_mut().zip(&mut self.vel) {
            let kernel = |(x, v): (&mut [f32], &mut [f32])| {
                for (x, v) in x.iter_mut().zip(v.iter_mut()) {
                    *v *= k;
                    *x += *v * dt;
                }
            };
            const CHUNK: usize = 1 << 14;
            #[cfg(feature = "parallel")]
            {
                use rayon::prelude::*;
                x.par_chunks_mut(CHUNK)
                    .zip(v.par_chunks_mut(CHUNK))
                    .for_each(kernel);
            }
            #[cfg(not(feature = "parallel"))]
            x.chunks_mut(CHUNK)
                .zip(v.chunks_mut(CHUNK))
                .for_each(kernel);
        }
    }

    /// A checksum so the optimiser cannot drop the passes.
    pub fn checksum(&self) -> f32 {
        self.pos[1][self.pos[1].len() / 2]
    }
}
