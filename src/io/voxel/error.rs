//! Why a voxel grid could not be made, checked or written.

use crate::contact::ShapeError;
use thiserror::Error;

/// Why [`voxelise`](super::voxelise) or one of its companions failed.
#[derive(Debug, Error)]
#[non_exhaustive]
pub enum VoxelError {
    /// A cell count is zero.
    #[error("voxel cells must be positive: cells[{axis}] = 0")]
    ZeroCells {
        /// Axis 0–2.
        axis: usize,
    },
    /// A 2D box asked for more than one layer of cells along z.
    #[error("a 2D grid has one layer of cells along z, not {cells}")]
    PlaneLayers {
        /// The cells asked for along z.
        cells: usize,
    },
    /// The grid is larger than a 32-bit signed index can address.
    #[error("{cells:?} voxels are too many: at most {max} cells in all")]
    TooManyCells {
        /// The cell counts asked for.
        cells: [usize; 3],
        /// [`MAX_CELLS`](super::MAX_CELLS).
        max: usize,
    },
    /// A box edge is not positive and finite.
    #[error("domain size[{axis}] = {value} must be positive and finite")]
    InvalidDomain {
        /// Axis 0–2.
        axis: usize,
        /// The edge length.
        value: f64,
    },
    /// More grains than 32-bit signed material numbers can hold.
    #[error("{count} grains are too many for Int32 material numbers")]
    TooManyGrains {
        /// The number of grains.
        count: usize,
    },
    /// `fill = grains` with no grain to fill the box with.
    #[error("fill = grains needs at least one grain")]
    NoGrains,
    /// A grain's shape or orientation is invalid.
    #[error("grain {id}: {source}")]
    Shape {
        /// The grain's id.
        id: u32,
        /// What is wrong with it.
        #[source]
        source: ShapeError,
    },
    /// A grain's centre is NaN or infinite.
    #[error("grain {id}: centre is not finite: {centre:?}")]
    NonFiniteCentre {
        /// The grain's id.
        id: u32,
        /// Its centre.
        centre: [f64; 3],
    },
    /// A grain's phase is not one of the scene's phases.
    #[error("grain {id}: phase {phase} but the scene has {phases} phases")]
    PhaseOutOfRange {
        /// The grain's id.
        id: u32,
        /// Its phase index.
        phase: usize,
        /// The number of phases.
        phases: usize,
    },
    /// The grains given to the report are not the ones the grid was made from.
    #[error("the grid was made from {grid} grains but {given} were given")]
    GrainCountMismatch {
        /// Grains in the grid.
        grid: usize,
        /// Grains passed in.
        given: usize,
    },
    /// Voxels left without a grain after the last pass (a bug: the last scale reaches
    /// every voxel by construction).
    #[error("{count} voxels left without a grain at scale {scale}")]
    Unassigned {
        /// How many.
        count: usize,
        /// The last scale tried.
        scale: f64,
    },
    /// Drawing the sections failed.
    #[error("drawing the sections: {0}")]
    Plot(String),
    /// Writing failed.
    #[error(transparent)]
    Io(#[from] std::io::Error),
}
