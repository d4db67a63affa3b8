//! The triangle rasteriser: near-plane clipping, perspective-correct interpolation of
//! per-vertex values, a depth buffer, and bands of rows shaded in parallel.
//!
//! A frame goes through three passes:
//!
//! 1. **Setup** (serial, `O(triangles)`): each triangle is clipped against the near plane
//!    in clip space, projected to pixels, and its edge functions and `value / w` are
//!    stored. Degenerate, off-screen and non-finite triangles are dropped here.
//! 2. **Binning** (serial): each triangle's index goes into the bin of every band of
//!    [`BAND_ROWS`] rows its bounding box touches, in index order.
//! 3. **Shading** (bands in parallel): a band walks its bin in order, testing each
//!    pixel centre against the three edge functions and the depth buffer (strictly
//!    nearer wins). A band owns its rows of the colour and depth buffers, so no two
//!    threads write the same pixel, and the order inside a band is fixed: the image is
//!    the same bit for bit for any thread count.

use glam::Vec4;

/// Rows per band, the unit of parallel work.
pub const BAND_ROWS: usize = 8;

/// Values interpolated across a triangle (bottom UV, Fresnel, transmitted light RGB,
/// reflected sky RGB).
pub const VALUES: usize = 9;

/// The level of triangles the wireframe overlay leaves alone (objects, not water).
pub const NO_WIRE: u8 = u8::MAX;

/// A vertex in clip space with the values to interpolate.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct ClipVertex {
    /// Clip-space position (`w` = distance along the view direction).
    pub clip: Vec4,
    /// Values to interpolate (perspective-correct).
    pub values: [f32; VALUES],
}

/// A triangle ready to shade: pixel-space edge functions and values divided by `w`.
#[derive(Debug, Clone, Copy)]
struct Setup {
    /// Edge functions `e_k(x, y) = a·x + b·y + c`, positive inside, scaled so that they
    /// sum to 1 (barycentric coordinates).
    edge: [[f32; 3]; 3],
    /// Length in pixels of each edge divided by twice the area, to turn a barycentric
    /// coordinate into a distance in pixels from the opposite edge (wireframe).
    edge_scale: [f32; 3],
    inv_w: [f32; 3],
    values: [[f32; VALUES]; 3],
    /// Pixel bounds, inclusive: x0, y0, x1, y1.
    bounds: [i32; 4],
    level: u8,
}

/// Reusable buffers of the rasteriser: setup triangles, bins, depth.
#[derive(Debug, Default)]
pub struct Rasteriser {
    tris: Vec<Setup>,
    bins: Vec<Vec<u32>>,
    depth: Vec<f32>,
}

/// The image being drawn, linear light.
pub struct Target<'a> {
    /// Width in pixels.
    pub width: usize,
    /// Height in pixels.
    pub height: usize,
    /// One colour per pixel, row by row.
    pub colour: &'a mut [[f32; 3]],
}

impl Rasteriser {
    /// Empty buffers.
    pub fn new() -> Self {
        Self::default()
    }

    /// Clears the triangle list for a new frame of `width × height` pixels.
    pub fn begin(&mut self, width: usize, height: usize) {
        self.tris.clear();
        let bands = height.div_ceil(BAND_ROWS);
        self.bins.resize_with(bands, Vec::new);
        self.bins.truncate(bands);
        for b in &mut self.bins {
            b.clear();
        }
        self.depth.clear();
        self.depth.resize(width * height, 0.0);
    }

    /// Triangles accepted so far this frame (after clipping; a clipped triangle can
    /// become two).
    #[cfg(test)]
    pub fn triangles(&self) -> usize {
        self.tris.len()
    }

    /// Clips, projects and bins one triangle with LOD level `level` ([`NO_WIRE`]: not
    /// outlined by the wireframe).
    pub fn push(&mut self, v: [ClipVertex; 3], level: u8, width: usize, height: usize) {
        let near = super::camera::NEAR;
        if v.iter().all(|p| p.clip.w >= near) {
            self.push_clipped(v, level, width, height);
            return;
        }
        // Sutherland–Hodgman against w = near: at most 4 vertices remain.
        let mut poly = [v[0]; 4];
        let mut n = 0;
        for k in 0..3 {
            let (a, b) = (v[k], v[(k + 1) % 3]);
            let (ia, ib) = (a.clip.w >= near, b.clip.w >= near);
            if ia {
                poly[n] = a;
                n += 1;
            }
            if ia != ib {
                let t = (near - a.clip.w) / (b.clip.w - a.clip.w);
                let mut values = [0.0; VALUES];
                for (k, out) in values.iter_mut().enumerate() {
                    *out = a.values[k] + t * (b.values[k] - a.values[k]);
                }
                poly[n] = ClipVertex {
                    clip: a.clip + t * (b.clip - a.clip),
                    values,
                };
                n += 1;
            }
        }
        for k in 1..n.saturating_sub(1) {
            self.push_clipped([poly[0], poly[k], poly[k + 1]], level, width, height);
        }
    }

    fn push_clipped(&mut self, v: [ClipVertex; 3], level: u8, width: usize, height: usize) {
        let (w, h) = (width as f32, height as f32);
        let mut x = [0.0f32; 3];
        let mut y = [0.0f32; 3];
        let mut inv_w = [0.0f32; 3];
        for k in 0..3 {
            let c = v[k].clip;
            inv_w[k] = 1.0 / c.w;
            x[k] = (c.x * inv_w[k] * 0.5 + 0.5) * w;
            y[k] = (0.5 - c.y * inv_w[k] * 0.5) * h;
        }
        let area = (x[1] - x[0]) * (y[2] - y[0]) - (x[2] - x[0]) * (y[1] - y[0]);
        if !(area.abs() > 1e-12 && area.is_finite()) {
            return;
        }
        let x0 = x.iter().fold(f32::MAX, |m, &v| m.min(v)).floor().max(0.0);
        let y0 = y.iter().fold(f32::MAX, |m, &v| m.min(v)).floor().max(0.0);
        let x1 = x
            .iter()
            .fold(f32::MIN, |m, &v| m.max(v))
            .ceil()
            .min(w - 1.0);
        let y1 = y
            .iter()
            .fold(f32::MIN, |m, &v| m.max(v))
            .ceil()
            .min(h - 1.0);
        if x0 > x1 || y0 > y1 {
            return;
        }
        // e_k is the edge opposite vertex k, normalised to be 1 at vertex k.
        let mut edge = [[0.0f32; 3]; 3];
        let mut edge_scale = [0.0f32; 3];
        for k in 0..3 {
            let (i, j) = ((k + 1) % 3, (k + 2) % 3);
            let a = (y[i] - y[j]) / area;
            let b = (x[j] - x[i]) / area;
            let c = (x[i] * y[j] - x[j] * y[i]) / area;
            edge[k] = [a, b, c];
            let len = ((x[j] - x[i]).powi(2) + (y[j] - y[i]).powi(2)).sqrt();
            edge_scale[k] = area.abs() / len.max(1e-6);
        }
        let mut values = [[0.0; VALUES]; 3];
        for k in 0..3 {
            for (out, &val) in values[k].iter_mut().zip(&v[k].values) {
                *out = val * inv_w[k];
            }
        }
        let index = self.tris.len() as u32;
        self.tris.push(Setup {
            edge,
            edge_scale,
            inv_w,
            values,
            bounds: [x0 as i32, y0 as i32, x1 as i32, y1 as i32],
            level,
        });
        let (b0, b1) = (y0 as usize / BAND_ROWS, y1 as usize / BAND_ROWS);
        let last = self.bins.len() - 1;
        for bin in &mut self.bins[b0.min(last)..=b1.min(last)] {
            bin.push(index);
        }
    }

    /// Shades every binned triangle into `target`, bands in parallel. `shade` turns the
    /// interpolated values into a colour; `wire`, when given, colours pixels within
    /// `width` pixels of a triangle's edge by the triangle's LOD level; pixels no
    /// triangle covers get `background(x, y)`, computed only for them.
    pub fn draw<S, W, B>(
        &mut self,
        target: Target<'_>,
        shade: &S,
        wire: Option<(&W, f32)>,
        background: &B,
    ) where
        S: Fn(&[f32; VALUES]) -> [f32; 3] + Sync,
        W: Fn(u8) -> [f32; 3] + Sync,
        B: Fn(usize, usize) -> [f32; 3] + Sync,
    {
        let width = target.width;
        assert_eq!(
            target.colour.len(),
            width * target.height,
            "colour buffer matches the image"
        );
        assert_eq!(
            self.depth.len(),
            target.colour.len(),
            "begin() was called for this image size"
        );
        let tris = &self.tris;
        let bins = &self.bins;
        let band_len = BAND_ROWS * width;
        let work = |(band, (colour, depth)): (usize, (&mut [[f32; 3]], &mut [f32]))| {
            let y_start = band * BAND_ROWS;
            let rows = colour.len() / width;
            for &t in &bins[band] {
                let t = &tris[t as usize];
                let ya = (t.bounds[1] as usize).max(y_start);
                let yb = (t.bounds[3] as usize).min(y_start + rows - 1);
                for py in ya..=yb {
                    let fy = py as f32 + 0.5;
                    let row = (py - y_start) * width;
                    for px in t.bounds[0] as usize..=t.bounds[2] as usize {
                        let fx = px as f32 + 0.5;
                        let l = t.edge.map(|[a, b, c]| a * fx + b * fy + c);
                        // A hair of slack so shared edges never leave a gap; the depth
                        // test decides pixels claimed twice.
                        if l[0] < -1e-5 || l[1] < -1e-5 || l[2] < -1e-5 {
                            continue;
                        }
                        let q = l[0] * t.inv_w[0] + l[1] * t.inv_w[1] + l[2] * t.inv_w[2];
                        let p = row + px;
                        if q.is_nan() || q <= depth[p] {
                            continue;
                        }
                        depth[p] = q;
                        let inv_q = 1.0 / q;
                        let mut vals = [0.0f32; VALUES];
                        for (k, out) in vals.iter_mut().enumerate() {
                            *out = (l[0] * t.values[0][k]
                                + l[1] * t.values[1][k]
                                + l[2] * t.values[2][k])
                                * inv_q;
                        }
                        let mut c = shade(&vals);
                        if let (Some((wire, line)), false) = (wire, t.level == NO_WIRE) {
                            let d = (0..3)
                                .map(|k| l[k] * t.edge_scale[k])
                                .fold(f32::MAX, f32::min);
                            if d < line {
                                let a = (1.0 - d / line).clamp(0.0, 1.0).sqrt();
                                let wc = wire(t.level);
                                for k in 0..3 {
                                    c[k] += (wc[k] - c[k]) * a;
                                }
                            }
                        }
                        colour[p] = c;
                    }
                }
            }
            for (p, (c, &d)) in colour.iter_mut().zip(depth.iter()).enumerate() {
                if d == 0.0 {
                    *c = background(p % width, y_start + p / width);
                }
            }
        };
        #[cfg(feature = "parallel")]
        {
            use rayon::prelude::*;
            target
                .colour
                .par_chunks_mut(band_len)
                .zip(self.depth.par_chunks_mut(band_len))
                .enumerate()
                .for_each(work);
        }
        #[cfg(not(feature = "parallel"))]
        target
            .colour
            .chunks_mut(band_len)
            .zip(self.depth.chunks_mut(band_len))
            .enumerate()
            .for_each(work);
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn vertex(x: f32, y: f32, w: f32, value: f32) -> ClipVertex {
        // Clip coordinates whose projection lands on pixel (x, y) of a 100×100 image.
        let ndc = Vec4::new(x / 50.0 - 1.0, 1.0 - y / 50.0, 0.5, 1.0);
        ClipVertex {
            clip: ndc * w,
            values: [value; VALUES],
        }
    }

    fn draw(r: &mut Rasteriser, colour: &mut [[f32; 3]]) {
        let black = |_: usize, _: usize| [0.0; 3];
        let shade = |v: &[f32; VALUES]| [v[0], v[1], v[2]];
        r.draw(
            Target {
                width: 100,
                height: 100,
                colour,
            },
            &shade,
            None::<(&fn(u8) -> [f32; 3], f32)>,
            &black,
        );
    }

    #[test]
    fn two_triangles_cover_a_square_without_gaps_or_spill() {
        let mut r = Rasteriser::new();
        r.begin(100, 100);
        let (a, b, c, d) = (
            vertex(10.0, 10.0, 1.0, 1.0),
            vertex(90.0, 10.0, 3.0, 1.0),
            vertex(90.0, 90.0, 2.0, 1.0),
            vertex(10.0, 90.0, 5.0, 1.0),
        );
        r.push([a, b, c], 0, 100, 100);
        r.push([a, c, d], 0, 100, 100);
        let mut colour = vec![[0.0; 3]; 100 * 100];
        draw(&mut r, &mut colour);
        for y in 0..100 {
            for x in 0..100 {
                let inside = (10..90).contains(&x) && (10..90).contains(&y);
                let lit = colour[y * 100 + x][0] > 0.5;
                assert_eq!(lit, inside, "pixel {x},{y}");
                if inside {
                    // Perspective-correct interpolation of a constant is that constant.
                    assert!((colour[y * 100 + x][0] - 1.0).abs() < 1e-4);
                }
            }
        }
    }

    #[test]
    fn nearer_triangles_win_whatever_the_order() {
        for order in [[0, 1], [1, 0]] {
            let mut r = Rasteriser::new();
            r.begin(100, 100);
            let tris = [
                [
                    vertex(0.0, 0.0, 2.0, 0.25),
                    vertex(100.0, 0.0, 2.0, 0.25),
                    vertex(0.0, 100.0, 2.0, 0.25),
                ],
                [
                    vertex(0.0, 0.0, 4.0, 0.75),
                    vertex(100.0, 0.0, 4.0, 0.75),
                    vertex(0.0, 100.0, 4.0, 0.75),
                ],
            ];
            for k in order {
                r.push(tris[k], 0, 100, 100);
            }
            let mut colour = vec![[0.0; 3]; 100 * 100];
            draw(&mut r, &mut colour);
            assert!((colour[20 * 100 + 20][0] - 0.25).abs() < 1e-5);
        }
    }

    #[test]
    fn triangles_crossing_the_near_plane_are_clipped_not_dropped() {
        let mut r = Rasteriser::new();
        r.begin(100, 100);
        let mut behind = vertex(50.0, 50.0, 1.0, 1.0);
        behind.clip.w = -1.0;
        r.push(
            [
                vertex(10.0, 10.0, 1.0, 1.0),
                vertex(90.0, 10.0, 1.0, 1.0),
                behind,
            ],
            0,
            100,
            100,
        );
        assert!(r.triangles() >= 1);
        let mut colour = vec![[0.0; 3]; 100 * 100];
        draw(&mut r, &mut colour);
        assert!(colour.iter().any(|c| c[0] > 0.5));
        assert!(colour.iter().all(|c| c[0].is_finite()));
    }
}
