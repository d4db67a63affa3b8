//! Image files: reading the bottom texture from PNG, writing frames as PNG, and the
//! animated GIF with one median-cut palette for the whole animation.

use crate::args::CliResult;
use springwater::render::Texture;
use std::fs::File;
use std::io::{BufReader, BufWriter, Write};
use std::path::Path;

/// The largest side of a texture: what `Texture::from_srgb8` takes.
const MAX_TEXTURE_SIDE: usize = 16384;

/// Bytes the PNG decoder may allocate besides the image (text and other ancillary chunks).
const PNG_CHUNK_BYTES: usize = 64 << 20;

/// Reads a PNG of any colour type and bit depth into a texture (alpha is ignored), as
/// `--bottom` gives it. The header is checked before any pixel is decoded: a side past
/// the renderer's [`MAX_TEXTURE_SIDE`] is refused, and the memory the decoded image and
/// its texture take is asked of the system first, so a header that lies (a few bytes
/// claiming 60000 × 60000 pixels) or a decompression bomb costs nothing.
pub fn read_png(path: &Path) -> CliResult<Texture> {
    let fail = |what: String| format!("cannot read {} as a PNG image: {what}", path.display());
    let file = File::open(path).map_err(|e| fail(e.to_string()))?;
    let limits = png::Limits {
        bytes: PNG_CHUNK_BYTES,
    };
    let mut decoder = png::Decoder::new_with_limits(BufReader::new(file), limits);
    decoder.set_transformations(png::Transformations::normalize_to_color8());
    let mut reader = decoder.read_info().map_err(|e| fail(e.to_string()))?;
    let (width, height) = (reader.info().width, reader.info().height);
    if width as usize > MAX_TEXTURE_SIDE || height as usize > MAX_TEXTURE_SIDE {
        return Err(format!(
            "--bottom {}: the image is {width}x{height} pixels, more than the \
             {MAX_TEXTURE_SIDE} on a side the renderer takes; scale it down",
            path.display()
        ));
    }
    let size = reader
        .output_buffer_size()
        .ok_or_else(|| fail("the image is too large".into()))?;
    // The decoded pixels, their RGB copy and the texture (three f32 a texel).
    let texels = width as u64 * height as u64;
    crate::memory::check(
        size as u64 + texels * (3 + 12),
        &format!("--bottom {}", path.display()),
        "use a smaller image",
    )?;
    let mut buf = vec![0; size];
    let info = reader
        .next_frame(&mut buf)
        .map_err(|e| fail(e.to_string()))?;
    let (w, h) = (info.width as usize, info.height as usize);
    let data = &buf[..info.buffer_size()];
    let rgb: Vec<u8> = match info.color_type {
        png::ColorType::Rgb => data.to_vec(),
        png::ColorType::Rgba => data
            .chunks_exact(4)
            .flat_map(|p| [p[0], p[1], p[2]])
            .collect(),
        png::ColorType::Grayscale => data.iter().flat_map(|&g| [g, g, g]).collect(),
        png::ColorType::GrayscaleAlpha => data
            .chunks_exact(2)
            .flat_map(|p| [p[0], p[0], p[0]])
            .collect(),
        png::ColorType::Indexed => return Err(fail("indexed colour was not expanded".into())),
    };
    Texture::from_srgb8(w, h, &rgb).map_err(|e| fail(e.to_string()))
}

/// Writes an 8-bit RGB PNG.
pub fn write_png(file: File, width: usize, height: usize, rgb: &[u8]) -> std::io::Result<()> {
    let mut w = BufWriter::new(file);
    let mut encoder = png::Encoder::new(&mut w, width as u32, height as u32);
    encoder.set_color(png::ColorType::Rgb);
    encoder.set_depth(png::BitDepth::Eight);
    encoder.set_source_srgb(png::SrgbRenderingIntent::Perceptual);
    let mut writer = encoder.write_header().map_err(std::io::Error::other)?;
    writer
        .write_image_data(rgb)
        .map_err(std::io::Error::other)?;
    writer.finish().map_err(std::io::Error::other)?;
    w.flush()
}

/// A palette of at most 256 colours chosen by median cut over the colours of frames,
/// and a table mapping every colour seen (6 bits per channel) to its nearest entry.
pub struct Palette {
    /// `[r, g, b]` per entry.
    pub colours: Vec<[u8; 3]>,
    lookup: Vec<u8>,
}

/// Counts of colours at 6 bits per channel.
pub struct Histogram {
    counts: Vec<u32>,
}

/// The histogram bin of an 8-bit colour.
#[inline]
fn bin(p: &[u8]) -> usize {
    ((p[0] as usize >> 2) << 12) | ((p[1] as usize >> 2) << 6) | (p[2] as usize >> 2)
}

impl Histogram {
    pub fn new() -> Self {
        Self {
            counts: vec![0; 1 << 18],
        }
    }

    /// Adds every pixel of an RGB frame.
    pub fn add(&mut self, rgb: &[u8]) {
        for p in rgb.chunks_exact(3) {
            let k = bin(p);
            self.counts[k] = self.counts[k].saturating_add(1);
        }
    }
}

impl Palette {
    /// Median cut: start from one box holding every colour seen, split the box with the
    /// most pixels times widest extent at the weighted median of its widest channel,
    /// until there are 256 boxes; each entry is its box's pixel-weighted mean. Ties are
    /// broken by position, so the palette depends only on the histogram.
    pub fn median_cut(hist: &Histogram) -> Self {
        let mut colours: Vec<([u8; 3], u32)> = hist
            .counts
            .iter()
            .enumerate()
            .filter(|(_, &n)| n > 0)
            .map(|(k, &n)| ([(k >> 12) as u8, ((k >> 6) & 63) as u8, (k & 63) as u8], n))
            .collect();
        if colours.is_empty() {
            colours.push(([0; 3], 1));
        }
        // Boxes are ranges of `colours`, which is reordered in place as boxes split.
        let mut boxes: Vec<std::ops::Range<usize>> = Vec::with_capacity(256);
        boxes.push(0..colours.len());
        while boxes.len() < 256 {
            let score = |r: &std::ops::Range<usize>| {
                let (ch, extent) = widest(&colours[r.clone()]);
                let pixels: u64 = colours[r.clone()].iter().map(|c| c.1 as u64).sum();
                (pixels * extent as u64, ch)
            };
            let Some((k, (s, ch))) = boxes
                .iter()
                .enumerate()
                .filter(|(_, r)| r.len() > 1)
                .map(|(k, r)| (k, score(r)))
                .max_by(|a, b| a.1 .0.cmp(&b.1 .0).then(b.0.cmp(&a.0)))
            else {
                break;
            };
            if s == 0 {
                break;
            }
            let r = boxes[k].clone();
            let slice = &mut colours[r.clone()];
            slice.sort_by_key(|c| (c.0[ch], c.0));
            let total: u64 = slice.iter().map(|c| c.1 as u64).sum();
            let mut acc = 0u64;
            let mut cut = 1;
            for (i, c) in slice.iter().enumerate() {
                acc += c.1 as u64;
                if 2 * acc >= total {
                    cut = (i + 1).clamp(1, slice.len() - 1);
                    break;
                }
            }
            boxes[k] = r.start..r.start + cut;
            boxes.push(r.start + cut..r.end);
        }
        let entries: Vec<[u8; 3]> = boxes
            .iter()
            .map(|r| {
                let mut sum = [0u64; 3];
                let mut n = 0u64;
                for (c, w) in &colours[r.clone()] {
                    for k in 0..3 {
                        // The middle of the 6-bit bin, in 8 bits.
                        sum[k] += (c[k] as u64 * 4 + 2) * *w as u64;
                    }
                    n += *w as u64;
                }
                sum.map(|s| ((s + n / 2) / n.max(1)).min(255) as u8)
            })
            .collect();
        let lookup = nearest_table(&entries, &hist.counts);
        Self {
            colours: entries,
            lookup,
        }
    }

    /// The palette index of an 8-bit colour.
    #[inline]
    pub fn index(&self, p: &[u8]) -> u8 {
        self.lookup[bin(p)]
    }

    /// The palette as `r, g, b, r, g, b, …`, padded to a power of two entries.
    pub fn flat(&self) -> Vec<u8> {
        let n = self.colours.len().next_power_of_two().max(2);
        let mut out: Vec<u8> = self.colours.iter().flatten().copied().collect();
        out.resize(n * 3, 0);
        out
    }
}

/// The channel with the largest extent and that extent.
fn widest(colours: &[([u8; 3], u32)]) -> (usize, u8) {
    let mut lo = [u8::MAX; 3];
    let mut hi = [0u8; 3];
    for (c, _) in colours {
        for k in 0..3 {
            lo[k] = lo[k].min(c[k]);
            hi[k] = hi[k].max(c[k]);
        }
    }
    (0..3)
        .map(|k| (k, hi[k].saturating_sub(lo[k])))
        .max_by(|a, b| a.1.cmp(&b.1).then(b.0.cmp(&a.0)))
        .unwrap_or((0, 0))
}

/// For every colour bin with pixels in it, the nearest palette entry (first on ties);
/// entry 0 for empty bins.
fn nearest_table(entries: &[[u8; 3]], counts: &[u32]) -> Vec<u8> {
    use rayon::prelude::*;
    let mut table = vec![0u8; 1 << 18];
    table
        .par_chunks_mut(1 << 12)
        .enumerate()
        .for_each(|(r, chunk)| {
            for (gb, out) in chunk.iter_mut().enumerate() {
                if counts[(r << 12) | gb] == 0 {
                    continue;
                }
                let c = [
                    r as i32 * 4 + 2,
                    (gb >> 6) as i32 * 4 + 2,
                    (gb & 63) as i32 * 4 + 2,
                ];
                let mut best = (i32::MAX, 0usize);
                for (i, e) in entries.iter().enumerate() {
                    // Weighted towards green as the eye is.
                    let d = [2, 4, 3]
                        .iter()
                        .zip(0..3)
                        .map(|(w, k)| w * (c[k] - e[k] as i32).pow(2))
                        .sum::<i32>();
                    if d < best.0 {
                        best = (d, i);
                    }
                }
                *out = best.1 as u8;
            }
        });
    table
}

/// A looping GIF written frame by frame with one global palette.
pub struct GifWriter<'p> {
    encoder: gif::Encoder<BufWriter<File>>,
    palette: &'p Palette,
    indices: Vec<u8>,
    width: u16,
    height: u16,
    delay_cs: u16,
}

impl<'p> GifWriter<'p> {
    /// Starts the file: header, palette, loop forever. `delay_cs` is the time each frame
    /// shows, in hundredths of a second.
    pub fn new(
        file: File,
        width: usize,
        height: usize,
        palette: &'p Palette,
        delay_cs: u16,
    ) -> Result<Self, String> {
        let (w, h) = (width as u16, height as u16);
        let mut encoder = gif::Encoder::new(BufWriter::new(file), w, h, &palette.flat())
            .map_err(|e| e.to_string())?;
        encoder
            .set_repeat(gif::Repeat::Infinite)
            .map_err(|e| e.to_string())?;
        Ok(Self {
            encoder,
            palette,
            indices: vec![0; width * height],
            width: w,
            height: h,
            delay_cs,
        })
    }

    /// Appends one RGB frame of the size given to [`GifWriter::new`].
    pub fn frame(&mut self, rgb: &[u8]) -> Result<(), String> {
        for (out, p) in self.indices.iter_mut().zip(rgb.chunks_exact(3)) {
            *out = self.palette.index(p);
        }
        let mut frame =
            gif::Frame::from_indexed_pixels(self.width, self.height, self.indices.as_slice(), None);
        frame.delay = self.delay_cs;
        self.encoder.write_frame(&frame).map_err(|e| e.to_string())
    }

    /// Writes the trailer and flushes the file.
    pub fn finish(self) -> Result<(), String> {
        let mut w = self.encoder.into_inner().map_err(|e| e.to_string())?;
        w.flush().map_err(|e| e.to_string())
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn few_colours_are_kept_exactly() {
        let rgb: Vec<u8> = [[0u8, 0, 0], [255, 255, 255], [40, 200, 80]]
            .iter()
            .cycle()
            .take(300)
            .flatten()
            .copied()
            .collect();
        let mut h = Histogram::new();
        h.add(&rgb);
        let p = Palette::median_cut(&h);
        assert_eq!(p.colours.len(), 3);
        for c in [[0u8, 0, 0], [255, 255, 255], [40, 200, 80]] {
            let e = p.colours[p.index(&c) as usize];
            assert!(
                (0..3).all(|k| (e[k] as i32 - c[k] as i32).abs() <= 4),
                "{c:?} -> {e:?}"
            );
        }
    }

    #[test]
    fn many_colours_get_256_entries_deterministically() {
        let rgb: Vec<u8> = (0..100_000u32)
            .flat_map(|i| [(i * 7) as u8, ((i * 13) >> 3) as u8, (i >> 9) as u8])
            .collect();
        let mut h = Histogram::new();
        h.add(&rgb);
        let a = Palette::median_cut(&h);
        let b = Palette::median_cut(&h);
        assert_eq!(a.colours.len(), 256);
        assert_eq!(a.colours, b.colours);
    }
}
