//! The crate's error type. Every variant says what was wrong and how to fix it.

use thiserror::Error;

/// Everything that can go wrong when building or driving a [`Surface`](crate::Surface).
///
/// A call that returns an error has changed nothing.
#[derive(Debug, Clone, PartialEq, Error)]
#[non_exhaustive]
pub enum Error {
    /// A parameter is not a finite number, or is outside its allowed range.
    #[error("{name} = {value} is invalid: {expected}")]
    InvalidParam {
        /// The parameter's name: the [`Params`](crate::Params) field or the argument
        /// (`mass`, `dt`, `drop radius`, …).
        name: &'static str,
        /// The value that was refused.
        value: f64,
        /// What the value must be.
        expected: &'static str,
    },

    /// `SPRINGWATER_SIMD` (or a level given by name) is not a SIMD level.
    #[error(
        "SIMD level '{value}' is unknown: use scalar, sse2, avx2, avx512, neon, simd128 or portable"
    )]
    InvalidSimdLevel {
        /// The name that was given.
        value: String,
    },

    /// The grid has fewer than 2 nodes in some direction.
    #[error("grid {cols}x{rows} is too small: a surface needs at least 2x2 nodes")]
    GridTooSmall {
        /// Nodes per row.
        cols: usize,
        /// Rows.
        rows: usize,
    },

    /// The grid has more nodes than this process can address or allocate.
    #[error(
        "grid {cols}x{rows} is too large to allocate ({bytes} bytes of state); \
         use at most 2^26 nodes (for example 8192x8192)"
    )]
    GridTooLarge {
        /// Nodes per row.
        cols: usize,
        /// Rows.
        rows: usize,
        /// Bytes the state would need (saturating).
        bytes: u128,
    },

    /// The timestep is at or past the critical timestep of the lattice.
    #[error(
        "timestep {dt} is at or past the critical timestep {} for these parameters; \
         use dt < {} (for example {}), raise the mass or lower the stiffness",
        Decimals(*.critical, 4), Decimals(*.critical, 4), Decimals(*.suggest, 3)
    )]
    TimestepTooLarge {
        /// The timestep that was asked for.
        dt: f32,
        /// `critical_dt()` for the parameters (largest stiffness, smallest mass).
        critical: f32,
        /// A safe suggestion (95% of the critical value).
        suggest: f32,
    },

    /// A step would have produced a non-finite position or velocity. The state is unchanged.
    #[error(
        "step {step} would make the state non-finite (node {node}); the step was not applied. \
         Check external forces for NaN or huge values, and drops for |height| > radius"
    )]
    NonFinite {
        /// Steps taken before the refused one.
        step: u64,
        /// The first node (row-major index) whose new value was not finite.
        node: usize,
    },

    /// A floating body's forces or motion would have become non-finite or left the ranges
    /// of [`Floater::validate`](crate::Floater::validate) (bodies far too large, dense,
    /// fast or hard pushed for `f32`). The step was not applied.
    #[error(
        "step {step} would make floater {floater} non-finite or out of range; the step was \
         not applied. Check the floater's size, mass, speed and push and the buoyancy's \
         gravity and density"
    )]
    FloaterNonFinite {
        /// Steps taken before the refused one.
        step: u64,
        /// The body's [`FloaterId`](crate::FloaterId) number.
        floater: u64,
    },

    /// No floater of this surface has this id (never added, or removed).
    #[error("floater {0} does not exist on this surface")]
    NoSuchFloater(u64),

    /// A node index or grid coordinate is outside the grid.
    #[error("{what} {index} is out of range (the grid has {len})")]
    OutOfRange {
        /// What was indexed ("node", "col", …).
        what: &'static str,
        /// The index that was given.
        index: usize,
        /// The number of valid indices.
        len: usize,
    },

    /// A slice passed in has the wrong length.
    #[error("{what} has length {got}, expected {expected}")]
    LengthMismatch {
        /// Which argument.
        what: &'static str,
        /// Its length.
        got: usize,
        /// The required length.
        expected: usize,
    },

    /// A query point is outside the surface's rest footprint.
    #[error(
        "point (x {x}, z {z}) from the window's origin is outside the water's footprint \
         [0, {width}] x [0, {length}]; check Surface::contains first or clamp the point into \
         the footprint"
    )]
    OutsideGrid {
        /// The point's x less the window's origin ([`Surface::origin`](crate::Surface::origin)).
        x: f32,
        /// The point's z less the window's origin.
        z: f32,
        /// `(cols − 1)·h`, the footprint's size along x.
        width: f32,
        /// `(rows − 1)·h`, the footprint's size along z.
        length: f32,
    },

    /// The LOD level count does not fit the patch size.
    #[error(
        "{levels} LOD levels do not fit {patch_cells}-cell patches: use 1 to {max} levels, \
         or larger patches (the coarsest level draws a patch as 2 triangles)"
    )]
    LodLevels {
        /// The level count asked for.
        levels: u32,
        /// The patch size in cells.
        patch_cells: usize,
        /// `log2(patch_cells) + 1`.
        max: u32,
    },

    /// The host's job system ([`Surface::set_job_system`](crate::Surface::set_job_system))
    /// returned without running every task it was given. The step was not applied.
    #[error(
        "the job system returned before running every task it was given; the step was not \
         applied (JobSystem::run must call the task once for each index below the count)"
    )]
    JobSystem,

    /// A hull mesh ([`Hull::new`](crate::body::Hull::new)) is not a closed, outward-wound,
    /// finite triangle mesh of the allowed size. The message names the first vertex,
    /// triangle or edge at fault and how to repair it.
    #[error("hull mesh refused: {0}")]
    InvalidHull(String),

    /// A snapshot could not be read: truncated, corrupted, or from another format version.
    #[error("snapshot refused: {0}")]
    Snapshot(String),

    /// Reading or writing a snapshot failed in the reader or writer given. The I/O error is
    /// the [`source`](std::error::Error::source).
    #[error("cannot {action} the snapshot: {source}")]
    Io {
        /// `"read"` or `"write"`.
        action: &'static str,
        /// What the reader or writer reported.
        #[source]
        source: IoError,
    },
}

/// A [`std::io::Error`] that can be cloned and compared (by kind and message), so that
/// [`Error`](enum@Error) stays `Clone` and `PartialEq`. [`IoError::get_ref`] gives the
/// original.
#[derive(Debug, Clone)]
pub struct IoError(std::sync::Arc<std::io::Error>);

impl IoError {
    /// The original I/O error.
    pub fn get_ref(&self) -> &std::io::Error {
        &self.0
    }

    /// Its kind.
    pub fn kind(&self) -> std::io::ErrorKind {
        self.0.kind()
    }
}

impl From<std::io::Error> for IoError {
    fn from(e: std::io::Error) -> Self {
        Self(std::sync::Arc::new(e))
    }
}

impl PartialEq for IoError {
    fn eq(&self, other: &Self) -> bool {
        self.kind() == other.kind() && self.0.to_string() == other.0.to_string()
    }
}

impl std::fmt::Display for IoError {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        self.0.fmt(f)
    }
}

impl std::error::Error for IoError {
    fn source(&self) -> Option<&(dyn std::error::Error + 'static)> {
        Some(&*self.0)
    }
}

/// Shorthand for results whose error is [`Error`](enum@Error).
pub type Result<T> = std::result::Result<T, Error>;

/// `Ok` when a buffer of `got` elements has the `expected` length, else
/// [`Error::LengthMismatch`] naming it `what`.
pub(crate) fn same_length(what: &'static str, got: usize, expected: usize) -> Result<()> {
    if got == expected {
        Ok(())
    } else {
        Err(Error::LengthMismatch {
            what,
            got,
            expected,
        })
    }
}

/// A number for a message: `digits` decimals, or, where that would leave fewer than three
/// significant digits (a critical timestep of 1e-16 is not "0.0000"), three significant
/// digits in exponent notation.
struct Decimals(f32, usize);

impl std::fmt::Display for Decimals {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        let Decimals(v, digits) = *self;
        if v == 0.0 || !v.is_finite() || v.abs() >= 10f32.powi(2 - digits as i32) {
            write!(f, "{v:.digits$}")
        } else {
            write!(f, "{v:.2e}")
        }
    }
}
