//! Headless tests of the plugin: MinimalPlugins, assets, meshes, transforms and a manual
//! clock of 1/60 s per update.

mod common;

use std::sync::Arc;

use bevy::camera::primitives::Aabb;
use bevy::mesh::{Indices, Mesh, Mesh3d, VertexAttributeValues};
use bevy::prelude::*;
use bevy::tasks::{ComputeTaskPool, TaskPoolBuilder};
use common::{app, bare_app, mesh_of, positions, run};
use springwater::{Params, Surface};
use springwater_bevy::prelude::*;
use springwater_bevy::TaskPoolJobs;

fn position_ptr(app: &App, water: Entity) -> *const [f32; 3] {
    let handle = &app.world().get::<Mesh3d>(water).unwrap().0;
    match app
        .world()
        .resource::<Assets<Mesh>>()
        .get(handle)
        .unwrap()
        .attribute(Mesh::ATTRIBUTE_POSITION)
    {
        Some(VertexAttributeValues::Float32x3(v)) => v.as_ptr(),
        _ => panic!("no positions"),
    }
}

fn indices(mesh: &Mesh) -> Vec<u32> {
    match mesh.indices() {
        Some(Indices::U32(v)) => v.clone(),
        other => panic!("indices: {other:?}"),
    }
}

fn drop(app: &mut App, x: f32, z: f32) {
    app.world_mut().write_message(WaterDrop {
        water: None,
        point: Vec3::new(x, 0.0, z),
        height: -1.0,
        radius: 3.0,
    });
}

#[test]
fn mesh_follows_ripples_in_place() {
    let mut app = app(SpringwaterPlugin::default());
    let water = app.world_mut().spawn(Water::with_size(65, 65)).id();
    run(&mut app, 2);
    let n = 65 * 65;
    let ptr = position_ptr(&app, water);
    let rest = mesh_of(&app, water);
    assert_eq!(positions(&rest).len(), n);
    assert!(positions(&rest).iter().all(|p| p[1] == 0.0));

    drop(&mut app, 32.0, 32.0);
    run(&mut app, 1);
    let first = mesh_of(&app, water);
    let far = 32 * 65 + 52; // 20 cells east of the drop
    assert!(positions(&first)[32 * 65 + 32][1] < -0.5);
    assert!(
        positions(&first)[far][1].abs() < 1e-9,
        "only the drop's far tail"
    );

    run(&mut app, 60);
    let later = mesh_of(&app, water);
    assert_ne!(positions(&first), positions(&later));
    assert!(
        positions(&later)[far][1].abs() > 1e-3,
        "the ripple reached 20 cells away"
    );
    // The mesh holds the surface's own positions, bit for bit.
    let ws = app.world().get::<WaterSurface>(water).unwrap();
    let [x, y, z] = ws.surface().positions();
    for (i, p) in positions(&later).iter().enumerate() {
        assert_eq!(p.map(f32::to_bits), [x[i], y[i], z[i]].map(f32::to_bits));
    }
    // Written in place: the same allocation as before the drop.
    assert_eq!(position_ptr(&app, water), ptr);
    // Normals and refracted bottom coordinates are written too.
    let uv = match later.attribute(Mesh::ATTRIBUTE_UV_0) {
        Some(VertexAttributeValues::Float32x2(v)) => v.clone(),
        _ => panic!("no uvs"),
    };
    assert_eq!(uv.len(), n);
    assert!(uv.iter().all(|t| t[0].is_finite() && t[1].is_finite()));
}

#[test]
fn indices_are_valid_and_change_only_with_the_lod() {
    let mut app = app(SpringwaterPlugin::default());
    let water = app.world_mut().spawn(Water::with_size(129, 129)).id();
    let viewer = app
        .world_mut()
        .spawn((WaterViewer, Transform::from_xyz(10.0, 10.0, 10.0)))
        .id();
    run(&mut app, 3);
    let n = 129 * 129;
    let near = indices(&mesh_of(&app, water));
    assert!(!near.is_empty() && near.len().is_multiple_of(3));
    assert!(near.iter().all(|&i| (i as usize) < n));

    drop(&mut app, 64.0, 64.0);
    run(&mut app, 20);
    assert_eq!(indices(&mesh_of(&app, water)), near, "same eye, same LOD");

    app.world_mut()
        .get_mut::<Transform>(viewer)
        .unwrap()
        .translation = Vec3::new(120.0, 10.0, 120.0);
    run(&mut app, 3);
    let moved = indices(&mesh_of(&app, water));
    assert_ne!(moved, near, "the eye moved across the pool");
    assert!(moved.iter().all(|&i| (i as usize) < n));
    let lod = app
        .world()
        .get::<WaterSurface>(water)
        .unwrap()
        .lod()
        .indices()
        .to_vec();
    assert_eq!(moved, lod);
}

#[test]
fn a_buoyant_ball_floats_and_settles() {
    let mut app = app(SpringwaterPlugin::default());
    app.world_mut().spawn(Water::with_size(65, 65));
    let settings = BuoyancySettings::default();
    let ball = app
        .world_mut()
        .spawn((
            Buoyant::sphere(1.0, 0.5, &settings),
            Transform::from_xyz(32.0, 3.0, 32.0),
        ))
        .id();
    run(&mut app, 900); // 15 s
    let y = app.world().get::<Transform>(ball).unwrap().translation.y;
    let body = app.world().get::<Buoyant>(ball).unwrap().clone();
    let mut waters = app.world_mut().query::<&WaterSurface>();
    let ws = waters.single(app.world()).unwrap();
    let surface = ws.surface().height_at(32.0, 32.0).unwrap();
    // Half the water's density: the centre sits at the surface.
    assert!((y - surface).abs() < 0.15, "centre {y}, water {surface}");
    assert!(body.velocity.length() < 0.2, "velocity {}", body.velocity);
    // Two-way: the ball dents the water around it.
    assert!(surface < 0.0, "water under the ball at {surface}");
}

/// The water's mesh positions as bits after 92 frames of a ball thrown across it and a
/// drop every 15 frames, `first_drop` along x the first.
fn scripted_mesh(first_drop: f32) -> Vec<u32> {
    let mut app = app(SpringwaterPlugin::default());
    let water = app.world_mut().spawn(Water::with_size(97, 65)).id();
    let settings = BuoyancySettings::default();
    app.world_mut().spawn((
        Buoyant {
            velocity: Vec3::new(3.0, 0.0, 1.0),
            ..Buoyant::sphere(1.5, 0.6, &settings)
        },
        Transform::from_xyz(30.0, 0.5, 30.0),
    ));
    run(&mut app, 2);
    for frame in 0..90 {
        if frame % 15 == 0 {
            drop(&mut app, first_drop + frame as f32 * 0.5, 40.0);
        }
        run(&mut app, 1);
    }
    positions(&mesh_of(&app, water))
        .iter()
        .flatten()
        .map(|v| v.to_bits())
        .collect()
}

#[test]
fn same_inputs_same_mesh_bits() {
    let first = scripted_mesh(20.0);
    assert_eq!(first, scripted_mesh(20.0));
    // The plugin did write the mesh: not the water at rest (every height 0), and a drop
    // half a cell over gives other bits.
    assert!(first.chunks(3).any(|p| p[1] != 0.0f32.to_bits()), "at rest");
    assert_ne!(
        first,
        scripted_mesh(20.5),
        "the inputs do not reach the mesh"
    );
}

#[test]
fn despawning_a_water_frees_its_mesh() {
    let mut app = app(SpringwaterPlugin::default());
    let water = app.world_mut().spawn(Water::with_size(33, 33)).id();
    run(&mut app, 2);
    let id = app.world().get::<Mesh3d>(water).unwrap().0.id();
    assert!(app.world().resource::<Assets<Mesh>>().get(id).is_some());
    app.world_mut().despawn(water);
    run(&mut app, 3);
    assert!(app.world().resource::<Assets<Mesh>>().get(id).is_none());
}

#[test]
fn bad_parameters_are_reported_not_panicked() {
    let mut app = app(SpringwaterPlugin::default());
    let mut params = Params::with_size(33, 33);
    params.dt = 10.0;
    let water = app.world_mut().spawn(Water::new(params)).id();
    run(&mut app, 3);
    assert!(app.world().get::<WaterSurface>(water).is_none());
    let errors = app.world().resource::<Messages<WaterError>>();
    let mut cursor = errors.get_cursor();
    let all: Vec<_> = cursor.read(errors).collect();
    assert_eq!(all.len(), 1, "reported once: {all:?}");
    assert_eq!(all[0].water, water);
    // Fixed in place, the water gets its surface and steps in the next frame.
    app.world_mut().get_mut::<Water>(water).unwrap().params.dt = 0.4;
    run(&mut app, 1);
    let ws = app.world().get::<WaterSurface>(water).expect("a surface");
    assert_eq!(ws.surface().steps(), 1);
    assert!(app.world().get::<Mesh3d>(water).is_some());

    // Refused new parameters leave the surface and its bounding box as they were.
    let aabb = *app.world().get::<Aabb>(water).unwrap();
    let mut bigger = Params::with_size(65, 65);
    bigger.dt = 10.0;
    app.world_mut().get_mut::<Water>(water).unwrap().params = bigger;
    run(&mut app, 2);
    assert_eq!(*app.world().get::<Aabb>(water).unwrap(), aabb);
    assert_eq!(
        app.world()
            .get::<WaterSurface>(water)
            .unwrap()
            .surface()
            .node_count(),
        33 * 33
    );

    // A NaN (which never equals itself) is reported once too, not every frame.
    let mut nan = Params::with_size(17, 17);
    nan.spacing = f32::NAN;
    let other = app.world_mut().spawn(Water::new(nan)).id();
    let mut about_other = 0;
    for _ in 0..4 {
        run(&mut app, 1);
        let errors = app.world().resource::<Messages<WaterError>>();
        about_other += cursor.read(errors).filter(|e| e.water == other).count();
    }
    assert_eq!(about_other, 1);
}

/// A new water has its surface as soon as the command that spawned it is applied, and the
/// plugin's sets run without a command flush among them (each flush is a hand-over to the
/// main thread and back, every frame).
#[test]
fn surfaces_appear_on_spawn_and_the_sets_need_no_command_flush() {
    use bevy::ecs::schedule::{ApplyDeferred, Schedules};
    let mut app = app(SpringwaterPlugin::default());
    app.world_mut().commands().spawn(Water::with_size(17, 17));
    app.world_mut().flush();
    let mut waters = app.world_mut().query::<(&Water, &WaterSurface, &Mesh3d)>();
    assert_eq!(waters.iter(app.world()).count(), 1);

    // The same app without the plugin has as many command flushes in `PostUpdate`.
    let flushes = |app: &mut App| {
        run(app, 1);
        let schedules = app.world().resource::<Schedules>();
        schedules
            .get(PostUpdate)
            .unwrap()
            .systems()
            .unwrap()
            .filter(|(_, system)| system.system_type() == std::any::TypeId::of::<ApplyDeferred>())
            .count()
    };
    let with = flushes(&mut app);
    let without = flushes(&mut bare_app());

    assert_eq!(with, without, "command flushes in PostUpdate");
}

#[test]
fn fixed_schedule_steps_by_the_fixed_clock() {
    let mut app = app(SpringwaterPlugin::default().in_fixed_schedule());
    let water = app.world_mut().spawn(Water::with_size(33, 33)).id();
    run(&mut app, 60);
    let steps = app
        .world()
        .get::<WaterSurface>(water)
        .unwrap()
        .surface()
        .steps();
    // 1 s of 64 Hz fixed steps (Bevy's default), each 24/64 model time: one step of dt.
    assert!((55..=66).contains(&steps), "{steps} steps");
}

#[test]
fn queries_read_the_water_at_world_points() {
    let mut app = app(SpringwaterPlugin::default());
    let water = app
        .world_mut()
        .spawn((
            Water::with_size(33, 33),
            Transform::from_xyz(100.0, 5.0, -50.0),
        ))
        .id();
    run(&mut app, 2);
    app.world_mut().write_message(WaterDrop {
        water: Some(water),
        point: Vec3::new(116.0, 5.0, -34.0),
        height: 1.0,
        radius: 3.0,
    });
    run(&mut app, 1);
    let ws = app.world().get::<WaterSurface>(water).unwrap();
    let local = ws.surface().height_at(16.0, 16.0).unwrap();
    let mut state: bevy::ecs::system::SystemState<WaterQuery> =
        bevy::ecs::system::SystemState::new(app.world_mut());
    let q = state.get(app.world()).unwrap();
    assert_eq!(q.height_at(Vec3::new(116.0, 0.0, -34.0)), Some(local + 5.0));
    assert_eq!(q.height_at(Vec3::new(0.0, 0.0, 0.0)), None);
    let mut heights = Vec::new();
    q.heights_at(
        water,
        &[Vec3::new(116.0, 0.0, -34.0), Vec3::new(101.0, 0.0, -49.0)],
        &mut heights,
    )
    .unwrap();
    assert_eq!(heights[0], local + 5.0);
    assert!(q.normal_at(Vec3::new(117.0, 0.0, -34.0)).unwrap().y > 0.5);
    // A sample is the library's: height, normal and velocity at the local point.
    let s = q.sample(Vec3::new(117.25, 0.0, -33.625)).unwrap();
    let surface = app.world().get::<WaterSurface>(water).unwrap().surface();
    let (x, z) = (17.25, 16.375);
    assert_eq!(s.water, water);
    assert_eq!(s.point.y, surface.height_at(x, z).unwrap() + 5.0);
    let normal = surface.normal_at(x, z).unwrap().to_array();
    let velocity = surface.velocity_at(x, z).unwrap().to_array();
    assert_eq!(s.normal.to_array(), normal);
    assert_eq!(s.velocity.to_array(), velocity);
    assert!(s.velocity.length() > 0.0, "the drop's water moves");
}

#[test]
fn task_pool_stepping_matches_a_plain_surface_bit_for_bit() {
    ComputeTaskPool::get_or_init(|| TaskPoolBuilder::new().num_threads(3).build());
    let mut plain = Surface::new(Params::with_size(256, 200)).unwrap();
    let mut pooled = Surface::new(Params::with_size(256, 200)).unwrap();
    pooled.set_job_system(Some(Arc::new(TaskPoolJobs)));
    for s in [&mut plain, &mut pooled] {
        s.drop_at(100.0, 80.0, -1.5, 3.0).unwrap();
        s.drop_at(30.0, 150.0, 1.0, 2.0).unwrap();
    }
    for frame in 0..40 {
        for s in [&mut plain, &mut pooled] {
            s.add_force_at(50.0 + frame as f32, 60.0, [0.0, -0.7, 0.0])
                .unwrap();
            s.advance(1.0 / 60.0).unwrap();
        }
    }
    assert_eq!(plain.steps(), 40);
    for (a, b) in plain.positions().iter().zip(pooled.positions()) {
        assert!(a
            .iter()
            .zip(b.iter())
            .all(|(x, y)| x.to_bits() == y.to_bits()));
    }
    for (a, b) in plain.velocities().iter().zip(pooled.velocities()) {
        assert!(a
            .iter()
            .zip(b.iter())
            .all(|(x, y)| x.to_bits() == y.to_bits()));
    }
}

/// Largest |height| of the water over 2 s with a ball thrown across it, or none.
fn wake(ball: bool) -> f32 {
    let mut app = app(SpringwaterPlugin::default());
    let water = app.world_mut().spawn(Water::with_size(97, 65)).id();
    if ball {
        app.world_mut().spawn((
            Buoyant {
                velocity: Vec3::new(60.0, 0.0, 0.0),
                drag: 0.0,
                ..Buoyant::sphere(1.5, 0.5, &BuoyancySettings::default())
            },
            Transform::from_xyz(20.0, 0.0, 32.0),
        ));
    }
    let mut largest = 0.0f32;
    for _ in 0..120 {
        run(&mut app, 1);
        let ws = app.world().get::<WaterSurface>(water).unwrap();
        let y = ws.surface().positions()[1];
        largest = y.iter().fold(largest, |m, y| m.max(y.abs()));
    }
    largest
}

#[test]
fn a_moving_ball_leaves_a_wake() {
    assert_eq!(wake(false), 0.0, "without the ball the water stays flat");
    let wave = wake(true);
    println!("largest wave behind the ball: {wave}");
    assert!(wave > 0.01, "the ball hardly disturbs the water: {wave}");
}

#[test]
fn a_buoyant_body_is_the_librarys_floater_and_goes_with_its_entity() {
    let mut app = app(SpringwaterPlugin::default());
    let water = app.world_mut().spawn(Water::with_size(65, 65)).id();
    let settings = BuoyancySettings::default();
    let crate_ = app
        .world_mut()
        .spawn((
            Buoyant::cuboid(Vec3::new(1.5, 0.5, 1.0), 0.4, &settings),
            Transform::from_xyz(20.0, 0.0, 30.0),
        ))
        .id();
    run(&mut app, 120);
    let floaters = |app: &App| {
        let ws = app.world().get::<WaterSurface>(water).unwrap();
        ws.surface()
            .floaters()
            .map(|(_, f)| f.clone())
            .collect::<Vec<_>>()
    };
    let [body] = &floaters(&app)[..] else {
        panic!("one floater expected");
    };
    let t = app.world().get::<Transform>(crate_).unwrap().translation;
    assert_eq!(
        t.to_array(),
        body.position.to_array(),
        "the entity sits where its floater is"
    );
    // The component holds the library's numbers as they are (seconds on both sides; the
    // water's transform is the identity here).
    let b = app.world().get::<Buoyant>(crate_).unwrap().clone();
    assert_eq!(b.velocity.to_array(), body.velocity.to_array());
    assert_eq!(b.water_force.to_array(), body.water_force.to_array());
    assert_eq!(b.drag, body.drag);
    let ws = app.world().get::<WaterSurface>(water).unwrap();
    assert_eq!(ws.surface().buoyancy().gravity, settings.gravity);
    // At rest: the water carries its weight (mass × g in world units).
    let weight = b.mass * settings.gravity;
    assert!(
        (b.water_force.y - weight).abs() < 0.02 * weight,
        "{} vs {weight}",
        b.water_force.y
    );
    app.world_mut().entity_mut(crate_).despawn();
    run(&mut app, 1);
    assert!(floaters(&app).is_empty(), "despawning removes the floater");
}

#[test]
fn a_buoyant_bodys_inertia_is_the_floaters() {
    let mut app = app(SpringwaterPlugin::default());
    let water = app.world_mut().spawn(Water::with_size(65, 65)).id();
    let settings = BuoyancySettings::default();
    let plain = Buoyant::cuboid(Vec3::new(1.5, 0.5, 1.0), 0.4, &settings);
    // A box whose mass is out at its walls: twice the uniform box's inertia.
    let uniform = plain.inertia_tensor();
    let hollow = uniform * 2.0;
    let spin = Vec3::new(0.0, 2.0, 0.0);
    let mut spawn = |body: Buoyant, x: f32| {
        let body = Buoyant {
            angular_velocity: spin,
            ..body
        };
        let at = Transform::from_xyz(x, 0.0, 32.0);
        app.world_mut().spawn((body, at)).id()
    };
    let a = spawn(plain.clone(), 16.0);
    let b = spawn(plain.with_inertia(hollow), 48.0);
    run(&mut app, 30);
    let ws = app.world().get::<WaterSurface>(water).unwrap();
    let inertias: Vec<_> = ws
        .surface()
        .floaters()
        .map(|(_, f)| f.inertia_tensor().to_cols_array())
        .collect();
    assert_eq!(inertias.len(), 2);
    assert!(inertias.contains(&uniform.to_cols_array()));
    assert!(inertias.contains(&hollow.to_cols_array()));
    // The water's drag slows the heavier spin less.
    let spin_of = |e| app.world().get::<Buoyant>(e).unwrap().angular_velocity.y;
    let (light, heavy) = (spin_of(a), spin_of(b));
    println!("spin after 0.5 s: {light} (uniform), {heavy} (hollow)");
    assert!(light < heavy && heavy < spin.y, "{light} vs {heavy}");

    // An inertia no body has is refused, reported, not panicked.
    let bad = Mat3::from_diagonal(Vec3::new(1.0, 1.0, 5.0));
    let odd = Buoyant::sphere(1.0, 0.5, &settings).with_inertia(bad);
    app.world_mut()
        .spawn((odd, Transform::from_xyz(32.0, 0.0, 16.0)));
    run(&mut app, 1);
    let errors = app.world().resource::<Messages<WaterError>>();
    let mut cursor = errors.get_cursor();
    let refused: Vec<_> = cursor.read(errors).map(|e| e.message.clone()).collect();
    assert!(refused.iter().any(|m| m.contains("inertia")), "{refused:?}");
}

#[test]
fn a_heeled_box_rights_itself_and_its_transform_turns_with_it() {
    let mut app = app(SpringwaterPlugin::default());
    let water = app.world_mut().spawn(Water::with_size(65, 65)).id();
    let settings = BuoyancySettings::default();
    let heeled = Quat::from_rotation_x(15f32.to_radians());
    let barge = app
        .world_mut()
        .spawn((
            Buoyant::cuboid(Vec3::new(4.0, 0.75, 3.0), 0.5, &settings),
            Transform::from_xyz(32.0, 0.0, 32.0).with_rotation(heeled),
        ))
        .id();
    run(&mut app, 1);
    let tilt = |app: &App| {
        let up = app.world().get::<Transform>(barge).unwrap().rotation * Vec3::Y;
        up.y.clamp(-1.0, 1.0).acos().to_degrees()
    };
    assert!(tilt(&app) > 10.0, "the plugin read the entity's rotation");
    run(&mut app, 600);
    // The Transform is the floater's pose, and the body stands upright again.
    let ws = app.world().get::<WaterSurface>(water).unwrap();
    let (_, body) = ws.surface().floaters().next().unwrap();
    let rotation = app.world().get::<Transform>(barge).unwrap().rotation;
    assert_eq!(rotation.to_array(), body.orientation.to_array());
    assert!(tilt(&app) < 1.0, "still heeled {}°", tilt(&app));
    let b = app.world().get::<Buoyant>(barge).unwrap();
    assert_eq!(
        b.angular_velocity.to_array(),
        body.angular_velocity.to_array()
    );
}

#[test]
fn bodies_come_back_one_each_when_the_surface_starts_over() {
    let mut app = app(SpringwaterPlugin::default());
    let water = app.world_mut().spawn(Water::with_size(65, 65)).id();
    let settings = BuoyancySettings::default();
    let spots = [(10.0, 12.0), (40.0, 30.0), (25.0, 50.0)];
    let balls: Vec<Entity> = spots
        .iter()
        .map(|&(x, z)| {
            app.world_mut()
                .spawn((
                    Buoyant::sphere(1.0, 0.5, &settings),
                    Transform::from_xyz(x, 0.0, z),
                ))
                .id()
        })
        .collect();
    run(&mut app, 30);
    // New parameters: the surface starts over and must get every body back, once each,
    // whatever order the bodies are visited in (moving the first body to another
    // archetype puts it last).
    #[derive(Component)]
    struct Marker;
    app.world_mut()
        .get_mut::<Water>(water)
        .unwrap()
        .params
        .viscosity = 0.1;
    app.world_mut().entity_mut(balls[0]).insert(Marker);
    run(&mut app, 30);
    let ws = app.world().get::<WaterSurface>(water).unwrap();
    let mut xs: Vec<f32> = ws.surface().floaters().map(|(_, f)| f.position.x).collect();
    xs.sort_by(f32::total_cmp);
    assert_eq!(xs.len(), 3, "{xs:?}");
    for (&ball, &(x, _)) in balls.iter().zip(&spots) {
        let t = app.world().get::<Transform>(ball).unwrap().translation;
        assert!((t.x - x).abs() < 1.0, "{t} drifted from {x}");
        assert!(xs.contains(&t.x), "{t} has no floater of its own: {xs:?}");
    }
}
