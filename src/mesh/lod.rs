//! The view-dependent, crack-free LOD index buffer ([`LodMesh`]; its docs give the method).

use crate::error::{same_length, Error, Result};
use crate::grid::Grid;
use crate::view::MeshView;
use glam::Vec3;

/// LOD parameters. Plain data with defaults; [`LodParams::validate`] checks it.
/// `#[non_exhaustive]` (a parameter may come): outside the crate, start from
/// `LodParams::default()` and change fields or use the `with_*` methods
/// (`LodParams::default().with_levels(1)` is the full grid).
#[derive(Debug, Clone, Copy, PartialEq)]
#[non_exhaustive]
pub struct LodParams {
    /// Patch size in cells, a power of two from 1 to 4096 (default: `16`).
    pub patch_cells: usize,
    /// Distance from the eye, in world units, within which patches get full detail
    /// (level 0) (default: `32.0`). Each further level's range is twice the previous one's.
    pub first_range: f32,
    /// Number of levels, from 1 (full detail everywhere) to `log2(patch_cells) + 1`
    /// (the coarsest level draws a patch as 2 triangles) (default: `5`).
    pub levels: u32,
    /// Relative distance a patch must move past a range boundary before its level changes,
    /// in `[0, 1]` (default: `0.1`, 10%).
    pub hysteresis: f32,
}

impl LodParams {
    /// With patches of `patch_cells` cells ([`LodParams::patch_cells`]).
    #[must_use]
    pub fn with_patch_cells(self, patch_cells: usize) -> Self {
        Self {
            patch_cells,
            ..self
        }
    }

    /// With full detail within `first_range` ([`LodParams::first_range`]).
    #[must_use]
    pub fn with_first_range(self, first_range: f32) -> Self {
        Self {
            first_range,
            ..self
        }
    }

    /// With `levels` levels ([`LodParams::levels`]; 1 is the full grid everywhere).
    #[must_use]
    pub fn with_levels(self, levels: u32) -> Self {
        Self { levels, ..self }
    }

    /// With `hysteresis` ([`LodParams::hysteresis`]).
    #[must_use]
    pub fn with_hysteresis(self, hysteresis: f32) -> Self {
        Self { hysteresis, ..self }
    }
}

impl Default for LodParams {
    fn default() -> Self {
        Self {
            patch_cells: 16,
            first_range: 32.0,
            levels: 5,
            hysteresis: 0.1,
        }
    }
}

impl LodParams {
    /// Checks every field.
    pub fn validate(&self) -> Result<()> {
        let p = self.patch_cells;
        if !(p.is_power_of_two() && p <= 4096) {
            return Err(Error::InvalidParam {
                name: "patch_cells",
                value: p as f64,
                expected: "a power of two from 1 to 4096 (for example 16)",
            });
        }
        crate::params::positive("first_range", self.first_range)?;
        let max = self.max_levels();
        if !(1..=max).contains(&self.levels) {
            return Err(Error::LodLevels {
                levels: self.levels,
                patch_cells: p,
                max,
            });
        }
        if !(self.hysteresis.is_finite() && (0.0..=1.0).contains(&self.hysteresis)) {
            return Err(Error::InvalidParam {
                name: "hysteresis",
                value: self.hysteresis as f64,
                expected: "a fraction in [0, 1] (for example 0.1)",
            });
        }
        Ok(())
    }

    /// `log2(patch_cells) + 1`: the most levels this patch size allows.
    pub fn max_levels(&self) -> u32 {
        self.patch_cells.max(1).trailing_zeros() + 1
    }

    /// The level for a patch at distance `d` from the eye, without hysteresis: 0 below
    /// `first_range`, `l` in `[first_range·2^(l−1), first_range·2^l)`, at most `levels − 1`.
    /// A NaN distance gives level 0.
    pub fn level_for_distance(&self, d: f32) -> u8 {
        let top = self.levels.saturating_sub(1).min(u8::MAX as u32) as u8;
        let mut level = 0;
        let mut bound = self.first_range;
        while level < top && d >= bound {
            level += 1;
            bound *= 2.0;
        }
        level
    }
}

/// The grid a cache was built for.
#[derive(Debug, Clone, Copy, PartialEq)]
struct Shape {
    grid: Grid,
    spacing: f32,
}

/// Scratch vertex lists, reused by every patch.
#[derive(Debug, Clone, Default)]
struct Scratch {
    xs: Vec<u32>,
    zs: Vec<u32>,
    edges: [Vec<u32>; 4],
    outer: Vec<(u32, u32)>,
    inner: Vec<(u32, u32)>,
}

/// A cached, view-dependent, crack-free triangle index buffer .
///
/// ```
/// use springwater::mesh::{LodMesh, LodParams};
/// use springwater::{Params, Surface};
/// use glam::Vec3;
///
/// let water = Surface::new(Params::with_size(200, 120))?;   // not 2^k + 1: fine
/// let mut lod = LodMesh::new(LodParams::default())?;
/// let eye = Vec3::new(20.0, 10.0, 20.0);
/// assert!(lod.update(&water.mesh_view(), eye));              // built
/// assert!(!lod.update(&water.mesh_view(), eye));             // cached
/// let full_grid = 2 * 199 * 119;
/// assert!(lod.indices().len() / 3 < full_grid);               // coarser far away
/// assert_eq!(lod.triangle_levels().len(), lod.indices().len() / 3);
/// # Ok::<(), springwater::Error>(())
/// ```
///
/// # Method
///
/// ## Patches and levels
///
/// The grid's cells are cut into square patches of `P = 2^k` cells
/// ([`LodParams::patch_cells`]), row-major, starting at node `(0, 0)`. When `cols − 1` or
/// `rows − 1` is not a multiple of `P` the last patch of a row or column is narrower: any
/// grid from 2×2 nodes up works. A patch at level `l` uses every `2^l`-th node of its
/// rows and columns (its step), always keeping its last row and column, so a patch whose
/// width is not a multiple of the step ends with one narrower column of cells.
///
/// A patch's level comes from the distance between the eye and the patch's rest footprint
/// (the rectangle it covers in the plane `y = 0`): level 0 within
/// [`first_range`](LodParams::first_range) `R`, level `l ≥ 1` for distances in
/// `[R·2^(l−1), R·2^l)`, capped at [`levels`](LodParams::levels)` − 1` — each level's range
/// twice the previous one's. The footprint, not the moving surface, sets the distance, so
/// the levels depend on the camera only and the index buffer can be cached.
///
/// ## Hysteresis
///
/// A patch keeps its level until the distance has crossed a range boundary by the factor
/// `1 + hysteresis`: it coarsens from level `l` when the distance exceeds `R·2^l·(1 + hys)`
/// and refines when it falls below `R·2^(l−1)/(1 + hys)`. An eye hovering at a boundary
/// therefore does not flip the mesh every frame. The first update (and the first one after
/// the grid shape changes) uses the plain distances.
///
/// ## Balance and stitching
///
/// The levels are then lowered where needed so that patches sharing an edge differ by at
/// most one level (2:1 balance). This is a city-block distance transform — each patch's
/// level becomes `min over patches q of (level(q) + |Δcol| + |Δrow|)` — done exactly by one
/// forward and one backward sweep.
///
/// Each patch edge then gets one list of vertices, the one of the *coarser* of the two
/// patches sharing it (at the grid border: the patch's own). Because steps are powers of
/// two starting at the patch corner, the coarser list is a subset of the finer side's own
/// vertices. Both patches use exactly that list on the edge, so every edge segment between
/// two patches is drawn by one triangle on each side, in opposite directions: no crack and
/// no T-junction. Inside a patch:
///
/// * no stitched edge: two triangles per cell of the patch's own step;
/// * stitched, at least two cells each way: the inner cells keep two triangles each, and
///   the ring of border cells becomes four trapezoids, each between an edge's vertex list
///   and the row (or column) of inner vertices next to it;
/// * stitched, one cell thick: the whole patch is one such strip between its two long edges.
///
/// A strip between two parallel rows of vertices is triangulated by zipping along them,
/// each time adding the triangle whose new diagonal is shorter. Any order of a zip covers
/// the (convex) strip exactly once with triangles that have two corners on one row and
/// one on the other, so none is degenerate.
///
/// Every triangle is written counter-clockwise seen from +y (its face normal points up) and
/// indexes the full row-major node array: `index = row·cols + col`.
///
/// ## Caching
///
/// [`LodMesh::update`] recomputes the levels (a few operations per patch) and rebuilds the
/// index buffer only if some level changed. The buffers keep their capacity.
#[derive(Debug, Clone)]
pub struct LodMesh {
    params: LodParams,
    shape: Option<Shape>,
    /// Patches across and down.
    patches: [usize; 2],
    /// Per patch: the distance level after hysteresis, before balancing.
    raw: Vec<u8>,
    /// Per patch: the balanced level the index buffer was built with.
    levels: Vec<u8>,
    next: Vec<u8>,
    /// Per patch column: squared x distance from the eye to its footprint.
    gap_x: Vec<f32>,
    indices: Vec<u32>,
    triangle_levels: Vec<u8>,
    scratch: Scratch,
}

impl LodMesh {
    /// An empty mesh with validated parameters; the first [`LodMesh::update`] builds it.
    pub fn new(params: LodParams) -> Result<Self> {
        params.validate()?;
        Ok(Self {
            params,
            shape: None,
            patches: [0, 0],
            raw: Vec::new(),
            levels: Vec::new(),
            next: Vec::new(),
            gap_x: Vec::new(),
            indices: Vec::new(),
            triangle_levels: Vec::new(),
            scratch: Scratch::default(),
        })
    }

    /// The parameters.
    pub fn params(&self) -> &LodParams {
        &self.params
    }

    /// Recomputes the patch levels for `eye` (in the water's local space) and rebuilds the
    /// index buffer if any level changed. Returns true if the buffer was rebuilt (upload
    /// it again), false if the cached one still holds.
    ///
    /// A different grid shape or spacing than last time starts over (levels without
    /// hysteresis). An eye with a non-finite coordinate leaves the mesh as it is; on a new
    /// mesh it builds level 0 everywhere.
    ///
    /// # Panics
    ///
    /// If the grid has more than 2^32 nodes (a `u32` cannot index them; a
    /// [`Surface`](crate::Surface) never has that many).
    pub fn update(&mut self, view: &MeshView<'_>, eye: Vec3) -> bool {
        let fresh = self.reshape(view);
        if !fresh && !eye.is_finite() {
            return false;
        }
        // The footprints are measured from node (0, 0): the eye relative to the window.
        let [ox, oz] = view.origin();
        self.distance_levels(eye - Vec3::new(ox, 0.0, oz), fresh);
        self.apply(fresh)
    }

    /// Builds the mesh from levels chosen by the caller (one per patch, row-major over
    /// [`LodMesh::patch_grid`] for this view's grid) instead of from an eye distance: for a
    /// renderer with its own error metric, or to force full detail. Levels are capped at
    /// `levels − 1`, then balanced 2:1 and stitched like [`LodMesh::update`]'s. Returns
    /// true if the index buffer was rebuilt. The next [`LodMesh::update`] applies its
    /// hysteresis against these levels.
    ///
    /// # Panics
    ///
    /// Like [`LodMesh::update`].
    pub fn set_levels(&mut self, view: &MeshView<'_>, levels: &[u8]) -> Result<bool> {
        let [across, down] = self.patches_for(view.grid());
        same_length("patch levels", levels.len(), across * down)?;
        let fresh = self.reshape(view);
        let top = (self.params.levels - 1) as u8;
        self.raw.clear();
        self.raw.extend(levels.iter().map(|&l| l.min(top)));
        Ok(self.apply(fresh))
    }

    /// Patches `[across, down]` for `grid`.
    fn patches_for(&self, grid: Grid) -> [usize; 2] {
        let p = self.params.patch_cells;
        [(grid.cols - 1).div_ceil(p), (grid.rows - 1).div_ceil(p)]
    }

    /// Starts over if `view` has another grid shape or spacing than the cache: returns
    /// true then (the levels are fresh, without hysteresis).
    fn reshape(&mut self, view: &MeshView<'_>) -> bool {
        let grid = view.grid();
        assert!(
            grid.node_count() - 1 <= u32::MAX as usize,
            "a u32 index buffer cannot address {} nodes",
            grid.node_count()
        );
        let shape = Shape {
            grid,
            spacing: view.spacing(),
        };
        if self.shape == Some(shape) {
            return false;
        }
        self.shape = Some(shape);
        self.patches = self.patches_for(grid);
        self.raw.clear();
        self.raw.resize(self.patches[0] * self.patches[1], 0);
        self.levels.clear();
        true
    }

    /// Balances `raw` and rebuilds the index buffer if the result differs from the levels
    /// it was built with (or always, when `fresh`). Returns true if it rebuilt.
    fn apply(&mut self, fresh: bool) -> bool {
        self.next.clear();
        self.next.extend_from_slice(&self.raw);
        balance(&mut self.next, self.patches);
        if !fresh && self.next == self.levels {
            return false;
        }
        std::mem::swap(&mut self.next, &mut self.levels);
        self.rebuild();
        true
    }

    /// Triangles, three indices each, counter-clockwise seen from +y, indexing the full
    /// row-major node array. Empty before the first [`LodMesh::update`].
    pub fn indices(&self) -> &[u32] {
        &self.indices
    }

    /// The LOD level of each triangle (for wireframe colouring), one per triangle.
    pub fn triangle_levels(&self) -> &[u8] {
        &self.triangle_levels
    }

    /// The level of each patch, row-major over patches (see [`LodMesh::patch_grid`]).
    pub fn patch_levels(&self) -> &[u8] {
        &self.levels
    }

    /// Patches `[across, down]`: `ceil((cols−1)/patch_cells)`, `ceil((rows−1)/patch_cells)`.
    pub fn patch_grid(&self) -> [usize; 2] {
        self.patches
    }

    /// Number of triangles.
    pub fn triangle_count(&self) -> usize {
        self.triangle_levels.len()
    }

    /// Sets `raw` from the eye's distance to each patch footprint, with hysteresis
    /// against the previous `raw` unless `fresh`.
    fn distance_levels(&mut self, eye: Vec3, fresh: bool) {
        let shape = self.shape.expect("reshape() ran first");
        let p = self.params.patch_cells;
        let [across, down] = self.patches;
        let (cols, rows, h) = (shape.grid.cols, shape.grid.rows, shape.spacing);
        let grow = 1.0 + self.params.hysteresis;
        let shrink = 1.0 / grow;
        // Squared distance from the eye to a patch's footprint, split by axis.
        let gap2 = |e: f32, patch: usize, last: usize| {
            let (lo, hi) = (patch * p, ((patch + 1) * p).min(last));
            let gap = (lo as f32 * h - e).max(e - hi as f32 * h).max(0.0);
            gap * gap
        };
        self.gap_x.clear();
        self.gap_x
            .extend((0..across).map(|pc| gap2(eye.x, pc, cols - 1)));
        for pr in 0..down {
            let yz2 = eye.y * eye.y + gap2(eye.z, pr, rows - 1);
            let row = &mut self.raw[pr * across..(pr + 1) * across];
            for (raw, gx2) in row.iter_mut().zip(&self.gap_x) {
                let d = (gx2 + yz2).sqrt();
                *raw = if fresh {
                    self.params.level_for_distance(d)
                } else {
                    let coarser = self.params.level_for_distance(d * shrink);
                    let finer = self.params.level_for_distance(d * grow);
                    if coarser > *raw {
                        coarser
                    } else if finer < *raw {
                        finer
                    } else {
                        *raw
                    }
                };
            }
        }
    }

    fn rebuild(&mut self) {
        let grid = self.shape.expect("reshape() ran first").grid;
        self.indices.clear();
        self.triangle_levels.clear();
        let p = self.params.patch_cells;
        let [across, down] = self.patches;
        let levels = &self.levels;
        let mut emit = Emit {
            cols: grid.cols as u32,
            indices: &mut self.indices,
            levels: &mut self.triangle_levels,
            level: 0,
        };
        for pr in 0..down {
            for pc in 0..across {
                let i = pr * across + pc;
                let l = levels[i];
                // Edge levels: the coarser of the patch and its neighbour (own at the border).
                let north = if pr > 0 { levels[i - across].max(l) } else { l };
                let south = if pr + 1 < down {
                    levels[i + across].max(l)
                } else {
                    l
                };
                let west = if pc > 0 { levels[i - 1].max(l) } else { l };
                let east = if pc + 1 < across {
                    levels[i + 1].max(l)
                } else {
                    l
                };
                let (c0, r0) = (pc * p, pr * p);
                let (c1, r1) = ((c0 + p).min(grid.cols - 1), (r0 + p).min(grid.rows - 1));
                emit.level = l;
                patch(
                    &mut emit,
                    &mut self.scratch,
                    [c0 as u32, c1 as u32, r0 as u32, r1 as u32],
                    l,
                    [north, south, west, east],
                );
            }
        }
    }
}

/// Lowers levels so that edge neighbours differ by at most one: an exact city-block
/// distance transform in two sweeps.
fn balance(levels: &mut [u8], [across, down]: [usize; 2]) {
    for r in 0..down {
        for c in 0..across {
            let i = r * across + c;
            if c > 0 {
                levels[i] = levels[i].min(levels[i - 1] + 1);
            }
            if r > 0 {
                levels[i] = levels[i].min(levels[i - across] + 1);
            }
        }
    }
    for r in (0..down).rev() {
        for c in (0..across).rev() {
            let i = r * across + c;
            if c + 1 < across {
                levels[i] = levels[i].min(levels[i + 1] + 1);
            }
            if r + 1 < down {
                levels[i] = levels[i].min(levels[i + across] + 1);
            }
        }
    }
}

/// `lo, lo + step, lo + 2·step, …` below `hi`, then `hi`.
fn vertices(lo: u32, hi: u32, step: u32, out: &mut Vec<u32>) {
    out.clear();
    out.extend((lo..hi).step_by(step as usize));
    out.push(hi);
}

/// Triangulates one patch `[c0, c1] × [r0, r1]` at `level`, with the edge vertex lists of
/// levels `[north, south, west, east]` (see the [`LodMesh`] docs).
fn patch(
    emit: &mut Emit<'_>,
    s: &mut Scratch,
    [c0, c1, r0, r1]: [u32; 4],
    level: u8,
    edge_levels: [u8; 4],
) {
    vertices(c0, c1, 1 << level, &mut s.xs);
    vertices(r0, r1, 1 << level, &mut s.zs);
    let [north, south, west, east] = edge_levels;
    vertices(c0, c1, 1 << north, &mut s.edges[0]);
    vertices(c0, c1, 1 << south, &mut s.edges[1]);
    vertices(r0, r1, 1 << west, &mut s.edges[2]);
    vertices(r0, r1, 1 << east, &mut s.edges[3]);
    let (xs, zs) = (&s.xs, &s.zs);
    let [en, es, ew, ee] = &s.edges;
    let (m, n) = (xs.len() - 1, zs.len() - 1);
    let stitched = en != xs || es != xs || ew != zs || ee != zs;
    if !stitched {
        for j in 0..n {
            for i in 0..m {
                emit.quad(xs[i], xs[i + 1], zs[j], zs[j + 1]);
            }
        }
        return;
    }
    let (outer, inner) = (&mut s.outer, &mut s.inner);
    if m == 1 {
        // One column of cells: zip the west edge with the east edge.
        fill(outer, ew.iter().map(|&z| (c0, z)));
        fill(inner, ee.iter().map(|&z| (c1, z)));
        emit.zip(outer, inner, Axis::Z);
        return;
    }
    if n == 1 {
        fill(outer, en.iter().map(|&x| (x, r0)));
        fill(inner, es.iter().map(|&x| (x, r1)));
        emit.zip(outer, inner, Axis::X);
        return;
    }
    for j in 1..n - 1 {
        for i in 1..m - 1 {
            emit.quad(xs[i], xs[i + 1], zs[j], zs[j + 1]);
        }
    }
    let inner_x = &xs[1..m];
    let inner_z = &zs[1..n];
    let sides: [(&Vec<u32>, u32, u32, Axis); 4] = [
        (en, r0, zs[1], Axis::X),
        (es, r1, zs[n - 1], Axis::X),
        (ew, c0, xs[1], Axis::Z),
        (ee, c1, xs[m - 1], Axis::Z),
    ];
    for (edge, at, inner_at, axis) in sides {
        match axis {
            Axis::X => {
                fill(outer, edge.iter().map(|&x| (x, at)));
                fill(inner, inner_x.iter().map(|&x| (x, inner_at)));
            }
            Axis::Z => {
                fill(outer, edge.iter().map(|&z| (at, z)));
                fill(inner, inner_z.iter().map(|&z| (inner_at, z)));
            }
        }
        emit.zip(outer, inner, axis);
    }
}

fn fill(v: &mut Vec<(u32, u32)>, it: impl Iterator<Item = (u32, u32)>) {
    v.clear();
    v.extend(it);
}

/// The direction a zipped strip runs in.
#[derive(Debug, Clone, Copy)]
enum Axis {
    X,
    Z,
}

/// Appends triangles given by `(col, row)` corners.
struct Emit<'a> {
    cols: u32,
    indices: &'a mut Vec<u32>,
    levels: &'a mut Vec<u8>,
    level: u8,
}

impl Emit<'_> {
    fn index(&self, (c, r): (u32, u32)) -> u32 {
        r * self.cols + c
    }

    /// A triangle, turned counter-clockwise seen from +y.
    fn triangle(&mut self, a: (u32, u32), b: (u32, u32), c: (u32, u32)) {
        let d = |p: (u32, u32), q: (u32, u32)| (q.0 as i64 - p.0 as i64, q.1 as i64 - p.1 as i64);
        let ((bx, bz), (cx, cz)) = (d(a, b), d(a, c));
        // y of (b − a) × (c − a), with x = col and z = row.
        let up = bz * cx - bx * cz;
        debug_assert!(up != 0, "degenerate triangle {a:?} {b:?} {c:?}");
        let (b, c) = if up > 0 { (b, c) } else { (c, b) };
        let tri = [self.index(a), self.index(b), self.index(c)];
        self.indices.extend_from_slice(&tri);
        self.levels.push(self.level);
    }

    /// The cell `[x0, x1] × [z0, z1]` as two triangles split along the (x1, z0)–(x0, z1)
    /// diagonal.
    fn quad(&mut self, x0: u32, x1: u32, z0: u32, z1: u32) {
        let (a, b) = (z0 * self.cols, z1 * self.cols);
        self.indices
            .extend_from_slice(&[a + x0, b + x0, a + x1, a + x1, b + x0, b + x1]);
        self.levels.extend_from_slice(&[self.level, self.level]);
    }

    /// Triangulates the strip between two parallel rows of vertices `a` and `b`, both
    /// ordered along `axis` and starting at the strip's same end.
    fn zip(&mut self, a: &[(u32, u32)], b: &[(u32, u32)], axis: Axis) {
        let key = |p: (u32, u32)| match axis {
            Axis::X => p.0,
            Axis::Z => p.1,
        };
        let (mut i, mut j) = (0, 0);
        while i + 1 < a.len() || j + 1 < b.len() {
            let advance_a = if i + 1 == a.len() {
                false
            } else if j + 1 == b.len() {
                true
            } else {
                key(a[i + 1]).abs_diff(key(b[j])) <= key(a[i]).abs_diff(key(b[j + 1]))
            };
            if advance_a {
                self.triangle(a[i], a[i + 1], b[j]);
                i += 1;
            } else {
                self.triangle(a[i], b[j + 1], b[j]);
                j += 1;
            }
        }
    }
}
