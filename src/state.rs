//! The structure-of-arrays node state.
//!
//! Every per-node quantity is its own lane-aligned `f32` buffer ([`Floats`]): x, y, z, vx, vy, vz, external forces,
//! mass, viscosity. (Spring forces live with the step that computes them: per family and
//! row in the engine, per family and node in the scalar reference.) Node `i` lives at index `i` of each buffer. Buffers are padded past the
//! last node by more than a lane so that a SIMD chunk starting at any node, or one node
//! further, stays in bounds; the padding is zero and never moves.
//!
//! Positions and velocities are double-buffered: a step reads the front buffers and writes
//! the back ones, and only swaps them when every new value is finite. That is what makes a
//! step transactional (see [`Surface::step`](crate::Surface::step)).

use crate::absorb::Frame;
use crate::grid::Grid;
use crate::params::{Boundary, Params};
use crate::simd::{round_up, Floats, MAX_LANES};

/// Three coordinate buffers, `[x, y, z]`.
pub(crate) type Xyz = [Floats; 3];

pub(crate) fn zeros3(len: usize) -> Xyz {
    [Floats::zeros(len), Floats::zeros(len), Floats::zeros(len)]
}

/// Length of a padded per-node buffer for `nodes` nodes.
pub(crate) fn padded_len(nodes: usize) -> usize {
    round_up(nodes + 2 * MAX_LANES)
}

/// Node state and per-node tables.
#[derive(Debug, Clone)]
pub(crate) struct State {
    pub grid: Grid,
    /// Positions (front buffer).
    pub pos: Xyz,
    /// Velocities (front buffer).
    pub vel: Xyz,
    /// Positions being written by a step (back buffer).
    pub next_pos: Xyz,
    /// Velocities being written by a step (back buffer).
    pub next_vel: Xyz,
    /// External force per node for the next step, cleared by a successful step.
    pub ext: Xyz,
    /// True when `ext` holds anything non-zero.
    pub ext_pending: bool,
    /// Every node whose `ext` may be non-zero, while there are few of them (`None`: any
    /// node may be). Lets a step clear a few forces without rewriting the whole buffer.
    pub ext_nodes: Option<Vec<usize>>,
    /// One flag per row: whether the row holds a node of `ext_nodes` (see
    /// [`State::mark_ext_rows`]).
    pub ext_rows: Vec<bool>,
    /// Nodal mass `m`.
    pub mass: Floats,
    /// `1/m` for free nodes, `0` for pinned nodes: the integrator's only use of mass.
    pub inv_mass: Floats,
    /// Viscosity `γ`.
    pub viscosity: Floats,
    /// Pinned nodes never move (but for the calm rule of [`crate::forces`]: a pinned
    /// height below 1e-18 becomes +0).
    pub pinned: Vec<bool>,
}

impl State {
    /// The flat rest state of `params`: node `(col, row)` at `(col·h, 0, row·h)`, at rest.
    pub fn new(params: &Params) -> Self {
        let grid = Grid::new(params.cols, params.rows);
        let n = grid.node_count();
        let len = padded_len(n);
        let mut pos = zeros3(len);
        let [x, _, z] = &mut pos;
        for (i, (x, z)) in x.iter_mut().zip(z.iter_mut()).take(n).enumerate() {
            let (c, r) = grid.coords(i);
            *x = c as f32 * params.spacing;
            *z = r as f32 * params.spacing;
        }
        let mut mass = Floats::zeros(len);
        mass[..n].fill(params.mass);
        let mut viscosity = Floats::zeros(len);
        viscosity[..n].fill(params.viscosity);
        if let Boundary::Absorbing { width } = params.boundary {
            let frame = Frame::new(params, width);
            for (i, g) in viscosity[..n].iter_mut().enumerate() {
                *g += frame.viscosity(grid.edge_distance(i));
            }
        }
        let pinned: Vec<bool> = (0..n)
            .map(|i| params.boundary.pins_border() && grid.is_border(i))
            .collect();
        let mut state = Self {
            grid,
            next_pos: pos.clone(),
            pos,
            vel: zeros3(len),
            next_vel: zeros3(len),
            ext: zeros3(len),
            ext_pending: false,
            ext_nodes: Some(Vec::new()),
            ext_rows: Vec::new(),
            mass,
            inv_mass: Floats::zeros(len),
            viscosity,
            pinned,
        };
        state.refresh_inv_mass();
        state
    }

    /// Number of nodes.
    pub fn len(&self) -> usize {
        self.grid.node_count()
    }

    /// Recomputes `inv_mass` from `mass` and `pinned`.
    pub fn refresh_inv_mass(&mut self) {
        for i in 0..self.len() {
            self.inv_mass[i] = if self.pinned[i] {
                0.0
            } else {
                1.0 / self.mass[i]
            };
        }
    }

    /// Makes the back buffers the front ones.
    pub fn swap(&mut self) {
        std::mem::swap(&mut self.pos, &mut self.next_pos);
        std::mem::swap(&mut self.vel, &mut self.next_vel);
    }

    /// The first node whose back-buffer position or velocity is not finite.
    pub fn first_non_finite_next(&self) -> Option<usize> {
        (0..self.len()).find(|&i| {
            self.next_pos
                .iter()
                .chain(&self.next_vel)
                .any(|b| !b[i].is_finite())
        })
    }

    /// Clears the external force buffer after it has been applied.
    pub fn clear_ext(&mut self) {
        if self.ext_pending {
            match &mut self.ext_nodes {
                Some(nodes) => {
                    for &i in nodes.iter() {
                        for c in &mut self.ext {
                            c[i] = 0.0;
                        }
                    }
                    nodes.clear();
                }
                None => {
                    for c in &mut self.ext {
                        c.fill(0.0);
                    }
                    self.ext_nodes = Some(Vec::new());
                }
            }
            self.ext_pending = false;
        }
    }

    /// Notes that `ext[node]` was written.
    pub fn touch_ext(&mut self, node: usize) {
        self.ext_pending = true;
        let limit = self.len() / 16;
        if let Some(nodes) = &mut self.ext_nodes {
            if nodes.len() < limit {
                nodes.push(node);
            } else {
                self.ext_nodes = None;
            }
        }
    }

    /// Sets `ext_rows` to the rows that hold a listed node of `ext_nodes` and returns true,
    /// or returns false when any node may hold a force (`ext_nodes` is `None`). A step
    /// then reads the force buffers only on those rows: a floating body's push costs its
    /// rows, not the grid.
    pub fn mark_ext_rows(&mut self) -> bool {
        let Some(nodes) = &self.ext_nodes else {
            return false;
        };
        let cols = self.grid.cols;
        self.ext_rows.clear();
        self.ext_rows.resize(self.grid.rows, false);
        for &i in nodes {
            self.ext_rows[i / cols] = true;
        }
        true
    }

    /// Notes that `ext` was written anywhere.
    pub fn touch_all_ext(&mut self) {
        self.ext_pending = true;
        self.ext_nodes = None;
    }
}
