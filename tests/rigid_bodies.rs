//! Floating bodies as rigid bodies, checked against naval architecture: drafts from
//! displacement, righting and capsizing from the metacentric height, the roll period, and
//! the water's forces for a body another engine owns (`body_forces`).
//!
//! "Water held still" is a surface whose nodes are all pinned: the water stays flat at
//! height 0, so the bodies meet exactly the still water the theory assumes.

use springwater::body::{BoatShape, Hull};
use springwater::glam::{Quat, Vec3};
use springwater::internals::Tuning;
use springwater::{Floater, FloaterId, Params, Shape, Surface};
use std::sync::Arc;

/// A 48 × 48 surface at the defaults whose water does not move.
fn still_water() -> Surface {
    let mut s = Surface::new(Params::with_size(48, 48)).unwrap();
    for node in 0..48 * 48 {
        s.set_pinned(node, true).unwrap();
    }
    s
}

/// The angle in degrees between the body's up axis and the world's.
fn heel(body: &Floater) -> f32 {
    let up = body.orientation * Vec3::Y;
    up.y.clamp(-1.0, 1.0).acos().to_degrees()
}

/// The body's lowest point below its origin, in the body's frame (upright).
fn keel(shape: &Shape) -> f32 {
    match shape {
        Shape::Sphere { radius } => -radius,
        Shape::Box { half_extents } => -half_extents.y,
        Shape::Hull(hull) => hull
            .vertices()
            .iter()
            .map(|v| v[1])
            .fold(f32::MAX, f32::min),
        _ => unreachable!(),
    }
}

/// The draft at which `shape` (upright) displaces `volume`, by bisection on the height of
/// a sphere's cap or a box's bottom, or on the hull's submerged volume in still water.
fn predicted_draft(shape: &Shape, volume: f32) -> f32 {
    let displaced = |draft: f32| -> f32 {
        match shape {
            Shape::Sphere { radius: r } => {
                std::f32::consts::PI * draft * draft * (3.0 * r - draft) / 3.0
            }
            Shape::Box { half_extents: e } => 4.0 * e.x * e.z * draft,
            Shape::Hull(hull) => {
                let y = -keel(shape) - draft;
                let still = springwater::Buoyancy {
                    gravity: 1.0,
                    density: 1.0,
                };
                let mut scratch = springwater::body::HullScratch::new();
                let pose = Vec3::new(0.0, y, 0.0);
                hull.submerged(pose, Quat::IDENTITY, still, |_, _| 0.0, &mut scratch)
                    .unwrap()
                    .volume
            }
            _ => unreachable!(),
        }
    };
    let height = match shape {
        Shape::Hull(hull) => {
            hull.vertices()
                .iter()
                .map(|v| v[1])
                .fold(f32::MIN, f32::max)
                - keel(shape)
        }
        _ => -2.0 * keel(shape),
    };
    let (mut lo, mut hi) = (0.0f32, height);
    for _ in 0..60 {
        let mid = 0.5 * (lo + hi);
        if displaced(mid) < volume {
            lo = mid;
        } else {
            hi = mid;
        }
    }
    0.5 * (lo + hi)
}

/// The shipped boat, its origin moved to its centroid (the centre of mass at uniform
/// density).
fn boat() -> Arc<Hull> {
    Arc::new(BoatShape::default().hull().unwrap().centred().unwrap())
}

fn name(shape: &Shape) -> &'static str {
    match shape {
        Shape::Sphere { .. } => "sphere",
        Shape::Box { .. } => "box",
        _ => "boat",
    }
}

#[test]
fn bodies_settle_at_the_draft_their_displacement_predicts() {
    let shapes = [
        Shape::Box {
            half_extents: Vec3::new(2.0, 1.0, 1.5),
        },
        Shape::Sphere { radius: 2.0 },
        Shape::Hull(boat()),
    ];
    // The small ones meet the water as a plane.
    for shape in shapes.into_iter().chain(small_shapes()) {
        for ratio in [0.25f32, 0.5, 0.75] {
            let mut s = still_water();
            let density = s.buoyancy().density;
            let mass = ratio * density * shape.volume();
            let mut body = Floater::sphere(1.0, mass, [24.0, 0.0, 24.0]);
            body.shape = shape.clone();
            let id = s.add_floater(body).unwrap();
            s.step_n(1500).unwrap();
            let b = s.floater(id).unwrap();
            let weight = mass * s.buoyancy().gravity;
            assert!((b.water_force.y - weight).abs() < 1e-3 * weight);
            if let Shape::Hull(hull) = &shape {
                // A boat trims until its centre of buoyancy is under its centre of mass:
                // its displaced volume is the prediction, and B is under G.
                let mut scratch = springwater::body::HullScratch::new();
                let sub = hull
                    .submerged(
                        b.position,
                        b.orientation,
                        s.buoyancy(),
                        |x, z| s.height_at(x, z).unwrap(),
                        &mut scratch,
                    )
                    .unwrap();
                let want = ratio * shape.volume();
                println!(
                    "boat at {ratio}: displaces {}, predicted {want}",
                    sub.volume
                );
                assert!(
                    (sub.volume - want).abs() < 0.01 * want,
                    "{ratio}: {}",
                    sub.volume
                );
                let off = (sub.centre_of_buoyancy - b.position) * Vec3::new(1.0, 0.0, 1.0);
                assert!(off.length() < 0.01, "{ratio}: B off G by {off}");
                continue;
            }
            let under = s.height_at(b.position.x, b.position.z).unwrap();
            let draft = under - (b.position.y + keel(&shape));
            let want = predicted_draft(&shape, ratio * shape.volume());
            println!(
                "{} at {ratio}: draft {draft}, predicted {want}",
                name(&shape)
            );
            assert!(
                (draft - want).abs() < 0.01 * want,
                "{ratio}: draft {draft} vs {want} ({:?})",
                b.position
            );
            assert!(heel(b) < 0.5, "{ratio}: heeled {}°", heel(b));
        }
    }
}

/// A ball and a box at most one cell from their centre to their farthest point: they meet
/// the water as a plane (the small-body model of `springwater::body`).
fn small_shapes() -> [Shape; 2] {
    [
        Shape::Sphere { radius: 0.8 },
        Shape::Box {
            half_extents: Vec3::new(0.5, 0.3, 0.6),
        },
    ]
}

/// The loads waiting in the water column for the next step (from `body_forces`), one
/// value per node: on a surface whose column carries nothing yet, the whole push.
fn waiting(s: &Surface) -> [Vec<f32>; 3] {
    let mut f = [(); 3].map(|_| vec![0.0; s.node_count()]);
    for (node, carried, pending) in s.water_column() {
        assert_eq!(carried, [0.0; 3]);
        for k in 0..3 {
            f[k][node] = pending[k];
        }
    }
    f
}

#[test]
fn the_water_gets_minus_a_small_bodys_force_and_torque() {
    for shape in small_shapes() {
        assert!(shape.bounding_radius() <= 1.0, "not a small body");
        for drag in [0.0f32, Floater::DEFAULT_DRAG] {
            let mut s = Surface::new(Params::with_size(48, 48)).unwrap();
            let scale2 = s.params().time_scale * s.params().time_scale;
            let mass = 0.4 * s.buoyancy().density * shape.volume();
            let mut body = Floater::sphere(1.0, mass, [20.3, -0.1, 21.7]);
            body.shape = shape.clone();
            body.drag = drag;
            body.orientation = Quat::from_rotation_x(0.3) * Quat::from_rotation_y(0.4);
            body.velocity = Vec3::new(0.5, -0.3, 0.2);
            body.angular_velocity = Vec3::new(0.4, -0.2, 0.3);
            let c = body.position;
            let push = s.body_forces(&body, 1.0 / 60.0).unwrap();
            // What waits in the water column for the next step (nothing is carried yet).
            let [fx, fy, fz] = waiting(&s);
            let (mut force, mut torque) = (Vec3::ZERO, Vec3::ZERO);
            for row in 0..48 {
                for col in 0..48 {
                    let i = row * 48 + col;
                    let f = Vec3::new(fx[i], fy[i], fz[i]) * scale2;
                    force += f;
                    // Still water: the nodes rest at height 0.
                    torque += (Vec3::new(col as f32, 0.0, row as f32) - c).cross(f);
                }
            }
            let size = push.force.length();
            println!(
                "small {} drag {drag}: body {push:?}, water {force} {torque}",
                name(&shape)
            );
            assert!(size > 0.1 * mass * s.buoyancy().gravity);
            assert!(
                (force + push.force).length() < 1e-4 * size,
                "{force} {push:?}"
            );
            if drag == 0.0 {
                // Without drag every force is vertical on still water, so the nodes' height
                // does not matter and the bilinear spread keeps each force's moment.
                let err = (torque + push.torque).length();
                assert!(err < 1e-4 * size, "{torque} {push:?}");
                assert!(push.torque.length() > 1e-3 * size, "no torque to check");
            }
        }
    }
}

#[test]
fn a_box_given_as_a_mesh_floats_and_rocks_like_the_cuboid() {
    let e = Vec3::new(2.0, 0.75, 1.5);
    let mesh = Hull::cuboid(e).unwrap();
    let tilt = Quat::from_rotation_x(10f32.to_radians());
    let mut histories = Vec::new();
    for as_mesh in [false, true] {
        let mut s = still_water();
        let mass = 0.5 * s.buoyancy().density * 8.0 * e.x * e.y * e.z;
        let mut body = if as_mesh {
            Floater::hull(mesh.vertices(), mesh.triangles(), mass, [24.0, 0.0, 24.0]).unwrap()
        } else {
            Floater::cuboid(e, mass, [24.0, 0.0, 24.0])
        };
        body.orientation = tilt;
        let id = s.add_floater(body).unwrap();
        let mut history = Vec::new();
        for _ in 0..600 {
            s.step().unwrap();
            let b = s.floater(id).unwrap();
            history.push((heel(b), b.position.y));
        }
        histories.push(history);
    }
    let worst_heel = histories[0]
        .iter()
        .zip(&histories[1])
        .map(|(a, b)| (a.0 - b.0).abs())
        .fold(0.0f32, f32::max);
    let (end_box, end_mesh) = (histories[0][599].1, histories[1][599].1);
    println!("largest heel difference {worst_heel}°, heights {end_box} and {end_mesh}");
    assert!(worst_heel < 0.2, "{worst_heel}");
    // Draft within 1%: both float half under, e.y − y deep.
    let (draft_box, draft_mesh) = (e.y - end_box, e.y - end_mesh);
    assert!((draft_box - draft_mesh).abs() < 0.01 * draft_box);
    assert!((draft_box - e.y).abs() < 0.01 * e.y, "{draft_box}");
}

#[test]
fn a_wide_barge_heeled_15_degrees_rights_itself() {
    let mut s = still_water();
    let e = Vec3::new(6.0, 0.75, 3.0);
    let mass = 0.5 * s.buoyancy().density * 8.0 * e.x * e.y * e.z;
    let mut barge = Floater::cuboid(e, mass, [24.0, 0.0, 24.0]);
    barge.orientation = Quat::from_rotation_x(15f32.to_radians());
    let id = s.add_floater(barge).unwrap();
    let mut worst_late = 0.0f32;
    for step in 0..1200 {
        s.step().unwrap();
        if step >= 900 {
            worst_late = worst_late.max(heel(s.floater(id).unwrap()));
        }
    }
    println!("heel over the last 300 steps at most {worst_late}°");
    assert!(worst_late < 0.5, "{worst_late}");
}

#[test]
fn a_tall_narrow_box_capsizes_and_stays_on_its_side() {
    let mut s = still_water();
    // Beam 1, height 4, half the water's density: draft 2, KB 1, BM 1/24, KG 2, so
    // GM = 1 + 1/24 − 2 < 0.
    let e = Vec3::new(0.5, 2.0, 0.5);
    let mass = 0.5 * s.buoyancy().density * 8.0 * e.x * e.y * e.z;
    let mut post = Floater::cuboid(e, mass, [24.0, 0.0, 24.0]);
    post.orientation = Quat::from_rotation_z(2f32.to_radians());
    let id = s.add_floater(post).unwrap();
    let mut late = Vec::new();
    for step in 0..1500 {
        s.step().unwrap();
        if step >= 1200 {
            late.push(heel(s.floater(id).unwrap()));
        }
    }
    let (lo, hi) = late
        .iter()
        .fold((f32::MAX, 0.0f32), |(lo, hi), &h| (lo.min(h), hi.max(h)));
    println!("heel over the last 300 steps: {lo}° to {hi}°");
    assert!(lo > 85.0 && hi < 95.0, "{lo} {hi}");
}

/// The roll period of a box (beam 4 along z, height 2, half the water's density) heeled
/// 3° about x, without drag, measured from upward zero crossings of the roll over 2,000
/// steps; and the theory's `2π sqrt(I / (m g GM))`.
fn roll_period(mut s: Surface) -> (f32, f32) {
    // Draft T = 1, KB = T/2, BM = b²/(12 T), KG = 1.
    let e = Vec3::new(3.0, 1.0, 2.0);
    let (b, h, t) = (2.0 * e.z, 2.0 * e.y, 1.0f32);
    let gm = t / 2.0 + b * b / (12.0 * t) - h / 2.0;
    let mass = 0.5 * s.buoyancy().density * 8.0 * e.x * e.y * e.z;
    let inertia = mass * (b * b + h * h) / 12.0;
    let g = s.buoyancy().gravity;
    let theory = 2.0 * std::f32::consts::PI * (inertia / (mass * g * gm)).sqrt();

    let mut body = Floater::cuboid(e, mass, [24.0, 0.0, 24.0]);
    body.drag = 0.0;
    body.orientation = Quat::from_rotation_x(3f32.to_radians());
    let id = s.add_floater(body).unwrap();
    let dt = s.params().dt / s.params().time_scale;
    // Times the roll crosses zero going up, linearly interpolated.
    let mut crossings = Vec::new();
    let roll = |f: &Floater| (f.orientation * Vec3::Y).z;
    let mut before = roll(s.floater(id).unwrap());
    for step in 1..=2000 {
        s.step().unwrap();
        let now = roll(s.floater(id).unwrap());
        if before < 0.0 && now >= 0.0 {
            crossings.push((step as f32 - 1.0 + before / (before - now)) * dt);
        }
        before = now;
    }
    assert!(crossings.len() >= 5, "{crossings:?}");
    let period = (crossings.last().unwrap() - crossings[0]) / (crossings.len() - 1) as f32;
    (period, theory)
}

#[test]
fn the_roll_period_on_still_water_is_the_metacentric_one() {
    let (period, theory) = roll_period(still_water());
    println!("roll period on still water {period} s, theory {theory} s");
    assert!(
        (period - theory).abs() < 0.03 * theory,
        "{period} vs {theory}"
    );
    // On the springy surface, two-way: the water column carries the body's weight, so the
    // membrane under it does not soften the righting moment, and the roll keeps the
    // metacentric period (+0.2% measured; docs/floating.md).
    let (live, _) = roll_period(Surface::new(Params::with_size(48, 48)).unwrap());
    println!(
        "on live water {live} s: {:+.1}%",
        100.0 * (live / period - 1.0)
    );
    assert!((live / period - 1.0).abs() < 0.03, "{live} vs {period}");
}

#[test]
fn a_step_changes_momentum_by_the_forces_and_the_water_gets_minus_the_force() {
    let mut s = Surface::new(Params::with_size(48, 48)).unwrap();
    let e = Vec3::new(2.0, 0.75, 1.5);
    let mass = 0.4 * s.buoyancy().density * 8.0 * e.x * e.y * e.z;
    let mut body = Floater::cuboid(e, mass, [24.0, 0.2, 24.0]);
    body.orientation = Quat::from_rotation_x(0.3) * Quat::from_rotation_y(0.4);
    body.angular_velocity = Vec3::new(0.5, -0.2, 0.3);
    body.velocity = Vec3::new(1.0, -0.5, 0.25);
    let id = s.add_floater(body).unwrap();
    let g = s.buoyancy().gravity;
    let dt = s.params().dt / s.params().time_scale;
    let scale2 = s.params().time_scale * s.params().time_scale;
    for _ in 0..20 {
        let before = s.floater(id).unwrap().clone();
        let inertia = {
            let r = springwater::glam::Mat3::from_quat(before.orientation);
            r * before.inertia_tensor() * r.transpose()
        };
        s.step().unwrap();
        let after = s.floater(id).unwrap().clone();
        let gained = mass * (after.velocity - before.velocity);
        let impulse = dt * (after.water_force - Vec3::new(0.0, mass * g, 0.0));
        assert!(
            (gained - impulse).length() < 1e-4 * (mass * g * dt),
            "{gained} {impulse}"
        );
        let spun = inertia * (after.angular_velocity - before.angular_velocity);
        let twist = dt * after.water_torque;
        assert!(
            (spun - twist).length() < 1e-3 * twist.length().max(1e-3),
            "{spun} {twist}"
        );
    }
    // What the water holds for its next step is minus the body's force of that step.
    let mut s2 = Surface::new(Params::with_size(48, 48)).unwrap();
    let probe = s.floater(id).unwrap().clone();
    let push = s2.body_forces(&probe, dt).unwrap();
    let f = waiting(&s2);
    let sum = Vec3::new(
        f[0].iter().sum::<f32>(),
        f[1].iter().sum::<f32>(),
        f[2].iter().sum::<f32>(),
    ) * scale2;
    assert!(
        (sum + push.force).length() < 1e-4 * push.force.length(),
        "{sum} {}",
        push.force
    );
}

#[test]
fn body_forces_lift_a_half_submerged_box_by_the_weight_of_the_water_it_displaces() {
    let mut s = Surface::new(Params::with_size(48, 48)).unwrap();
    let e = Vec3::new(2.0, 1.0, 1.5);
    let displaced = 4.0 * e.x * e.z * e.y; // half under: the lower half
    let water = s.buoyancy();
    // Heavy, so that the force over the tick is the still-water one.
    let mut body = Floater::cuboid(e, 1e6, [24.0, 0.0, 24.0]);
    body.drag = 0.0;
    let push = s.body_forces(&body, 1.0 / 60.0).unwrap();
    let want = water.density * water.gravity * displaced;
    assert!(
        (push.force.y - want).abs() < 0.02 * want,
        "{} vs {want}",
        push.force.y
    );
    assert!(push.torque.length() < 1e-4 * want);

    // Heeled about x by 10°, the torque turns it back upright (about −x).
    body.orientation = Quat::from_rotation_x(10f32.to_radians());
    let push = s.body_forces(&body, 1.0 / 60.0).unwrap();
    assert!(push.torque.x < 0.0, "{}", push.torque);
    assert!(push.torque.x.abs() > 10.0 * (push.torque.y.abs() + push.torque.z.abs()));
}

#[test]
fn an_explicit_engine_at_60_hz_floats_a_light_box_with_body_forces() {
    // A game engine's step: semi-implicit Euler with the water's force and gravity, the
    // orientation turned by the angular velocity, at 60 Hz; the box is a tenth of the
    // water's density, light enough that explicit buoyancy alone would blow up.
    let mut s = Surface::new(Params::with_size(48, 48)).unwrap();
    let g = s.buoyancy().gravity;
    let e = Vec3::new(1.5, 0.5, 1.0);
    let mass = 0.1 * s.buoyancy().density * 8.0 * e.x * e.y * e.z;
    let mut body = Floater::cuboid(e, mass, [24.0, 1.0, 24.0]);
    body.orientation = Quat::from_rotation_z(0.3);
    let dt = 1.0 / 60.0;
    for _ in 0..600 {
        let push = s.body_forces(&body, dt).unwrap();
        let r = springwater::glam::Mat3::from_quat(body.orientation);
        let inertia = r * body.inertia_tensor() * r.transpose();
        body.velocity += dt * (push.force / mass - Vec3::new(0.0, g, 0.0));
        body.angular_velocity += dt * (inertia.inverse() * push.torque);
        body.position += dt * body.velocity;
        let w = body.angular_velocity;
        let spin = Quat::from_xyzw(w.x, w.y, w.z, 0.0) * body.orientation;
        body.orientation = (body.orientation + spin * (0.5 * dt)).normalize();
        s.advance(dt).unwrap();
        assert!(
            body.position.is_finite() && body.velocity.length() < 100.0,
            "{body:?}"
        );
    }
    let draft = 0.1 * 2.0 * e.y;
    let under = s.height_at(body.position.x, body.position.z).unwrap();
    println!("after 10 s: {body:?}, water under it {under}");
    assert!(body.velocity.length() < 0.05, "{body:?}");
    assert!(heel(&body) < 1.0, "{}", heel(&body));
    assert!((under - (body.position.y - e.y) - draft).abs() < 0.1 * draft);
}

#[test]
fn a_small_box_on_a_long_wave_pitches_in_phase_with_the_slope() {
    // A standing wave 64 cells long along x in a pool (its walls at nodes of the wave);
    // the box sits where the surface tilts most (a node of the height, an antinode of the
    // slope), in the middle across. The box is flat: its own pitch period (about 0.3 s)
    // is far shorter than the wave's (about 1.6 s), so it follows the slope.
    let (cols, rows, wavelength) = (97, 33, 64.0f32);
    let mut s = Surface::new(Params::with_size(cols, rows)).unwrap();
    for r in 0..rows {
        for c in 0..cols {
            let phase = 2.0 * std::f32::consts::PI * c as f32 / wavelength;
            s.add_velocity(r * cols + c, [0.0, 0.15 * phase.sin(), 0.0])
                .unwrap();
        }
    }
    let x = 0.5 * wavelength;
    let e = Vec3::new(0.5, 0.1, 0.5);
    let mass = 0.5 * s.buoyancy().density * 8.0 * e.x * e.y * e.z;
    let id = s
        .add_floater(Floater::cuboid(e, mass, [x, 0.0, 16.0]))
        .unwrap();
    let (mut tilt, mut slope) = (Vec::new(), Vec::new());
    for step in 0..600 {
        s.step().unwrap();
        if step < 100 {
            continue; // the box finds its draft
        }
        let b = s.floater(id).unwrap();
        let (bx, bz) = (b.position.x, b.position.z);
        let dx = s.height_at(bx + 0.5, bz).unwrap() - s.height_at(bx - 0.5, bz).unwrap();
        // The box's up axis leans against the slope: −x when the surface rises along x.
        tilt.push(-(b.orientation * Vec3::Y).x);
        slope.push(dx);
    }
    let mean = |v: &[f32]| v.iter().sum::<f32>() / v.len() as f32;
    let (mt, ms) = (mean(&tilt), mean(&slope));
    let (mut sxy, mut sxx, mut syy) = (0.0f32, 0.0f32, 0.0f32);
    for (a, b) in tilt.iter().zip(&slope) {
        sxy += (a - mt) * (b - ms);
        sxx += (a - mt) * (a - mt);
        syy += (b - ms) * (b - ms);
    }
    let correlation = sxy / (sxx * syy).sqrt();
    let gain = (sxx / syy).sqrt();
    println!("tilt against slope: correlation {correlation}, amplitude ratio {gain}");
    assert!(
        syy.sqrt() / (slope.len() as f32).sqrt() > 0.02,
        "the wave is too weak"
    );
    assert!(correlation > 0.9, "{correlation}");
    assert!((0.5..1.5).contains(&gain), "{gain}");
}

/// Kinetic energy, gravity's potential and the still water's (hydrostatic) potential
/// `−ρ g V y_B` of a body on water held still at height 0.
fn still_energy(s: &Surface, b: &Floater, hull: &Hull) -> f64 {
    let r = springwater::glam::Mat3::from_quat(b.orientation);
    let inertia = r * b.inertia_tensor() * r.transpose();
    let w = b.angular_velocity;
    let kinetic = 0.5 * b.mass * b.velocity.length_squared() + 0.5 * w.dot(inertia * w);
    let water = s.buoyancy();
    let mut scratch = springwater::body::HullScratch::new();
    let sub = hull
        .submerged(b.position, b.orientation, water, |_, _| 0.0, &mut scratch)
        .unwrap();
    let g = water.gravity;
    let buoyancy = -water.density * g * sub.volume * sub.centre_of_buoyancy.y;
    (kinetic + b.mass * g * b.position.y + buoyancy) as f64
}

#[test]
fn with_drag_a_body_on_still_water_never_gains_energy() {
    let mut s = still_water();
    let e = Vec3::new(2.0, 0.75, 1.5);
    let hull = Hull::cuboid(e).unwrap();
    let mass = 0.4 * s.buoyancy().density * 8.0 * e.x * e.y * e.z;
    let mut body = Floater::cuboid(e, mass, [24.0, 1.0, 24.0]);
    body.orientation = Quat::from_rotation_x(0.5) * Quat::from_rotation_z(0.3);
    body.angular_velocity = Vec3::new(0.0, 2.0, 1.0);
    let id = s.add_floater(body).unwrap();
    let start = still_energy(&s, s.floater(id).unwrap(), &hull);
    let mut last = start;
    let mut worst = 0.0f64;
    for _ in 0..600 {
        s.step().unwrap();
        let now = still_energy(&s, s.floater(id).unwrap(), &hull);
        worst = worst.max(now - last);
        last = now;
    }
    println!("energy {start} → {last}, largest rise in a step {worst}");
    assert!(worst <= 1e-4 * start.abs(), "{worst}");
    assert!(last < start);
}

/// The state hash after [`rocking_boats`] (two boats of the shipped hull, one heeled, and a
/// spinning box, on waves from drops): the same on every level, thread count and target.
const GOLDEN_ROCKING: u64 = 0x8b54_396e_1633_8560;

/// Two boats of one shared hull and a box, turned and spinning, rocked by drops for 240
/// steps on `level` and `threads` threads; returns the final state hash and the largest
/// heel any body reached (degrees).
fn rocking_boats(level: springwater::SimdLevel, threads: usize) -> (u64, f32) {
    let mut s = surface_on(40, 32, level, threads);
    let hull = boat();
    let density = s.buoyancy().density;
    let mut ids = Vec::new();
    for (k, at) in [[12.0, 0.0, 10.0], [26.0, 0.0, 20.0]]
        .into_iter()
        .enumerate()
    {
        let mut b = Floater::with_hull(Arc::clone(&hull), 0.4 * density * hull.volume(), at);
        b.orientation = Quat::from_rotation_x(0.2 * k as f32) * Quat::from_rotation_y(0.7);
        ids.push(s.add_floater(b).unwrap());
    }
    let mut crate_ = Floater::cuboid([1.0, 0.5, 0.75], 1.2, [30.0, 0.5, 8.0]);
    crate_.angular_velocity = Vec3::new(0.5, 2.0, -0.3);
    ids.push(s.add_floater(crate_).unwrap());
    rock(&mut s, &ids, 240, 40, 4.5, 16.0)
}

/// A `cols` × `rows` surface stepping at `level` on `threads` threads.
fn surface_on(cols: usize, rows: usize, level: springwater::SimdLevel, threads: usize) -> Surface {
    let mut s = Surface::new(Params::with_size(cols, rows)).unwrap();
    s.set_simd_level(level);
    #[cfg(feature = "parallel")]
    {
        let pool = rayon::ThreadPoolBuilder::new().num_threads(threads);
        s.set_thread_pool(Some(Arc::new(pool.build().unwrap())));
    }
    #[cfg(not(feature = "parallel"))]
    let _ = threads;
    s
}

/// Steps `s` `steps` times with a drop every `every` steps, marching along `z` at
/// `x = 8 + k · stride`; returns the final state hash and the largest heel of `ids`.
fn rock(
    s: &mut Surface,
    ids: &[FloaterId],
    steps: usize,
    every: usize,
    stride: f32,
    z: f32,
) -> (u64, f32) {
    let mut most = 0.0f32;
    for step in 0..steps {
        if step % every == 0 {
            let x = 8.0 + (step / every) as f32 * stride;
            s.drop_at(x, z, 0.5, 3.0).unwrap();
        }
        s.step().unwrap();
        for id in ids {
            most = most.max(heel(s.floater(*id).unwrap()));
        }
    }
    (s.state_hash(), most)
}

/// The golden state hash of [`small_bodies`], the same on every level, thread count and
/// platform.
const GOLDEN_SMALL: u64 = 0x4424_79e1_9d52_2b69;

/// Two balls and two spinning boxes small enough to meet the water as a plane, rocked by
/// drops for 240 steps on `level` and `threads` threads; returns the final state hash and
/// the largest heel any body reached (degrees).
fn small_bodies(level: springwater::SimdLevel, threads: usize) -> (u64, f32) {
    let mut s = surface_on(28, 24, level, threads);
    let mut ids = Vec::new();
    for (k, at) in [
        [8.0, 0.0, 8.0],
        [14.0, 0.0, 14.0],
        [20.0, 0.0, 9.0],
        [11.0, 0.0, 17.0],
    ]
    .into_iter()
    .enumerate()
    {
        let mut b = if k % 2 == 0 {
            Floater::sphere(0.6 + 0.2 * k as f32 / 2.0, 1.0, at)
        } else {
            Floater::cuboid([0.5, 0.3, 0.6], 1.0, at)
        };
        b.mass = 0.5 * s.buoyancy().density * b.shape.volume();
        b.orientation = Quat::from_rotation_z(0.3 * k as f32);
        b.angular_velocity = Vec3::new(0.4, 1.5, -0.2 * k as f32);
        ids.push(s.add_floater(b).unwrap());
    }
    rock(&mut s, &ids, 240, 30, 2.5, 12.0)
}

/// Runs `scene` on the scalar reference, checks that its bodies rocked (over 5°), that every
/// level on 1 and 2 threads gives the same state hash, and that the hash is `golden`.
fn same_bits_everywhere(
    name: &str,
    scene: fn(springwater::SimdLevel, usize) -> (u64, f32),
    golden: u64,
) {
    let (reference, most) = scene(springwater::SimdLevel::Scalar, 1);
    println!("{name}: hash {reference:#018x}, largest heel {most}°");
    assert!(most > 5.0, "the bodies hardly rocked: {most}°");
    for level in springwater::SimdLevel::ALL {
        for threads in [1, 2] {
            let (hash, _) = scene(level, threads);
            assert_eq!(hash, reference, "{level} on {threads} threads");
        }
    }
    assert_eq!(reference, golden, "{reference:#018x}");
}

#[test]
fn small_bodies_give_the_same_bits_on_every_level_and_thread_count() {
    same_bits_everywhere("small bodies", small_bodies, GOLDEN_SMALL);
}

#[test]
fn rocking_boats_give_the_same_bits_on_every_level_and_thread_count() {
    same_bits_everywhere("rocking boats", rocking_boats, GOLDEN_ROCKING);
}

#[test]
fn bad_rigid_bodies_are_refused_with_one_clear_error_and_change_nothing() {
    use springwater::glam::Mat3;
    let mut s = Surface::new(Params::with_size(32, 32)).unwrap();
    let good = Floater::cuboid([1.0, 0.5, 1.0], 2.0, [16.0, 0.0, 16.0]);
    let id = s.add_floater(good.clone()).unwrap();
    let before = s.to_bytes();
    let edited = |f: fn(&mut Floater)| {
        let mut b = good.clone();
        f(&mut b);
        b
    };
    let bad = [
        edited(|b| b.orientation = Quat::from_xyzw(f32::NAN, 0.0, 0.0, 1.0)),
        edited(|b| b.orientation = Quat::from_xyzw(0.0, 0.0, 0.0, 2.0)),
        edited(|b| b.angular_velocity = Vec3::new(0.0, f32::INFINITY, 0.0)),
        edited(|b| b.angular_velocity = Vec3::new(0.0, 2e6, 0.0)),
        edited(|b| b.push_torque = Vec3::new(f32::NAN, 0.0, 0.0)),
        edited(|b| b.mass = 0.0),
        edited(|b| b.mass = -1.0),
        edited(|b| b.inertia = Some(Mat3::ZERO)),
        edited(|b| b.inertia = Some(Mat3::from_diagonal(Vec3::new(1.0, 1.0, 3.0)))),
        edited(|b| {
            b.inertia = Some(Mat3::from_cols_array(&[
                1.0, 0.5, 0.0, 0.0, 1.0, 0.0, 0.0, 0.0, 1.0,
            ]))
        }),
        edited(|b| b.inertia = Some(Mat3::from_diagonal(Vec3::new(1.0, f32::NAN, 1.0)))),
    ];
    for body in bad {
        let message = s.add_floater(body.clone()).unwrap_err().to_string();
        assert!(!message.contains('\n') && !message.is_empty(), "{message}");
        assert!(s.set_floater(id, body.clone()).is_err());
        assert!(s.body_forces(&body, 1.0 / 60.0).is_err());
        println!("refused: {message}");
    }
    assert_eq!(s.to_bytes(), before, "nothing changed");
    assert_eq!(s.floaters().len(), 1);

    // Meshes: open (a box missing a face) and inside out.
    let cube = Hull::cuboid([1.0, 1.0, 1.0]).unwrap();
    let open = &cube.triangles()[..10];
    let err = Floater::hull(cube.vertices(), open, 1.0, [16.0, 0.0, 16.0]).unwrap_err();
    println!("open mesh: {err}");
    assert!(
        err.to_string().contains("closed") || err.to_string().contains("edge"),
        "{err}"
    );
    let inside_out: Vec<[u32; 3]> = cube
        .triangles()
        .iter()
        .map(|&[a, b, c]| [a, c, b])
        .collect();
    let err = Floater::hull(cube.vertices(), &inside_out, 1.0, [16.0, 0.0, 16.0]).unwrap_err();
    println!("inside out: {err}");
    assert!(err.to_string().contains("inside out"), "{err}");
}
