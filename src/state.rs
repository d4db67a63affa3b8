//! The structure-of-arrays node state.
//!
//! What is stored per node, always: x, y, z, vx, vy, vz (twice, see below) and the
//! external forces, each its own lane-aligned `f32` buffer ([`Floats`]), and the pinned
//! flags (one byte). Node `i` lives at index `i` of each buffer. Buffers are padded past
//! the last node by more than a lane so that a SIMD chunk starting at any node, or one
//! node further, stays in bounds; the padding is zero and never moves. (Spring forces live
//! with the step that computes them: per family and row in the engine, per family and
//! node in the scalar reference.)
//!
//! What is stored per node only when a caller makes it so: mass, `1/m` and viscosity are
//! [`NodeTable`]s. While every node holds its place's default (the parameters' mass and
//! viscosity, the absorbing frame's ramp, `1/m` zero on a pinned ring) a table keeps a few
//! rows by distance from the edge, not an array; a per-node setter, a moved pin or a
//! snapshot whose arrays differ from the defaults gives it one. See [`table`] for how the
//! step reads either.
//!
//! Positions and velocities are double-buffered: a step reads the front buffers and writes
//! the back ones, and only swaps them when every new value is finite. That is what makes a
//! step transactional (see [`Surface::step`](crate::Surface::step)).

pub(crate) mod external;
pub(crate) mod table;

use crate::absorb::Frame;
use crate::grid::Grid;
use crate::params::{Boundary, Params};
use crate::simd::{round_up, Floats, MAX_LANES};
pub(crate) use external::External;
pub(crate) use table::NodeTable;
pub use table::{NodeValues, NodeValuesIter};

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
    /// External forces for the next step, cleared by a successful step.
    pub ext: External,
    /// Nodal mass `m`.
    pub mass: NodeTable,
    /// `1/m` for free nodes, `0` for pinned nodes: the integrator's only use of mass.
    /// Kept equal to what `mass` and `pinned` give ([`State::refresh_inv_mass`]).
    pub inv_mass: NodeTable,
    /// Viscosity `γ` (with the absorbing frame's ramp).
    pub viscosity: NodeTable,
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
        let pins_border = params.boundary.pins_border();
        let pinned: Vec<bool> = (0..n).map(|i| pins_border && grid.is_border(i)).collect();
        let (m, last) = (params.mass, grid.cols - 1);
        let mass = NodeTable::uniform(grid, m);
        // Row k from the top or bottom edge: the ring's row, then the rows inside it.
        let inv_mass = if pins_border {
            NodeTable::by_edge_distance(grid, 2, |k, c| {
                if k == 0 || c == 0 || c == last {
                    0.0
                } else {
                    1.0 / m
                }
            })
        } else {
            NodeTable::uniform(grid, 1.0 / m)
        };
        let viscosity = match params.boundary {
            Boundary::Absorbing { width } => {
                // The same sum as a node's `γ + frame(edge distance)` (the ramp is 0 from
                // `frame.width` rings in), one profile per row distance below the width.
                let frame = Frame::new(params, width);
                NodeTable::by_edge_distance(grid, frame.width + 1, |k, c| {
                    params.viscosity + frame.viscosity(k.min(c).min(last - c))
                })
            }
            _ => NodeTable::uniform(grid, params.viscosity),
        };
        let mut state = Self {
            grid,
            next_pos: pos.clone(),
            pos,
            vel: zeros3(len),
            next_vel: zeros3(len),
            ext: External::new(n, len),
            mass,
            inv_mass,
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

    /// Recomputes `inv_mass` from `mass` and `pinned` (profile rows again when every
    /// node's `1/m` is its default).
    pub fn refresh_inv_mass(&mut self) {
        let (mass, pinned) = (&self.mass, &self.pinned);
        self.inv_mass
            .assign(|i| if pinned[i] { 0.0 } else { 1.0 / mass.get(i) });
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
}

#[cfg(test)]
mod tests {
    use crate::{Boundary, Params, Surface};

    fn per_node(s: &Surface) -> [bool; 3] {
        let t = s.state_ref();
        [&t.mass, &t.inv_mass, &t.viscosity].map(|t| t.is_per_node())
    }

    #[test]
    fn tables_are_per_node_only_once_a_caller_sets_a_value_of_its_own() {
        for boundary in [Boundary::Pinned, Boundary::Free, Boundary::absorbing()] {
            let p = Params::with_size(40, 30).with_boundary(boundary);
            let mut s = Surface::new(p).unwrap();
            assert_eq!(per_node(&s), [false; 3], "{boundary:?}");
            // Stored as rows, read as nodes: the same values a new surface always had.
            let grid = s.grid();
            let frame = match boundary {
                Boundary::Absorbing { width } => Some(crate::absorb::Frame::new(&p, width)),
                _ => None,
            };
            for i in 0..grid.node_count() {
                let pinned = boundary.pins_border() && grid.is_border(i);
                let mut g = p.viscosity;
                if let Some(frame) = frame {
                    g += frame.viscosity(grid.edge_distance(i));
                }
                let inv = if pinned { 0.0 } else { 1.0 / p.mass };
                assert_eq!(s.state_ref().viscosity.get(i).to_bits(), g.to_bits());
                assert_eq!(s.state_ref().inv_mass.get(i).to_bits(), inv.to_bits());
                assert_eq!(s.state_ref().mass.get(i), p.mass);
            }
            // A snapshot of the defaults loads without per-node arrays.
            let back = Surface::from_bytes(&s.to_bytes()).unwrap();
            assert_eq!(per_node(&back), [false; 3]);
            // Setting a node to its own value changes nothing.
            s.set_mass(100, p.mass).unwrap();
            s.set_viscosity(100, s.viscosities()[100]).unwrap();
            assert_eq!(per_node(&s), [false; 3]);
            s.set_viscosity(100, 0.3).unwrap();
            assert_eq!(per_node(&s), [false, false, true]);
            s.set_mass(101, 5.0).unwrap();
            assert_eq!(per_node(&s), [true; 3]);
            let back = Surface::from_bytes(&s.to_bytes()).unwrap();
            assert_eq!(per_node(&back), [true; 3]);
            assert_eq!(back.masses().to_vec(), s.masses().to_vec());
            assert_eq!(back.viscosities()[100], 0.3);
        }
    }

    #[test]
    fn a_pin_makes_only_the_inverse_mass_per_node() {
        let mut s = Surface::new(Params::with_size(20, 20)).unwrap();
        s.set_pinned(50, true).unwrap();
        assert_eq!(per_node(&s), [false, true, false]);
        assert_eq!(s.state_ref().inv_mass.get(50), 0.0);
        s.set_pinned(50, false).unwrap();
        s.state_mut().refresh_inv_mass();
        assert_eq!(
            per_node(&s),
            [false; 3],
            "back to the defaults, back to rows"
        );
    }

    #[test]
    fn set_values_that_leave_the_window_leave_no_array_behind() {
        let mut s = Surface::new(Params::with_size(24, 24)).unwrap();
        s.set_viscosity(24 * 12 + 2, 0.4).unwrap();
        s.shift(-1, 0).unwrap();
        assert!(
            s.state_ref().viscosity.is_per_node(),
            "the value moved with the water"
        );
        s.shift(8, 0).unwrap();
        assert!(
            !s.state_ref().viscosity.is_per_node(),
            "the value left the window"
        );
        assert!(s.viscosities().iter().all(|&g| g == 0.05));
        // A mass that leaves takes its `1/m` along.
        s.set_mass(24 * 12 + 2, 6.0).unwrap();
        assert_eq!(per_node(&s), [true, true, false]);
        s.shift(4, 0).unwrap();
        assert_eq!(per_node(&s), [false; 3]);
        let fresh = Surface::new(Params::with_size(24, 24)).unwrap();
        for i in 0..24 * 24 {
            assert_eq!(
                s.state_ref().inv_mass.get(i),
                fresh.state_ref().inv_mass.get(i),
                "node {i}"
            );
        }
    }
}
