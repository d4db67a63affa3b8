//! The scalar reference step: the oracle the engine is tested against.
//!
//! It evaluates every spring once into per-family force buffers, then gives every node
//! the sum of its springs in the fixed order of [`node_force`], then integrates.
//!
//! Each spring's force is evaluated once, for one of its ends, and the other end gets it
//! negated: E, S and SE springs for their origin (the node they leave), SW springs for
//! their lower end (the node one row down and one column west). Those are the lanes the
//! engine evaluates them in, which lets it move forces between columns with one shuffle
//! per axis (see [`node_force`]).

// Index loops read like the equations here; that is the point of the oracle.
#![allow(clippy::needless_range_loop)]

use super::StepConfig;
use crate::grid::Family;
use crate::springs::Springs;
use crate::state::{zeros3, State, Xyz};

/// Force on node i from the spring (i → j): `c (L − L0) d / L` with `d = x_j − x_i`.
#[inline(always)]
pub(crate) fn spring_force(pi: [f32; 3], pj: [f32; 3], coef: f32, rest: f32) -> [f32; 3] {
    let d = [pj[0] - pi[0], pj[1] - pi[1], pj[2] - pi[2]];
    let l2 = d[0] * d[0] + d[1] * d[1] + d[2] * d[2];
    let l = l2.sqrt();
    let s = if l2 > 0.0 { coef * (l - rest) / l } else { 0.0 };
    [s * d[0], s * d[1], s * d[2]]
}

/// A node's force from its eight springs, in the order the engine sums its lanes:
///
/// ```text
/// ((E + S) + SE) + (SW[north] − S[north])  −  ((E[west] + SW[west]) + SE[north-west])
/// ```
///
/// `own = [E, S, SE]` are the springs the node is the origin of (forces on it);
/// `north = [S, SW]` the north neighbour's S spring (its force on the north neighbour)
/// and the SW spring leaving the north-east neighbour (its force on this node);
/// `west = [E, SW, SE]` what the west neighbour's lane sends east: its E spring (on it),
/// the SW spring leaving this node (on that spring's lower end), and the north-west
/// neighbour's SE spring (on it). Every term is the force on some other node
/// than this one exactly when it is subtracted. A missing spring, or a missing west
/// neighbour, counts as +0. On a flat, uniformly tensioned lattice both halves are the
/// same sums of the same numbers, so the rest state is exactly at rest.
#[inline(always)]
pub(crate) fn node_force(own: [f32; 3], north: [f32; 2], west: [f32; 3]) -> f32 {
    (((own[0] + own[1]) + own[2]) + (north[1] - north[0])) - ((west[0] + west[1]) + west[2])
}

/// Symplectic Euler for one component: returns `(x', v')`.
#[inline(always)]
pub(crate) fn integrate(
    x: f32,
    v: f32,
    force: f32,
    inv_mass: f32,
    viscosity: f32,
    accel: f32,
    dt: f32,
) -> (f32, f32) {
    let a = (force - viscosity * v) * inv_mass + accel;
    let v1 = v + a * dt;
    (x + v1 * dt, v1)
}

/// `x`, or +0 when it is smaller in magnitude than [`super::CALM`] (NaN stays NaN): the
/// rule for new heights and vertical velocities.
#[inline(always)]
pub(crate) fn calm(x: f32) -> f32 {
    if x.abs() < super::CALM {
        0.0
    } else {
        x
    }
}

/// Per-family spring force buffers of the reference step, allocated on first use.
#[derive(Debug, Clone, Default)]
pub(crate) struct Scratch {
    /// `forces[family][axis][origin]`: that spring's force on its origin node (SW: on
    /// its lower end).
    forces: Vec<Xyz>,
}

/// One step into the back buffers. Returns the first node whose new state is not finite.
pub(crate) fn step(
    state: &mut State,
    springs: &Springs,
    scratch: &mut Scratch,
    cfg: StepConfig,
) -> Result<(), usize> {
    let grid = state.grid;
    let n = grid.node_count();
    if scratch.forces.len() != 4 || scratch.forces[0][0].len() != n {
        scratch.forces = (0..4).map(|_| zeros3(n)).collect();
    }
    let forces = &mut scratch.forces;
    for family in Family::ALL {
        let fam = family as usize;
        for i in 0..n {
            let f = match grid.spring_end(family, i) {
                Some(j) => {
                    // SW springs are evaluated for their lower end (see the module docs).
                    let (a, b) = if family == Family::SW { (j, i) } else { (i, j) };
                    let pa = [state.pos[0][a], state.pos[1][a], state.pos[2][a]];
                    let pb = [state.pos[0][b], state.pos[1][b], state.pos[2][b]];
                    let (coef, rest) = springs.get(family, i);
                    spring_force(pa, pb, coef, rest)
                }
                None => [0.0; 3],
            };
            for k in 0..3 {
                forces[fam][k][i] = f[k];
            }
        }
    }
    // Family `f`'s force (as evaluated above) of the spring leaving node (c, r), or +0.
    let (cols, rows) = (grid.cols, grid.rows);
    let at = |f: Family, k: usize, c: usize, r: usize| {
        if c < cols && r < rows {
            forces[f as usize][k][grid.index(c, r)]
        } else {
            0.0
        }
    };
    let ext = state.ext.pending();
    let mut first_bad = None;
    for i in 0..n {
        let (c, r) = grid.coords(i);
        let (inv_mass, viscosity) = (state.inv_mass.get(i), state.viscosity.get(i));
        let free = inv_mass > 0.0;
        let mut finite = true;
        for k in 0..3 {
            let own = [Family::E, Family::S, Family::SE].map(|f| at(f, k, c, r));
            let north = match r.checked_sub(1) {
                Some(up) => [at(Family::S, k, c, up), at(Family::SW, k, c + 1, up)],
                None => [0.0; 2],
            };
            let west = match c.checked_sub(1) {
                Some(w) => [
                    at(Family::E, k, w, r),
                    at(Family::SW, k, c, r),
                    r.checked_sub(1).map_or(0.0, |up| at(Family::SE, k, w, up)),
                ],
                None => [0.0; 3],
            };
            let mut force = node_force(own, north, west);
            if let Some(ext) = ext {
                force += ext[k][i];
            }
            let accel = if free { cfg.accel[k] } else { 0.0 };
            let (x, v) = integrate(
                state.pos[k][i],
                state.vel[k][i],
                force,
                inv_mass,
                viscosity,
                accel,
                cfg.dt,
            );
            // Vertical: calm water is exactly calm (see the module docs of `forces`).
            let (x, v) = if k == 1 { (calm(x), calm(v)) } else { (x, v) };
            state.next_pos[k][i] = x;
            state.next_vel[k][i] = v;
            finite &= x.is_finite() && v.is_finite();
        }
        if !finite && first_bad.is_none() {
            first_bad = Some(i);
        }
    }
    first_bad.map_or(Ok(()), Err)
}
