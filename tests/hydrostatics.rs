//! The submerged part of a hull against theory: Archimedes at every heel and draft
//! (checked against an independent clipper), the torque of the buoyancy, the waterplane,
//! the metacentric height of a box, righting and capsizing, water surfaces that slope,
//! bad poses, and one fingerprint of the bits that every platform must reproduce.

mod hull_meshes;

use hull_meshes::{clip_convex, sphere_mesh, world_triangles};
use springwater::body::{BoatShape, Hull, HullScratch, Submerged};
use springwater::glam::{DVec3, Quat, Vec3};
use springwater::{Buoyancy, Error};

const WATER: Buoyancy = Buoyancy {
    gravity: 9.81,
    density: 1.3,
};

fn rho_g() -> f64 {
    WATER.density as f64 * WATER.gravity as f64
}

fn flat(hull: &Hull, position: Vec3, orientation: Quat, level: f32) -> Submerged {
    hull.submerged(
        position,
        orientation,
        WATER,
        |_, _| level,
        &mut HullScratch::new(),
    )
    .unwrap()
}

/// `|got − want| ≤ tol · scale`, per component.
fn near(got: Vec3, want: DVec3, tol: f64, scale: f64) -> bool {
    (got.as_dvec3() - want).abs().max_element() <= tol * scale
}

/// Poses over many axes, angles and drafts, for a body of `radius` around its origin.
fn poses(radius: f32) -> Vec<(Vec3, Quat)> {
    let mut out = Vec::new();
    for i in 0..24 {
        let f = i as f32;
        let axis = Vec3::new(
            (f * 0.7).sin(),
            0.3 + (f * 1.3).cos().abs(),
            (f * 0.4).cos(),
        );
        let angle = 0.05 + f * 0.27;
        let q = Quat::from_axis_angle(axis.normalize(), angle);
        for k in 0..9 {
            let y = radius * (1.2 - 0.3 * k as f32);
            out.push((Vec3::new(0.3 * f, y, -0.2 * f), q));
        }
    }
    out
}

/// Checks a hull's submerged part in flat water at many poses against `clip_convex`.
fn archimedes_holds(hull: &Hull, radius: f32) {
    let level = 0.0;
    let scale = radius as f64;
    let volume_scale = hull.volume() as f64;
    let mut partial = 0;
    for (p, q) in poses(radius) {
        let sub = flat(hull, p, q, level);
        let tris = world_triangles(hull, p, q);
        let (volume, centre) = clip_convex(&tris, |r| level as f64 - r.y);
        let context = format!("pose {p} {q}: {sub:?}, clipped volume {volume} centre {centre}");
        // F = ρ g V, straight up.
        assert!(
            (sub.volume as f64 - volume).abs() <= 1e-6 * volume_scale,
            "{context}"
        );
        let lift = rho_g() * volume;
        assert!(
            near(
                sub.force,
                DVec3::new(0.0, lift, 0.0),
                1e-6,
                rho_g() * volume_scale
            ),
            "{context}"
        );
        if volume > 1e-6 * volume_scale {
            partial += 1;
            assert!(
                near(sub.centre_of_buoyancy, centre, 1e-5, scale),
                "{context}"
            );
            // The torque about the body's origin is that of the lift at the centre.
            let arm = centre - p.as_dvec3();
            let torque = arm.cross(DVec3::new(0.0, lift, 0.0));
            assert!(near(sub.torque, torque, 1e-5, lift * scale), "{context}");
        }
    }
    assert!(partial > 100, "most poses are partly submerged: {partial}");
}

#[test]
fn a_box_at_any_heel_and_draft_displaces_its_submerged_volume() {
    let hull = Hull::cuboid([1.5, 0.5, 0.8]).unwrap();
    archimedes_holds(&hull, 1.8);
}

#[test]
fn a_sphere_mesh_at_any_heel_and_draft_displaces_its_submerged_volume() {
    let (v, t) = sphere_mesh(1.0, 3);
    let hull = Hull::new(&v, &t).unwrap();
    archimedes_holds(&hull, 1.0);
}

#[test]
fn dry_and_wholly_submerged_hulls() {
    let hull = BoatShape::default().hull().unwrap();
    let q = Quat::from_rotation_z(0.3);
    let dry = flat(&hull, Vec3::new(1.0, 5.0, 2.0), q, 0.0);
    assert_eq!(dry.volume, 0.0);
    assert_eq!(dry.force, Vec3::ZERO);
    assert_eq!(dry.torque, Vec3::ZERO);
    assert_eq!(dry.centre_of_buoyancy, Vec3::new(1.0, 5.0, 2.0));
    assert_eq!(dry.waterplane.area, 0.0);

    let position = Vec3::new(1.0, -5.0, 2.0);
    let under = flat(&hull, position, q, 0.0);
    let v = hull.volume() as f64;
    assert!((under.volume as f64 / v - 1.0).abs() < 1e-6);
    assert!(near(
        under.force,
        DVec3::new(0.0, rho_g() * v, 0.0),
        1e-6,
        rho_g() * v
    ));
    let centroid = position + q * hull.centroid();
    assert!(near(
        under.centre_of_buoyancy,
        centroid.as_dvec3(),
        1e-5,
        1.0
    ));
    assert_eq!(under.waterplane.area, 0.0);
}

#[test]
fn the_parts_add_up_to_the_force_and_torque() {
    let hull = BoatShape::default().hull().unwrap();
    let position = Vec3::new(3.0, -0.3, -1.0);
    let q = Quat::from_euler(springwater::glam::EulerRot::XYZ, 0.3, 0.5, -0.2);
    let wave = |x: f32, z: f32| 0.2 * (0.8 * x).sin() + 0.1 * (1.3 * z).cos();
    let mut scratch = HullScratch::new();
    let (mut force, mut torque, mut count) = (DVec3::ZERO, DVec3::ZERO, 0);
    let sub = hull
        .submerged_parts(position, q, WATER, wave, &mut scratch, |point, f| {
            let f = f.as_dvec3();
            force += f;
            torque += (point - position).as_dvec3().cross(f);
            count += 1;
        })
        .unwrap();
    assert!(count > 100);
    let scale = sub.force.length() as f64;
    assert!(
        near(sub.force, force, 1e-6, scale),
        "{} vs {force}",
        sub.force
    );
    assert!(
        near(sub.torque, torque, 1e-5, scale),
        "{} vs {torque}",
        sub.torque
    );
    // The same again, with the scratch reused: the same bits.
    let again = hull
        .submerged(position, q, WATER, wave, &mut scratch)
        .unwrap();
    assert_eq!(again, sub);
}

#[test]
fn a_sloping_water_plane_pushes_along_its_normal() {
    // η = a x + b z + c: the pressure ρ g (η − y) grows along (a, −1, b), so the force is
    // ρ g V (−a, 1, −b) with V the volume under the sloping plane (divergence theorem).
    let (v, t) = sphere_mesh(1.0, 3);
    let sphere = Hull::new(&v, &t).unwrap();
    let cube = Hull::cuboid([0.7, 0.4, 1.1]).unwrap();
    let (a, b, c) = (0.15f32, -0.1f32, 0.2f32);
    for hull in [sphere, cube] {
        for (p, q) in poses(1.3).into_iter().step_by(5) {
            let sub = hull
                .submerged(
                    p,
                    q,
                    WATER,
                    |x, z| a * x + b * z + c,
                    &mut HullScratch::new(),
                )
                .unwrap();
            let tris = world_triangles(&hull, p, q);
            let plane = |r: DVec3| a as f64 * r.x + b as f64 * r.z + c as f64 - r.y;
            let (volume, centre) = clip_convex(&tris, plane);
            let want = DVec3::new(-(a as f64), 1.0, -(b as f64)) * (rho_g() * volume);
            let scale = rho_g() * hull.volume() as f64;
            assert!(
                near(sub.force, want, 2e-6, scale),
                "{} vs {want}",
                sub.force
            );
            assert!((sub.volume as f64 - volume).abs() < 1e-6 * hull.volume() as f64);
            if volume > 1e-3 {
                assert!(near(sub.centre_of_buoyancy, centre, 1e-5, 1.0));
            }
        }
    }
}

/// The height of the body's origin at which the hull displaces `volume` in flat water at
/// 0, for an orientation (bisection: the displacement grows as the body sinks).
fn equilibrium(hull: &Hull, q: Quat, volume: f64) -> f32 {
    let (mut lo, mut hi) = (-10.0f32, 10.0f32);
    for _ in 0..60 {
        let mid = 0.5 * (lo + hi);
        if (flat(hull, Vec3::new(0.0, mid, 0.0), q, 0.0).volume as f64) > volume {
            lo = mid;
        } else {
            hi = mid;
        }
    }
    0.5 * (lo + hi)
}

#[test]
fn a_boxs_metacentric_height_is_the_closed_forms() {
    // A box 4 long (x), 3 wide (z), 2 deep (y), centred on its origin, at draft T.
    let (length, beam, depth) = (4.0f64, 3.0f64, 2.0f64);
    let hull = Hull::cuboid([2.0, 1.0, 1.5]).unwrap();
    for draft in [0.3f64, 0.8, 1.0, 1.7] {
        let keel = -depth / 2.0;
        let sub = flat(&hull, Vec3::ZERO, Quat::IDENTITY, (keel + draft) as f32);
        let volume = length * beam * draft;
        assert!((sub.volume as f64 - volume).abs() < 1e-5 * volume);
        let wp = sub.waterplane;
        assert!((wp.area as f64 - length * beam).abs() < 1e-5);
        assert!(wp.centre.abs().max_element() < 1e-6);
        // Rolling about the length (x): I = L B³ / 12; pitching about z: B L³ / 12.
        let i_roll = wp.second_moment_about(Vec3::X) as f64;
        let i_pitch = wp.second_moment_about(Vec3::Z) as f64;
        assert!((i_roll / (length * beam.powi(3) / 12.0) - 1.0).abs() < 1e-5);
        assert!((i_pitch / (beam * length.powi(3) / 12.0) - 1.0).abs() < 1e-5);
        // Diagonal axes: the rotated second moment (product of inertia zero by symmetry).
        let diagonal = wp.second_moment_about(Vec3::new(1.0, 0.0, 1.0)) as f64;
        assert!((diagonal / (0.5 * (i_roll + i_pitch)) - 1.0).abs() < 1e-5);
        let kb = sub.centre_of_buoyancy.y as f64 - keel;
        let bm = i_roll / sub.volume as f64;
        let kg = -keel; // uniform density: G at the centre
        let gm = kb + bm - kg;
        let closed = draft / 2.0 + beam * beam / (12.0 * draft) - depth / 2.0;
        assert!(
            (gm - closed).abs() < 1e-5,
            "draft {draft}: GM {gm} vs {closed}"
        );
    }
}

/// The righting arm `GZ` of a box heeled by `phi` about x at its equilibrium draft for
/// `fill` (its density over the water's): the torque about G over the weight, positive
/// when it rights the box.
fn righting_arm(hull: &Hull, fill: f64, phi: f32) -> (f64, Submerged) {
    let q = Quat::from_rotation_x(phi);
    let volume = fill * hull.volume() as f64;
    let y = equilibrium(hull, q, volume);
    let sub = flat(hull, Vec3::new(0.0, y, 0.0), q, 0.0);
    (-(sub.torque.x as f64) / (rho_g() * volume), sub)
}

#[test]
fn a_heeled_box_has_the_wall_sided_righting_arm() {
    // Wall-sided formula: GZ = sin φ (GM + BM tan² φ / 2) while neither the deck edge nor
    // the bilge leaves the sides.
    let (beam, depth) = (3.0f64, 1.0f64);
    let hull = Hull::cuboid([2.0, 0.5, 1.5]).unwrap();
    let fill = 0.5;
    let draft = fill * depth;
    let bm = beam * beam / (12.0 * draft);
    let gm = draft / 2.0 + bm - depth / 2.0;
    for degrees in [2.0f32, 5.0, 10.0, 15.0] {
        let phi = degrees.to_radians();
        let (gz, sub) = righting_arm(&hull, fill, phi);
        let (s, t) = ((phi as f64).sin(), (phi as f64).tan());
        let want = s * (gm + 0.5 * bm * t * t);
        assert!(
            (gz - want).abs() < 1e-4 * want.abs().max(0.01),
            "{degrees}°: GZ {gz} vs {want}"
        );
        assert!(
            sub.torque.y.abs() < 1e-4 && sub.torque.z.abs() < 1e-4,
            "{}",
            sub.torque
        );
    }
}

#[test]
fn a_wide_barge_rights_itself_and_a_tall_box_capsizes() {
    // GM of a uniform box at half the water's density: B² / (6 D) − D / 4.
    let barge = Hull::cuboid([3.0, 0.5, 2.0]).unwrap(); // beam 4, depth 1: GM = 2.42
    let tower = Hull::cuboid([0.5, 1.5, 0.5]).unwrap(); // beam 1, depth 3: GM = −0.69
    for degrees in [2.0f32, 15.0, 30.0] {
        let (gz, _) = righting_arm(&barge, 0.5, degrees.to_radians());
        assert!(gz > 0.0, "the barge at {degrees}° rights itself: GZ {gz}");
        let (gz, _) = righting_arm(&barge, 0.5, -degrees.to_radians());
        assert!(gz < 0.0, "and the other way: GZ {gz}");
        let (gz, _) = righting_arm(&tower, 0.5, degrees.to_radians());
        assert!(gz < 0.0, "the tall box at {degrees}° goes on over: GZ {gz}");
    }
    // Small angles: GZ ≈ GM sin φ.
    let phi = 0.5f32.to_radians();
    for (hull, beam, depth) in [(&barge, 4.0f64, 1.0f64), (&tower, 1.0, 3.0)] {
        let gm = beam * beam / (6.0 * depth) - depth / 4.0;
        let (gz, _) = righting_arm(hull, 0.5, phi);
        assert!(
            (gz / ((phi as f64).sin() * gm) - 1.0).abs() < 1e-3,
            "{gz} vs GM {gm}"
        );
    }
}

#[test]
fn the_boat_floats_upright_and_stable() {
    let boat = BoatShape::default().hull().unwrap().centred().unwrap();
    let fill = 0.35;
    let volume = fill * boat.volume() as f64;
    let y = equilibrium(&boat, Quat::IDENTITY, volume);
    let sub = flat(&boat, Vec3::new(0.0, y, 0.0), Quat::IDENTITY, 0.0);
    // Upright it floats level in roll (symmetric) with its centre of buoyancy below G.
    assert!(
        sub.torque.x.abs() < 1e-4 * (rho_g() * volume) as f32,
        "{}",
        sub.torque
    );
    assert!(sub.centre_of_buoyancy.y < y);
    let gm = sub.centre_of_buoyancy.y as f64 - y as f64
        + sub.waterplane.second_moment_about(Vec3::X) as f64 / sub.volume as f64;
    assert!(gm > 0.1, "GM {gm}");
    for degrees in [5.0f32, 20.0] {
        let (gz, _) = righting_arm(&boat, fill, degrees.to_radians());
        assert!(gz > 0.0, "{degrees}°: {gz}");
    }
}

#[test]
fn bad_poses_and_water_are_refused() {
    let hull = Hull::cuboid([1.0, 1.0, 1.0]).unwrap();
    let mut scratch = HullScratch::new();
    let mut run = |p: Vec3, q: Quat, eta: f32, water: Buoyancy| {
        hull.submerged(p, q, water, |_, _| eta, &mut scratch)
    };
    let name = |r: Result<Submerged, Error>| match r {
        Err(Error::InvalidParam { name, .. }) => name,
        other => panic!("expected a refusal, got {other:?}"),
    };
    let q = Quat::IDENTITY;
    assert_eq!(
        name(run(Vec3::new(f32::NAN, 0.0, 0.0), q, 0.0, WATER)),
        "body position"
    );
    let zero = Quat::from_xyzw(0.0, 0.0, 0.0, 0.0);
    assert_eq!(
        name(run(Vec3::ZERO, zero, 0.0, WATER)),
        "body orientation's squared norm"
    );
    let long = Quat::from_xyzw(0.0, 0.0, 0.0, 1.01);
    assert_eq!(
        name(run(Vec3::ZERO, long, 0.0, WATER)),
        "body orientation's squared norm"
    );
    let nan = Quat::from_xyzw(f32::NAN, 0.0, 0.0, 1.0);
    assert_eq!(name(run(Vec3::ZERO, nan, 0.0, WATER)), "body orientation");
    assert_eq!(name(run(Vec3::ZERO, q, f32::NAN, WATER)), "water height");
    assert_eq!(name(run(Vec3::ZERO, q, 2e9, WATER)), "water height");
    let bad = Buoyancy {
        gravity: -1.0,
        density: 1.0,
    };
    assert_eq!(name(run(Vec3::ZERO, q, 0.0, bad)), "gravity");
    // A quaternion a little off unit length is still a rotation: the same result.
    let tilt = Quat::from_rotation_x(0.3);
    let off = Quat::from_vec4(tilt.to_array().map(|c| c * 1.0004).into());
    let (a, b) = (
        run(Vec3::ZERO, tilt, 0.2, WATER),
        run(Vec3::ZERO, off, 0.2, WATER),
    );
    let (a, b) = (a.unwrap(), b.unwrap());
    assert!((a.force - b.force).abs().max_element() < 1e-5 * a.force.y);
}

/// FNV-1a over the bits of `values`.
fn fold(hash: u64, values: &[f32]) -> u64 {
    values.iter().fold(hash, |h, v| {
        v.to_bits().to_le_bytes().iter().fold(h, |h, &byte| {
            (h ^ byte as u64).wrapping_mul(0x0100_0000_01b3)
        })
    })
}

/// Everything `submerged` returns, in a fixed order.
fn bits(sub: &Submerged) -> Vec<f32> {
    let w = sub.waterplane;
    let mut v = vec![sub.volume, w.area, w.centre.x, w.centre.y];
    v.extend(sub.centre_of_buoyancy.to_array());
    v.extend(sub.force.to_array());
    v.extend(sub.torque.to_array());
    v.extend(w.second_moments);
    v
}

/// The golden fingerprint: the boat's mass properties and its submerged part in several
/// poses on a wavy surface given by a polynomial (no libm), the same bits on every
/// platform. A changed value means the arithmetic changed: if on purpose, update it.
#[test]
fn the_same_bits_on_every_platform() {
    let boat = BoatShape::default().hull().unwrap().centred().unwrap();
    let mut hash = 0xcbf2_9ce4_8422_2325u64;
    let mut mass = vec![boat.volume()];
    mass.extend(boat.centroid().to_array());
    mass.extend(boat.inertia(123.0).to_cols_array());
    hash = fold(hash, &mass);
    let wave = |x: f32, z: f32| 0.05 * x - 0.03 * z + 0.01 * x * z - 0.002 * x * x * x;
    let mut scratch = HullScratch::new();
    // Unit quaternions from integer quadruples whose squares sum to a square (glam's
    // `normalize` may take a SIMD path whose sums are ordered differently).
    let turns = [
        [0, 0, 0, 1, 1],
        [1, 1, 1, 1, 2],
        [1, 2, 2, 4, 5],
        [-2, 4, 5, 6, 9],
        [2, -3, 6, 0, 7],
        [1, 2, -4, 10, 11],
        [2, 6, 9, 0, 11],
        [-1, -2, 2, 4, 5],
    ];
    for (k, [x, y, z, w, n]) in turns.into_iter().enumerate() {
        let f = k as f32;
        let n = n as f32;
        let q = Quat::from_xyzw(x as f32 / n, y as f32 / n, z as f32 / n, w as f32 / n);
        let p = Vec3::new(0.5 * f - 2.0, 0.3 - 0.1 * f, 0.25 * f);
        let sub = boat.submerged(p, q, WATER, wave, &mut scratch).unwrap();
        hash = fold(hash, &bits(&sub));
    }
    assert_eq!(format!("{hash:016x}"), "0789c3d369169110");
}
