//! Small bodies: balls and boxes at most 1.75 cells of the water from centre to corner (a
//! cube of side 2, a ball 3.5 cells across), which meet the water as a plane.
//!
//! # Why a cheaper model
//!
//! The per-triangle model (the `hydrostatics` module) samples the water at every corner
//! and every wet piece of a body's mesh cut into triangles a cell across. For a body a few
//! cells across, that is 10 to 60 wet pieces sampling the same 4 to 16 nodes; the water
//! under it is taken as one plane (measured against the triangles in
//! `tests/rigid_bodies.rs` and `docs/floating.md`). So a small body samples
//! the water once, at its centre `c`: the height `η₀` and the slope `(s_x, s_z)` of the
//! bilinear blend there (its gradient), and the water below is the half-space
//!
//! ```text
//! d(r) = η₀ + s_x (x − c_x) + s_z (z − c_z) − y > 0
//! ```
//!
//! (`d` the depth under the plane, measured vertically, as the per-triangle model
//! measures it).
//!
//! # Pressure under a plane
//!
//! The pressure `p = ρ g d` is linear in position, so the divergence theorem over the
//! submerged volume `V` (closed by the water plane, where `p = 0`) gives the force and its
//! torque about any point `o` in closed form:
//!
//! ```text
//! F = −∫_V ∇p dV = ρ g V a,   a = (−s_x, 1, −s_z)        τ = (B − o) × F
//! ```
//!
//! with `B` the centroid of the submerged volume: the force is normal to the plane, acts
//! through the centre of buoyancy, and its vertical part is `ρ g V`, as in still water.
//! What is left is `V`, `B` and the waterplane (the body's section by the water plane,
//! seen from above) for the implicit step's stiffness:
//!
//! * **A ball** of radius `R` is cut by the plane into a cap. With `n = a / |a|` the
//!   plane's unit normal and `δ = (η₀ − c_y) / |a|` the centre's distance below it, the
//!   cap under water has height `k = R + δ` (clamped to `[0, 2R]`), volume
//!   `V = π k² (3R − k) / 3` and centroid `B = c − n · 3 (2R − k)² / (4 (3R − k))`; the
//!   section is a disc of radius² `R² − δ²` about `c + δ n`, which seen from above is an
//!   ellipse: area `π (R² − δ²) n_y`, second moments `π (R² − δ²)² / 4 · n_y (1 − n nᵀ)`
//!   (the horizontal block). `B − c` is along `n`, so the force passes through the centre
//!   and turns nothing.
//! * **A box** is its 12 triangles clipped at the plane by the per-triangle pass
//!   (`Hull::pressed`), which against a plane is exact at any heel: eight corners, twelve
//!   triangles, no sampling.
//!
//! The body then steps like any other (the `rigid` module) with a single wet piece: the
//! pressure force `F` at `B`, and the drag pulling `B` towards the water's velocity there,
//! at the body's whole drag rate `k ρ V`. Its reaction goes into the water at `B`, and
//! the waterplane stiffness's at four points of the section, as for every body: the water
//! gets exactly minus the body's force and torque.
//!
//! What the plane cannot see: waves shorter than about four cells under a body (the
//! bilinear slope is one cell's), and the drag on a small body's spin about `B` (one drag
//! point turns only about its lever arm to the centre of mass).

use super::hydrostatics::Pressure;
use super::rigid::Section;
use super::{Hull, HullScratch};
use crate::error::Result;
use glam::{DVec3, Quat, Vec3};
use std::f64::consts::PI;

/// The water under a small body as a plane: its height at the world point `(x, z)` and
/// its slope `[∂η/∂x, ∂η/∂z]`.
#[derive(Debug, Clone, Copy)]
pub(crate) struct Plane {
    pub at: [f64; 2],
    pub height: f64,
    pub slope: [f64; 2],
}

impl Plane {
    /// The plane's height at world `(x, z)`.
    fn height_at(&self, x: f64, z: f64) -> f64 {
        self.height + self.slope[0] * (x - self.at[0]) + self.slope[1] * (z - self.at[1])
    }
}

/// What the water plane does to a small body: the submerged volume, its centroid `B`
/// (world; the body's position when dry), the pressure force (through `B`) and the
/// waterplane.
#[derive(Debug, Clone, Copy)]
pub(crate) struct Wet {
    pub volume: f64,
    pub centre: DVec3,
    pub force: DVec3,
    pub plane: Section,
}

/// A ball of `radius` centred at `centre` in the water below `water` (see the module docs).
pub(crate) fn sphere(radius: f64, centre: DVec3, water: Plane, rho_g: f64) -> Wet {
    let r = radius;
    let [sx, sz] = water.slope;
    let a = DVec3::new(-sx, 1.0, -sz);
    let norm = (1.0 + sx * sx + sz * sz).sqrt();
    let n = a / norm;
    let delta = (water.height_at(centre.x, centre.z) - centre.y) / norm;
    let k = r + delta;
    let no_plane = Section {
        area: 0.0,
        centre: [centre.x, centre.z],
        second: [0.0; 3],
    };
    if k <= 0.0 {
        return Wet {
            volume: 0.0,
            centre,
            force: DVec3::ZERO,
            plane: no_plane,
        };
    }
    if k >= 2.0 * r {
        let volume = 4.0 / 3.0 * PI * r * r * r;
        return Wet {
            volume,
            centre,
            force: a * (rho_g * volume),
            plane: no_plane,
        };
    }
    let volume = PI * k * k * (3.0 * r - k) / 3.0;
    let below = 3.0 * (2.0 * r - k) * (2.0 * r - k) / (4.0 * (3.0 * r - k));
    // The section: a disc of radius² r² − δ² = k (2r − k), seen from above.
    let disc = k * (2.0 * r - k);
    let area = PI * disc * n.y;
    let second = 0.25 * PI * disc * disc * n.y;
    Wet {
        volume,
        centre: centre - n * below,
        force: a * (rho_g * volume),
        plane: Section {
            area,
            centre: [centre.x + delta * n.x, centre.z + delta * n.z],
            second: [
                second * (1.0 - n.x * n.x),
                -second * n.x * n.z,
                second * (1.0 - n.z * n.z),
            ],
        },
    }
}

/// A small body of the closed `mesh` (a box's 12 triangles) at `position` and
/// `orientation`, in the water below `water`: its triangles clipped at the plane.
pub(crate) fn mesh(
    mesh: &Hull,
    position: Vec3,
    orientation: Quat,
    water: Plane,
    rho_g: f64,
    scratch: &mut HullScratch,
) -> Result<Wet> {
    let Pressure {
        volume,
        centre,
        force,
        plane,
        ..
    } = mesh.pressed(
        position,
        orientation,
        rho_g,
        |x, z| water.height_at(x as f64, z as f64) as f32,
        scratch,
        |_, _, _| {},
    )?;
    Ok(Wet {
        volume,
        centre,
        force,
        plane,
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    fn calm(height: f64) -> Plane {
        Plane {
            at: [0.0, 0.0],
            height,
            slope: [0.0, 0.0],
        }
    }

    #[test]
    fn a_ball_half_under_displaces_half_its_volume_through_its_lower_half() {
        let wet = sphere(2.0, DVec3::new(3.0, 0.0, 4.0), calm(0.0), 10.0);
        let half = 2.0 / 3.0 * PI * 8.0;
        assert!((wet.volume - half).abs() < 1e-12 * half);
        // The centroid of a half ball is 3R/8 below its centre.
        assert!((wet.centre - DVec3::new(3.0, -0.75, 4.0)).length() < 1e-12);
        assert!((wet.force - DVec3::new(0.0, 10.0 * half, 0.0)).length() < 1e-9);
        assert!((wet.plane.area - 4.0 * PI).abs() < 1e-12);
        assert!((wet.plane.second[0] - PI * 16.0 / 4.0).abs() < 1e-12);
        assert!(wet.plane.second[1].abs() < 1e-12);
    }

    #[test]
    fn a_ball_on_a_slope_is_pushed_along_the_plane_normal_through_its_centre() {
        let water = Plane {
            at: [0.0, 0.0],
            height: 0.3,
            slope: [0.2, -0.1],
        };
        let c = DVec3::new(0.5, 0.0, -0.25);
        let wet = sphere(1.0, c, water, 1.0);
        // The force is along (−s_x, 1, −s_z) and its line passes through the centre.
        let a = DVec3::new(-0.2, 1.0, 0.1);
        assert!(wet.force.cross(a).length() < 1e-12 * wet.force.length());
        assert!((wet.centre - c).cross(wet.force).length() < 1e-12 * wet.force.length());
        // The vertical force is ρ g V, the volume a cap's.
        assert!((wet.force.y - wet.volume).abs() < 1e-12);
        assert!(wet.volume > 0.0 && wet.volume < 4.0 / 3.0 * PI);
    }

    #[test]
    fn a_cube_cut_through_its_centre_by_a_tilted_plane_displaces_half() {
        // A cube's displaced volume under a plane through its centre is half, whatever
        // the slope (the plane cuts it into two congruent halves).
        let cube = Hull::cuboid([0.5, 0.5, 0.5]).unwrap();
        let water = Plane {
            at: [2.0, 1.0],
            height: 0.0,
            slope: [0.3, 0.1],
        };
        let mut scratch = HullScratch::new();
        let pos = Vec3::new(2.0, 0.0, 1.0);
        let wet = mesh(&cube, pos, Quat::IDENTITY, water, 1.0, &mut scratch).unwrap();
        assert!((wet.volume - 0.5).abs() < 1e-6, "{}", wet.volume);
        assert!((wet.force - DVec3::new(-0.3, 1.0, -0.1) * 0.5).length() < 1e-6);
    }
}
