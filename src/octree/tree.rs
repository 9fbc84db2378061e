//! The tree itself: parameters, node layout and accessors.

use super::boundary::Aabb;
use super::kernel::Lanes;
use super::scratch::Scratch;
use super::{BoxShape, OctreeError};

/// Largest number of periodic images a sphere may span along one axis,
/// `⌈2 r_max / L⌉ ≤ 8`, i.e. a radius of at most four box lengths. Past that the
/// output grows as `(r/L)³` images per pair and the scene is almost surely a unit
/// mistake, so [`Octree::build`](super::Octree::build) refuses it.
pub const MAX_IMAGES_PER_AXIS: u32 = 8;

/// Limits and switches of the octree. One flat struct; see [`Params::default`].
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Params {
    /// A node with at most this many spheres is a leaf (at least 1). A bucket of large
    /// spheres, or a leaf at `max_depth`, may hold more.
    pub max_leaf_size: usize,
    /// No node is split below this depth (the root is depth 0); a leaf at this depth
    /// may hold more than `max_leaf_size` spheres, e.g. when many centres coincide.
    pub max_depth: u32,
    /// A sphere moves down into a child cell only if its radius is at most
    /// `loose_factor ×` half the child's shortest side; larger ones stay in a bucket
    /// leaf at the parent (positive and finite).
    pub loose_factor: f64,
    /// Use rayon for the pair walk when the tree holds at least
    /// [`PARALLEL_MIN_SPHERES`] spheres. The output is identical either way, order
    /// included. (The build stays on one thread: it is 10–15% of a rebuild-and-query
    /// step, so two cores could save at most ~7%.)
    pub parallel: bool,
}

/// Below this many spheres the pair walk runs on one thread whatever
/// [`Params::parallel`] says: splitting costs more than it saves. Measured on 2 cores
/// (`cargo bench --bench octree`, medians): at 1e4 spheres two threads were slower in
/// seven of eight comparisons (e.g. 2.4 → 3.0 ms walled); at 1e5 they took 12.7 against
/// 19.7 ms and at 1e6 155 against 248 ms, when the second core was free.
pub const PARALLEL_MIN_SPHERES: usize = 20_000;

impl Default for Params {
    /// `max_leaf_size = 48`, `max_depth = 16`, `loose_factor = 1.0`, `parallel = true`.
    ///
    /// Leaf size and loose factor come from `OCTREE_BENCH_QUICK=1 cargo bench --bench
    /// octree` (one thread, best of 21, build + all pairs, lognormal σ = 0.3, φ = 0.6,
    /// periodic; ms for 1e5 / 1e6 spheres): leaf 16: 36–49 / 338–376, 24: 31–44 /
    /// 346–378, 32: 26–39 / 303–318, 48: 27 / 274–300, 64: 25 / 279–289. Small leaves make
    /// many node pairs (1.4 M node tests at leaf 16 against 0.2 M at 48) and a node
    /// test costs several sphere tests, which the blocked kernel runs cheaply; past 48
    /// nothing changes. The loose factor (1 or 2) moved results by less than the noise.
    /// A depth of 16 resolves `L/65536`, far below any grain that a million-grain box
    /// holds; it only stops runaway splitting of coincident centres.
    fn default() -> Self {
        Self {
            max_leaf_size: 48,
            max_depth: 16,
            loose_factor: 1.0,
            parallel: true,
        }
    }
}

impl Params {
    /// Checks the ranges documented on each field.
    pub fn validate(&self) -> Result<(), OctreeError> {
        if self.max_leaf_size == 0 {
            return Err(OctreeError::InvalidParam {
                name: "max_leaf_size",
                value: 0.0,
            });
        }
        if !(self.loose_factor.is_finite() && self.loose_factor > 0.0) {
            return Err(OctreeError::InvalidParam {
                name: "loose_factor",
                value: self.loose_factor,
            });
        }
        Ok(())
    }
}

/// A node: a range of the sphere arrays and the exact bounds of those spheres.
///
/// Children are stored contiguously at `first_child..first_child + child_count`, after
/// their parent, and their ranges tile the parent's range in order. A leaf has
/// `child_count == 0`.
#[derive(Debug, Clone, Copy)]
pub(crate) struct Node {
    pub bounds: Aabb,
    pub start: u32,
    pub end: u32,
    pub first_child: u32,
    pub child_count: u32,
}

impl Node {
    pub fn is_leaf(&self) -> bool {
        self.child_count == 0
    }

    pub fn children(&self) -> std::ops::Range<usize> {
        self.first_child as usize..(self.first_child + self.child_count) as usize
    }

    pub fn range(&self) -> std::ops::Range<usize> {
        self.start as usize..self.end as usize
    }

    pub fn len(&self) -> u32 {
        self.end - self.start
    }
}

/// A loose octree over bounding spheres in a periodic or walled box.
///
/// Build it with [`Octree::build`], then ask for [`Octree::pairs`] or
/// [`Octree::neighbours`]. The tree owns copies of the (wrapped) centres and radii in
/// tree order; it does not borrow the caller's slice.
#[derive(Debug, Clone)]
pub struct Octree {
    pub(crate) shape: BoxShape,
    pub(crate) params: Params,
    /// Node 0 is the root (absent when there are no spheres).
    pub(crate) nodes: Vec<Node>,
    /// Spheres in tree order: every node owns a contiguous range.
    pub(crate) spheres: Lanes,
    /// Depth of the deepest node.
    pub(crate) depth: u32,
    /// Buffers reused by [`Octree::rebuild`].
    pub(super) scratch: Scratch,
}

impl Octree {
    /// Number of spheres stored.
    pub fn len(&self) -> usize {
        self.spheres.len()
    }

    /// True when no sphere is stored.
    pub fn is_empty(&self) -> bool {
        self.spheres.len() == 0
    }

    /// The box the tree was built for.
    pub fn shape(&self) -> &BoxShape {
        &self.shape
    }

    /// The parameters the tree was built with.
    pub fn params(&self) -> &Params {
        &self.params
    }

    /// Number of nodes, leaves and bucket leaves included.
    pub fn node_count(&self) -> usize {
        self.nodes.len()
    }

    /// Depth of the deepest node (the root is 0).
    pub fn depth(&self) -> u32 {
        self.depth
    }

    /// Whether the pair walk would use rayon.
    pub(crate) fn runs_parallel(&self) -> bool {
        self.params.parallel && self.len() >= PARALLEL_MIN_SPHERES
    }

    /// The slack for box-overlap tests given the largest other magnitude in play (the
    /// largest shift, plus the query box for a neighbour query); see
    /// [`OVERLAP_TOL_ULPS`](super::boundary::OVERLAP_TOL_ULPS).
    pub(crate) fn overlap_tol(&self, extra: f64) -> f64 {
        let root = self.nodes.first().map_or(0.0, |n| n.bounds.magnitude());
        super::boundary::OVERLAP_TOL_ULPS * f64::EPSILON * (root + extra)
    }
}
