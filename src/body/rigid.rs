//! One step of a floating rigid body: the water's forces on its wet triangles, solved
//! implicitly for the new velocity and angular velocity, then the pose moved.
//!
//! # What acts on the body
//!
//! The `hydrostatics` module hands over the wet part of the body's mesh as pieces: a point
//! `pᵢ` (the piece's centre of pressure), the pressure force `fᵢ` there and the piece's
//! area `Aᵢ`; and the waterplane (area `A_w`, centre, second moments). With `c` the centre
//! of mass, `dᵢ = pᵢ − c`, `u = (v, ω)` the body's velocity and angular velocity:
//!
//! * **Pressure** `fᵢ` at `pᵢ`: buoyancy, and on waves the push of the slope.
//! * **Drag** pulls each piece towards the water's velocity `wᵢ` under it, by how much of
//!   the piece faces the motion: `gᵢ = Gᵢ (wᵢ − v − ω × dᵢ)` with
//!   `Gᵢ = rᵢ (F nᵢnᵢᵀ + S (1 − nᵢnᵢᵀ))`, `nᵢ` the piece's outward normal. The form part
//!   `F` = [`FORM`] pushes along the normal (water meeting a face head on), the skin part
//!   `S` = [`SKIN`] along the face (water sliding past it); `F + 2S = 3`, so a body whose
//!   faces point every way (a ball) is slowed as by the rate `rᵢ` in every direction, and
//!   a hull is slowed far more sideways than along its length: its keel. The rates
//!   `rᵢ = R Aᵢ / Σ A` share out the body's rate `R = k ρ V` (the drag rate `k` times the
//!   displaced water's mass) by wet area; a piece without a normal (the one point of a
//!   small body) has `Gᵢ = rᵢ 1`. Written with `Jᵢ = [1, −[dᵢ]×]` (the map from `u` to the
//!   piece's velocity), the drag's force and torque are `Σ Jᵢᵀ gᵢ = s − D u` with the
//!   damping matrix `D = Σ JᵢᵀGᵢJᵢ` (symmetric, positive semidefinite) and
//!   `s = Σ Jᵢᵀ Gᵢ wᵢ`. Since `Gᵢ = rᵢ S 1 + rᵢ (F − S) nᵢnᵢᵀ`, `D` is built as the
//!   isotropic sum of the rates `rᵢ S` plus the rank-one terms `rᵢ (F − S) aᵢaᵢᵀ` with
//!   `aᵢ = Jᵢᵀ nᵢ = (nᵢ, dᵢ × nᵢ)`.
//! * **Gravity** `−m g ŷ` through `c`, and the caller's push and torque.
//!
//! # Why implicit, and how
//!
//! For a light body the water is a stiff spring and a strong damper: a ping-pong ball's
//! buoyancy changes by many times its weight when it dips by its radius, and a wide raft's
//! righting moment is huge against its small moment of inertia. An explicit step of
//! either blows up. So the step is linearly implicit in the velocities (backward Euler on
//! the forces, linearised at the current pose), as the water's own absorbing frame is:
//!
//! ```text
//! (M + Δt D + Δt² K) u' = M u + Δt (F₀ + s + F_ext)
//! ```
//!
//! with `M = diag(m 1, I_world)` (`I_world = R I_body Rᵀ`), `F₀` the pressure forces and
//! their torques about `c` at the current pose, and `K` the hydrostatic stiffness: how the
//! buoyancy's force and torque change as the body moves, `−K Δt u'` over the step. `K`
//! comes from the waterplane, the water's section through the body: raising a point of
//! the waterplane at `(x', z')` (measured from `c`) by `δ` loses buoyancy `ρ g δ` per unit
//! area there, and the point rises at `jᵀ u` with `j = (0, 1, 0, −z', 0, x')` (heave,
//! and roll and pitch about `c`), so
//!
//! ```text
//! K = ρ g ∫_waterplane j jᵀ dA
//! ```
//!
//! built from the waterplane's area, first and second moments. `K` and `D` are symmetric
//! positive semidefinite and `M` is positive definite, so the system always has one
//! solution and the step cannot gain energy from them, whatever the mass, size and drag.
//! (The part of the righting moment that comes from the centre of buoyancy sitting below
//! or above `c`, `ρ g V·KB − m g·KG`, stays explicit: it can be negative, which is what
//! capsizes a tall box, and it is gentle next to the waterplane's.)
//!
//! The solve runs in `f64` by Gaussian elimination (no pivoting is needed for a symmetric
//! positive definite matrix), with `+`, `−`, `×`, `÷` only.
//!
//! # The forces handed back, and the water's share
//!
//! The body's force and torque over the step are the forces above at `u'`: each piece's
//! `fᵢ + gᵢ(u')` at `pᵢ`, and the stiffness term `−Δt K u'` as four vertical forces on the
//! waterplane, at points that reproduce its area, first and second moments (its centre
//! plus and minus √2 times the columns of the Cholesky factor of its second moments per
//! area, each carrying a quarter of the area), which makes their sum and their moments
//! exactly `−Δt K u'`. The water gets minus every one of these pieces at its own point,
//! so its force and torque (about any point) are exactly minus the body's, to rounding;
//! and `M (u' − u) = Δt (F + F_ext)` to the rounding of the solve.
//!
//! # Moving the pose
//!
//! `x ← x + Δt v'` and `q ← normalise(q + Δt/2 (ω' ⊗ q))` (symplectic Euler, like the
//! water): the orientation stays a unit quaternion. The gyroscopic term `ω × I ω` is left
//! out, as most game physics engines leave it by default: the angular momentum changes only
//! by the torques, which cannot make a free spin speed up, and a floating body's spin is
//! slow and damped by the water.

use super::math::{normalised, outer, rotation, skew};
use glam::{DMat3, DQuat, DVec3};

/// A rigid body's state for one step, in `f64`: what [`step`] needs of a floating body.
#[derive(Debug, Clone, Copy)]
pub(crate) struct Rigid {
    pub mass: f64,
    /// Inertia tensor about the centre of mass, body axes.
    pub inertia: DMat3,
    /// Centre of mass, world.
    pub position: DVec3,
    /// Body to world.
    pub orientation: DQuat,
    pub velocity: DVec3,
    pub angular_velocity: DVec3,
    /// External force through the centre of mass, and torque about it.
    pub push: DVec3,
    pub push_torque: DVec3,
}

/// The form part of the drag: along a piece's normal, per unit of its share of the rate.
pub(crate) const FORM: f64 = 2.8;
/// The skin part of the drag: along a piece's face (`FORM + 2 SKIN = 3`).
pub(crate) const SKIN: f64 = 0.1;

/// A wet piece of the hull (from the `hydrostatics` module), with the water under it.
#[derive(Debug, Clone, Copy, Default)]
pub(crate) struct Piece {
    /// Centre of pressure, world.
    pub point: DVec3,
    /// Pressure force on the body there.
    pub force: DVec3,
    /// Wet area.
    pub area: f64,
    /// Water velocity under the point, world units per second.
    pub flow: DVec3,
    /// Outward unit normal, or zero for a piece that drags alike in every direction.
    pub normal: DVec3,
}

impl Piece {
    /// The piece's drag at rate `r` as its isotropic rate and the rate along its normal:
    /// `G = iso 1 + along n nᵀ` (`(r S, r (F − S))`, or `(r, 0)` without a normal).
    fn rates(&self, r: f64) -> (f64, f64) {
        if self.normal == DVec3::ZERO {
            (r, 0.0)
        } else {
            (r * SKIN, r * (FORM - SKIN))
        }
    }

    /// The drag force `G u` on the piece moving at `u` relative to the water, at rate `r`.
    fn drag(&self, r: f64, u: DVec3) -> DVec3 {
        let (iso, along) = self.rates(r);
        u * iso + self.normal * (along * self.normal.dot(u))
    }
}

/// The water's section through the body, seen from above (its waterplane), in `f64`: area
/// and moments, world `(x, z)`. The public [`Waterplane`](super::Waterplane) is this
/// rounded to `f32`.
#[derive(Debug, Clone, Copy, Default)]
pub(crate) struct Section {
    pub area: f64,
    /// Its centroid's world `(x, z)`.
    pub centre: [f64; 2],
    /// Second moments about the centre: `∫ x'², ∫ x' z', ∫ z'²`.
    pub second: [f64; 3],
}

/// The world the body floats in, for one step.
#[derive(Debug, Clone, Copy)]
pub(crate) struct World {
    /// `ρ g`.
    pub rho_g: f64,
    /// Gravity's magnitude, per second².
    pub gravity: f64,
    /// The step, seconds.
    pub dt: f64,
    /// The body's drag rate in mass per second (`k ρ V`, capped by the water's room).
    pub drag_rate: f64,
}

/// The body after its step: new velocities and pose, and the water's force and torque
/// (about the centre of mass before the step) over it.
#[derive(Debug, Clone, Copy)]
pub(crate) struct Moved {
    pub velocity: DVec3,
    pub angular_velocity: DVec3,
    pub position: DVec3,
    pub orientation: DQuat,
    pub force: DVec3,
    pub torque: DVec3,
}

/// One implicit step of `body` under the wet `pieces` and `plane` (see the module docs).
/// Fills `forces` with each force the body feels and the point it acts at (the pieces'
/// pressure and drag, then the four waterplane forces): the water gets minus each.
pub(crate) fn step(
    body: &Rigid,
    pieces: &[Piece],
    plane: &Section,
    world: World,
    forces: &mut Vec<(DVec3, DVec3)>,
) -> Moved {
    let dt = world.dt;
    let m = body.mass;
    let c = body.position;
    let q = normalised(body.orientation);
    let r = rotation(q);
    let inertia = r * body.inertia * r.transpose();
    let (v, w) = (body.velocity, body.angular_velocity);

    // Pressure at the current pose, and the drag's matrix and source.
    let wet: f64 = pieces.iter().map(|p| p.area).sum();
    let per_area = if wet > 0.0 {
        world.drag_rate / wet
    } else {
        0.0
    };
    let (mut f0, mut t0) = (DVec3::ZERO, DVec3::ZERO);
    // The isotropic part of D (Σ rate, Σ rate d, Σ rate (|d|² 1 − d dᵀ)), its rank-one
    // part (Σ along a aᵀ, a = (n, d × n), a 6 × 6 sum), and the source.
    let (mut rate, mut rate_d, mut rate_dd) = (0.0, DVec3::ZERO, DMat3::ZERO);
    let mut ranked = [[0.0f64; 6]; 6];
    let (mut src_f, mut src_t) = (DVec3::ZERO, DVec3::ZERO);
    for p in pieces {
        let d = p.point - c;
        f0 += p.force;
        t0 += d.cross(p.force);
        let (iso, along) = p.rates(per_area * p.area);
        rate += iso;
        rate_d += d * iso;
        rate_dd += (DMat3::IDENTITY * d.length_squared() - outer(d, d)) * iso;
        let pull = p.drag(per_area * p.area, p.flow);
        src_f += pull;
        src_t += d.cross(pull);
        if along != 0.0 {
            let (n, m) = (p.normal, d.cross(p.normal));
            let a = [n.x, n.y, n.z, m.x, m.y, m.z];
            for (i, row) in ranked.iter_mut().enumerate() {
                let ai = along * a[i];
                for (j, value) in row.iter_mut().enumerate().skip(i) {
                    *value += ai * a[j];
                }
            }
        }
    }

    // The waterplane's moments about c, and its stiffness K on (v_y, ω_x, ω_z).
    let (a, [cx, cz], [sxx, sxz, szz]) = (plane.area, plane.centre, plane.second);
    let (x0, z0) = (cx - c.x, cz - c.z);
    let k = world.rho_g;
    let (k_yy, k_yx, k_yz) = (k * a, -k * a * z0, k * a * x0);
    let k_xx = k * (szz + a * z0 * z0);
    let k_xz = -k * (sxz + a * x0 * z0);
    let k_zz = k * (sxx + a * x0 * x0);

    // The system (M + Δt D + Δt² K) u' = b, unknowns (v'x, v'y, v'z, ω'x, ω'y, ω'z).
    let mut sys = [[0.0f64; 7]; 6];
    let h2 = dt * dt;
    for i in 0..3 {
        sys[i][i] = m + dt * rate;
        for j in 0..3 {
            sys[3 + i][3 + j] = inertia.col(j)[i] + dt * rate_dd.col(j)[i];
        }
    }
    // The isotropic part's off-diagonal blocks: −[Σ r d]× above, [Σ r d]× below.
    let cross = skew(rate_d);
    for i in 0..3 {
        for j in 0..3 {
            sys[i][3 + j] = -dt * cross.col(j)[i];
            sys[3 + i][j] = dt * cross.col(j)[i];
        }
    }
    // The rank-one part, symmetric (its upper triangle summed), if any piece has a normal.
    let ranked_any = pieces.iter().any(|p| p.normal != DVec3::ZERO);
    for i in (0..6).filter(|_| ranked_any) {
        for j in i..6 {
            sys[i][j] += dt * ranked[i][j];
            if i != j {
                sys[j][i] += dt * ranked[i][j];
            }
        }
    }
    let stiff = [
        (1, 1, k_yy),
        (1, 3, k_yx),
        (1, 5, k_yz),
        (3, 3, k_xx),
        (3, 5, k_xz),
        (5, 5, k_zz),
    ];
    for (i, j, value) in stiff {
        sys[i][j] += h2 * value;
        if i != j {
            sys[j][i] += h2 * value;
        }
    }
    let gravity = DVec3::new(0.0, -m * world.gravity, 0.0);
    let b_f = v * m + (f0 + src_f + body.push + gravity) * dt;
    let b_t = inertia * w + (t0 + src_t + body.push_torque) * dt;
    for i in 0..3 {
        sys[i][6] = b_f[i];
        sys[3 + i][6] = b_t[i];
    }
    let u = solve(sys);
    let (v1, w1) = (DVec3::new(u[0], u[1], u[2]), DVec3::new(u[3], u[4], u[5]));

    // The forces at u', piece by piece.
    forces.clear();
    let (mut force, mut torque) = (DVec3::ZERO, DVec3::ZERO);
    let mut feel = |point: DVec3, f: DVec3| {
        force += f;
        torque += (point - c).cross(f);
        forces.push((point, f));
    };
    for p in pieces {
        let d = p.point - c;
        let drag = p.drag(per_area * p.area, p.flow - v1 - w1.cross(d));
        feel(p.point, p.force + drag);
    }
    if a > 0.0 {
        for (x, z) in quadrature(a, [sxx, sxz, szz]) {
            let (px, pz) = (x0 + x, z0 + z);
            let rise = v1.y - pz * w1.x + px * w1.z;
            let f = DVec3::new(0.0, -dt * k * 0.25 * a * rise, 0.0);
            feel(DVec3::new(c.x + px, c.y, c.z + pz), f);
        }
    }

    let spin = DQuat::from_xyzw(w1.x, w1.y, w1.z, 0.0) * q;
    let turned = DQuat::from_xyzw(
        q.x + 0.5 * dt * spin.x,
        q.y + 0.5 * dt * spin.y,
        q.z + 0.5 * dt * spin.z,
        q.w + 0.5 * dt * spin.w,
    );
    Moved {
        velocity: v1,
        angular_velocity: w1,
        position: c + v1 * dt,
        orientation: normalised(turned),
        force,
        torque,
    }
}

/// Four points (offsets from the centre) that, each with a quarter of the area `a`,
/// reproduce a region's area, first moments (zero about its centre) and second moments
/// `[xx, xz, zz]`: `±√2` times the columns of the Cholesky factor `L` of the second
/// moments per area (`L Lᵀ = S / a`).
fn quadrature(a: f64, [sxx, sxz, szz]: [f64; 3]) -> [(f64, f64); 4] {
    let l11 = (sxx / a).max(0.0).sqrt();
    let l21 = if l11 > 0.0 { sxz / a / l11 } else { 0.0 };
    let l22 = (szz / a - l21 * l21).max(0.0).sqrt();
    let s = 2f64.sqrt();
    [
        (s * l11, s * l21),
        (-s * l11, -s * l21),
        (0.0, s * l22),
        (0.0, -s * l22),
    ]
}

/// Solves the 6 × 6 system `[A | b]` by Gaussian elimination without pivoting (`A` is
/// symmetric positive definite).
fn solve(mut sys: [[f64; 7]; 6]) -> [f64; 6] {
    for col in 0..6 {
        let pivot = sys[col];
        for row in &mut sys[col + 1..] {
            let factor = row[col] / pivot[col];
            // (Column `col` of the rows below is never read again: left as it is.)
            if factor != 0.0 {
                for (x, p) in row[col + 1..].iter_mut().zip(&pivot[col + 1..]) {
                    *x -= factor * p;
                }
            }
        }
    }
    let mut u = [0.0; 6];
    for row in (0..6).rev() {
        let mut sum = sys[row][6];
        for k in row + 1..6 {
            sum -= sys[row][k] * u[k];
        }
        u[row] = sum / sys[row][row];
    }
    u
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_quadrature_reproduces_the_moments() {
        let (a, s) = (3.0, [2.0, 0.5, 1.0]);
        let pts = quadrature(a, s);
        let w = a / 4.0;
        let sum = |f: &dyn Fn(f64, f64) -> f64| pts.iter().map(|&(x, z)| w * f(x, z)).sum::<f64>();
        assert!(sum(&|x, _| x).abs() < 1e-12 && sum(&|_, z| z).abs() < 1e-12);
        assert!((sum(&|x, _| x * x) - s[0]).abs() < 1e-12);
        assert!((sum(&|x, z| x * z) - s[1]).abs() < 1e-12);
        assert!((sum(&|_, z| z * z) - s[2]).abs() < 1e-12);
    }

    #[test]
    fn the_solver_solves() {
        // A symmetric positive definite matrix and a known solution.
        let x = [1.0, -2.0, 0.5, 3.0, 0.0, -1.0];
        let entry = |i: usize, j: usize| {
            if i == j {
                10.0 + i as f64
            } else {
                1.0 / (1.0 + (i + j) as f64)
            }
        };
        let sys: [[f64; 7]; 6] = std::array::from_fn(|i| {
            std::array::from_fn(|j| match j {
                6 => (0..6).map(|k| entry(i, k) * x[k]).sum(),
                j => entry(i, j),
            })
        });
        let u = solve(sys);
        for (got, want) in u.iter().zip(x) {
            assert!((got - want).abs() < 1e-12);
        }
    }
}
