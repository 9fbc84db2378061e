//! grainpack: packs ellipsoidal grains into a box without overlaps.
//!
//! The crate has four layers, one module each:
//! - [`contact`]: the narrow phase. The Perram–Wertheim contact function μ² of two
//!   ellipsoids, the yes/no overlap test, contact geometry, and the Wang–Wang–Kim
//!   algebraic separation test as an independent cross-check.
//! - [`octree`]: the broad phase. Candidate pairs from bounding spheres in a periodic or
//!   walled box.
//! - [`packing`]: the growth-and-collision loop, and the exact check of its result.
//! - [`io`]: scene files (TOML), contact cases (CSV), the written outputs and reports.

// `!(x > y)` is how the numerics say "not positive, or NaN": a NaN must fail the
// test it meets, which `x <= y` would let through.
#![allow(clippy::neg_cmp_op_on_partial_ord)]

pub mod contact;
pub mod io;
pub mod octree;
pub mod packing;
