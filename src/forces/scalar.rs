//! The scalar reference step: the oracle the engine is tested against.
//!
//! It evaluates every spring once into per-family force buffers, then gives every node
//! the sum of its springs in the fixed order of [`node_force`], then integrates.

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

/// Sum of a node's spring forces, pairing each family's spring leaving the node with the
/// same family's spring arriving at it:
///
/// ```text
/// (E[i] − E[west]) + (S[i] − S[north]) + (SE[i] − SE[north-west]) + (SW[i] − SW[north-east])
/// ```
///
/// (a missing spring counts as 0). On a flat, uniformly tensioned lattice each pair is
/// the same number twice, so the rest state is exactly at rest. The engine evaluates the
/// same expression in lanes, which makes the two steps bitwise equal.
#[inline(always)]
pub(crate) fn node_force(out: [f32; 4], arriving: [f32; 4]) -> f32 {
    (out[0] - arriving[0])
        + (out[1] - arriving[1])
        + (out[2] - arriving[2])
        + (out[3] - arriving[3])
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
    /// `forces[family][axis][origin]`: force of that spring on its origin node.
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
    let n = grid.len();
    if scratch.forces.len() != 4 || scratch.forces[0][0].len() != n {
        scratch.forces = (0..4).map(|_| zeros3(n)).collect();
    }
    let forces = &mut scratch.forces;
    for family in Family::ALL {
        let fam = family as usize;
        for i in 0..n {
            let f = match grid.spring_end(family, i) {
                Some(j) => {
                    let pi = [state.pos[0][i], state.pos[1][i], state.pos[2][i]];
                    let pj = [state.pos[0][j], state.pos[1][j], state.pos[2][j]];
                    spring_force(pi, pj, springs.coef[fam][i], springs.rest[fam][i])
                }
                None => [0.0; 3],
            };
            for k in 0..3 {
                forces[fam][k][i] = f[k];
            }
        }
    }
    // The node each family's spring arrives from: west, north, north-west, north-east.
    let from = |family: Family, i: usize| {
        let (dc, dr) = family.offset();
        let (c, r) = grid.coords(i);
        let c = c.checked_add_signed(-dc)?;
        let r = r.checked_add_signed(-dr)?;
        (c < grid.cols).then(|| grid.index(c, r))
    };
    let mut first_bad = None;
    for i in 0..n {
        let free = state.inv_mass[i] > 0.0;
        let mut finite = true;
        for k in 0..3 {
            let leaving = Family::ALL.map(|f| forces[f as usize][k][i]);
            let arriving =
                Family::ALL.map(|f| from(f, i).map_or(0.0, |j| forces[f as usize][k][j]));
            let mut force = node_force(leaving, arriving);
            if state.ext_pending {
                force += state.ext[k][i];
            }
            let accel = if free { cfg.accel[k] } else { 0.0 };
            let (x, v) = integrate(
                state.pos[k][i],
                state.vel[k][i],
                force,
                state.inv_mass[i],
                state.viscosity[i],
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
