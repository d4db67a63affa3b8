//! [`Camera`]: a perspective camera looking from an eye point at a target.

use crate::error::{Error, Result};
use glam::{Mat4, Vec3, Vec4};

/// A pinhole camera: eye, target, vertical field of view and image size.
///
/// World space is the surface's: y up, the water at rest in the plane y = 0.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Camera {
    /// Where the eye is.
    pub eye: Vec3,
    /// The point the camera looks at (the middle of the image).
    pub look_at: Vec3,
    /// Vertical field of view in degrees (default in [`Camera::new`]: `45`).
    pub fov_y_degrees: f32,
    /// Image width in pixels.
    pub width: u32,
    /// Image height in pixels.
    pub height: u32,
}

/// Nearest distance along the view direction that is drawn; closer geometry is clipped.
pub const NEAR: f32 = 0.05;

impl Camera {
    /// A camera at `eye` looking at `look_at` with a 45° vertical field of view.
    pub fn new(eye: Vec3, look_at: Vec3, width: u32, height: u32) -> Self {
        Self {
            eye,
            look_at,
            fov_y_degrees: 45.0,
            width,
            height,
        }
    }

    /// A camera framing a `cols × rows` grid of spacing `h` from above its near (+z) edge,
    /// looking down about 25°: the default view of `render`. Its distance is chosen so the
    /// far edge spans about two thirds of the image width and the water two thirds of
    /// its height (the near corners may leave the image), whatever the grid's shape.
    pub fn framing(cols: usize, rows: usize, spacing: f32, width: u32, height: u32) -> Self {
        let w = (cols.max(2) - 1) as f32 * spacing;
        let d = (rows.max(2) - 1) as f32 * spacing;
        let centre = Vec3::new(w / 2.0, 0.0, d / 2.0);
        let place = |dist: f32| {
            let eye = centre + Vec3::new(0.0, 0.39, 0.87) * dist;
            let look_at = centre + Vec3::new(0.0, -0.06, -0.03) * dist;
            Self::new(eye, look_at, width, height)
        };
        // Projected sizes shrink about as 1/distance, so scaling the distance by how much
        // too big the picture is converges in a few rounds. The targets are what a square
        // pool gets at a distance of its side (far edge ±0.647, water 1.331 of the 2-unit
        // normalised height).
        let mut dist = w.max(d);
        for _ in 0..8 {
            let vp = place(dist).view_projection();
            let ndc = |x: f32, z: f32| {
                let c = vp * Vec4::new(x, 0.0, z, 1.0);
                (c.x / c.w, c.y / c.w, c.w)
            };
            let (far_x, far_y, _) = ndc(w, 0.0);
            let (_, near_y, near_w) = ndc(w, d);
            let grow = if near_w > NEAR {
                (far_x.abs() / 0.95).max((far_y - near_y) / 1.331)
            } else {
                2.0
            };
            if !(grow.is_finite() && grow > 0.0) {
                break;
            }
            dist *= grow;
        }
        place(dist)
    }

    /// A camera straight above the middle of the grid, looking down, whose image just
    /// holds the grid's rest footprint.
    pub fn top_down(cols: usize, rows: usize, spacing: f32, width: u32, height: u32) -> Self {
        let w = (cols.max(2) - 1) as f32 * spacing;
        let d = (rows.max(2) - 1) as f32 * spacing;
        let centre = Vec3::new(w / 2.0, 0.0, d / 2.0);
        let fov: f32 = 30.0;
        let aspect = width.max(1) as f32 / height.max(1) as f32;
        let half = (d / 2.0).max(w / 2.0 / aspect);
        let height_above = half / (fov.to_radians() / 2.0).tan();
        Self {
            eye: centre + Vec3::Y * height_above,
            look_at: centre,
            fov_y_degrees: fov,
            width,
            height,
        }
    }

    /// Checks that the camera can form an image: finite points, eye ≠ target, a field of
    /// view in (0°, 180°) and an image between 1×1 and 16384×16384 pixels.
    pub fn validate(&self) -> Result<()> {
        for (name, v) in [("eye", self.eye), ("look_at", self.look_at)] {
            if !v.is_finite() {
                return Err(Error::InvalidParam {
                    name,
                    value: f64::NAN,
                    expected: "finite coordinates",
                });
            }
        }
        let dist = (self.look_at - self.eye).length();
        if dist.is_nan() || dist <= 1e-4 {
            return Err(Error::InvalidParam {
                name: "look_at",
                value: dist as f64,
                expected: "a point away from the eye",
            });
        }
        if !(self.fov_y_degrees > 0.5 && self.fov_y_degrees < 179.0) {
            return Err(Error::InvalidParam {
                name: "field of view",
                value: self.fov_y_degrees as f64,
                expected: "degrees in (0.5, 179)",
            });
        }
        for (name, v) in [("width", self.width), ("height", self.height)] {
            if !(1..=16384).contains(&v) {
                return Err(Error::InvalidParam {
                    name,
                    value: v as f64,
                    expected: "between 1 and 16384 pixels",
                });
            }
        }
        Ok(())
    }

    /// Pixels per world unit at distance 1 in the middle of the image: the focal length
    /// in pixels.
    pub fn focal_pixels(&self) -> f32 {
        self.height as f32 / 2.0 / (self.fov_y_degrees.to_radians() / 2.0).tan()
    }

    /// The [`LodParams::first_range`](crate::mesh::LodParams::first_range) at which a
    /// cell of size `spacing` facing the camera shrinks to `pixels` pixels. Beyond it the
    /// LOD halves the detail, and each further level's range is twice the previous one's,
    /// which keeps every triangle's side about `pixels` pixels or more on screen.
    pub fn lod_first_range(&self, spacing: f32, pixels: f32) -> f32 {
        self.focal_pixels() * spacing / pixels
    }

    /// World → clip space (right-handed, depth in [0, 1], w = distance along the view).
    pub fn view_projection(&self) -> Mat4 {
        let forward = (self.look_at - self.eye).normalize();
        // Straight up or down: any horizontal "up" will do; -z keeps +z at the image bottom.
        let up = if forward.cross(Vec3::Y).length_squared() < 1e-8 {
            Vec3::NEG_Z
        } else {
            Vec3::Y
        };
        let view = Mat4::look_at_rh(self.eye, self.look_at, up);
        let aspect = self.width as f32 / self.height as f32;
        let proj = Mat4::perspective_infinite_rh(self.fov_y_degrees.to_radians(), aspect, NEAR);
        proj * view
    }

    /// Pixel coordinates `(x right, y down)` and clip `w` of a world point, or `None`
    /// behind the near plane.
    pub fn project(&self, p: Vec3) -> Option<(f32, f32, f32)> {
        let c = self.view_projection() * Vec4::new(p.x, p.y, p.z, 1.0);
        (c.w > NEAR).then(|| {
            let x = (c.x / c.w * 0.5 + 0.5) * self.width as f32;
            let y = (0.5 - c.y / c.w * 0.5) * self.height as f32;
            (x, y, c.w)
        })
    }

    /// The world-space direction of the ray through pixel position `(px, py)`.
    pub fn ray(&self, px: f32, py: f32) -> Vec3 {
        let inv = self.view_projection().inverse();
        let ndc_x = px / self.width as f32 * 2.0 - 1.0;
        let ndc_y = 1.0 - py / self.height as f32 * 2.0;
        let far = inv * Vec4::new(ndc_x, ndc_y, 0.5, 1.0);
        ((far.truncate() / far.w) - self.eye).normalize()
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_target_projects_to_the_middle() {
        let cam = Camera::framing(128, 128, 1.0, 400, 300);
        cam.validate().unwrap();
        let (x, y, w) = cam.project(cam.look_at).unwrap();
        assert!(
            (x - 200.0).abs() < 1e-2 && (y - 150.0).abs() < 1e-2,
            "{x} {y}"
        );
        assert!(w > 0.0);
        let top = Camera::top_down(64, 64, 1.0, 100, 100);
        let (x, y, _) = top.project(Vec3::new(31.5, 0.0, 31.5)).unwrap();
        assert!((x - 50.0).abs() < 1e-2 && (y - 50.0).abs() < 1e-2);
        // +x to the right, +z down the image when looking straight down.
        let (x1, y1, _) = top.project(Vec3::new(40.0, 0.0, 40.0)).unwrap();
        assert!(x1 > x && y1 > y);
    }

    #[test]
    fn rays_go_through_their_pixels() {
        let cam = Camera::framing(64, 32, 1.0, 320, 240);
        let d = cam.ray(100.0, 70.0);
        let (x, y, _) = cam.project(cam.eye + d * 30.0).unwrap();
        assert!(
            (x - 100.0).abs() < 0.05 && (y - 70.0).abs() < 0.05,
            "{x} {y}"
        );
    }

    #[test]
    fn bad_cameras_are_refused() {
        let mut cam = Camera::framing(64, 64, 1.0, 320, 240);
        cam.look_at = cam.eye;
        assert!(cam.validate().is_err());
        let mut cam = Camera::framing(64, 64, 1.0, 0, 240);
        assert!(cam.validate().is_err());
        cam.width = 10;
        cam.eye.x = f32::INFINITY;
        assert!(cam.validate().is_err());
    }
}
