//! [`Texture`]: the pool bottom (an image or the built-in tiles), stored in linear light.

use crate::error::{same_length, Error, Result};
use crate::rng::Rng;

/// An RGB image in linear light (`f32` per channel, 0..1), sampled bilinearly with
/// clamp-to-edge. `u` runs along +x (columns), `v` along +z (rows); `(0, 0)` is the
/// first texel's corner, `(1, 1)` the last one's.
#[derive(Debug, Clone, PartialEq)]
pub struct Texture {
    width: usize,
    height: usize,
    texels: Vec<[f32; 3]>,
}

/// Largest side of a texture.
pub const MAX_TEXTURE_SIDE: usize = 16384;

impl Texture {
    /// A texture from 8-bit sRGB pixels, row by row, 3 bytes per pixel (what PNG decoders
    /// give for RGB images).
    pub fn from_srgb8(width: usize, height: usize, rgb: &[u8]) -> Result<Self> {
        for (name, v) in [("texture width", width), ("texture height", height)] {
            if !(1..=MAX_TEXTURE_SIDE).contains(&v) {
                return Err(Error::InvalidParam {
                    name,
                    value: v as f64,
                    expected: "between 1 and 16384 pixels",
                });
            }
        }
        same_length("texture pixels", rgb.len(), width * height * 3)?;
        let lut: Vec<f32> = (0..=255u8).map(srgb_to_linear).collect();
        let texels = rgb
            .chunks_exact(3)
            .map(|p| [lut[p[0] as usize], lut[p[1] as usize], lut[p[2] as usize]])
            .collect();
        Ok(Self {
            width,
            height,
            texels,
        })
    }

    /// The built-in pool bottom: small pale tiles with grout lines, a darker border one
    /// tile wide and a dark lane line down the middle, 24 × 24 tiles on `size × size`
    /// texels. Every tile's shade varies a little (from a fixed seed), so the same call
    /// gives the same image.
    pub fn pool_tiles(size: usize) -> Self {
        let size = size.clamp(24, MAX_TEXTURE_SIDE);
        Self::pool(24, 24, size / 24)
    }

    /// The built-in pool bottom for a rest footprint of `width × depth` world units:
    /// 24 tiles along the longer side and square tiles (as near as whole tiles allow)
    /// along the other, 21 texels per tile.
    pub fn pool_tiles_for(width: f32, depth: f32) -> Self {
        let long = width.max(depth);
        let count = |side: f32| {
            let n = if long > 0.0 && side.is_finite() {
                (24.0 * side / long).round()
            } else {
                24.0
            };
            (n as usize).clamp(6, 24)
        };
        Self::pool(count(width), count(depth), 21)
    }

    fn pool(tiles_x: usize, tiles_y: usize, texels_per_tile: usize) -> Self {
        let tile = texels_per_tile.max(1) as f32;
        let (width, height) = (
            tiles_x * texels_per_tile.max(1),
            tiles_y * texels_per_tile.max(1),
        );
        let grout = (tile * 0.09).max(1.0);
        let mut rng = Rng::new(0x9001);
        let shades: Vec<f32> = (0..tiles_x * tiles_y)
            .map(|_| rng.range(-0.045, 0.045))
            .collect();
        let srgb = |r: u8, g: u8, b: u8| [srgb_to_linear(r), srgb_to_linear(g), srgb_to_linear(b)];
        let pale = srgb(178, 222, 232);
        let border = srgb(34, 112, 160);
        let lane = srgb(22, 48, 92);
        let grout_colour = srgb(120, 150, 160);
        let mid = tiles_x / 2;
        let mut texels = Vec::with_capacity(width * height);
        for y in 0..height {
            for x in 0..width {
                let (fx, fy) = (x as f32 + 0.5, y as f32 + 0.5);
                let (tx, ty) = ((fx / tile) as usize, (fy / tile) as usize);
                let (tx, ty) = (tx.min(tiles_x - 1), ty.min(tiles_y - 1));
                let (ox, oy) = (fx - tx as f32 * tile, fy - ty as f32 * tile);
                let in_grout = ox < grout || oy < grout;
                let edge = tx < 1 || ty < 1 || tx + 1 >= tiles_x || ty + 1 >= tiles_y;
                // The lane line: two tiles wide down the middle, stopping short of the ends
                // with a T at each end, as in a competition pool.
                let in_lane =
                    (tx + 1 == mid || tx == mid) && (3..tiles_y.saturating_sub(3)).contains(&ty);
                let in_t = (ty == 3 || ty + 4 == tiles_y)
                    && (mid.saturating_sub(3)..mid + 3).contains(&tx);
                let base = if in_grout {
                    grout_colour
                } else if edge {
                    border
                } else if in_lane || in_t {
                    lane
                } else {
                    pale
                };
                let shade = 1.0
                    + if in_grout {
                        0.0
                    } else {
                        shades[ty * tiles_x + tx]
                    };
                texels.push(base.map(|c| (c * shade).clamp(0.0, 1.0)));
            }
        }
        Self {
            width,
            height,
            texels,
        }
    }

    /// Width in texels.
    pub fn width(&self) -> usize {
        self.width
    }

    /// Height in texels.
    pub fn height(&self) -> usize {
        self.height
    }

    /// The texel at `(x, y)` in linear light.
    pub fn texel(&self, x: usize, y: usize) -> [f32; 3] {
        self.texels[y.min(self.height - 1) * self.width + x.min(self.width - 1)]
    }

    /// Bilinear sample at `(u, v)`, clamped to the edge. Non-finite coordinates give the
    /// first texel.
    #[inline]
    pub fn sample(&self, u: f32, v: f32) -> [f32; 3] {
        let x = (u * self.width as f32 - 0.5).clamp(0.0, (self.width - 1) as f32);
        let y = (v * self.height as f32 - 0.5).clamp(0.0, (self.height - 1) as f32);
        // `clamp` passes NaN through; `as usize` turns it into 0.
        let (x0, y0) = (x as usize, y as usize);
        let (x1, y1) = ((x0 + 1).min(self.width - 1), (y0 + 1).min(self.height - 1));
        let (fx, fy) = (
            if x.is_nan() { 0.0 } else { x - x0 as f32 },
            if y.is_nan() { 0.0 } else { y - y0 as f32 },
        );
        let row0 = y0 * self.width;
        let row1 = y1 * self.width;
        let t = &self.texels;
        let (a, b, c, d) = (t[row0 + x0], t[row0 + x1], t[row1 + x0], t[row1 + x1]);
        let mut out = [0.0; 3];
        for k in 0..3 {
            let top = a[k] + (b[k] - a[k]) * fx;
            let bottom = c[k] + (d[k] - c[k]) * fx;
            out[k] = top + (bottom - top) * fy;
        }
        out
    }
}

/// An 8-bit sRGB value in linear light.
pub fn srgb_to_linear(c: u8) -> f32 {
    let c = c as f32 / 255.0;
    if c <= 0.04045 {
        c / 12.92
    } else {
        ((c + 0.055) / 1.055).powf(2.4)
    }
}

/// Linear light to 8-bit sRGB through a table (4096 steps, exact to the nearest level
/// in the bright range and within one level in the dark range).
#[derive(Debug, Clone)]
pub(crate) struct SrgbEncoder {
    table: Vec<u8>,
}

impl SrgbEncoder {
    const STEPS: usize = 4096;

    pub(crate) fn new() -> Self {
        let table = (0..=Self::STEPS)
            .map(|k| {
                let c = k as f32 / Self::STEPS as f32;
                let s = if c <= 0.003_130_8 {
                    c * 12.92
                } else {
                    1.055 * c.powf(1.0 / 2.4) - 0.055
                };
                (s * 255.0 + 0.5).clamp(0.0, 255.0) as u8
            })
            .collect();
        Self { table }
    }

    #[inline]
    pub(crate) fn encode(&self, c: f32) -> u8 {
        // NaN → 0 through `as usize`.
        let k = (c.clamp(0.0, 1.0) * Self::STEPS as f32 + 0.5) as usize;
        self.table[k.min(Self::STEPS)]
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn srgb_round_trips() {
        let enc = SrgbEncoder::new();
        for c in 0..=255u8 {
            let back = enc.encode(srgb_to_linear(c));
            assert!((back as i32 - c as i32).abs() <= 1, "{c} -> {back}");
        }
        assert_eq!(enc.encode(f32::NAN), 0);
        assert_eq!(enc.encode(7.0), 255);
    }

    #[test]
    fn sampling_hits_texel_centres_and_clamps() {
        let t = Texture::from_srgb8(2, 1, &[0, 0, 0, 255, 255, 255]).unwrap();
        assert_eq!(t.sample(0.25, 0.5), [0.0; 3]);
        assert_eq!(t.sample(0.75, 0.5), [1.0; 3]);
        assert_eq!(t.sample(-3.0, 9.0), [0.0; 3]);
        assert!((t.sample(0.5, 0.5)[0] - 0.5).abs() < 1e-6);
        assert_eq!(t.sample(f32::NAN, f32::NAN), [0.0; 3]);
        assert!(Texture::from_srgb8(2, 2, &[0; 3]).is_err());
        assert!(Texture::from_srgb8(0, 2, &[]).is_err());
    }

    #[test]
    fn pool_tiles_are_deterministic_and_varied() {
        let a = Texture::pool_tiles(256);
        assert_eq!(a, Texture::pool_tiles(256));
        let lum: Vec<f32> = a.texels.iter().map(|t| t[0] + t[1] + t[2]).collect();
        let (lo, hi) = lum
            .iter()
            .fold((f32::MAX, f32::MIN), |(l, h), &v| (l.min(v), h.max(v)));
        assert!(hi - lo > 0.5);
    }
}
