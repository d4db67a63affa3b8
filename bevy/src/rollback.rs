//! Rollback netcode with [bevy_ggrs](https://github.com/gschup/bevy_ggrs) (feature `ggrs`).
//!
//! A rollback session saves the game every frame; when a peer's input arrives late it
//! loads an earlier frame and simulates the frames since again, and it compares
//! checksums between peers (a `SyncTestSession` rolls back every frame on one machine
//! and compares the resimulated checksums with the first ones). springwater steps the
//! same bits on every SIMD level, thread count and platform, so its water can take part:
//! [`SpringwaterPlugin::with_rollback`](crate::SpringwaterPlugin::with_rollback)
//!
//! - runs the plugin's [`SyncInputs`](crate::WaterSystems::SyncInputs),
//!   [`Step`](crate::WaterSystems::Step) and the bodies' write-back in bevy_ggrs's
//!   [`GgrsSchedule`](bevy_ggrs::GgrsSchedule), where `Time` is bevy_ggrs's frame clock: every simulated frame
//!   advances each surface by the same frame time and takes whole steps of its `dt`
//!   ([`Surface::advance`](springwater::Surface::advance); the carried remainder is part
//!   of the saved state);
//! - writes the meshes in `PostUpdate`, once per rendered frame, from the frame the
//!   session ended on;
//! - saves each water with [`Surface::save_into`](springwater::Surface::save_into) into
//!   buffers it keeps from frame to frame ([`WaterSnapshots`]: once they have held a save
//!   of their water, saving allocates nothing), and loads a frame with
//!   [`Surface::restore`](springwater::Surface::restore), which copies into the surface's
//!   own buffers. The [`Buoyant`] bodies' floaters are part of their water's save; their
//!   components and `Transform`s are saved beside it, so the game sees them where they
//!   were at that frame;
//! - gives bevy_ggrs each water's
//!   [`Surface::state_hash`](springwater::Surface::state_hash) as its part of the frame's
//!   checksum (its `checksum_component`), the hash peers compare;
//! - makes [`Water`] and [`Buoyant`] require bevy_ggrs's [`Rollback`] marker.
//!
//! ```no_run
//! use bevy::prelude::*;
//! use bevy_ggrs::prelude::*;
//! use springwater_bevy::prelude::*;
//!
//! type Config = GgrsConfig<u8>; // one byte of input per player
//!
//! /// A drop where player 0 says, from the inputs of this frame (never from outside them).
//! fn play(inputs: Res<PlayerInputs<Config>>, mut drops: MessageWriter<WaterDrop>) {
//!     let (input, _) = inputs[0];
//!     if input != 0 {
//!         let x = 4.0 + f32::from(input % 60);
//!         drops.write(WaterDrop { water: None, point: Vec3::new(x, 0.0, 32.0), height: -1.0, radius: 3.0 });
//!     }
//! }
//!
//! # fn read_inputs() {}
//! # fn session() -> Session<Config> { unimplemented!() }
//! App::new()
//!     .add_plugins((MinimalPlugins, GgrsPlugin::<Config>::default()))
//!     .add_plugins(SpringwaterPlugin::default().with_rollback())
//!     .add_systems(ReadInputs, read_inputs)
//!     .add_systems(GgrsSchedule, play.before(WaterSystems::SyncInputs))
//!     .add_systems(Startup, |mut commands: Commands| {
//!         commands.spawn(Water::with_size(65, 65));
//!     })
//!     .insert_resource(session())
//!     .run();
//! ```
//!
//! What the game must do: disturb the water only from systems in `GgrsSchedule`
//! ordered before [`WaterSystems::SyncInputs`](crate::WaterSystems::SyncInputs), from the
//! frame's `PlayerInputs` and rolled-back state (drops and forces sent from `Update`
//! would land on whichever frame runs next, and differently when it runs again); give
//! every peer the same crate version, water parameters and bevy_ggrs frame rate.
//!
//! Avian's bodies (feature `avian`, [`with_avian`](crate::SpringwaterPlugin::with_avian)
//! with `with_rollback`): everything runs in `GgrsSchedule`, Avian too
//! (`PhysicsPlugins::new(GgrsSchedule)`). The plugin saves and loads the waters (with
//! the reactions of the bodies on them) and each body's [`AvianBuoyant`](crate::AvianBuoyant),
//! which requires [`Rollback`]; Avian's own state is the game's to register, as for any
//! Avian body under bevy_ggrs: at least `Position`, `Rotation`, `LinearVelocity`,
//! `AngularVelocity` and `Transform`, and what else its bodies use (Avian's sleeping
//! components; its contacts, for warm starting, if bodies touch). A body whose motion is
//! not rolled back starts the frames simulated again from where the session left it, not
//! from the frame loaded, and the peers' checksums differ.
//!
//! ```ignore
//! app.add_plugins((
//!     GgrsPlugin::<Config>::default(),
//!     PhysicsPlugins::new(GgrsSchedule),
//!     SpringwaterPlugin::default().with_rollback().with_avian(),
//! ))
//! .rollback_component_with_copy::<Position>()
//! .rollback_component_with_copy::<Rotation>()
//! .rollback_component_with_copy::<LinearVelocity>()
//! .rollback_component_with_copy::<AngularVelocity>()
//! .rollback_component_with_copy::<Transform>();
//! ```
//!
//! Not covered: a [`WaterFollow`](crate::WaterFollow) (it reads its entity's
//! `GlobalTransform`, which Bevy propagates once per rendered frame, not per
//! resimulated frame); a [`WaterDisturbance`](crate::WaterDisturbance) with state of its
//! own (rain's random numbers are not saved); changes to a [`Water`] component (its
//! parameters restart the surface and are not rolled back); despawning a water or a
//! body within the frames a session may roll back (the saves are kept by entity).

use std::collections::VecDeque;

use bevy::ecs::prelude::*;
use bevy::log::error;
use bevy::prelude::App;
use bevy::transform::components::Transform;
use bevy_ggrs::{
    ConfirmedFrameCount, LoadWorld, LoadWorldSystems, Rollback, RollbackApp, RollbackFrameCount,
    SaveWorld, SaveWorldSystems,
};

use crate::buoyancy::{Bodies, Buoyant, Link};
use crate::water::{report, Water, WaterError, WaterSurface};

/// The frames a rollback session may load: each water's save and each body's state,
/// oldest first, and the buffers of frames no longer needed, kept for the next saves.
///
/// A frame is kept until bevy_ggrs confirms a later one (the session's confirmed frame;
/// in a `SyncTestSession`, the current frame less the check distance), so a session of
/// check distance 7 holds 8 or 9 saves of each water.
#[derive(Resource, Default)]
pub struct WaterSnapshots {
    frames: VecDeque<Saved>,
    spare: Vec<Saved>,
    grown: usize,
}

/// One frame's save.
#[derive(Default)]
struct Saved {
    frame: i32,
    /// Each water's [`Surface::save_into`](springwater::Surface::save_into).
    waters: Vec<(Entity, Vec<u8>)>,
    bodies: Vec<SavedBody>,
}

/// A [`Buoyant`] body as it was: the components the game sees and which floater it is
/// (its floater's state is in its water's save).
struct SavedBody {
    entity: Entity,
    buoyant: Buoyant,
    transform: Transform,
    link: Option<Link>,
}

impl WaterSnapshots {
    /// How many frames are saved.
    pub fn frames(&self) -> usize {
        self.frames.len()
    }

    /// How many times a water's save needed a new or a larger buffer. It stops growing
    /// once the session has saved as many frames as it keeps: from then on every save
    /// reuses the buffer of a frame that was let go.
    pub fn buffers_grown(&self) -> usize {
        self.grown
    }

    /// Lets go of the saved frames from `frame` on (they are being simulated again).
    fn forget_from(&mut self, frame: i32) {
        while self.frames.back().is_some_and(|s| s.frame >= frame) {
            self.spare.extend(self.frames.pop_back());
        }
    }

    /// Lets go of the saved frames before `frame` (no session will load them).
    fn forget_before(&mut self, frame: i32) {
        while self.frames.front().is_some_and(|s| s.frame < frame) {
            self.spare.extend(self.frames.pop_front());
        }
    }
}

/// Registers the saves, loads and checksums (called by the plugin's `build`).
pub(crate) fn build(app: &mut App) {
    app.init_resource::<WaterSnapshots>()
        .checksum_component::<WaterSurface>(|ws| ws.surface.state_hash())
        .add_systems(SaveWorld, save.in_set(SaveWorldSystems::Snapshot))
        .add_systems(LoadWorld, load.in_set(LoadWorldSystems::Data));
    // (An app that already made them require it keeps its own registration.)
    let _ = app.try_register_required_components::<Water, Rollback>();
    let _ = app.try_register_required_components::<Buoyant, Rollback>();
}

/// Registers [`AvianBuoyant`](crate::AvianBuoyant) for rollback (with Avian, feature
/// `avian`; called by the plugin's `build`): it requires [`Rollback`], and bevy_ggrs
/// saves and loads it (its read-only `water_force` and `water_torque` are part of the
/// frame the game sees).
#[cfg(feature = "avian")]
pub(crate) fn build_avian(app: &mut App) {
    app.rollback_component_with_clone::<crate::AvianBuoyant>();
    let _ = app.try_register_required_components::<crate::AvianBuoyant, Rollback>();
}

/// Saves every water and body for this frame, after bevy_ggrs took the checksum.
fn save(
    frame: Res<RollbackFrameCount>,
    confirmed: Option<Res<ConfirmedFrameCount>>,
    mut snapshots: ResMut<WaterSnapshots>,
    waters: Query<(Entity, &WaterSurface)>,
    bodies: Query<(Entity, &Buoyant, &Transform)>,
    registry: Res<Bodies>,
) {
    let snapshots = &mut *snapshots;
    snapshots.forget_from(frame.0);
    if let Some(confirmed) = confirmed {
        snapshots.forget_before(confirmed.0);
    }
    let mut saved = snapshots.spare.pop().unwrap_or_default();
    saved.frame = frame.0;
    let mut count = 0;
    for (entity, ws) in &waters {
        if count == saved.waters.len() {
            saved.waters.push((entity, Vec::new()));
        }
        let (owner, bytes) = &mut saved.waters[count];
        *owner = entity;
        let capacity = bytes.capacity();
        ws.surface.save_into(bytes);
        if bytes.capacity() != capacity {
            snapshots.grown += 1;
        }
        count += 1;
    }
    saved.waters.truncate(count);
    saved.bodies.clear();
    saved
        .bodies
        .extend(bodies.iter().map(|(entity, buoyant, transform)| SavedBody {
            entity,
            buoyant: buoyant.clone(),
            transform: *transform,
            link: registry.link(entity),
        }));
    snapshots.frames.push_back(saved);
}

/// Puts every water and body back as they were at the frame bevy_ggrs loads.
fn load(
    frame: Res<RollbackFrameCount>,
    mut snapshots: ResMut<WaterSnapshots>,
    mut waters: Query<&mut WaterSurface>,
    mut bodies: Query<(Entity, &mut Buoyant, &mut Transform)>,
    mut registry: ResMut<Bodies>,
    mut errors: MessageWriter<WaterError>,
) {
    snapshots.forget_from(frame.0.saturating_add(1));
    let Some(saved) = snapshots.frames.back().filter(|s| s.frame == frame.0) else {
        error!(
            "springwater: rollback to frame {}, which was not saved",
            frame.0
        );
        return;
    };
    for (entity, bytes) in &saved.waters {
        if let Ok(mut ws) = waters.get_mut(*entity) {
            if let Err(e) = ws.surface.restore(bytes) {
                report(&mut errors, *entity, "rollback refused", &e);
            }
        }
    }
    for (i, (entity, mut buoyant, mut transform)) in bodies.iter_mut().enumerate() {
        // The same order as when saved, unless bodies came or went.
        let was = saved
            .bodies
            .get(i)
            .filter(|b| b.entity == entity)
            .or_else(|| saved.bodies.iter().find(|b| b.entity == entity));
        match was {
            Some(was) => {
                buoyant.set_if_neq(was.buoyant.clone());
                transform.set_if_neq(was.transform);
                registry.set_link(entity, was.link.clone());
            }
            // Not yet a body at that frame: it joins its water again when it steps.
            None => registry.set_link(entity, None),
        }
    }
}
