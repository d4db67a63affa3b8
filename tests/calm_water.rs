//! Bodies on calm water stay calm: a body resting at its draft does not set off by
//! itself, two bodies a few cells apart do not pull together, a stable box heeled on the
//! live, springy pool rights itself, and a symmetric body on still water gets no side force
//! and no torque. The water column (the bodies' subsystem) carries a body's steady weight
//! to the bottom; what changes still reaches the water: a body towed across still water
//! leaves a wake whose energy is measured here.

use springwater::body::{BoatShape, Hull};
use springwater::glam::{Quat, Vec3};
use springwater::{Floater, FloaterId, Params, Surface};
use std::sync::Arc;

/// The calm 65 × 65 pool of the seed's defaults.
fn pool() -> Surface {
    Surface::new(Params::with_size(65, 65)).unwrap()
}

/// The angle in degrees by which `b`'s orientation differs from `a`'s.
fn turned(a: Quat, b: Quat) -> f32 {
    let d = (a.inverse() * b).normalize();
    2.0 * d.w.abs().min(1.0).acos().to_degrees()
}

/// The angle in degrees between the body's up axis and the world's.
fn heel(body: &Floater) -> f32 {
    let up = body.orientation * Vec3::Y;
    up.y.clamp(-1.0, 1.0).acos().to_degrees()
}

/// `body` with the mass of `relative` times the water it would displace whole (the default
/// water density).
fn at_density(relative: f32, mut body: Floater) -> Floater {
    body.mass = relative * springwater::Buoyancy::default().density * body.shape.volume();
    body
}

/// The shipped boat, its origin at its centroid.
fn boat() -> Arc<Hull> {
    Arc::new(BoatShape::default().hull().unwrap().centred().unwrap())
}

/// `body` on the calm pool: settles 2,000 steps, then returns how far it drifted (cells,
/// horizontally) and turned (degrees) over 6,000 more.
fn drift(body: Floater) -> (f32, f32) {
    let mut s = pool();
    let id = s.add_floater(body).unwrap();
    s.step_n(2000).unwrap();
    let before = s.floater(id).unwrap().clone();
    s.step_n(6000).unwrap();
    let after = s.floater(id).unwrap();
    let moved = (after.position - before.position) * Vec3::new(1.0, 0.0, 1.0);
    (
        moved.length(),
        turned(before.orientation, after.orientation),
    )
}

#[test]
fn bodies_at_rest_on_calm_water_stay_where_they_are() {
    let ball = Floater::sphere(2.0, 1.0, [32.0, 0.0, 32.0]);
    let cube = |at| Floater::cuboid([1.0, 1.0, 1.0], 1.0, at);
    let cases = [
        ("light ball of radius 2", ball.clone()),
        ("ball of radius 2, half density", at_density(0.5, ball)),
        // (A cube between 0.21 and 0.79 of the water's density has GM < 0: upright is
        // not its equilibrium pose, and it rolls over, as it should.)
        (
            "cube of side 2, 0.15 of the density",
            at_density(0.15, cube([32.0, 0.0, 32.0])),
        ),
        (
            "cube of side 2 off the centre, 0.85 of the density",
            at_density(0.85, cube([20.3, 0.0, 41.6])),
        ),
        (
            "the shipped boat",
            at_density(0.5, Floater::with_hull(boat(), 1.0, [32.0, 0.0, 32.0])),
        ),
    ];
    for (name, body) in cases {
        let (moved, turn) = drift(body);
        println!("{name}: drifted {moved:.2e} cells, turned {turn:.2e} degrees");
        assert!(moved < 0.01, "{name} drifted {moved} cells");
        assert!(turn < 0.1, "{name} turned {turn} degrees");
    }
}

#[test]
fn two_balls_a_few_cells_apart_do_not_pull_together() {
    let mut s = pool();
    let ball = |at| at_density(0.5, Floater::sphere(1.5, 1.0, at));
    let a = s.add_floater(ball([29.0, 0.0, 32.0])).unwrap();
    let b = s.add_floater(ball([35.0, 0.0, 32.0])).unwrap();
    let apart =
        |s: &Surface| (s.floater(a).unwrap().position - s.floater(b).unwrap().position).length();
    s.step_n(2000).unwrap();
    let before = apart(&s);
    s.step_n(6000).unwrap();
    let change = (apart(&s) - before).abs();
    println!("two balls 6 cells apart: distance {before} changed by {change:.2e}");
    assert!(change < 0.01, "distance changed by {change}");
}

#[test]
fn a_box_heeled_10_degrees_rights_itself_on_the_live_pool() {
    let mut s = pool();
    // A wide, flat box of half the water's density: GM > 0.
    let mut raft = at_density(
        0.5,
        Floater::cuboid([3.0, 0.5, 2.0], 1.0, [32.0, 0.0, 32.0]),
    );
    raft.orientation = Quat::from_rotation_x(10f32.to_radians());
    let id = s.add_floater(raft).unwrap();
    s.step_n(3000).unwrap();
    let left = heel(s.floater(id).unwrap());
    println!("heeled 10 degrees on the live pool: {left:.3} degrees after 3,000 steps");
    assert!(left < 0.5, "still heeled {left} degrees");
}

/// The side force and torque the water gives `body` on still water, from the built-in
/// step (`Floater::water_force`, `water_torque` after one step) and from `body_forces`.
fn side_forces(body: &Floater) -> [(Vec3, Vec3); 2] {
    let mut s = pool();
    let pushed = s.body_forces(body, 1.0 / 60.0).unwrap();
    let mut s = pool();
    let id = s.add_floater(body.clone()).unwrap();
    s.step().unwrap();
    let b = s.floater(id).unwrap();
    [
        (pushed.force, pushed.torque),
        (b.water_force, b.water_torque),
    ]
}

#[test]
fn symmetric_bodies_on_still_water_get_no_side_force_and_no_torque() {
    let hull = boat();
    let boat_mass = 0.5 * hull.volume();
    for at in [[32.0, 32.0], [32.5, 32.5]] {
        let p = |y: f32| Vec3::new(at[0], y, at[1]);
        let bodies = [
            ("ball", Floater::sphere(2.0, 10.0, p(0.0)), true),
            ("small ball", Floater::sphere(0.8, 0.5, p(0.0)), true),
            ("cube", Floater::cuboid([1.0, 1.0, 1.0], 1.0, p(0.0)), true),
            ("box", Floater::cuboid([2.5, 0.75, 1.5], 5.0, p(0.2)), true),
            (
                "small box",
                Floater::cuboid([0.5, 0.3, 0.6], 0.2, p(0.0)),
                true,
            ),
            // The boat is mirror-symmetric across its keel plane (z = 0) only.
            (
                "boat",
                Floater::with_hull(hull.clone(), boat_mass, p(0.0)),
                false,
            ),
        ];
        for (name, body, both) in bodies {
            for (how, (force, torque)) in ["body_forces", "built-in step"]
                .into_iter()
                .zip(side_forces(&body))
            {
                let scale = force.y.abs().max(1.0);
                let what = format!("{name} at {at:?}, {how}: force {force}, torque {torque}");
                // Mirrored across z = 0: no force along z, no torque about x or y.
                assert!(force.z.abs() <= 1e-5 * scale, "{what}");
                assert!(torque.x.abs() <= 1e-5 * scale, "{what}");
                assert!(torque.y.abs() <= 1e-5 * scale, "{what}");
                if both {
                    // And across x = 0: no force along x, no torque about z.
                    assert!(force.x.abs() <= 1e-5 * scale, "{what}");
                    assert!(torque.z.abs() <= 1e-5 * scale, "{what}");
                }
            }
        }
    }
}

/// The water's kinetic energy before and after a ball of radius 1.5 at half density,
/// settled on the calm pool, is towed at `speed` world units per second for `steps` steps.
fn wake_energy(speed: f32, steps: u64) -> (f64, f64) {
    let mut s = pool();
    let ball = at_density(0.5, Floater::sphere(1.5, 1.0, [12.0, 0.0, 32.0]));
    let id = s.add_floater(ball).unwrap();
    s.step_n(2000).unwrap();
    let settled = s.energy().kinetic;
    for _ in 0..steps {
        let mut b = s.floater(id).unwrap().clone();
        b.velocity.x = speed;
        s.set_floater(id, b).unwrap();
        s.step().unwrap();
    }
    (settled, s.energy().kinetic)
}

#[test]
fn a_body_towed_across_still_water_leaves_a_wake() {
    // Four seconds at 8 units per second: from x = 12 to x = 44.
    let (settled, towed) = wake_energy(8.0, 240);
    println!("wake: the water's kinetic energy {settled:.3e} settled, {towed:.3e} after the tow");
    // Settled, the water is nearly still; the towed ball leaves waves.
    assert!(towed > 10.0 * settled, "no wake: {towed} against {settled}");
}

#[test]
fn a_body_resting_on_still_water_leaves_it_flat() {
    let mut s = pool();
    let raft = at_density(
        0.5,
        Floater::cuboid([3.0, 0.5, 2.0], 1.0, [32.0, 0.0, 32.0]),
    );
    let id: FloaterId = s.add_floater(raft).unwrap();
    s.step_n(3000).unwrap();
    let deepest = s.positions()[1].iter().fold(0.0f32, |m, y| m.max(y.abs()));
    let b = s.floater(id).unwrap();
    println!(
        "a raft at rest: the water's largest height {deepest:.2e}, draft {}",
        -b.position.y + 0.5
    );
    // Without the column the raft's weight dents the membrane (by 0.055 when measured).
    assert!(deepest < 1e-3, "the water is dented by {deepest}");
}

/// The boat's speed after coasting `steps` steps on still water from 4 units per second
/// along `heading` (the boat's length is along x).
fn coast(heading: Vec3, steps: u64) -> f32 {
    let mut s = Surface::new(Params::with_size(96, 96)).unwrap();
    for node in 0..96 * 96 {
        s.set_pinned(node, true).unwrap();
    }
    let boat = at_density(0.5, Floater::with_hull(boat(), 1.0, [48.0, 0.0, 48.0]));
    let id = s.add_floater(boat).unwrap();
    s.step_n(600).unwrap();
    let mut b = s.floater(id).unwrap().clone();
    b.velocity = heading * 4.0;
    s.set_floater(id, b).unwrap();
    s.step_n(steps).unwrap();
    let v = s.floater(id).unwrap().velocity;
    Vec3::new(v.x, 0.0, v.z).length()
}

#[test]
fn a_boat_has_a_keel_it_coasts_forward_longer_than_sideways() {
    let (ahead, abeam) = (coast(Vec3::X, 30), coast(Vec3::Z, 30));
    println!("after half a second from 4 units/s: forward {ahead:.3}, sideways {abeam:.3}");
    assert!(ahead > 2.0 * abeam, "forward {ahead}, sideways {abeam}");
}
