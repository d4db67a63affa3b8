//! Disturbances worth watching: [`Rain`] (random drops, reproducible from a seed) and
//! [`Wake`] (a moving object pushing the surface along a path).
//!
//! Both drive a [`Surface`] only through its public API (`drop_at`, `add_force`), so a
//! game can use them as they are, or read them as examples of writing its own. Lengths
//! are world units, rates, speeds and times seconds of the game's clock: a disturbance is
//! handed each step's length in seconds (`dt / time_scale`,
//! [`Params::time_scale`](crate::Params::time_scale)). Forces pushed into the water are
//! the lattice's (see [`Surface::add_force`]).
//! [`Surface::advance_with`] applies a disturbance before every substep of a frame; a
//! pair, a tuple of up to four, a slice or an `Option` of disturbances is a disturbance too:
//!
//! ```
//! use springwater::disturb::{Rain, Wake};
//! use springwater::{Params, Surface};
//!
//! let mut water = Surface::new(Params::with_size(64, 64))?;
//! let mut rain = Rain::new(12.0, 7);                 // 12 drops a second
//! let mut boat = Wake::circle(&water, 16.0);          // circles the middle of the pool
//! for _frame in 0..50 {
//!     water.advance_with(1.0 / 60.0, &mut (&mut rain, &mut boat))?;
//! }
//! # Ok::<(), springwater::Error>(())
//! ```
//!
//! Stepping by hand, call [`Disturbance::apply`] right before each [`Surface::step`] with
//! that step's length in seconds, `params().dt / params().time_scale`.
//!
//! Both keep to the regime where the timestep limit holds: a raindrop's depth never
//! exceeds its radius, and the wake pushes with a bounded force spread over several nodes.

use crate::error::{Error, Result};
use crate::params;
use crate::rng::Rng;
use crate::surface::window::rest_coordinate;
use crate::surface::Surface;

pub use crate::surface::Disturbance;

/// Rain: drops at random places and random times, the same ones for the same seed.
///
/// Drops arrive as a Poisson process of `rate` drops per second. Each one is a
/// [`Surface::drop_at`] dent with a radius drawn from `radius` and height
/// `−depth × radius`, all in world units: as steep on any grid, and within the stable
/// regime (`|height| ≤ radius`) as long as `depth ≤ 1`. Drops are placed uniformly over
/// the rest footprint, at least one radius away from its edge where the footprint allows,
/// so the same seed drops at the same world points on any spacing.
///
/// The times and places depend only on the seed and the time passed to
/// [`Disturbance::apply`], not on how that time is cut into steps (up to the rounding of
/// the seconds it adds up in `f64`): a drop due at time `t` lands at the first step
/// boundary at or after `t`.
#[derive(Debug, Clone)]
pub struct Rain {
    /// Mean drops per second (default in [`Rain::new`]: as given). Zero: no rain.
    pub rate: f32,
    /// Range of drop radii in world units (default: `1.5..3.0`, one and a half to three
    /// cells at the default spacing of 1). Keep it at one cell or more.
    pub radius: std::ops::Range<f32>,
    /// Drop depth as a fraction of its radius, in `(0, 1]` (default: `0.6`).
    pub depth: f32,
    rng: Rng,
    time: f64,
    next: f64,
    fallen: u64,
}

impl Rain {
    /// Rain of `rate` drops per second from `seed`.
    pub fn new(rate: f32, seed: u64) -> Self {
        let mut rain = Self {
            rate,
            radius: 1.5..3.0,
            depth: 0.6,
            rng: Rng::new(seed),
            time: 0.0,
            next: 0.0,
            fallen: 0,
        };
        rain.next = rain.wait();
        rain
    }

    /// Drops that have fallen so far.
    pub fn fallen(&self) -> u64 {
        self.fallen
    }

    /// Seconds of rain so far.
    pub fn time(&self) -> f64 {
        self.time
    }

    /// Seconds until the next drop: exponential with mean `1 / rate`.
    fn wait(&mut self) -> f64 {
        if self.rate.is_finite() && self.rate > 0.0 {
            // 1 − u is in (0, 1], so the logarithm is finite.
            -((1.0 - self.rng.next_f32() as f64).ln()) / self.rate as f64
        } else {
            f64::INFINITY
        }
    }

    fn check(&self) -> Result<()> {
        params::non_negative("rain rate", self.rate)?;
        params::positive("rain radius", self.radius.start)?;
        params::positive("rain radius", self.radius.end)?;
        if self.radius.end < self.radius.start {
            return Err(Error::InvalidParam {
                name: "rain radius",
                value: self.radius.end as f64,
                expected: "a range whose end is at least its start",
            });
        }
        if !(self.depth > 0.0 && self.depth <= 1.0) {
            return Err(Error::InvalidParam {
                name: "rain depth",
                value: self.depth as f64,
                expected: "a fraction of the radius in (0, 1] (deeper drops can fold the lattice)",
            });
        }
        Ok(())
    }
}

impl Disturbance for Rain {
    fn apply(&mut self, surface: &mut Surface, dt: f32) -> Result<()> {
        self.check()?;
        params::non_negative("dt", dt)?;
        if self.next.is_infinite() {
            // The rate may have been raised since the last call.
            self.next = self.time + self.wait();
        }
        let [width, length] = surface.mesh_view().extent();
        while self.next <= self.time {
            let radius = self.rng.range(self.radius.start, self.radius.end);
            // Keep the dent off the pinned ring where the footprint allows it.
            let place = |rng: &mut Rng, size: f32| {
                let margin = radius.min(size / 2.0);
                rng.range(margin, size - margin)
            };
            // Over the window, wherever it is (its origin is 0 until it moves).
            let [ox, oz] = surface.origin();
            let x = ox + place(&mut self.rng, width);
            let z = oz + place(&mut self.rng, length);
            surface.drop_at(x, z, -self.depth * radius, radius)?;
            self.fallen += 1;
            self.next += self.wait();
        }
        self.time += dt as f64;
        Ok(())
    }
}

/// A wake: an object (a boat, a duck, a finger) moving along a closed path at constant
/// speed, pushing the water down under it with a Gaussian footprint.
///
/// Each step it presses down with the pressure `strength · exp(−d²/radius²)` (force per
/// unit area in the lattice's force units, like every force on the water; `d` the
/// distance from the object), over the disc of radius `3 × radius`:
/// every node there gets that pressure times its cell's area `h²`. Everything is in world
/// units, so the same wake pushes the same total force along the same path on any
/// spacing. Moving faster than the ripples ([`Params::ripple_speed`](crate::Params::ripple_speed),
/// about 39 world units per second with the defaults) leaves a V-shaped wake behind it.
#[derive(Debug, Clone)]
pub struct Wake {
    /// Corners of the closed path, world `[x, z]` in the water's local space.
    path: Vec<[f32; 2]>,
    /// Cumulative length of the path at each corner; the last entry is the full length.
    lengths: Vec<f32>,
    /// Speed along the path in world units per second (default: `60`, half again as fast
    /// as the ripples with the defaults).
    pub speed: f32,
    /// Footprint radius in world units (default: `2.5`).
    pub radius: f32,
    /// Peak downward pressure under the object, lattice force units per unit area (default:
    /// `1.5`: a force of 1.5 on the node under it at the default spacing of 1).
    pub strength: f32,
    distance: f32,
}

impl Wake {
    /// A wake along the closed polyline `path` (world `[x, z]` corners), starting at its
    /// first corner. The path needs at least two distinct finite corners.
    pub fn new(path: Vec<[f32; 2]>) -> Result<Self> {
        for p in &path {
            params::finite("wake path", p[0])?;
            params::finite("wake path", p[1])?;
        }
        let mut lengths = Vec::with_capacity(path.len() + 1);
        let mut total = 0.0f32;
        lengths.push(0.0);
        for (k, a) in path.iter().enumerate() {
            let b = path[(k + 1) % path.len()];
            total += ((b[0] - a[0]).powi(2) + (b[1] - a[1]).powi(2)).sqrt();
            lengths.push(total);
        }
        if !(total > 0.0 && total.is_finite()) {
            return Err(Error::InvalidParam {
                name: "wake path",
                value: total as f64,
                expected: "a closed path with at least two distinct corners",
            });
        }
        Ok(Self {
            path,
            lengths,
            speed: 60.0,
            radius: 2.5,
            strength: 1.5,
            distance: 0.0,
        })
    }

    /// A circle of `radius` world units around the middle of `surface`'s footprint,
    /// counter-clockwise seen from above, as a 64-gon.
    pub fn circle(surface: &Surface, radius: f32) -> Self {
        let [width, length] = surface.mesh_view().extent();
        let (cx, cy) = (width / 2.0, length / 2.0);
        let path = (0..64)
            .map(|k| {
                let a = k as f32 * std::f32::consts::TAU / 64.0;
                [cx + radius * a.cos(), cy - radius * a.sin()]
            })
            .collect();
        Self::new(path).unwrap_or_else(|_| {
            Self::new(vec![[cx, cy], [cx + 1.0, cy]]).expect("two distinct corners")
        })
    }

    /// Moves the whole path by `(dx, dz)` world units, keeping the object's progress along
    /// it: for a host that rebases its world ([`Surface::rebase`] by `(dcols, drows)` cells
    /// moves the water frame by `(dcols·h, drows·h)`, so a wake follows with
    /// `translate(−dcols·h, −drows·h)`). Refused, with nothing changed, if a corner would not
    /// be finite.
    pub fn translate(&mut self, dx: f32, dz: f32) -> Result<()> {
        let moved: Vec<[f32; 2]> = self.path.iter().map(|p| [p[0] + dx, p[1] + dz]).collect();
        for p in &moved {
            params::finite("wake path", p[0])?;
            params::finite("wake path", p[1])?;
        }
        self.path = moved;
        Ok(())
    }

    /// Where the object is now, world `[x, z]`.
    pub fn position(&self) -> [f32; 2] {
        let total = *self.lengths.last().expect("at least one corner");
        let s = self.distance.rem_euclid(total);
        let k = self
            .lengths
            .partition_point(|&l| l <= s)
            .saturating_sub(1)
            .min(self.path.len() - 1);
        let a = self.path[k];
        let b = self.path[(k + 1) % self.path.len()];
        let seg = self.lengths[k + 1] - self.lengths[k];
        let t = if seg > 0.0 {
            (s - self.lengths[k]) / seg
        } else {
            0.0
        };
        [a[0] + t * (b[0] - a[0]), a[1] + t * (b[1] - a[1])]
    }
}

impl Disturbance for Wake {
    fn apply(&mut self, surface: &mut Surface, dt: f32) -> Result<()> {
        params::non_negative("dt", dt)?;
        params::finite("wake speed", self.speed)?;
        params::positive("wake radius", self.radius)?;
        params::finite("wake strength", self.strength)?;
        let [px, pz] = self.position();
        let grid = surface.grid();
        let h = surface.params().spacing;
        let reach = 3.0 * self.radius;
        let inv_r2 = 1.0 / (self.radius * self.radius);
        let peak = -self.strength * h * h;
        // Rest positions are in the water frame: node (col, row) at origin + (col, row)·h.
        let [ocol, orow] = surface.origin_cells();
        let rest = |k: usize, o: i64| rest_coordinate(k, o, h);
        // The nodes whose rest position lies within `reach` of `p` along one axis.
        let span = |p: f32, n: usize, o: i64| {
            let p = p - o as f32 * h;
            let lo = ((p - reach) / h).ceil().max(0.0).min(n as f32) as usize;
            let hi = ((p + reach) / h).floor().max(-1.0).min(n as f32 - 1.0) as isize;
            lo..(hi + 1).max(0) as usize
        };
        for row in span(pz, grid.rows, orow) {
            for col in span(px, grid.cols, ocol) {
                let d2 = (rest(col, ocol) - px).powi(2) + (rest(row, orow) - pz).powi(2);
                let f = peak * (-d2 * inv_r2).exp();
                surface.add_force(row * grid.cols + col, [0.0, f, 0.0])?;
            }
        }
        // Keep the distance small so f32 keeps its precision on long runs.
        let total = *self.lengths.last().expect("at least one corner");
        let step = self.speed * dt;
        self.distance = (self.distance + step).rem_euclid(total);
        Ok(())
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::Params;

    #[test]
    fn rain_does_not_depend_on_how_time_is_cut() {
        let p = Params::with_size(32, 32);
        let mut s1 = Surface::new(p).unwrap();
        let mut s2 = Surface::new(p).unwrap();
        let mut r1 = Rain::new(48.0, 9);
        let mut r2 = Rain::new(48.0, 9);
        // Same drops when the same total time is passed in 1 call or in 10 (exact binary
        // fractions of a second: 1/32 each).
        r1.apply(&mut s1, 0.3125).unwrap();
        r1.apply(&mut s1, 0.0).unwrap();
        for _ in 0..10 {
            r2.apply(&mut s2, 0.03125).unwrap();
        }
        r2.apply(&mut s2, 0.0).unwrap();
        assert_eq!(r1.fallen(), r2.fallen());
        assert!(r1.fallen() > 5);
        assert_eq!(s1.positions()[1], s2.positions()[1]);
    }

    #[test]
    fn rain_stays_stable_for_a_long_time() {
        let mut s = Surface::new(Params::with_size(48, 48)).unwrap();
        let mut rain = Rain::new(24.0, 3);
        for _ in 0..2000 {
            let dt = s.params().dt / s.params().time_scale;
            rain.apply(&mut s, dt).unwrap();
            s.step().unwrap();
        }
        assert!(rain.fallen() > 100);
        assert!(s.positions()[1].iter().all(|y| y.abs() < 10.0));
    }

    #[test]
    fn wake_moves_and_pushes() {
        let mut s = Surface::new(Params::with_size(64, 64)).unwrap();
        let mut wake = Wake::circle(&s, 20.0);
        let start = wake.position();
        assert!((start[0] - 51.5).abs() < 1e-4 && (start[1] - 31.5).abs() < 1e-4);
        for _ in 0..500 {
            let dt = s.params().dt / s.params().time_scale;
            wake.apply(&mut s, dt).unwrap();
            s.step().unwrap();
        }
        assert_ne!(wake.position(), start);
        let y = s.positions()[1];
        assert!(y.iter().any(|v| v.abs() > 0.05));
        assert!(y.iter().all(|v| v.is_finite() && v.abs() < 10.0));
    }

    #[test]
    fn advance_with_takes_the_same_substeps_as_advance() {
        let p = Params::with_size(32, 32);
        let mut a = Surface::new(p).unwrap();
        let mut b = Surface::new(p).unwrap();
        a.drop_at(16.0, 16.0, -1.0, 2.0).unwrap();
        b.drop_at(16.0, 16.0, -1.0, 2.0).unwrap();
        for seconds in [1.0 / 24.0, 1.0 / 60.0, 0.002, 0.1, 0.0] {
            let n = a.advance_with(seconds, &mut ()).unwrap();
            assert_eq!(n, b.advance(seconds).unwrap());
            assert_eq!(a.steps(), b.steps());
        }
        assert_eq!(a.positions(), b.positions());
        let mut rain = Rain::new(1.0, 2);
        assert!(a.advance_with(f32::NAN, &mut rain).is_err());
        assert!(a.advance_with(-1.0, &mut rain).is_err());
    }

    #[test]
    fn advance_with_applies_every_disturbance_before_every_substep() {
        /// Counts its calls and the seconds it was given.
        struct Count(usize, f64);
        impl Disturbance for Count {
            fn apply(&mut self, _: &mut Surface, dt: f32) -> Result<()> {
                self.0 += 1;
                self.1 += dt as f64;
                Ok(())
            }
        }
        let mut s = Surface::new(Params::with_size(16, 16)).unwrap();
        let (mut a, mut b) = (Count(0, 0.0), Count(0, 0.0));
        let n = s.advance_with(0.1, &mut (&mut a, &mut b)).unwrap();
        assert_eq!(n, 6); // 0.1 s: 2.4 units of model time in steps of 0.4
        assert_eq!((a.0, b.0), (6, 6));
        assert!((a.1 - 0.1).abs() < 1e-6 && (s.time() - 0.1).abs() < 1e-6);
        assert!((s.model_time() - 2.4).abs() < 1e-5);
        let mut list: Vec<&mut dyn Disturbance> = vec![&mut a, &mut b];
        s.advance_with(1.0 / 60.0, list.as_mut_slice()).unwrap();
        assert_eq!((a.0, b.0), (7, 7));
    }

    #[test]
    fn bad_wake_paths_are_refused() {
        assert!(Wake::new(vec![]).is_err());
        assert!(Wake::new(vec![[1.0, 1.0], [1.0, 1.0]]).is_err());
        assert!(Wake::new(vec![[f32::NAN, 1.0], [2.0, 1.0]]).is_err());
    }
}
