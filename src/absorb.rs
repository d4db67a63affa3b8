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
//! extra work per node and no memory per node (the step reads every node's viscosity
//! from a row of its table, and the frame's ramp is a few profile rows of that table, see
//! `state::table`).
//!
//! # Chosen by measurement
//!
//! `docs/open-water.md` has the ring tests behind the choice (a bump at the centre or near
//! a corner, compared with the same bump on a grid padded so far that nothing returns,
//! the reflected energy taken after every step of a 300-step run). A frame sends waves
//! back two ways: from its inner edge, where the damping starts (early, and worse the
//! faster the profile rises there), and from the pinned ring behind it (late, and worse
//! the less damping the frame holds). Linear ramps and (1 − cos) or smoothstep onsets lose
//! on the first, cubic ones and lower peaks on the second, a first-order Mur condition
//! alone reflects 0.4–4%. A quadratic frame of 32 cells with the seed's parameters
//! reflects at most 9.5·10⁻⁴ of a 4-cell bump's energy and 1.4·10⁻⁴ of a 2-cell one's at
//! any step (the aims are 2·10⁻³ and 5·10⁻⁴); the best power measured (2.2) gains 13% on
//! the worst case, less than growing the grid from 192 to 200 nodes changes the corner
//! case (22%), so the profile stays quadratic.
//! [`Boundary::ABSORBING_WIDTH`](crate::Boundary::ABSORBING_WIDTH) is 32.
//! `tests/absorbing.rs` repeats the ring test on every run.
//!
//! # The default width on small grids
//!
//! A frame of 32 rings needs a grid of at least 66 nodes across and leaves a middle of 2
//! nodes there. The default width ([`Boundary::absorbing`](crate::Boundary::absorbing),
//! a width equal to `ABSORBING_WIDTH`) therefore fits itself to the grid
//! ([`crate::params::default_width`]): 32 rings where that leaves an undamped middle of at least 32
//! nodes across (grids of 98 nodes and more), otherwise the widest frame that leaves a
//! middle of 32 nodes or, on grids narrower than 66 nodes, half of what lies inside the
//! pinned ring; at least one ring. A 64² grid gets 15 rings and a 32-node middle, a 16²
//! grid 3 rings and an 8-node middle. Narrow frames reflect more (about 1.2·10⁻² of a
//! bump's energy at 15 rings): the fitted default is open water as good as the grid
//! allows, not the 32-ring figure. Any other width is used as given and refused when it
//! does not fit.
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

use crate::params::{self, Params};

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
    /// The frame of an absorbing boundary asking for `width` cells for `params` (the default
    /// width fitted to the grid, see [`crate::params::frame_width`]).
    pub fn new(params: &Params, width: usize) -> Self {
        let width = params::frame_width(width, params.cols, params.rows);
        let (m, c, dt) = (
            params.mass as f64,
            params.stiffness as f64,
            params.dt as f64,
        );
        let ripple = |c: f64, r: f64, m: f64| (3.0 * c * (1.0 - r) / m).sqrt();
        let ideal = SEED_PEAK_RATE * ripple(c, params.rest_ratio as f64, m) / ripple(7.0, 0.5, 4.0);
        let limit = crate::stability::damping_limit(12.0 * c / m, dt);
        let room = LIMIT_SHARE * limit - params.viscosity as f64 / m;
        let rate = ideal.min(room).max(0.0);
        let peak = (rate * m) as f32;
        Self {
            width,
            peak: if peak.is_finite() { peak } else { 0.0 },
        }
    }

    /// Extra viscosity `d` cells from the outer edge (0 from `d = W` on): the profile is a
    /// function of the distance from the edge only.
    pub fn viscosity(&self, d: usize) -> f32 {
        if d >= self.width {
            return 0.0;
        }
        let s = (self.width - d) as f32 / self.width as f32;
        self.peak * s * s
    }
}
