//! The step: spring forces plus symplectic Euler, in two implementations.
//!
//! # The physics
//!
//! A spring from node i to node j with coefficient `c` and rest length `L0`, at current
//! length `L = |x_j − x_i|`, pulls i towards j with
//!
//! ```text
//! F = c (L − L0) (x_j − x_i) / L        (and j with −F; F = 0 when L = 0)
//! ```
//!
//! Each node then follows the seed's `m x'' + γ x' + f = f_ext`, integrated with the new
//! velocity (symplectic Euler, what the seed calls explicit Euler):
//!
//! ```text
//! a = (F_springs + f_ext − γ v) / m + g      v ← v + a Δt      x ← x + v Δt
//! ```
//!
//! Pinned nodes have `1/m = 0` and no `g`, so they never move (but for the calm rule
//! below: a pinned height smaller than 1e-18 reads +0 after a step).
//!
//! # Calm water is exactly calm
//!
//! A new height or vertical velocity smaller in magnitude than [`CALM`] (1e-18, in the
//! positions' units) is stored as +0. Left alone, a calm pool's ripples decay
//! exponentially through magnitudes where the arithmetic meets subnormal numbers: first
//! the squared vertical offset of a spring (heights of 1e-19 to 1e-23), then the heights
//! and velocities themselves (below 1.2e-38). With the rule, no height or velocity is ever
//! subnormal, and a subnormal square is left to the rare spring whose two heights, both
//! above 1e-18, differ by less than 1e-19. Many x86 cores take a microcode assist of
//! about a hundred cycles for each such operation: a 256² pool left to settle stepped up
//! to eight times slower after 15,000 steps, for motion of a billionth of a billionth of
//! a grid step. Both implementations apply the same rule to the same values, so they
//! still agree bit for bit. Horizontal components need no rule: they sit near `col·h`
//! and `row·h`, where a float's resolution is far coarser than the subnormal range.
//!
//! # Two implementations
//!
//! * [`scalar`] is the oracle: a loop over every spring adding into full force buffers,
//!   then a loop over every node. Plain and easy to check.
//! * [`engine`] is the engine: colour-partitioned bands ([`crate::springs`]) run on the
//!   rayon pool, each streaming its rows once with SIMD lanes across columns at the level
//!   the CPU has ([`crate::simd`]), and advancing up to [`engine::MAX_PASS_STEPS`] steps
//!   per pass over memory.
//!
//! Both use the same operations in the same order per spring and per node, never FMA,
//! evaluate each spring for the same one of its ends, and sum a node's spring forces in
//! the same order (the springs in its own column, then minus what its west neighbour's
//! column sends east, see [`scalar::node_force`]). So they agree bit for bit, and the
//! parity tests hold them to tolerance zero.
//!
//! Both write the back buffers, check every new value for finiteness, and report the first
//! non-finite node instead of swapping: the front buffers are never touched.

pub(crate) mod engine;
pub(crate) mod scalar;

/// Heights and vertical velocities smaller in magnitude than this are stored as +0 (see
/// the module docs: it keeps a settling pool out of subnormal arithmetic).
pub(crate) const CALM: f32 = 1e-18;

/// What a step reads besides the state: timestep and uniform acceleration.
#[derive(Debug, Clone, Copy)]
pub(crate) struct StepConfig {
    pub dt: f32,
    pub accel: [f32; 3],
}
