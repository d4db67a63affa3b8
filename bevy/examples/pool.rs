//! A pool in the rain: a tiled bottom seen through the water (refracted `UV_0`), a ball
//! floating on it, an orbit camera.
//!
//! `cargo run --release -p springwater-bevy --example pool --features example`
//!
//! Drag with the left mouse button to orbit, scroll to zoom, arrows or WASD push the
//! ball, space drops a splash under the ball, R toggles the rain, F makes the water's
//! window follow the ball (a [`WaterFollow`] on it; the camera follows too) out of the
//! pool and across an open sea of the same tiles.
//!
//! `SPRINGWATER_SCREENSHOT=pool.png` runs on a fixed 1/60 s clock instead, saves the
//! window after `SPRINGWATER_SCREENSHOT_FRAME` frames (default 180) and exits: the
//! picture in the README was made so, under Xvfb with Mesa's software Vulkan.
//! `SPRINGWATER_FOLLOW=1` as well makes the second one: the window follows the ball from
//! the start, and the ball cruises to the right at twice the ripple speed with 30 times
//! the gravity, so that it dents the water enough for its wake to show (no rain, no deck,
//! the camera further back).

use bevy::asset::RenderAssetUsages;
use bevy::image::{ImageAddressMode, ImageSampler, ImageSamplerDescriptor};
use bevy::input::mouse::{AccumulatedMouseMotion, AccumulatedMouseScroll};
use bevy::prelude::*;
use bevy::render::render_resource::{Extent3d, TextureDimension, TextureFormat};
use bevy::render::view::screenshot::{save_to_disk, Screenshot, ScreenshotCaptured};
use bevy::time::TimeUpdateStrategy;
use springwater::disturb::{Disturbance, Rain};
use springwater_bevy::prelude::*;

const COLS: usize = 129;
const ROWS: usize = 97;
/// Rain drops per second.
const RAIN: f32 = 7.2;

fn main() {
    let mut app = App::new();
    app.add_plugins((DefaultPlugins, SpringwaterPlugin::default()))
        .insert_resource(ClearColor(Color::srgb(0.55, 0.7, 0.85)))
        .add_systems(Startup, setup)
        .add_systems(Update, (orbit_camera, push_ball, toggle_rain, follow_ball));
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
            let gravity = 30.0 * BuoyancySettings::default().gravity;
            app.insert_resource(Cruise)
                .insert_resource(BuoyancySettings {
                    gravity,
                    ..default()
                })
                .add_systems(Update, cruise);
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

fn screenshot(mut frames: Local<u32>, at: Res<ScreenshotAt>, mut commands: Commands) {
    *frames += 1;
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
    mut balls: Query<(Entity, &mut Buoyant, Has<WaterFollow>), With<Ball>>,
    mut commands: Commands,
) {
    let Ok(camera) = cameras.single() else {
        return;
    };
    let right = (camera.right().as_vec3() * Vec3::new(1.0, 0.0, 1.0)).normalize_or_zero();
    for (ball, mut buoyant, following) in &mut balls {
        if !following {
            commands.entity(ball).insert(WaterFollow::default());
        }
        let push = right * buoyant.mass * 500.0;
        buoyant.force += push;
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

/// Orbit state of the camera: around `focus`, at `distance`, `yaw` and `pitch` radians.
#[derive(Component)]
struct Orbit {
    focus: Vec3,
    distance: f32,
    yaw: f32,
    pitch: f32,
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
    buoyancy: Res<BuoyancySettings>,
    cruise: Option<Res<Cruise>>,
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
    // The ball: half as dense as the water.
    commands.spawn((
        Ball,
        Buoyant::sphere(2.5, 0.5, &buoyancy),
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
            Transform::from_translation((min + max) / 2.0),
            if cruising {
                Visibility::Hidden
            } else {
                Visibility::Inherited
            },
        ));
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
        Orbit {
            focus: Vec3::new(-4.0, 0.0, 0.0),
            distance,
            yaw: 0.6,
            pitch,
        },
    ));
}

/// The ball while the water follows it (never the camera).
type FollowedBall = (With<Ball>, With<WaterFollow>, Without<Camera3d>);

fn orbit_camera(
    buttons: Res<ButtonInput<MouseButton>>,
    motion: Res<AccumulatedMouseMotion>,
    scroll: Res<AccumulatedMouseScroll>,
    mut cameras: Query<(&mut Orbit, &mut Transform), With<Camera3d>>,
    followed: Query<&Transform, FollowedBall>,
) {
    for (mut orbit, mut transform) in &mut cameras {
        if let Ok(ball) = followed.single() {
            orbit.focus = ball.translation.with_y(0.0);
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
    mut balls: Query<(&mut Buoyant, &Transform), With<Ball>>,
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
    for (mut ball, transform) in &mut balls {
        let push = dir * ball.mass * 12.0;
        ball.force += push;
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

/// F: the water's window follows the ball (or stops following it).
fn follow_ball(
    keys: Res<ButtonInput<KeyCode>>,
    balls: Query<(Entity, Has<WaterFollow>), With<Ball>>,
    mut commands: Commands,
) {
    if keys.just_pressed(KeyCode::KeyF) {
        for (ball, following) in &balls {
            if following {
                commands.entity(ball).remove::<WaterFollow>();
            } else {
                commands.entity(ball).insert(WaterFollow::default());
            }
        }
    }
}
