//! Solids drawn with the water, sharing its depth buffer: floating balls (a buoy, the
//! object making a wake) and facets (the triangles of a hull or a crate). The water hides
//! them where it is in front of them, and they hide the water behind them.
//!
//! Both come through the water's shader as vertices of reflectance 1 whose "sky" is their
//! lit colour, so a pixel of a solid is its colour.

use super::camera::Camera;
use super::raster::{ClipVertex, Rasteriser, NO_WIRE};
use super::Look;
use glam::Vec3;

/// A floating ball drawn with the water (a buoy, a toy boat, the object making a wake):
/// two-coloured stripes, lit by the sun.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Ball {
    /// Centre in the water's space.
    pub centre: Vec3,
    /// Radius in world units.
    pub radius: f32,
    /// The colours of its alternate stripes, linear RGB.
    pub colours: [[f32; 3]; 2],
}

/// A triangle of a solid drawn with the water: its corners in the water's space, and its
/// colour (linear RGB), lit flat by the sun: an ambient part and a diffuse part from its
/// normal (the side its corners turn counter-clockwise about faces out).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Facet {
    /// The corners, counter-clockwise seen from outside the solid.
    pub corners: [Vec3; 3],
    /// Colour, linear RGB.
    pub colour: [f32; 3],
}

/// Triangulates a ball as a 12 × 16 latitude-longitude sphere and pushes it, each vertex
/// coloured by its stripe and lit by the sun (ambient plus diffuse plus a highlight).
pub(super) fn push_ball(
    raster: &mut Rasteriser,
    ball: &Ball,
    camera: &Camera,
    look: &Look,
    width: usize,
    height: usize,
) {
    const RINGS: usize = 12;
    const SEGMENTS: usize = 16;
    let vp = camera.view_projection();
    let sun = look.sun.normalize();
    let vertex = |ring: usize, seg: usize| -> ClipVertex {
        let theta = std::f32::consts::PI * ring as f32 / RINGS as f32;
        let phi = std::f32::consts::TAU * seg as f32 / SEGMENTS as f32;
        let n = Vec3::new(
            theta.sin() * phi.cos(),
            theta.cos(),
            theta.sin() * phi.sin(),
        );
        let p = ball.centre + n * ball.radius;
        // Three stripes: colour 0 at the poles and colour 1 round the middle.
        let stripe = ball.colours[usize::from((RINGS / 3..2 * RINGS / 3).contains(&ring))];
        let to_eye = (camera.eye - p).normalize_or(Vec3::Y);
        let half = (to_eye + sun).normalize_or(Vec3::Y);
        let diffuse = n.dot(sun).max(0.0);
        let highlight = 0.5 * n.dot(half).max(0.0).powi(40);
        let c = stripe.map(|s| s * (0.35 + 0.75 * diffuse) + highlight);
        let values = [0.0, 0.0, 1.0, 0.0, 0.0, 0.0, c[0], c[1], c[2]];
        ClipVertex {
            clip: vp * p.extend(1.0),
            values,
        }
    };
    for ring in 0..RINGS {
        for seg in 0..SEGMENTS {
            let (a, b) = (vertex(ring, seg), vertex(ring, seg + 1));
            let (c, d) = (vertex(ring + 1, seg), vertex(ring + 1, seg + 1));
            raster.push([a, c, b], NO_WIRE, width, height);
            raster.push([b, c, d], NO_WIRE, width, height);
        }
    }
}

/// Pushes every facet, flat-lit: `colour × (0.35 + 0.75 max(0, n · sun))`.
pub(super) fn push_facets(
    raster: &mut Rasteriser,
    facets: &[Facet],
    camera: &Camera,
    look: &Look,
    width: usize,
    height: usize,
) {
    let vp = camera.view_projection();
    let sun = look.sun.normalize();
    for f in facets {
        let [a, b, c] = f.corners;
        let n = (b - a).cross(c - a).normalize_or_zero();
        let light = 0.35 + 0.75 * n.dot(sun).max(0.0);
        let [r, g, b_] = f.colour.map(|c| c * light);
        let values = [0.0, 0.0, 1.0, 0.0, 0.0, 0.0, r, g, b_];
        let v = f.corners.map(|p| ClipVertex {
            clip: vp * p.extend(1.0),
            values,
        });
        raster.push(v, NO_WIRE, width, height);
    }
}
