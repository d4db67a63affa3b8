//! A simple displacement hull, generated: the boat of the examples, tests and benchmarks.

use super::Hull;
use crate::error::{Error, Result};
use crate::params;

/// The dimensions and resolution of a generated boat hull ([`BoatShape::hull`]): a
/// displacement hull with a flat transom at the stern, a sharp vertical stem at the bow, a
/// keel that rises towards both ends, round bilges amidships that sharpen into V sections
/// towards the bow, and a deck whose sheer rises forward.
///
/// Body frame: the bow points to +x, y is up, starboard is +z; the origin is on the keel
/// amidships (the baseline, from which naval architects measure heights). The hull is
/// symmetric about `z = 0`. [`Hull::centred`] moves it onto its centroid.
///
/// The mesh: `stations` cross-sections from the transom forward (the last is the stem),
/// each of `2 × segments` edges from the port deck edge round the keel to the starboard
/// one; a deck strip between stations; the transom as a fan around its centre.
/// `4 · stations · segments + 2 · stations + 2 · segments` triangles: 2,024 with the
/// defaults. `assets/boat.obj` in the repository is the default boat.
///
/// ```
/// use springwater::body::BoatShape;
///
/// let boat = BoatShape::default().hull()?;
/// assert_eq!(boat.triangles().len(), 2024);
/// let mut coarse = BoatShape::default();
/// (coarse.stations, coarse.segments) = (12, 4);
/// assert_eq!(coarse.hull()?.triangles().len(), 4 * 12 * 4 + 2 * 12 + 2 * 4);
/// # Ok::<(), springwater::Error>(())
/// ```
///
/// `#[non_exhaustive]` (a dimension may come): start from [`BoatShape::default`] and
/// assign the fields to change.
#[derive(Debug, Clone, Copy, PartialEq)]
#[non_exhaustive]
pub struct BoatShape {
    /// Length overall, transom to stem, world units (default 6).
    pub length: f32,
    /// Greatest beam, world units (default 2).
    pub beam: f32,
    /// Depth from the keel to the deck amidships, world units (default 1); the sheer
    /// rises a quarter of it more at the bow.
    pub depth: f32,
    /// Cross-sections from the transom to the stem (default 40, at least 2).
    pub stations: u32,
    /// Edges per side of each cross-section (default 12, at least 2).
    pub segments: u32,
}

impl Default for BoatShape {
    fn default() -> Self {
        Self {
            length: 6.0,
            beam: 2.0,
            depth: 1.0,
            stations: 40,
            segments: 12,
        }
    }
}

/// Vertices and triangles.
type Mesh = (Vec<[f32; 3]>, Vec<[u32; 3]>);

/// The lines of the hull as fractions: `u` runs from 0 at the transom to 1 at the bow.
/// Only `+`, `−`, `×` and `÷`, so the mesh is the same on every platform.
mod lines {
    /// Half-breadth at the deck, as a fraction of half the beam: full at 40% of the
    /// length, 3/4 at the transom, zero at the stem.
    pub fn half_breadth(u: f64) -> f64 {
        if u >= 0.4 {
            let t = (u - 0.4) / 0.6;
            1.0 - t * t
        } else {
            let t = (0.4 - u) / 0.4;
            1.0 - 0.25 * t * t
        }
    }

    /// Height of the keel above the baseline, as a fraction of the depth: zero amidships,
    /// rising to 0.45 at the stem and 0.1 at the transom.
    pub fn keel(u: f64) -> f64 {
        if u >= 0.6 {
            let t = (u - 0.6) / 0.4;
            0.45 * t * t
        } else if u < 0.15 {
            let t = (0.15 - u) / 0.15;
            0.1 * t * t
        } else {
            0.0
        }
    }

    /// Height of the deck edge (the sheer), as a fraction of the depth.
    pub fn sheer(u: f64) -> f64 {
        let u2 = u * u;
        1.0 + 0.25 * u2 * u2
    }

    /// How far up the side (0 at the keel, 1 at the deck) the section is at `t` (0 at the
    /// keel, 1 at the deck edge, in beam): round bilges amidships (`t²` and `t⁴`), a V
    /// (`t`) at the stem.
    pub fn section(u: f64, t: f64) -> f64 {
        let full = if u > 0.5 {
            let f = (u - 0.5) / 0.5;
            1.0 - f * f
        } else {
            1.0
        };
        let t2 = t * t;
        full * (0.25 * t2 + 0.75 * t2 * t2) + (1.0 - full) * t
    }
}

impl BoatShape {
    /// The validated hull: vertices in the body frame of the type's docs,
    /// counter-clockwise triangles.
    pub fn hull(&self) -> Result<Hull> {
        let (vertices, triangles) = self.mesh()?;
        Hull::new(&vertices, &triangles)
    }

    /// The vertices and triangles of [`hull`](Self::hull).
    fn mesh(&self) -> Result<Mesh> {
        params::positive("boat length", self.length)?;
        params::positive("boat beam", self.beam)?;
        params::positive("boat depth", self.depth)?;
        for (name, v) in [
            ("boat stations", self.stations),
            ("boat segments", self.segments),
        ] {
            if !(2..=1024).contains(&v) {
                return Err(Error::InvalidParam {
                    name,
                    value: v as f64,
                    expected: "2 to 1024",
                });
            }
        }
        let (n, m) = (self.stations as usize, self.segments as usize);
        let (length, half_beam, depth) = (
            self.length as f64,
            0.5 * self.beam as f64,
            self.depth as f64,
        );
        let ring = 2 * m + 1;
        let mut vertices: Vec<[f32; 3]> = Vec::with_capacity(n * ring + m + 2);
        let point = |u: f64, s: f64| {
            let t = if s < 0.0 { -s } else { s };
            let (keel, deck) = (lines::keel(u), lines::sheer(u));
            let y = keel + (deck - keel) * lines::section(u, t);
            [
                ((u - 0.5) * length) as f32,
                (y * depth) as f32,
                (s * lines::half_breadth(u) * half_beam) as f32,
            ]
        };
        // Station k at u = k / n, k < n: a full ring, port deck (s = −1) to starboard deck.
        for k in 0..n {
            let u = k as f64 / n as f64;
            for j in 0..ring {
                vertices.push(point(u, j as f64 / m as f64 - 1.0));
            }
        }
        // The stem at u = 1: one vertex per height, shared by both sides (ring index j and
        // 2m − j meet at stem index min(j, 2m − j)).
        let stem = vertices.len();
        for j in 0..=m {
            vertices.push(point(1.0, j as f64 / m as f64 - 1.0));
        }
        let centre = vertices.len();
        let mid = 0.5 * (lines::keel(0.0) + lines::sheer(0.0)) * depth;
        vertices.push([(-0.5 * length) as f32, mid as f32, 0.0]);

        let at = |k: usize, j: usize| -> u32 {
            if k < n {
                (k * ring + j) as u32
            } else {
                (stem + j.min(2 * m - j)) as u32
            }
        };
        let mut triangles = Vec::new();
        // A quad as two triangles, cut along a → c, or along b → d for the mirror image.
        let mut quad = |a: u32, b: u32, c: u32, d: u32, mirror: bool| {
            if mirror {
                triangles.extend([[a, b, d], [b, c, d]]);
            } else {
                triangles.extend([[a, b, c], [a, c, d]]);
            }
        };
        // The sides: aft to forward (+x) and port to starboard (+z) wind outward below.
        // Starboard quads are cut along the other diagonal, so that the mesh is its own
        // mirror image.
        for k in 0..n {
            for j in 0..2 * m {
                let (a, b) = (at(k, j), at(k + 1, j));
                quad(a, b, at(k + 1, j + 1), at(k, j + 1), j >= m);
            }
        }
        // The deck (flat trapezoids): port edge to starboard edge, then forward.
        for k in 0..n - 1 {
            quad(
                at(k, 0),
                at(k, 2 * m),
                at(k + 1, 2 * m),
                at(k + 1, 0),
                false,
            );
        }
        triangles.push([at(n - 1, 0), at(n - 1, 2 * m), at(n, 0)]);
        // The transom, seen from astern: the ring runs counter-clockwise.
        let centre = centre as u32;
        for j in 0..2 * m {
            triangles.push([centre, at(0, j), at(0, j + 1)]);
        }
        triangles.push([centre, at(0, 2 * m), at(0, 0)]);
        Ok((vertices, triangles))
    }
}
