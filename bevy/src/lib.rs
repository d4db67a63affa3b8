//! # springwater-bevy
//!
//! A [Bevy](https://bevy.org) plugin for [`springwater`]: a water surface simulated on the
//! CPU as a mass-spring lattice, drawn as a [`Mesh3d`](bevy::mesh::Mesh3d) whose
//! positions, normals and refracted bottom coordinates (`UV_0`) are rewritten in place
//! every frame, with a view-dependent LOD index buffer, point queries, drops and forces
//! from game systems, two-way buoyancy, and a window that follows a camera or a ship
//! across an open sea.
//!
//! The plugin is a thin layer: the physics, LOD, refraction, interleaving and queries are
//! springwater's own, called once per frame.
//!
//! ```no_run
//! use bevy::prelude::*;
//! use springwater_bevy::prelude::*;
//!
//! fn main() {
//!     App::new()
//!         .add_plugins((DefaultPlugins, SpringwaterPlugin::default()))
//!         .add_systems(Startup, |mut commands: Commands| {
//!             // A 128 × 128 pool of spacing 1 from the origin; add a material to see it:
//!             // MeshMaterial3d(materials.add(StandardMaterial { base_color_texture: Some(tiles), .. }))
//!             commands.spawn(Water::with_size(129, 129).with_depth(4.0));
//!         })
//!         .add_systems(Update, |mut drops: MessageWriter<WaterDrop>| {
//!             drops.write(WaterDrop { water: None, point: Vec3::new(64.0, 0.0, 64.0), height: -1.0, radius: 3.0 });
//!         })
//!         .run();
//! }
//! ```
//!
//! (`DefaultPlugins` needs Bevy's default features; this crate itself depends on Bevy with
//! `default-features = false` and only the ECS, assets, meshes, camera types, transforms,
//! time and task pools.)
//!
//! ## What runs when
//!
//! [`SpringwaterPlugin`] adds its systems to one schedule (`PostUpdate` by default, before
//! transform propagation; or a fixed-timestep schedule with
//! [`SpringwaterPlugin::in_fixed_schedule`]), in three chained sets, [`WaterSystems`]. A
//! new [`Water`] gets its [`springwater::Surface`] and mesh before that, from an observer,
//! in the command flush that adds the component (a water whose parameters were refused is
//! tried again in `PreUpdate` once they change). The sets make no structural change, so
//! none of their systems needs a command flush after it (an exclusive system: a hand-over
//! to the main thread and back).
//!
//! 1. [`WaterSystems::SyncInputs`]: restarts surfaces whose `Params` changed, moves
//!    the windows of waters with a [`WaterFollow`] entity, applies [`WaterDrop`]
//!    and [`WaterForce`] messages, hands every [`Buoyant`] body's state to its water
//!    (springwater's floating bodies, which step with the water and push back on it).
//! 2. [`WaterSystems::Step`]: [`springwater::Surface::advance`] (or `advance_with` a
//!    [`WaterDisturbance`]) by the schedule's `Time` delta, on Bevy's compute task pool
//!    ([`TaskPoolJobs`]).
//! 3. [`WaterSystems::Writeback`]: normals and refraction from the eye (a [`WaterViewer`],
//!    else the active camera), the LOD, and the mesh attributes written in place, on the
//!    same pool (the bounding box follows the window); the bodies' `Transform`s and
//!    velocities from their water.
//!
//! Game systems that read the water ([`WaterQuery`]) see the state of the last frame's
//! step; drops and forces land before the next one. The eye, the followers and the
//! water's `GlobalTransform` are read before this frame's transform propagation (one
//! frame late if they moved).
//!
//! For rollback netcode (feature `ggrs`), [`SpringwaterPlugin::with_rollback`] runs the
//! first two sets and the bodies' write-back in bevy_ggrs's `GgrsSchedule`, the mesh
//! write in `PostUpdate`, and registers every water and body for rollback through
//! springwater's own saves, restores and state hashes: see the `rollback` module.
//!
//! For Avian's rigid bodies (feature `avian`), `SpringwaterPlugin::with_avian` runs the
//! sets in `FixedPostUpdate` after Avian's step, and pushes every `AvianBuoyant` body
//! before it, with the tick Avian takes and Avian's gravity: see the `avian` module.
//!
//! Errors (refused parameters, a step that would go non-finite) never panic: they are
//! logged and sent as [`WaterError`] messages.
//!
//! ## Layers
//!
//! The modules' arrows run one way. `water` is the bottom: the components, the messages,
//! world ↔ local transforms (`Space`), the frame's pushes on floating bodies and
//! `report` (the one way errors leave); it uses no other module. `jobs` stands alone.
//! `buoyancy`, `follow`, `mesh` and `query` use `water` only; `avian` (feature `avian`) uses
//! `water` and `buoyancy`. `step` (surfaces for new
//! waters, messages, the step itself, and the plugin's settings) uses `water`, `mesh`,
//! `buoyancy` and `jobs`. `rollback` (feature `ggrs`) uses `water` and `buoyancy`, and with
//! feature `avian` the `AvianBuoyant` component. This file uses them all to wire the
//! plugin, and nothing uses it.

#![warn(missing_docs)]

#[cfg(feature = "avian")]
pub mod avian;
mod buoyancy;
mod follow;
mod jobs;
mod mesh;
mod query;
#[cfg(feature = "ggrs")]
pub mod rollback;
mod step;
mod water;

use bevy::app::{App, FixedPostUpdate, Plugin, PostUpdate, PreUpdate};
use bevy::ecs::intern::Interned;
use bevy::ecs::prelude::*;
use bevy::ecs::schedule::ScheduleLabel;
use bevy::transform::TransformSystems;

pub use buoyancy::{BuoyancySettings, Buoyant};
pub use follow::WaterFollow;
pub use jobs::TaskPoolJobs;
pub use query::{WaterQuery, WaterQueryError, WaterQueryMut, WaterSample};
pub use water::{
    Water, WaterDisturbance, WaterDrop, WaterError, WaterForce, WaterSurface, WaterViewer,
};

#[cfg(feature = "avian")]
pub use avian::AvianBuoyant;
/// Re-exported so that a game needs no direct dependency on the library.
pub use springwater;

/// Everything a game usually names.
pub mod prelude {
    pub use crate::{
        BuoyancySettings, Buoyant, SpringwaterPlugin, Water, WaterDisturbance, WaterDrop,
        WaterError, WaterFollow, WaterForce, WaterQuery, WaterQueryMut, WaterSample, WaterSurface,
        WaterSystems, WaterViewer,
    };

    #[cfg(feature = "avian")]
    pub use crate::AvianBuoyant;
}

/// The plugin's system sets, run in this order in the plugin's schedule.
#[derive(SystemSet, Debug, Clone, Copy, PartialEq, Eq, Hash)]
pub enum WaterSystems {
    /// Parameter changes, windows following their [`WaterFollow`], drops and forces,
    /// buoyancy.
    SyncInputs,
    /// Advancing every surface by the frame's seconds.
    Step,
    /// Normals, refraction, LOD, the mesh write and the bodies' transforms (under
    /// rollback, the mesh write is in `PostUpdate` and the bodies' in `GgrsSchedule`).
    Writeback,
}

/// Adds water simulation to an app. See the [crate docs](crate).
///
/// ```
/// use bevy::app::FixedUpdate;
/// use springwater_bevy::SpringwaterPlugin;
///
/// let default = SpringwaterPlugin::default();                  // PostUpdate, task pool
/// let fixed = SpringwaterPlugin::default().in_fixed_schedule(); // FixedPostUpdate
/// let custom = SpringwaterPlugin::default().in_schedule(FixedUpdate).with_task_pool(false);
/// ```
#[derive(Debug, Clone)]
pub struct SpringwaterPlugin {
    schedule: Interned<dyn ScheduleLabel>,
    task_pool: bool,
    /// Registered for bevy_ggrs's rollback, the mesh written in `PostUpdate`.
    rollback: bool,
    /// Pushes Avian's [`AvianBuoyant`] bodies.
    #[cfg(feature = "avian")]
    avian: bool,
}

impl Default for SpringwaterPlugin {
    /// `PostUpdate`, before transform propagation, stepping on Bevy's compute task pool.
    fn default() -> Self {
        Self {
            schedule: PostUpdate.intern(),
            task_pool: true,
            rollback: false,
            #[cfg(feature = "avian")]
            avian: false,
        }
    }
}

impl SpringwaterPlugin {
    /// Runs the plugin's systems in `schedule` instead of `PostUpdate`. In a fixed-timestep
    /// schedule, `Time` is the fixed clock and each run steps by the fixed timestep.
    pub fn in_schedule(mut self, schedule: impl ScheduleLabel) -> Self {
        self.schedule = schedule.intern();
        self
    }

    /// Runs in `FixedPostUpdate`: the water steps by `Time<Fixed>`'s timestep, as often as
    /// the fixed clock asks (a deterministic clock, independent of the frame rate).
    pub fn in_fixed_schedule(self) -> Self {
        self.in_schedule(FixedPostUpdate)
    }

    /// Rollback with bevy_ggrs (feature `ggrs`): runs the simulation in
    /// [`GgrsSchedule`](bevy_ggrs::GgrsSchedule), saves every water and [`Buoyant`] body
    /// when bevy_ggrs saves a frame and puts them back when it loads one (springwater's
    /// [`save_into`](springwater::Surface::save_into) and
    /// [`restore`](springwater::Surface::restore)), and gives bevy_ggrs the surfaces'
    /// [`state_hash`](springwater::Surface::state_hash) as their checksum; the mesh is
    /// written in `PostUpdate`, once per rendered frame. See the [`rollback`] module.
    #[cfg(feature = "ggrs")]
    pub fn with_rollback(mut self) -> Self {
        self.rollback = true;
        self.in_schedule(bevy_ggrs::GgrsSchedule)
    }

    /// Buoyancy for Avian's rigid bodies (feature `avian`): runs in `FixedPostUpdate`, the
    /// schedule of Avian's `PhysicsPlugins::default()`, and pushes every [`AvianBuoyant`]
    /// body before Avian's step; the water steps after it by the same fixed timestep, with
    /// Avian's gravity. Keep Avian in `FixedPostUpdate`. `Time<Physics>` at a relative
    /// speed other than 1 scales the bodies' tick (their forces are taken over it) but not
    /// the water's, whose waves keep the fixed timestep's pace. See the [`avian`] module.
    ///
    /// With [`with_rollback`](Self::with_rollback) too (in either order), everything runs
    /// in bevy_ggrs's `GgrsSchedule` instead, and so must Avian
    /// (`PhysicsPlugins::new(GgrsSchedule)`); the game registers Avian's own components
    /// for rollback (see the [`rollback`] module).
    #[cfg(feature = "avian")]
    pub fn with_avian(mut self) -> Self {
        self.avian = true;
        match self.rollback {
            true => self,
            false => self.in_fixed_schedule(),
        }
    }

    /// Whether surfaces step on Bevy's `ComputeTaskPool` ([`TaskPoolJobs`], the default)
    /// or, when false, on rayon's global pool. The results are the same bits either way.
    pub fn with_task_pool(mut self, on: bool) -> Self {
        self.task_pool = on;
        self
    }
}

impl Plugin for SpringwaterPlugin {
    fn build(&self, app: &mut App) {
        app.insert_resource(step::SpringwaterSettings {
            task_pool: self.task_pool,
        })
        .init_resource::<BuoyancySettings>()
        .init_resource::<buoyancy::Bodies>()
        .add_message::<WaterDrop>()
        .add_message::<WaterForce>()
        .add_message::<WaterError>();

        let schedule = self.schedule;
        // Under rollback the mesh is drawn once per rendered frame, not once per simulated
        // (or resimulated) frame.
        let mesh_schedule = match self.rollback {
            true => PostUpdate.intern(),
            false => schedule,
        };
        app.configure_sets(
            schedule,
            (
                WaterSystems::SyncInputs,
                WaterSystems::Step,
                WaterSystems::Writeback,
            )
                .chain(),
        );
        if schedule == PostUpdate.intern() || mesh_schedule == PostUpdate.intern() {
            app.configure_sets(
                PostUpdate,
                WaterSystems::Writeback.before(TransformSystems::Propagate),
            );
        }
        // No system of the sets has commands, so none needs a command flush after it: a
        // new water gets its surface from an observer, a refused one is retried in
        // `PreUpdate` (see the crate docs).
        app.add_observer(step::create_surface)
            .add_systems(PreUpdate, step::retry_refused)
            .add_systems(
                schedule,
                (
                    (
                        step::update_surfaces,
                        follow::follow_followers,
                        step::apply_messages,
                        buoyancy::sync_bodies,
                    )
                        .chain()
                        .in_set(WaterSystems::SyncInputs),
                    step::step_surfaces.in_set(WaterSystems::Step),
                    buoyancy::write_bodies.in_set(WaterSystems::Writeback),
                ),
            );
        // Both read the surface, the mesh write changes its LOD: an order, not an ambiguity.
        let write_meshes = mesh::write_meshes.in_set(WaterSystems::Writeback);
        if mesh_schedule == schedule {
            app.add_systems(schedule, write_meshes.before(buoyancy::write_bodies));
        } else {
            app.add_systems(mesh_schedule, write_meshes);
        }
        #[cfg(feature = "ggrs")]
        if self.rollback {
            rollback::build(app);
        }
        #[cfg(all(feature = "ggrs", feature = "avian"))]
        if self.rollback && self.avian {
            rollback::build_avian(app);
        }
        #[cfg(feature = "avian")]
        if self.avian {
            use avian3d::schedule::PhysicsSystems;
            app.init_resource::<avian::AvianShapes>()
                .configure_sets(
                    schedule,
                    WaterSystems::SyncInputs.after(PhysicsSystems::Writeback),
                )
                .add_systems(
                    schedule,
                    avian::apply_water_forces
                        .after(PhysicsSystems::Prepare)
                        .before(PhysicsSystems::StepSimulation),
                );
        }
    }
}
