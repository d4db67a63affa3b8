//! Floating bodies, two-way: the water lifts and drags a [`Buoyant`] sphere, the sphere
//! pushes back on the water.

use bevy::ecs::prelude::*;
use bevy::math::Vec3;
use bevy::time::Time;
use bevy::transform::components::{GlobalTransform, Transform};
use std::f32::consts::PI;

use crate::step::report;
use crate::water::{Space, WaterError, WaterSurface};

/// A floating sphere. Needs a `Transform`; the plugin moves it.
///
/// # The model
///
/// A body is a sphere of radius `r` and mass `m` centred on its `Transform`'s translation
/// (a root entity: its `Transform` is its world placement). Once per frame, before the
/// water steps, the plugin samples the water under the centre (height `y_w`, velocity
/// `v_w`, springwater's bilinear queries) and computes
///
/// * the immersion `d = clamp(y_w − (y − r), 0, 2r)` and the submerged volume of the
///   spherical cap, `V = π d² (3r − d) / 3`;
/// * buoyancy `F_b = −ρ V g` (Archimedes, with the [`BuoyancySettings`] density `ρ` and
///   gravity `g`);
/// * drag `F_d = −k m (V / V_sphere) (v − v_w)`: linear in the velocity relative to the
///   water, proportional to the submerged fraction, `k` = [`Buoyant::drag`] per second.
///   Only its vertical part unless [`Buoyant::horizontal`], in which case the water's
///   flow also carries the body sideways.
///
/// and integrates `m v' = m g + F_b + F_d + F_ext` with semi-implicit Euler in substeps of
/// at most 1/120 s (the water is sampled once per frame). A body of density `ρ_b` settles
/// where `V / V_sphere = ρ_b / ρ`: half under for half the water's density.
///
/// **Reaction.** The water receives `−coupling × (F_b + F_d)`'s vertical component (in the
/// water's local frame) at the body's point through [`springwater::Surface::add_force_at`],
/// times the frame's substep count because springwater applies such a force to one step.
/// A body's forces are in world units per second², the lattice's in its own mass and
/// model-time units, so [`Buoyant::coupling`] is a tuning factor, not a derived constant;
/// the default makes a floating ball dent the surface and leave a wake when it moves.
///
/// Not modelled: rotation, added mass, waves' pressure beyond the height at the centre,
/// contact with the pool's walls (a body leaving the footprint falls).
#[derive(Component, Debug, Clone, Copy, PartialEq)]
#[require(Transform)]
pub struct Buoyant {
    /// Radius in world units (> 0).
    pub radius: f32,
    /// Mass (> 0), in the units of [`BuoyancySettings::density`] × volume.
    pub mass: f32,
    /// Linear drag rate `k`, per second, at full immersion (default: 2).
    pub drag: f32,
    /// Scale of the reaction pushed into the water (default: 0.05; 0: one-way).
    pub coupling: f32,
    /// Integrate horizontal motion too (drag towards the water's flow, external forces);
    /// when false only `y` moves (default: true).
    pub horizontal: bool,
    /// World velocity, per second. Set it to throw the body.
    pub velocity: Vec3,
    /// External world force for the next frame (game input, wind); cleared after use.
    pub force: Vec3,
}

impl Buoyant {
    /// A sphere of `radius` with `density` relative to the water's (0.5: floats half
    /// under), at rest.
    pub fn sphere(radius: f32, relative_density: f32, settings: &BuoyancySettings) -> Self {
        let volume = 4.0 / 3.0 * PI * radius.powi(3);
        Self {
            radius,
            mass: relative_density * settings.density * volume,
            drag: 2.0,
            coupling: 0.05,
            horizontal: true,
            velocity: Vec3::ZERO,
            force: Vec3::ZERO,
        }
    }

    /// Submerged volume of the sphere when the water is `depth` above its lowest point.
    pub fn submerged_volume(&self, depth: f32) -> f32 {
        let r = self.radius;
        let d = depth.clamp(0.0, 2.0 * r);
        PI * d * d * (3.0 * r - d) / 3.0
    }
}

/// Gravity and the water's density for every [`Buoyant`] body.
#[derive(Resource, Debug, Clone, Copy, PartialEq)]
pub struct BuoyancySettings {
    /// Gravity, world units per second² (default: `(0, −9.81, 0)`).
    pub gravity: Vec3,
    /// Density of the water, mass per cubic world unit (default: 1).
    pub density: f32,
}

impl Default for BuoyancySettings {
    fn default() -> Self {
        Self {
            gravity: Vec3::new(0.0, -9.81, 0.0),
            density: 1.0,
        }
    }
}

/// Longest substep of a body's integration, seconds.
const MAX_BODY_STEP: f32 = 1.0 / 120.0;

/// Samples the water under every body, integrates the bodies over the frame and pushes
/// the reactions into the water (runs before the water steps).
pub(crate) fn float_bodies(
    time: Res<Time>,
    settings: Res<BuoyancySettings>,
    mut bodies: Query<(&mut Buoyant, &mut Transform)>,
    mut waters: Query<(Entity, &mut WaterSurface, &GlobalTransform)>,
    mut errors: MessageWriter<WaterError>,
) {
    let seconds = time.delta_secs();
    if seconds <= 0.0 {
        return;
    }
    for (mut body, mut transform) in &mut bodies {
        if !(body.radius > 0.0 && body.mass > 0.0) {
            continue;
        }
        let centre = transform.translation;
        // The water under the body: its surface point and velocity, world space.
        let mut under = None;
        for (water_entity, ws, global) in &mut waters {
            let space = Space::new(global);
            let p = space.local_point(centre);
            let s = &ws.surface;
            if let (Ok(h), Ok(v)) = (s.height_at(p.x, p.z), s.velocity_at(p.x, p.z)) {
                let surface_y = space.world_point(Vec3::new(p.x, h, p.z)).y;
                let flow =
                    space.world_vector(Vec3::from_array(v.to_array()) * s.params().time_scale);
                under = Some((water_entity, space, p, surface_y, flow));
                break;
            }
        }
        let full = 4.0 / 3.0 * PI * body.radius.powi(3);
        let (buoyancy, drag_rate, flow) = match &under {
            Some((_, _, _, surface_y, flow)) => {
                let volume = body.submerged_volume(surface_y - (centre.y - body.radius));
                let fraction = volume / full;
                (
                    -settings.gravity * settings.density * volume,
                    body.drag * fraction,
                    *flow,
                )
            }
            None => (Vec3::ZERO, 0.0, Vec3::ZERO),
        };
        // Integrate: semi-implicit Euler; drag implicit in the relative velocity so that
        // any rate stays stable.
        let substeps = (seconds / MAX_BODY_STEP).ceil().max(1.0);
        let h = seconds / substeps;
        let external = body.force;
        let mass = body.mass;
        let horizontal = body.horizontal;
        let mut v = body.velocity;
        let mut x = centre;
        let mut mean_drag = Vec3::ZERO;
        for _ in 0..substeps as u32 {
            let accel = settings.gravity + (buoyancy + external) / mass;
            let mut rel = v - flow + accel * h;
            rel /= 1.0 + drag_rate * h;
            let next = rel + flow;
            mean_drag += (next - v) / h - accel;
            v = next;
            if !horizontal {
                v.x = 0.0;
                v.z = 0.0;
            }
            x += v * h;
        }
        let drag = mean_drag / substeps * mass;
        body.velocity = v;
        body.force = Vec3::ZERO;
        transform.translation = x;

        // Two-way: the reaction into the water, for this frame's substeps.
        let Some((water_entity, space, p, _, _)) = under else {
            continue;
        };
        if body.coupling == 0.0 || buoyancy == Vec3::ZERO {
            continue;
        }
        let Ok((_, mut ws, _)) = waters.get_mut(water_entity) else {
            continue;
        };
        let steps = ws.surface.split_frame(seconds).map_or(1, |(n, _)| n.max(1));
        let reaction = space.local_vector(-(buoyancy + drag) * body.coupling * steps as f32);
        if let Err(e) = ws.surface.add_force_at(p.x, p.z, [0.0, reaction.y, 0.0]) {
            report(&mut errors, water_entity, "buoyancy reaction refused", &e);
        }
    }
}
