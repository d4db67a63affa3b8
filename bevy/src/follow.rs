//! The moving window: a [`WaterFollow`] entity (a camera, a ship) drags its water's
//! simulated window through the world with springwater's [`Surface::follow`].
//!
//! [`Surface::follow`]: springwater::Surface::follow

use bevy::ecs::prelude::*;
use bevy::transform::components::GlobalTransform;

use crate::water::{report, Space, WaterError, WaterSurface};

/// Makes a water's window follow this entity (a camera, a ship) across an open sea.
///
/// Every frame, before the step (in [`WaterSystems::SyncInputs`]), the plugin turns the
/// entity's [`GlobalTransform`] translation into the water's local space and calls
/// [`Surface::follow`] there: once the point leaves a dead zone around the window's
/// middle ([`Surface::follow_dead_zone`] cells either side), the window moves by whole
/// cells to put it back near the middle. The water that stays in the window is kept bit
/// for bit; the strip that comes in is calm. Like the eye, the translation is read before
/// this frame's transform propagation (one frame late if the entity moved).
///
/// `water` names the water entity that follows, or is `None` for every water (the usual
/// case: one sea), as [`WaterDrop`](crate::WaterDrop) names its target. A water that
/// several entities would drag follows one of them: one that names it before one with
/// `None`, then the lowest [`Entity::index_u32`].
///
/// ```
/// use bevy::prelude::*;
/// use springwater_bevy::prelude::*;
///
/// fn setup(mut commands: Commands) {
///     let sea = commands.spawn(Water::with_size(257, 257)).id();
///     commands.spawn((Camera3d::default(), Transform::from_xyz(128.0, 20.0, 128.0), WaterFollow::default()));
///     // Or a ship that drags only this water:
///     commands.spawn((Transform::from_xyz(128.0, 0.0, 128.0), WaterFollow { water: Some(sea) }));
/// }
/// ```
///
/// # The water entity does not move; its mesh's vertices do
///
/// springwater keeps its positions in the water frame, which the window travels through:
/// node `(col, row)` rests at [`Surface::origin`]` + (col·h, row·h)`. So the mesh's
/// vertices carry the window's place themselves, and the water entity's `Transform` stays
/// where the game put it. Everything the plugin converts with that transform stays right
/// across a shift with no correction: [`WaterQuery`](crate::WaterQuery) reads the same
/// water at a world point before and after (bit for bit, over the overlap), drops and
/// forces land where they are aimed, [`Buoyant`](crate::Buoyant) bodies keep their world
/// positions (springwater's floaters live in the water frame too), the refracted bottom
/// coordinates (`UV_0`) stay put in the world (a bottom texture with a repeating sampler
/// tiles the whole sea), and the plugin moves the bounding box with the window. Moving
/// the transform by each shift instead would have to rebase every vertex, floater and
/// pending input by the opposite amount: rounding, which the library's overlap guarantee
/// rules out.
///
/// A body the window leaves behind floats on calm water at rest height until the window
/// comes back: put the `WaterFollow` on the ship to keep it in simulated water.
///
/// Horizontal coordinates in the water frame grow as the window travels, with `f32`'s
/// resolution (about `|x|·6·10⁻⁸`): windows within about 10⁴ cells of where the water
/// entity was placed are unaffected in practice. A larger world rebases: a fresh water
/// entity placed near the camera (see springwater's [`window`](springwater::window)
/// module docs).
///
/// A follower that is not finite, or one that would take the window past
/// [`MAX_ORIGIN_CELLS`](springwater::window::MAX_ORIGIN_CELLS), leaves the window where
/// it is and is reported as a [`WaterError`] on the water (every frame it stays so).
///
/// [`WaterSystems::SyncInputs`]: crate::WaterSystems::SyncInputs
/// [`Surface::follow`]: springwater::Surface::follow
/// [`Surface::follow_dead_zone`]: springwater::Surface::follow_dead_zone
/// [`Surface::origin`]: springwater::Surface::origin
#[derive(Component, Debug, Clone, Copy, Default, PartialEq, Eq)]
pub struct WaterFollow {
    /// The water entity whose window follows, or `None` for every water.
    pub water: Option<Entity>,
}

/// Moves every followed water's window to its follower, before drops, forces and bodies
/// are handed to the water (they land in the window's new place).
pub(crate) fn follow_followers(
    followers: Query<(Entity, &WaterFollow, &GlobalTransform)>,
    mut waters: Query<(Entity, &mut WaterSurface, &GlobalTransform)>,
    mut errors: MessageWriter<WaterError>,
) {
    if followers.is_empty() {
        return;
    }
    for (water, mut ws, global) in &mut waters {
        let leader = followers
            .iter()
            .filter(|(_, follow, _)| follow.water.is_none_or(|w| w == water))
            .min_by_key(|(follower, follow, _)| (follow.water.is_none(), follower.index_u32()));
        let Some((_, _, at)) = leader else {
            continue;
        };
        let p = Space::new(global).local_point(at.translation());
        if let Err(e) = ws.surface.follow(p.x, p.z) {
            report(&mut errors, water, "follow refused", &e);
        }
    }
}
