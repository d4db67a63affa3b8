//! Floating bodies: action and reaction, settling, riding waves, wakes, stability at the
//! critical timestep, snapshots, bits, and bad input.

mod common;

use glam::Vec3;
use springwater::internals::Tuning;
use springwater::{Boundary, Buoyancy, Error, Floater, FloaterId, Params, Shape, Surface};

/// `f` with `edit` applied (`Floater` is `#[non_exhaustive]`: no struct update syntax).
fn edited(mut f: Floater, edit: impl FnOnce(&mut Floater)) -> Floater {
    edit(&mut f);
    f
}

/// A sphere of `radius` floating at `relative_density` of the water's, at rest at `at`.
fn ball(s: &Surface, radius: f32, relative_density: f32, at: [f32; 3]) -> Floater {
    let mut f = Floater::sphere(radius, 1.0, at);
    f.mass = relative_density * s.buoyancy().density * f.shape.volume();
    f
}

fn vertical_momentum(s: &Surface) -> f64 {
    let vy = s.velocities()[1];
    s.masses()
        .iter()
        .zip(vy)
        .map(|(&m, &v)| m as f64 * v as f64)
        .sum()
}

#[test]
fn what_the_water_gets_is_minus_what_the_body_gets_less_what_the_column_carries() {
    // A free sheet without viscosity: the springs' forces cancel in pairs, so the water's
    // momentum changes only by the bodies' reactions. The body's momentum changes by its
    // water force, gravity and push; the water gets minus that force less what the water
    // column carries, every step (the body's force in seconds, the water's in the
    // lattice's units: `time_scale²` apart; see `docs/floating.md`).
    let p = Params::with_size(40, 40)
        .with_viscosity(0.0)
        .with_boundary(Boundary::Free);
    let mut s = Surface::new(p).unwrap();
    let a = s
        .add_floater(ball(&s, 3.0, 0.4, [20.0, 2.0, 20.0]))
        .unwrap();
    let mut boxy = Floater::cuboid([2.0, 1.0, 1.5], 8.0, [9.3, 0.0, 27.6]);
    boxy.velocity = Vec3::new(7.2, -4.8, 2.4);
    let b = s.add_floater(boxy).unwrap();
    let dt = p.dt as f64;
    let ts2 = (p.time_scale as f64).powi(2);
    let (mut worst, mut felt) = (0.0f64, 0.0);
    for step in 0..300 {
        if step % 50 == 0 {
            s.push_floater(a, [576.0, 0.0, -288.0]).unwrap();
        }
        let before = vertical_momentum(&s);
        let carried: f64 = s.water_column().iter().map(|e| e.1[1] as f64).sum();
        s.step().unwrap();
        let water = (vertical_momentum(&s) - before) / dt;
        let bodies: f64 = [a, b]
            .iter()
            .map(|&id| s.floater(id).unwrap().water_force.y as f64)
            .sum::<f64>()
            / ts2;
        felt += bodies.abs();
        // The springs' forces cancel only to rounding, which grows as the free sheet
        // deforms: measured about 1e-6 per step on the same sheet without bodies, up to a
        // few 1e-4 late in this run. A reaction off by 1% would be 0.01 × |body| ≈ 0.03.
        worst = worst.max((water + bodies + carried).abs());
    }
    println!("largest |water + body| over 300 steps: {worst:.2e}");
    assert!(felt / 300.0 > 1.0, "the bodies hardly touched the water");
    assert!(worst < 1e-3, "{worst}");
}

#[test]
fn a_released_body_settles_where_buoyancy_balances_its_weight() {
    let mut s = Surface::new(Params::with_size(64, 64)).unwrap();
    let g = s.buoyancy().gravity;
    let ids: Vec<FloaterId> = [
        ball(&s, 3.0, 0.5, [32.0, 4.0, 32.0]),
        Floater::cuboid([2.0, 1.0, 2.5], 12.0, [14.0, 3.0, 48.0]),
    ]
    .into_iter()
    .map(|f| s.add_floater(f.clone()).unwrap())
    .collect();
    s.step_n(3000).unwrap();
    for id in ids {
        let f = s.floater(id).unwrap().clone();
        let weight = f.mass * g;
        // At rest up and down. Sideways, the pool's last ripples still nudge it, and near
        // the pinned walls its own dent is lopsided: the slope's pressure slides it slowly
        // towards the middle.
        assert!(
            f.velocity.y.abs() < 1e-3,
            "{id:?} still bobs: {:?}",
            f.velocity
        );
        assert!(
            f.velocity.length() < 0.05,
            "{id:?} still moves: {:?}",
            f.velocity
        );
        assert!(
            (f.water_force.y - weight).abs() < 1e-3 * weight,
            "{id:?}: buoyancy {} vs weight {weight}",
            f.water_force.y
        );
        // The water under it is calm: the water column carries the body's weight.
        let under = s.height_at(f.position.x, f.position.z).unwrap();
        assert!(under.abs() < 1e-3, "{id:?}: water under it at {under}");
        // Submerged: displaced volume × density = mass.
        if let Shape::Box { half_extents: e } = f.shape {
            let draft = f.mass / (s.buoyancy().density * 4.0 * e.x * e.z);
            let bottom = f.position.y - e.y;
            let wet = under - bottom;
            assert!(
                (wet - draft).abs() < 0.1 * draft,
                "box draft {wet} vs {draft}"
            );
        }
    }
}

/// Times at which `y` crosses its mean upwards, by linear interpolation.
fn up_crossings(y: &[f32], dt: f32) -> Vec<f32> {
    let mean = y.iter().sum::<f32>() / y.len() as f32;
    (1..y.len())
        .filter(|&k| y[k - 1] < mean && y[k] >= mean)
        .map(|k| {
            let t = (mean - y[k - 1]) / (y[k] - y[k - 1]);
            (k as f32 - 1.0 + t) * dt
        })
        .collect()
}

#[test]
fn a_body_riding_a_passing_wave_bobs_with_the_waves_period() {
    // A long plane wave driven along a line of nodes in open water; a small light ball
    // further along rides it.
    let p = Params::with_size(260, 72).with_boundary(Boundary::Absorbing { width: 16 });
    let mut s = Surface::new(p).unwrap();
    let body = s
        .add_floater(ball(&s, 1.0, 0.3, [150.0, 0.0, 36.0]))
        .unwrap();
    let period = 30.0f32; // model time: 75 steps, a wavelength of about 49 cells
    let mut heights = Vec::new();
    for step in 0..900 {
        let t = step as f32 * p.dt;
        let f = 0.4 * (std::f32::consts::TAU * t / period).sin();
        for row in 16..56 {
            s.add_force(row * p.cols + 60, [0.0, f, 0.0]).unwrap();
        }
        s.step().unwrap();
        if step >= 450 {
            heights.push(s.floater(body).unwrap().position.y);
        }
    }
    let ups = up_crossings(&heights, p.dt);
    assert!(ups.len() >= 4, "the ball did not bob: {ups:?}");
    let measured = (ups[ups.len() - 1] - ups[0]) / (ups.len() - 1) as f32;
    println!("wave period {period}, bobbing period {measured}");
    assert!(
        (measured - period).abs() < 0.03 * period,
        "{measured} vs {period}"
    );
    let swing = heights.iter().fold(0.0f32, |a, &y| a.max(y.abs()));
    assert!(swing > 0.05, "it barely moves: {swing}");
}

/// Largest |y| over the nodes whose rest position satisfies `region`.
fn largest_height(s: &Surface, region: impl Fn(f32, f32) -> bool) -> f32 {
    let grid = s.grid();
    let y = s.positions()[1];
    (0..s.node_count())
        .filter(|&i| {
            let (c, r) = grid.coords(i);
            region(c as f32, r as f32)
        })
        .fold(0.0, |a, i| a.max(y[i].abs()))
}

/// Drives a ball along the middle of a pool at `speed` (a multiple of the ripple speed)
/// and returns the largest heights ahead of it and behind it.
fn drive(speed: f32) -> (f32, f32) {
    let p = Params::with_size(260, 120).with_boundary(Boundary::absorbing());
    let mut s = Surface::new(p).unwrap();
    let v = speed * p.ripple_speed();
    let mut b = ball(&s, 2.0, 0.5, [50.0, 0.0, 60.0]);
    let id = s.add_floater(b).unwrap();
    for _ in 0..300 {
        b = s.floater(id).unwrap().clone();
        b.velocity = Vec3::new(v, 0.0, 0.0);
        b.position.y = 0.0;
        s.set_floater(id, b).unwrap();
        s.step().unwrap();
    }
    let front = s.floater(id).unwrap().position.x + 2.0 + 2.0;
    let ahead = largest_height(&s, |x, _| x > front && x < 225.0);
    let behind = largest_height(&s, |x, _| x < front - 8.0 && x > 35.0);
    (ahead, behind)
}

#[test]
fn a_body_faster_than_the_waves_leaves_a_wake_and_calm_water_ahead() {
    let (ahead, behind) = drive(2.0);
    println!("twice the ripple speed: ahead {ahead:.2e}, behind {behind:.2e}");
    // (The water column carries what stays steady under the body: the wake is made by the
    // load arriving ahead of it and leaving behind it; 5.7e-3 when measured.)
    assert!(behind > 2e-3, "no wake: {behind}");
    assert!(
        ahead < 1e-3 * behind,
        "waves ran ahead: {ahead} vs {behind}"
    );
    // Slower than the waves, the ripples outrun the body.
    let (ahead, behind) = drive(0.5);
    println!("half the ripple speed: ahead {ahead:.2e}, behind {behind:.2e}");
    assert!(ahead > 0.05 * behind, "{ahead} vs {behind}");
}

/// Forty bodies of many sizes, masses and speeds and a `dt` of `share` of the critical
/// timestep with them floating.
fn crowded(share: f32) -> Surface {
    let base = Params::with_size(96, 96);
    let bodies = |s: &mut Surface| {
        for k in 0..40u32 {
            let x = 8.0 + (k % 8) as f32 * 11.0;
            let z = 8.0 + (k / 8) as f32 * 18.0;
            let size = 0.3 + (k % 5) as f32 * 0.9;
            let mut f = if k % 3 == 0 {
                Floater::cuboid([size, 0.5 * size, 1.3 * size], 1.0, [x, 1.0, z])
            } else {
                Floater::sphere(size, 1.0, [x, 0.5, z])
            };
            f.mass = [0.05, 0.3, 0.7, 0.95, 0.5][k as usize % 5] * f.shape.volume();
            f.velocity = 24.0 * Vec3::new((k % 7) as f32 - 3.0, 0.5, (k % 4) as f32 - 1.5);
            f.drag = [0.0, 6.0, 48.0, 1200.0][k as usize % 4];
            s.add_floater(f.clone()).unwrap();
        }
    };
    let mut probe = Surface::new(base).unwrap();
    bodies(&mut probe);
    let p = base.with_dt(share * probe.critical_dt());
    let mut s = Surface::new(p).unwrap();
    bodies(&mut s);
    s
}

#[test]
fn many_bodies_stay_stable_at_099_of_the_critical_timestep() {
    let mut s = crowded(0.99);
    for step in 0..3000 {
        if step % 40 == 0 {
            let k = step as f32;
            s.drop_at((k * 7.3) % 90.0 + 3.0, (k * 3.1) % 90.0 + 3.0, 1.0, 2.0)
                .unwrap();
        }
        s.step().unwrap();
    }
    // The prestressed lattice's energy at rest, and what the drops and bodies add.
    let rest = Surface::new(*s.params()).unwrap().energy().total();
    let e = s.energy().total();
    assert!(
        e.is_finite() && e < rest + 1e3,
        "energy {e}, at rest {rest}"
    );
    for (id, f) in s.floaters() {
        assert!(
            f.position.is_finite() && f.velocity.length() < 240.0,
            "{id:?}: {f:?}"
        );
    }
}

#[test]
fn bodies_step_with_the_same_bits_at_every_level_and_thread_count() {
    common::same_bits_everywhere(
        || {
            let mut s = crowded(0.9);
            s.drop_at(40.0, 40.0, 1.0, 3.0).unwrap();
            s
        },
        |s| {
            for _ in 0..60 {
                s.step().unwrap();
            }
            s.advance(0.1).unwrap();
        },
    );
}

#[test]
fn bodies_are_part_of_snapshots() {
    let mut a = crowded(0.9);
    a.step_n(25).unwrap();
    let id = a.floaters().nth(3).unwrap().0;
    a.push_floater(id, [0.0, 2880.0, 0.0]).unwrap();
    let first = a.floaters().next().unwrap().0;
    a.remove_floater(first).unwrap();
    let mut b = Surface::from_bytes(&a.to_bytes()).unwrap();
    assert_eq!(b.floaters().count(), 39);
    assert_eq!(b.snapshot(), a.snapshot());
    a.step_n(40).unwrap();
    b.step_n(40).unwrap();
    assert_eq!(a.to_bytes(), b.to_bytes());
    // Ids are never reused, also across a snapshot.
    let next = b
        .add_floater(Floater::sphere(1.0, 2.0, [5.0, 0.0, 5.0]))
        .unwrap();
    assert_eq!(next, FloaterId::from_raw(40));
}

#[test]
fn bad_bodies_are_refused_and_change_nothing() {
    let mut s = Surface::new(Params::with_size(32, 32)).unwrap();
    let good = Floater::sphere(1.0, 2.0, [16.0, 0.0, 16.0]);
    let id = s.add_floater(good.clone()).unwrap();
    let before = s.to_bytes();
    let bad = [
        Floater::sphere(0.0, 1.0, [1.0, 0.0, 1.0]),
        Floater::sphere(f32::NAN, 1.0, [1.0, 0.0, 1.0]),
        Floater::sphere(2e9, 1.0, [1.0, 0.0, 1.0]),
        Floater::sphere(1.0, 0.0, [1.0, 0.0, 1.0]),
        Floater::sphere(1.0, -1.0, [1.0, 0.0, 1.0]),
        Floater::sphere(1.0, 1e-40, [1.0, 0.0, 1.0]),
        Floater::cuboid([1.0, -1.0, 1.0], 1.0, [1.0, 0.0, 1.0]),
        Floater::sphere(1.0, 1.0, [f32::INFINITY, 0.0, 1.0]),
        edited(good.clone(), |f| f.velocity = Vec3::new(0.0, 2e11, 0.0)),
        edited(good.clone(), |f| f.drag = -1.0),
        edited(good.clone(), |f| f.push = Vec3::new(f32::NAN, 0.0, 0.0)),
    ];
    for f in bad {
        assert!(
            matches!(s.add_floater(f.clone()), Err(Error::InvalidParam { .. })),
            "{f:?}"
        );
        assert!(s.set_floater(id, f.clone()).is_err(), "{f:?}");
    }
    assert!(s.push_floater(id, [f32::NAN, 0.0, 0.0]).is_err());
    assert!(s.push_floater(id, [f32::MAX, 0.0, 0.0]).is_ok());
    assert!(
        s.push_floater(id, [f32::MAX, 0.0, 0.0]).is_err(),
        "overflows"
    );
    s.set_floater(id, good).unwrap();
    for b in [
        Buoyancy {
            gravity: -1.0,
            ..Buoyancy::default()
        },
        Buoyancy {
            density: f32::NAN,
            ..Buoyancy::default()
        },
        // A waterline stiff enough to need a smaller timestep.
        Buoyancy {
            gravity: 57_600.0,
            density: 100.0,
        },
    ] {
        assert!(s.set_buoyancy(b).is_err(), "{b:?}");
    }
    assert!(matches!(
        s.floater(FloaterId::from_raw(7)),
        Err(Error::NoSuchFloater(7))
    ));
    assert_eq!(s.to_bytes(), before);
}

#[test]
fn a_step_whose_bodies_blow_up_changes_nothing() {
    // A body pushed hard enough to leave every valid range in one step: the step is
    // refused, and the water, its pending forces, the other body's reactions already
    // written and every body are untouched.
    let mut s = Surface::new(Params::with_size(32, 32)).unwrap();
    s.add_force(100, [0.0, 1.0, 0.0]).unwrap();
    s.add_floater(Floater::sphere(2.0, 5.0, [16.0, 0.0, 16.0]))
        .unwrap();
    let thrown = s
        .add_floater(Floater::cuboid([1.0, 0.5, 1.0], 1.0, [8.0, 0.0, 8.0]))
        .unwrap();
    s.push_floater(thrown, [0.0, -f32::MAX, 0.0]).unwrap();
    let before = s.to_bytes();
    let err = s.step().unwrap_err();
    assert!(
        matches!(err, Error::FloaterNonFinite { floater: 1, .. }),
        "{err}"
    );
    assert_eq!(s.to_bytes(), before);
    // Without the push the same surface steps.
    s.set_floater(
        thrown,
        Floater::cuboid([1.0, 0.5, 1.0], 1.0, [8.0, 0.0, 8.0]),
    )
    .unwrap();
    s.step().unwrap();
}

#[test]
fn bodies_wider_than_64_cells_are_refused() {
    let mut s = Surface::new(Params::with_size(200, 200)).unwrap();
    assert!(s
        .add_floater(Floater::sphere(32.0, 1.0, [100.0, 0.0, 100.0]))
        .is_ok());
    let err = s.add_floater(Floater::sphere(32.5, 1.0, [100.0, 0.0, 100.0]));
    assert!(
        matches!(
            err,
            Err(Error::InvalidParam {
                name: "floater size",
                ..
            })
        ),
        "{err:?}"
    );
    // Tall is as wide once it lies down: the limit is twice the bounding radius.
    assert!(s
        .add_floater(Floater::cuboid([2.0, 500.0, 2.0], 10.0, [50.0, 0.0, 50.0]))
        .is_err());
    assert!(s
        .add_floater(Floater::cuboid([2.0, 30.0, 2.0], 10.0, [50.0, 0.0, 50.0]))
        .is_ok());
}

#[test]
fn a_large_body_keeps_the_water_stable() {
    // 64 cells across: columns of one cell, the water carries it at the seed's timestep.
    let mut s = Surface::new(Params::with_size(128, 128)).unwrap();
    let mut raft = Floater::sphere(16.0, 1.0, [64.0, 8.0, 64.0]);
    raft.mass = 0.5 * raft.shape.volume();
    raft.drag = 48.0;
    s.add_floater(raft).unwrap();
    s.step_n(2000).unwrap();
    assert!(s.energy().total().is_finite());
}

#[test]
fn bodies_off_the_patch_float_on_calm_water() {
    let mut s = Surface::new(Params::with_size(16, 16)).unwrap();
    let id = s
        .add_floater(ball(&s, 1.0, 0.5, [-20.0, 1.0, 8.0]))
        .unwrap();
    s.step_n(2000).unwrap();
    let f = s.floater(id).unwrap();
    assert!(f.position.y.abs() < 0.05, "{f:?}");
    let calm = Surface::new(*s.params()).unwrap();
    assert_eq!(
        s.positions(),
        calm.positions(),
        "nothing was pushed into the water"
    );
}

#[test]
fn a_push_that_would_throw_a_body_out_of_range_is_refused() {
    let mut s = Surface::new(Params::with_size(16, 16)).unwrap();
    let mut f = Floater::sphere(1.0, 1.0, [8.0, 0.0, 8.0]);
    f.drag = 0.0;
    let id = s.add_floater(f.clone()).unwrap();
    s.push_floater(id, [f32::MAX, 0.0, 0.0]).unwrap();
    let before = s.to_bytes();
    assert!(matches!(
        s.step(),
        Err(Error::FloaterNonFinite { floater: 0, .. })
    ));
    assert_eq!(s.to_bytes(), before);
    // Every snapshot a surface writes loads again.
    Surface::from_bytes(&before).unwrap();
}

#[test]
fn ids_run_out_with_an_error_not_an_overflow() {
    // The id the next body gets is not a public field: set it in the binary format
    // (offset 120, `u64`).
    let mut bytes = Surface::new(Params::with_size(16, 16)).unwrap().to_bytes();
    bytes[120..128].copy_from_slice(&u64::MAX.to_le_bytes());
    common::fix_crc(&mut bytes);
    let mut s = Surface::from_bytes(&bytes).unwrap();
    let before = s.to_bytes();
    let err = s.add_floater(Floater::sphere(1.0, 1.0, [8.0, 0.0, 8.0]));
    assert!(
        matches!(
            err,
            Err(Error::InvalidParam {
                name: "floater id",
                ..
            })
        ),
        "{err:?}"
    );
    assert_eq!(s.to_bytes(), before);
}

#[test]
fn water_force_is_read_only() {
    let mut s = Surface::new(Params::with_size(16, 16)).unwrap();
    let f = edited(Floater::sphere(1.0, 2.0, [8.0, 0.0, 8.0]), |f| {
        f.water_force = Vec3::NAN
    });
    let id = s.add_floater(f.clone()).unwrap();
    assert_eq!(s.floater(id).unwrap().water_force, Vec3::ZERO);
    s.step().unwrap();
    let felt = s.floater(id).unwrap().water_force;
    s.set_floater(id, edited(f.clone(), |f| f.water_force = Vec3::splat(7.0)))
        .unwrap();
    assert_eq!(s.floater(id).unwrap().water_force, felt);
}

#[test]
fn a_body_set_is_read_back_exactly() {
    // A body's state is kept in the units it is given in (seconds): nothing is converted
    // on the way in or out, at the default time scale or any other.
    for time_scale in [24.0, 10.0 / 3.0] {
        let p = Params::with_size(32, 32).with_time_scale(time_scale);
        let mut s = Surface::new(p).unwrap();
        let id = s
            .add_floater(Floater::sphere(1.5, 3.0, [16.0, 0.0, 16.0]))
            .unwrap();
        s.step_n(5).unwrap();
        let mut f = s.floater(id).unwrap().clone();
        f.velocity = Vec3::new(0.1, -1.0 / 3.0, std::f32::consts::E);
        f.drag = 0.3;
        f.push = Vec3::new(1.0 / 7.0, 0.0, -0.2);
        f.position = Vec3::new(15.123_457, 0.1, 16.9);
        s.set_floater(id, f.clone()).unwrap();
        assert_eq!(s.floater(id).unwrap().clone(), f);
        let other = s.add_floater(f.clone()).unwrap();
        let fresh = edited(f.clone(), |f| {
            f.water_force = Vec3::ZERO;
            f.water_torque = Vec3::ZERO;
        });
        assert_eq!(s.floater(other).unwrap().clone(), fresh);
        // And through a snapshot.
        let back = Surface::from_bytes(&s.to_bytes()).unwrap();
        assert_eq!(*back.floater(id).unwrap(), f);
        assert_eq!(*back.floater(other).unwrap(), fresh);
        assert_eq!(back.buoyancy(), s.buoyancy());
    }
}

#[test]
fn a_body_released_at_rest_settles_at_archimedes_depth_at_any_time_scale() {
    // A box released at rest with its centre on calm water sinks until the water it
    // displaces weighs what it weighs: draft = mass / (density × footprint). Gravity is set
    // to the same 0.1 per unit of model time² at every time scale, so the lattice sees the
    // same forces and the body must come to the same place, to rounding: the time scale
    // only changes the units the body is counted in.
    let e = Vec3::new(2.0, 1.0, 2.5);
    let mut depths = Vec::new();
    for time_scale in [24.0f32, 10.0, 60.0] {
        let p = Params::with_size(48, 48).with_time_scale(time_scale);
        let mut s = Surface::new(p).unwrap();
        let gravity = 0.1 * time_scale * time_scale;
        s.set_buoyancy(Buoyancy {
            gravity,
            density: 1.0,
        })
        .unwrap();
        let id = s
            .add_floater(Floater::cuboid(e, 12.0, [24.0, 0.0, 24.0]))
            .unwrap();
        s.step_n(3000).unwrap();
        let f = s.floater(id).unwrap().clone();
        let weight = f.mass * gravity;
        assert!(
            f.velocity.length() < 1e-3 * time_scale,
            "{time_scale}: {f:?}"
        );
        assert!(
            (f.water_force.y - weight).abs() < 1e-3 * weight,
            "{time_scale}: buoyancy {} vs weight {weight}",
            f.water_force.y
        );
        let draft = f.mass / (4.0 * e.x * e.z);
        let under = s.height_at(f.position.x, f.position.z).unwrap();
        let wet = under - (f.position.y - e.y);
        assert!(
            (wet - draft).abs() < 0.1 * draft,
            "{time_scale}: draft {wet} vs {draft}"
        );
        depths.push(f.position.y);
    }
    println!("centre heights at time scales 24, 10, 60: {depths:?}");
    // The same physics in seconds: equal to rounding, which the body's slow rocking in
    // the pool's last ripples carries to a few 1e-5.
    for y in &depths[1..] {
        assert!((y - depths[0]).abs() < 1e-4, "{depths:?}");
    }
    // At the default gravity (57.6 per second², 0.1 per unit of model time² at the
    // default time scale) the box floats where it did at the first time scale above.
    let mut s = Surface::new(Params::with_size(48, 48)).unwrap();
    assert_eq!(s.buoyancy().gravity, 57.6);
    let id = s
        .add_floater(Floater::cuboid(e, 12.0, [24.0, 0.0, 24.0]))
        .unwrap();
    s.step_n(3000).unwrap();
    let y = s.floater(id).unwrap().position.y;
    assert!((y - depths[0]).abs() < 1e-6, "{y} vs {}", depths[0]);
}

#[test]
fn a_bodys_velocity_is_its_change_of_position_per_second() {
    let mut s = Surface::new(Params::with_size(48, 48)).unwrap();
    let mut b = ball(&s, 2.0, 0.5, [16.0, 3.0, 24.0]);
    b.velocity = Vec3::new(12.0, 0.0, -6.0);
    let id = s.add_floater(b).unwrap();
    let seconds = s.params().dt / s.params().time_scale;
    for _ in 0..90 {
        let before = s.floater(id).unwrap().position;
        s.step().unwrap();
        let after = s.floater(id).unwrap().clone();
        let rate = (after.position - before) / seconds;
        // Positions of about 20 carry about 2e-6 of rounding, over a 60th of a second.
        assert!(
            (rate - after.velocity).abs().max_element() < 1e-3,
            "{rate} vs {}",
            after.velocity
        );
    }
    // Over a second of the game's clock the body moves by about its mean velocity.
    let (start, v0) = {
        let f = s.floater(id).unwrap();
        (f.position, f.velocity)
    };
    let mut mean = Vec3::ZERO;
    for _ in 0..60 {
        assert_eq!(s.advance(1.0 / 60.0).unwrap(), 1);
        mean += s.floater(id).unwrap().velocity / 60.0;
    }
    let moved = s.floater(id).unwrap().position - start;
    assert!(
        (moved - mean).abs().max_element() < 1e-3,
        "moved {moved} in 1 s, mean velocity {mean} (started at {v0})"
    );
}

#[test]
fn a_step_a_body_refuses_changes_nothing_after_a_load_or_body_forces() {
    // Found by the restore_bodies fuzz target (fuzz/regressions/restore_bodies/): a step
    // that failed in a body's own step, before the water column gathered anything, undid
    // the column from a stale mark of where that step's entries began. A surface just
    // loaded (mark 0) lost every load its column carried. The same with `body_forces`
    // loads waiting, which also move entries past the mark.
    let mut s = Surface::new(Params::with_size(16, 16).with_dt(0.2)).unwrap();
    let id = s.add_floater(ball(&s, 1.5, 0.5, [8.0, 0.0, 8.0])).unwrap();
    s.step_n(20).unwrap();
    assert!(!s.water_column().is_empty(), "the column carries the ball");
    // A push no body's step takes (its velocity would pass 1e11 in a step).
    let overwhelm = |s: &mut Surface| {
        s.push_floater(id, [0.0, 0.0, -4e28]).unwrap();
        let before = s.to_bytes();
        assert!(s.step().is_err());
        assert!(s.to_bytes() == before, "a failed step changed the surface");
    };
    let mut loaded = Surface::from_bytes(&s.to_bytes()).unwrap();
    overwhelm(&mut loaded);
    let probe = ball(&s, 0.5, 0.5, [3.0, 0.0, 3.0]);
    s.body_forces(&probe, 1.0 / 60.0).unwrap();
    overwhelm(&mut s);
}
