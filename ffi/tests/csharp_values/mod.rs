//! What `Tests~/Frames.cs`, `Tests~/Shapes.cs` and `Tests~/Disturbances.cs` print, computed
//! here through the Rust API for `csharp.rs` to compare with the C# run's lines.

use crate::common::fnv;
use springwater::body::BoatShape;
use springwater::disturb::{Rain, Wake};
use springwater::mesh::{LodMesh, LodParams};
use springwater::refraction::RefractionParams;
use springwater::{Floater, Params, Shape, Surface};
use std::sync::Arc;

fn hex(f: f32) -> String {
    format!("{:08x}", f.to_bits())
}

/// `Frames()` of Frames.cs.
pub fn frames() -> Vec<(&'static str, String)> {
    let mut s = Surface::new(Params::with_size(24, 20)).unwrap();
    let n = s.node_count();
    s.drop_at(10.0, 8.0, 0.5, 2.0).unwrap();
    let (substeps, each) = s.split_frame(0.05).unwrap();
    assert_eq!(s.advance_variable(0.05).unwrap(), substeps);
    s.set_acceleration([0.0, -1.0, 0.5]).unwrap();
    let forces: Vec<f32> = (0..3 * n).map(|i| 0.01 * (i % 7) as f32 - 0.03).collect();
    let [x, y, z]: [Vec<f32>; 3] =
        std::array::from_fn(|k| forces.chunks(3).map(|f| f[k]).collect());
    s.set_forces([&x, &y, &z]).unwrap();
    s.add_force(30, [0.0, 0.25, 0.0]).unwrap();
    s.step_n(2).unwrap();
    let [vx, vy, vz] = s.velocities();
    let velocities = (0..n).flat_map(|i| [vx[i], vy[i], vz[i]]);

    let mut lod = LodMesh::new(LodParams::default().with_patch_cells(8).with_levels(3)).unwrap();
    lod.set_levels(&s.mesh_view(), &[0, 1, 2, 2, 0, 7, 1, 1, 0])
        .unwrap();
    let patches: Vec<String> = lod
        .patch_levels()
        .iter()
        .map(|l| format!("{l:02X}"))
        .collect();

    let mut p = Params::default();
    p.set_ripple_speed(100.0).unwrap();
    vec![
        ("split_frame", format!("{substeps} {}", hex(each))),
        ("frames_velocities", format!("{:016x}", fnv(velocities))),
        ("frames_hash", format!("{:016x}", s.state_hash())),
        ("lod_patch_levels", patches.join("-")),
        ("lod_triangles", lod.triangle_count().to_string()),
        ("ripple_time_scale", hex(p.time_scale)),
        ("r0", hex(RefractionParams::default().r0())),
    ]
}

/// `Shapes()` of Shapes.cs.
pub fn shapes() -> Vec<(&'static str, String)> {
    let mut shape = BoatShape::default();
    (shape.stations, shape.segments) = (12, 4);
    let boat = shape.hull().unwrap();
    let centroid = boat.centroid();
    let centred = Shape::Hull(Arc::new(boat.centred().unwrap()));
    let mut body = Floater::cuboid([1.0, 0.5, 2.0], 3.0, [4.0, 0.0, 5.0]);
    body.velocity = glam::Vec3::new(1.0, -0.5, 0.25);
    body.angular_velocity = glam::Vec3::new(0.3, 1.5, -0.2);
    let v = body.velocity_at([5.0, 0.5, 3.0]);
    vec![
        (
            "boat_mesh",
            format!("{:016x}", fnv(boat.vertices().iter().flatten().copied())),
        ),
        ("boat_volume", hex(boat.volume())),
        (
            "boat_centroid",
            [centroid.x, centroid.y, centroid.z].map(hex).concat(),
        ),
        ("centred_radius", hex(centred.bounding_radius())),
        ("point_velocity", [v.x, v.y, v.z].map(hex).concat()),
        ("box_bounding_radius", hex(body.shape.bounding_radius())),
    ]
}

/// `Disturbances()` of Disturbances.cs.
pub fn disturbances() -> Vec<(&'static str, String)> {
    let mut s = Surface::new(Params::with_size(48, 40)).unwrap();
    let mut rain = Rain::new(20.0, 7);
    rain.radius = 1.0..2.5;
    rain.depth = 0.5;
    let mut wake = Wake::new(vec![[10.0, 10.0], [38.0, 10.0], [38.0, 30.0]]).unwrap();
    (wake.speed, wake.radius, wake.strength) = (30.0, 2.0, 1.0);
    let mut circle = Wake::circle(&s, 12.0);
    for _ in 0..30 {
        s.advance_with(1.0 / 60.0, &mut (&mut rain, &mut wake, &mut circle))
            .unwrap();
    }
    let [x, z] = wake.position();
    let fallen = rain.fallen();
    wake.translate(-2.0, 1.0).unwrap();
    rain.rate = 0.0;
    s.advance_with(0.25, &mut (&mut rain, &mut wake, &mut circle))
        .unwrap();
    vec![
        ("wake_position", hex(x) + &hex(z)),
        ("rain_fallen", fallen.to_string()),
        ("disturbed_hash", format!("{:016x}", s.state_hash())),
    ]
}
