//! Typed errors of the broad phase.

use thiserror::Error;

/// Why an octree could not be built or queried.
#[derive(Debug, Clone, PartialEq, Error)]
#[non_exhaustive]
pub enum OctreeError {
    /// A box edge length is zero, negative, NaN or infinite.
    #[error("box length along axis {axis} must be positive and finite, got {value}")]
    InvalidBoxLength {
        /// Axis 0–2.
        axis: usize,
        /// The offending length.
        value: f64,
    },
    /// A centre coordinate is NaN or infinite.
    #[error("sphere {id}: centre[{axis}] is not finite: {value}")]
    NonFiniteCentre {
        /// The sphere's id.
        id: u32,
        /// Axis 0–2.
        axis: usize,
        /// The offending coordinate.
        value: f64,
    },
    /// A radius is zero, negative, NaN or infinite.
    #[error("sphere {id}: radius must be positive and finite, got {value}")]
    InvalidRadius {
        /// The sphere's id.
        id: u32,
        /// The offending radius.
        value: f64,
    },
    /// Two spheres share an id.
    #[error("sphere id {id} appears more than once")]
    DuplicateId {
        /// The repeated id.
        id: u32,
    },
    /// In a periodic box, a sphere so large that it would meet more than
    /// [`MAX_IMAGES_PER_AXIS`](super::MAX_IMAGES_PER_AXIS) images of the box along one axis.
    #[error(
        "sphere {id}: radius {radius} is too large for the periodic box length {length} \
         along axis {axis} (it would span more than {max_images} images)"
    )]
    TooLargeForBox {
        /// The sphere's id.
        id: u32,
        /// Its radius.
        radius: f64,
        /// Axis 0–2.
        axis: usize,
        /// The box length along that axis.
        length: f64,
        /// The limit, [`MAX_IMAGES_PER_AXIS`](super::MAX_IMAGES_PER_AXIS).
        max_images: u32,
    },
    /// More spheres than `u32` ids can name.
    #[error("{count} spheres exceed the u32 index range")]
    TooManySpheres {
        /// How many were given.
        count: usize,
    },
    /// A parameter is out of its documented range.
    #[error("parameter {name} is out of range: {value}")]
    InvalidParam {
        /// The field of [`Params`](super::Params).
        name: &'static str,
        /// Its value.
        value: f64,
    },
    /// A neighbour query has a non-finite centre or a negative or non-finite radius.
    #[error("neighbour query: centre {centre:?} and radius {radius} must be finite, radius ≥ 0")]
    InvalidQuery {
        /// The query centre.
        centre: [f64; 3],
        /// The query radius.
        radius: f64,
    },
}

/// A broken structural invariant, found by
/// [`Octree::check_invariants`](super::Octree::check_invariants). Any of these is a bug.
#[derive(Debug, Clone, PartialEq, Error)]
#[non_exhaustive]
pub enum InvariantViolation {
    /// The leaves do not tile the sphere array: a sphere is stored twice or not at all.
    #[error("node {node}: children's sphere ranges do not tile the node's range")]
    RangesDoNotTile {
        /// The node whose children are wrong.
        node: u32,
    },
    /// A node holds no sphere.
    #[error("node {node} is empty")]
    EmptyNode {
        /// The empty node.
        node: u32,
    },
    /// Two stored spheres share an id.
    #[error("id {id} is stored more than once")]
    DuplicateId {
        /// The repeated id.
        id: u32,
    },
    /// A leaf's bounds do not contain one of its spheres.
    #[error("leaf {node}: bounds do not contain sphere {id}")]
    BoundsMissSphere {
        /// The leaf.
        node: u32,
        /// The sphere outside its bounds.
        id: u32,
    },
    /// An internal node's bounds do not contain one of its children's bounds.
    #[error("node {node}: bounds do not contain child {child}")]
    BoundsMissChild {
        /// The parent.
        node: u32,
        /// The child sticking out.
        child: u32,
    },
    /// A stored centre of a periodic box is outside `[0, L)`.
    #[error("sphere {id}: centre[{axis}] = {value} is not wrapped into the box")]
    NotWrapped {
        /// The sphere.
        id: u32,
        /// Axis 0–2.
        axis: usize,
        /// The coordinate.
        value: f64,
    },
    /// The tree is deeper than [`Params::max_depth`](super::Params::max_depth) allows.
    #[error("node {node} is at depth {depth}, deeper than the limit")]
    TooDeep {
        /// The node.
        node: u32,
        /// Its depth.
        depth: u32,
    },
}
