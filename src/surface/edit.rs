//! Editing the water between steps: drops, forces and impulses for the next step, pins,
//! per-node masses and viscosities, single springs. Every edit checks its input first and
//! changes nothing when it refuses; edits that could make `params().dt` unsafe (a lighter
//! node, a stiffer spring, more viscosity) are checked against the critical timestep.

use super::window::rest_coordinate;
use super::{Spring, Surface};
use crate::error::{same_length, Error, Result};
use crate::grid::SpringId;
use crate::params;
use crate::state::NodeValues;

impl Surface {
    /// Drops a disturbance: adds `height · exp(−d²/radius²)` to y of every free node, `d`
    /// the distance from the node's rest position `(col·h, row·h)` to the point `(x, z)`.
    ///
    /// Everything is in world units: `x`, `z` in the water's local space (any finite point,
    /// also outside the footprint), `height` and `radius` in the same length unit as
    /// `params().spacing`. Drops with `|height| ≤ radius` and a radius of at least one cell
    /// keep the lattice in the regime where `critical_dt` guarantees stability.
    /// On error nothing changes.
    pub fn drop_at(&mut self, x: f32, z: f32, height: f32, radius: f32) -> Result<()> {
        params::finite("drop x", x)?;
        params::finite("drop z", z)?;
        params::finite("drop height", height)?;
        params::positive("drop radius", radius)?;
        let grid = self.grid();
        let h = self.params.spacing;
        let [oc, or] = self.window.origin;
        let inv_r2 = 1.0 / (radius * radius);
        // `d2 * inv_r2` is 0 × ∞ = NaN at the centre when radius² underflows: the weight
        // there is 1 by definition.
        let lift = |y: &[f32], i: usize| {
            let (c, r) = grid.coords(i);
            // Rest place in the water frame.
            let (rx, rz) = (rest_coordinate(c, oc, h), rest_coordinate(r, or, h));
            let d2 = (rx - x).powi(2) + (rz - z).powi(2);
            let w = if d2 == 0.0 { 1.0 } else { (-d2 * inv_r2).exp() };
            y[i] + height * w
        };
        // Past `CUT` radii the weight `exp(−d²/r²)` is below e⁻¹²⁰, which is 0 in f32, so
        // only the nodes of the square around the centre need the exponential; the rest
        // get `y + height · 0`, which leaves y as it is except that it turns a −0 into +0
        // when `height ≥ 0` (kept, so the result is the formula's to the bit).
        const CUT: f32 = 10.954_452; // sqrt(120)
        let span = |centre: f32, n: usize, origin: i64| {
            let reach = CUT * radius / h;
            let centre = centre - origin as f32 * h;
            let lo = ((centre / h - reach).floor().max(0.0) as usize).min(n);
            let hi = ((centre / h + reach).ceil().clamp(0.0, n as f32) as usize + 1).min(n);
            lo..hi
        };
        let (cols, rows) = (span(x, grid.cols, oc), span(z, grid.rows, or));
        let near = |i: usize| {
            let (c, r) = grid.coords(i);
            cols.contains(&c) && rows.contains(&r)
        };
        let box_nodes = || {
            rows.clone()
                .flat_map(|r| cols.clone().map(move |c| r * grid.cols + c))
        };
        // Check first, then write: a drop that would overflow a height changes nothing
        // (outside the square the heights do not change, and the state is finite).
        let pinned = &self.lattice.state.pinned;
        if box_nodes().any(|i| !pinned[i] && !lift(&self.lattice.state.pos[1], i).is_finite()) {
            return Err(Error::InvalidParam {
                name: "drop height",
                value: height as f64,
                expected: "small enough that every node's height stays finite",
            });
        }
        for i in box_nodes() {
            if !self.lattice.state.pinned[i] {
                self.lattice.state.pos[1][i] = lift(&self.lattice.state.pos[1], i);
            }
        }
        if height >= 0.0 {
            let y = &mut self.lattice.state.pos[1];
            for i in 0..grid.node_count() {
                if y[i] == 0.0 && !pinned[i] && !near(i) {
                    y[i] += 0.0;
                }
            }
        }
        Ok(())
    }

    /// Adds `force` to node `node` for the next step only (buoyancy, a paddle, a wake), in
    /// the lattice's force units (mass units × world units per unit of model time², the
    /// units of its springs; a force in seconds' units divided by `time_scale²`, see
    /// `docs/units.md`).
    pub fn add_force(&mut self, node: usize, force: [f32; 3]) -> Result<()> {
        self.check_node(node)?;
        for f in force {
            params::finite("force", f)?;
        }
        self.lattice
            .state
            .ext
            .add([(node, force)])
            .or_else(|sum| params::finite("accumulated force", sum))
    }

    /// Discards the pending external forces (for example after a step refused them),
    /// the reactions of [`Surface::body_forces`] waiting for the next step among them.
    pub fn clear_forces(&mut self) {
        self.lattice.state.ext.clear();
        self.bodies.drop_pending();
    }

    /// Adds a velocity change `dv` to a free node now (an impulse divided by its mass), in
    /// world units per unit of model time like [`Surface::velocities`].
    pub fn add_velocity(&mut self, node: usize, dv: [f32; 3]) -> Result<()> {
        self.check_node(node)?;
        for v in dv {
            params::finite("velocity", v)?;
        }
        let sum: [f32; 3] = std::array::from_fn(|k| self.lattice.state.vel[k][node] + dv[k]);
        for v in sum {
            params::finite("resulting velocity", v)?;
        }
        if !self.lattice.state.pinned[node] {
            for (k, v) in sum.into_iter().enumerate() {
                self.lattice.state.vel[k][node] = v;
            }
        }
        Ok(())
    }

    /// Replaces the external force buffer for the next step with `[fx, fy, fz]`, one
    /// value per node, in the lattice's force units (as [`Surface::add_force`]). Every
    /// value must be finite; on error nothing changes.
    pub fn set_forces(&mut self, force: [&[f32]; 3]) -> Result<()> {
        let n = self.node_count();
        for c in force {
            same_length("force buffer", c.len(), n)?;
            if let Some(&bad) = c.iter().find(|v| !v.is_finite()) {
                return Err(Error::InvalidParam {
                    name: "force",
                    value: bad as f64,
                    expected: "finite values",
                });
            }
        }
        self.lattice.state.ext.set(force);
        Ok(())
    }

    /// Pending external forces `[fx, fy, fz]` for the next step, in the lattice's force
    /// units (as [`Surface::add_force`]).
    pub fn forces(&self) -> [&[f32]; 3] {
        let n = self.node_count();
        [
            &self.lattice.state.ext.buffers()[0][..n],
            &self.lattice.state.ext.buffers()[1][..n],
            &self.lattice.state.ext.buffers()[2][..n],
        ]
    }

    /// Sets the uniform acceleration applied to every free node (gravity, wind), in world
    /// units per second² ([`Params::acceleration`](crate::Params::acceleration)).
    pub fn set_acceleration(&mut self, accel: [f32; 3]) -> Result<()> {
        for a in accel {
            params::finite("acceleration", a)?;
        }
        self.params.acceleration = accel;
        Ok(())
    }

    /// Pins (`true`) or frees a node. Pinning zeroes its velocity.
    pub fn set_pinned(&mut self, node: usize, pinned: bool) -> Result<()> {
        self.check_node(node)?;
        self.lattice.state.pinned[node] = pinned;
        self.window.customised();
        if pinned {
            for v in &mut self.lattice.state.vel {
                v[node] = 0.0;
            }
        }
        let inv_mass = if pinned {
            0.0
        } else {
            1.0 / self.lattice.state.mass.get(node)
        };
        self.lattice.state.inv_mass.set(node, inv_mass);
        Ok(())
    }

    /// Whether a node is pinned.
    pub fn is_pinned(&self, node: usize) -> Result<bool> {
        self.check_node(node)?;
        Ok(self.lattice.state.pinned[node])
    }

    /// Sets a node's mass. Refused if it would put `params().dt` at or past the critical
    /// timestep (the bound uses the smallest mass ever set).
    pub fn set_mass(&mut self, node: usize, mass: f32) -> Result<()> {
        self.check_node(node)?;
        check_mass(mass)?;
        let stability = self.lattice.stability.with_mass(mass);
        self.admit_bounds(stability)?;
        self.lattice.stability = stability;
        self.lattice.state.mass.set(node, mass);
        self.window.customised();
        if !self.lattice.state.pinned[node] {
            self.lattice.state.inv_mass.set(node, 1.0 / mass);
        }
        Ok(())
    }

    /// Sets a node's viscosity `γ` (≥ 0). Refused if it would put `params().dt` at or past
    /// the critical timestep (explicit damping has a limit too; the bound uses the largest
    /// viscosity ever set).
    pub fn set_viscosity(&mut self, node: usize, viscosity: f32) -> Result<()> {
        self.check_node(node)?;
        params::non_negative("viscosity", viscosity)?;
        let stability = self.lattice.stability.with_viscosity(viscosity);
        self.admit_bounds(stability)?;
        self.lattice.stability = stability;
        self.lattice.state.viscosity.set(node, viscosity);
        self.window.customised();
        Ok(())
    }

    /// Sets every node's mass from `masses`, row-major, one per node: each checked as by
    /// [`Surface::set_mass`] and the lightest against the critical timestep, all before
    /// anything changes, so a refused call changes nothing. The same state as setting the
    /// nodes one by one.
    pub fn set_masses(&mut self, masses: &[f32]) -> Result<()> {
        same_length("masses", masses.len(), self.node_count())?;
        let mut stability = self.lattice.stability;
        for &mass in masses {
            check_mass(mass)?;
            stability = stability.with_mass(mass);
        }
        self.admit_bounds(stability)?;
        self.lattice.stability = stability;
        self.window.customised();
        let state = &mut self.lattice.state;
        state.mass.assign(|i| masses[i]);
        let pinned = &state.pinned;
        state
            .inv_mass
            .assign(|i| if pinned[i] { 0.0 } else { 1.0 / masses[i] });
        Ok(())
    }

    /// Sets every node's viscosity from `viscosities`, row-major, one per node: each
    /// checked as by [`Surface::set_viscosity`] and the largest against the critical
    /// timestep, all before anything changes, so a refused call changes nothing.
    pub fn set_viscosities(&mut self, viscosities: &[f32]) -> Result<()> {
        same_length("viscosities", viscosities.len(), self.node_count())?;
        let mut stability = self.lattice.stability;
        for &viscosity in viscosities {
            params::non_negative("viscosity", viscosity)?;
            stability = stability.with_viscosity(viscosity);
        }
        self.admit_bounds(stability)?;
        self.lattice.stability = stability;
        self.window.customised();
        self.lattice.state.viscosity.assign(|i| viscosities[i]);
        Ok(())
    }

    /// Node masses, row-major. Uniform masses are not stored per node: the view reads
    /// them where they are (see [`NodeValues`]).
    pub fn masses(&self) -> NodeValues<'_> {
        NodeValues::new(&self.lattice.state.mass)
    }

    /// Node viscosities `γ`, row-major, the absorbing frame's ramp included. Stored per
    /// node only once a node differs from its default (see [`NodeValues`]).
    pub fn viscosities(&self) -> NodeValues<'_> {
        NodeValues::new(&self.lattice.state.viscosity)
    }

    /// Pinned flags.
    pub fn pinned(&self) -> &[bool] {
        &self.lattice.state.pinned
    }

    /// A spring's rest length and coefficient; `None` if the grid has no such spring.
    pub fn spring(&self, id: SpringId) -> Option<Spring> {
        (id.origin < self.node_count() && self.grid().spring_end(id.family, id.origin).is_some())
            .then(|| {
                let (stiffness, rest) = self.lattice.springs.get(id.family, id.origin);
                Spring { rest, stiffness }
            })
    }

    /// Sets a spring's rest length (≥ 0) and coefficient (> 0). Refused, with nothing
    /// changed, if the spring does not exist or the coefficient would put `params().dt` at
    /// or past the critical timestep.
    ///
    /// ```
    /// use springwater::{Family, Params, Spring, SpringId, Surface};
    ///
    /// let mut water = Surface::new(Params::with_size(8, 8))?;
    /// let id = SpringId { family: Family::E, origin: 9 };
    /// assert_eq!(water.spring(id), Some(Spring { rest: 0.5, stiffness: 7.0 }));
    /// water.set_spring(id, Spring { rest: 0.8, stiffness: 5.0 })?;
    /// assert_eq!(water.spring(id).unwrap().stiffness, 5.0);
    /// # Ok::<(), springwater::Error>(())
    /// ```
    pub fn set_spring(&mut self, id: SpringId, spring: Spring) -> Result<()> {
        let Spring {
            rest,
            stiffness: coef,
        } = spring;
        self.check_node(id.origin)?;
        if self.grid().spring_end(id.family, id.origin).is_none() {
            return Err(Error::OutOfRange {
                what: "spring origin",
                index: id.origin,
                len: self.node_count(),
            });
        }
        params::non_negative("rest length", rest)?;
        params::positive("stiffness", coef)?;
        let stability = self.lattice.stability.with_stiffness(coef);
        self.admit_bounds(stability)?;
        self.lattice.stability = stability;
        self.lattice.springs.set(id, rest, coef);
        Ok(())
    }

    fn check_node(&self, node: usize) -> Result<()> {
        if node < self.node_count() {
            Ok(())
        } else {
            Err(Error::OutOfRange {
                what: "node",
                index: node,
                len: self.node_count(),
            })
        }
    }
}

/// A node mass [`Surface::set_mass`] takes, apart from the timestep: positive, with a
/// finite reciprocal.
fn check_mass(mass: f32) -> Result<()> {
    params::positive("mass", mass)?;
    if !(1.0 / mass).is_finite() {
        return Err(Error::InvalidParam {
            name: "mass",
            value: mass as f64,
            expected: "at least 1.2e-38 (the reciprocal must be finite)",
        });
    }
    Ok(())
}
