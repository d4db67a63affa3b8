//! The public API: validation errors, substepping, editing tables.

mod common;

use common::state_bits;
use springwater::{Error, Family, Params, Spring, SpringId, Surface};

#[test]
fn every_invalid_parameter_is_refused_with_its_name() {
    let base = Params::default();
    let cases: Vec<(Params, &str)> = vec![
        (base.with_mass(0.0), "mass"),
        (base.with_mass(f32::NAN), "mass"),
        (base.with_stiffness(-1.0), "stiffness"),
        (base.with_spacing(f32::INFINITY), "spacing"),
        (base.with_viscosity(-0.1), "viscosity"),
        (base.with_dt(0.0), "dt"),
        (base.with_rest_ratio(1.5), "rest_ratio"),
        (base.with_rest_ratio(f32::NAN), "rest_ratio"),
        (base.with_acceleration([0.0, f32::NAN, 0.0]), "acceleration"),
    ];
    for (p, name) in cases {
        match Surface::new(p) {
            Err(Error::InvalidParam { name: got, .. }) => assert_eq!(got, name),
            other => panic!("{name}: expected InvalidParam, got {other:?}"),
        }
    }
    for (c, r) in [(1, 5), (5, 1), (0, 0)] {
        assert!(matches!(
            Surface::new(Params::with_size(c, r)),
            Err(Error::GridTooSmall { .. })
        ));
    }
    assert!(matches!(
        Surface::new(Params::with_size(1 << 20, 1 << 20)),
        Err(Error::GridTooLarge { .. })
    ));
    assert!(matches!(
        Surface::new(Params::with_size(usize::MAX, 3)),
        Err(Error::GridTooLarge { .. })
    ));
}

#[test]
fn a_timestep_at_or_past_critical_names_the_critical_value() {
    let p = Params::default().with_dt(0.5);
    let err = Surface::new(p).unwrap_err();
    assert!(matches!(err, Error::TimestepTooLarge { .. }));
    // 0.4364 = sqrt(m / 3c) without damping; the seed's γ = 0.05 lowers it to 0.4358.
    assert!(err.to_string().contains("0.4358"), "{err}");
    let at = Params::default().with_dt(Params::default().critical_dt());
    assert!(Surface::new(at).is_err());
    assert!(Surface::new_without_dt_check(p).is_ok());
}

#[test]
fn advance_takes_whole_steps_and_keeps_the_rest_for_the_next_frame() {
    // Frames in seconds; a time scale of 10 model time units per second makes the model
    // times 0, 0.4, 0.41 and 1.0.
    let mut s = Surface::new(Params::with_size(8, 8).with_time_scale(10.0)).unwrap();
    assert_eq!(s.advance(0.0).unwrap(), 0);
    assert_eq!(s.advance(0.04).unwrap(), 1);
    assert_eq!(s.advance(0.041).unwrap(), 1); // 0.01 owed
    assert!((s.interpolation() - 0.025).abs() < 1e-4);
    assert_eq!(s.advance(0.1).unwrap(), 2); // 1.01: 0.21 owed
    assert!((s.interpolation() - 0.525).abs() < 1e-4);
    assert!((s.owed_seconds() - 0.021).abs() < 1e-6);
    assert!((s.model_time() - 1.6).abs() < 1e-5);
    assert!((s.time() - 0.16).abs() < 1e-6, "seconds: {}", s.time());
    for bad in [-1.0, f32::NAN, f32::INFINITY, f32::NEG_INFINITY] {
        let (before, owed) = (state_bits(&s), s.owed_seconds());
        assert!(s.advance(bad).is_err(), "{bad}");
        assert!(state_bits(&s) == before && s.owed_seconds() == owed);
    }
}

#[test]
fn advance_variable_splits_a_frame_into_substeps_no_longer_than_dt() {
    let mut s = Surface::new(Params::with_size(8, 8).with_time_scale(10.0)).unwrap();
    assert_eq!(s.advance_variable(0.0).unwrap(), 0);
    assert_eq!(s.advance_variable(0.04).unwrap(), 1);
    assert_eq!(s.advance_variable(0.041).unwrap(), 2);
    assert_eq!(s.advance_variable(0.1).unwrap(), 3);
    assert!((s.model_time() - 1.81).abs() < 1e-5);
    assert!((s.time() - 0.181).abs() < 1e-6);
    assert_eq!(
        s.interpolation(),
        0.0,
        "the variable split leaves the accumulator"
    );
    // Two substeps of 0.0205 s, that is 0.205 units of model time.
    let (n, sub) = s.split_frame(0.041).unwrap();
    assert_eq!(n, 2);
    assert!((sub - 0.0205).abs() < 1e-7 && sub <= s.params().dt / 10.0);
    for bad in [-1.0, f32::NAN, f32::INFINITY, 1e9] {
        let before = state_bits(&s);
        assert!(s.advance_variable(bad).is_err(), "{bad}");
        assert!(state_bits(&s) == before);
    }
}

#[test]
fn the_default_time_scale_takes_one_step_per_60_hz_frame() {
    let p = Params::default();
    assert_eq!(p.time_scale, 24.0);
    let mut s = Surface::new(Params::with_size(8, 8)).unwrap();
    for _ in 0..600 {
        assert_eq!(s.advance(1.0 / 60.0).unwrap(), 1);
    }
    // Ten seconds of frames are 240 units of model time.
    assert!((s.time() - 10.0).abs() < 10.0 * 1e-5, "{}", s.time());
    assert!((s.model_time() - 240.0).abs() < 240.0 * 1e-5);
    assert_eq!(s.advance(1.0 / 30.0).unwrap(), 2);
    // A 144 Hz frame is 0.4167 of a step: none now, one in the third frame.
    let steps: Vec<usize> = (0..3).map(|_| s.advance(1.0 / 144.0).unwrap()).collect();
    assert_eq!(steps, [0, 0, 1]);
    // Ripples: about 39 world units per second with the seed's parameters.
    assert!((p.ripple_speed() - 24.0 * 2.625f32.sqrt()).abs() < 1e-3);
}

#[test]
fn the_ripple_speed_sets_the_time_scale() {
    let mut p = Params::with_size(65, 65);
    p.set_ripple_speed(32.0).unwrap();
    assert!((p.ripple_speed() - 32.0).abs() < 1e-4);
    // Doubling the speed doubles the model time of a frame: twice the steps of `dt`,
    // each half as many seconds long.
    let frame = Surface::new(p).unwrap().split_frame(1.0).unwrap();
    p.set_ripple_speed(64.0).unwrap();
    let double = Surface::new(p).unwrap().split_frame(1.0).unwrap();
    let seconds = |(n, dt): (usize, f32)| n as f32 * dt;
    assert!((seconds(frame) - 1.0).abs() < 1e-4 && (seconds(double) - 1.0).abs() < 1e-4);
    assert!((double.0 as f32 - 2.0 * frame.0 as f32).abs() <= 1.0);
    // Refused, nothing changed.
    let before = p;
    for bad in [0.0, -1.0, f32::NAN, f32::INFINITY] {
        assert!(p.set_ripple_speed(bad).is_err());
        assert_eq!(p, before);
    }
    p.rest_ratio = 1.0; // no tension, no travelling ripples
    assert_eq!(p.ripple_speed(), 0.0);
    assert!(p.set_ripple_speed(10.0).is_err());
    for bad in [0.0, -1.0, f32::NAN] {
        let p = Params::default().with_time_scale(bad);
        assert!(matches!(
            Surface::new(p),
            Err(Error::InvalidParam {
                name: "time_scale",
                ..
            })
        ));
    }
}

#[test]
fn bad_edits_are_refused_and_change_nothing() {
    let mut s = Surface::new(Params::with_size(6, 5)).unwrap();
    s.drop_at(2.0, 2.0, 0.5, 1.0).unwrap();
    let before = state_bits(&s);
    assert!(matches!(
        s.add_force(30, [0.0; 3]),
        Err(Error::OutOfRange { .. })
    ));
    assert!(s.add_force(3, [f32::NAN, 0.0, 0.0]).is_err());
    assert!(s.add_velocity(7, [0.0, f32::INFINITY, 0.0]).is_err());
    assert!(s.drop_at(1.0, 1.0, 1.0, 0.0).is_err());
    assert!(s.drop_at(f32::NAN, 1.0, 1.0, 1.0).is_err());
    assert!(s.set_forces([&[0.0; 29], &[0.0; 30], &[0.0; 30]]).is_err());
    assert!(s.set_mass(3, -1.0).is_err());
    assert!(
        s.set_mass(3, 0.1).is_err(),
        "a tiny mass puts dt past the critical timestep"
    );
    assert!(s.set_viscosity(3, f32::NAN).is_err());
    let east_of_last_column = SpringId {
        family: Family::E,
        origin: 5,
    };
    assert!(s.spring(east_of_last_column).is_none());
    assert!(s
        .set_spring(
            east_of_last_column,
            Spring {
                rest: 1.0,
                stiffness: 7.0
            }
        )
        .is_err());
    assert!(s
        .set_spring(
            SpringId {
                family: Family::S,
                origin: 0
            },
            Spring {
                rest: 0.5,
                stiffness: 100.0
            }
        )
        .is_err());
    assert!(state_bits(&s) == before);
    assert!(s.forces().iter().all(|c| c.iter().all(|&f| f == 0.0)));
}

#[test]
fn edits_take_effect() {
    let mut s = Surface::new(Params::with_size(6, 5)).unwrap();
    let id = SpringId {
        family: Family::SE,
        origin: 7,
    };
    assert_eq!(
        s.spring(id),
        Some(Spring {
            rest: 0.5 * std::f32::consts::SQRT_2,
            stiffness: 7.0
        })
    );
    s.set_spring(
        id,
        Spring {
            rest: 1.0,
            stiffness: 6.0,
        },
    )
    .unwrap();
    assert_eq!(
        s.spring(id),
        Some(Spring {
            rest: 1.0,
            stiffness: 6.0
        })
    );
    assert!(!s.is_pinned(7).unwrap());
    s.set_pinned(7, true).unwrap();
    assert!(s.is_pinned(7).unwrap());
    s.add_force(8, [0.0, 1.0, 0.0]).unwrap();
    s.step().unwrap();
    assert!(s.positions()[1][8] > 0.0, "the force lifted the node");
    assert_eq!(s.positions()[1][7], 0.0, "a pinned node never moves");
    assert!(
        s.forces()[1].iter().all(|&f| f == 0.0),
        "forces apply for one step"
    );
}

#[test]
fn whole_tables_of_masses_and_viscosities_are_set_at_once_or_not_at_all() {
    let mut s = Surface::new(Params::with_size(6, 5)).unwrap();
    s.set_pinned(8, true).unwrap();
    let masses: Vec<f32> = (0..30).map(|i| 4.0 + 0.25 * i as f32).collect();
    let viscosities: Vec<f32> = (0..30).map(|i| 0.01 * (i % 3) as f32).collect();
    let (hash, critical) = (s.state_hash(), s.critical_dt());
    // The last value refused: a tiny mass puts dt past the critical timestep.
    for bad in [f32::NAN, -1.0, 0.1] {
        let mut m = masses.clone();
        m[29] = bad;
        assert!(s.set_masses(&m).is_err(), "mass {bad}");
    }
    for bad in [f32::NAN, -1.0, f32::INFINITY] {
        let mut v = viscosities.clone();
        v[29] = bad;
        assert!(s.set_viscosities(&v).is_err(), "viscosity {bad}");
    }
    assert!(s.set_viscosities(&[1e9; 30]).is_err(), "too viscous for dt");
    assert!(matches!(
        s.set_masses(&masses[1..]),
        Err(Error::LengthMismatch { .. })
    ));
    assert_eq!((s.state_hash(), s.critical_dt()), (hash, critical));

    // The same state as setting the nodes one by one.
    let mut one_by_one = Surface::new(Params::with_size(6, 5)).unwrap();
    one_by_one.set_pinned(8, true).unwrap();
    for i in 0..30 {
        one_by_one.set_mass(i, masses[i]).unwrap();
        one_by_one.set_viscosity(i, viscosities[i]).unwrap();
    }
    s.set_masses(&masses).unwrap();
    s.set_viscosities(&viscosities).unwrap();
    assert_eq!(s.masses().to_vec(), masses);
    assert_eq!(s.viscosities().to_vec(), viscosities);
    s.drop_at(2.0, 2.0, 0.5, 1.0).unwrap();
    one_by_one.drop_at(2.0, 2.0, 0.5, 1.0).unwrap();
    s.step_n(20).unwrap();
    one_by_one.step_n(20).unwrap();
    assert_eq!(s.state_hash(), one_by_one.state_hash());
    assert_eq!(s.critical_dt(), one_by_one.critical_dt());
}

#[test]
fn an_overflowing_step_leaves_the_state_bitwise_unchanged() {
    let mut s = Surface::new(Params::with_size(9, 9)).unwrap();
    s.drop_at(4.0, 4.0, 1.0, 2.0).unwrap();
    s.step().unwrap();
    s.add_velocity(41, [0.0, 3.3e38, 0.0]).unwrap();
    s.add_force(40, [0.0, f32::MAX, 0.0]).unwrap();
    assert!(
        s.add_force(40, [0.0, f32::MAX, 0.0]).is_err(),
        "the sum would overflow"
    );
    let before = state_bits(&s);
    // Every value is finite, but v + F/m·dt overflows at node 41.
    let mut big = vec![0.0f32; 81];
    big[41] = f32::MAX;
    s.set_forces([&vec![0.0; 81], &big, &vec![0.0; 81]])
        .unwrap();
    let steps = s.steps();
    let err = s.step().unwrap_err();
    assert!(matches!(err, Error::NonFinite { node: 41, .. }), "{err}");
    assert!(state_bits(&s) == before);
    assert_eq!(s.steps(), steps);
    assert_eq!(
        s.forces()[1][41],
        f32::MAX,
        "a refused step keeps the pending forces"
    );
}

/// `drop_at` only evaluates the Gaussian near its centre; everywhere it must still give
/// `y + height · exp(−d²/radius²)` to the bit (including the sign of zero heights), for
/// drops inside, at the edge of and outside the grid, of any size, at any spacing.
#[test]
fn a_drop_is_the_gaussian_formula_on_every_node_to_the_bit() {
    let mut rng = common::Rng(0x2545_f491);
    for case in 0..300 {
        let cols = 2 + (rng.next().abs() * 60.0) as usize;
        let rows = 2 + (rng.next().abs() * 60.0) as usize;
        let mut p = Params::with_size(cols, rows);
        p.spacing = [1.0, 0.5, 0.25, 3.0][case % 4];
        p.mass *= p.spacing;
        p.dt *= p.spacing.sqrt().min(1.0);
        let mut s = Surface::new(p).unwrap();
        let h = p.spacing;
        let (w, l) = ((cols - 1) as f32 * h, (rows - 1) as f32 * h);
        // A surface that has moved, with some heights exactly −0.
        s.drop_at(w / 3.0, l / 2.0, 0.3 * h, 2.0 * h).unwrap();
        s.step_n(3).unwrap();
        let mut state = s.snapshot();
        for (i, y) in state.positions[1].iter_mut().enumerate() {
            if i % 7 == 0 && !state.pinned[i] {
                *y = -0.0;
            }
        }
        let mut s = Surface::from_snapshot(state).unwrap();
        let x = (rng.next() * 1.6 + 0.5) * w;
        let z = (rng.next() * 1.6 + 0.5) * l;
        let height = rng.next() * 2.0 * h;
        let radius = h * [0.01, 0.5, 1.0, 3.0, 40.0, 1e6][case % 6] * (1.0 + rng.next().abs());
        let before: Vec<f32> = s.positions()[1].to_vec();
        s.drop_at(x, z, height, radius).unwrap();
        let g = s.grid();
        let inv_r2 = 1.0 / (radius * radius);
        for (i, &y0) in before.iter().enumerate() {
            let want = if s.is_pinned(i).unwrap() {
                y0
            } else {
                let (c, r) = g.coords(i);
                let d2 = (c as f32 * h - x).powi(2) + (r as f32 * h - z).powi(2);
                let wgt = if d2 == 0.0 { 1.0 } else { (-d2 * inv_r2).exp() };
                y0 + height * wgt
            };
            let got = s.positions()[1][i];
            assert_eq!(
                got.to_bits(),
                want.to_bits(),
                "case {case}: node {i} of {cols}x{rows}, drop ({x}, {z}, {height}, {radius})"
            );
        }
    }
}
