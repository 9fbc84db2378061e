//! grainpack: packs ellipsoidal grains into a box without overlaps.
//!
//! It makes synthetic microstructures (representative volume elements) for full-field
//! FE and FFT simulations: grains drawn from size, shape and orientation laws (or read
//! from a measured table), packed to a target fraction, checked pair by pair with the
//! exact Perram–Wertheim contact function, and written as a grain table, VTK files, a
//! voxel RVE, DAMASK and Abaqus/CalculiX input and figures. The `pack` command line
//! (the default `cli` feature) and the Python package are thin layers over this crate;
//! the user guide (`docs/`, built with MkDocs) explains the scene files and the
//! workflows.
//!
//! # Quick start
//!
//! A scene file says what to pack; one call packs it, another writes the files:
//!
//! ```no_run
//! use grainpack::io::report::write_outputs;
//! use grainpack::run::{run, RunOptions};
//! use grainpack::scene::Scene;
//!
//! let scene = Scene::from_path("configs/grains.toml".as_ref())?;
//! let result = run(&scene, RunOptions { seed: Some(7), ..RunOptions::default() })?;
//! println!("φ = {:.3}, stopped: {:?}", result.packing.fraction, result.packing.stop);
//! write_outputs(&scene, &result)?; // grains.csv, VTK, RVE, figures, summary.json
//! # Ok::<(), Box<dyn std::error::Error>>(())
//! ```
//!
//! A scene can also come from TOML text ([`scene::Scene::from_str`], read in
//! [`io::scene`]). The narrow phase stands on its own: two ellipsoids, one call.
//!
//! ```
//! use grainpack::contact::{contact_function, Ellipsoid};
//!
//! let needle = Ellipsoid::new([10.0, 0.1, 0.1], [1.0, 0.0, 0.0, 0.0])?; // along x
//! let ball = Ellipsoid::sphere(1.0)?;
//! let c = contact_function(&[10.5, 0.0, 0.0], &needle.q, &ball.q)?;
//! assert!(c.mu2 < 1.0); // μ² < 1: they overlap
//! # Ok::<(), Box<dyn std::error::Error>>(())
//! ```
//!
//! # Layers
//!
//! The crate is built in layers; each imports only the ones listed before it
//! (`docs/architecture.md` draws the map, and `tests/layers.rs` enforces it):
//! - [`contact`]: the narrow phase. The Perram–Wertheim contact function μ² of two
//!   ellipsoids, the yes/no overlap test, contact geometry, and the Wang–Wang–Kim
//!   algebraic separation test as an independent cross-check.
//! - [`octree`]: the broad phase. Candidate pairs from bounding spheres in a periodic or
//!   walled box.
//! - [`laws`]: the probability laws of grain sizes, shapes and angles, and the
//!   statistics that compare a sample with them.
//! - [`scene`]: the model of what to pack: box, phases, packing parameters, outputs;
//!   and the grains drawn from it.
//! - [`packing`]: the compress-and-relax loop, and the exact check of its result.
//! - [`run`]: the whole job as one call: grains drawn, packed, checked, and their
//!   statistics against the scene's laws.
//! - [`io`]: scene files (TOML), contact cases (CSV), and every file a run writes.

// `!(x > y)` is how the numerics say "not positive, or NaN": a NaN must fail the
// test it meets, which `x <= y` would let through.
#![allow(clippy::neg_cmp_op_on_partial_ord)]
// Every public item is documented; `-D warnings` in CI makes this binding.
#![warn(missing_docs)]

pub mod contact;
pub mod io;
pub mod laws;
pub mod octree;
pub mod packing;
pub mod run;
pub mod scene;

// The code in the README, docs/architecture.md and the guide's Rust page compiles (and
// runs) as doc tests.
#[cfg(doctest)]
#[doc = include_str!("../docs/architecture.md")]
struct ArchitectureDoc;

#[cfg(doctest)]
#[doc = include_str!("../README.md")]
struct Readme;

#[cfg(doctest)]
#[doc = include_str!("../docs/library.md")]
struct LibraryGuide;
