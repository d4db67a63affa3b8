//! # springwater
//!
//! A water surface for games and animation, simulated on the CPU as a mass-spring
//! lattice (Markhichev & Soupikov): a `cols × rows` grid of nodes joined by springs on
//! every grid edge and both diagonals, moved by `m x'' + γ x' + f = f_ext` with
//! symplectic Euler at the seed's near-critical timestep.
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
//! ## The pipeline
//!
//! ```text
//! Params ─validate─▶ Surface (SoA state + spring tables + colour batches)
//!                       │ step(): forces (colour batches, SIMD, rayon) + integrate
//!                       ▼
//!                    MeshView<'_>  (borrows the SoA arrays: zero copy)
//!                       ├─▶ normals      (per node)
//!                       ├─▶ LOD indices  (view-dependent, crack-free, cached per camera)
//!                       └─▶ refraction   (per node bottom UV, Fresnel)
//! ```
//!
//! * [`params`]: the model's parameters, their defaults and the stability limits.
//! * [`grid`]: index math and spring families. Row-major, y up.
//! * [`springs`]: per-spring tables and the colour batches (bands of rows).
//! * `forces`: the scalar reference step and the SIMD + rayon engine step.
//! * [`surface`]: [`Surface`], what a game owns.
//! * [`snapshot`]: save and restore a surface bitwise ([`Snapshot`], a versioned binary
//!   format with a checksum).
//! * [`mesh`]: the zero-copy [`MeshView`] and the render-side stages: normals, the LOD
//!   index buffer ([`mesh::LodMesh`]), point queries ([`Surface::height_at`] and friends).
//!   Its docs show a renderer's frame.
//! * [`refraction`]: per-node bottom texture coordinates through the surface, Fresnel.
//! * [`disturb`]: disturbances worth watching, through the public API: rain reproducible
//!   from a seed ([`disturb::Rain`]) and a moving object's wake ([`disturb::Wake`]).
//! * `render` (feature `render`): a CPU preview renderer drawing the LOD mesh in
//!   perspective with the bottom refracted through it, sky reflections and caustics.
//! * [`baselines`]: comparison kernels for benchmarks (naive AoS, memory floor).
//!
//! ## Features
//!
//! * `parallel` (default): colour batches run on the rayon pool. Results are bitwise
//!   identical with it off and for any number of threads.
//! * `cli` (default): the `springwater` command-line tool (turns on `render`). Engines
//!   embedding the library use `default-features = false, features = ["parallel"]`.
//! * `render`: the CPU preview renderer (`springwater::render`). No extra dependencies.
//! * `serde`: derive `Serialize`/`Deserialize` for [`Params`] and [`Snapshot`].

#![warn(missing_docs)]
#![deny(unsafe_op_in_unsafe_fn)]
#![warn(clippy::undocumented_unsafe_blocks)]

pub mod baselines;
pub mod buffers;
pub mod disturb;
pub mod error;
mod forces;
pub mod grid;
pub mod mesh;
pub mod params;
pub mod refraction;
#[cfg(feature = "render")]
pub mod render;
pub mod simd;
pub mod snapshot;
pub mod springs;
mod state;
pub mod surface;

pub use error::{Error, Result};
pub use forces::simd::MAX_PASS_STEPS;
pub use grid::{Family, Grid, SpringId};
pub use mesh::MeshView;
pub use params::{Boundary, Params};
pub use snapshot::Snapshot;
pub use surface::{Energy, Spring, Stepper, Surface};

/// The README's examples, compiled and run as doc tests.
#[cfg(doctest)]
#[doc = include_str!("../README.md")]
pub struct ReadmeDoctests;

/// The examples of docs/reliability.md, compiled and run as doc tests.
#[cfg(doctest)]
#[doc = include_str!("../docs/reliability.md")]
pub struct ReliabilityDoctests;
