//! [`NodeTable`]: one `f32` per node, stored as a few rows while every node holds its
//! place's default, and as a full array only once a caller sets a value of its own.
//!
//! # Why rows
//!
//! The step reads a per-node table one grid row at a time ([`NodeTable::row`]): the row
//! kernel loads it in chunks from the row's first column. So the table answers with a
//! row slice, and where the row comes from is the table's business:
//!
//! * **Defaults** — what a new surface gives each place — depend only on the place's
//!   distance from the edges: a node's mass is the same everywhere, its `1/m` is 0 on a
//!   pinned ring and `1/m` inside, its viscosity adds the absorbing frame's ramp, a
//!   function of `min(col, row, cols−1−col, rows−1−row)`. Two rows at the same distance
//!   from the top or bottom edge are therefore equal, and every row at least `K − 1` rows
//!   in is equal to every other. The defaults are kept as `K` *profile rows*: profile
//!   `k` is the row `k` rows from the top or bottom edge, the last one also every row
//!   further in. Uniform mass and viscosity keep one profile, `1/m` with a pinned ring
//!   two (the ring's all-zero row and `[0, 1/m, …, 1/m, 0]`), the absorbing viscosity
//!   `W + 1` for a frame of `W` rings: a few rows of `cols` floats in all, nothing per
//!   node.
//! * **Per-node values** appear when a node is set to anything but its default (a
//!   per-node mass, viscosity or pin, a snapshot whose arrays differ from the defaults):
//!   the table then holds a padded per-node array, and row `r` is the slice from node
//!   `r · cols`. The kernel cannot tell the two apart.
//!
//! The profiles stay when the per-node array comes, so the table always knows every
//! place's default ([`NodeTable::default_at`]): the moving window needs them (a default
//! stays with its place, a set value travels with the water), and a table whose nodes are
//! all back at their defaults drops its array again ([`NodeTable::compact`]).
//!
//! # What a row slice holds past the row
//!
//! A row is read in whole chunks, so the lanes past column `cols − 1` of the last chunk
//! read whatever follows: the next row's first nodes in the per-node array, zeros in a
//! profile row (each is padded by at least [`MAX_LANES`] zeros). The kernel discards
//! those lanes (a partial store writes and checks only the row's own lanes), so what they
//! hold never reaches a result: every SIMD level and the scalar reference agree, bit for
//! bit, whichever storage a table has.

use crate::grid::Grid;
use crate::simd::{round_up, Floats, MAX_LANES};

/// One `f32` per node: profile rows for the defaults, a per-node array once a node
/// differs from its default (see the [module docs](self)).
#[derive(Debug, Clone)]
pub(crate) struct NodeTable {
    defaults: Profiles,
    /// Every node's value (padded like the other per-node buffers), once any differs
    /// from its default.
    nodes: Option<Floats>,
}

/// The default rows of a [`NodeTable`].
#[derive(Debug, Clone)]
struct Profiles {
    cols: usize,
    rows: usize,
    /// Floats from one profile row to the next: `cols` and at least a lane of zeros.
    stride: usize,
    /// Number of profile rows, at least 1.
    count: usize,
    data: Floats,
}

impl Profiles {
    /// The profile row `r` reads: its distance from the top or bottom edge, at most the
    /// last profile.
    #[inline(always)]
    fn index(&self, r: usize) -> usize {
        r.min(self.rows - 1 - r).min(self.count - 1)
    }

    #[inline(always)]
    fn row(&self, r: usize) -> &[f32] {
        let start = self.index(r) * self.stride;
        &self.data[start..start + self.stride]
    }

    #[inline(always)]
    fn get(&self, i: usize) -> f32 {
        let (r, c) = (i / self.cols, i % self.cols);
        self.row(r)[c]
    }
}

impl NodeTable {
    /// The table whose default at node `(c, r)` is `profile(min(k, count − 1), c)`, `k`
    /// the row's distance from the top or bottom edge. `profile(count − 1, c)` must be
    /// the value of every row at least `count − 1` rows in.
    pub fn by_edge_distance(
        grid: Grid,
        count: usize,
        profile: impl Fn(usize, usize) -> f32,
    ) -> Self {
        let (cols, rows) = (grid.cols, grid.rows);
        // No grid has more distinct distances than half its rows (rounded up).
        let count = count.clamp(1, rows.div_ceil(2).max(1));
        let stride = round_up(cols + MAX_LANES);
        let mut data = Floats::zeros(count * stride);
        for (k, row) in data.chunks_exact_mut(stride).enumerate() {
            for (c, v) in row[..cols].iter_mut().enumerate() {
                *v = profile(k, c);
            }
        }
        Self {
            defaults: Profiles {
                cols,
                rows,
                stride,
                count,
                data,
            },
            nodes: None,
        }
    }

    /// The table holding `value` at every node by default.
    pub fn uniform(grid: Grid, value: f32) -> Self {
        Self::by_edge_distance(grid, 1, |_, _| value)
    }

    /// Number of nodes.
    pub fn len(&self) -> usize {
        self.defaults.cols * self.defaults.rows
    }

    /// Nodes per row.
    pub fn cols(&self) -> usize {
        self.defaults.cols
    }

    /// Row `r`'s values from column 0, padded past the row (see the [module
    /// docs](self)): at least `round_up(cols)` floats, the kernel's chunks of the row.
    #[inline(always)]
    pub fn row(&self, r: usize) -> &[f32] {
        debug_assert!(r < self.defaults.rows);
        match &self.nodes {
            Some(nodes) => &nodes[r * self.defaults.cols..],
            None => self.defaults.row(r),
        }
    }

    /// Node `i`'s value.
    #[inline]
    pub fn get(&self, i: usize) -> f32 {
        match &self.nodes {
            Some(nodes) => nodes[i],
            None => self.defaults.get(i),
        }
    }

    /// Node `i`'s default: the value a new surface gives its place.
    #[inline]
    pub fn default_at(&self, i: usize) -> f32 {
        self.defaults.get(i)
    }

    /// Whether the table holds a per-node array (some node may differ from its default).
    #[cfg(test)]
    pub fn is_per_node(&self) -> bool {
        self.nodes.is_some()
    }

    /// Sets node `i` to `value`. A value with the bits of the node's current one changes
    /// nothing (and allocates nothing); any other makes the table per-node.
    pub fn set(&mut self, i: usize, value: f32) {
        if value.to_bits() != self.get(i).to_bits() {
            self.per_node_mut()[i] = value;
        }
    }

    /// Makes every node's value `value(i)`: profile rows again when each is its node's
    /// default (bit for bit), a per-node array otherwise. Reads `value` once per node
    /// while it matches the defaults, and allocates only when it does not.
    pub fn assign(&mut self, value: impl Fn(usize) -> f32) {
        let n = self.len();
        match (0..n).find(|&i| value(i).to_bits() != self.default_at(i).to_bits()) {
            None => self.nodes = None,
            Some(_) => {
                let nodes = self.per_node_mut();
                for (i, v) in nodes[..n].iter_mut().enumerate() {
                    *v = value(i);
                }
            }
        }
    }

    /// The per-node values and the defaults beside them, for a caller that rewrites the
    /// values in place (the moving window); `None` while every node holds its default.
    /// Call [`NodeTable::compact`] afterwards.
    pub fn nodes_and_defaults(&mut self) -> Option<(&mut [f32], impl Fn(usize) -> f32 + '_)> {
        let n = self.len();
        let defaults = &self.defaults;
        let nodes = self.nodes.as_mut()?;
        Some((&mut nodes[..n], move |i| defaults.get(i)))
    }

    /// Drops the per-node array when every node holds its default again.
    pub fn compact(&mut self) {
        if let Some(nodes) = &self.nodes {
            let n = self.len();
            if (0..n).all(|i| nodes[i].to_bits() == self.default_at(i).to_bits()) {
                self.nodes = None;
            }
        }
    }

    /// Every node's value, row-major.
    pub fn iter(&self) -> NodeValuesIter<'_> {
        NodeValues::new(self).iter()
    }

    /// Every node's value, row-major, in a new vector.
    pub fn to_vec(&self) -> Vec<f32> {
        match &self.nodes {
            Some(nodes) => nodes[..self.len()].to_vec(),
            None => self.iter().copied().collect(),
        }
    }

    /// The per-node array, made from the defaults if the table had none.
    fn per_node_mut(&mut self) -> &mut [f32] {
        let defaults = &self.defaults;
        self.nodes.get_or_insert_with(|| {
            let n = defaults.cols * defaults.rows;
            let mut nodes = Floats::zeros(super::padded_len(n));
            for (i, v) in nodes[..n].iter_mut().enumerate() {
                *v = defaults.get(i);
            }
            nodes
        })
    }
}

/// One value per node of a [`Surface`](crate::Surface), row-major, read where the surface
/// keeps it: [`Surface::masses`](crate::Surface::masses) and
/// [`Surface::viscosities`](crate::Surface::viscosities).
///
/// While every node holds its default (the parameters' value, with the absorbing frame's
/// ramp for viscosities) the surface stores a few rows, not one value per node, so there
/// is no slice to lend: the view indexes (`values[i]`) and iterates (over `&f32`, like a
/// slice) instead, and [`NodeValues::to_vec`] copies the values out.
///
/// ```
/// use springwater::{Params, Surface};
///
/// let water = Surface::new(Params::with_size(8, 6))?;
/// let masses = water.masses();
/// assert_eq!(masses.len(), 48);
/// assert_eq!(masses[9], 4.0);
/// assert!(masses.iter().all(|&m| m == 4.0));
/// # Ok::<(), springwater::Error>(())
/// ```
#[derive(Clone, Copy)]
pub struct NodeValues<'a> {
    table: &'a NodeTable,
}

impl<'a> NodeValues<'a> {
    pub(crate) fn new(table: &'a NodeTable) -> Self {
        Self { table }
    }

    /// Number of nodes.
    pub fn len(&self) -> usize {
        self.table.len()
    }

    /// Always false: a surface has at least 2×2 nodes.
    pub fn is_empty(&self) -> bool {
        self.len() == 0
    }

    /// Node `i`'s value, `None` past the last node.
    pub fn get(&self, i: usize) -> Option<f32> {
        (i < self.len()).then(|| self.table.get(i))
    }

    /// Every node's value, row-major.
    pub fn iter(&self) -> NodeValuesIter<'a> {
        NodeValuesIter {
            table: self.table,
            row: 0,
            rest: [].iter(),
            left: self.len(),
        }
    }

    /// Every node's value, row-major, in a new vector.
    pub fn to_vec(&self) -> Vec<f32> {
        self.table.to_vec()
    }
}

impl std::ops::Index<usize> for NodeValues<'_> {
    type Output = f32;

    /// Node `i`'s value. Panics if `i` is not below [`NodeValues::len`].
    fn index(&self, i: usize) -> &f32 {
        let cols = self.table.cols();
        assert!(i < self.len(), "node {i} of {}", self.len());
        &self.table.row(i / cols)[i % cols]
    }
}

impl<'a> IntoIterator for NodeValues<'a> {
    type Item = &'a f32;
    type IntoIter = NodeValuesIter<'a>;

    fn into_iter(self) -> NodeValuesIter<'a> {
        self.iter()
    }
}

impl<'a> IntoIterator for &NodeValues<'a> {
    type Item = &'a f32;
    type IntoIter = NodeValuesIter<'a>;

    fn into_iter(self) -> NodeValuesIter<'a> {
        self.iter()
    }
}

impl std::fmt::Debug for NodeValues<'_> {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.debug_list().entries(self.iter()).finish()
    }
}

/// The iterator of [`NodeValues::iter`]: every node's value, row-major.
#[derive(Clone)]
pub struct NodeValuesIter<'a> {
    table: &'a NodeTable,
    /// The next row to start.
    row: usize,
    /// What is left of the current row.
    rest: std::slice::Iter<'a, f32>,
    /// Values left in all.
    left: usize,
}

impl<'a> Iterator for NodeValuesIter<'a> {
    type Item = &'a f32;

    #[inline]
    fn next(&mut self) -> Option<&'a f32> {
        loop {
            if let Some(v) = self.rest.next() {
                self.left -= 1;
                return Some(v);
            }
            if self.left == 0 {
                return None;
            }
            let cols = self.table.cols();
            self.rest = self.table.row(self.row)[..cols].iter();
            self.row += 1;
        }
    }

    fn size_hint(&self) -> (usize, Option<usize>) {
        (self.left, Some(self.left))
    }
}

impl ExactSizeIterator for NodeValuesIter<'_> {}

impl std::fmt::Debug for NodeValuesIter<'_> {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.debug_struct("NodeValuesIter")
            .field("left", &self.left)
            .finish_non_exhaustive()
    }
}

impl std::iter::FusedIterator for NodeValuesIter<'_> {}

#[cfg(test)]
mod tests {
    use super::*;

    fn frame(grid: Grid) -> NodeTable {
        // A ramp of 3 rings, keyed by the node's distance from the nearest edge.
        let ramp = |d: usize| if d < 3 { (3 - d) as f32 } else { 0.0 };
        let last = grid.cols - 1;
        NodeTable::by_edge_distance(grid, 4, move |k, c| 0.5 + ramp(k.min(c).min(last - c)))
    }

    #[test]
    fn profile_rows_give_each_node_its_edge_distance_value() {
        for (cols, rows) in [(2, 2), (3, 7), (9, 4), (20, 13), (33, 40)] {
            let grid = Grid::new(cols, rows);
            let t = frame(grid);
            for i in 0..grid.node_count() {
                let d = grid.edge_distance(i);
                let want = 0.5 + if d < 3 { (3 - d) as f32 } else { 0.0 };
                assert_eq!(t.get(i), want, "{cols}x{rows} node {i}");
                let (c, r) = grid.coords(i);
                assert_eq!(t.row(r)[c], want, "{cols}x{rows} row {r}");
            }
            for r in 0..rows {
                let row = t.row(r);
                assert!(row.len() >= round_up(cols) && row.len() >= cols + MAX_LANES);
                assert!(row[cols..].iter().all(|&v| v == 0.0), "padding of row {r}");
            }
            assert!(!t.is_per_node());
            assert_eq!(t.to_vec().len(), cols * rows);
        }
    }

    #[test]
    fn a_set_value_makes_the_table_per_node_and_compact_undoes_it() {
        let grid = Grid::new(12, 10);
        let mut t = frame(grid);
        let before = t.to_vec();
        t.set(30, before[30]);
        assert!(!t.is_per_node(), "the same bits cost nothing");
        t.set(30, 9.0);
        assert!(t.is_per_node());
        assert_eq!(t.get(30), 9.0);
        assert_eq!(t.row(2)[6], 9.0);
        let mut expected = before.clone();
        expected[30] = 9.0;
        assert_eq!(t.to_vec(), expected);
        t.set(30, before[30]);
        t.compact();
        assert!(!t.is_per_node());
        t.assign(|i| before[i]);
        assert!(!t.is_per_node(), "the defaults load as profiles");
        t.assign(|i| if i == 5 { -0.0 } else { before[i] });
        assert!(t.is_per_node());
        assert_eq!(t.get(5).to_bits(), (-0.0f32).to_bits());
    }
}
