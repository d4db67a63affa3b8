//! The game's clock: how [`Surface::advance`] turns frames of real time into whole steps.
//!
//! A game's frames are not all the same length (59.94 Hz displays, a frame that takes a
//! tenth of a millisecond longer, a stall while a level loads), but the lattice must be
//! stepped with a fixed `dt` for two reasons: the state after a given stretch of time must
//! not depend on how that time was cut into frames (two machines running the same game
//! agree on where a boat floats), and a step shorter than `dt` costs as much as a full one.
//! So `advance` works as physics engines do with a fixed timestep (Bevy's `FixedUpdate`,
//! Godot's physics ticks, "Fix Your Timestep!"):
//!
//! 1. the frame's seconds, times [`Params::time_scale`](crate::Params::time_scale), are
//!    added to an accumulator of model time that is owed;
//! 2. as many whole steps of `dt` as the accumulator holds are taken, at most the cap
//!    ([`Surface::set_step_cap`]); what the cap leaves is dropped or carried
//!    ([`Overflow`]);
//! 3. the rest, less than one step, stays in the accumulator for the next frame, and
//!    [`Surface::interpolation`] says how far the game's clock is past the last step, for
//!    a renderer that blends between the last two states.
//!
//! The accumulator is part of the surface's state: a snapshot keeps it, and a clone
//! continues exactly as the original would. Frames of the same total length give the
//! same steps, whatever their lengths: the sum is kept in `f64`, and a step is due when
//! the accumulator is within [`TOLERANCE`] of a whole `dt`, so that the rounding of many
//! `f32` frame lengths (1/60 s is not exactly representable) can never cost or add a step.

use super::{Disturbance, Surface};
use crate::error::{Error, Result};
use crate::params;

/// What [`Surface::advance`] does with the steps a frame owes beyond the cap.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default, Hash)]
#[cfg_attr(feature = "serde", derive(serde::Serialize, serde::Deserialize))]
#[non_exhaustive]
pub enum Overflow {
    /// The steps past the cap are dropped: after a stall the water goes on from where it
    /// was, a little behind the game's clock ([`Surface::dropped_seconds`] says by how
    /// much). What engines do by default, so that a slow frame cannot make the next one
    /// slower still.
    #[default]
    Drop,
    /// The steps past the cap stay owed and are taken by the following calls, at most the
    /// cap per call: the water catches up with the game's clock over several frames.
    Carry,
}

/// A fraction of `dt` that the accumulator may fall short of a whole step and still take
/// it: far above the rounding of a sum of `f32` frame lengths in `f64` (about 10⁻⁸ of a
/// step per frame), far below anything a game could mean (10⁻⁴ of a step is 1.7 µs of
/// game time at the defaults).
pub(crate) const TOLERANCE: f64 = 1e-4;

/// How far, per step, a whole number of steps may be off from the frames that meant them:
/// `dt` and a frame's length are each an `f32`, rounded by up to half an ulp (2⁻²⁴) from
/// what the game meant, and a frame of `n` steps may be off by `n` times that, twice over.
/// A frame of 100 s at the default time scale holds 5,999.99991 steps of the `f32` nearest
/// 0.4 (0.4000000059604645): it takes 6,000, and the few 10⁻⁵ of a step it is short are
/// forgiven (the accumulator goes back to zero) instead of piling up frame after frame.
const F32_ROUNDING: f64 = 1.0 / (1u64 << 22) as f64;

/// The accumulator and the cap, one per surface.
#[derive(Debug, Clone, Copy, PartialEq)]
pub(crate) struct Clock {
    /// Model time owed and not yet stepped. After a call of `advance` it is below one
    /// `dt` (unless steps are carried), and may be below zero by up to `TOLERANCE · dt` plus
    /// the `f32` rounding of the steps just taken (see `F32_ROUNDING`)
    /// (a step taken a hair early is paid back by the next frame).
    pub owed: f64,
    /// Most steps one call of `advance` takes.
    pub max_steps: u32,
    /// What happens to the steps past `max_steps`.
    pub overflow: Overflow,
    /// Seconds of the game's clock dropped by the cap so far.
    pub dropped: f64,
}

impl Default for Clock {
    fn default() -> Self {
        Self {
            owed: 0.0,
            max_steps: Surface::DEFAULT_MAX_STEPS,
            overflow: Overflow::Drop,
            dropped: 0.0,
        }
    }
}

impl Clock {
    /// Adds `model` time to the accumulator and takes out the steps of `dt` to run now:
    /// returns how many, the cap and the overflow rule applied.
    pub fn tick(&mut self, model: f64, dt: f32, time_scale: f32) -> u32 {
        let dt = dt as f64;
        self.owed += model;
        let owed_steps = self.owed / dt;
        let due = (owed_steps + TOLERANCE + owed_steps.abs() * F32_ROUNDING)
            .floor()
            .max(0.0);
        let steps = due.min(self.max_steps as f64);
        self.owed -= steps * dt;
        if self.owed.abs() <= steps * dt * F32_ROUNDING {
            // What is left is the rounding of the steps just taken, not time the game owes.
            self.owed = 0.0;
        }
        if due > steps && self.overflow == Overflow::Drop {
            // What is left is the fraction of a step past the last whole one. Taken as a
            // remainder rather than by subtracting the dropped steps, which for an absurd
            // frame (10³⁰ s) would cancel catastrophically and leave an arbitrary debt.
            let mut left = self.owed.rem_euclid(dt);
            if left > dt * (1.0 - TOLERANCE) {
                left -= dt;
            }
            self.dropped += (self.owed - left) / time_scale as f64;
            self.owed = left;
        }
        steps as u32
    }

    /// How far the owed time is into the next step, in `[0, 1)`.
    pub fn fraction(&self, dt: f32) -> f32 {
        let f = (self.owed / dt as f64) as f32;
        if f >= 1.0 {
            // Only when steps are carried past the cap: the renderer is a whole step or
            // more behind, and the nearest it can show is the last state.
            return 1.0 - f32::EPSILON / 2.0;
        }
        f.max(0.0)
    }
}

impl Surface {
    /// The default cap on the steps one [`Surface::advance`] call takes: 16, a quarter of a
    /// second of game time at the default time scale and timestep (one step per 60 Hz
    /// frame). A frame that owes more is a stall, not gameplay.
    pub const DEFAULT_MAX_STEPS: u32 = 16;

    /// Sets the most steps one [`Surface::advance`] (or [`Surface::advance_with`]) call
    /// takes, and what happens to the steps a long frame owes beyond it ([`Overflow::Drop`]
    /// by default; the default cap is [`Surface::DEFAULT_MAX_STEPS`]). `max_steps` is from
    /// 1 to [`Surface::MAX_SUBSTEPS`]; otherwise an error, and nothing changes.
    pub fn set_step_cap(&mut self, max_steps: u32, overflow: Overflow) -> Result<()> {
        if max_steps == 0 || max_steps as usize > Self::MAX_SUBSTEPS {
            return Err(Error::InvalidParam {
                name: "max steps per frame",
                value: max_steps as f64,
                expected: "from 1 to 10000",
            });
        }
        self.clock.max_steps = max_steps;
        self.clock.overflow = overflow;
        Ok(())
    }

    /// The cap on steps per [`Surface::advance`] call and what happens past it.
    pub fn step_cap(&self) -> (u32, Overflow) {
        (self.clock.max_steps, self.clock.overflow)
    }

    /// How far the game's clock is past the last step, as a fraction of a step in
    /// `[0, 1)`: after [`Surface::advance`] the water's state is the game's time minus
    /// `interpolation() × dt`. A renderer that keeps the previous frame's positions can
    /// blend `previous + (current − previous) × interpolation()`-style to hide that the
    /// water moves in whole steps; most games at one step per frame can ignore it.
    pub fn interpolation(&self) -> f32 {
        self.clock.fraction(self.params.dt)
    }

    /// Seconds of the game's clock that [`Surface::advance`] owes and has not stepped
    /// yet: under one step normally, more while [`Overflow::Carry`] catches up after a
    /// stall.
    pub fn owed_seconds(&self) -> f64 {
        self.clock.owed.max(0.0) / self.params.time_scale as f64
    }

    /// Seconds of the game's clock that the cap has dropped so far ([`Overflow::Drop`]):
    /// how far the water is behind the seconds passed to [`Surface::advance`].
    pub fn dropped_seconds(&self) -> f64 {
        self.clock.dropped
    }

    /// The steps [`Surface::advance`] takes for a frame of `frame_seconds`, with the
    /// accumulator updated: the frame is checked first and refused with nothing changed.
    pub(crate) fn tick(&mut self, frame_seconds: f32) -> Result<usize> {
        params::non_negative("frame seconds", frame_seconds)?;
        let model = frame_seconds as f64 * self.params.time_scale as f64;
        Ok(self
            .clock
            .tick(model, self.params.dt, self.params.time_scale) as usize)
    }

    /// Advances the water by one frame of a game's clock, `frame_seconds` seconds long, in
    /// whole steps of `params().dt`: the frame's time (times `params().time_scale`) goes
    /// into an accumulator of model time (kept in `f64`, part of the state and of
    /// snapshots), and every whole step it holds is taken (a step is due 10⁻⁴ of a step
    /// early, so that the rounding of `f32` frame lengths never costs one). Returns the number of steps taken: 0 when the frame was shorter than what
    /// the accumulator lacked for the next step, 1 for a 60 Hz frame at the defaults.
    ///
    /// The state depends on the total time passed, not on how it was cut into frames:
    /// 60 frames of 1/60 s, jittered frames or 59.94 Hz frames that add up to the same
    /// second give the same bits. [`Surface::interpolation`] is the fraction of a step the
    /// game's clock is past the water's. A frame that owes more than the cap
    /// ([`Surface::set_step_cap`], [`Surface::DEFAULT_MAX_STEPS`]) takes the cap's steps and
    /// drops the rest, or carries it into the next calls ([`Overflow`]);
    /// [`Surface::dropped_seconds`] and [`Surface::owed_seconds`] say which.
    ///
    /// A negative or non-finite frame is refused with nothing changed. A failing step stops
    /// the frame there and returns its error: the earlier steps stay applied, the failing
    /// one is not, and the frame's time is spent (if no step was taken, nothing changed,
    /// the accumulator included). See [`Surface::advance_with`]
    /// to disturb the water before every step.
    ///
    /// ```
    /// use springwater::{Params, Surface};
    ///
    /// let mut water = Surface::new(Params::with_size(32, 32))?;
    /// let frames = [0.016, 0.0173, 0.0167, 0.0167];     // a jittery display
    /// let steps: usize = frames.iter().map(|&f| water.advance(f)).sum::<Result<_, _>>()?;
    /// assert_eq!(steps, 4);                               // 0.0667 s: four steps of 1/60 s
    /// assert!((0.0..1.0).contains(&water.interpolation()));
    /// # Ok::<(), springwater::Error>(())
    /// ```
    pub fn advance(&mut self, frame_seconds: f32) -> Result<usize> {
        let (clock, before) = (self.clock, self.steps);
        let steps = self.tick(frame_seconds)?;
        // Nothing reads the water between these steps: the engine takes several per pass.
        let result = self.run(steps as u64, self.params.dt);
        self.settle(clock, before, steps, result)
    }

    /// [`Surface::advance`] with `disturbance` applied before every step, with the step's
    /// length in seconds, `params().dt / params().time_scale`: rain, wakes, buoyancy,
    /// anything implementing
    /// [`Disturbance`] (tuples, slices and `&mut` of disturbances are disturbances too).
    /// A failing disturbance or step stops the frame there and returns its error.
    ///
    /// ```
    /// use springwater::disturb::{Rain, Wake};
    /// use springwater::{Params, Surface};
    ///
    /// let mut water = Surface::new(Params::with_size(64, 64))?;
    /// let mut rain = Rain::new(48.0, 1);                  // 48 drops a second
    /// let mut boat = Wake::circle(&water, 16.0);
    /// for _frame in 0..60 {
    ///     water.advance_with(1.0 / 60.0, &mut (&mut rain, &mut boat))?;
    /// }
    /// assert!(rain.fallen() > 20);                        // one second
    /// # Ok::<(), springwater::Error>(())
    /// ```
    pub fn advance_with<D: Disturbance + ?Sized>(
        &mut self,
        frame_seconds: f32,
        disturbance: &mut D,
    ) -> Result<usize> {
        let (clock, before) = (self.clock, self.steps);
        let steps = self.tick(frame_seconds)?;
        let dt = self.params.dt;
        let seconds = dt / self.params.time_scale;
        let result = (0..steps).try_for_each(|_| {
            disturbance.apply(self, seconds)?;
            self.run(1, dt)
        });
        self.settle(clock, before, steps, result)
    }

    /// Ends a clocked frame of `steps` steps begun with `clock` at step count `before`. If
    /// a step failed before any was taken the clock is put back, so the call changed
    /// nothing; after some steps the frame's time is spent, the failed steps with it.
    fn settle(
        &mut self,
        clock: Clock,
        before: u64,
        steps: usize,
        result: Result<()>,
    ) -> Result<usize> {
        match result {
            Ok(()) => Ok(steps),
            Err(e) => {
                if self.steps == before {
                    self.clock = clock;
                }
                Err(e)
            }
        }
    }

    /// The frame split of earlier versions, for callers who ask for it by name: advances
    /// by `frame_seconds` in [`Surface::split_frame`]'s equal substeps of *variable*
    /// length (never longer than `dt`), so that every frame ends exactly on the game's
    /// clock, at the price of results that depend on the frame times and of a second full
    /// step whenever a frame is a hair longer than `dt`. It ignores and keeps the
    /// accumulator of [`Surface::advance`]. Refuses frames of more than
    /// [`Surface::MAX_SUBSTEPS`] steps.
    pub fn advance_variable(&mut self, frame_seconds: f32) -> Result<usize> {
        let (substeps, dt) = self.split_model_frame(frame_seconds)?;
        self.run(substeps as u64, dt)?;
        Ok(substeps)
    }

    /// How [`Surface::advance_variable`] cuts a frame of `frame_seconds`: the number of equal
    /// substeps and their length in seconds, never longer than one step of `params().dt`.
    ///
    /// A frame whose model time is within a relative 10⁻⁵ of a whole number of timesteps
    /// takes that number (the sliver left over is dropped), so that a 60 Hz frame at the
    /// default time scale is one step of `dt`, not two steps of `dt / 2` because
    /// `(1/60) × 24` rounds a little above 0.4 in `f32`.
    pub fn split_frame(&self, frame_seconds: f32) -> Result<(usize, f32)> {
        let (substeps, dt) = self.split_model_frame(frame_seconds)?;
        Ok((substeps, dt / self.params.time_scale))
    }

    /// [`Surface::split_frame`] with the substep's length in model time, never longer than
    /// `params().dt` (not even by a rounding error).
    fn split_model_frame(&self, frame_seconds: f32) -> Result<(usize, f32)> {
        params::non_negative("frame seconds", frame_seconds)?;
        let dt = self.params.dt;
        let model = frame_seconds as f64 * self.params.time_scale as f64;
        let substeps = (model / dt as f64 * (1.0 - 1e-5)).ceil();
        if substeps > Self::MAX_SUBSTEPS as f64 {
            return Err(Error::InvalidParam {
                name: "frame seconds",
                value: frame_seconds as f64,
                expected:
                    "a frame of at most 10000 timesteps (frame seconds × time_scale ≤ 10000 dt)",
            });
        }
        let substeps = substeps as usize;
        let sub = if substeps == 0 {
            0.0
        } else {
            ((model / substeps as f64) as f32).min(dt)
        };
        Ok((substeps, sub))
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn clock(max_steps: u32, overflow: Overflow) -> Clock {
        Clock {
            max_steps,
            overflow,
            ..Clock::default()
        }
    }

    #[test]
    fn whole_steps_and_a_remainder() {
        let mut c = clock(16, Overflow::Drop);
        assert_eq!(c.tick(0.3, 0.4, 24.0), 0);
        assert!((c.fraction(0.4) - 0.75).abs() < 1e-6);
        assert_eq!(c.tick(0.3, 0.4, 24.0), 1);
        assert!((c.fraction(0.4) - 0.5).abs() < 1e-6);
    }

    #[test]
    fn a_hair_short_of_a_step_is_a_step() {
        let mut c = clock(16, Overflow::Drop);
        assert_eq!(c.tick(0.4 * (1.0 - 1e-6), 0.4, 24.0), 1);
        assert_eq!(c.fraction(0.4), 0.0);
        assert_eq!(c.tick(0.4, 0.4, 24.0), 1);
    }

    /// Frames of thousands of steps of `dt = 0.4`, whose `f32` is a little longer than 0.4:
    /// each frame takes every step it meant, frame after frame.
    #[test]
    fn long_frames_take_every_step_they_mean() {
        let mut c = clock(10_000, Overflow::Drop);
        for frame in 0..100_000 {
            // 100 s at the default time scale: 6,000 steps of 0.4.
            assert_eq!(c.tick(100.0 * 24.0, 0.4, 24.0), 6_000, "frame {frame}");
        }
        assert_eq!(c.dropped, 0.0);
    }

    /// Frames exactly one `f32` step long, and 60 Hz frames at the default time scale
    /// (a hair longer than a step): one step each, for ever; 59.94 Hz frames catch up with
    /// an extra step now and then, as their time says.
    #[test]
    fn frames_of_one_step_take_one_step_for_ever() {
        for (frame, dt, scale) in [
            (1.0f32 / 60.0, 1.0f32 / 60.0, 1.0f32),
            (1.0 / 120.0, 1.0 / 120.0, 1.0),
            (0.02, 0.02, 1.0),
            (1.0 / 60.0, 0.4, 24.0),
        ] {
            let mut c = clock(16, Overflow::Drop);
            for k in 0..1_000_000 {
                let model = frame as f64 * scale as f64;
                assert_eq!(
                    c.tick(model, dt, scale),
                    1,
                    "frame {k} of {frame} s, dt {dt}"
                );
            }
        }
        let mut c = clock(16, Overflow::Drop);
        let steps: u32 = (0..100_000)
            .map(|_| c.tick((1.0f32 / 59.94) as f64 * 24.0, 0.4, 24.0))
            .sum();
        // 100,000 frames of 1/59.94 s are 100,100.1 steps of 1/60 s.
        assert_eq!(steps, 100_100);
    }

    #[test]
    fn the_cap_drops_or_carries() {
        let mut d = clock(3, Overflow::Drop);
        assert_eq!(d.tick(10.0 * 0.4 + 0.1, 0.4, 24.0), 3);
        assert!((d.dropped - 7.0 * 0.4 / 24.0).abs() < 1e-6);
        assert!((d.owed - 0.1).abs() < 1e-6);
        let mut c = clock(3, Overflow::Carry);
        let steps: Vec<u32> = (0..5)
            .map(|k| c.tick(if k == 0 { 4.1 } else { 0.0 }, 0.4, 24.0))
            .collect();
        assert_eq!(steps, [3, 3, 3, 1, 0]);
        assert_eq!(c.dropped, 0.0);
        assert!(c.fraction(0.4) < 1.0);
    }
}
