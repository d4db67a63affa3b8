//! Reading and pushing the water from game systems, at world points: [`WaterQuery`]
//! (read-only, runs in parallel with other readers) and [`WaterQueryMut`] (adds drops and
//! forces). Both transform world points into each water's local space and call
//! springwater's own queries; nothing is re-implemented here.

use bevy::ecs::prelude::*;
use bevy::ecs::system::SystemParam;
use bevy::math::Vec3;
use bevy::transform::components::GlobalTransform;

use crate::water::{Space, WaterSurface};

/// The water at one world point, in world space.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct WaterSample {
    /// The water entity that answered.
    pub water: Entity,
    /// The surface point above or below the query point: the water's local `(x, z)` of the
    /// query point, at the water's height there.
    pub point: Vec3,
    /// Unit normal of the surface there.
    pub normal: Vec3,
    /// Velocity of the surface there, in world units per second (springwater's
    /// [`Surface::sample_at`](springwater::Surface::sample_at), turned into world space).
    pub velocity: Vec3,
}

/// Why a water query gave no answer.
#[derive(Debug, Clone, PartialEq)]
pub enum WaterQueryError {
    /// The entity is not a water with a surface (its parameters were refused, or it is
    /// not a water).
    NoSurface(Entity),
    /// springwater refused the query (a point outside the footprint, a non-finite value).
    Surface(String),
}

impl std::fmt::Display for WaterQueryError {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        match self {
            WaterQueryError::NoSurface(e) => write!(f, "{e} has no water surface"),
            WaterQueryError::Surface(m) => f.write_str(m),
        }
    }
}

impl std::error::Error for WaterQueryError {}

impl From<springwater::Error> for WaterQueryError {
    fn from(e: springwater::Error) -> Self {
        WaterQueryError::Surface(e.to_string())
    }
}

fn sample_one(
    entity: Entity,
    ws: &WaterSurface,
    space: &Space,
    world: Vec3,
) -> Option<WaterSample> {
    let p = space.local_point(world);
    let s = ws.surface.sample_at(p.x, p.z).ok()?;
    Some(WaterSample {
        water: entity,
        point: space.world_point(Vec3::new(p.x, s.height, p.z)),
        normal: space.world_normal(Vec3::from_array(s.normal.to_array())),
        velocity: space.world_vector(Vec3::from_array(s.velocity.to_array())),
    })
}

/// One of springwater's batched queries.
type BatchQuery<T> = fn(&springwater::Surface, &[[f32; 2]], &mut Vec<T>) -> springwater::Result<()>;

/// A batched query at world points: world points → local `[x, z]` → springwater's batch
/// → `to_world` of each local point and answer, into `out`.
fn batch<T, U>(
    ws: &WaterSurface,
    space: &Space,
    points: &[Vec3],
    out: &mut Vec<U>,
    query: BatchQuery<T>,
    to_world: impl Fn(&Space, [f32; 2], T) -> U,
) -> Result<(), WaterQueryError> {
    let local: Vec<[f32; 2]> = points
        .iter()
        .map(|&p| {
            let l = space.local_point(p);
            [l.x, l.z]
        })
        .collect();
    let mut answers = Vec::with_capacity(points.len());
    query(&ws.surface, &local, &mut answers)?;
    out.clear();
    out.extend(
        local
            .into_iter()
            .zip(answers)
            .map(|(at, answer)| to_world(space, at, answer)),
    );
    Ok(())
}

macro_rules! read_api {
    () => {
        /// [`batch`] on the water entity `water`.
        fn batch<T, U>(
            &self,
            water: Entity,
            points: &[Vec3],
            out: &mut Vec<U>,
            query: BatchQuery<T>,
            to_world: impl Fn(&Space, [f32; 2], T) -> U,
        ) -> Result<(), WaterQueryError> {
            let (_, ws, g) = self
                .waters
                .get(water)
                .map_err(|_| WaterQueryError::NoSurface(water))?;
            batch(&ws, &Space::new(g), points, out, query, to_world)
        }

        /// The water under (or over) a world point: the first water whose footprint holds
        /// the point's projection onto its plane. `None` when no water does.
        pub fn sample(&self, point: Vec3) -> Option<WaterSample> {
            self.waters
                .iter()
                .find_map(|(e, ws, g)| sample_one(e, &ws, &Space::new(g), point))
        }

        /// [`Self::sample`] on one water entity.
        pub fn sample_on(&self, water: Entity, point: Vec3) -> Option<WaterSample> {
            let (e, ws, g) = self.waters.get(water).ok()?;
            sample_one(e, &ws, &Space::new(g), point)
        }

        /// World height (y) of the water surface at a world point, if a water is there.
        pub fn height_at(&self, point: Vec3) -> Option<f32> {
            self.sample(point).map(|s| s.point.y)
        }

        /// World unit normal of the water surface at a world point.
        pub fn normal_at(&self, point: Vec3) -> Option<Vec3> {
            self.sample(point).map(|s| s.normal)
        }

        /// World velocity of the water surface at a world point.
        pub fn velocity_at(&self, point: Vec3) -> Option<Vec3> {
            self.sample(point).map(|s| s.velocity)
        }

        /// World heights of `water` at many world points, into `out` (one per point),
        /// with springwater's batched query. All points must be over this water's
        /// footprint; on error `out` holds nothing useful.
        pub fn heights_at(
            &self,
            water: Entity,
            points: &[Vec3],
            out: &mut Vec<f32>,
        ) -> Result<(), WaterQueryError> {
            self.batch(
                water,
                points,
                out,
                springwater::Surface::heights_at,
                |space, [x, z], h| space.world_point(Vec3::new(x, h, z)).y,
            )
        }

        /// World unit normals of `water` at many world points, into `out`.
        pub fn normals_at(
            &self,
            water: Entity,
            points: &[Vec3],
            out: &mut Vec<Vec3>,
        ) -> Result<(), WaterQueryError> {
            self.batch(
                water,
                points,
                out,
                springwater::Surface::normals_at,
                |space, _, n| space.world_normal(Vec3::from_array(n.to_array())),
            )
        }

        /// World velocities of `water` at many world points, into `out`, in world units per
        /// second.
        pub fn velocities_at(
            &self,
            water: Entity,
            points: &[Vec3],
            out: &mut Vec<Vec3>,
        ) -> Result<(), WaterQueryError> {
            self.batch(
                water,
                points,
                out,
                springwater::Surface::velocities_at,
                |space, _, v| space.world_vector(Vec3::from_array(v.to_array())),
            )
        }
    };
}

/// Reads the water at world points from any system:
///
/// ```
/// use bevy::prelude::*;
/// use springwater_bevy::WaterQuery;
///
/// fn bob(water: WaterQuery, mut corks: Query<&mut Transform, With<Name>>) {
///     for mut t in &mut corks {
///         if let Some(h) = water.height_at(t.translation) {
///             t.translation.y = h;
///         }
///     }
/// }
/// ```
#[derive(SystemParam)]
pub struct WaterQuery<'w, 's> {
    waters: Query<'w, 's, (Entity, &'static WaterSurface, &'static GlobalTransform)>,
}

impl WaterQuery<'_, '_> {
    read_api!();
}

/// [`WaterQuery`] plus drops and forces at world points, applied at once (a force acts on
/// the next step). Systems using it do not run in parallel with other water systems; use
/// the [`WaterDrop`](crate::WaterDrop) and [`WaterForce`](crate::WaterForce) messages to
/// push from many systems without that.
#[derive(SystemParam)]
pub struct WaterQueryMut<'w, 's> {
    waters: Query<'w, 's, (Entity, &'static mut WaterSurface, &'static GlobalTransform)>,
}

impl WaterQueryMut<'_, '_> {
    read_api!();

    fn under(&mut self, point: Vec3) -> Option<(Entity, Mut<'_, WaterSurface>, Space, Vec3)> {
        self.waters.iter_mut().find_map(|(e, ws, g)| {
            let space = Space::new(g);
            let p = space.local_point(point);
            ws.surface.contains(p.x, p.z).then_some((e, ws, space, p))
        })
    }

    /// A drop at a world point on the water under it (`height` negative: a dent; both in
    /// the water's local units). Returns the water entity, or `None` if no water is there.
    pub fn drop_at(
        &mut self,
        point: Vec3,
        height: f32,
        radius: f32,
    ) -> Result<Option<Entity>, WaterQueryError> {
        let Some((e, mut ws, _, p)) = self.under(point) else {
            return Ok(None);
        };
        ws.surface.drop_at(p.x, p.z, height, radius)?;
        Ok(Some(e))
    }

    /// A world force at a world point on the water under it, for the next step, in the
    /// lattice's force units ([`springwater::Surface::add_force_at`]). Returns the water
    /// entity, or `None` if no water is there.
    pub fn add_force_at(
        &mut self,
        point: Vec3,
        force: Vec3,
    ) -> Result<Option<Entity>, WaterQueryError> {
        let Some((e, mut ws, space, p)) = self.under(point) else {
            return Ok(None);
        };
        let f = space.local_vector(force);
        ws.surface.add_force_at(p.x, p.z, f.to_array())?;
        Ok(Some(e))
    }

    /// The surface of one water entity, for springwater's whole API (local space).
    pub fn surface_mut(&mut self, water: Entity) -> Option<Mut<'_, WaterSurface>> {
        self.waters.get_mut(water).ok().map(|(_, ws, _)| ws)
    }
}
