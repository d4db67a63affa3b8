//! The absorbing boundary ([`Boundary::Absorbing`](crate::Boundary::Absorbing)): a damping
//! frame that lets waves leave the patch, as if it sat in open water.
//!
//! # The frame
//!
//! The outer ring of nodes is pinned, and the `W` rings inside it (the frame) get extra
//! viscosity that grows quadratically towards the edge:
//!
//! ```text
//! γ(d) = γ_water + γ_peak · ((W − d) / W)²     for 1 ≤ d < W,  γ_water beyond
//! ```
//!
//! where `d` counts cells from the outer edge (`min(col, row, cols−1−col, rows−1−row)`) and
//! `γ_water` is [`Params::viscosity`]. A wave entering the frame meets damping that rises
//! slowly enough not to reflect off its start, and is spent before it reaches the pinned
//! ring and comes back. The frame lies **inside** the user's grid: the surface keeps its
//! `cols × rows` nodes, its footprint, mesh, queries and snapshots as they are, and the
//! undamped water is the `(cols − 2W) × (rows − 2W)` middle. Seen from above, waves fade out
//! as they approach the edge, which is how a patch of open water ends. A grid that wants a
//! given area of undamped water asks for `2W` more nodes per side; the frame costs no
//! extra work per node (every node already carries its own viscosity).
//!
//! # Chosen by measurement
//!
//! `docs/open-water.md` has the ring tests behind the choice (a bump at the centre or near
//! a corner, compared with the same bump on a grid padded so far that nothing returns):
//! linear ramps reflect from where the damping starts, cubic ones need more damping than
//! the timestep allows, a first-order Mur condition alone reflects 0.4–4%. A quadratic
//! frame of 32 cells with the seed's parameters reflects at most 9.5·10⁻⁴ of a 4-cell
//! bump's energy and 1.3·10⁻⁴ of a 2-cell one; 28 cells just meet the same bars (2·10⁻³,
//! 5·10⁻⁴), so [`Boundary::ABSORBING_WIDTH`](crate::Boundary::ABSORBING_WIDTH) is 32.
//! `tests/absorbing.rs` repeats the ring test on every run.
//!
//! # The peak damping and the critical timestep
//!
//! Explicit damping has its own stability limit: symplectic Euler with `−γv` is stable
//! while `ω²Δt² + 2bΔt < 4` (`b = γ/m`, see [`Params`]), so with the large-wave bound
//! `ω² ≤ 12c/m` the timestep leaves room for `b < b_lim = (4 − 12(c/m)Δt²) / (2Δt)`
//! (0.8 with the seed's parameters: `γ < 3.2`). The frame takes
//!
//! ```text
//! b_peak = min(0.6 · v / v_seed,  0.75 · b_lim − γ_water / m)   (never below 0)
//! ```
//!
//! `0.6` per unit of model time (`γ = 2.4` at `m = 4`) is the measured best for the seed's
//! lattice, whose ripples travel `v_seed = sqrt(3·7·0.5/4) ≈ 1.62` cells per unit of model
//! time; other parameters scale it with their ripple speed `v = sqrt(3c(1 − r)/m)` cells
//! per unit of model time, so that a wave loses the same share of its energy per cell it
//! crosses. The second term keeps the largest viscosity at three quarters of what the
//! timestep allows, so an absorbing boundary never makes a valid timestep invalid; close
//! to the critical timestep the frame has less damping to work with and reflects more.
//! With `rest_ratio = 1` ripples do not travel and the frame does nothing.

use crate::params::Params;

/// An absorbing boundary's damping frame, computed from the parameters.
#[derive(Debug, Clone, Copy, PartialEq)]
pub(crate) struct Frame {
    /// Rings of extra damping inside the pinned outer ring.
    pub width: usize,
    /// `γ_peak`: the extra viscosity the profile starts from at the edge.
    pub peak: f32,
}

/// Peak damping rate `b = γ/m` of the seed's lattice, per unit of model time: the measured
/// best of `docs/open-water.md`.
const SEED_PEAK_RATE: f64 = 0.6;

/// The share of the damped stability limit the frame may use.
const LIMIT_SHARE: f64 = 0.75;

impl Frame {
    /// The frame of an absorbing boundary `width` cells wide for `params`.
    pub fn new(params: &Params, width: usize) -> Self {
        let (m, c, dt) = (
            params.mass as f64,
            params.stiffness as f64,
            params.dt as f64,
        );
        let ripple = |c: f64, r: f64, m: f64| (3.0 * c * (1.0 - r) / m).sqrt();
        let ideal = SEED_PEAK_RATE * ripple(c, params.rest_ratio as f64, m) / ripple(7.0, 0.5, 4.0);
        let limit = (4.0 - 12.0 * c / m * dt * dt) / (2.0 * dt);
        let room = LIMIT_SHARE * limit - params.viscosity as f64 / m;
        let rate = ideal.min(room).max(0.0);
        let peak = (rate * m) as f32;
        Self {
            width,
            peak: if peak.is_finite() { peak } else { 0.0 },
        }
    }

    /// Extra viscosity `d` cells from the outer edge (0 from `d = W` on).
    pub fn viscosity(&self, d: usize) -> f32 {
        if d >= self.width {
            return 0.0;
        }
        let s = (self.width - d) as f32 / self.width as f32;
        self.peak * s * s
    }
}
