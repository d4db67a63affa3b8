//! The ring test of an edge condition: a bump dropped on calm water spreads as a ring;
//! whatever the edge sends back into the middle is measured against a reference run on a
//! grid padded so far that nothing comes back within the time window. Shared by
//! `tests/absorbing.rs` and `examples/ring_test.rs` (which plots it).
//!
//! Energies are the linear vertical energy of the lattice,
//! `E = ½ m Σ vy² + ½ Σ_springs c (1 − r) (y_i − y_j)²`, summed over nodes (and springs
//! with both ends) inside a region.

#![allow(dead_code)]

use springwater::{Boundary, Params, Surface};

/// Steps in the time window (the ring crosses about 0.65 cells per step: from the centre
/// of a 192² grid with a 32-ring frame, what the pinned ring sends back is inside the
/// undamped middle again by step 250).
pub const WINDOW: usize = 300;
/// Steps between the samples of the plot (`examples/ring_test.rs`); the reflection is
/// taken at every step.
pub const SAMPLE: usize = 4;
/// Height of the bump (small: the test is about the linear waves).
pub const HEIGHT: f32 = 0.05;

/// Where the bump is dropped.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum Source {
    Centre,
    /// Near a corner of the undamped middle.
    Corner,
}

/// The seed's lattice without viscosity on an `n × n` grid.
pub fn params(n: usize, boundary: Boundary) -> Params {
    Params::with_size(n, n)
        .with_viscosity(0.0)
        .with_boundary(boundary)
}

/// Width of a surface's damping frame, read off its viscosities (the frame damps the
/// rings `1 ≤ d < W` from the edge; 0 for walls and free edges). The default absorbing
/// width fits itself to the grid, so the boundary alone does not say it.
pub fn frame(s: &Surface) -> usize {
    let grid = s.grid();
    let water = s.params().viscosity;
    s.viscosities()
        .iter()
        .enumerate()
        .filter(|&(_, &g)| g > water)
        .map(|(i, _)| grid.edge_distance(i) + 1)
        .max()
        .unwrap_or(0)
}

/// Where the bump goes on an `n × n` grid whose edge has a frame of `w` cells.
pub fn source(n: usize, w: usize, at: Source) -> (f32, f32) {
    match at {
        Source::Centre => ((n / 2) as f32, (n / 2) as f32),
        Source::Corner => {
            let s = (1.5 * w as f32 + 4.0).max(16.0).round();
            (s, s)
        }
    }
}

/// Heights and vertical velocities of a window, row-major, in `f64`.
pub type Field = (Vec<f64>, Vec<f64>);

/// `y` and `vy` of the `n × n` window at `(off, off)` of `s`, in `f64`.
pub fn window(s: &Surface, n: usize, off: usize) -> Field {
    let cols = s.params().cols;
    let (y, vy) = (s.positions()[1], s.velocities()[1]);
    let at = |r: usize, c: usize| (r + off) * cols + c + off;
    let pick = |a: &[f32]| {
        (0..n * n)
            .map(|i| a[at(i / n, i % n)] as f64)
            .collect::<Vec<_>>()
    };
    (pick(y), pick(vy))
}

/// Linear vertical energy of an `n × n` field over nodes `d` cells or more from its edge.
pub fn energy(p: &Params, n: usize, y: &[f64], vy: &[f64], d: usize) -> f64 {
    let inside = |c: isize, r: isize| {
        let n = n as isize;
        let d = d as isize;
        c >= d && r >= d && c < n - d && r < n - d
    };
    let (m, k) = (p.mass as f64, (p.stiffness * (1.0 - p.rest_ratio)) as f64);
    let mut e = 0.0;
    for r in 0..n as isize {
        for c in 0..n as isize {
            if !inside(c, r) {
                continue;
            }
            let i = (r * n as isize + c) as usize;
            e += 0.5 * m * vy[i] * vy[i];
            for (dc, dr) in [(1, 0), (0, 1), (1, 1), (-1, 1)] {
                let (cj, rj) = (c + dc, r + dr);
                if inside(cj, rj) {
                    let dy = y[i] - y[(rj * n as isize + cj) as usize];
                    e += 0.5 * k * dy * dy;
                }
            }
        }
    }
    e
}

/// The reference: the same bump on an `n`-grid padded by enough cells on every side that
/// nothing reflected reaches the window in time, run step by step beside the surface under
/// test.
pub struct Reference {
    surface: Surface,
    pad: usize,
    n: usize,
    /// The bump's energy.
    pub e0: f64,
}

impl Reference {
    pub fn new(n: usize, w: usize, at: Source, radius: f32) -> Self {
        let (sx, sz) = source(n, w, at);
        // The fastest linear waves cross 0.8 cells per step at most.
        let reach = 0.8 * WINDOW as f64 - sx as f64 - w.max(1) as f64;
        let pad = (reach / 2.0).max(0.0).ceil() as usize + 12;
        let big = n + 2 * pad;
        let params = params(big, Boundary::Pinned);
        let mut surface = Surface::new(params).unwrap();
        surface
            .drop_at(sx + pad as f32, sz + pad as f32, HEIGHT, radius)
            .unwrap();
        let (y0, v0) = window(&surface, big, 0);
        let e0 = energy(&params, big, &y0, &v0, 0);
        Self {
            surface,
            pad,
            n,
            e0,
        }
    }

    pub fn step(&mut self) {
        self.surface.step().unwrap();
    }

    /// The window the surface under test is compared with.
    pub fn field(&self) -> Field {
        window(&self.surface, self.n, self.pad)
    }
}

/// Reflected energy of a run: the share of the bump's energy in the difference between a
/// run with the boundary and the reference, on the undamped middle, at every step.
#[derive(Debug, Clone)]
pub struct Reflection {
    /// The share after each step (`at[k]` after step `k + 1`).
    pub at: Vec<f64>,
    /// The frame width the surface had.
    pub frame: usize,
}

impl Reflection {
    /// The largest share at any step of the window.
    pub fn worst(&self) -> f64 {
        self.at.iter().copied().fold(0.0, f64::max)
    }

    /// The step at which the largest share was seen.
    pub fn worst_step(&self) -> usize {
        let w = self.worst();
        self.at.iter().position(|&e| e == w).map_or(0, |k| k + 1)
    }

    /// The largest share over the steps that are multiples of `every` (a sampled window).
    pub fn sampled(&self, every: usize) -> f64 {
        self.at
            .iter()
            .skip(every - 1)
            .step_by(every)
            .copied()
            .fold(0.0, f64::max)
    }
}

/// The ring test: a bump at `at` on an `n × n` grid with `boundary`, compared at every step
/// of the window with the reference. The middle is the nodes at least `max(W, 1)` cells from
/// the edge (`W` the frame's width): the frame's own nodes are damped by design and do
/// not count.
pub fn reflection(n: usize, boundary: Boundary, at: Source, radius: f32) -> Reflection {
    let p = params(n, boundary);
    let mut s = Surface::new(p).unwrap();
    let w = frame(&s);
    let mut reference = Reference::new(n, w, at, radius);
    let (sx, sz) = source(n, w, at);
    s.drop_at(sx, sz, HEIGHT, radius).unwrap();
    let mut shares = Vec::with_capacity(WINDOW);
    for _ in 0..WINDOW {
        s.step().unwrap();
        reference.step();
        let (ry, rv) = reference.field();
        let (y, vy) = window(&s, n, 0);
        let dy: Vec<f64> = y.iter().zip(&ry).map(|(a, b)| a - b).collect();
        let dv: Vec<f64> = vy.iter().zip(&rv).map(|(a, b)| a - b).collect();
        shares.push(energy(&p, n, &dy, &dv, w.max(1)) / reference.e0);
    }
    Reflection {
        at: shares,
        frame: w,
    }
}
