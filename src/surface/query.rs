//! Point queries and forces at a point: the bilinear sampling of the rest grid.

use super::Surface;
use crate::error::{Error, Result};
use crate::view::MeshView;
use glam::Vec3;

/// `x.floor()` for finite `|x| < 2⁶³` (every query point, in cells, is within 1e15), without
/// the library call that `floor` is on x86-64 CPUs before SSE4.1: the same bits.
///
/// Below 2²² in size, adding and taking away `1.5 · 2²³` rounds `x` to a whole number (the
/// sum lies in `[2²³, 2²⁴)`, where the floats are the integers), one below when that went
/// up; `0.0` and `-0.0` both give `0.0`, as `floor`'s truncation does. Larger points
/// truncate through an integer, which Rust's saturating cast makes longer.
#[inline]
fn floor(x: f32) -> f32 {
    const ROUND: f32 = 12_582_912.0;
    let t = if x.abs() < 4_194_304.0 {
        (x + ROUND) - ROUND
    } else {
        x as i64 as f32
    };
    if t > x {
        t - 1.0
    } else {
        t
    }
}

/// The cell and the bilinear weights of one query point.
#[derive(Debug, Clone, Copy)]
struct Sample {
    /// Index of the cell's top-left node `(c, r)`; the others are `+1`, `+cols`, `+cols+1`.
    c: usize,
    r: usize,
    fx: f32,
    fz: f32,
}

impl Sample {
    /// The cell under the water-frame point `(x, z)` of a window whose node `(0, 0)` is
    /// `origin` cells from the frame's origin (see [`super::window`]), or why there is none.
    fn at(view: &MeshView<'_>, origin: [i64; 2], x: f32, z: f32) -> Result<Self> {
        crate::params::finite("query x", x)?;
        crate::params::finite("query z", z)?;
        Self::near(view, origin, x, z).ok_or_else(|| {
            let [width, length] = view.extent();
            let h = view.spacing();
            Error::OutsideGrid {
                x: x - origin[0] as f32 * h,
                z: z - origin[1] as f32 * h,
                width,
                length,
            }
        })
    }

    /// [`Sample::at`] without the reason: `None` off the footprint (a point that is not
    /// finite is off it too).
    #[inline]
    fn near(view: &MeshView<'_>, origin: [i64; 2], x: f32, z: f32) -> Option<Self> {
        let [width, length] = view.extent();
        let h = view.spacing();
        let [ox, oz] = origin.map(|o| o as f32);
        // The footprint check in window-relative units (exact while the window has not
        // moved).
        let (lx, lz) = (x - ox * h, z - oz * h);
        if !((0.0..=width).contains(&lx) && (0.0..=length).contains(&lz)) {
            return None;
        }
        // The cell and the weights from the point in cells of the water frame, `x / h`,
        // and its whole cell: the same numbers wherever the window is, so a query at a
        // world point answers the same bits before and after a shift. The cell is then
        // counted from the window's origin, and the far edge belongs to the last cell.
        let cell = |p: f32, origin: i64, cells: usize| {
            let w = p / h;
            let whole = floor(w);
            match whole as i64 - origin {
                c if c < 0 => (0, 0.0),
                c if c as usize >= cells => (cells - 1, 1.0),
                // `+ 0.0`: a point at −0 gives the weight −0, as `w − 0` does.
                c => (c as usize, (w - (whole + 0.0)).clamp(0.0, 1.0)),
            }
        };
        let (c, fx) = cell(x, origin[0], view.cols() - 1);
        let (r, fz) = cell(z, origin[1], view.rows() - 1);
        Some(Self { c, r, fx, fz })
    }

    fn weights(&self) -> [f32; 4] {
        let (fx, fz) = (self.fx, self.fz);
        [
            (1.0 - fx) * (1.0 - fz),
            fx * (1.0 - fz),
            (1.0 - fx) * fz,
            fx * fz,
        ]
    }

    fn spread(&self) -> Spread {
        Spread {
            cell: [self.c, self.r],
            weights: self.weights(),
        }
    }

    fn corners(&self, cols: usize) -> [usize; 4] {
        let i = self.r * cols + self.c;
        [i, i + 1, i + cols, i + cols + 1]
    }

    fn blend(&self, cols: usize, s: &[f32]) -> f32 {
        let w = self.weights();
        let i = self.corners(cols);
        w[0] * s[i[0]] + w[1] * s[i[1]] + w[2] * s[i[2]] + w[3] * s[i[3]]
    }

    fn blend3(&self, cols: usize, s: [&[f32]; 3]) -> Vec3 {
        Vec3::new(
            self.blend(cols, s[0]),
            self.blend(cols, s[1]),
            self.blend(cols, s[2]),
        )
    }

    /// The water at the point; `vel` the lattice's velocities and `scale` the time scale
    /// that turns them into world units per second.
    fn water(&self, view: &MeshView<'_>, vel: [&[f32]; 3], scale: f32) -> WaterSample {
        WaterSample {
            height: self.blend(view.cols(), view.y()),
            normal: self.normal(view),
            velocity: self.blend3(view.cols(), vel) * scale,
        }
    }

    fn normal(&self, view: &MeshView<'_>) -> Vec3 {
        let w = self.weights();
        let (c, r) = (self.c, self.r);
        let n = w[0] * view.node_normal(c, r)
            + w[1] * view.node_normal(c + 1, r)
            + w[2] * view.node_normal(c, r + 1)
            + w[3] * view.node_normal(c + 1, r + 1);
        n.try_normalize().unwrap_or(Vec3::Y)
    }
}

/// The cell a force at a point spreads onto, and the bilinear weights of its four
/// corners `(c, r)`, `(c + 1, r)`, `(c, r + 1)`, `(c + 1, r + 1)`.
#[derive(Debug, Clone, Copy)]
pub(crate) struct Spread {
    pub cell: [usize; 2],
    pub weights: [f32; 4],
}

/// The last cell [`Waters::flow`] computed the damping room of, and that room: points of
/// one body fall in few cells, one after the other.
pub(crate) type RoomCache = Option<([usize; 2], f32)>;

/// The water as the floating bodies read it (see [`Surface::waters`]).
pub(crate) struct Waters<'a> {
    view: MeshView<'a>,
    origin: [i64; 2],
    velocities: [&'a [f32]; 3],
    mass: &'a crate::state::table::NodeTable,
    viscosity: &'a crate::state::table::NodeTable,
}

impl Waters<'_> {
    fn sample(&self, x: f32, z: f32) -> Option<Sample> {
        Sample::near(&self.view, self.origin, x, z)
    }

    /// The height at world `(x, z)`, or `None` off the window's footprint.
    pub fn height(&self, x: f32, z: f32) -> Option<f32> {
        let s = self.sample(x, z)?;
        Some(s.blend(self.view.cols(), self.view.y()))
    }

    /// The water near `(x, z)` as a plane, or `None` off the footprint: the height there
    /// and the slope `[∂η/∂x, ∂η/∂z]`, for a body too small to feel the water's curvature.
    /// The slope is the central difference of the bilinear height one cell either side,
    /// `(η(x + h) − η(x − h)) / 2h` (one-sided at the grid's edge): continuous as the point
    /// moves, and level at the bottom of a symmetric dent, where the gradient of the one
    /// cell holding the point would tilt towards that cell.
    pub fn plane(&self, x: f32, z: f32) -> Option<(f32, [f32; 2])> {
        let s = self.sample(x, z)?;
        let (cols, rows) = (self.view.cols(), self.view.rows());
        let y = self.view.y();
        let w = s.weights();
        // The bilinear height at the point moved to the same spot of cell (c, r).
        let at = |c: usize, r: usize| {
            let i = r * cols + c;
            w[0] * y[i] + w[1] * y[i + 1] + w[2] * y[i + cols] + w[3] * y[i + cols + 1]
        };
        // Cells either side of the point's, where the grid has them.
        let either = |k: usize, cells: usize| (k.saturating_sub(1), (k + 1).min(cells - 1));
        let h = self.view.spacing();
        let ((west, east), (north, south)) = (either(s.c, cols - 1), either(s.r, rows - 1));
        // A grid one cell wide: that cell's own gradient.
        let [i00, i10, i01, i11] = s.corners(cols);
        let slope_x = if east > west {
            (at(east, s.r) - at(west, s.r)) / ((east - west) as f32 * h)
        } else {
            ((1.0 - s.fz) * (y[i10] - y[i00]) + s.fz * (y[i11] - y[i01])) / h
        };
        let slope_z = if south > north {
            (at(s.c, south) - at(s.c, north)) / ((south - north) as f32 * h)
        } else {
            ((1.0 - s.fx) * (y[i01] - y[i00]) + s.fx * (y[i11] - y[i10])) / h
        };
        Some((at(s.c, s.r), [slope_x, slope_z]))
    }

    /// The water under `(x, z)`, or `None` off the footprint: its velocity (the
    /// lattice's, per unit of model time), and the least `mass × rate − viscosity` over the
    /// four nodes the point blends (the damping room `rate` leaves them).
    pub fn flow(
        &self,
        x: f32,
        z: f32,
        rate: f32,
        cache: &mut RoomCache,
    ) -> Option<(Vec3, f32, Spread)> {
        let s = self.sample(x, z)?;
        let cols = self.view.cols();
        let room = match *cache {
            Some((cell, room)) if cell == [s.c, s.r] => room,
            _ => {
                // The room of each corner, `mass × rate − viscosity`, the least of the four.
                let room_on = |r: usize| {
                    let (mass, viscosity) = (self.mass.row(r), self.viscosity.row(r));
                    let room = |c: usize| mass[c] * rate - viscosity[c];
                    (room(s.c), room(s.c + 1))
                };
                let ((a, b), (c, d)) = (room_on(s.r), room_on(s.r + 1));
                let room = a.min(b).min(c).min(d);
                *cache = Some(([s.c, s.r], room));
                room
            }
        };
        Some((s.blend3(cols, self.velocities), room, s.spread()))
    }

    /// Nodes per row of the grid.
    pub fn cols(&self) -> usize {
        self.view.cols()
    }

    /// The cell a force at `(x, z)` spreads onto and its corners' bilinear weights (those
    /// [`Surface::add_force_at`] uses), or `None` off the footprint.
    pub fn spread(&self, x: f32, z: f32) -> Option<Spread> {
        Some(self.sample(x, z)?.spread())
    }
}

/// The water at one point: what a floating object or a game's gameplay code reads.
#[derive(Debug, Clone, Copy, PartialEq)]
#[non_exhaustive]
pub struct WaterSample {
    /// Height (y) of the water, as [`Surface::height_at`].
    pub height: f32,
    /// Unit normal, as [`Surface::normal_at`].
    pub normal: Vec3,
    /// Velocity of the water, as [`Surface::velocity_at`] (world units per second).
    pub velocity: Vec3,
}

/// Checks every point, then fills `out` with `f` of each: all or nothing.
fn batch<T>(
    view: &MeshView<'_>,
    origin: [i64; 2],
    points: &[[f32; 2]],
    out: &mut Vec<T>,
    f: impl Fn(&Sample) -> T,
) -> Result<()> {
    for &[x, z] in points {
        Sample::at(view, origin, x, z)?;
    }
    out.clear();
    out.extend(
        points
            .iter()
            .map(|&[x, z]| f(&Sample::at(view, origin, x, z).expect("checked above"))),
    );
    Ok(())
}

/// # Queries and forces at a point
///
/// Height, normal and velocity of the water at a world `(x, z)`, sampled from the
/// full-resolution simulation (never from the LOD mesh), and forces pushed in at a world
/// point with the same weights. Batched forms take `[x, z]` pairs and fill a caller-owned
/// `Vec` (cleared first, capacity kept).
///
/// ## Method
///
/// A point `(x, z)` of the water's local space is mapped to fractional grid coordinates
/// `col = x / h`, `row = z / h` (the node positions *at rest*), and the four nodes of the
/// cell it falls in are blended bilinearly:
///
/// ```text
/// f(col, row) = (1−fx)(1−fz) f00 + fx(1−fz) f10 + (1−fx) fz f01 + fx fz f11
/// ```
///
/// So a query at a node's rest position returns that node's value, and values vary
/// continuously between nodes. Heights are the nodes' current `y`; velocities the nodes'
/// current velocities in world units per second (the lattice's, per unit of model time,
/// times `params().time_scale`); normals the per-node normals of
/// [`MeshView::node_normal`] blended the same way and renormalised.
/// The lattice also moves sideways a little; the queries follow the nodes (the surface
/// point whose rest position is `(x, z)`), which is what a floating object riding the
/// water feels.
///
/// Points must lie in the rest footprint `[0, (cols−1)h] × [0, (rows−1)h]` (edges
/// included) and be finite; anything else is an error, and a batched query that errors
/// has written nothing. [`Surface::contains`] tells in advance.
impl Surface {
    /// True if `(x, z)` is finite and inside the rest footprint
    /// `[0, (cols−1)h] × [0, (rows−1)h]`, where the queries answer.
    pub fn contains(&self, x: f32, z: f32) -> bool {
        Sample::at(&self.mesh_view(), self.window.origin, x, z).is_ok()
    }

    /// Height (y) of the water at world `(x, z)`, interpolated bilinearly between nodes.
    ///
    /// ```
    /// use springwater::{Params, Surface};
    ///
    /// let mut water = Surface::new(Params::with_size(33, 33))?;
    /// water.drop_at(16.0, 16.0, 1.0, 3.0)?;
    /// assert_eq!(water.height_at(16.0, 16.0)?, 1.0);           // the crest, at a node
    /// let between = water.height_at(16.5, 16.0)?;
    /// assert!(between < 1.0 && between > water.height_at(17.0, 16.0)?);
    /// assert!(water.height_at(40.0, 0.0).is_err());            // outside the pool
    /// # Ok::<(), springwater::Error>(())
    /// ```
    pub fn height_at(&self, x: f32, z: f32) -> Result<f32> {
        let view = self.mesh_view();
        Ok(Sample::at(&view, self.window.origin, x, z)?.blend(view.cols(), view.y()))
    }

    /// Adds `force` at the world point `(x, z)` for the next step only, in the lattice's
    /// force units like every force on the water ([`Surface::add_force`]; a force in
    /// seconds' units, such as a body's, divided by `time_scale²`): the force is spread
    /// onto the four nodes of the cell holding the point with exactly the bilinear weights
    /// [`Surface::height_at`] reads with (its adjoint), so what a floating body feels and
    /// what it pushes into the water agree, and the spread forces sum to `force`.
    ///
    /// The point must be finite and inside the rest footprint; every component of `force`
    /// finite, and the accumulated force on each node too. On error nothing changes.
    ///
    /// ```
    /// use springwater::{Params, Surface};
    ///
    /// let mut water = Surface::new(Params::with_size(33, 33))?;
    /// water.add_force_at(10.25, 20.0, [0.0, -4.0, 0.0])?;   // a quarter of the way to x = 11
    /// let fy = water.forces()[1];
    /// assert_eq!(fy[20 * 33 + 10], -3.0);
    /// assert_eq!(fy[20 * 33 + 11], -1.0);
    /// assert!(water.add_force_at(-1.0, 0.0, [0.0, 1.0, 0.0]).is_err());
    /// # Ok::<(), springwater::Error>(())
    /// ```
    pub fn add_force_at(&mut self, x: f32, z: f32, force: [f32; 3]) -> Result<()> {
        for f in force {
            crate::params::finite("force", f)?;
        }
        let view = self.mesh_view();
        let sample = Sample::at(&view, self.window.origin, x, z)?;
        let cols = view.cols();
        let (w, corners) = (sample.weights(), sample.corners(cols));
        let batch = std::array::from_fn::<_, 4, _>(|k| (corners[k], w[k]));
        self.lattice
            .state
            .ext
            .add(batch.map(|(i, w)| (i, force.map(|f| w * f))))
            .or_else(|sum| crate::params::finite("accumulated force", sum))
    }

    /// A reader of the water for the floating bodies' step: one view of the surface for
    /// the many points they sample.
    pub(crate) fn waters(&self) -> Waters<'_> {
        Waters {
            view: self.mesh_view(),
            origin: self.window.origin,
            velocities: self.velocities(),
            mass: &self.lattice.state.mass,
            viscosity: &self.lattice.state.viscosity,
        }
    }

    /// Unit normal of the water at world `(x, z)`: node normals blended bilinearly and
    /// renormalised.
    pub fn normal_at(&self, x: f32, z: f32) -> Result<Vec3> {
        let view = self.mesh_view();
        Ok(Sample::at(&view, self.window.origin, x, z)?.normal(&view))
    }

    /// Velocity of the water at world `(x, z)`, interpolated bilinearly between nodes, in
    /// world units per second.
    pub fn velocity_at(&self, x: f32, z: f32) -> Result<Vec3> {
        let view = self.mesh_view();
        let s = Sample::at(&view, self.window.origin, x, z)?;
        Ok(s.blend3(view.cols(), self.velocities()) * self.params.time_scale)
    }

    /// Height, normal and velocity at world `(x, z)` in one lookup of the cell.
    pub fn sample_at(&self, x: f32, z: f32) -> Result<WaterSample> {
        let view = self.mesh_view();
        let s = Sample::at(&view, self.window.origin, x, z)?;
        Ok(s.water(&view, self.velocities(), self.params.time_scale))
    }

    /// [`Surface::sample_at`] for every `[x, z]` of `points`, point by point: `out[k]` is
    /// `None` where point `k` is off the window's footprint or not finite, so one object
    /// that has drifted off the water does not cost the others their answers. `out` is
    /// cleared first and keeps its capacity.
    ///
    /// ```
    /// use springwater::{Params, Surface};
    ///
    /// let mut water = Surface::new(Params::with_size(33, 33))?;
    /// water.drop_at(16.0, 16.0, 1.0, 3.0)?;
    /// let mut out = Vec::new();
    /// water.samples_at(&[[16.0, 16.0], [99.0, 0.0], [f32::NAN, 1.0]], &mut out);
    /// assert_eq!(out[0].map(|s| s.height), Some(1.0));
    /// assert!(out[1].is_none() && out[2].is_none());
    /// # Ok::<(), springwater::Error>(())
    /// ```
    pub fn samples_at(&self, points: &[[f32; 2]], out: &mut Vec<Option<WaterSample>>) {
        let view = self.mesh_view();
        let (origin, vel) = (self.window.origin, self.velocities());
        let scale = self.params.time_scale;
        out.clear();
        out.extend(points.iter().map(|&[x, z]| {
            Sample::at(&view, origin, x, z)
                .ok()
                .map(|s| s.water(&view, vel, scale))
        }));
    }

    /// [`Surface::height_at`] for every `[x, z]` of `points`, into `out`; all or nothing
    /// ([`Surface::samples_at`] answers point by point).
    pub fn heights_at(&self, points: &[[f32; 2]], out: &mut Vec<f32>) -> Result<()> {
        let view = self.mesh_view();
        batch(&view, self.window.origin, points, out, |s| {
            s.blend(view.cols(), view.y())
        })
    }

    /// [`Surface::normal_at`] for every `[x, z]` of `points`, into `out`.
    pub fn normals_at(&self, points: &[[f32; 2]], out: &mut Vec<Vec3>) -> Result<()> {
        let view = self.mesh_view();
        batch(&view, self.window.origin, points, out, |s| s.normal(&view))
    }

    /// [`Surface::velocity_at`] for every `[x, z]` of `points`, into `out` (world units
    /// per second).
    pub fn velocities_at(&self, points: &[[f32; 2]], out: &mut Vec<Vec3>) -> Result<()> {
        let view = self.mesh_view();
        let (vel, scale) = (self.velocities(), self.params.time_scale);
        batch(&view, self.window.origin, points, out, |s| {
            s.blend3(view.cols(), vel) * scale
        })
    }
}

#[cfg(test)]
mod tests {
    use super::floor;

    /// The library's floor, with `-0.0` as `0.0`.
    fn want(x: f32) -> u32 {
        (x.floor() + 0.0).to_bits()
    }

    #[test]
    fn floor_is_the_library_floor_with_zero_unsigned() {
        let edges = [
            -4_194_304.5,
            -4_194_303.5,
            -2.5,
            -0.5,
            -0.0,
            0.0,
            0.5,
            2.5,
            3.5,
            4_194_303.5,
        ];
        for x in edges
            .into_iter()
            .chain([1e15, -1e15, 8_388_607.5, -6_000_000.5])
        {
            assert_eq!(floor(x).to_bits(), want(x), "{x}");
        }
        let (mut x, mut step) = (-9_000_000.0f32, 0.37f32);
        while x < 9_000_000.0 {
            assert_eq!(floor(x).to_bits(), want(x), "{x}");
            x += step;
            step *= 1.0001;
        }
    }
}
