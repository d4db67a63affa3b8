//! The water's [`Mesh`]: positions, normals and refracted bottom coordinates written in
//! place every frame, indices replaced only when the LOD changes.

use bevy::asset::{Assets, RenderAssetUsages};
use bevy::camera::primitives::Aabb;
use bevy::camera::Camera;
use bevy::ecs::prelude::*;
use bevy::math::Vec3;
use bevy::mesh::{
    Indices, Mesh, Mesh3d, MeshVertexAttribute, PrimitiveTopology, VertexAttributeValues,
};
use bevy::transform::components::GlobalTransform;
use springwater::buffers::{fill_frame, VertexBuffers};
use springwater::refraction::RefractionParams;
use springwater::Surface;

use crate::water::{report, Space, Water, WaterError, WaterSurface, WaterViewer};

/// The eye a water is seen from when there is neither a [`WaterViewer`] nor a camera:
/// above the middle of the window, as high as the window is wide.
fn default_eye(ws: &WaterSurface) -> Vec3 {
    let [w, d] = ws.surface.mesh_view().extent();
    let [x, z] = ws.surface.origin();
    Vec3::new(x + w * 0.5, w.max(d), z + d * 0.5)
}

/// The bounding box the plugin gives a water entity: the window's rest footprint (it moves
/// with [`Surface::origin`]), one cell wider on every side (the lattice moves sideways a
/// little), `bounds_height` above and below the rest surface, and down to the bottom.
pub(crate) fn bounds(water: &Water, surface: &Surface) -> Aabb {
    let h = surface.params().spacing;
    let [w, d] = surface.mesh_view().extent();
    let [x, z] = surface.origin();
    let up = water.bounds_height.max(0.0);
    let down = up.max(water.refraction.depth);
    Aabb::from_min_max(
        Vec3::new(x - h, -down, z - h),
        Vec3::new(x + w + h, up, z + d + h),
    )
}

/// A new mesh for a surface: every attribute at its final length, the first LOD.
pub(crate) fn new_mesh(ws: &WaterSurface) -> Mesh {
    let n = ws.surface.node_count();
    let mut mesh = Mesh::new(
        PrimitiveTopology::TriangleList,
        // Both worlds: the main world keeps the data so that it can be written in place
        // every frame after the render world has extracted it.
        RenderAssetUsages::MAIN_WORLD | RenderAssetUsages::RENDER_WORLD,
    );
    mesh.insert_attribute(Mesh::ATTRIBUTE_POSITION, vec![[0.0f32; 3]; n]);
    mesh.insert_attribute(Mesh::ATTRIBUTE_NORMAL, vec![[0.0f32, 1.0, 0.0]; n]);
    mesh.insert_attribute(Mesh::ATTRIBUTE_UV_0, vec![[0.0f32; 2]; n]);
    let mut lod = springwater::mesh::LodMesh::new(*ws.lod.params())
        .expect("parameters already validated by the surface's own LodMesh");
    lod.update(&ws.surface.mesh_view(), default_eye(ws).to_array().into());
    mesh.insert_indices(Indices::U32(lod.indices().to_vec()));
    mesh
}

/// The eye in world space: the first [`WaterViewer`], else the active camera of lowest
/// order.
fn world_eye(
    viewers: &Query<&GlobalTransform, With<WaterViewer>>,
    cameras: &Query<(&Camera, &GlobalTransform)>,
) -> Option<Vec3> {
    if let Some(v) = viewers.iter().next() {
        return Some(v.translation());
    }
    cameras
        .iter()
        .filter(|(c, _)| c.is_active)
        .min_by_key(|(c, _)| c.order)
        .map(|(_, t)| t.translation())
}

/// Takes an attribute's vector out of the mesh (leaving an empty one), so that several
/// attributes can be filled in one pass and put back without reallocating.
fn take<T>(
    mesh: &mut Mesh,
    attribute: MeshVertexAttribute,
    get: fn(&mut VertexAttributeValues) -> Option<&mut Vec<T>>,
) -> Result<Vec<T>, String> {
    match mesh.try_attribute_mut_option(attribute) {
        Ok(Some(values)) => Ok(get(values).map(std::mem::take).unwrap_or_default()),
        Ok(None) => Ok(Vec::new()),
        Err(e) => Err(e.to_string()),
    }
}

fn f32x3(v: &mut VertexAttributeValues) -> Option<&mut Vec<[f32; 3]>> {
    match v {
        VertexAttributeValues::Float32x3(v) => Some(v),
        _ => None,
    }
}

fn f32x2(v: &mut VertexAttributeValues) -> Option<&mut Vec<[f32; 2]>> {
    match v {
        VertexAttributeValues::Float32x2(v) => Some(v),
        _ => None,
    }
}

/// Writes one water's mesh: positions, and normals and refraction coordinates seen from
/// `eye`, straight into the attributes in one pass (springwater's `fill_frame`), in place
/// (the vectors keep their allocations); the indices only when `indices` is given.
fn write_mesh(
    mesh: &mut Mesh,
    surface: &Surface,
    (eye, refraction): (Vec3, &RefractionParams),
    indices: Option<&[u32]>,
) -> Result<(), String> {
    // The indices first: the LOD has moved on, whatever happens to the attributes.
    if let Some(indices) = indices {
        match mesh.try_indices_mut() {
            Ok(Indices::U32(v)) => {
                v.clear();
                v.extend_from_slice(indices);
            }
            _ => mesh
                .try_insert_indices(Indices::U32(indices.to_vec()))
                .map_err(|e| e.to_string())?,
        }
    }
    let n = surface.node_count();
    let mut positions = take(mesh, Mesh::ATTRIBUTE_POSITION, f32x3)?;
    let mut normals = take(mesh, Mesh::ATTRIBUTE_NORMAL, f32x3)?;
    let mut uvs = take(mesh, Mesh::ATTRIBUTE_UV_0, f32x2)?;
    // Same length every frame: no reallocation (only when the grid size changes).
    positions.resize(n, [0.0; 3]);
    normals.resize(n, [0.0; 3]);
    uvs.resize(n, [0.0; 2]);
    let written = fill_frame(
        &surface.mesh_view(),
        eye.to_array().into(),
        refraction,
        VertexBuffers {
            positions: Some(&mut positions),
            normals: Some(&mut normals),
            uvs: Some(&mut uvs),
            vertices: None,
        },
    );
    // Put the vectors back even if that failed (then they hold last frame's data).
    let put = mesh
        .try_insert_attribute(Mesh::ATTRIBUTE_POSITION, positions)
        .and_then(|()| mesh.try_insert_attribute(Mesh::ATTRIBUTE_NORMAL, normals))
        .and_then(|()| mesh.try_insert_attribute(Mesh::ATTRIBUTE_UV_0, uvs));
    written.map_err(|e| e.to_string())?;
    put.map_err(|e| e.to_string())
}

/// A water's mesh and what the plugin keeps in step with it.
type MeshOf = (
    Entity,
    &'static Water,
    &'static mut WaterSurface,
    &'static Mesh3d,
    &'static GlobalTransform,
    Option<&'static mut Aabb>,
);

/// Normals, refraction, LOD and the mesh write of every water, from the eye in each
/// water's local space; the bounding box follows the surface (its size, and the window's
/// place when it moved).
pub(crate) fn write_meshes(
    mut meshes: ResMut<Assets<Mesh>>,
    viewers: Query<&GlobalTransform, With<WaterViewer>>,
    cameras: Query<(&Camera, &GlobalTransform)>,
    mut waters: Query<MeshOf>,
    mut errors: MessageWriter<WaterError>,
) {
    let eye = world_eye(&viewers, &cameras);
    for (entity, water, mut ws, mesh3d, global, aabb) in &mut waters {
        let ws = &mut *ws;
        if let Some(mut aabb) = aabb {
            aabb.set_if_neq(bounds(water, &ws.surface));
        }
        let local_eye = match eye {
            Some(e) => Space::new(global).local_point(e),
            None => default_eye(ws),
        };
        let WaterSurface { surface, lod, .. } = ws;
        let lod_changed = lod.update(&surface.mesh_view(), local_eye.to_array().into());
        let Some(mut mesh) = meshes.get_mut(&mesh3d.0) else {
            continue;
        };
        let indices = lod_changed.then(|| lod.indices());
        let frame = (local_eye, &water.refraction);
        if let Err(e) = write_mesh(&mut mesh, surface, frame, indices) {
            report(&mut errors, entity, "mesh write failed", &e);
        }
    }
}
