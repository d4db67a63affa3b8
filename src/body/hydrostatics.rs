//! The submerged part of a hull: pressure on each triangle below the water, clipped at the
//! waterline.
//!
//! # The method
//!
//! The water pushes on every wet part of the hull with the hydrostatic pressure
//! `p = ρ g d`, `d` the depth below the water surface, along the inward normal. Summed over
//! the wet surface `W`:
//!
//! ```text
//! F = −ρ g ∫_W d n dA          τ = −ρ g ∫_W d (r − o) × n dA   (about the body's origin o)
//! ```
//!
//! Each triangle gets the depth of the water at its three corners, `d_i = η(x_i, z_i) − y_i`
//! with `η` the water's height there. A triangle wholly below water is taken whole; one
//! crossing the waterline is cut where the depth, linear along each edge, is zero
//! (Kerner's model, "Water interaction model for boats in video games", 2015): one wet
//! corner leaves a triangle, two leave a quadrilateral, cut into two triangles. The point
//! where an edge crosses is computed from its wet end towards its dry end, so the two
//! triangles sharing that edge get the same bits and the wet surface has no cracks. Over
//! a triangle the depth is linear, and the integrals are exact:
//!
//! ```text
//! ∫ d dA = A (d₀ + d₁ + d₂) / 3        ∫ d r dA = A (Σ dᵢ rᵢ + (Σ dᵢ)(Σ rᵢ)) / 12
//! ```
//!
//! (from `∫ λᵢ λⱼ dA = A (1 + δᵢⱼ) / 12` for the barycentric coordinates λ).
//!
//! **Archimedes, exactly.** Close the wet surface with the water surface inside the hull
//! (the "lid", where `d = 0`). The divergence theorem turns surface integrals over the
//! closed wet region into volume integrals, and the lid contributes nothing to any of them
//! because the depth vanishes on it:
//!
//! * in flat water, `F = ρ g V ŷ` with `V` the submerged volume, and the buoyancy acts
//!   through the centroid `B` of that volume: `τ = (B − o) × F`;
//! * the submerged volume itself is `V = −∫_W d n_y dA` (the field `(0, −d, 0)` has
//!   divergence 1 and vanishes on the lid), and its first moments are
//!   `∫ x dV = −∫_W x d n_y dA`, the same for z, and `∫ y dV = −∫_W d (y + d/2) n_y dA`;
//! * the waterplane (the lid, seen from above) has `∫ f dA = −∫_W f n_y dA` for any
//!   `f(x, z)`, which gives its area, centre and second moments; Stokes' theorem turns
//!   that into an integral along the wet surface's edge, the waterline, so only the
//!   triangles the waterline cuts add to it.
//!
//! The last two hold for any water surface that is one height per `(x, z)`: on waves, `V`
//! is the volume below the water's surface (taken linear across each triangle) and still
//! `F_y / (ρ g)`, the force also has horizontal parts (the pressure on a slope), and
//! force and torque are still the integrals of the pressure over the clipped triangles.
//! Against a flat plane every result is exact to rounding.
//!
//! **Why triangles rather than columns.** Columns under the hull (a grid of vertical rays
//! through the mesh, each column's submerged length) make Archimedes hold only to the
//! column size, must be rebuilt whenever the body turns (the footprint moves under a
//! rotated hull), and need a ray–mesh test per column. Clipped triangles cost one pass
//! over the mesh, a few dozen multiplications per wet triangle, allocate nothing, and are
//! exact for a flat plane at any heel. The price: the water is sampled only at the hull's
//! vertices, so waves much shorter than the triangles that cross the waterline are
//! averaged away; a hull for buoyancy should have triangles no longer than about a cell of
//! the water where it meets the waves.
//!
//! **Arithmetic.** The pose's rotation is built from the quaternion's components with
//! `+`, `−`, `×` and `÷` (scaled by `2 / |q|²`, so a quaternion a little off unit length
//! still gives a rotation), and every sum runs in `f64` in the mesh's order, so every
//! platform gets the same bits.

use super::{math, rigid, Hull};
use crate::error::{Error, Result};
use crate::{params, Buoyancy};
use glam::{DVec3, Quat, Vec2, Vec3};

/// What the water does to a hull in one pose: [`Hull::submerged`]. World frame, world
/// units; forces in mass units × world units per second². `#[non_exhaustive]`: a
/// quantity may come.
#[derive(Debug, Clone, Copy, PartialEq, Default)]
#[non_exhaustive]
pub struct Submerged {
    /// The volume below the water, cubic world units (`F_y / (ρ g)`, zero when dry).
    pub volume: f32,
    /// The centroid of that volume (the centre of buoyancy); the body's position when dry.
    pub centre_of_buoyancy: Vec3,
    /// The water's pressure force on the hull (upwards `ρ g V` on a flat water plane).
    pub force: Vec3,
    /// The pressure's torque about the body's origin (its `position`; the centre of mass
    /// for a [`centred`](Hull::centred) hull).
    pub torque: Vec3,
    /// The water surface's section through the hull.
    pub waterplane: Waterplane,
}

/// The water surface's section through a hull, projected on the horizontal plane.
/// `#[non_exhaustive]`: a quantity may come.
#[derive(Debug, Clone, Copy, PartialEq, Default)]
#[non_exhaustive]
pub struct Waterplane {
    /// Area, square world units (zero when the hull is dry or wholly under).
    pub area: f32,
    /// Its centroid's world `(x, z)` (the centre of flotation); the body's `(x, z)` when
    /// the area is zero.
    pub centre: Vec2,
    /// Second moments about the centre: `[∫ x'² dA, ∫ x' z' dA, ∫ z'² dA]`, `x'`, `z'`
    /// measured from the centre (world units⁴).
    pub second_moments: [f32; 3],
}

impl Waterplane {
    /// The second moment of area about the horizontal line through the centre along
    /// `axis` (only its x and z count): `∫ (distance from the line)² dA`. The
    /// metacentric radius for heeling about that line is this over the submerged volume,
    /// `BM = I / V`. Zero for an axis with no horizontal part.
    pub fn second_moment_about(&self, axis: Vec3) -> f32 {
        let (ux, uz) = (axis.x as f64, axis.z as f64);
        let norm = ux * ux + uz * uz;
        if norm == 0.0 {
            return 0.0;
        }
        // distance = x' u_z − z' u_x for a unit (u_x, u_z).
        let [xx, xz, zz] = self.second_moments.map(f64::from);
        ((xx * uz * uz - 2.0 * xz * ux * uz + zz * ux * ux) / norm) as f32
    }
}

/// Reused per-vertex workspace for [`Hull::submerged`]: keeps its capacity, so a step
/// that floats the same hull again allocates nothing.
#[derive(Debug, Clone, Default)]
pub struct HullScratch {
    /// Per vertex: world position relative to the body's origin, and depth below water.
    corners: Vec<Corner>,
}

impl HullScratch {
    /// An empty workspace.
    pub fn new() -> Self {
        Self::default()
    }
}

impl Hull {
    /// The submerged part of the hull at `position` (world, of the body frame's origin)
    /// and `orientation` (body to world, a unit quaternion), in water whose surface is at
    /// height `water_height(x, z)` at world `(x, z)`, with the gravity and density of
    /// `buoyancy`. The module docs explain the method.
    ///
    /// Refused ([`Error::InvalidParam`]): a non-finite position, an orientation whose
    /// squared norm is not within 1e-3 of 1, an invalid `buoyancy`, a water height that is
    /// not finite or exceeds 1e9 in size, results too large for `f32`.
    ///
    /// ```
    /// use springwater::body::{Hull, HullScratch};
    /// use springwater::glam::{Quat, Vec3};
    /// use springwater::Buoyancy;
    ///
    /// let hull = Hull::cuboid([1.0, 0.5, 2.0])?;
    /// let water = Buoyancy { gravity: 10.0, density: 1.0 };
    /// let mut scratch = HullScratch::new();
    /// // Half under a calm surface at height 0: 2 × 0.5 × 4 = 4 cubic units displaced.
    /// let sub = hull.submerged(Vec3::ZERO, Quat::IDENTITY, water, |_, _| 0.0, &mut scratch)?;
    /// assert!((sub.volume - 4.0).abs() < 1e-6);
    /// assert!((sub.force.y - 10.0 * 4.0).abs() < 1e-5);
    /// assert!((sub.centre_of_buoyancy.y + 0.25).abs() < 1e-6);
    /// assert!((sub.waterplane.area - 8.0).abs() < 1e-6);
    /// # Ok::<(), springwater::Error>(())
    /// ```
    pub fn submerged(
        &self,
        position: Vec3,
        orientation: Quat,
        buoyancy: Buoyancy,
        water_height: impl FnMut(f32, f32) -> f32,
        scratch: &mut HullScratch,
    ) -> Result<Submerged> {
        self.submerged_parts(
            position,
            orientation,
            buoyancy,
            water_height,
            scratch,
            |_, _| {},
        )
    }

    /// [`submerged`](Self::submerged), also handing each wet (clipped) triangle's
    /// pressure force to `part(point, force)`, `point` its centre of pressure (world): the
    /// parts add up to the total force, and their moments about the body's origin to the
    /// total torque, to rounding. For pushing the reaction into the water where it acts.
    pub fn submerged_parts(
        &self,
        position: Vec3,
        orientation: Quat,
        buoyancy: Buoyancy,
        water_height: impl FnMut(f32, f32) -> f32,
        scratch: &mut HullScratch,
        mut part: impl FnMut(Vec3, Vec3),
    ) -> Result<Submerged> {
        for v in position.to_array() {
            params::finite("body position", v)?;
        }
        buoyancy.validate()?;
        let rho_g = buoyancy.density as f64 * buoyancy.gravity as f64;
        let pressure = self.pressed(
            position,
            orientation,
            rho_g,
            water_height,
            scratch,
            |point, force, _| part(point.as_vec3(), force.as_vec3()),
        )?;
        pressure.submerged()
    }

    /// The pressure pass behind [`submerged_parts`](Self::submerged_parts), in `f64`:
    /// `part(point, force, area)` for each wet (clipped) triangle, and the totals.
    #[inline(always)]
    pub(crate) fn pressed(
        &self,
        position: Vec3,
        orientation: Quat,
        rho_g: f64,
        mut water_height: impl FnMut(f32, f32) -> f32,
        scratch: &mut HullScratch,
        mut part: impl FnMut(DVec3, DVec3, f64),
    ) -> Result<Pressure> {
        let rotate = rotation(orientation)?;
        let origin = position.as_dvec3();

        scratch.corners.clear();
        for v in self.vertices() {
            let rel = rotate(DVec3::from(v.map(f64::from)));
            let world = origin + rel;
            let eta = water_height(world.x as f32, world.z as f32);
            if !(eta.is_finite() && eta.abs() <= 1e9) {
                return Err(Error::InvalidParam {
                    name: "water height",
                    value: eta as f64,
                    expected: "a finite number, at most 1e9 in size",
                });
            }
            scratch.corners.push(Corner {
                r: rel,
                d: eta as f64 - world.y,
            });
        }

        let mut sums = Sums::default();
        let corners = &scratch.corners;
        for tri in self.triangles() {
            let corner = |k: usize| corners[tri[k] as usize];
            // Which corners are wet, one bit each, and from that the corners' order
            // starting at the odd one out (the only wet corner, or the only dry one).
            let wet = (corner(0).d > 0.0) as usize
                | ((corner(1).d > 0.0) as usize) << 1
                | ((corner(2).d > 0.0) as usize) << 2;
            let [k, a, b] = match wet {
                0b111 => {
                    sums.add(corner(0), corner(1), corner(2), rho_g, origin, &mut part);
                    continue;
                }
                0 => continue,
                wet => {
                    let [k, a, b] = ODD_FIRST[wet];
                    [corner(k), corner(a), corner(b)]
                }
            };
            if wet.count_ones() == 1 {
                let (ka, kb) = (crossing(k, a), crossing(k, b));
                sums.add(k, ka, kb, rho_g, origin, &mut part);
                sums.waterline(ka.r, kb.r);
            } else {
                let (ak, bk) = (crossing(a, k), crossing(b, k));
                sums.add(a, b, bk, rho_g, origin, &mut part);
                sums.add(a, bk, ak, rho_g, origin, &mut part);
                sums.waterline(bk.r, ak.r);
            }
        }
        Ok(sums.finish(origin, rho_g, self.extent()))
    }
}

/// A cut triangle's corners in their order (turned, not reversed) starting at the odd one
/// out, by which corners are wet (bit `k` for corner `k`): one wet corner, or one dry.
const ODD_FIRST: [[usize; 3]; 8] = [
    [0, 1, 2], // dry: not cut
    [0, 1, 2], // corner 0 wet
    [1, 2, 0], // corner 1 wet
    [2, 0, 1], // corner 2 dry
    [2, 0, 1], // corner 2 wet
    [1, 2, 0], // corner 1 dry
    [0, 1, 2], // corner 0 dry
    [0, 1, 2], // wet: not cut
];

/// The body-to-world rotation of `q`, as a function of body-frame vectors, scaled by
/// `2 / |q|²` so that it is a rotation for any `q` near unit length.
fn rotation(q: Quat) -> Result<impl Fn(DVec3) -> DVec3> {
    let n = math::check_unit(q, "body orientation", "body orientation's squared norm")?;
    let m = math::rotation_scaled(q.as_dquat(), 2.0 / n);
    let (cx, cy, cz) = (m.x_axis, m.y_axis, m.z_axis);
    Ok(move |v: DVec3| cx * v.x + cy * v.y + cz * v.z)
}

/// Where the depth reaches zero on the edge from the wet corner `w` to the dry corner `d`,
/// always computed from the wet end, so both triangles of an edge agree to the bit.
fn crossing(w: Corner, d: Corner) -> Corner {
    let t = w.d / (w.d - d.d);
    Corner {
        r: w.r + (d.r - w.r) * t,
        d: 0.0,
    }
}

/// A corner of a wet triangle: its position relative to the body's origin (world axes)
/// and its depth below the water.
#[derive(Debug, Clone, Copy, Default)]
struct Corner {
    r: DVec3,
    d: f64,
}

/// Running sums over the wet triangles (positions relative to the body's origin).
#[derive(Default)]
struct Sums {
    /// Σ S (d₀ + d₁ + d₂), S twice the triangle's area vector: 6 ∫ d n dA.
    pressure: DVec3,
    /// Σ M × S, M = Σ dᵢ rᵢ + (Σ dᵢ)(Σ rᵢ): 24 ∫ d r × n dA.
    moment: DVec3,
    /// −Σ S_y M_x, −Σ S_y (2 M_y + D² + Σ dᵢ²) / 2, −Σ S_y M_z: 24 ∫ r dV.
    first: DVec3,
    /// The waterplane from its boundary, the waterline (see `waterline`): Σ c, Σ c (x_p +
    /// x_q), Σ c (z_p + z_q), Σ c (x_p² + x_p x_q + x_q²), Σ c (2 x_p z_p + x_p z_q +
    /// x_q z_p + 2 x_q z_q), Σ c (z_p² + z_p z_q + z_q²), with c = x_p z_q − x_q z_p:
    /// 2, 6, 6, 12, 24 and 12 times area, first and second moments.
    lid: [f64; 6],
}

impl Sums {
    /// Adds the wet triangle `c0 c1 c2` (corners relative to the body's origin, with depths).
    #[inline(always)]
    #[allow(clippy::too_many_arguments)]
    fn add(
        &mut self,
        c0: Corner,
        c1: Corner,
        c2: Corner,
        rho_g: f64,
        origin: DVec3,
        part: &mut impl FnMut(DVec3, DVec3, f64),
    ) {
        let (Corner { r: r0, d: d0 }, Corner { r: r1, d: d1 }) = (c0, c1);
        let Corner { r: r2, d: d2 } = c2;
        let s = (r1 - r0).cross(r2 - r0);
        let depth = d0 + d1 + d2;
        // M = Σ dᵢ rᵢ + (Σ dᵢ)(Σ rᵢ), grouped by corner.
        let m = r0 * (d0 + depth) + r1 * (d1 + depth) + r2 * (d2 + depth);
        self.pressure += s * depth;
        self.moment += m.cross(s);
        let squares = d0 * d0 + d1 * d1 + d2 * d2;
        self.first -= DVec3::new(m.x, m.y + 0.5 * (depth * depth + squares), m.z) * s.y;

        // The centre of pressure ∫ d r dA / ∫ d dA = M / (4 D) carries this triangle's
        // force; its moment is then exactly this triangle's share of the torque.
        let force = s * (-rho_g * depth / 6.0);
        part(origin + m / (4.0 * depth), force, 0.5 * s.length());
    }

    /// Adds a piece `p → q` of the waterline, in the direction the wet triangle's edges
    /// run. The waterplane's integrals `∫ f dA` equal `−∫ f n_y dA` over the wet hull
    /// (the closed wet region's lid, seen from above), which Stokes' theorem turns into an
    /// integral round the wet hull's edge, the waterline: `∮ F dz` with `∂F/∂x = f`.
    /// Along straight pieces these are the polygon formulas summed here.
    #[inline(always)]
    fn waterline(&mut self, p: DVec3, q: DVec3) {
        let (xp, zp, xq, zq) = (p.x, p.z, q.x, q.z);
        let c = xp * zq - xq * zp;
        self.lid[0] += c;
        self.lid[1] += c * (xp + xq);
        self.lid[2] += c * (zp + zq);
        self.lid[3] += c * (xp * xp + xp * xq + xq * xq);
        self.lid[4] += c * (2.0 * xp * zp + xp * zq + xq * zp + 2.0 * xq * zq);
        self.lid[5] += c * (zp * zp + zp * zq + zq * zq);
    }

    fn finish(self, origin: DVec3, rho_g: f64, extent: f64) -> Pressure {
        let force = self.pressure * (-rho_g / 6.0);
        let torque = self.moment * (-rho_g / 24.0);
        let volume = -self.pressure.y / 6.0;
        // What rounding leaves of a dry or barely touching hull is no volume at all.
        let (volume, centre) = if volume > 1e-12 * extent * extent * extent {
            (volume, origin + self.first / (24.0 * volume))
        } else {
            (0.0, origin)
        };
        let area = 0.5 * self.lid[0];
        let plane = if area > 1e-9 * extent * extent {
            let cx = self.lid[1] / (6.0 * area);
            let cz = self.lid[2] / (6.0 * area);
            let (xx, xz, zz) = (self.lid[3] / 12.0, self.lid[4] / 24.0, self.lid[5] / 12.0);
            rigid::Section {
                area,
                centre: [origin.x + cx, origin.z + cz],
                second: [
                    xx - area * cx * cx,
                    xz - area * cx * cz,
                    zz - area * cz * cz,
                ],
            }
        } else {
            rigid::Section {
                area: 0.0,
                centre: [origin.x, origin.z],
                second: [0.0; 3],
            }
        };
        Pressure {
            volume,
            centre,
            force,
            torque,
            plane,
        }
    }
}

/// The totals of the pressure pass, in `f64`.
#[derive(Debug, Clone, Copy)]
pub(crate) struct Pressure {
    /// Submerged volume.
    pub volume: f64,
    /// Centre of buoyancy, world.
    pub centre: DVec3,
    pub force: DVec3,
    /// About the body's origin.
    pub torque: DVec3,
    pub plane: rigid::Section,
}

impl Pressure {
    /// In `f32`, for [`Hull::submerged`]; refused when a result is too large for `f32`.
    fn submerged(&self) -> Result<Submerged> {
        let p = &self.plane;
        let out = Submerged {
            volume: self.volume as f32,
            centre_of_buoyancy: self.centre.as_vec3(),
            force: self.force.as_vec3(),
            torque: self.torque.as_vec3(),
            waterplane: Waterplane {
                area: p.area as f32,
                centre: Vec2::new(p.centre[0] as f32, p.centre[1] as f32),
                second_moments: p.second.map(|v| v as f32),
            },
        };
        let finite = out.force.is_finite() && out.torque.is_finite() && out.volume.is_finite();
        if !finite {
            return Err(Error::InvalidParam {
                name: "buoyancy force",
                value: self.force.length(),
                expected: "finite in f32: the hull is too large, deep or dense for f32",
            });
        }
        Ok(out)
    }
}
