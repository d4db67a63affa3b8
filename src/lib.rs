//! # springwater
//!
//! A water surface for games and animation, simulated on the CPU as a mass-spring
//! lattice (from Markhichev & Soupikov's presentation on water surface animation, "the
//! seed" in these docs): a `cols × rows` grid of nodes joined by springs on every grid
//! edge and both diagonals, moved by `m x'' + γ x' + f = f_ext` with symplectic Euler at
//! a near-critical timestep. The defaults (h 1, m 4, c 7, γ 0.05, Δt 0.4) are the seed's.
//!
//! ```
//! use springwater::{Params, Surface};
//!
//! let mut water = Surface::new(Params::with_size(128, 128))?;   // seed defaults
//! water.drop_at(64.0, 64.0, 2.0, 3.0)?;
//! for _ in 0..100 {
//!     water.step()?;
//! }
//! let view = water.mesh_view();           // borrowed positions for the renderer
//! assert_eq!(view.y().len(), 128 * 128);
//! # Ok::<(), springwater::Error>(())
//! ```
//!
//! ## The model
//!
//! * **Grid.** Node `(col, row)` has index `row * cols + col` and rests at
//!   `(col·h, 0, row·h)` in the water's local space, `h` = [`Params::spacing`]; y is up.
//!   By default the outer ring of nodes is pinned (a pool, [`Boundary`]).
//! * **Springs** on every grid edge and both diagonals of every cell (families E, S, SE,
//!   SW: [`Family`]); a spring of rest length `L0` and coefficient `c` at length `L`
//!   pulls its ends with `c (L − L0)`. Rest lengths are [`Params::rest_ratio`] times the
//!   initial lengths: below 1 the flat sheet is under tension and vertical ripples travel
//!   at about `h·sqrt(3c(1 − rest_ratio)/m)` per unit of model time.
//! * **Motion** `m x'' + γ x' + f = f_ext`, integrated with symplectic Euler at
//!   [`Params::dt`]; [`Params`] explains the stability limit the timestep must stay below
//!   and what validation checks.
//! * **Units.** Lengths are world units everywhere (the unit of `spacing`): drops, forces
//!   at a point, queries, wakes. Everything with time in it that a game sets or reads is
//!   in **seconds**: [`Surface::advance`], [`Surface::time`], velocity queries, the uniform
//!   acceleration, floating bodies (velocity, drag, gravity, forces), rain rates and wake
//!   speeds. *Model time* stays inside the model and in the lattice's constants (`dt`,
//!   `mass`, `stiffness`, `viscosity`), with [`Surface::model_time`] to read its clock;
//!   the lattice's own arrays ([`Surface::velocities`]) and the forces pushed into the
//!   water ([`Surface::add_force_at`]) are in its units. [`Params::time_scale`] (model time
//!   per second, with [`Params::ripple_speed`] to read it as a speed) converts: with the
//!   defaults 1 s is 24 units of model time, 60 steps of 0.4. `docs/units.md` lists every
//!   quantity with its unit.
//!
//! ## The pipeline
//!
//! ```text
//! Params ─validate─▶ Surface (SoA state + spring tables + colour batches)
//!                       │ advance(seconds) / step(): forces (colour batches, SIMD, rayon) + integrate
//!                       ▼
//!                    MeshView<'_>  (borrows the SoA arrays: zero copy)
//!                       ├─▶ normals      (per node)                    mesh
//!                       ├─▶ LOD indices  (view-dependent, crack-free)  mesh
//!                       ├─▶ refraction   (per node bottom UV, Fresnel) refraction
//!                       └─▶ interleaved positions/normals/UVs/vertices buffers
//! ```
//!
//! Arrows run one way: the physics ([`Surface`]) knows nothing of meshes or renderers; the
//! render-side stages read it only through [`MeshView`].
//!
//! * [`Surface`]: what a game owns: stepping, drops and forces, point queries
//!   ([`Surface::height_at`] and friends), snapshots ([`Snapshot`], a versioned binary
//!   format with a checksum), the host's threads ([`Surface::set_thread_pool`], or any
//!   [`JobSystem`] with [`Surface::set_job_system`]).
//! * [`Params`], [`Boundary`]: the model's parameters, their defaults and limits; the
//!   boundary is a pinned pool, a free sheet, or open water whose waves leave through a
//!   damping frame ([`Boundary::Absorbing`]).
//! * [`floater`]: floating rigid bodies, spheres, boxes and hull meshes ([`Floater`],
//!   [`Surface::add_floater`]) that pitch and roll with the waves and push back on them,
//!   two-way; [`Surface::body_forces`] for bodies another physics engine owns. [`body`]
//!   holds their physics: hulls, the pressure on the wet triangles, the rigid step.
//! * [`disturb`]: rain reproducible from a seed, a moving object's wake, and the
//!   [`disturb::Disturbance`] trait that [`Surface::advance_with`] applies every substep.
//! * [`mesh`]: normals and the LOD index buffer. Its docs show a renderer's frame.
//! * [`refraction`]: per-node bottom texture coordinates through the surface, Fresnel.
//! * [`buffers`]: the per-node arrays interleaved for a GPU upload (packed [`buffers::Vertex`]).
//! * `render` (feature `render`): a CPU preview renderer drawing the LOD mesh in
//!   perspective with the bottom refracted through it, sky reflections and caustics.
//!
//! * [`SimdLevel`]: the instruction set the engine and the render-side stages run. The
//!   default build detects the CPU once and runs the widest it has: SSE2, AVX2 or
//!   AVX-512 on x86-64, NEON on AArch64, SIMD128 on wasm32 builds made with
//!   `+simd128`, portable lanes elsewhere; [`Surface::set_simd_level`] forces one (the
//!   command line reads `SPRINGWATER_SIMD` for it: `scalar`, `sse2`, `avx2`, `avx512`,
//!   `neon`, `simd128`, `portable`; the library never reads the environment).
//!   Every level, on every target, gives the same bits.
//!
//! ## Features
//!
//! * `parallel` (default): colour batches run on a rayon pool (the global one, or the
//!   host's: [`Surface::set_thread_pool`]). Results are bitwise identical with it off and
//!   for any number of threads.
//! * `render`: the CPU preview renderer (`springwater::render`). No extra dependencies.
//! * `serde`: derive `Serialize`/`Deserialize` for [`Params`] and [`Snapshot`].
//! * `internals`: the unstable `springwater::internals` module (scalar twins of the SIMD
//!   stages, comparison kernels, the engine's schedule knobs, for the crate's own tests,
//!   benchmarks and command line). Not covered by semver.
//!
//! The `springwater` command line is a separate crate, `springwater-cli`, so depending on
//! the library brings none of its dependencies.

#![warn(missing_docs)]
#![deny(unsafe_op_in_unsafe_fn)]
#![warn(clippy::undocumented_unsafe_blocks)]

mod absorb;
#[cfg(feature = "internals")]
mod baselines;
pub mod body;
pub mod buffers;
pub mod disturb;
mod error;
pub mod floater;
mod forces;
mod grid;
mod jobs;
pub mod mesh;
mod params;
pub mod refraction;
#[cfg(feature = "render")]
pub mod render;
mod rng;
mod simd;
mod springs;
mod stability;
mod state;
mod surface;
mod view;

pub use error::{Error, IoError, Result};
pub use floater::{BodyForces, Buoyancy, Floater, FloaterId, Shape};
/// The `glam` the public API speaks (`Vec3` in floaters and queries), for callers whose own
/// `glam` is another version.
pub use glam;
pub use grid::{Family, Grid, SpringId};
pub use jobs::JobSystem;
pub use params::{Boundary, Params, MAX_NODES};
pub use simd::SimdLevel;
pub use state::{NodeValues, NodeValuesIter};
pub use surface::snapshot::Snapshot;
pub use surface::window;
pub use surface::{Energy, FarField, Overflow, Spring, Surface, WaterSample, MAX_ORIGIN_CELLS};
pub use view::MeshView;

/// Unstable internals for the crate's command line, tests and benchmarks: the scalar
/// twins the SIMD stages are tested against, the comparison kernels of `bench`, and the
/// engine's schedule (bands, tiling, steps per pass) that the colouring and parity tests
/// check. **Not part of the public API**: no semver promise, may change or vanish in any
/// release. It exists because integration tests, benchmarks and the command line are
/// outside the crate and can only reach public items; it is behind the `internals` feature
/// (which the `springwater-cli` crate turns on) and hidden from the docs so that a game
/// does not build on it by accident.
#[cfg(feature = "internals")]
#[doc(hidden)]
pub mod internals {
    pub use crate::mesh::normals::compute_normals_scalar;
    pub use crate::refraction::scalar::{refract_node, refract_scalar};

    pub use crate::baselines::{MemoryFloor, NaiveSurface};
    pub use crate::forces::engine::tiling::{
        band_rows, bands, Band, Tiling, MAX_BAND_ROWS, MIN_BAND_ROWS,
    };
    pub use crate::forces::engine::MAX_PASS_STEPS;
    pub use crate::surface::tuning::Tuning;
}

/// The README's examples, compiled and run as doc tests.
#[cfg(doctest)]
#[doc = include_str!("../README.md")]
pub struct ReadmeDoctests;

/// The guide's examples, compiled and run as doc tests.
#[cfg(doctest)]
#[doc = include_str!("../docs/guide.md")]
pub struct GuideDoctests;

/// The examples of docs/units.md, compiled and run as doc tests.
#[cfg(doctest)]
#[doc = include_str!("../docs/units.md")]
pub struct UnitsDoctests;

/// The examples of docs/reliability.md, compiled and run as doc tests.
#[cfg(doctest)]
#[doc = include_str!("../docs/reliability.md")]
pub struct ReliabilityDoctests;
