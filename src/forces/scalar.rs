//! The scalar reference step: the oracle the engine is tested against.

use super::StepConfig;
use crate::springs::Springs;
use crate::state::State;

/// Force on node i from the spring (i → j): `c (L − L0) d / L` with `d = x_j − x_i`.
#[inline(always)]
pub(crate) fn spring_force(pi: [f32; 3], pj: [f32; 3], coef: f32, rest: f32) -> [f32; 3] {
    let d = [pj[0] - pi[0], pj[1] - pi[1], pj[2] - pi[2]];
    let l2 = d[0] * d[0] + d[1] * d[1] + d[2] * d[2];
    let l = l2.sqrt();
    let s = if l2 > 0.0 { coef * (l - rest) / l } else { 0.0 };
    [s * d[0], s * d[1], s * d[2]]
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

/// One step into the back buffers. Returns the first node whose new state is not finite.
pub(crate) fn step(state: &mut State, springs: &Springs, cfg: StepConfig) -> Result<(), usize> {
    let grid = state.grid;
    let n = grid.len();
    for f in &mut state.force {
        f[..n].fill(0.0);
    }
    for (id, j) in grid.springs() {
        let i = id.origin;
        let pi = [state.pos[0][i], state.pos[1][i], state.pos[2][i]];
        let pj = [state.pos[0][j], state.pos[1][j], state.pos[2][j]];
        let fam = id.family as usize;
        let f = spring_force(pi, pj, springs.coef[fam][i], springs.rest[fam][i]);
        for k in 0..3 {
            state.force[k][i] += f[k];
            state.force[k][j] -= f[k];
        }
    }
    let mut first_bad = None;
    for i in 0..n {
        let free = state.inv_mass[i] > 0.0;
        let mut finite = true;
        for k in 0..3 {
            let force = state.force[k][i] + state.ext[k][i];
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
