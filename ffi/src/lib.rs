//! # springwater-ffi
//!
//! The C ABI of [springwater](https://docs.rs/springwater): a water surface simulated on
//! the CPU as a mass-spring lattice, for C, C++ and C# engines. Build it with
//! `cargo build --release -p springwater-ffi` and link `libspringwater_ffi.a`
//! (static) or `libspringwater_ffi.so` / `.dylib` / `springwater_ffi.dll` (dynamic);
//! include `ffi/include/springwater.h`, which cbindgen generates from this crate (a test
//! fails when the checked-in header is out of date).
//!
//! This crate is a thin layer over the library's public API: every function checks its
//! arguments, calls the Rust method of the same name and turns the result into a status.
//!
//! ## Conventions
//!
//! * **Handles.** A `SwSurface *` (and a hull's `SwHull *`, a rain's or a wake's
//!   `SwDisturbance *`) is opaque and never dereferenced by the library: it is a key into a
//!   table of live surfaces (hulls, disturbances).
//!   NULL, destroyed and made-up handles give `SW_ERROR_INVALID_HANDLE` (or
//!   `SW_ERROR_NULL_POINTER`), never a crash. Different
//!   surfaces may be used from different threads at once; calls on one surface must not
//!   overlap (an overlapping call returns `SW_ERROR_BUSY` and changes nothing).
//! * **Status codes.** Every function that can fail returns an `SwStatus` (`int32_t`):
//!   `SW_OK` (0) or a negative `SW_ERROR_*` code. `sw_last_error` gives the calling
//!   thread's last message. A call that fails changes nothing.
//! * **Checked input.** Every pointer is checked for NULL (out-pointers documented as
//!   optional may be NULL), every buffer length against what the call writes, every
//!   float for finiteness, every enum value against its constants. No panic crosses the
//!   boundary: an internal failure is `SW_ERROR_INTERNAL`, and that surface should be
//!   destroyed.
//! * **Types for any language.** Enums and booleans are `int32_t` with `#define`d
//!   values; structs hold only integers, floats and pointers (C# `StructLayout.Sequential`
//!   maps them as they are); no varargs, no callbacks but the job system's.
//! * **Units.** World units for lengths and points (`x, z` in the water's local space, y
//!   up), and seconds for everything with time in it that a game sets or reads: frame
//!   times, velocities (per second), the uniform acceleration and the buoyancy's gravity
//!   (per second²), floating bodies' state and forces. `SwParams`' lattice constants
//!   (`mass`, `stiffness`, `viscosity`, `dt`) are in model time, and `time_scale` converts;
//!   so is the lattice's state node by node: forces pushed into the water
//!   (`sw_surface_add_force_at`, `sw_surface_set_forces`) are in the lattice's force units,
//!   every node's velocity (`sw_surface_write_velocities`) per unit of model time. The same
//!   as the Rust API (docs/units.md).

#![deny(unsafe_op_in_unsafe_fn)]

// The C ABI, one file per topic. cbindgen writes the header's functions and constants in
// the order it meets them, which is the order of these modules (the blank lines keep
// `cargo fmt` from sorting them).

// The structs a caller fills (`SwParams`, LOD, refraction), their defaults and codes;
// the version; the CPU's SIMD level.
mod params;

// Creating and destroying a surface, its parameters, the clock, steps, drops.
mod surface;

// The moving window and the floating origin.
mod window;

// Forces and queries at points.
mod queries;

// The lattice node by node: pins, masses, viscosities, single springs.
mod lattice;

// What a renderer uploads: positions, normals, refraction, vertices, LOD indices.
mod buffers;

// Snapshots: save, restore, load.
mod snapshots;

// A surface's energy and the SIMD level it runs.
mod engine;

// Floating bodies.
mod floaters;

// Hull meshes, pushes at a point and torques, and the forces on bodies another engine
// owns.
mod bodies;

// Hulls the library makes (a box, the boat, a hull on its centroid) and reads.
mod hulls;

// Rain and wakes as handles, applied before every substep of a frame.
mod disturb;

// The host's job system.
mod jobs;

// For WebAssembly hosts only (the npm package in web/): buffers, and rain and wakes by
// number. Not in the header.
#[cfg(target_family = "wasm")]
mod wasm;

// The thread's last error message and the names of status codes.
mod errors;

// Beneath the topics: handles; status codes and the guard every call runs in; the
// pointer and length checks, where the crate's `unsafe` code is (with the job system's
// callbacks in jobs.rs).
mod handle;
mod ptr;
mod status;

pub use bodies::*;
pub use buffers::*;
pub use disturb::*;
pub use engine::*;
pub use errors::*;
pub use floaters::*;
pub use handle::SwSurface;
pub use hulls::*;
pub use jobs::*;
pub use lattice::*;
pub use params::*;
pub use queries::*;
pub use snapshots::*;
pub use status::*;
pub use surface::*;
#[cfg(target_family = "wasm")]
pub use wasm::*;
pub use window::*;
