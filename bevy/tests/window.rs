//! Headless tests of the moving window (a `WaterFollow` drags a water's window across an
//! open sea): MinimalPlugins, assets, meshes, transforms and a manual clock of 1/60 s per
//! update.

mod common;

use bevy::camera::primitives::Aabb;
use bevy::prelude::*;
use common::{app, mesh_of, positions, run};
use springwater_bevy::prelude::*;

/// Where the sea of the window tests sits in the world (not at the origin, so that every
/// conversion between the world and the water's local space is exercised).
const SEA: Vec3 = Vec3::new(-40.0, 2.0, 10.0);

/// Puts an entity at a world point now (`Transform` and `GlobalTransform`, so that the
/// plugin sees it this frame rather than after the next transform propagation).
fn place(app: &mut App, entity: Entity, at: Vec3) {
    app.world_mut()
        .get_mut::<Transform>(entity)
        .unwrap()
        .translation = at;
    *app.world_mut().get_mut::<GlobalTransform>(entity).unwrap() =
        GlobalTransform::from_translation(at);
}

fn origin(app: &App, water: Entity) -> [f32; 2] {
    app.world()
        .get::<WaterSurface>(water)
        .unwrap()
        .surface()
        .origin()
}

/// World heights of the water at `points` through the plugin's `WaterQuery`.
fn world_heights(app: &mut App, points: &[Vec3]) -> Vec<Option<f32>> {
    let mut state: bevy::ecs::system::SystemState<WaterQuery> =
        bevy::ecs::system::SystemState::new(app.world_mut());
    let q = state.get(app.world()).unwrap();
    points.iter().map(|&p| q.height_at(p)).collect()
}

fn errors_about(app: &App, water: Entity) -> Vec<String> {
    let errors = app.world().resource::<Messages<WaterError>>();
    errors
        .get_cursor()
        .read(errors)
        .filter(|e| e.water == water)
        .map(|e| e.message.clone())
        .collect()
}

#[test]
fn a_follower_drags_the_window_and_the_mesh_stays_where_the_world_says() {
    let mut app = app(SpringwaterPlugin::default());
    let sea = app
        .world_mut()
        .spawn((Water::with_size(65, 65), Transform::from_translation(SEA)))
        .id();
    let pond_at = Vec3::new(500.0, 0.0, 500.0);
    let pond = app
        .world_mut()
        .spawn((
            Water::with_size(17, 17),
            Transform::from_translation(pond_at),
        ))
        .id();
    // A ship that drags the sea only, and a buoy (every water) over the pond: the sea has
    // two followers and follows the one that names it, the ship.
    let start = SEA + Vec3::new(32.0, 3.0, 32.0);
    let ship = app
        .world_mut()
        .spawn((
            Transform::from_translation(start),
            WaterFollow { water: Some(sea) },
        ))
        .id();
    app.world_mut().spawn((
        Transform::from_translation(pond_at + Vec3::new(8.0, 0.0, 30.0)),
        WaterFollow::default(),
    ));
    run(&mut app, 2);
    assert_eq!(
        origin(&app, sea),
        [0.0, 0.0],
        "the ship is in the dead zone"
    );
    assert_eq!(origin(&app, pond), [0.0, 22.0], "the buoy drags the pond");

    // The ship sails 60 units along +x and 30 along +z, a unit a frame along x.
    let mut origins = vec![origin(&app, sea)];
    for step in 1..=60 {
        let at = start + Vec3::new(step as f32, 0.0, step as f32 * 0.5);
        app.world_mut()
            .get_mut::<Transform>(ship)
            .unwrap()
            .translation = at;
        run(&mut app, 1);
        origins.push(origin(&app, sea));
    }
    let last = *origins.last().unwrap();
    assert!(
        last[0] > 40.0 && last[1] > 15.0,
        "the window moved: {last:?}"
    );
    assert!(
        origins
            .windows(2)
            .all(|o| o[1][0] >= o[0][0] && o[1][1] >= o[0][1]),
        "only forward: {origins:?}"
    );
    let ws = app.world().get::<WaterSurface>(sea).unwrap();
    let dead = ws.surface().follow_dead_zone() as f32;
    // The ship is near the middle of the window (its transform is read a frame late).
    let local = start + Vec3::new(60.0, 0.0, 30.0) - SEA;
    assert!(
        (local.x - (last[0] + 32.0)).abs() <= dead + 1.0,
        "{local} {last:?}"
    );
    assert!(
        (local.z - (last[1] + 32.0)).abs() <= dead + 1.0,
        "{local} {last:?}"
    );
    assert_eq!(
        origin(&app, pond),
        [0.0, 22.0],
        "the pond stays with its buoy"
    );

    // The entity did not move; the vertices carry the window's place: the mesh holds the
    // surface's positions, and on calm water node (c, r) is at SEA + origin + (c, 0, r).
    assert_eq!(app.world().get::<Transform>(sea).unwrap().translation, SEA);
    let global = *app.world().get::<GlobalTransform>(sea).unwrap();
    let mesh = mesh_of(&app, sea);
    let [x, y, z] = ws.surface().positions();
    for (i, p) in positions(&mesh).iter().enumerate() {
        assert_eq!(p.map(f32::to_bits), [x[i], y[i], z[i]].map(f32::to_bits));
        let (c, r) = (i % 65, i / 65);
        let expected = SEA + Vec3::new(last[0] + c as f32, 0.0, last[1] + r as f32);
        let world = global.transform_point(Vec3::from_array(*p));
        assert!(
            world.distance(expected) < 1e-3,
            "node {c},{r}: {world} vs {expected}"
        );
    }
    // The bounding box moved with the window.
    let aabb = *app.world().get::<Aabb>(sea).unwrap();
    assert_eq!(aabb.min().x, last[0] - 1.0);
    assert_eq!(aabb.max().z, last[1] + 65.0);
    // Drops aimed at world points land there: at the ship, now inside the window.
    assert!(
        world_heights(&mut app, &[start])[0].is_none(),
        "the start is behind"
    );

    // A follower too far away is reported, not panicked, and the window stays.
    place(&mut app, ship, Vec3::new(1.0e9, 0.0, 0.0));
    run(&mut app, 1);
    assert_eq!(origin(&app, sea), last);
    let errors = errors_about(&app, sea);
    assert!(
        errors.iter().any(|m| m.starts_with("follow refused")),
        "{errors:?}"
    );
}

/// Runs a sea with a drop at its middle for 20 frames, with or without a follower that
/// then drags the window 12 cells along +x (keeping the drop well inside), and returns the
/// app, the sea and the world points around the drop.
fn rippled_sea(follower: bool) -> (App, Entity, Option<Entity>, Vec<Vec3>) {
    let mut app = app(SpringwaterPlugin::default());
    let sea = app
        .world_mut()
        .spawn((Water::with_size(65, 65), Transform::from_translation(SEA)))
        .id();
    let centre = SEA + Vec3::new(32.0, 0.0, 32.0);
    let follower = follower.then(|| {
        app.world_mut()
            .spawn((Transform::from_translation(centre), WaterFollow::default()))
            .id()
    });
    run(&mut app, 2);
    app.world_mut().write_message(WaterDrop {
        water: None,
        point: centre,
        height: -1.0,
        radius: 3.0,
    });
    run(&mut app, 20);
    let points = (0..35)
        .flat_map(|i| (0..35).map(move |j| (i, j)))
        .map(|(i, j)| centre + Vec3::new(i as f32 * 0.7 - 12.0, 0.0, j as f32 * 0.7 - 12.0))
        .collect();
    (app, sea, follower, points)
}

#[test]
fn world_heights_stay_put_when_the_window_shifts() {
    let (mut app, sea, follower, points) = rippled_sea(true);
    let follower = follower.unwrap();
    let behind = SEA + Vec3::new(5.0, 0.0, 32.0); // leaves the window
    assert_eq!(origin(&app, sea), [0.0, 0.0]);

    // Paused, the shift is the only change: every world height is the same, bit for bit.
    app.world_mut().get_mut::<Water>(sea).unwrap().paused = true;
    run(&mut app, 1);
    let before = world_heights(&mut app, &points);
    assert!(before.iter().all(Option::is_some));
    assert!(
        before.iter().any(|h| (h.unwrap() - SEA.y).abs() > 0.01),
        "ripples"
    );
    assert!(world_heights(&mut app, &[behind])[0].is_some());
    place(&mut app, follower, SEA + Vec3::new(44.0, 0.0, 32.0));
    run(&mut app, 1);
    assert_eq!(origin(&app, sea), [12.0, 0.0], "the window moved");
    let after = world_heights(&mut app, &points);
    assert_eq!(
        before
            .iter()
            .map(|h| h.map(f32::to_bits))
            .collect::<Vec<_>>(),
        after
            .iter()
            .map(|h| h.map(f32::to_bits))
            .collect::<Vec<_>>()
    );
    assert_eq!(world_heights(&mut app, &[behind])[0], None, "left behind");

    // Running again, the shifted water goes on as the unshifted one does: bit for bit,
    // until the difference between their edges (the shifted window's pinned edge is 12
    // cells nearer the drop) reaches the points; near the drop, for the whole run.
    let (mut still, _, _, _) = rippled_sea(false);
    app.world_mut().get_mut::<Water>(sea).unwrap().paused = false;
    let near = |p: &Vec3| {
        let d = *p - SEA - Vec3::new(32.0, 0.0, 32.0);
        d.x.abs() < 4.0 && d.z.abs() < 4.0
    };
    for frame in 0..15 {
        run(&mut app, 1);
        run(&mut still, 1);
        let shifted = world_heights(&mut app, &points);
        let unshifted = world_heights(&mut still, &points);
        for ((a, b), p) in shifted.iter().zip(&unshifted).zip(&points) {
            if frame < 5 || near(p) {
                assert_eq!(
                    a.unwrap().to_bits(),
                    b.unwrap().to_bits(),
                    "frame {frame} at {p}"
                );
            }
        }
    }
}

#[test]
fn a_floating_body_keeps_its_world_place_when_the_window_shifts() {
    let settled = |follower: bool| {
        let mut app = app(SpringwaterPlugin::default());
        let sea = app
            .world_mut()
            .spawn((Water::with_size(65, 65), Transform::from_translation(SEA)))
            .id();
        let ball = app
            .world_mut()
            .spawn((
                Buoyant::sphere(1.0, 0.5, &BuoyancySettings::default()),
                Transform::from_translation(SEA + Vec3::new(30.0, 1.0, 30.0)),
            ))
            .id();
        let camera = follower.then(|| {
            app.world_mut()
                .spawn((
                    Transform::from_translation(SEA + Vec3::new(32.0, 20.0, 32.0)),
                    WaterFollow::default(),
                ))
                .id()
        });
        run(&mut app, 300);
        (app, sea, ball, camera)
    };
    let (mut app, sea, ball, camera) = settled(true);
    let (mut still, _, still_ball, _) = settled(false);
    let at = |app: &App, ball: Entity| app.world().get::<Transform>(ball).unwrap().translation;
    assert_eq!(at(&app, ball), at(&still, still_ball));
    assert_eq!(origin(&app, sea), [0.0, 0.0]);

    // The camera moves 12 cells along −z: the window follows, the ball stays inside it.
    place(&mut app, camera.unwrap(), SEA + Vec3::new(32.0, 20.0, 20.0));
    run(&mut app, 1);
    run(&mut still, 1);
    assert_eq!(origin(&app, sea), [0.0, -12.0]);
    // The frame of the shift: the same water under the ball, the same ball, bit for bit.
    assert_eq!(at(&app, ball), at(&still, still_ball));
    let ws = app.world().get::<WaterSurface>(sea).unwrap();
    let (_, floater) = ws.surface().floaters().next().unwrap();
    assert_eq!(
        Vec3::from_array(floater.position.to_array()) + SEA,
        at(&app, ball),
        "the floater lives in the water frame, the entity at its world place"
    );
    assert!(ws
        .surface()
        .contains(floater.position.x, floater.position.z));
    // Later the two seas' edges differ, far from the ball: it floats where the other does.
    run(&mut app, 60);
    run(&mut still, 60);
    let (a, b) = (at(&app, ball), at(&still, still_ball));
    println!("ball after 60 frames: {a} vs unshifted {b}");
    assert!(a.distance(b) < 0.01, "{a} vs {b}");
}
