//! Broad phase: octree over the box plus bounding spheres.
//!
//! The octree answers one question each step of the packing loop: which pairs of grains
//! could touch? It knows ids, centres and bounding radii ([`Sphere`]) in a box with a
//! [`Boundary`], and nothing of ellipsoids.
//!
//! # What a pair is
//! A [`Pair`] `(i, j, shift)` says that sphere `j`, moved by `shift` (a multiple of the
//! box lengths, zero in a walled box), meets sphere `i`:
//! `|c_j + shift − c_i| ≤ r_i + r_j` ([`spheres_intersect`]; touching counts). The
//! relative vector the narrow phase wants is `r_ij = c_j + shift − c_i`. Then:
//! - `i < j`, and every intersecting `(i, j, shift)` is reported exactly once;
//! - in a periodic box, a pair that meets through several images (a grain larger than
//!   half the box) is reported once per image, each with its own shift;
//! - a grain whose diameter reaches its own image (`2r ≥ |shift|`) gives a self-image
//!   pair `(i, i, shift)`, reported once, with the lexicographically positive one of
//!   `±shift`. The packing decides whether to allow such grains; the broad phase only
//!   reports them.
//!
//! [`brute_force_pairs`] is the O(n²) reference with the same definition; the tests
//! require the octree's pair set to equal it exactly. Centres in a periodic box may lie
//! outside `[0, L)`: both wrap them with [`BoxShape::wrap`] first, and shifts refer to
//! the wrapped centres (a caller that keeps centres in `[0, L)` sees them unchanged).
//!
//! # How
//! A loose octree used as a bounding-volume hierarchy. Cells are split by centre (only
//! along axes at least half the longest, so a non-cubic box gets near-cubic cells); a
//! sphere descends into a child cell only while its radius is at most
//! `loose_factor ×` half the child's shortest side, and bigger ones stay in a bucket
//! leaf at the node whose size matches theirs, so a 100:1 size ratio neither inflates
//! the small leaves nor stores anything twice. Every node keeps the exact bounds of
//! what it holds, so spheres straddling cell faces need no special case.
//!
//! Pairs come from a dual-tree walk: within each node, every child with itself and
//! with each later sibling; between two nodes, pruned when their bounds are apart,
//! else the bigger one opened, down to leaf against leaf. A periodic box adds, at the
//! root, one walk of the tree against itself moved by each lexicographically positive
//! image `k` whose shifted root bounds overlap, which yields every cross-face, -edge,
//! -corner, multi-image and self-image pair exactly once (`(i, j, k)` and
//! `(j, i, −k)` are the same pair). Completeness rests only on "bounds contain
//! contents", which [`Octree::check_invariants`] checks, and on box tests that carry
//! a rounding slack (see [`spheres_intersect`] for the exact predicate).
//!
//! The packing loop calls [`Octree::rebuild`] at each list build (measured faster than
//! a refit: see `build.rs`) and [`Octree::pairs`] with a reused buffer. rayon builds
//! the children of large nodes in parallel, each into a node array of its own appended
//! in order (the tree of a serial build), and splits the walk into a fixed list of
//! tasks, so the output, order included, does not depend on the thread count. The
//! walk's innermost loops test blocks of spheres into a bit mask (`kernel.rs`). See [`Params`] for the limits and `BENCHMARKS.md` for the
//! figures.
//!
//! ```
//! use grainpack::octree::{BoxShape, Octree, Params, Sphere};
//! let shape = BoxShape::periodic([10.0, 10.0, 10.0]).unwrap();
//! let spheres = [
//!     Sphere { id: 0, centre: [0.5, 5.0, 5.0], radius: 1.0 },
//!     Sphere { id: 1, centre: [9.0, 5.0, 5.0], radius: 1.0 }, // across the x face
//!     Sphere { id: 2, centre: [5.0, 5.0, 5.0], radius: 1.0 },
//! ];
//! let tree = Octree::build(&spheres, shape, Params::default()).unwrap();
//! let mut pairs = Vec::new();
//! tree.pairs(&mut pairs);
//! assert_eq!(pairs.len(), 1);
//! assert_eq!((pairs[0].i, pairs[0].j, pairs[0].image), (0, 1, [-1, 0, 0]));
//! assert_eq!(pairs[0].shift(&shape), [-10.0, 0.0, 0.0]);
//! ```

mod boundary;
mod brute;
mod build;
mod error;
mod invariants;
mod kernel;
mod neighbours;
mod pairs;
mod scratch;
mod split;
mod tree;
mod validate;

pub use boundary::{spheres_intersect, wrap_coordinate, Boundary, BoxShape};
pub use brute::{brute_force_neighbours, brute_force_pairs};
pub use error::{InvariantViolation, OctreeError};
pub use pairs::PairStats;
pub use tree::{Octree, Params, MAX_IMAGES_PER_AXIS, PARALLEL_MIN_SPHERES};

/// A bounding sphere: all the broad phase knows of a grain.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Sphere {
    /// The grain's id, unique within one build.
    pub id: u32,
    /// Centre; in a periodic box it may lie outside `[0, L)` (see [`BoxShape::wrap`]).
    pub centre: [f64; 3],
    /// Bounding radius, positive and finite (for an ellipsoid, its largest semi-axis).
    pub radius: f64,
}

impl Sphere {
    /// A sphere with a finite centre and a positive finite radius.
    ///
    /// ```
    /// use grainpack::octree::Sphere;
    /// assert!(Sphere::new(7, [0.0; 3], 1.0).is_ok());
    /// assert!(Sphere::new(7, [0.0; 3], 0.0).is_err());
    /// ```
    pub fn new(id: u32, centre: [f64; 3], radius: f64) -> Result<Self, OctreeError> {
        let sphere = Self { id, centre, radius };
        sphere.validate()?;
        Ok(sphere)
    }

    /// Checks the centre and radius (the fields are public, so builds check again).
    pub fn validate(&self) -> Result<(), OctreeError> {
        for (axis, &value) in self.centre.iter().enumerate() {
            if !value.is_finite() {
                return Err(OctreeError::NonFiniteCentre {
                    id: self.id,
                    axis,
                    value,
                });
            }
        }
        if !(self.radius.is_finite() && self.radius > 0.0) {
            return Err(OctreeError::InvalidRadius {
                id: self.id,
                value: self.radius,
            });
        }
        Ok(())
    }
}

/// A candidate pair: sphere `j` moved by `shift` meets sphere `i`.
///
/// `i < j`, or `i == j` for a grain meeting its own periodic image (then `shift ≠ 0`).
/// The narrow phase takes `r_ij = c_j + shift − c_i` with wrapped centres. Twelve
/// bytes: a list of them is the largest array of a packing, so the shift is kept as
/// the image it comes from.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash, PartialOrd, Ord)]
pub struct Pair {
    /// The lower id.
    pub i: u32,
    /// The higher id (or `i` itself for a self-image pair).
    pub j: u32,
    /// The periodic image of `j` that meets `i`, in box lengths along each axis; zero in
    /// a walled box. At most [`MAX_IMAGES_PER_AXIS`] + 1 in size.
    pub image: [i8; 3],
}

impl Pair {
    /// The multiple of the box lengths that brings `j` next to `i`:
    /// [`BoxShape::shift`] of the image, bit for bit.
    #[inline]
    pub fn shift(&self, shape: &BoxShape) -> [f64; 3] {
        shape.shift(self.image.map(i32::from))
    }
}

/// A sphere met by a neighbour query: sphere `id` moved by `shift` meets the query.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Neighbour {
    /// The stored sphere's id.
    pub id: u32,
    /// Multiple of the box lengths that brings it next to the query centre.
    pub shift: [f64; 3],
}
