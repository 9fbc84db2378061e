//! grainpack: packs ellipsoidal grains into a box without overlaps.
//!
//! The crate has four layers, one module each:
//! - [`contact`]: the narrow phase. The Perram–Wertheim contact function μ² of two
//!   ellipsoids, the yes/no overlap test, contact geometry, and the Wang–Wang–Kim
//!   algebraic separation test as an independent cross-check.
//! - [`octree`]: the broad phase. Candidate pairs from bounding spheres in a periodic or
//!   walled box.
//! - `packing` and `io`: the growth-and-collision loop and the scene files (to come).

// `!(x > y)` is how the numerics say "not positive, or NaN": a NaN must fail the
// test it meets, which `x <= y` would let through.
#![allow(clippy::neg_cmp_op_on_partial_ord)]

pub mod contact;
pub mod io;
#[cfg(not(feature = "wip-no-octree"))]
pub mod octree;
