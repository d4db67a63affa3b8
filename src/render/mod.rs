//! A CPU preview renderer: the water drawn in perspective, the pool bottom seen through
//! it, the sky reflected in it (feature `render`).
//!
//! ```
//! use springwater::render::{Camera, Renderer, RenderParams, Texture};
//! use springwater::{Params, Surface};
//!
//! let mut water = Surface::new(Params::with_size(48, 48))?;
//! water.drop_at(24.0, 24.0, -1.5, 3.0)?;
//! for _ in 0..20 {
//!     water.step()?;
//! }
//! let camera = Camera::framing(48, 48, 1.0, 160, 120);
//! let mut renderer = Renderer::new(RenderParams::default(), Texture::pool_tiles(256))?;
//! let frame = renderer.render(&water.mesh_view(), &camera)?;
//! assert_eq!(frame.rgb().len(), 160 * 120 * 3);
//! # Ok::<(), springwater::Error>(())
//! ```
//!
//! # What a frame is made of
//!
//! For every node the renderer takes the crate's render-side stages as they are:
//! [`compute_normals`], the view-dependent [`LodMesh`] and [`refract`] (bottom UV and
//! Fresnel per node). It adds, per node, the light transmitted from the bottom to the eye
//! (absorption along the refracted path, times caustic light) and the sky colour
//! reflected about the normal (a zenith-to-horizon gradient plus a sun glint), and then
//! rasterises the LOD triangles, interpolating those values perspective-correctly. Each
//! pixel samples the bottom texture at its interpolated UV and mixes
//! `bottom × transmitted` with `sky` by the Fresnel term. Pixels no triangle covers show
//! the pool deck (the plane y = 0 around the water) or the sky. Floating [`Ball`]s (a
//! buoy, the object making a wake) and the [`Facet`]s of solids (a hull, a crate) are
//! drawn with the water, sharing its depth buffer: the water hides them where it is in
//! front of them.
//!
//! **Caustics** use the area-ratio method: the sunlight is refracted through every
//! node with the same [`refract`] call (the eye far away along the sun direction), and
//! each cell's light is concentrated by `rest area / area of its refracted quad on the
//! bottom`. A node averages the ratios of its cells; the eye's view of the bottom at UV
//! `(u, v)` is lit by that map sampled at `(u, v)`. The map is kept at the node it
//! comes from rather than moved to where its light lands, which shifts it by
//! `depth × slope / ior` (a fraction of a cell for the default waves): cheap, and
//! invisible in motion.
//!
//! # Why it lives in the library, and why it is hand-written
//!
//! The renderer is in the library, behind the `render` feature (which the
//! `springwater-cli` crate turns on), not in the binary: its tests can check pixels
//! without parsing a GIF, and a game can use it as a CPU preview or a reference image for
//! its GPU shader. It needs nothing beyond what the library already depends on (`glam`,
//! and `rayon` under `parallel`).
//!
//! The rasteriser (the private `raster` module) is about 250 lines written for this job
//! rather than a crate: what it draws is one kind of primitive (triangles with nine
//! interpolated values over a depth buffer), and writing it lets it split the image into
//! bands of rows that rayon shades in parallel while the picture stays bit-identical for
//! any thread count, with no `unsafe` (only the lane layer, `src/simd/`, and the engine
//! have any). Of the crates looked at, tiny-skia draws 2-D paths with no per-vertex
//! values to interpolate, and euc (shaders behind its own `Pipeline` trait, maths in
//! `vek` types) would mean converting our data to its types and leaving the parallel
//! split, and whether the picture depends on it, to a dependency; the glue would be about
//! as long as the rasteriser.

mod camera;
mod raster;
mod solids;
mod texture;

use std::time::{Duration, Instant};

use glam::Vec3;

pub use camera::Camera;
pub use solids::{Ball, Facet};
pub use texture::Texture;

use crate::error::{Error, Result};
use crate::mesh::{compute_normals, LodMesh, LodParams, Normals};
use crate::refraction::{refract, Refraction, RefractionParams};
use crate::view::MeshView;
use raster::{ClipVertex, Rasteriser, Target, VALUES};
use solids::{push_ball, push_facets};
use texture::SrgbEncoder;

/// How the scene looks. Colours are linear RGB in `[0, 1]`.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Look {
    /// Sky colour straight up (default: a deep blue).
    pub sky_zenith: [f32; 3],
    /// Sky colour at the horizon (default: a pale blue).
    pub sky_horizon: [f32; 3],
    /// Direction towards the sun (default: behind the pool, 30° up); normalised on use.
    pub sun: Vec3,
    /// Brightness of the sun's glint on the water (default: `6.0`; 0 turns it off).
    pub glint: f32,
    /// Light absorbed per unit of path length in the water, per channel (default:
    /// `[0.05, 0.016, 0.011]`, a blue-green tint that deepens with depth and slant).
    pub absorption: [f32; 3],
    /// Strength of the caustics: light on the bottom is `1 + caustics × (ratio − 1)`
    /// (default: `1.3`; 0 turns them off, and a flat surface is lit by exactly 1).
    pub caustics: f32,
    /// Draw the deck and sky around the water; off, pixels no triangle covers are black
    /// (default: `true`).
    pub surroundings: bool,
}

impl Default for Look {
    fn default() -> Self {
        Self {
            sky_zenith: [0.045, 0.16, 0.48],
            sky_horizon: [0.62, 0.76, 0.90],
            sun: Vec3::new(-0.2, 0.5, -0.85),
            glint: 6.0,
            absorption: [0.05, 0.016, 0.011],
            caustics: 1.3,
            surroundings: true,
        }
    }
}

impl Look {
    /// Checks that colours, absorption, glint and caustics are finite and ≥ 0 and the sun
    /// direction finite and non-zero.
    pub fn validate(&self) -> Result<()> {
        for c in self.sky_zenith.iter().chain(&self.sky_horizon) {
            crate::params::non_negative("sky colour", *c)?;
        }
        for a in self.absorption {
            crate::params::non_negative("absorption", a)?;
        }
        crate::params::non_negative("glint", self.glint)?;
        crate::params::non_negative("caustics", self.caustics)?;
        if !self.sun.is_finite() || self.sun.length_squared() < 1e-12 {
            return Err(Error::InvalidParam {
                name: "sun",
                value: self.sun.length() as f64,
                expected: "a finite non-zero direction",
            });
        }
        Ok(())
    }
}

/// Everything that sets up a [`Renderer`].
#[derive(Debug, Clone, Copy)]
pub struct RenderParams {
    /// Bottom depth and index of refraction.
    pub refraction: RefractionParams,
    /// Level-of-detail parameters. With [`RenderParams::lod_pixels`] set, its
    /// `first_range` is replaced by the camera's.
    pub lod: LodParams,
    /// On-screen size in pixels of a cell at the first LOD range (default: `Some(1.5)`):
    /// the renderer sets `lod.first_range` from the camera with
    /// [`Camera::lod_first_range`], so triangles stay at least this big on screen and
    /// the ripples keep full detail wherever the grid is coarser than the pixels.
    /// `None` uses `lod.first_range` as given.
    pub lod_pixels: Option<f32>,
    /// Colours, sun, absorption, caustics.
    pub look: Look,
    /// Overlay the triangle edges, coloured by LOD level (default: `false`).
    pub wireframe: bool,
}

impl Default for RenderParams {
    fn default() -> Self {
        Self {
            refraction: RefractionParams::default(),
            lod: LodParams::default(),
            lod_pixels: Some(1.5),
            look: Look::default(),
            wireframe: false,
        }
    }
}

/// Wall time the last frame spent in each stage.
#[derive(Debug, Clone, Copy, PartialEq, Default)]
pub struct StageTimes {
    /// [`compute_normals`].
    pub normals: Duration,
    /// [`LodMesh::update`].
    pub lod: Duration,
    /// [`refract`] for the eye, and for the sun with the caustic map.
    pub refraction: Duration,
    /// Per-node colours, triangle setup, rasterising and shading, sRGB encoding.
    pub drawing: Duration,
}

impl std::ops::AddAssign for StageTimes {
    fn add_assign(&mut self, o: Self) {
        self.normals += o.normals;
        self.lod += o.lod;
        self.refraction += o.refraction;
        self.drawing += o.drawing;
    }
}

/// An 8-bit sRGB image, row by row, 3 bytes per pixel.
#[derive(Debug, Clone, PartialEq, Eq, Default)]
pub struct Frame {
    width: usize,
    height: usize,
    rgb: Vec<u8>,
}

impl Frame {
    /// Width in pixels.
    pub fn width(&self) -> usize {
        self.width
    }

    /// Height in pixels.
    pub fn height(&self) -> usize {
        self.height
    }

    /// The pixels, `[r, g, b]` per pixel, row by row from the top.
    pub fn rgb(&self) -> &[u8] {
        &self.rgb
    }

    /// The pixel at `(x, y)`, `(0, 0)` top left.
    pub fn pixel(&self, x: usize, y: usize) -> [u8; 3] {
        let i = (y * self.width + x) * 3;
        [self.rgb[i], self.rgb[i + 1], self.rgb[i + 2]]
    }
}

/// Draws frames of a surface. Owns every buffer it needs and keeps them between frames.
#[derive(Debug)]
pub struct Renderer {
    params: RenderParams,
    bottom: Texture,
    normals: Normals,
    lod: LodMesh,
    eye_uv: Refraction,
    sun_uv: Refraction,
    caustic: Vec<f32>,
    caustic_counts: Vec<u8>,
    vertices: Vec<ClipVertex>,
    raster: Rasteriser,
    linear: Vec<[f32; 3]>,
    frame: Frame,
    encoder: SrgbEncoder,
    times: StageTimes,
    balls: Vec<Ball>,
    facets: Vec<Facet>,
    /// The rest footprint `(width, depth)` of the last surface drawn, world units.
    footprint: (f32, f32),
}

/// Highest light concentration a caustic may reach (folded quads would be infinite).
const MAX_CAUSTIC: f32 = 4.0;

impl Renderer {
    /// A renderer with `params`, showing `bottom` on the pool floor (the texture spans
    /// the grid's rest footprint).
    pub fn new(params: RenderParams, bottom: Texture) -> Result<Self> {
        params.refraction.validate()?;
        if let Some(p) = params.lod_pixels {
            crate::params::positive("lod pixels", p)?;
        }
        params.look.validate()?;
        Ok(Self {
            lod: LodMesh::new(params.lod)?,
            params,
            bottom,
            normals: Normals::default(),
            eye_uv: Refraction::default(),
            sun_uv: Refraction::default(),
            caustic: Vec::new(),
            caustic_counts: Vec::new(),
            vertices: Vec::new(),
            raster: Rasteriser::new(),
            linear: Vec::new(),
            frame: Frame::default(),
            encoder: SrgbEncoder::new(),
            times: StageTimes::default(),
            balls: Vec::new(),
            facets: Vec::new(),
            footprint: (0.0, 0.0),
        })
    }

    /// The parameters.
    pub fn params(&self) -> &RenderParams {
        &self.params
    }

    /// Changes the look and the wireframe overlay from the next frame on. On error
    /// nothing changes.
    pub fn set_look(&mut self, look: Look, wireframe: bool) -> Result<()> {
        look.validate()?;
        self.params.look = look;
        self.params.wireframe = wireframe;
        Ok(())
    }

    /// Sets the balls drawn from the next frame on (none by default). Balls with a
    /// non-finite centre or a radius that is not finite and > 0 are refused.
    pub fn set_balls(&mut self, balls: &[Ball]) -> Result<()> {
        for b in balls {
            if !b.centre.is_finite() {
                return Err(Error::InvalidParam {
                    name: "ball centre",
                    value: f64::NAN,
                    expected: "finite coordinates",
                });
            }
            crate::params::positive("ball radius", b.radius)?;
            for c in b.colours.iter().flatten() {
                crate::params::non_negative("ball colour", *c)?;
            }
        }
        self.balls.clear();
        self.balls.extend_from_slice(balls);
        Ok(())
    }

    /// Sets the facets drawn from the next frame on (none by default): the triangles of
    /// solids such as hulls, drawn with the water and hidden where it is in front of
    /// them. A facet with a corner that is not finite, or a colour that is not finite and
    /// ≥ 0, is refused (and nothing changes).
    pub fn set_facets(&mut self, facets: &[Facet]) -> Result<()> {
        for f in facets {
            if !f.corners.iter().all(|c| c.is_finite()) {
                return Err(Error::InvalidParam {
                    name: "facet corner",
                    value: f64::NAN,
                    expected: "finite coordinates",
                });
            }
            for c in f.colour {
                crate::params::non_negative("facet colour", c)?;
            }
        }
        self.facets.clear();
        self.facets.extend_from_slice(facets);
        Ok(())
    }

    /// Forgets the LOD levels of earlier frames (their hysteresis), so the next frame is
    /// drawn as by a new renderer.
    pub fn reset(&mut self) -> Result<()> {
        self.lod = LodMesh::new(self.params.lod)?;
        Ok(())
    }

    /// The last frame drawn.
    pub fn frame(&self) -> &Frame {
        &self.frame
    }

    /// Time spent in each stage by the last [`Renderer::render`].
    pub fn times(&self) -> StageTimes {
        self.times
    }

    /// The LOD mesh as last updated (for its levels and triangle count).
    pub fn lod(&self) -> &LodMesh {
        &self.lod
    }

    /// Draws `view` seen by `camera` and returns the frame.
    pub fn render(&mut self, view: &MeshView<'_>, camera: &Camera) -> Result<&Frame> {
        camera.validate()?;
        let (width, height) = (camera.width as usize, camera.height as usize);
        let h = view.spacing();
        self.footprint = ((view.cols() - 1) as f32 * h, (view.rows() - 1) as f32 * h);

        let t = Instant::now();
        compute_normals(view, &mut self.normals);
        let t_normals = t.elapsed();

        let t = Instant::now();
        if let Some(pixels) = self.params.lod_pixels {
            let first_range = camera.lod_first_range(view.spacing(), pixels);
            if self.lod.params().first_range != first_range {
                let lod = LodParams {
                    first_range,
                    ..self.params.lod
                };
                self.lod = LodMesh::new(lod)?;
                self.params.lod = lod;
            }
        }
        self.lod.update(view, camera.eye);
        let t_lod = t.elapsed();

        let t = Instant::now();
        refract(
            view,
            &self.normals,
            camera.eye,
            &self.params.refraction,
            &mut self.eye_uv,
        )?;
        self.caustic_map(view)?;
        let t_refraction = t.elapsed();

        let t = Instant::now();
        self.node_vertices(view, camera);
        self.draw(camera, width, height);
        let t_drawing = t.elapsed();

        self.times = StageTimes {
            normals: t_normals,
            lod: t_lod,
            refraction: t_refraction,
            drawing: t_drawing,
        };
        Ok(&self.frame)
    }

    /// Refracts the sunlight through every node and turns each cell's change of area on
    /// the bottom into a light concentration per node.
    fn caustic_map(&mut self, view: &MeshView<'_>) -> Result<()> {
        let (cols, rows) = (view.cols(), view.rows());
        self.caustic.clear();
        self.caustic.resize(cols * rows, 1.0);
        if self.params.look.caustics == 0.0 {
            return Ok(());
        }
        let h = view.spacing();
        let (w, d) = ((cols - 1) as f32 * h, (rows - 1) as f32 * h);
        let centre = Vec3::new(w / 2.0, 0.0, d / 2.0);
        // Far enough that the rays are parallel to well under a texel, near enough
        // that f32 keeps the node positions' precision.
        let sun = centre + self.params.look.sun.normalize() * (1.0e4 * (1.0 + w.max(d)));
        refract(
            view,
            &self.normals,
            sun,
            &self.params.refraction,
            &mut self.sun_uv,
        )?;
        let (u, v) = (&self.sun_uv.u, &self.sun_uv.v);
        // Rest area of a cell in UV units is 1 / ((cols − 1)(rows − 1)).
        let rest = 1.0 / ((cols - 1) * (rows - 1)) as f32;
        let sums = &mut self.caustic;
        sums.fill(0.0);
        let counts = &mut self.caustic_counts;
        counts.clear();
        counts.resize(cols * rows, 0);
        for r in 0..rows - 1 {
            for c in 0..cols - 1 {
                let a = r * cols + c;
                let (b, cc, dd) = (a + 1, a + cols, a + cols + 1);
                // Shoelace area of the quad a, b, d, c.
                let area = 0.5
                    * ((u[a] * v[b] - u[b] * v[a])
                        + (u[b] * v[dd] - u[dd] * v[b])
                        + (u[dd] * v[cc] - u[cc] * v[dd])
                        + (u[cc] * v[a] - u[a] * v[cc]))
                        .abs();
                let ratio = if area * MAX_CAUSTIC > rest {
                    rest / area
                } else {
                    MAX_CAUSTIC
                };
                let ratio = if ratio.is_finite() { ratio } else { 1.0 };
                for n in [a, b, cc, dd] {
                    sums[n] += ratio;
                    counts[n] += 1;
                }
            }
        }
        for (s, &k) in sums.iter_mut().zip(counts.iter()) {
            *s = if k > 0 { *s / k as f32 } else { 1.0 };
        }
        Ok(())
    }

    /// Clip position and shading values of every node.
    fn node_vertices(&mut self, view: &MeshView<'_>, camera: &Camera) {
        let (cols, rows) = (view.cols(), view.rows());
        let h = view.spacing();
        let (w, d) = ((cols - 1) as f32 * h, (rows - 1) as f32 * h);
        let vp = camera.view_projection();
        let look = self.params.look;
        let sun = look.sun.normalize();
        let depth = self.params.refraction.depth;
        let caustic = &self.caustic;
        let sample_caustic = |u: f32, v: f32| -> f32 {
            let x = (u * (cols - 1) as f32).clamp(0.0, (cols - 1) as f32);
            let y = (v * (rows - 1) as f32).clamp(0.0, (rows - 1) as f32);
            let (x0, y0) = ((x as usize).min(cols - 2), (y as usize).min(rows - 2));
            let (fx, fy) = (x - x0 as f32, y - y0 as f32);
            let fx = if fx.is_finite() { fx } else { 0.0 };
            let fy = if fy.is_finite() { fy } else { 0.0 };
            let i = y0 * cols + x0;
            let top = caustic[i] + (caustic[i + 1] - caustic[i]) * fx;
            let bottom = caustic[i + cols] + (caustic[i + cols + 1] - caustic[i + cols]) * fx;
            top + (bottom - top) * fy
        };
        let (eu, ev, ef) = (&self.eye_uv.u, &self.eye_uv.v, &self.eye_uv.fresnel);
        let normals = &self.normals;
        let vertex = |i: usize| -> ClipVertex {
            let p = view.position(i);
            let n = Vec3::new(normals.x[i], normals.y[i], normals.z[i]);
            let (u, v, f) = (eu[i], ev[i], ef[i].clamp(0.0, 1.0));
            let view_dir = (p - camera.eye).normalize_or(Vec3::NEG_Y);
            // Light from the bottom: absorbed along the refracted path, lit by caustics.
            let hit = Vec3::new(u * w, -depth, v * d);
            let path = (hit - p).length().min(1.0e4);
            let light = (1.0 + look.caustics * (sample_caustic(u, v) - 1.0)).max(0.0);
            let trans = look.absorption.map(|a| (-a * path).exp() * light);
            // The sky seen in the mirror direction.
            let mut r = view_dir - 2.0 * view_dir.dot(n) * n;
            r.y = r.y.abs();
            let sky = sky_colour(&look, r);
            let glint = look.glint * r.dot(sun).max(0.0).powi(64);
            let values = [
                u,
                v,
                f,
                trans[0],
                trans[1],
                trans[2],
                sky[0] + glint,
                sky[1] + glint,
                sky[2] + glint,
            ];
            let values = values.map(|x| if x.is_finite() { x } else { 0.0 });
            ClipVertex {
                clip: vp * p.extend(1.0),
                values,
            }
        };
        self.vertices.clear();
        self.vertices.resize(
            cols * rows,
            ClipVertex {
                clip: glam::Vec4::ZERO,
                values: [0.0; VALUES],
            },
        );
        #[cfg(feature = "parallel")]
        {
            use rayon::prelude::*;
            self.vertices
                .par_iter_mut()
                .enumerate()
                .with_min_len(1024)
                .for_each(|(i, out)| *out = vertex(i));
        }
        #[cfg(not(feature = "parallel"))]
        for (i, out) in self.vertices.iter_mut().enumerate() {
            *out = vertex(i);
        }
    }

    /// Background, triangles, sRGB.
    fn draw(&mut self, camera: &Camera, width: usize, height: usize) {
        let look = self.params.look;
        self.linear.clear();
        self.linear.resize(width * height, [0.0; 3]);

        self.raster.begin(width, height);
        let indices = self.lod.indices();
        let levels = self.lod.triangle_levels();
        for (t, tri) in indices.chunks_exact(3).enumerate() {
            let v = [tri[0], tri[1], tri[2]].map(|i| self.vertices[i as usize]);
            self.raster
                .push(v, levels.get(t).copied().unwrap_or(0), width, height);
        }
        for ball in &self.balls {
            push_ball(&mut self.raster, ball, camera, &look, width, height);
        }
        push_facets(&mut self.raster, &self.facets, camera, &look, width, height);
        let bottom = &self.bottom;
        // Balls and facets come through the same shader: reflectance 1 and their colour as
        // the "sky", so a pixel of either is its colour.
        let shade = |v: &[f32; VALUES]| -> [f32; 3] {
            let tex = bottom.sample(v[0], v[1]);
            let f = v[2];
            [0, 1, 2].map(|k| tex[k] * v[3 + k] * (1.0 - f) + v[6 + k] * f)
        };
        let rays = Rays::new(camera);
        let footprint = self.footprint;
        let background = |px: usize, py: usize| {
            if look.surroundings {
                surroundings(&look, &rays, footprint, px as f32 + 0.5, py as f32 + 0.5)
            } else {
                [0.0; 3]
            }
        };
        let target = Target {
            width,
            height,
            colour: &mut self.linear,
        };
        let wire = self.params.wireframe.then_some((&wire_colour, 0.7));
        self.raster.draw(target, &shade, wire, &background);

        let encoder = &self.encoder;
        self.frame.width = width;
        self.frame.height = height;
        self.frame.rgb.clear();
        self.frame.rgb.resize(width * height * 3, 0);
        let encode = |(src, dst): (&[f32; 3], &mut [u8])| {
            for k in 0..3 {
                dst[k] = encoder.encode(src[k]);
            }
        };
        #[cfg(feature = "parallel")]
        {
            use rayon::prelude::*;
            self.linear
                .par_iter()
                .zip(self.frame.rgb.par_chunks_exact_mut(3))
                .with_min_len(4096)
                .for_each(encode);
        }
        #[cfg(not(feature = "parallel"))]
        self.linear
            .iter()
            .zip(self.frame.rgb.chunks_exact_mut(3))
            .for_each(encode);
    }
}

/// Rays through pixel positions: `corner + x·dx + y·dy` (not normalised).
#[derive(Debug, Clone, Copy)]
struct Rays {
    eye: Vec3,
    corner: Vec3,
    dx: Vec3,
    dy: Vec3,
}

impl Rays {
    fn new(camera: &Camera) -> Self {
        let forward = (camera.look_at - camera.eye).normalize();
        let up_hint = if forward.cross(Vec3::Y).length_squared() < 1e-8 {
            Vec3::NEG_Z
        } else {
            Vec3::Y
        };
        let right = forward.cross(up_hint).normalize();
        let up = right.cross(forward);
        let half_h = (camera.fov_y_degrees.to_radians() / 2.0).tan();
        let half_w = half_h * camera.width as f32 / camera.height as f32;
        let dx = right * (2.0 * half_w / camera.width as f32);
        let dy = -up * (2.0 * half_h / camera.height as f32);
        Self {
            eye: camera.eye,
            corner: forward - right * half_w + up * half_h,
            dx,
            dy,
        }
    }
}

/// The sky seen along direction `r` (y ≥ 0): horizon to zenith.
fn sky_colour(look: &Look, r: Vec3) -> [f32; 3] {
    let t = (r.y / r.length().max(1e-12)).clamp(0.0, 1.0).sqrt();
    [0, 1, 2].map(|k| look.sky_horizon[k] + (look.sky_zenith[k] - look.sky_horizon[k]) * t)
}

/// What a pixel that no triangle covers shows: stone paving on the plane y = 0 around
/// the pool (a pale coping two units wide at the water's edge), sky above the horizon.
fn surroundings(look: &Look, rays: &Rays, footprint: (f32, f32), px: f32, py: f32) -> [f32; 3] {
    let dir = rays.corner + rays.dx * px + rays.dy * py;
    if dir.y >= -1e-6 || rays.eye.y <= 0.0 {
        return sky_colour(look, Vec3::new(dir.x, dir.y.max(0.0), dir.z));
    }
    let s = -rays.eye.y / dir.y;
    let hit = rays.eye + dir * s;
    let (w, d) = footprint;
    // Distance outside the footprint (0 inside).
    let ox = (-hit.x).max(hit.x - w).max(0.0);
    let oz = (-hit.z).max(hit.z - d).max(0.0);
    let outside = ox.max(oz);
    // The paving scales with the pool: slabs of 1/21 of its longer side (6 units for the
    // default 128-node pool), a coping a third of a slab wide.
    let slab = w.max(d).max(1e-3) / 21.0;
    let coping = slab / 3.0;
    // World size of the pixel's footprint along its longest side, to filter the paving
    // pattern: sharp joints near the eye, their average colour where a slab shrinks to a
    // few pixels (unfiltered, they alias into moiré bands towards the horizon).
    let len = dir.length();
    let footprint_px = s * len * rays.dx.length() / (dir.y.abs() / len).max(0.02);
    let base = if outside < coping {
        [0.80, 0.78, 0.72]
    } else {
        let joint_width = slab / 30.0;
        let stone = [0.52, 0.45, 0.37];
        let joint_colour = [0.30, 0.27, 0.24];
        // Joint coverage of the pixel across each axis, box-filtered.
        let cover = |g: f32| {
            let d = (g / slab - (g / slab).round()).abs() * slab;
            ((joint_width / 2.0 - d) / footprint_px + 0.5).clamp(0.0, 1.0)
        };
        let joint = cover(hit.x).max(cover(hit.z));
        let cell = (((hit.x / slab).floor() as i32).wrapping_mul(73_856_093)
            ^ ((hit.z / slab).floor() as i32).wrapping_mul(19_349_663)) as u32;
        let shade = 0.92 + 0.08 * ((cell >> 7) % 97) as f32 / 97.0;
        let sharp: [f32; 3] =
            [0, 1, 2].map(|k| (stone[k] * shade) * (1.0 - joint) + joint_colour[k] * joint);
        // The average over many slabs: joints cover about 2·joint/slab of the area.
        let f = 2.0 * joint_width / slab;
        let mean: [f32; 3] = [0, 1, 2].map(|k| stone[k] * 0.96 * (1.0 - f) + joint_colour[k] * f);
        let t = ((footprint_px / slab - 0.1) / 0.3).clamp(0.0, 1.0);
        [0, 1, 2].map(|k| sharp[k] + (mean[k] - sharp[k]) * t)
    };
    // Sunlight on the deck, and haze towards the horizon.
    let sun = look.sun.normalize().y.max(0.2);
    let haze = (1.0 - (-s / (12.0 * (w.max(d) + 1.0))).exp()).clamp(0.0, 1.0);
    [0, 1, 2].map(|k| base[k] * sun + (look.sky_horizon[k] - base[k] * sun) * haze)
}

/// Wireframe colour of a LOD level: finest yellow, then orange, red, magenta, blue, cyan.
fn wire_colour(level: u8) -> [f32; 3] {
    const LEVELS: [[f32; 3]; 6] = [
        [1.0, 0.85, 0.0],
        [1.0, 0.35, 0.0],
        [0.9, 0.02, 0.02],
        [0.8, 0.0, 0.8],
        [0.1, 0.2, 1.0],
        [0.0, 0.9, 0.9],
    ];
    LEVELS[(level as usize).min(LEVELS.len() - 1)]
}
