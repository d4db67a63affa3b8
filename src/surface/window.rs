//! The moving window: the grid travels through the world by whole cells
//! ([`Surface::shift`], [`Surface::follow`]) while the water in it stays where it is.
//!
//! # Frames
//!
//! A surface speaks one frame, the **water frame**: positions ([`Surface::positions`],
//! [`Surface::mesh_view`] and every buffer written from it), [`Surface::height_at`],
//! [`Surface::add_force_at`], [`Surface::drop_at`] and the floaters all use it. It is the
//! frame the surface was created in, and it does not move when the window does (only a
//! [`Surface::rebase`] moves it): node `(col, row)` rests at
//! `(origin.x + col·h, 0, origin.z + row·h)`, where [`Surface::origin`] is `h` times the
//! whole cells the window has travelled in this frame ([`Surface::origin_cells`]). A host
//! that places the water at the world's origin (no transform) reads world positions
//! directly; one that places it elsewhere adds that one fixed translation, which never
//! changes as the window moves.
//!
//! The view carries the origin ([`MeshView::origin`](crate::MeshView::origin)): the LOD
//! takes the eye in the water frame and measures it against the patches' rest footprints
//! at the window's place. Refraction's bottom coordinates are the hit point in the water
//! frame over the footprint's size, so a bottom texture that wraps stays put in the world
//! as the window moves.
//!
//! A shift therefore leaves the stored positions of the overlap untouched, bit for bit:
//! what moves is which array slot a node lives in, not its coordinates. That is what makes
//! a shifted run the same computation as an unshifted one on the overlap (the spring
//! forces see the same differences of the same numbers), and a shift followed by the
//! opposite shift the same as none.
//!
//! # Precision far from the origin: a floating origin
//!
//! Heights (`y`) keep full `f32` precision anywhere, since they stay near 0. Horizontal
//! coordinates have the resolution of `f32` at their magnitude: about `|x|·6·10⁻⁸`, so
//! 0.008 units at 10⁵ units from the water frame's origin, where a node's horizontal
//! sway (a few hundredths of a cell with the seed's parameters) is resolved only coarsely
//! and the spring forces, which see differences of those coordinates, lose digits with it.
//! Windows within about 10⁴ cells of the frame's origin are unaffected in practice.
//!
//! An open world larger than that keeps a floating origin, as engines do for every other
//! object: when the camera has gone far, the host moves its world's origin near the camera
//! and every object's coordinates by the same offset. The water takes part with
//! [`Surface::rebase`]: it moves the water frame by whole cells (the host rounds its offset
//! to cells and leaves the remainder in the water's transform), re-expressing every node,
//! floater and query in the new frame, so the mesh's coordinates are small again and keep
//! their full resolution. A rebase changes no height or velocity. Positions change by at
//! most the rounding of their old magnitude, and a node at rest lands exactly on its new
//! rest place, so a calm window rebased to the origin after travelling steps bit for bit as
//! a fresh one near the origin would (`tests/window.rs`; without the rebase the same run
//! drifts). Water that moves when it is rebased keeps its displacements exactly and goes
//! on with the finer rounding of the new frame, so it is close to, not bit for bit, what
//! a run that never went far would give.
//! Shifts never round anything: the window may travel up to [`MAX_ORIGIN_CELLS`] cells
//! from the frame's origin, the range in which every cell index is an exact `f32`. Things
//! the host holds in the water frame (a [`Wake`](crate::disturb::Wake)'s path, with
//! [`Wake::translate`](crate::disturb::Wake::translate); a point it follows; its camera for
//! the LOD and refraction) are the host's to move by the same offset.
//!
//! # What moves and what stays
//!
//! - The water moves with the world: positions, velocities, pending external forces, and
//!   per-node or per-spring values a caller set (mass, viscosity, pinned flags, spring
//!   rest lengths and coefficients) keep their world place.
//! - The boundary stays with the window: the pinned outer ring of a pinned or absorbing
//!   boundary and the absorbing frame's damping profile are properties of a node's place
//!   in the window. A node whose value is its place's default (for example the frame's
//!   viscosity `d` cells from the edge) takes the default of its new place; a value the
//!   caller set travels. (A value set equal to the default of its place is a default.)
//!   A node that the boundary newly pins is put at rest.
//! - The strip that comes in is calm: rest positions, zero velocity, no force, default
//!   parameters; or, through [`Surface::shift_with`], heights and vertical velocities from
//!   the host's far field ([`FarField`]), for example a swell or a wake that was there.
//! - Floating bodies keep their positions and velocities (they live in the water frame).
//!   A body that the window leaves behind floats on calm water (height 0, no flow, no
//!   push back) until the window comes back: follow the body ([`Surface::follow`]) to keep
//!   it in the simulated water.
//!
//! # Moving rows, not a ring buffer
//!
//! A shift copies the overlap into place on every per-node array that holds more than its
//! positional default (positions and velocities; forces only while some are pending;
//! mass, viscosity, pins and spring tables only when a caller made them non-uniform: mass
//! and viscosity tables that hold only their defaults keep them as rows by place, which
//! stay where they are), one `copy_within` per row (one for all rows when only rows
//! move), then fills the incoming strip. The arrays move as tasks on the host's threads.
//!
//! Three ways were weighed, by what they cost per node and what they cost everything else:
//!
//! - **Moving rows** (this): 24 bytes read and 24 written per node, the same as the
//!   step's own floor (it reads and writes positions and velocities), so a shift costs a
//!   fraction of a step and nothing at all between shifts. Measured with
//!   `benches/window.rs` (AMD EPYC Zen 5, 2 threads, `docs/performance.md`): a shift of 1,
//!   8 or 64 cells along both axes takes 0.38–0.68 of one step at 512² (once 0.94 in
//!   five runs) and 0.41–0.55 at 1024², 1.8–2× six plain `copy_within`s of the same
//!   arrays (`floor`) where the arrays leave the cache.
//! - **A ring buffer** (wrap-around addressing, as clipmaps do) makes the shift free, but
//!   the engine streams whole rows through SIMD lanes with neighbours one lane over: a
//!   seam inside a row would cut every row the window crosses, and every kernel, query,
//!   mesh view and vertex buffer would pay for the indirection on every step and frame,
//!   which the zero-copy `MeshView` (row-major slices) cannot express.
//! - **Folding the shift into the next step's reads** (the step writes a second buffer
//!   anyway) would save the copy without a seam, but the nodes next to the incoming strip
//!   need the strip's values as neighbours before the step, and the strip has no slots of
//!   its own in the front buffer: every kernel would need a second source for its edge
//!   lanes. For a cost of about half a step, paid once per shift (a window following a
//!   ship at 10 cells per second shifts a few times a second), that complexity is not
//!   worth it.

use super::Surface;
use crate::error::{Error, Result};
use crate::grid::{Family, Grid};
use crate::jobs::Runner;
use crate::params;
use crate::simd::Floats;
use crate::state::NodeTable;
use std::sync::atomic::{AtomicBool, Ordering};
use std::sync::Mutex;

/// The farthest the window may travel from the water frame's origin, in cells along each
/// axis (2²⁴ − 2²⁰): every cell index up to 2²⁴ is an exact `f32`, so every rest position
/// is the same number however the window got there, with room for a window of 2²⁰ cells.
pub const MAX_ORIGIN_CELLS: i64 = (1 << 24) - (1 << 20);

/// Fills the strip of water a shift brings into the window.
///
/// An open-world game keeps a cheaper model of the water far from the camera (a swell, a
/// sum of Gerstner waves, a coarse grid, or nothing): the window asks it for the state of
/// each node as that node enters. Heights are in the water frame's units, added to the
/// rest height 0; velocities in world units per second (as [`Surface::velocity_at`]
/// answers them). Every value must be finite, or the
/// shift is refused and nothing changes. Nodes the boundary pins stay at rest.
///
/// A closure `FnMut(x, z) -> height` is a far field with zero vertical velocity.
pub trait FarField {
    /// Height of the water at `(x, z)` (water frame).
    fn height(&mut self, x: f32, z: f32) -> f32;

    /// Vertical velocity of the water at `(x, z)`, world units per second; 0 unless
    /// overridden.
    fn vertical_velocity(&mut self, _x: f32, _z: f32) -> f32 {
        0.0
    }
}

impl<F: FnMut(f32, f32) -> f32> FarField for F {
    fn height(&mut self, x: f32, z: f32) -> f32 {
        self(x, z)
    }
}

/// Calm water: every incoming node at rest.
struct Calm;

impl FarField for Calm {
    fn height(&mut self, _x: f32, _z: f32) -> f32 {
        0.0
    }
}

/// Where a shift moves things: node `(col, row)` of the new window is node
/// `(col + dc, row + dr)` of the old one.
#[derive(Debug, Clone, Copy)]
struct Move {
    grid: Grid,
    dc: isize,
    dr: isize,
}

impl Move {
    /// The old index of new node `i`, if that node was in the old window.
    fn source(&self, i: usize) -> Option<usize> {
        let (c, r) = self.grid.coords(i);
        let c = c.checked_add_signed(self.dc)?;
        let r = r.checked_add_signed(self.dr)?;
        (c < self.grid.cols && r < self.grid.rows).then(|| self.grid.index(c, r))
    }

    /// The new index of old node `i`, if it stays in the window.
    fn destination(&self, i: usize) -> Option<usize> {
        Move {
            dc: -self.dc,
            dr: -self.dr,
            ..*self
        }
        .source(i)
    }

    /// The columns of a row that come from the old window.
    fn kept_cols(&self) -> std::ops::Range<usize> {
        let cols = self.grid.cols as isize;
        let lo = (-self.dc).clamp(0, cols);
        let hi = (cols - self.dc).clamp(0, cols);
        lo as usize..hi.max(lo) as usize
    }

    /// Moves the overlap of `buf` (row-major, at least `grid.node_count()` long) to its new
    /// place; the incoming nodes keep whatever they held (the caller fills them).
    fn apply<T: Copy + Default>(&self, buf: &mut [T]) {
        let (cols, rows) = (self.grid.cols, self.grid.rows);
        let kept = self.kept_cols();
        if kept.is_empty() {
            return;
        }
        // Destination `d` reads source `d + delta`: walking the rows away from the
        // side the data comes from never reads a row already overwritten.
        let delta = self.dr * cols as isize + self.dc;
        if self.dc == 0 {
            // Whole rows: one move of the kept rows.
            let kept_rows = rows - self.dr.unsigned_abs().min(rows);
            if kept_rows == 0 {
                return;
            }
            let (src, dst) = if self.dr > 0 {
                (self.dr as usize * cols, 0)
            } else {
                (0, self.dr.unsigned_abs() * cols)
            };
            buf.copy_within(src..src + kept_rows * cols, dst);
            return;
        }
        // One `copy_within` per row. (Sending rows through a small buffer in L1, against
        // the 4K aliasing of a source and destination a multiple of 4 KiB plus a few bytes
        // apart, cost 1.5 times as much on Zen 5 and gained nothing: docs/performance.md.)
        let copy_row = |r: usize| {
            if let Some(src_row) = r.checked_add_signed(self.dr).filter(|&s| s < rows) {
                let src = src_row * cols + kept.start.wrapping_add_signed(self.dc);
                buf.copy_within(src..src + kept.len(), r * cols + kept.start);
            }
        };
        if delta > 0 {
            (0..rows).for_each(copy_row);
        } else {
            (0..rows).rev().for_each(copy_row);
        }
    }

    /// Calls `f(row, cols)` on every run of columns of a row that was not in the old
    /// window, rows in order.
    fn for_incoming_runs(&self, mut f: impl FnMut(usize, std::ops::Range<usize>)) {
        let (cols, rows) = (self.grid.cols, self.grid.rows);
        let kept = self.kept_cols();
        for r in 0..rows {
            if r.checked_add_signed(self.dr).is_some_and(|s| s < rows) && !kept.is_empty() {
                for run in [0..kept.start, kept.end..cols] {
                    if !run.is_empty() {
                        f(r, run);
                    }
                }
            } else {
                f(r, 0..cols);
            }
        }
    }

    /// Calls `f(index, col, row)` on every node of the new window that was not in the old
    /// one, in row-major order.
    fn for_incoming(&self, mut f: impl FnMut(usize, usize, usize)) {
        let (cols, rows) = (self.grid.cols, self.grid.rows);
        let kept = self.kept_cols();
        for r in 0..rows {
            let row = r * cols;
            if r.checked_add_signed(self.dr).is_some_and(|s| s < rows) && !kept.is_empty() {
                (0..kept.start)
                    .chain(kept.end..cols)
                    .for_each(|c| f(row + c, c, r));
            } else {
                (0..cols).for_each(|c| f(row + c, c, r));
            }
        }
    }
}

/// The water-frame coordinate of the rest place of column (or row) `index` of a window
/// whose node 0 is `origin` cells from the frame's origin. Every rest place is this one
/// expression, so a node at rest sits exactly on it wherever the window has been.
pub(crate) fn rest_coordinate(index: usize, origin: i64, h: f32) -> f32 {
    (index as i64 + origin) as f32 * h
}

/// An origin, one axis at a time (`None`: it overflowed), checked to be within
/// [`MAX_ORIGIN_CELLS`] of the frame's origin; `name` and `moved` describe the request.
fn origin_in_range(
    origin: Option<i64>,
    name: &'static str,
    moved: i64,
    expected: &'static str,
) -> Result<i64> {
    origin
        .filter(|v| v.abs() <= MAX_ORIGIN_CELLS)
        .ok_or(Error::InvalidParam {
            name,
            value: moved as f64,
            expected,
        })
}

/// Checks a shift and returns the origin it leads to.
fn shifted_origin(origin: [i64; 2], dcols: i32, drows: i32) -> Result<[i64; 2]> {
    let expected = "a shift that keeps the window within 15,728,640 cells (2^24 - 2^20) of \
                    the water frame's origin, where every cell index is an exact f32";
    Ok([
        origin_in_range(
            origin[0].checked_add(dcols as i64),
            "shift columns",
            dcols as i64,
            expected,
        )?,
        origin_in_range(
            origin[1].checked_add(drows as i64),
            "shift rows",
            drows as i64,
            expected,
        )?,
    ])
}

/// Where a surface's window is: the whole cells it has travelled, and whether a shift must
/// move per-node values with their water.
#[derive(Debug, Clone, Copy, Default)]
pub(crate) struct Placement {
    /// Whole cells the window has travelled, `[cols, rows]`.
    pub origin: [i64; 2],
    /// Whether a per-node mass, viscosity or pin may differ from its place's default (a
    /// shift then moves them; a window that never had any moves none).
    custom: bool,
}

impl Placement {
    /// A per-node mass, viscosity or pin was set: shifts move them from now on.
    pub fn customised(&mut self) {
        self.custom = true;
    }

    /// A snapshot's origin, whose per-node values may be anything.
    pub fn load(&mut self, origin: [i64; 2]) {
        self.origin = origin;
        self.custom = true;
    }
}

impl Surface {
    /// The water-frame position `(x, z)` of node `(0, 0)`'s rest place: `h` times
    /// [`Surface::origin_cells`]. `[0.0, 0.0]` until the window moves. Node `(col, row)`
    /// rests at `origin + (col·h, row·h)`; see [the module docs](crate::window) for the frame.
    pub fn origin(&self) -> [f32; 2] {
        let h = self.params.spacing;
        self.window.origin.map(|c| c as f32 * h)
    }

    /// Whole cells the window has travelled since the surface was made, `[cols, rows]`:
    /// the sum of every shift.
    pub fn origin_cells(&self) -> [i64; 2] {
        self.window.origin
    }

    /// Moves the window `dcols` cells along +x and `drows` along +z (negative values go
    /// the other way): node `(col, row)` afterwards is the water that was at node
    /// `(col + dcols, row + drows)`, bit for bit, and the strip that comes in is calm.
    /// See [the module docs](crate::window) for what travels with the water and what stays with the
    /// window. A shift larger than the grid replaces all of the water.
    ///
    /// Refused, with nothing changed, if the window would leave [`MAX_ORIGIN_CELLS`].
    ///
    /// ```
    /// use springwater::{Params, Surface};
    ///
    /// let mut water = Surface::new(Params::with_size(64, 64))?;
    /// water.drop_at(40.0, 32.0, 1.0, 3.0)?;
    /// let before = water.height_at(40.0, 32.0)?;
    /// water.shift(8, 0)?;                        // the window moves 8 cells along +x
    /// assert_eq!(water.origin(), [8.0, 0.0]);
    /// assert_eq!(water.height_at(40.0, 32.0)?, before); // the water stayed in place
    /// # Ok::<(), springwater::Error>(())
    /// ```
    pub fn shift(&mut self, dcols: i32, drows: i32) -> Result<()> {
        self.shift_filled(dcols, drows, None::<&mut Calm>)
    }

    /// Like [`Surface::shift`], but the incoming strip's free nodes take their height and
    /// vertical velocity from `far_field`, asked once per incoming node at its rest place
    /// in the water frame (rows in order, columns in order within a row). Values that are
    /// not finite refuse the shift, with nothing changed.
    ///
    /// ```
    /// use springwater::{Params, Surface};
    ///
    /// let mut water = Surface::new(Params::with_size(32, 32))?;
    /// // A long swell along x: the water that enters already carries it.
    /// water.shift_with(4, 0, |x: f32, _z: f32| 0.1 * (x * 0.2).sin())?;
    /// let i = water.grid().index(30, 10);      // an incoming node (the edge stays pinned)
    /// assert_eq!(water.positions()[0][i], 34.0);
    /// assert_eq!(water.positions()[1][i], 0.1 * (34.0f32 * 0.2).sin());
    /// # Ok::<(), springwater::Error>(())
    /// ```
    pub fn shift_with<F: FarField>(
        &mut self,
        dcols: i32,
        drows: i32,
        mut far_field: F,
    ) -> Result<()> {
        self.shift_filled(dcols, drows, Some(&mut far_field))
    }

    /// [`Surface::shift_with`], with `None` for calm water (no far field asked).
    fn shift_filled<F: FarField>(
        &mut self,
        dcols: i32,
        drows: i32,
        mut far_field: Option<&mut F>,
    ) -> Result<()> {
        let origin = shifted_origin(self.window.origin, dcols, drows)?;
        if dcols == 0 && drows == 0 {
            return Ok(());
        }
        let grid = self.grid();
        let (h, time_scale) = (self.params.spacing, self.params.time_scale);
        let mv = Move {
            grid,
            dc: dcols as isize,
            dr: drows as isize,
        };
        let pins_border = self.params.boundary.pins_border();
        let rest = |c: usize, r: usize| {
            (
                rest_coordinate(c, origin[0], h),
                rest_coordinate(r, origin[1], h),
            )
        };
        // Ask the far field first: a value it refuses leaves the surface unchanged.
        let mut incoming = Vec::new();
        let mut bad = None;
        let border = |c, r| c == 0 || r == 0 || c == grid.cols - 1 || r == grid.rows - 1;
        mv.for_incoming(|i, c, r| {
            let Some(far_field) = far_field.as_mut() else {
                return;
            };
            if pins_border && border(c, r) {
                return;
            }
            let (x, z) = rest(c, r);
            let (y, vy) = (far_field.height(x, z), far_field.vertical_velocity(x, z));
            // Per second in, per unit of model time in the lattice.
            let vy = vy / time_scale;
            if !(y.is_finite() && vy.is_finite()) && bad.is_none() {
                bad = Some(if y.is_finite() { vy } else { y });
            }
            incoming.push((i, y + 0.0, vy + 0.0));
        });
        if let Some(value) = bad {
            return Err(Error::InvalidParam {
                name: "far-field height or velocity",
                value: value as f64,
                expected: "finite values at every incoming node",
            });
        }

        // Per-node parameters: a default stays with its place, a set value travels.
        let defaults = Defaults::of(self);
        // Which nodes were pinned before: the outer ring, unless a caller set pins (then a
        // copy, since moving the parameters rewrites them).
        let was_pinned = self
            .window
            .custom
            .then(|| self.lattice.state.pinned.clone());
        let params_moved = self.window.custom && self.move_parameters(mv, &defaults);
        self.window.custom = params_moved;

        for family in Family::ALL {
            let default = defaults.spring(family);
            self.lattice
                .springs
                .shift_family(family, grid, |i| mv.source(i), default);
        }

        // The water itself.
        let runner = Runner::of(self.host.as_ref());
        let state = &mut self.lattice.state;
        let (pos, vel) = (&mut state.pos, &mut state.vel);
        move_arrays(runner, mv, pos.iter_mut().chain(vel.iter_mut()));
        mv.for_incoming_runs(|r, cs| {
            let run = r * grid.cols + cs.start..r * grid.cols + cs.end;
            state.pos[1][run.clone()].fill(0.0);
            for v in &mut state.vel {
                v[run.clone()].fill(0.0);
            }
            let z = rest(0, r).1;
            state.pos[2][run.clone()].fill(z);
            for (x, c) in state.pos[0][run].iter_mut().zip(cs) {
                *x = rest(c, r).0;
            }
        });
        for (i, y, vy) in incoming {
            state.pos[1][i] = y;
            state.vel[1][i] = vy;
        }
        state.ext.shift(
            |ext| {
                move_arrays(runner, mv, ext.iter_mut());
                mv.for_incoming_runs(|r, cs| {
                    for e in ext.iter_mut() {
                        e[r * grid.cols + cs.start..r * grid.cols + cs.end].fill(0.0);
                    }
                });
            },
            |i| mv.destination(i),
        );

        // The load the water column carries moves with its water.
        self.bodies.shift(|i| mv.destination(i));

        // Nodes the boundary now pins that were free (or new): at rest, like the ring of a
        // new surface.
        let pinned_now: Vec<usize> = if params_moved {
            (0..grid.node_count())
                .filter(|&i| state.pinned[i])
                .collect()
        } else if pins_border {
            // The outer ring only.
            let (cols, rows) = (grid.cols, grid.rows);
            let sides = (0..rows).flat_map(|r| [r * cols, r * cols + cols - 1]);
            let ends = (1..cols - 1).flat_map(|c| [c, (rows - 1) * cols + c]);
            sides.chain(ends).collect()
        } else {
            Vec::new()
        };
        for i in pinned_now {
            let was = mv.source(i).is_some_and(|s| match &was_pinned {
                Some(pinned) => pinned[s],
                None => pins_border && grid.is_border(s),
            });
            if !was {
                let (c, r) = grid.coords(i);
                let (x, z) = rest(c, r);
                state.pos[0][i] = x;
                state.pos[1][i] = 0.0;
                state.pos[2][i] = z;
            }
            for v in &mut state.vel {
                v[i] = 0.0;
            }
        }
        self.window.origin = origin;
        Ok(())
    }

    /// Moves mass, viscosity and pins where a caller set values; returns whether any node
    /// holds a value other than its place's default.
    fn move_parameters(&mut self, mv: Move, defaults: &Defaults) -> bool {
        let n = mv.grid.node_count();
        let state = &mut self.lattice.state;
        let mass_moved = move_table(&mut state.mass, mv);
        let visc_moved = move_table(&mut state.viscosity, mv);
        let pins_moved = move_param(
            &mut state.pinned[..n],
            mv,
            |i| defaults.pins_border && mv.grid.is_border(i),
            |a, b| a == b,
        );
        if mass_moved || pins_moved {
            state.refresh_inv_mass();
        }
        mass_moved || pins_moved || visc_moved
    }

    /// Shifts the window so that the world point `(x, z)` (water frame) is back near its
    /// middle once it has left a dead zone around the middle, and returns the shift made
    /// (`[0, 0]` while the point is inside the dead zone, so a camera that jitters does
    /// not move the water every frame).
    ///
    /// The dead zone is a square of [`Surface::follow_dead_zone`] cells either side of the
    /// window's centre; when the point leaves it along an axis, that axis shifts by the
    /// whole cells that put the point within half a cell of the centre. Refused, with
    /// nothing changed, for a point that is not finite or that would take the window past
    /// [`MAX_ORIGIN_CELLS`].
    ///
    /// ```
    /// use springwater::{Params, Surface};
    ///
    /// let mut water = Surface::new(Params::with_size(65, 65))?; // centre at (32, 32)
    /// assert_eq!(water.follow(33.0, 31.0)?, [0, 0]);             // inside the dead zone
    /// assert_eq!(water.follow(52.0, 32.0)?, [20, 0]);            // re-centred on x = 52
    /// assert_eq!(water.origin(), [20.0, 0.0]);
    /// # Ok::<(), springwater::Error>(())
    /// ```
    pub fn follow(&mut self, x: f32, z: f32) -> Result<[i32; 2]> {
        params::finite("follow x", x)?;
        params::finite("follow z", z)?;
        let grid = self.grid();
        let h = self.params.spacing as f64;
        let dead = self.follow_dead_zone() as f64;
        let mut shift = [0i32; 2];
        for (k, (p, n, name)) in [(x, grid.cols, "follow x"), (z, grid.rows, "follow z")]
            .into_iter()
            .enumerate()
        {
            let centre = self.window.origin[k] as f64 + (n - 1) as f64 / 2.0;
            let off = p as f64 / h - centre;
            if off.abs() <= dead {
                continue;
            }
            let cells = off.round();
            if cells.abs() > MAX_ORIGIN_CELLS as f64 * 2.0 {
                return Err(Error::InvalidParam {
                    name,
                    value: p as f64,
                    expected: "a point within 15,728,640 cells of the water frame's origin",
                });
            }
            shift[k] = cells as i32;
        }
        shifted_origin(self.window.origin, shift[0], shift[1])?;
        self.shift(shift[0], shift[1])?;
        Ok(shift)
    }

    /// Moves the water frame itself `dcols` cells along +x and `drows` along +z, for a host
    /// with a floating origin: the water stays where it is in the world, but every
    /// coordinate the surface stores or hands out (node positions, floaters, queries, the
    /// mesh) is now measured from a point `(dcols·h, drows·h)` further along. Afterwards
    /// [`Surface::origin_cells`] is smaller by `[dcols, drows]`, heights and velocities are
    /// unchanged bit for bit, and the host moves the water's transform by the same
    /// `(dcols·h, 0, drows·h)` (plus, if its own rebase was not a whole number of cells, the
    /// remainder). See [the module docs](crate::window) for when and why.
    ///
    /// Each node is re-expressed as its rest place in the new frame plus its displacement
    /// from its old rest place (an exact difference), so a node at rest lands exactly on its
    /// new rest place, and a node near the new frame's origin gets the finer resolution of
    /// the smaller numbers. Refused, with nothing changed, if the window would end up past
    /// [`MAX_ORIGIN_CELLS`] from the new origin.
    ///
    /// ```
    /// use springwater::{Params, Surface};
    ///
    /// let mut water = Surface::new(Params::with_size(64, 64))?;
    /// water.shift(100_000, 0)?;                  // far out: x near 10^5
    /// water.drop_at(100_032.0, 32.0, 0.5, 3.0)?;
    /// let before = water.height_at(100_032.0, 32.0)?;
    /// water.rebase(100_000, 0)?;                 // the host's floating origin moved too
    /// assert_eq!(water.origin_cells(), [0, 0]);
    /// assert_eq!(water.height_at(32.0, 32.0)?, before);
    /// # Ok::<(), springwater::Error>(())
    /// ```
    pub fn rebase(&mut self, dcols: i64, drows: i64) -> Result<()> {
        let old = self.window.origin;
        let expected =
            "a rebase that leaves the window within 15,728,640 cells (2^24 - 2^20) of the new origin";
        let new = [
            origin_in_range(old[0].checked_sub(dcols), "rebase columns", dcols, expected)?,
            origin_in_range(old[1].checked_sub(drows), "rebase rows", drows, expected)?,
        ];
        if new == old {
            return Ok(());
        }
        let grid = self.grid();
        let h = self.params.spacing;
        // A calm node lands exactly on its new rest place ([`rest_coordinate`]).
        let rest = |c: usize, o: i64| rest_coordinate(c, o, h);
        let [x, _, z] = &mut self.lattice.state.pos;
        for r in 0..grid.rows {
            let (z_old, z_new) = (rest(r, old[1]), rest(r, new[1]));
            let row = r * grid.cols..(r + 1) * grid.cols;
            for (c, (x, z)) in x[row.clone()].iter_mut().zip(&mut z[row]).enumerate() {
                *x = rest(c, new[0]) + (*x - rest(c, old[0]));
                *z = z_new + (*z - z_old);
            }
        }
        let (dx, dz) = (dcols as f64 * h as f64, drows as f64 * h as f64);
        self.bodies.rebase(dx, dz);
        self.window.origin = new;
        Ok(())
    }

    /// Half the side of [`Surface::follow`]'s dead zone, in cells: an eighth of the
    /// window's shorter side, at least 1.
    pub fn follow_dead_zone(&self) -> usize {
        let g = self.grid();
        (g.cols.min(g.rows) / 8).max(1)
    }
}

/// Moves the overlap of every array in `arrays`, one task per array on the host's threads
/// (copies only: the same bits on any number of threads). Each array moves exactly once,
/// whatever the runner does with the tasks: a task claims its array first, and the calling
/// thread moves any array no task claimed.
fn move_arrays<'a>(runner: Runner<'_>, mv: Move, arrays: impl Iterator<Item = &'a mut Floats>) {
    let arrays: Vec<Mutex<&mut Floats>> = arrays.map(Mutex::new).collect();
    let claimed: Vec<AtomicBool> = arrays.iter().map(|_| AtomicBool::new(false)).collect();
    let task = |k: usize| {
        if k < arrays.len() && !claimed[k].swap(true, Ordering::AcqRel) {
            let mut a = arrays[k].lock().unwrap_or_else(|e| e.into_inner());
            mv.apply(&mut a[..]);
        }
    };
    runner.run(arrays.len(), &task);
    (0..arrays.len()).for_each(task);
}

/// Bitwise equality of two floats (a set `-0.0` or NaN pattern is a value like any other).
fn same_f32(a: f32, b: f32) -> bool {
    a.to_bits() == b.to_bits()
}

/// [`move_param`] for a table that keeps its defaults beside its values: a table without
/// per-node values holds its defaults, which stay with their places, so it needs no work.
/// A table whose set values all left the window drops its per-node array. Returns whether
/// any value changed (as `move_param` does).
fn move_table(table: &mut NodeTable, mv: Move) -> bool {
    let Some((values, default)) = table.nodes_and_defaults() else {
        return false;
    };
    let moved = move_param(values, mv, default, same_f32);
    table.compact();
    moved
}

/// Moves the nodes of `buf` that differ from their place's default with the water; every
/// other node takes its new place's default. Returns false (and changes nothing) when every
/// node holds its default, which is the common case: uniform parameters cost no copy.
fn move_param<T: Copy + Default>(
    buf: &mut [T],
    mv: Move,
    default: impl Fn(usize) -> T,
    same: impl Fn(T, T) -> bool,
) -> bool {
    if (0..buf.len()).all(|i| same(buf[i], default(i))) {
        return false;
    }
    let mut set: Vec<Option<T>> = (0..buf.len())
        .map(|i| (!same(buf[i], default(i))).then_some(buf[i]))
        .collect();
    mv.apply(&mut set);
    mv.for_incoming(|i, _, _| set[i] = None);
    for (i, v) in set.into_iter().enumerate() {
        buf[i] = v.unwrap_or_else(|| default(i));
    }
    true
}

/// The values a new surface gives each place of the window (mass and viscosity tables
/// keep their own, see [`NodeTable::default_at`]).
struct Defaults {
    pins_border: bool,
    /// `(rest, coef)` per family.
    springs: [(f32, f32); 4],
}

impl Defaults {
    fn of(surface: &Surface) -> Self {
        let p = &surface.params;
        Self {
            pins_border: p.boundary.pins_border(),
            springs: Family::ALL
                .map(|f| (p.rest_ratio * f.initial_length() * p.spacing, p.stiffness)),
        }
    }

    fn spring(&self, family: Family) -> (f32, f32) {
        self.springs[family as usize]
    }
}
