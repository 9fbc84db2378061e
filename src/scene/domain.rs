//! The box the grains are packed into.

pub use crate::octree::Boundary;
use crate::octree::{BoxShape, OctreeError};

/// The box `[0, Lx) × [0, Ly) × [0, Lz)` and its boundary.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Domain {
    /// Edge lengths `[Lx, Ly, Lz]`, positive and finite.
    pub size: [f64; 3],
    /// Periodic or walled.
    pub boundary: Boundary,
}

impl Domain {
    /// `Lx·Ly·Lz`.
    pub fn volume(&self) -> f64 {
        self.size.iter().product()
    }

    /// The shortest edge.
    pub fn min_side(&self) -> f64 {
        self.size.iter().copied().fold(f64::INFINITY, f64::min)
    }

    /// The box as the broad phase sees it: the same lengths and boundary, checked
    /// positive and finite.
    pub fn box_shape(&self) -> Result<BoxShape, OctreeError> {
        BoxShape::new(self.size, self.boundary)
    }
}
