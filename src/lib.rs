//! grainpack: packs ellipsoidal grains into a box without overlaps.
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

pub mod contact;
pub mod io;
pub mod laws;
pub mod octree;
pub mod packing;
pub mod run;
pub mod scene;

// The code in the README and docs/architecture.md compiles as doc tests.
#[cfg(doctest)]
#[doc = include_str!("../docs/architecture.md")]
struct ArchitectureDoc;

#[cfg(doctest)]
#[doc = include_str!("../README.md")]
struct Readme;
