//! Restoring a snapshot of the current version into a surface of the same shape, in
//! place: the bytes are checked where they lie (framing, checksum, every invariant of
//! `validate.rs`), then copied into the surface's buffers. Only what differs from the
//! surface's current state is written beyond the positions, velocities and forces, so a
//! rollback between states with the same tables copies three arrays and a few fields.
//!
//! The bodies are decoded into a list the bodies' subsystem keeps for restores (whose
//! capacity a rollback reuses), borrowing their hull meshes where the stored mesh has the
//! bits of one the surface holds; each gets the mesh the water presses on (the current
//! body's at its place when the shape is the same, so a rollback makes none); they replace
//! the old bodies once everything is checked, and are dropped if anything is refused.

use super::read::{self, Layout, Le};
use super::validate::{blocks, first_bad, spring_columns, Contents, NodeFloats, NodePins, BLOCK};
use super::{Scalars, VERSION};
use crate::error::Result;
use crate::floater::{Floater, FloaterId};
use crate::grid::Family;
use crate::params::Params;
use crate::springs::Springs;
use crate::state::NodeTable;
use crate::surface::bodies::Entry;
use crate::surface::Surface;

impl Surface {
    /// Restores `bytes` in place and returns true, or returns false (with nothing
    /// changed) when they are of another version or for another size or model. Errors
    /// when the bytes are refused; then nothing changed either.
    pub(super) fn restore_in_place(&mut self, bytes: &[u8]) -> Result<bool> {
        let (version, mut r) = read::framing(bytes)?;
        if version != VERSION {
            return Ok(false);
        }
        let saved = Layout::read(&mut r, version)?;
        let scalars = saved.scalars()?;
        let nodes = &saved.nodes;
        let (current, bodies, column) = self.bodies.restoring();
        let checked = saved.bodies.decode_into(bodies, current);
        saved.column.decode_into(column);
        let checked = checked.and_then(|()| Self::check(&saved, &scalars, bodies, column));
        let same = same_model(&self.params, &scalars.params);
        let checked = checked.and_then(|()| match same {
            true => self.bodies.mesh_restored(scalars.params.spacing),
            false => Ok(()),
        });
        if checked.is_err() || !same {
            self.bodies.finish_restore(false);
            return checked.map(|()| false);
        }
        // Checked: from here on nothing can fail.
        let n = self.node_count();
        let state = &mut self.lattice.state;
        for (dst, src) in state.pos.iter_mut().zip(nodes.positions) {
            src.read(0, &mut dst[..n]);
        }
        for (dst, src) in state.vel.iter_mut().zip(nodes.velocities) {
            src.read(0, &mut dst[..n]);
        }
        state.ext.load(scalars.forces_pending, |ext| {
            for (dst, src) in ext.iter_mut().zip(nodes.forces) {
                src.read(0, &mut dst[..n]);
            }
        });
        let mass_changed = assign(&mut state.mass, nodes.mass);
        assign(&mut state.viscosity, nodes.viscosity);
        let pins_changed = !same_pins(&state.pinned, nodes.pinned);
        if pins_changed {
            for (p, &b) in state.pinned.iter_mut().zip(nodes.pinned) {
                *p = b == 1;
            }
        }
        if mass_changed || pins_changed {
            state.refresh_inv_mass();
        }
        if !self.springs_equal(&saved) {
            let grid = self.grid();
            let (rest, coef) = (nodes.rest.map(Le::to_vec), nodes.stiffness.map(Le::to_vec));
            self.lattice.springs = Springs::from_tables(
                grid,
                std::array::from_fn(|f| rest[f].as_slice()),
                std::array::from_fn(|f| coef[f].as_slice()),
            );
        }
        self.bodies.finish_restore(true);
        self.take_scalars(&scalars);
        Ok(true)
    }

    /// Validates a saved state whose bodies are decoded (see [`Contents::validate`]).
    fn check(
        saved: &Layout<'_>,
        scalars: &Scalars,
        bodies: &[(FloaterId, Floater)],
        column: &[Entry],
    ) -> Result<()> {
        let nodes = &saved.nodes;
        Contents {
            scalars,
            positions: nodes.positions,
            velocities: nodes.velocities,
            forces: nodes.forces,
            mass: nodes.mass,
            viscosity: nodes.viscosity,
            pinned: nodes.pinned,
            rest: nodes.rest,
            stiffness: nodes.stiffness,
            bodies,
            column,
        }
        .validate()
    }

    /// Whether every spring of `saved` has the bits of this surface's.
    fn springs_equal(&self, saved: &Layout<'_>) -> bool {
        let grid = self.grid();
        let tables = self.lattice.springs.tables();
        Family::ALL.into_iter().all(|family| {
            let f = family as usize;
            (0..grid.rows).all(|r| {
                let inside = spring_columns(grid, family, r);
                let row = r * grid.cols;
                let nodes = row + inside.start..row + inside.end;
                let (rest, coef) = (saved.nodes.rest[f], saved.nodes.stiffness[f]);
                let (rest, coef) = (rest.part(nodes.clone()), coef.part(nodes.clone()));
                match tables {
                    Some(t) => {
                        same_bits(rest, &t.rest[f][nodes.clone()])
                            && same_bits(coef, &t.coef[f][nodes])
                    }
                    None if nodes.is_empty() => true,
                    None => {
                        let (c, l) = self.lattice.springs.get(family, nodes.start);
                        all_bits(rest, l) && all_bits(coef, c)
                    }
                }
            })
        })
    }
}

/// Whether two surfaces' buffers and default tables are alike: the same grid and the same
/// model but for the acceleration (which is a field of the state, set any time).
fn same_model(a: &Params, b: &Params) -> bool {
    let bits = |p: &Params| (super::model(p).map(f32::to_bits), p.time_scale.to_bits());
    (a.cols, a.rows, a.boundary) == (b.cols, b.rows, b.boundary) && bits(a) == bits(b)
}

/// Whether `a` holds the bits of `b`.
fn same_bits(a: Le<'_>, b: &[f32]) -> bool {
    a.len() == b.len()
        && blocks([a], |start, [a]| {
            let b = &b[start..start + a.len()];
            first_bad(a.len(), |i| a[i].to_bits() != b[i].to_bits())
        })
        .is_none()
}

/// Whether every value of `a` has the bits of `value`.
fn all_bits(a: Le<'_>, value: f32) -> bool {
    blocks([a], |_, [a]| {
        first_bad(a.len(), |i| a[i].to_bits() != value.to_bits())
    })
    .is_none()
}

fn same_pins(pinned: &[bool], stored: &[u8]) -> bool {
    let mut mine = [0u8; BLOCK];
    pinned.len() == stored.len()
        && stored.chunks(BLOCK).enumerate().all(|(k, theirs)| {
            let mine = &mut mine[..theirs.len()];
            pinned.read(k * BLOCK, mine);
            mine == theirs
        })
}

/// Gives `table` the values of `src` unless it has them already (bit for bit); returns
/// whether it changed.
fn assign(table: &mut NodeTable, src: Le<'_>) -> bool {
    let cols = table.cols();
    let rows = src.len() / cols;
    let equal =
        (0..rows).all(|r| same_bits(src.part(r * cols..(r + 1) * cols), &table.row(r)[..cols]));
    if !equal {
        // (A change of per-node values: rare in a rollback, and it may allocate anyway.)
        let mut values = vec![0.0; src.len()];
        src.read(0, &mut values);
        table.assign(|i| values[i]);
    }
    !equal
}
