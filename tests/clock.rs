//! The fixed-step clock of `Surface::advance`: the same total time gives the same bits
//! whatever the frames, the cap drops or carries what a long frame owes, the interpolation
//! factor stays in [0, 1), and the accumulator is state.

mod common;

use common::{state_bits, Rng};
use proptest::prelude::*;
use springwater::disturb::Rain;
use springwater::{Overflow, Params, Surface};

/// A 48 × 40 pool with two drops.
fn pool() -> Surface {
    let mut s = Surface::new(Params::with_size(48, 40)).unwrap();
    s.drop_at(14.0, 12.0, 1.5, 3.0).unwrap();
    s.drop_at(33.0, 27.0, -1.0, 2.0).unwrap();
    s
}

/// Frame lengths in seconds that add up to `total` (in `f64`): `next()` as long as the
/// frames fit, then one frame of what is left.
fn frames(total: f64, mut next: impl FnMut() -> f32) -> Vec<f32> {
    let (mut out, mut sum) = (Vec::new(), 0.0f64);
    loop {
        let f = next();
        if sum + f as f64 >= total {
            out.push((total - sum) as f32);
            return out;
        }
        sum += f as f64;
        out.push(f);
    }
}

/// Two seconds cut three ways: 60 Hz frames, 59.94 Hz frames, and frames jittering
/// between 14 and 20 ms.
fn two_seconds() -> [Vec<f32>; 3] {
    let mut rng = Rng(0x5eed);
    [
        vec![1.0 / 60.0; 120],
        frames(2.0, || 1.0 / 59.94),
        frames(2.0, || 0.017 + 0.006 * rng.next()),
    ]
}

#[test]
fn the_same_total_time_gives_the_same_bits_whatever_the_frames() {
    let mut reference = pool();
    reference.step_n(120).unwrap();
    for cut in two_seconds() {
        let mut s = pool();
        let steps: usize = cut.iter().map(|&f| s.advance(f).unwrap()).sum();
        assert_eq!(steps, 120, "{} frames", cut.len());
        assert_eq!(s.steps(), 120);
        assert!(
            state_bits(&s) == state_bits(&reference),
            "{} frames",
            cut.len()
        );
        assert!(s.interpolation() < 1e-3, "{}", s.interpolation());
    }
}

#[test]
fn disturbances_see_the_same_steps_whatever_the_frames() {
    let run = |cut: &[f32]| {
        let mut s = pool();
        let mut rain = Rain::new(30.0, 7);
        for &f in cut {
            s.advance_with(f, &mut rain).unwrap();
        }
        assert!(rain.fallen() > 40, "{}", rain.fallen());
        state_bits(&s)
    };
    let [sixty, ntsc, jitter] = two_seconds();
    let want = run(&sixty);
    assert!(run(&ntsc) == want);
    assert!(run(&jitter) == want);
}

#[test]
fn a_frame_past_the_cap_takes_the_capped_steps_and_drops_the_rest() {
    let mut s = pool();
    assert_eq!(s.step_cap(), (Surface::DEFAULT_MAX_STEPS, Overflow::Drop));
    // A one-second stall owes 60 steps at the defaults.
    assert_eq!(s.advance(1.0).unwrap(), 16);
    assert!((s.dropped_seconds() - 44.0 / 60.0).abs() < 1e-6);
    assert!(s.owed_seconds() < 1e-6);
    // The water is where 16 steps put it, and the next frame is an ordinary one.
    let mut sixteen = pool();
    sixteen.step_n(16).unwrap();
    assert!(state_bits(&s) == state_bits(&sixteen));
    assert_eq!(s.advance(1.0 / 60.0).unwrap(), 1);
}

#[test]
fn carried_steps_are_taken_by_the_next_calls() {
    let mut s = pool();
    s.set_step_cap(16, Overflow::Carry).unwrap();
    let taken: Vec<usize> = [1.0, 0.0, 0.0, 0.0]
        .iter()
        .map(|&f| s.advance(f).unwrap())
        .collect();
    assert_eq!(taken, [16, 16, 16, 12]);
    assert_eq!(s.dropped_seconds(), 0.0);
    let mut sixty = pool();
    sixty.step_n(60).unwrap();
    assert!(state_bits(&s) == state_bits(&sixty));
}

#[test]
fn a_bad_cap_is_refused_and_changes_nothing() {
    let mut s = pool();
    s.set_step_cap(4, Overflow::Carry).unwrap();
    for bad in [0, Surface::MAX_SUBSTEPS as u32 + 1] {
        assert!(s.set_step_cap(bad, Overflow::Drop).is_err());
        assert_eq!(s.step_cap(), (4, Overflow::Carry));
    }
}

#[test]
fn an_absurd_frame_drops_to_the_cap_without_leaving_a_debt() {
    let mut s = pool();
    assert_eq!(s.advance(f32::MAX).unwrap(), 16);
    assert!(s.owed_seconds() < 1.0 / 60.0 && s.interpolation() < 1.0);
    assert_eq!(
        s.advance(1.0 / 60.0).unwrap() + s.advance(1.0 / 60.0).unwrap(),
        2
    );
}

#[test]
fn a_clone_continues_the_accumulator() {
    let mut a = pool();
    a.advance(0.01).unwrap();
    let mut b = a.clone();
    assert_eq!(a.interpolation(), b.interpolation());
    for _ in 0..7 {
        assert_eq!(a.advance(0.013).unwrap(), b.advance(0.013).unwrap());
    }
    assert!(state_bits(&a) == state_bits(&b));
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(64))]

    /// Whatever the frames, the factor is in [0, 1), the steps taken match the time
    /// passed (none dropped below the cap), and it says where the clock is.
    #[test]
    fn the_interpolation_factor_is_a_fraction_of_a_step(
        cut in prop::collection::vec(0.0f32..0.1, 1..40),
    ) {
        let mut s = Surface::new(Params::with_size(8, 8)).unwrap();
        let mut steps = 0usize;
        for &f in &cut {
            steps += s.advance(f).unwrap();
            let t = s.interpolation();
            prop_assert!((0.0..1.0).contains(&t), "{t}");
        }
        let model: f64 = cut.iter().map(|&f| f as f64 * 24.0).sum();
        let dt = s.params().dt as f64;
        let owed = model - steps as f64 * dt;
        prop_assert!(owed > -1e-3 * dt && owed < dt, "{owed}");
        prop_assert!((s.interpolation() as f64 - owed.max(0.0) / dt).abs() < 1e-3);
        prop_assert_eq!(s.dropped_seconds(), 0.0);
    }
}

#[test]
fn snapshots_keep_the_accumulator_and_the_cap() {
    let mut a = pool();
    a.set_step_cap(5, Overflow::Carry).unwrap();
    a.advance(0.01).unwrap();
    a.advance(0.2).unwrap(); // 12.6 steps owed: 5 now, the rest carried
    let mut b = Surface::from_bytes(&a.to_bytes()).unwrap();
    assert_eq!(b.step_cap(), (5, Overflow::Carry));
    assert_eq!(b.owed_seconds(), a.owed_seconds());
    assert_eq!(b.interpolation(), a.interpolation());
    for f in [0.0, 0.013, 0.0, 0.02] {
        assert_eq!(a.advance(f).unwrap(), b.advance(f).unwrap());
    }
    assert!(state_bits(&a) == state_bits(&b));
    // The plain-data form too, and a bad cap in it is refused.
    let mut snap = a.snapshot();
    assert_eq!(snap.step_cap, (5, Overflow::Carry));
    snap.step_cap.0 = 0;
    assert!(Surface::from_snapshot(snap).is_err());
    let mut snap = a.snapshot();
    snap.owed_time = f64::NAN;
    assert!(Surface::from_snapshot(snap).is_err());
}
