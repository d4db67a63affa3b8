//! Rigid floating bodies' geometry and hydrostatics: hull meshes, their mass properties,
//! and what still water or waves do to them in a given pose.
//!
//! * [`Hull`]: a closed, outward-wound triangle mesh in the body's frame, validated, with
//!   its volume, centroid and inertia tensor computed from the triangles by the divergence
//!   theorem (the `hull` source file explains the sums). [`Hull::cuboid`] is a box as 12
//!   triangles.
//! * [`Hull::submerged`]: for a pose (position and a unit quaternion, body to world) and a
//!   water height at each world `(x, z)`, the submerged volume, the centre of buoyancy,
//!   the pressure force and its torque about the body's origin, and the waterplane
//!   ([`Submerged`], [`Waterplane`]). The pressure `ρ g d` is integrated over each
//!   triangle below the water, clipped at the waterline; against a flat water plane the
//!   result is Archimedes' exactly, at any heel (the `hydrostatics` source file gives the
//!   method, and why it rather than columns under the hull).
//! * Small balls and boxes (at most two cells across) meet the water as a plane: the
//!   `small` source file computes a ball's cap and a box's clipped triangles under it.
//! * [`BoatShape`]: a simple displacement hull, generated, for examples and tests
//!   (`assets/boat.obj` is the default one).
//!
//! # Stability of a floating body
//!
//! A body floats upright where its weight `m g` equals the buoyancy `ρ g V` and its
//! centre of mass `G` is above the centre of buoyancy `B` of the displaced volume. Heeled
//! by a small angle `φ`, the displaced volume's shape changes: `B` moves towards the side
//! that went down, and the buoyancy's line of action crosses the centre line at the
//! metacentre `M`, a height `BM = I / V` above `B`, where `I` is the waterplane's second
//! moment of area about the heeling axis ([`Waterplane::second_moment_about`]). The
//! righting moment is `m g · GM · sin φ`, with the metacentric height
//!
//! ```text
//! GM = KB + BM − KG
//! ```
//!
//! (heights from the keel `K`). `GM > 0`: the body rights itself, `GM < 0`: it capsizes. A
//! box of beam `b` floating at draft `T` has `KB = T / 2` and `BM = b² / (12 T)`: a wide
//! barge is stiff, a tall narrow box (large `KG`, small `b`) rolls over. The tests of
//! this module check these figures against the pressure integral.
//!
//! # Arithmetic
//!
//! Every formula here uses `+`, `−`, `×`, `÷` (and `sqrt`) only, in `f64` with the plain
//! scalar operations of `glam`'s `DVec3` (no fused multiply-add, no SIMD, no library
//! functions such as `sin` whose results differ between platforms): a hull's mass
//! properties and its submerged part have the same bits on every target. Results are
//! handed back in `f32`, like the rest of the crate.

mod boat;
mod hull;
mod hydrostatics;
pub(crate) mod math;
pub(crate) mod rigid;
pub(crate) mod small;
pub(crate) mod tessellate;

pub use boat::BoatShape;
pub use hull::Hull;
pub use hydrostatics::{HullScratch, Submerged, Waterplane};
