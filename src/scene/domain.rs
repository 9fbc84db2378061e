//! The box the grains are packed into.

use crate::contact::Dimension;
pub use crate::octree::Boundary;
use crate::octree::{BoxShape, OctreeError};

/// The box `[0, Lx) × [0, Ly) × [0, Lz)` and its boundary.
///
/// A 2D domain (the rectangle `[0, Lx) × [0, Ly)`, [`Domain::plane`]) is held as the
/// slab of thickness `Lz = max(Lx, Ly)` whose mid-plane `z = Lz/2` the ellipses lie in
/// (see [`Dimension`]): no grain reaches a `z` face, so the broad phase finds no `z`
/// image and no `z` wall. Its measure ([`Domain::volume`]) is the area `Lx·Ly`.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Domain {
    /// Edge lengths `[Lx, Ly, Lz]`, positive and finite.
    pub size: [f64; 3],
    /// Periodic or walled.
    pub boundary: Boundary,
    /// Ellipsoids in a box or ellipses in a rectangle.
    pub dimension: Dimension,
}

impl Domain {
    /// The 3D box with edges `size`.
    pub const fn new(size: [f64; 3], boundary: Boundary) -> Self {
        Self {
            size,
            boundary,
            dimension: Dimension::Three,
        }
    }

    /// The 2D rectangle `[0, Lx) × [0, Ly)`, as the slab described above.
    pub fn plane(size: [f64; 2], boundary: Boundary) -> Self {
        Self {
            size: [size[0], size[1], size[0].max(size[1])],
            boundary,
            dimension: Dimension::Two,
        }
    }

    /// The box's measure: `Lx·Ly·Lz`, or the rectangle's area `Lx·Ly` in 2D.
    pub fn volume(&self) -> f64 {
        self.sides().iter().product()
    }

    /// The edges the grains are packed along: `[Lx, Ly, Lz]`, or `[Lx, Ly]` in 2D.
    pub fn sides(&self) -> &[f64] {
        match self.dimension {
            Dimension::Two => &self.size[..2],
            Dimension::Three => &self.size,
        }
    }

    /// The shortest edge (of the rectangle, in 2D).
    pub fn min_side(&self) -> f64 {
        self.sides().iter().copied().fold(f64::INFINITY, f64::min)
    }

    /// Where a 2D grain's centre lies along `z` (the slab's mid-plane); 0 in 3D.
    pub fn plane_z(&self) -> f64 {
        match self.dimension {
            Dimension::Two => 0.5 * self.size[2],
            Dimension::Three => 0.0,
        }
    }

    /// The box as the broad phase sees it: the same lengths and boundary, checked
    /// positive and finite.
    pub fn box_shape(&self) -> Result<BoxShape, OctreeError> {
        BoxShape::new(self.size, self.boundary)
    }
}
