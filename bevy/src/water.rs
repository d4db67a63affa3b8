//! The water's components and messages: what a game spawns ([`Water`]), what the plugin
//! adds ([`WaterSurface`]), and how other systems disturb it ([`WaterDrop`], [`WaterForce`],
//! [`WaterDisturbance`]) or hear of its failures ([`WaterError`]).

use bevy::ecs::prelude::*;
use bevy::log::error;
use bevy::math::{Affine3A, Vec3};
use bevy::transform::components::{GlobalTransform, Transform};
use springwater::disturb::Disturbance;
use springwater::mesh::{LodMesh, LodParams};
use springwater::refraction::RefractionParams;
use springwater::{FloaterId, Params, Surface};

/// A water surface. Spawn it with a [`Transform`]; the plugin creates its
/// [`springwater::Surface`] ([`WaterSurface`]) and its mesh ([`Mesh3d`](bevy::mesh::Mesh3d))
/// as soon as the component is added (the same command flush), or sends a [`WaterError`]
/// and tries again when the parameters change.
///
/// The water's local space is springwater's water frame: node `(col, row)` rests at
/// `(col·spacing, 0, row·spacing)`, y up, so the pool covers `[0, (cols−1)·spacing] ×
/// [0, (rows−1)·spacing]` from the entity's origin. Translate the entity to place it.
/// When the window moves ([`WaterFollow`](crate::WaterFollow), or
/// [`Surface::shift`](springwater::Surface::shift) through [`WaterSurface::surface_mut`])
/// the footprint starts at [`Surface::origin`](springwater::Surface::origin) instead; the
/// entity stays where it is.
///
/// Changing `params` later starts the surface over (flat, at rest); changing `lod` rebuilds
/// the index buffer; `refraction` is read every frame.
#[derive(Component, Debug, Clone, PartialEq)]
#[require(Transform)]
pub struct Water {
    /// The model: grid size, spacing, mass, stiffness, damping, timestep, time scale.
    pub params: Params,
    /// Level of detail of the index buffer around the active camera.
    pub lod: LodParams,
    /// The pool's flat bottom (depth below the rest surface) and the index of refraction,
    /// for the bottom texture coordinates written to `UV_0`.
    pub refraction: RefractionParams,
    /// How far above and below the rest surface the mesh's bounding box reaches, in world
    /// units of the water's local space (default: 8). The plugin sets the box once instead
    /// of letting Bevy recompute it from every vertex each frame; waves taller than this
    /// may be culled at the screen's edge.
    pub bounds_height: f32,
    /// When true the surface is not stepped (the mesh is still written).
    pub paused: bool,
}

impl Default for Water {
    fn default() -> Self {
        Self::new(Params::default())
    }
}

impl Water {
    /// Water with these model parameters and default LOD, refraction and bounds.
    pub fn new(params: Params) -> Self {
        Self {
            params,
            lod: LodParams::default(),
            refraction: RefractionParams::default(),
            bounds_height: 8.0,
            paused: false,
        }
    }

    /// The seed's model on a `cols × rows` grid (spacing 1).
    pub fn with_size(cols: usize, rows: usize) -> Self {
        Self::new(Params::with_size(cols, rows))
    }

    /// Sets the bottom depth (world units below the rest surface).
    pub fn with_depth(mut self, depth: f32) -> Self {
        self.refraction.depth = depth;
        self
    }

    /// Sets the LOD parameters.
    pub fn with_lod(mut self, lod: LodParams) -> Self {
        self.lod = lod;
        self
    }
}

/// The simulated surface of a [`Water`] entity and the LOD state of its mesh, added by
/// the plugin. Game code that wants springwater's whole API (snapshots, pinning,
/// energy, per-node forces) queries `&mut WaterSurface` and calls [`WaterSurface::surface_mut`].
#[derive(Component)]
pub struct WaterSurface {
    pub(crate) surface: Surface,
    pub(crate) lod: LodMesh,
    pub(crate) substeps: usize,
    /// The frame's forces on floating bodies, applied before every substep.
    pub(crate) pushes: Pushes,
}

impl WaterSurface {
    pub(crate) fn new(water: &Water) -> springwater::Result<Self> {
        Ok(Self {
            surface: Surface::new(water.params)?,
            lod: LodMesh::new(water.lod)?,
            substeps: 0,
            pushes: Default::default(),
        })
    }

    /// The simulation.
    pub fn surface(&self) -> &Surface {
        &self.surface
    }

    /// The simulation, mutably: drops, forces, pinning, snapshots, anything of
    /// [`springwater::Surface`]'s API, in the water's local space.
    pub fn surface_mut(&mut self) -> &mut Surface {
        &mut self.surface
    }

    /// The LOD index buffer the mesh was last given.
    pub fn lod(&self) -> &LodMesh {
        &self.lod
    }

    /// Substeps the last frame took (0 when paused or the frame was 0 s).
    pub fn last_substeps(&self) -> usize {
        self.substeps
    }
}

/// A disturbance applied before every substep of a water's step (see
/// [`springwater::Surface::advance_with`]): [`springwater::disturb::Rain`], a
/// [`springwater::disturb::Wake`], a tuple of them, or a game's own.
#[derive(Component)]
pub struct WaterDisturbance(pub Box<dyn Disturbance + Send + Sync>);

impl WaterDisturbance {
    /// Wraps a disturbance.
    pub fn new(disturbance: impl Disturbance + Send + Sync + 'static) -> Self {
        Self(Box::new(disturbance))
    }
}

/// Marks the entity whose [`GlobalTransform`] is the eye for the water's LOD and
/// refraction. Without one, the plugin uses the active camera of lowest order, and
/// without a camera a point above the middle of each pool.
#[derive(Component, Debug, Clone, Copy, Default)]
pub struct WaterViewer;

/// A drop on the water at a world point: `height` (negative: a dent) and `radius` in
/// world units of the water's local space, as in [`springwater::Surface::drop_at`].
/// Applied in [`WaterSystems::SyncInputs`](crate::WaterSystems::SyncInputs) to `water`,
/// or to every water whose footprint holds the point when `water` is `None`.
#[derive(Message, Debug, Clone, Copy, PartialEq)]
pub struct WaterDrop {
    /// Target water entity, or `None` for every water under the point.
    pub water: Option<Entity>,
    /// World point; only its projection onto the water's plane matters.
    pub point: Vec3,
    /// Height of the drop (negative: a dent).
    pub height: f32,
    /// Radius of the drop.
    pub radius: f32,
}

/// A force on the water at a world point for the next step, spread onto the four nodes
/// around it ([`springwater::Surface::add_force_at`]). `force` is a world vector,
/// turned into the water's local space, in the lattice's force units (mass units × world
/// units per unit of model time²: a force of `F` per second² is `F / time_scale²`; see the
/// library's `docs/units.md`).
#[derive(Message, Debug, Clone, Copy, PartialEq)]
pub struct WaterForce {
    /// Target water entity, or `None` for every water under the point.
    pub water: Option<Entity>,
    /// World point.
    pub point: Vec3,
    /// World force, in the lattice's force units.
    pub force: Vec3,
}

/// Something failed on a water entity: its parameters were refused, a step went
/// non-finite (the surface is then unchanged and its pending forces are cleared), or a
/// mesh write failed. Also logged with `error!`.
#[derive(Message, Debug, Clone)]
pub struct WaterError {
    /// The water entity.
    pub water: Entity,
    /// springwater's message.
    pub message: String,
}

/// World ↔ water-local transforms of one water entity.
#[derive(Debug, Clone, Copy)]
pub(crate) struct Space {
    pub to_local: Affine3A,
    pub to_world: Affine3A,
}

impl Space {
    pub fn new(global: &GlobalTransform) -> Self {
        let to_world = global.affine();
        Self {
            to_local: to_world.inverse(),
            to_world,
        }
    }

    pub fn local_point(&self, p: Vec3) -> Vec3 {
        self.to_local.transform_point3(p)
    }

    pub fn local_vector(&self, v: Vec3) -> Vec3 {
        self.to_local.transform_vector3(v)
    }

    pub fn world_point(&self, p: Vec3) -> Vec3 {
        self.to_world.transform_point3(p)
    }

    pub fn world_vector(&self, v: Vec3) -> Vec3 {
        self.to_world.transform_vector3(v)
    }

    /// The rotation from world to the water's local axes (the water's transform's
    /// rotation, inverted; its scale left out).
    pub fn local_rotation(&self) -> bevy::math::Quat {
        self.to_local.to_scale_rotation_translation().1
    }

    /// A world direction (a normal): the inverse transpose, normalised.
    pub fn world_normal(&self, n: Vec3) -> Vec3 {
        self.to_local
            .matrix3
            .transpose()
            .mul_vec3a(n.into())
            .normalize_or_zero()
            .into()
    }
}

/// The external forces of the frame on a water's floating bodies (the [`Buoyant`]
/// components' `force`, in the water's local space, per second²), filled by the
/// buoyancy sync and applied before every substep of the step.
///
/// [`Buoyant`]: crate::Buoyant
#[derive(Debug, Default)]
pub(crate) struct Pushes(pub Vec<(FloaterId, springwater::glam::Vec3, springwater::glam::Vec3)>);

impl Disturbance for Pushes {
    fn apply(&mut self, surface: &mut Surface, _dt: f32) -> springwater::Result<()> {
        for &(id, force, torque) in &self.0 {
            surface.push_floater(id, force)?;
            surface.push_floater_torque(id, torque)?;
        }
        Ok(())
    }
}

/// Logs a failure on `water` and sends it as a [`WaterError`]: the one way the plugin's
/// systems report errors.
pub(crate) fn report(
    errors: &mut MessageWriter<WaterError>,
    water: Entity,
    what: &str,
    e: &dyn std::fmt::Display,
) {
    error!("springwater: {what} on {water}: {e}");
    errors.write(WaterError {
        water,
        message: format!("{what}: {e}"),
    });
}
