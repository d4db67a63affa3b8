//! Grid index math and the four spring families.
//!
//! Node `(col, row)` has index `row * cols + col` (row-major) and rests at
//! `(col·h, 0, row·h)`: y is up, the surface lies in the xz plane.

/// The four spring families, by the offset from a spring's origin node to its other end.
/// Every grid edge and both diagonals of every cell carry one spring, so an interior
/// node has 8 springs; each spring is stored once, at its origin.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
#[repr(u8)]
pub enum Family {
    /// East, `(+1, 0)`: along a row.
    E = 0,
    /// South, `(0, +1)`: to the next row.
    S = 1,
    /// South-east diagonal, `(+1, +1)`.
    SE = 2,
    /// South-west diagonal, `(-1, +1)`.
    SW = 3,
}

impl Family {
    /// All families in storage order.
    pub const ALL: [Family; 4] = [Family::E, Family::S, Family::SE, Family::SW];

    /// `(dcol, drow)` from the origin node to the other end.
    pub const fn offset(self) -> (isize, isize) {
        match self {
            Family::E => (1, 0),
            Family::S => (0, 1),
            Family::SE => (1, 1),
            Family::SW => (-1, 1),
        }
    }

    /// Initial length in grid steps: 1 for edges, √2 for diagonals.
    pub fn initial_length(self) -> f32 {
        match self {
            Family::E | Family::S => 1.0,
            Family::SE | Family::SW => std::f32::consts::SQRT_2,
        }
    }
}

/// One spring, named by its family and its origin node.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
pub struct SpringId {
    /// The family (direction) of the spring.
    pub family: Family,
    /// Row-major index of the origin node.
    pub origin: usize,
}

/// The shape of a grid: `cols × rows` nodes.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct Grid {
    /// Nodes per row.
    pub cols: usize,
    /// Rows of nodes.
    pub rows: usize,
}

impl Grid {
    /// A grid of `cols × rows` nodes.
    pub const fn new(cols: usize, rows: usize) -> Self {
        Self { cols, rows }
    }

    /// Number of nodes, `cols × rows`.
    pub const fn node_count(&self) -> usize {
        self.cols * self.rows
    }

    /// Number of nodes.
    #[deprecated(
        since = "0.2.0",
        note = "use `node_count`, the one name for the node count"
    )]
    pub const fn len(&self) -> usize {
        self.node_count()
    }

    /// Whether the grid has no node.
    #[deprecated(since = "0.2.0", note = "use `node_count() == 0`")]
    pub const fn is_empty(&self) -> bool {
        self.node_count() == 0
    }

    /// Row-major index of `(col, row)`.
    pub const fn index(&self, col: usize, row: usize) -> usize {
        row * self.cols + col
    }

    /// `(col, row)` of a row-major index.
    pub const fn coords(&self, index: usize) -> (usize, usize) {
        (index % self.cols, index / self.cols)
    }

    /// The other end of the spring of `family` at `origin`, if that spring exists.
    pub fn spring_end(&self, family: Family, origin: usize) -> Option<usize> {
        let (col, row) = self.coords(origin);
        let (dc, dr) = family.offset();
        let c = col.checked_add_signed(dc)?;
        let r = row.checked_add_signed(dr)?;
        (c < self.cols && r < self.rows).then(|| self.index(c, r))
    }

    /// Every spring of the grid, family-major, in origin order.
    pub fn springs(&self) -> impl Iterator<Item = (SpringId, usize)> + '_ {
        Family::ALL.into_iter().flat_map(move |family| {
            (0..self.node_count()).filter_map(move |origin| {
                self.spring_end(family, origin)
                    .map(|end| (SpringId { family, origin }, end))
            })
        })
    }

    /// Number of springs: `(cols−1)·rows + cols·(rows−1) + 2·(cols−1)·(rows−1)`.
    pub fn spring_count(&self) -> usize {
        let (c, r) = (self.cols, self.rows);
        (c - 1) * r + c * (r - 1) + 2 * (c - 1) * (r - 1)
    }

    /// True for nodes on the outer ring.
    pub fn is_border(&self, index: usize) -> bool {
        self.edge_distance(index) == 0
    }

    /// Cells from node `index` to the nearest edge of the grid (0 on the outer ring).
    pub fn edge_distance(&self, index: usize) -> usize {
        let (c, r) = self.coords(index);
        c.min(r).min(self.cols - 1 - c).min(self.rows - 1 - r)
    }
}
