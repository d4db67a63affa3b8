//! The headless app of the tests (MinimalPlugins, assets, meshes, transforms and a manual
//! clock of 1/60 s per update), and running it and reading its water's mesh.

use std::time::Duration;

use bevy::asset::AssetPlugin;
use bevy::mesh::{Mesh3d, MeshPlugin, VertexAttributeValues};
use bevy::prelude::*;
use bevy::time::TimeUpdateStrategy;
use bevy::transform::TransformPlugin;
use springwater_bevy::prelude::SpringwaterPlugin;

/// The app of the tests without the plugin.
pub fn bare_app() -> App {
    let mut app = App::new();
    app.add_plugins((
        MinimalPlugins,
        AssetPlugin::default(),
        MeshPlugin,
        TransformPlugin,
    ))
    .insert_resource(TimeUpdateStrategy::ManualDuration(Duration::from_secs_f32(
        1.0 / 60.0,
    )));
    app
}

// Each test binary uses some of what follows.

/// The app of the tests with `plugin`.
#[allow(dead_code)]
pub fn app(plugin: SpringwaterPlugin) -> App {
    let mut app = bare_app();
    app.add_plugins(plugin);
    app
}

/// `frames` updates of `app`.
#[allow(dead_code)]
pub fn run(app: &mut App, frames: usize) {
    for _ in 0..frames {
        app.update();
    }
}

/// A copy of the mesh of the water entity `water`.
#[allow(dead_code)]
pub fn mesh_of(app: &App, water: Entity) -> Mesh {
    let handle = &app
        .world()
        .get::<Mesh3d>(water)
        .expect("water has a mesh")
        .0;
    app.world()
        .resource::<Assets<Mesh>>()
        .get(handle)
        .expect("mesh asset exists")
        .clone()
}

/// The vertex positions of `mesh`.
#[allow(dead_code)]
pub fn positions(mesh: &Mesh) -> &Vec<[f32; 3]> {
    match mesh.attribute(Mesh::ATTRIBUTE_POSITION) {
        Some(VertexAttributeValues::Float32x3(v)) => v,
        other => panic!("positions: {other:?}"),
    }
}
