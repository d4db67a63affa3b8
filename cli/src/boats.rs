//! `render --boats N`: boats under way in the rain, and how they are drawn.
//!
//! Each boat is the library's rigid body with the shipped hull ([`BoatShape`], one mesh
//! shared by all of them): the water lifts, pitches and rolls it, and it pushes back, so
//! it leaves a wake. What the command adds is a helmsman: a thrust along the heading and a
//! turning moment that keep each boat on its own circle, so the boats stay in the pool.
//!
//! The library's preview renderer draws the hulls with the water, as facets sharing its
//! depth buffer: the water hides a hull's part under the surface, and a crest between the
//! camera and a boat hides the boat.

use crate::args::CliResult;
use glam::{Quat, Vec3};
use springwater::body::{BoatShape, Hull};
use springwater::disturb::Disturbance;
use springwater::render::Facet;
use springwater::{Floater, FloaterId, Surface};
use std::sync::Arc;

/// The boats' density against the water's: they float with a little under half their
/// depth in the water, low enough that a wave under one side rolls them.
const DENSITY: f32 = 0.35;

/// Radius of each boat's circle, in boat lengths.
const TURN: f32 = 0.75;

/// Speed under way, in boat lengths per second.
const SPEED: f32 = 0.8;

/// Hull colours (topsides, deck), linear RGB, one pair per boat in turn.
const COLOURS: [[[f32; 3]; 2]; 4] = [
    [[0.75, 0.05, 0.03], [0.55, 0.36, 0.18]],
    [[0.85, 0.85, 0.80], [0.55, 0.36, 0.18]],
    [[0.05, 0.20, 0.60], [0.80, 0.75, 0.62]],
    [[0.95, 0.60, 0.05], [0.55, 0.36, 0.18]],
];

/// The boats on a surface and the course each one holds.
#[derive(Debug)]
pub struct Fleet {
    hull: Arc<Hull>,
    length: f32,
    boats: Vec<Boat>,
    /// The greatest heel and trim seen, degrees.
    tilt: (f32, f32),
}

/// One boat: its body on the surface and the circle it runs.
#[derive(Debug, Clone, Copy)]
struct Boat {
    id: FloaterId,
    /// Centre of its circle (x, z), world units.
    centre: [f32; 2],
    /// +1 turning to port (anticlockwise seen from above), −1 to starboard.
    turn: f32,
}

/// Each boat's square of water: its circle and a boat length to spare, world units.
fn berth(length: f32) -> f32 {
    (2.0 * TURN + 1.0) * length
}

/// The side of a boat's berth in cells.
pub fn berth_cells() -> f32 {
    berth(BoatShape::default().length)
}

/// The shipped boat at the scale of the grid: its default size (6 by 2 by 1 world units)
/// at spacing 1, as many cells at any other spacing (like the rain's drops), moved onto
/// its centroid (a body's origin is its centre of mass).
fn hull(spacing: f32) -> CliResult<Hull> {
    let mut shape = BoatShape::default();
    shape.length *= spacing;
    shape.beam *= spacing;
    shape.depth *= spacing;
    shape
        .hull()
        .and_then(|h| h.centred())
        .map_err(|e| format!("--boats: {e}"))
}

/// How many boats the pool of `surface` has room for: one per berth on a square grid.
pub fn room(surface: &Surface) -> usize {
    let p = surface.params();
    let length = BoatShape::default().length * p.spacing;
    let across = |nodes: usize| ((nodes - 1) as f32 * p.spacing / berth(length)) as usize;
    across(p.cols) * across(p.rows)
}

impl Fleet {
    /// `n` boats on `surface`, each in the middle of its berth, on the block of berths
    /// nearest to square in the middle of the pool, under way on its circle. `n` must be
    /// at most [`room`].
    pub fn launch(surface: &mut Surface, n: usize) -> CliResult<Self> {
        let p = *surface.params();
        let hull = Arc::new(hull(p.spacing)?);
        let length = BoatShape::default().length * p.spacing;
        let slot = berth(length);
        let (w, d) = (
            (p.cols - 1) as f32 * p.spacing,
            (p.rows - 1) as f32 * p.spacing,
        );
        let (fit_x, fit_z) = ((w / slot) as usize, (d / slot) as usize);
        let mut across = ((n as f32).sqrt().ceil() as usize).clamp(1, fit_x.max(1));
        if n.div_ceil(across) > fit_z {
            across = n.div_ceil(fit_z.max(1));
        }
        let down = n.div_ceil(across);
        let mass = DENSITY * surface.buoyancy().density * hull.volume();
        let mut boats = Vec::with_capacity(n);
        for k in 0..n {
            let (i, j) = ((k % across) as f32, (k / across) as f32);
            let centre = [
                w / 2.0 + (i - (across as f32 - 1.0) / 2.0) * slot,
                d / 2.0 + (j - (down as f32 - 1.0) / 2.0) * slot,
            ];
            let turn = if k % 2 == 0 { 1.0 } else { -1.0 };
            // Start somewhere different on each circle (the golden angle apart), the first
            // on the side nearest the default camera (+z).
            let start = k as f32 * 2.4;
            let out = Vec3::new(start.sin(), 0.0, start.cos());
            let heading = turn * Vec3::Y.cross(out);
            let mut body = Floater::with_hull(
                hull.clone(),
                mass,
                [
                    centre[0] + TURN * length * out.x,
                    0.0,
                    centre[1] + TURN * length * out.z,
                ],
            );
            // Body +x (the bow) along the heading: a turn about +y by the heading's angle.
            body.orientation = Quat::from_rotation_y((-heading.z).atan2(heading.x));
            body.velocity = heading * SPEED * length;
            let id = surface
                .add_floater(body)
                .map_err(|e| format!("--boats: {e}"))?;
            boats.push(Boat { id, centre, turn });
        }
        Ok(Self {
            hull,
            length,
            boats,
            tilt: (0.0, 0.0),
        })
    }

    /// Notes the boats' heel and trim now: the tilt of each deck's athwartships and
    /// fore-and-aft lines from the horizontal.
    pub fn observe(&mut self, surface: &Surface) {
        for b in &self.boats {
            let Ok(body) = surface.floater(b.id) else {
                continue;
            };
            let angle = |axis: Vec3| (body.orientation * axis).y.clamp(-1.0, 1.0).asin();
            self.tilt.0 = self.tilt.0.max(angle(Vec3::Z).abs().to_degrees());
            self.tilt.1 = self.tilt.1.max(angle(Vec3::X).abs().to_degrees());
        }
    }

    /// The greatest heel and trim of any boat [`observe`](Self::observe) saw, degrees.
    pub fn greatest_tilt(&self) -> (f32, f32) {
        self.tilt
    }
}

/// The helmsman, before every step: a thrust along each boat's heading that holds its
/// speed against the water's drag, and a turning moment (a couple, so it pushes the boat
/// nowhere) that steers it along its circle and back onto it when the waves push it off.
impl Disturbance for Fleet {
    fn apply(&mut self, surface: &mut Surface, _dt: f32) -> springwater::Result<()> {
        let radius = TURN * self.length;
        let speed = SPEED * self.length;
        for b in &self.boats {
            let body = surface.floater(b.id)?;
            let flat = |v: Vec3| Vec3::new(v.x, 0.0, v.z).normalize_or_zero();
            let heading = flat(body.orientation * Vec3::X);
            let from_centre = body.position - Vec3::new(b.centre[0], 0.0, b.centre[1]);
            let out = flat(from_centre);
            if heading == Vec3::ZERO || out == Vec3::ZERO {
                continue;
            }
            // Along the circle, leaning inwards when outside it and outwards when inside.
            let off = (Vec3::new(from_centre.x, 0.0, from_centre.z).length() - radius) / radius;
            let wanted = flat(b.turn * Vec3::Y.cross(out) - off.clamp(-1.0, 1.0) * out);
            // The sine of the angle to turn through (about +y), full helm when it is behind.
            let sine = heading.cross(wanted).y;
            let error = if heading.dot(wanted) >= 0.0 {
                sine
            } else if sine >= 0.0 {
                1.0
            } else {
                -1.0
            };
            let rate = b.turn * speed / radius;
            let yaw = body.inertia_tensor().y_axis.y;
            // Rates per second: the drag rate the water already applies (6 per second)
            // and a firm hand on top of it.
            let moment = yaw * (12.0 * error + 8.0 * (rate - body.angular_velocity.y));
            // What the water held the boat back with in the last step (its drag along the
            // heading, by how much hull faces the motion: the keel), and a firm hand on
            // the speed.
            let held = -body.water_force.dot(heading);
            let thrust = held + body.mass * 4.0 * (speed - body.velocity.dot(heading));
            let (id, position) = (b.id, body.position);
            surface.push_floater(id, heading * thrust)?;
            // The moment as a couple: ±f at half a boat length fore and aft.
            let arm = heading * (0.5 * self.length);
            let f = Vec3::Y.cross(arm) * (moment / (2.0 * arm.length_squared()));
            surface.push_floater_at(id, f, position + arm)?;
            surface.push_floater_at(id, -f, position - arm)?;
        }
        Ok(())
    }
}

/// The hulls as facets for the renderer, which draws them with the water: a buffer kept
/// between frames.
#[derive(Debug, Default)]
pub struct Painter {
    facets: Vec<Facet>,
}

impl Painter {
    /// Every boat of `fleet` on `surface` as facets: each face its boat's colour, the
    /// topsides' or, facing up in the boat's frame, the deck's.
    pub fn facets(&mut self, surface: &Surface, fleet: &Fleet) -> &[Facet] {
        self.facets.clear();
        let hull = &fleet.hull;
        for (k, b) in fleet.boats.iter().enumerate() {
            let Ok(body) = surface.floater(b.id) else {
                continue;
            };
            let [topsides, deck] = COLOURS[k % COLOURS.len()];
            let world =
                |i: u32| body.position + body.orientation * Vec3::from(hull.vertices()[i as usize]);
            self.facets.extend(hull.triangles().iter().map(|tri| {
                let corners = tri.map(world);
                let [a, b, c] = corners;
                let normal = (b - a).cross(c - a).normalize_or_zero();
                let up = body.orientation.inverse() * normal;
                let colour = if up.y > 0.7 { deck } else { topsides };
                Facet { corners, colour }
            }));
        }
        &self.facets
    }
}
