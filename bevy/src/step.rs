//! Creating surfaces for new [`Water`] entities, applying drops and forces, stepping.

use std::sync::Arc;

use bevy::asset::Assets;
use bevy::ecs::change_detection::Tick;
use bevy::ecs::prelude::*;
use bevy::ecs::system::{SystemChangeTick, SystemParam};
use bevy::log::info;
use bevy::mesh::{Mesh, Mesh3d};
use bevy::time::Time;
use bevy::transform::components::GlobalTransform;

use crate::buoyancy::Bodies;
use crate::jobs::TaskPoolJobs;
use crate::mesh::{bounds, new_mesh};
use crate::water::{
    report, Space, Water, WaterDisturbance, WaterDrop, WaterError, WaterForce, WaterSurface,
};

/// Set on a [`Water`] whose parameters were refused, with the tick of the refusal, so that
/// the error is reported once per change of the component rather than every frame.
#[derive(Component)]
pub(crate) struct WaterFailed(Tick);

/// Settings the plugin's systems read (from [`SpringwaterPlugin`](crate::SpringwaterPlugin)).
#[derive(Resource, Debug, Clone, Copy)]
pub(crate) struct SpringwaterSettings {
    pub task_pool: bool,
}

fn make_surface(
    water: &Water,
    settings: &SpringwaterSettings,
) -> springwater::Result<WaterSurface> {
    let mut surface = WaterSurface::new(water)?;
    if settings.task_pool {
        surface.surface.set_job_system(Some(Arc::new(TaskPoolJobs)));
    }
    Ok(surface)
}

/// What giving a water its surface takes: [`Installer::install`].
#[derive(SystemParam)]
pub(crate) struct Installer<'w, 's> {
    commands: Commands<'w, 's>,
    settings: Res<'w, SpringwaterSettings>,
    meshes: ResMut<'w, Assets<Mesh>>,
    errors: MessageWriter<'w, WaterError>,
    ticks: SystemChangeTick,
}

impl Installer<'_, '_> {
    /// Gives `entity` a surface and mesh for `water`, or marks it refused (with this run's
    /// tick).
    fn install(&mut self, entity: Entity, water: &Water) {
        match make_surface(water, &self.settings) {
            Ok(surface) => {
                let handle = self.meshes.add(new_mesh(&surface));
                self.commands
                    .entity(entity)
                    .remove::<WaterFailed>()
                    .try_insert((
                        Mesh3d(handle),
                        bounds(water, &surface.surface),
                        bevy::camera::visibility::NoAutoAabb,
                        surface,
                    ));
            }
            Err(e) => {
                report(&mut self.errors, entity, "water parameters refused", &e);
                let now = self.ticks.this_run();
                self.commands.entity(entity).try_insert(WaterFailed(now));
            }
        }
    }
}

/// Creates the surface and mesh of a water as soon as its [`Water`] is added (an observer:
/// the components arrive in the same command flush), so that the frame's systems never
/// wait for a command flush.
pub(crate) fn create_surface(
    add: On<Add, Water>,
    waters: Query<&Water, Without<WaterSurface>>,
    mut installer: Installer,
) {
    if let Ok(water) = waters.get(add.entity) {
        installer.install(add.entity, water);
    }
}

/// A water with no surface: refused (with the tick), or added before the plugin.
type WithoutSurface = (Entity, Ref<'static, Water>, Option<&'static WaterFailed>);

/// Tries again a water whose parameters were refused, once they changed (and creates the
/// surface of one added before the plugin). Runs in `PreUpdate`, away from the plugin's
/// sets, so that its commands need no flush among them: a water fixed in `Update` gets
/// its surface in the next frame's `PreUpdate` and steps in that frame.
pub(crate) fn retry_refused(
    waters: Query<WithoutSurface, Without<WaterSurface>>,
    mut installer: Installer,
) {
    let now = installer.ticks.this_run();
    for (entity, water, failed) in &waters {
        // Changed since it was refused (a tick, not a comparison: NaN never equals itself).
        if failed.is_none_or(|f| water.last_changed().is_newer_than(f.0, now)) {
            installer.install(entity, &water);
        }
    }
}

/// Restarts the surface of a water whose `Params` changed and rebuilds the LOD of one
/// whose `LodParams` changed, in place. (The bounding box follows in the mesh write.)
pub(crate) fn update_surfaces(
    mut bodies: ResMut<Bodies>,
    settings: Res<SpringwaterSettings>,
    mut changed: Query<(Entity, &Water, &mut WaterSurface), Changed<Water>>,
    mut errors: MessageWriter<WaterError>,
) {
    for (entity, water, mut surface) in &mut changed {
        if *surface.surface.params() != water.params {
            match make_surface(water, &settings) {
                Ok(fresh) => {
                    info!("springwater: parameters of {entity} changed, the surface starts over");
                    *surface = fresh;
                    bodies.forget_water(entity);
                }
                Err(e) => report(&mut errors, entity, "new water parameters refused", &e),
            }
        } else if *surface.lod.params() != water.lod {
            match springwater::mesh::LodMesh::new(water.lod) {
                Ok(lod) => surface.lod = lod,
                Err(e) => report(&mut errors, entity, "LOD parameters refused", &e),
            }
        }
    }
}

/// Applies [`WaterDrop`] and [`WaterForce`] messages.
pub(crate) fn apply_messages(
    mut drops: MessageReader<WaterDrop>,
    mut forces: MessageReader<WaterForce>,
    mut waters: Query<(Entity, &mut WaterSurface, &GlobalTransform)>,
    mut errors: MessageWriter<WaterError>,
) {
    if drops.is_empty() && forces.is_empty() {
        return;
    }
    let drops: Vec<WaterDrop> = drops.read().copied().collect();
    let forces: Vec<WaterForce> = forces.read().copied().collect();
    for (entity, mut ws, global) in &mut waters {
        let space = Space::new(global);
        let surface = &mut ws.surface;
        for d in &drops {
            let p = space.local_point(d.point);
            let hit = match d.water {
                Some(target) => target == entity,
                None => surface.contains(p.x, p.z),
            };
            if hit {
                if let Err(e) = surface.drop_at(p.x, p.z, d.height, d.radius) {
                    report(&mut errors, entity, "drop refused", &e);
                }
            }
        }
        for f in &forces {
            let p = space.local_point(f.point);
            let hit = match f.water {
                Some(target) => target == entity,
                None => surface.contains(p.x, p.z),
            };
            if hit {
                let v = space.local_vector(f.force);
                if let Err(e) = surface.add_force_at(p.x, p.z, v.to_array()) {
                    report(&mut errors, entity, "force refused", &e);
                }
            }
        }
    }
}

/// Advances every water by the schedule's `Time` delta (the frame's seconds in
/// `PostUpdate`, the fixed timestep in a fixed schedule).
pub(crate) fn step_surfaces(
    time: Res<Time>,
    mut waters: Query<(
        Entity,
        &Water,
        &mut WaterSurface,
        Option<&mut WaterDisturbance>,
    )>,
    mut errors: MessageWriter<WaterError>,
) {
    let seconds = time.delta_secs();
    for (entity, water, mut ws, disturbance) in &mut waters {
        if water.paused {
            ws.substeps = 0;
            continue;
        }
        let WaterSurface {
            surface, pushes, ..
        } = &mut *ws;
        let result = match disturbance {
            Some(mut d) => surface.advance_with(seconds, &mut (&mut *pushes, &mut *d.0)),
            None if pushes.0.is_empty() => surface.advance(seconds),
            None => surface.advance_with(seconds, pushes),
        };
        match result {
            Ok(n) => ws.substeps = n,
            Err(e) => {
                ws.substeps = 0;
                ws.surface.clear_forces();
                report(&mut errors, entity, "step failed", &e);
            }
        }
    }
}
