//! Validation: every invariant the engine relies on, checked on a snapshot's contents
//! wherever they are, in a [`Snapshot`](super::Snapshot)'s vectors or in the bytes of a
//! saved one (so that [`Surface::restore`](crate::Surface::restore) can check before it
//! copies, allocating nothing).
//!
//! The checks run part by part, in the order of the format: the parameters; each array's
//! length and finiteness; the derived state (bounds, the pending flag, the counters); each
//! node's mass, viscosity and pin; the springs; the bodies; the clock and the window; and
//! last the timestep against the critical one. The version-specific checks (reserved
//! fields, codes a version did not have) are the decoders' (`versions.rs`).

use super::read::Le;
use super::{bad, Scalars};
use crate::error::Result;
use crate::floater::{Floater, FloaterId};
use crate::grid::{Family, Grid};
use crate::params;
use crate::stability::Stability;
use crate::surface::bodies::{section, Entry};
use crate::surface::{Surface, MAX_ORIGIN_CELLS};
use std::ops::Range;

/// One `f32` per node, in a slice or in little-endian bytes.
pub(super) trait NodeFloats: Copy {
    fn len(self) -> usize;
    /// The values `range` of the nodes.
    fn part(self, range: Range<usize>) -> Self;
    /// Writes the values from node `at` on into `out` (`out.len()` of them).
    fn read(self, at: usize, out: &mut [f32]);
    /// The values as a slice, where they can be read in place.
    fn as_slice(&self) -> Option<&[f32]>;
}

impl NodeFloats for &[f32] {
    fn len(self) -> usize {
        <[f32]>::len(self)
    }
    fn part(self, range: Range<usize>) -> Self {
        &self[range]
    }
    fn read(self, at: usize, out: &mut [f32]) {
        out.copy_from_slice(&self[at..at + out.len()]);
    }
    fn as_slice(&self) -> Option<&[f32]> {
        Some(self)
    }
}

impl NodeFloats for Le<'_> {
    fn len(self) -> usize {
        self.0.len() / 4
    }
    fn part(self, range: Range<usize>) -> Self {
        Le(&self.0[4 * range.start..4 * range.end])
    }
    fn read(self, at: usize, out: &mut [f32]) {
        let bytes = &self.0[4 * at..4 * (at + out.len())];
        for (o, c) in out.iter_mut().zip(bytes.chunks_exact(4)) {
            *o = f32::from_le_bytes([c[0], c[1], c[2], c[3]]);
        }
    }
    /// On a little-endian target, bytes aligned for `f32` (a save in a `Vec<u8>` whose
    /// arrays start at multiples of 4) are the values themselves.
    fn as_slice(&self) -> Option<&[f32]> {
        cfg!(target_endian = "little")
            .then(|| bytemuck::try_cast_slice(self.0).ok())
            .flatten()
    }
}

/// One pinned flag per node, as `bool`s or as bytes 0 and 1.
pub(super) trait NodePins: Copy {
    fn len(self) -> usize;
    /// Writes the flags from node `at` on into `out` as 0 and 1.
    fn read(self, at: usize, out: &mut [u8]);
}

impl NodePins for &[bool] {
    fn len(self) -> usize {
        <[bool]>::len(self)
    }
    fn read(self, at: usize, out: &mut [u8]) {
        for (o, &p) in out.iter_mut().zip(&self[at..]) {
            *o = p as u8;
        }
    }
}

impl NodePins for &[u8] {
    fn len(self) -> usize {
        <[u8]>::len(self)
    }
    fn read(self, at: usize, out: &mut [u8]) {
        out.copy_from_slice(&self[at..at + out.len()]);
    }
}

/// Nodes per block that [`blocks`] reads into the stack.
pub(super) const BLOCK: usize = 256;

/// Calls `f(start, values)` for consecutive blocks of up to [`BLOCK`] nodes of `arrays`
/// (of one length), each block a slice of the array where it can be read in place, else
/// read into the stack: the checks then run over plain slices, which the compiler keeps
/// in SIMD registers, wherever the values are stored. Stops at the first `Some`.
pub(super) fn blocks<F: NodeFloats, T, const K: usize>(
    arrays: [F; K],
    mut f: impl FnMut(usize, [&[f32]; K]) -> Option<T>,
) -> Option<T> {
    let n = arrays.first().map_or(0, |a| a.len());
    let in_place = arrays.each_ref().map(|a| a.as_slice());
    let mut buffers = [[0f32; BLOCK]; K];
    for start in (0..n).step_by(BLOCK) {
        let len = BLOCK.min(n - start);
        for ((buffer, a), direct) in buffers.iter_mut().zip(arrays).zip(in_place) {
            if direct.is_none() {
                a.read(start, &mut buffer[..len]);
            }
        }
        let values = std::array::from_fn(|k| match in_place[k] {
            Some(direct) => &direct[start..start + len],
            None => &buffers[k][..len],
        });
        if let Some(found) = f(start, values) {
            return Some(found);
        }
    }
    None
}

/// The first index below `len` where `bad` holds: one pass without early exit (which the
/// compiler vectorises), a second only when something is wrong, to say where.
pub(super) fn first_bad(len: usize, bad: impl Fn(usize) -> bool) -> Option<usize> {
    if (0..len).fold(false, |any, i| any | bad(i)) {
        (0..len).position(bad)
    } else {
        None
    }
}

/// The first node of `a` where `bad` holds, with its value.
fn first_bad_value<F: NodeFloats>(a: F, bad: impl Fn(f32) -> bool) -> Option<(usize, f32)> {
    blocks([a], |start, [v]| {
        first_bad(v.len(), |i| bad(v[i])).map(|i| (start + i, v[i]))
    })
}

/// A snapshot's contents, borrowed: the fields beside the arrays, the arrays and the
/// bodies (decoded: a body's record and hull mesh are checked as they are decoded).
pub(super) struct Contents<'a, F, P> {
    pub scalars: &'a Scalars,
    pub positions: [F; 3],
    pub velocities: [F; 3],
    pub forces: [F; 3],
    pub mass: F,
    pub viscosity: F,
    pub pinned: P,
    pub rest: [F; 4],
    pub stiffness: [F; 4],
    pub bodies: &'a [(FloaterId, Floater)],
    /// The water column's entries.
    pub column: &'a [Entry],
}

/// The columns of row `r` whose spring of `family` exists (the others store zeros).
pub(super) fn spring_columns(grid: Grid, family: Family, r: usize) -> Range<usize> {
    let (dc, dr) = family.offset();
    if r + dr as usize >= grid.rows {
        return 0..0;
    }
    match dc {
        1 => 0..grid.cols - 1,
        -1 => 1..grid.cols,
        _ => 0..grid.cols,
    }
}

impl<F, P> Contents<'_, F, P>
where
    F: NodeFloats,
    P: NodePins,
{
    /// Checks every invariant a surface relies on (see [`Surface::from_snapshot`]).
    pub fn validate(&self) -> Result<()> {
        let p = &self.scalars.params;
        p.validate_except_dt()
            .map_err(|e| bad(format!("parameters: {e}")))?;
        let grid = Grid::new(p.cols, p.rows);
        self.arrays(grid)?;
        self.derived()?;
        self.nodes(grid.node_count())?;
        self.springs(grid)?;
        let s = self.scalars;
        section::check_bodies(self.bodies, s.next_floater_id, s.buoyancy, p.spacing)?;
        section::check_column(self.column, grid.node_count())?;
        self.clock_and_window()?;
        self.timestep()
    }

    /// Every array holds one finite value per node.
    fn arrays(&self, grid: Grid) -> Result<()> {
        let n = grid.node_count();
        let named = ["x", "y", "z", "vx", "vy", "vz", "fx", "fy", "fz"]
            .into_iter()
            .zip(
                self.positions
                    .iter()
                    .chain(&self.velocities)
                    .chain(&self.forces),
            );
        for (what, &a) in named.chain([("mass", &self.mass), ("viscosity", &self.viscosity)]) {
            if a.len() != n {
                return Err(bad(format!(
                    "{what} has {} values for a {}x{} grid",
                    a.len(),
                    grid.cols,
                    grid.rows
                )));
            }
            if let Some((i, v)) = first_bad_value(a, |v| !v.is_finite()) {
                return Err(bad(format!(
                    "{what} of node {i} is {v}, not a finite number"
                )));
            }
        }
        if self.pinned.len() != n {
            return Err(bad(format!(
                "pinned has {} flags for {n} nodes",
                self.pinned.len()
            )));
        }
        for f in 0..4 {
            for (what, a) in [
                ("rest length", self.rest[f]),
                ("stiffness", self.stiffness[f]),
            ] {
                if a.len() != n {
                    return Err(bad(format!(
                        "{what} table {f} has {} values for {n} nodes",
                        a.len()
                    )));
                }
            }
        }
        Ok(())
    }

    /// The pending flag covers the forces; the counters and bounds are in range.
    fn derived(&self) -> Result<()> {
        let s = self.scalars;
        if !s.forces_pending
            && self
                .forces
                .iter()
                .any(|&f| first_bad_value(f, |v| v.to_bits() != 0).is_some())
        {
            return Err(bad(
                "external forces are stored but not marked pending (flag bit 0)",
            ));
        }
        if !(s.model_time.is_finite() && s.model_time >= 0.0) {
            return Err(bad(format!(
                "model time {} is not a finite number >= 0",
                s.model_time
            )));
        }
        let [min_mass, max_stiffness, max_viscosity] = s.bounds;
        let to_bad = |e: crate::Error| bad(e.to_string());
        params::positive("min_mass", min_mass).map_err(to_bad)?;
        params::positive("max_stiffness", max_stiffness).map_err(to_bad)?;
        params::non_negative("max_viscosity", max_viscosity).map_err(to_bad)
    }

    /// Each node's mass and viscosity are within the bounds; pinned nodes stand still.
    fn nodes(&self, n: usize) -> Result<()> {
        let [min_mass, _, max_viscosity] = self.scalars.bounds;
        let light = |m: f32| m < min_mass || !(1.0 / m).is_finite();
        if let Some((i, m)) = first_bad_value(self.mass, light) {
            return Err(bad(format!(
                "mass {m} of node {i} is below min_mass {min_mass} or too small to invert"
            )));
        }
        let out = |g: f32| !(0.0..=max_viscosity).contains(&g);
        if let Some((i, g)) = first_bad_value(self.viscosity, out) {
            return Err(bad(format!(
                "viscosity {g} of node {i} is negative or above max_viscosity {max_viscosity}"
            )));
        }
        debug_assert_eq!(self.pinned.len(), n);
        let mut pins = [0u8; BLOCK];
        let moving = blocks(self.velocities, |start, [vx, vy, vz]| {
            let pins = &mut pins[..vx.len()];
            self.pinned.read(start, pins);
            let moving = |i: usize| (vx[i] != 0.0) | (vy[i] != 0.0) | (vz[i] != 0.0);
            first_bad(pins.len(), |i| (pins[i] != 0) & moving(i)).map(|i| start + i)
        });
        match moving {
            Some(i) => Err(bad(format!("node {i} is pinned but has a velocity"))),
            None => Ok(()),
        }
    }

    /// Springs outside the grid are zero; the others positive, finite, within the bound.
    fn springs(&self, grid: Grid) -> Result<()> {
        let max_stiffness = self.scalars.bounds[1];
        for (f, family) in Family::ALL.into_iter().enumerate() {
            let (rest, coef) = (self.rest[f], self.stiffness[f]);
            for r in 0..grid.rows {
                let row = r * grid.cols;
                let inside = spring_columns(grid, family, r);
                let inside = row + inside.start..row + inside.end;
                let outside = if inside.is_empty() {
                    [row..row + grid.cols, 0..0]
                } else {
                    [row..inside.start, inside.end..row + grid.cols]
                };
                for range in outside {
                    let pair = [rest.part(range.clone()), coef.part(range.clone())];
                    let stored = blocks(pair, |start, [l, c]| {
                        first_bad(l.len(), |i| (l[i].to_bits() | c[i].to_bits()) != 0)
                            .map(|i| start + i)
                    });
                    if let Some(k) = stored {
                        return Err(bad(format!(
                            "spring {family:?} at node {} lies outside the grid but is not zero",
                            range.start + k
                        )));
                    }
                }
                let pair = [rest.part(inside.clone()), coef.part(inside.clone())];
                let wrong = blocks(pair, |start, [l, c]| {
                    let valid = |i: usize| {
                        l[i].is_finite() & (l[i] >= 0.0) & c[i].is_finite() & (c[i] > 0.0)
                    };
                    first_bad(l.len(), |i| !valid(i) | (c[i] > max_stiffness))
                        .map(|i| (start + i, l[i], c[i], valid(i)))
                });
                if let Some((k, l, c, valid)) = wrong {
                    let i = inside.start + k;
                    return Err(if valid {
                        bad(format!(
                            "spring {family:?} at node {i}: stiffness {c} is above max_stiffness {max_stiffness}"
                        ))
                    } else {
                        bad(format!(
                            "spring {family:?} at node {i}: rest length {l} and stiffness {c} must be finite, >= 0 and > 0"
                        ))
                    });
                }
            }
        }
        Ok(())
    }

    /// The step cap, the owed and dropped time and the window's origin are in range.
    fn clock_and_window(&self) -> Result<()> {
        let s = self.scalars;
        let (max_steps, _) = s.step_cap;
        if max_steps == 0 || max_steps as usize > Surface::MAX_SUBSTEPS {
            return Err(bad(format!(
                "step cap {max_steps} is not from 1 to {}",
                Surface::MAX_SUBSTEPS
            )));
        }
        let dt = s.params.dt as f64;
        if !(s.owed_time.is_finite() && s.owed_time >= -dt) {
            return Err(bad(format!(
                "owed time {} is not finite and at least −dt",
                s.owed_time
            )));
        }
        if !(s.dropped_seconds.is_finite() && s.dropped_seconds >= 0.0) {
            return Err(bad(format!(
                "dropped seconds {} are not finite and at least 0",
                s.dropped_seconds
            )));
        }
        if let Some(&o) = s
            .origin_cells
            .iter()
            .find(|o| o.unsigned_abs() > MAX_ORIGIN_CELLS as u64)
        {
            return Err(bad(format!(
                "window origin {o} cells is past the limit of {MAX_ORIGIN_CELLS} cells"
            )));
        }
        Ok(())
    }

    /// `dt` is below the critical timestep of the bounds (and of the bodies' waterlines).
    fn timestep(&self) -> Result<()> {
        let s = self.scalars;
        let p = &s.params;
        let floating = !self.bodies.is_empty();
        let extra = if floating {
            s.buoyancy.node_stiffness(p.spacing, p.time_scale)
        } else {
            0.0
        };
        Stability::from_bounds(s.bounds)
            .admit(p.dt, extra)
            .map_err(|e| bad(e.to_string()))
    }
}
