//! A pool in the rain: a tiled bottom seen through the water (refracted `UV_0`), a ball
//! floating on it and three boats under way (Avian rigid bodies with an
//! [`AvianBuoyant`]), an orbit camera.
//!
//! `cargo run --release -p springwater-bevy --example pool --features example`
//!
//! Drag with the left mouse button to orbit, scroll to zoom, arrows or WASD push the
//! ball, space drops a splash under the ball, R toggles the rain, B makes the camera ride
//! along with the white boat and back, F makes the water's window follow the ball (a
//! [`WaterFollow`] on it; the camera follows too) out of the pool and across an open sea
//! of the same tiles.
//!
//! The boats are the shipped hull (`BoatShape::default()`, 6 × 2 × 1), each an Avian
//! `RigidBody` with the hull as its trimesh collider and its mesh; a helmsman keeps each
//! on its own circle. The water lifts, pitches and rolls them and takes the reaction, so
//! they leave wakes; the deck around the pool is a static collider they bump into. The
//! ball is an Avian ball at half the water's density: the boats run into it and push it
//! away, and it bumps into the deck too, until F lets it leave the pool over the deck.
//!
//! `SPRINGWATER_SCREENSHOT=pool.png` runs on a fixed 1/60 s clock instead, saves the
//! window after `SPRINGWATER_SCREENSHOT_FRAME` frames (default 180), prints the boats'
//! heel and trim, and exits: the pictures in the README were made so, under Xvfb with
//! Mesa's software Vulkan. `SPRINGWATER_BOATS=1` as well starts with the camera riding
//! along with a boat.
//! `SPRINGWATER_FOLLOW=1` as well makes the second one: the window follows the ball from
//! the start, and the ball cruises to the right at twice the ripple speed with 30 times
//! the gravity, so that it dents the water enough for its wake to show (no rain, no deck,
//! the camera further back).

use std::sync::Arc;

use avian3d::prelude::*;
use bevy::asset::RenderAssetUsages;
use bevy::image::{ImageAddressMode, ImageSampler, ImageSamplerDescriptor};
use bevy::input::mouse::{AccumulatedMouseMotion, AccumulatedMouseScroll};
use bevy::mesh::PrimitiveTopology;
use bevy::prelude::*;
use bevy::render::render_resource::{Extent3d, TextureDimension, TextureFormat};
use bevy::render::view::screenshot::{save_to_disk, Screenshot, ScreenshotCaptured};
use bevy::time::TimeUpdateStrategy;
use springwater::body::BoatShape;
use springwater::disturb::{Disturbance, Rain};
use springwater_bevy::prelude::*;

const COLS: usize = 129;
const ROWS: usize = 97;
/// Rain drops per second.
const RAIN: f32 = 7.2;
/// The boats' density against the water's: a little under half the hull's depth in the
/// water, so that a ripple under one side rolls it.
const BOAT_DENSITY: f32 = 0.35;
/// The boats' speed under way, units per second (a sixth of the ripples' speed).
const BOAT_SPEED: f32 = 7.0;
/// The radius of each boat's circle.
const BOAT_CIRCLE: f32 = 6.5;
/// Each boat: the centre of its circle (x, z), +1 to go round it anticlockwise seen from
/// above or −1 clockwise, and the colour of its topsides.
const BOATS: [(Vec2, f32, Color); 3] = [
    (Vec2::new(20.0, -8.0), 1.0, Color::srgb(0.75, 0.08, 0.05)),
    (Vec2::new(40.0, 6.0), -1.0, Color::srgb(0.92, 0.92, 0.88)),
    (Vec2::new(18.0, 16.0), 1.0, Color::srgb(0.1, 0.25, 0.65)),
];

fn main() {
    let mut app = App::new();
    // Avian steps in `FixedPostUpdate`; the water steps there too, after it, by the same
    // tick (60 Hz, as the screenshot clock), with Avian's gravity. That gravity is
    // springwater's default (`BuoyancySettings`), the fast water's own.
    app.add_plugins((
        DefaultPlugins,
        PhysicsPlugins::default(),
        SpringwaterPlugin::default().with_avian(),
    ))
    .insert_resource(Time::<Fixed>::from_hz(60.0))
    .insert_resource(Gravity(Vec3::NEG_Y * BuoyancySettings::default().gravity))
    .insert_resource(ClearColor(Color::srgb(0.55, 0.7, 0.85)))
    .add_systems(Startup, setup)
    .add_systems(FixedUpdate, (steer_boats, drive_ball))
    .add_systems(
        Update,
        (
            orbit_camera,
            push_ball,
            toggle_rain,
            follow_ball,
            look_at_boats,
        ),
    );
    if let Ok(path) = std::env::var("SPRINGWATER_SCREENSHOT") {
        let frame = std::env::var("SPRINGWATER_SCREENSHOT_FRAME")
            .ok()
            .and_then(|f| f.parse().ok())
            .unwrap_or(180)
            .max(1);
        // A fixed clock, so the picture does not depend on how fast the machine renders.
        app.insert_resource(TimeUpdateStrategy::ManualDuration(
            std::time::Duration::from_secs_f64(1.0 / 60.0),
        ))
        .insert_resource(ScreenshotAt { path, frame })
        .add_systems(Update, screenshot);
        if std::env::var("SPRINGWATER_FOLLOW").is_ok_and(|v| v == "1") {
            // Avian's gravity is every water's (`with_avian`).
            let gravity = 30.0 * BuoyancySettings::default().gravity;
            app.insert_resource(Cruise)
                .insert_resource(Gravity(Vec3::NEG_Y * gravity))
                .add_systems(Update, cruise.after(push_ball));
        }
        if std::env::var("SPRINGWATER_BOATS").is_ok_and(|v| v == "1") {
            app.insert_resource(StartOnBoats);
        }
    }
    app.run();
}

/// Where and after how many frames to save the window (screenshot mode).
#[derive(Resource)]
struct ScreenshotAt {
    path: String,
    frame: u32,
}

/// Screenshot mode with `SPRINGWATER_BOATS=1`: the camera starts riding along with a boat.
#[derive(Resource)]
struct StartOnBoats;

/// Saves the window at the frame asked for, and prints each boat's heel and trim then
/// and the greatest seen before (degrees, the deck's athwartships and fore-and-aft lines
/// from the horizontal; positive: starboard down, bow up).
fn screenshot(
    mut frames: Local<u32>,
    mut greatest: Local<[[f32; 2]; BOATS.len()]>,
    at: Res<ScreenshotAt>,
    boats: Query<(&Transform, &Helm)>,
    mut commands: Commands,
) {
    *frames += 1;
    for (boat, helm) in &boats {
        let k = helm.number;
        let tilt = heel_and_trim(boat.rotation);
        for (most, now) in greatest[k].iter_mut().zip(tilt) {
            *most = most.max(now.abs());
        }
        if *frames == at.frame {
            let [most_heel, most_trim] = greatest[k];
            println!(
                "boat {k}: heel {:+.1}°, trim {:+.1}° (greatest so far {most_heel:.1}°, {most_trim:.1}°)",
                tilt[0], tilt[1]
            );
        }
    }
    if *frames == at.frame {
        commands
            .spawn(Screenshot::primary_window())
            .observe(save_to_disk(at.path.clone()))
            .observe(
                |_: On<ScreenshotCaptured>, mut exit: MessageWriter<AppExit>| {
                    exit.write(AppExit::Success);
                },
            );
    }
}

/// Screenshot mode with `SPRINGWATER_FOLLOW=1`: the ball cruises, the window following.
#[derive(Resource)]
struct Cruise;

/// Makes the window follow the ball and pushes the ball to the camera's right, as D does
/// but some 40 times harder: about 80 units per second, twice the ripple speed, so that it
/// leaves a V-shaped wake.
fn cruise(
    cameras: Query<&Transform, With<Camera3d>>,
    mut balls: Query<(Entity, &mut Thrust, Has<WaterFollow>), With<Ball>>,
    mut commands: Commands,
) {
    let Ok(camera) = cameras.single() else {
        return;
    };
    let right = (camera.right().as_vec3() * Vec3::new(1.0, 0.0, 1.0)).normalize_or_zero();
    for (ball, mut thrust, following) in &mut balls {
        if !following {
            commands
                .entity(ball)
                .insert((WaterFollow::default(), ball_layers(true)));
        }
        thrust.0 += right * 500.0;
    }
}

/// Pool tiles with grout lines, RGBA8: 16 × 12 tiles over the pool's bottom.
fn tiles() -> Image {
    let (w, h, tile) = (512u32, 384u32, 32u32);
    let mut data = Vec::with_capacity((w * h * 4) as usize);
    for y in 0..h {
        for x in 0..w {
            let (tx, ty) = (x % tile, y % tile);
            let grout = tx < 2 || ty < 2;
            let shade = if ((x / tile) + (y / tile)) % 2 == 0 {
                235
            } else {
                215
            };
            let px = if grout {
                [70, 90, 110, 255]
            } else {
                [shade - 60, shade - 10, shade, 255]
            };
            data.extend_from_slice(&px);
        }
    }
    let mut image = Image::new(
        Extent3d {
            width: w,
            height: h,
            depth_or_array_layers: 1,
        },
        TextureDimension::D2,
        data,
        TextureFormat::Rgba8UnormSrgb,
        RenderAssetUsages::RENDER_WORLD,
    );
    image.sampler = ImageSampler::Descriptor(ImageSamplerDescriptor {
        address_mode_u: ImageAddressMode::Repeat,
        address_mode_v: ImageAddressMode::Repeat,
        ..ImageSamplerDescriptor::linear()
    });
    image
}

#[derive(Component)]
struct Ball;

/// The acceleration the keys (or the cruise) give the ball, applied every physics tick
/// until the next frame sets it again.
#[derive(Component, Default)]
struct Thrust(Vec3);

/// The deck's collision layer: the ball leaves it out while the water follows the ball,
/// so that it can leave the pool.
const DECK: u32 = 1 << 1;

/// The ball's collision layers: everything (the boats and the deck), or everything but
/// the deck while the water follows it.
fn ball_layers(following: bool) -> CollisionLayers {
    let filters = match following {
        true => LayerMask::ALL.0 & !DECK,
        false => LayerMask::ALL.0,
    };
    CollisionLayers::new(LayerMask::DEFAULT, filters)
}

/// Orbit state of the camera: around `focus`, at `distance`, `yaw` and `pitch` radians.
#[derive(Component, Clone, Copy)]
struct Orbit {
    focus: Vec3,
    distance: f32,
    yaw: f32,
    pitch: f32,
    /// Riding along with the [`Ridden`] boat: the focus on it, looking from ahead of it,
    /// a little to the inside of its turn, the yaw following its heading.
    ride: bool,
}

/// Rain that can be switched off.
struct Toggled(Rain, bool);

impl Disturbance for Toggled {
    fn apply(&mut self, surface: &mut springwater::Surface, dt: f32) -> springwater::Result<()> {
        if self.1 {
            self.0.apply(surface, dt)
        } else {
            Ok(())
        }
    }
}

fn setup(
    mut commands: Commands,
    mut meshes: ResMut<Assets<Mesh>>,
    mut materials: ResMut<Assets<StandardMaterial>>,
    mut images: ResMut<Assets<Image>>,
    cruise: Option<Res<Cruise>>,
    on_boats: Option<Res<StartOnBoats>>,
) {
    let cruising = cruise.is_some();
    let bottom = images.add(tiles());
    let (w, d) = ((COLS - 1) as f32, (ROWS - 1) as f32);
    // The water: its mesh and `UV_0` come from the plugin; the material samples the
    // bottom's tiles at the refracted coordinates, tinted like water.
    commands.spawn((
        Water::with_size(COLS, ROWS).with_depth(6.0),
        WaterDisturbance::new(Toggled(Rain::new(RAIN, 7), !cruising)),
        MeshMaterial3d(materials.add(StandardMaterial {
            base_color: Color::srgb(0.55, 0.8, 0.95),
            base_color_texture: Some(bottom),
            perceptual_roughness: 0.08,
            reflectance: 0.6,
            double_sided: true,
            cull_mode: None,
            ..default()
        })),
        Transform::from_xyz(-w / 2.0, 0.0, -d / 2.0),
    ));
    // The ball: an Avian ball half as dense as the water, floated by it.
    commands.spawn((
        Ball,
        Thrust::default(),
        RigidBody::Dynamic,
        Collider::sphere(2.5),
        ColliderDensity(0.5),
        AvianBuoyant::default(),
        ball_layers(cruising),
        Mesh3d(meshes.add(Sphere::new(2.5).mesh().uv(32, 18))),
        MeshMaterial3d(materials.add(StandardMaterial {
            base_color: Color::srgb(0.95, 0.35, 0.2),
            perceptual_roughness: 0.4,
            ..default()
        })),
        Transform::from_xyz(-10.0, 4.0, 5.0),
    ));
    // The deck around the pool: four stone slabs whose tops stand a little above the water
    // (hidden when the ball cruises: the window leaves the pool and would pass under it).
    let stone = materials.add(StandardMaterial {
        base_color: Color::srgb(0.5, 0.47, 0.42),
        perceptual_roughness: 0.9,
        ..default()
    });
    let (far, rim) = (200.0, 0.8);
    for (x0, z0, x1, z1) in [
        (-far, -far, far, -d / 2.0),
        (-far, d / 2.0, far, far),
        (-far, -d / 2.0, -w / 2.0, d / 2.0),
        (w / 2.0, -d / 2.0, far, d / 2.0),
    ] {
        let (min, max) = (Vec3::new(x0, -8.0, z0), Vec3::new(x1, rim, z1));
        commands.spawn((
            Mesh3d(meshes.add(Cuboid::from_corners(min, max))),
            MeshMaterial3d(stone.clone()),
            // A wall for the boats and the ball.
            RigidBody::Static,
            Collider::cuboid(max.x - min.x, max.y - min.y, max.z - min.z),
            CollisionLayers::new(DECK, LayerMask::ALL),
            Transform::from_translation((min + max) / 2.0),
            if cruising {
                Visibility::Hidden
            } else {
                Visibility::Inherited
            },
        ));
    }
    // No boats when the window leaves the pool.
    if !cruising {
        spawn_boats(&mut commands, &mut meshes, &mut materials);
    }
    // A low sun behind the pool, so that the ripples glint towards the camera.
    commands.spawn((
        DirectionalLight {
            illuminance: 12_000.0,
            ..default()
        },
        Transform::from_xyz(-30.0, 30.0, -45.0).looking_at(Vec3::ZERO, Vec3::Y),
    ));
    // Further and higher when the ball cruises, to see the whole window and the wake.
    let (distance, pitch) = if cruising { (150.0, 0.8) } else { (85.0, 0.6) };
    let mut orbit = Orbit {
        focus: Vec3::new(-4.0, 0.0, 0.0),
        distance,
        yaw: 0.6,
        pitch,
        ride: false,
    };
    if on_boats.is_some() {
        orbit = BOATS_VIEW;
    }
    commands.spawn((
        Camera3d::default(),
        Transform::default(),
        // The sky, for the water's reflections.
        EnvironmentMapLight {
            intensity: 1500.0,
            ..EnvironmentMapLight::hemispherical_gradient(
                &mut images,
                Color::srgb(0.45, 0.6, 0.85),
                Color::srgb(0.8, 0.85, 0.9),
                Color::srgb(0.3, 0.3, 0.3),
            )
        },
        orbit,
    ));
}

/// The ball while the water follows it (never the camera).
type FollowedBall = (With<Ball>, With<WaterFollow>, Without<Camera3d>);

/// The boat the camera rides along with (never the camera).
type RiddenBoat = (With<Ridden>, Without<Camera3d>);

fn orbit_camera(
    buttons: Res<ButtonInput<MouseButton>>,
    motion: Res<AccumulatedMouseMotion>,
    scroll: Res<AccumulatedMouseScroll>,
    mut cameras: Query<(&mut Orbit, &mut Transform), With<Camera3d>>,
    followed: Query<&Transform, FollowedBall>,
    ridden: Query<(&Transform, &Helm), RiddenBoat>,
) {
    for (mut orbit, mut transform) in &mut cameras {
        if let Ok(ball) = followed.single() {
            orbit.focus = ball.translation.with_y(0.0);
        }
        if let (true, Ok((boat, helm))) = (orbit.ride, ridden.single()) {
            let heading = (boat.rotation * Vec3::X).with_y(0.0).normalize_or_zero();
            let inside = (helm.centre - boat.translation)
                .with_y(0.0)
                .normalize_or_zero();
            let from = heading + 0.4 * inside;
            orbit.focus = boat.translation.with_y(0.0);
            orbit.yaw = from.x.atan2(from.z);
        }
        if buttons.pressed(MouseButton::Left) {
            orbit.yaw -= motion.delta.x * 0.005;
            orbit.pitch = (orbit.pitch + motion.delta.y * 0.005).clamp(0.05, 1.5);
        }
        orbit.distance = (orbit.distance * (1.0 - scroll.delta.y * 0.1)).clamp(10.0, 400.0);
        let offset = Vec3::new(
            orbit.yaw.sin() * orbit.pitch.cos(),
            orbit.pitch.sin(),
            orbit.yaw.cos() * orbit.pitch.cos(),
        ) * orbit.distance;
        *transform =
            Transform::from_translation(orbit.focus + offset).looking_at(orbit.focus, Vec3::Y);
    }
}

fn push_ball(
    keys: Res<ButtonInput<KeyCode>>,
    cameras: Query<&Transform, With<Camera3d>>,
    mut balls: Query<(&mut Thrust, &Transform), With<Ball>>,
    mut drops: MessageWriter<WaterDrop>,
) {
    let Ok(camera) = cameras.single() else {
        return;
    };
    // Push relative to where the camera looks, in the water's plane.
    let forward = (camera.forward().as_vec3() * Vec3::new(1.0, 0.0, 1.0)).normalize_or_zero();
    let right = forward.cross(Vec3::Y);
    let mut dir = Vec3::ZERO;
    for (keys_for, v) in [
        ([KeyCode::ArrowUp, KeyCode::KeyW], forward),
        ([KeyCode::ArrowDown, KeyCode::KeyS], -forward),
        ([KeyCode::ArrowRight, KeyCode::KeyD], right),
        ([KeyCode::ArrowLeft, KeyCode::KeyA], -right),
    ] {
        if keys.any_pressed(keys_for) {
            dir += v;
        }
    }
    for (mut thrust, transform) in &mut balls {
        thrust.0 = dir * 12.0;
        if keys.just_pressed(KeyCode::Space) {
            drops.write(WaterDrop {
                water: None,
                point: transform.translation,
                height: -2.0,
                radius: 4.0,
            });
        }
    }
}

fn toggle_rain(
    keys: Res<ButtonInput<KeyCode>>,
    mut off: Local<bool>,
    mut rain: Query<&mut WaterDisturbance>,
) {
    if keys.just_pressed(KeyCode::KeyR) {
        *off = !*off;
        for mut d in &mut rain {
            d.0 = Box::new(Toggled(Rain::new(RAIN, 7), !*off));
        }
    }
}

/// F: the water's window follows the ball over the deck (or stops following it, and the
/// deck is a wall for the ball again).
fn follow_ball(
    keys: Res<ButtonInput<KeyCode>>,
    balls: Query<(Entity, Has<WaterFollow>), With<Ball>>,
    mut commands: Commands,
) {
    if keys.just_pressed(KeyCode::KeyF) {
        for (ball, following) in &balls {
            let mut ball = commands.entity(ball);
            if following {
                ball.remove::<WaterFollow>().insert(ball_layers(false));
            } else {
                ball.insert((WaterFollow::default(), ball_layers(true)));
            }
        }
    }
}

/// Every physics tick before Avian steps: the ball's thrust.
fn drive_ball(mut balls: Query<(&Thrust, Forces), With<Ball>>) {
    for (thrust, mut forces) in &mut balls {
        forces.apply_linear_acceleration(thrust.0);
    }
}

/// B: the camera rides along with the white boat, or goes back where it looked before.
fn look_at_boats(
    keys: Res<ButtonInput<KeyCode>>,
    mut before: Local<Option<Orbit>>,
    mut cameras: Query<&mut Orbit, With<Camera3d>>,
) {
    if keys.just_pressed(KeyCode::KeyB) {
        for mut orbit in &mut cameras {
            *orbit = match before.take() {
                Some(view) => view,
                None => {
                    *before = Some(*orbit);
                    BOATS_VIEW
                }
            };
        }
    }
}

/// The camera riding along with the white boat, low (B, and `SPRINGWATER_BOATS=1`).
const BOATS_VIEW: Orbit = Orbit {
    focus: Vec3::new(36.0, 0.0, 4.0),
    distance: 15.0,
    yaw: 0.9,
    pitch: 0.28,
    ride: true,
};

/// The boat the camera rides along with in the boats' view (the white one).
#[derive(Component)]
struct Ridden;

/// A boat's helmsman: keeps it under way round its circle.
#[derive(Component)]
struct Helm {
    /// Which of [`BOATS`].
    number: usize,
    /// The centre of the circle, world.
    centre: Vec3,
    /// +1: round the circle anticlockwise seen from above; −1: clockwise.
    turn: f32,
}

/// The boats, one on each circle of [`BOATS`], under way.
fn spawn_boats(
    commands: &mut Commands,
    meshes: &mut Assets<Mesh>,
    materials: &mut Assets<StandardMaterial>,
) {
    // The body's origin is its centre of mass: the hull moved onto its centroid (Avian's
    // centre of mass for a uniform density).
    let hull = BoatShape::default()
        .hull()
        .and_then(|hull| hull.centred())
        .expect("the shipped boat is a valid hull");
    let hull = Arc::new(hull);
    let vertices: Vec<Vec3> = hull.vertices().iter().map(|v| Vec3::from(*v)).collect();
    let collider = Collider::trimesh(vertices.clone(), hull.triangles().to_vec());
    // The vertex colours carry the paint.
    let material = materials.add(StandardMaterial {
        perceptual_roughness: 0.6,
        ..default()
    });
    for (k, &(centre, turn, paint)) in BOATS.iter().enumerate() {
        let centre = Vec3::new(centre.x, 0.0, centre.y);
        // Each starts at a different place on its circle, heading along it.
        let out = Quat::from_rotation_y(2.0 * k as f32) * Vec3::X;
        let heading = turn * Vec3::Y.cross(out);
        let mut boat = commands.spawn((
            Helm {
                number: k,
                centre,
                turn,
            },
            RigidBody::Dynamic,
            collider.clone(),
            ColliderDensity(BOAT_DENSITY),
            AvianBuoyant::with_hull(Arc::clone(&hull)),
            LinearVelocity(heading * BOAT_SPEED),
            Mesh3d(meshes.add(hull_mesh(&vertices, hull.triangles(), paint))),
            MeshMaterial3d(material.clone()),
            // The bow (the body's +x) along the heading.
            Transform::from_translation(centre + BOAT_CIRCLE * out)
                .with_rotation(Quat::from_rotation_y(f32::atan2(-heading.z, heading.x))),
        ));
        if k == 1 {
            boat.insert(Ridden);
        }
    }
}

/// The hull as drawn: flat-shaded faces in vertex colours, the deck (faces looking up)
/// wooden, the topsides `paint`, the bottom up to a little above the waterline dark red,
/// so that the water's line along the side shows how the boat heels and trims.
fn hull_mesh(vertices: &[Vec3], triangles: &[[u32; 3]], paint: Color) -> Mesh {
    let keel = vertices.iter().map(|v| v.y).fold(f32::INFINITY, f32::min);
    let boot_top = keel + 0.5 * BoatShape::default().depth;
    let deck = Color::srgb(0.42, 0.27, 0.13);
    let bottom = Color::srgb(0.45, 0.08, 0.06);
    let corners = 3 * triangles.len();
    let (mut positions, mut normals, mut colours) = (
        Vec::with_capacity(corners),
        Vec::with_capacity(corners),
        Vec::with_capacity(corners),
    );
    for triangle in triangles {
        let [a, b, c] = triangle.map(|i| vertices[i as usize]);
        let normal = (b - a).cross(c - a).normalize_or_zero();
        let colour = if normal.y > 0.6 {
            deck
        } else if (a.y + b.y + c.y) / 3.0 < boot_top {
            bottom
        } else {
            paint
        };
        for p in [a, b, c] {
            positions.push(p.to_array());
            normals.push(normal.to_array());
            colours.push(colour.to_linear().to_f32_array());
        }
    }
    Mesh::new(
        PrimitiveTopology::TriangleList,
        RenderAssetUsages::RENDER_WORLD,
    )
    .with_inserted_attribute(Mesh::ATTRIBUTE_POSITION, positions)
    .with_inserted_attribute(Mesh::ATTRIBUTE_NORMAL, normals)
    .with_inserted_attribute(Mesh::ATTRIBUTE_COLOR, colours)
}

/// The helmsmen, every physics tick before Avian steps. The propeller, aft and below the
/// centre of mass (so the bow lifts a little under way), pushes along the heading with
/// what holds the speed against the water's drag (its rate times the speed, for a body
/// displacing its own mass). The rudder is a turning acceleration towards a point a
/// little ahead on the circle, over the turn rate the circle needs (speed / radius), which
/// the water's drag on the turning hull would otherwise slow.
fn steer_boats(mut boats: Query<(&Helm, &AvianBuoyant, Forces)>) {
    for (helm, buoyant, mut forces) in &mut boats {
        let (position, rotation) = (forces.position().0, forces.rotation().0);
        let level = |v: Vec3| v.with_y(0.0).normalize_or_zero();
        let heading = level(rotation * Vec3::X);
        let out = level(position - helm.centre);
        let aim = helm.centre + Quat::from_rotation_y(0.5 * helm.turn) * out * BOAT_CIRCLE;
        let off_course = heading.cross(level(aim - position)).y;
        let rate = helm.turn * BOAT_SPEED / BOAT_CIRCLE + 2.0 * off_course;
        let spin = forces.angular_velocity().y;
        forces.apply_angular_acceleration(Vec3::Y * (buoyant.drag * rate + 8.0 * (rate - spin)));
        let speed = forces.linear_velocity().dot(heading);
        let push = buoyant.drag * BOAT_SPEED + 4.0 * (BOAT_SPEED - speed);
        let propeller = position + rotation * Vec3::new(-2.5, -0.3, 0.0);
        forces.apply_linear_acceleration_at_point(heading * push, propeller);
    }
}

/// A deck's heel and trim in degrees: its athwartships and fore-and-aft lines from the
/// horizontal, positive with the starboard side (+z) down and the bow (+x) up.
fn heel_and_trim(rotation: Quat) -> [f32; 2] {
    let rise = |axis: Vec3| (rotation * axis).y.clamp(-1.0, 1.0).asin().to_degrees();
    [-rise(Vec3::Z), rise(Vec3::X)]
}
