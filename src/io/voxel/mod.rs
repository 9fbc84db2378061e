//! The voxel RVE: packed grains sampled on a regular grid, for FFT solvers (DAMASK).
//!
//! [`voxelise`] assigns every voxel (cell) of an `Nx × Ny × Nz` grid over the box a
//! material, judged at the voxel centre `x = ((i + ½) Lx/Nx, (j + ½) Ly/Ny, (k + ½) Lz/Nz)`.
//! [`write_vti`] writes the grid as VTK XML ImageData (`rve.vti`), which
//! `damask.GeomGrid.load` reads; [`grain_report`] compares each voxel grain with its
//! ellipsoid; [`write_sections_png`] draws three orthogonal mid-sections.
//!
//! # Two dimensions
//! A 2D box (ellipses in a rectangle, [`Domain::plane`](crate::scene::Domain::plane))
//! gives a pixel image: one layer of cells along z (`cells = [Nx, Ny, 1]`), as DAMASK's
//! grid solver takes a 2D (plane) grid. The layer is rasterised by the same code at
//! its centre, the grains' plane `z = Lz/2`, where each ellipsoid's `t` is its
//! ellipse's (the embedded form is block diagonal: `t² = dᵀ P d` with `d_z = 0` is the
//! 2×2 form of the ellipse), so a pixel belongs to the ellipse containing its centre.
//! The grid's z edge is then the layer's thickness [`layer_thickness`] (`√(hx hy)`, a
//! cube for square pixels), not the slab's `Lz`. Pieces are 4-connected (the 6
//! neighbours of a cell less the two along z, which are itself), and the report
//! measures areas (see [`grain_report`]).
//!
//! # Which grain a voxel belongs to
//! Grain `g` with centre `c` and quadratic form `Q = R diag(a²) Rᵀ` reaches `x` when
//! scaled by `t_g(x) = √((x − c)ᵀ Q⁻¹ (x − c))`: inside the grain `t ≤ 1`. In a periodic
//! box `c` runs over all images `c + (kx Lx, ky Ly, kz Lz)`, so grains crossing a face
//! appear on both sides and the fields are periodic; a reflecting box has no images.
//! - [`RveFill::Matrix`]: a voxel whose centre lies in a grain (`t ≤ 1`) is that grain's,
//!   every other voxel is the matrix.
//! - [`RveFill::Grains`]: every voxel goes to the grain of smallest `t`, the one that must
//!   be scaled least to reach it (a Voronoi tessellation in the grains' own metrics).
//!
//! In both modes a voxel inside several grains (only possible if they overlap) goes to
//! the smallest `t` too, and ties go to the lower material number, so the result is
//! unique. [`brute_force_voxelise`] computes it by looping over every grain and image for
//! every voxel; the tests require [`voxelise`] to give the identical field.
//!
//! # Material and phase numbering
//! - Material `k` is the `k`-th grain of the slice passed in, which is grain id `k` for
//!   the grains `pack` writes (ids `0..n−1` in order). When `fill = matrix`, the matrix
//!   is material `n` (the number of grains). A DAMASK `material.yaml` therefore lists the
//!   grains first, in id order, then the matrix.
//! - The `phase` array holds the grain's phase index in the scene (`0..phases−1`), and
//!   the matrix is phase `phases` (the scene's number of phases).
//!
//! # How it is fast
//! Grains are scattered onto voxels, not voxels gathered from grains: no voxel ever loops
//! over all grains. The grid is cut into slabs of whole z-layers, filled in parallel
//! (rayon), each on its own. A slab rasterises every grain image whose (scaled) bounding
//! box meets it, row by row along x: on a row, `t²` is a quadratic in x, so the voxels
//! with `t ≤ s` form an interval found in closed form, and only those are evaluated.
//! `RveFill::Matrix` is one pass at scale `s = 1`. `RveFill::Grains` goes on with scales
//! growing by [`GROWTH`], each pass evaluating only the shell `s_prev < t ≤ s` of each
//! grain, and only within the x-range of each row (and the block of the slab) that still
//! holds undecided voxels. A voxel is decided after the pass at scale `s` once its best
//! `t ≤ s`: every grain with `t ≤ s` there has then been evaluated, so none can do
//! better later. The last scale is one at which some grain reaches every voxel (the
//! farthest voxel over the inscribed radius), so every voxel is decided. The work is
//! about the volume of the grains scaled by the largest `t` in the box, a few evaluations
//! per voxel for a dense packing, and the memory is 8 bytes per voxel (the two arrays)
//! plus a slab of scratch per thread. A uniform cell list or the octree would be queried
//! once per voxel and its candidates tested there, which is what this avoids. The result
//! does not depend on the slabs or the thread count.
//!
//! ```
//! use grainpack::scene::{Boundary, Domain};
//! use grainpack::io::voxel::voxelise;
//! use grainpack::scene::RveFill;
//! use grainpack::packing::PackedGrain;
//! let grain = PackedGrain {
//!     id: 0, phase: 0, centre: [0.0; 3], semi_axes: [3.0, 2.0, 2.0],
//!     quaternion: [1.0, 0.0, 0.0, 0.0],
//! };
//! let domain = Domain::new([10.0; 3], Boundary::Periodic);
//! let grid = voxelise(&[grain], &domain, [10, 10, 10], RveFill::Matrix, 1).unwrap();
//! // The grain sits on a corner: it shows in all eight corners of the periodic box.
//! assert_eq!(grid.material[grid.index(0, 0, 0)], 0);
//! assert_eq!(grid.material[grid.index(9, 9, 9)], 0);
//! assert_eq!(grid.material[grid.index(5, 5, 5)], grid.matrix_material());
//! ```

mod brute;
mod error;
mod geometry;
mod moments;
mod pieces;
mod raster;
mod report;
mod sections;
mod spans;
mod vti;

pub use brute::brute_force_voxelise;
pub use error::VoxelError;
pub use geometry::MAX_CELLS;
pub use moments::VoxelShape;
pub use raster::{voxelise, GROWTH, MARGIN_VOXELS, ROW_ROUNDING};
pub use report::{grain_report, GrainVoxels, VoxelReport};
pub use sections::write_sections_png;
pub use vti::{write_vti, EULER_ARRAYS};

use crate::contact::Dimension;
use crate::scene::RveFill;

/// The z edge of a 2D grid's one layer of cells: `√(hx hy)` for pixels of edges `hx`,
/// `hy`, so that the cells are cubes when the pixels are square.
pub fn layer_thickness(hx: f64, hy: f64) -> f64 {
    (hx * hy).sqrt()
}

/// The voxel grid: a material and a phase number per cell, x fastest, then y, then z.
#[derive(Debug, Clone, PartialEq)]
pub struct VoxelGrid {
    /// Cells along x, y and z.
    pub cells: [usize; 3],
    /// Edge lengths of the box `[Lx, Ly, Lz]`; the grid's origin is 0. In 2D, `Lz` is
    /// the thickness of the one layer ([`layer_thickness`]).
    pub size: [f64; 3],
    /// A box of grains (3D) or a pixel image of one layer (2D).
    pub dimension: Dimension,
    /// Whether the box (and so the field) is periodic.
    pub periodic: bool,
    /// How the gaps were filled.
    pub fill: RveFill,
    /// Number of grains `n`: materials `0..n−1` are grains, `n` the matrix.
    pub grains: usize,
    /// Number of phases in the scene: the matrix is phase `phases`.
    pub phases: usize,
    /// Material of cell `(i, j, k)` at [`VoxelGrid::index`].
    pub material: Vec<u32>,
    /// Phase of cell `(i, j, k)` at [`VoxelGrid::index`].
    pub phase: Vec<u32>,
}

impl VoxelGrid {
    /// Index of cell `(i, j, k)` in `material` and `phase`: `i + Nx (j + Ny k)`.
    pub fn index(&self, i: usize, j: usize, k: usize) -> usize {
        i + self.cells[0] * (j + self.cells[1] * k)
    }

    /// Total number of cells `Nx Ny Nz`.
    pub fn len(&self) -> usize {
        self.material.len()
    }

    /// Whether the grid has no cells (never, for a grid from [`voxelise`]).
    pub fn is_empty(&self) -> bool {
        self.material.is_empty()
    }

    /// Cell edge lengths `L/N`.
    pub fn spacing(&self) -> [f64; 3] {
        [0, 1, 2].map(|a| self.size[a] / self.cells[a] as f64)
    }

    /// Volume of one cell; in 2D the area of one pixel `hx hy`.
    pub fn voxel_volume(&self) -> f64 {
        let h = self.spacing();
        match self.dimension {
            Dimension::Two => h[0] * h[1],
            Dimension::Three => h.iter().product(),
        }
    }

    /// The matrix's material number `n` (used by no cell when `fill = grains`).
    pub fn matrix_material(&self) -> u32 {
        self.grains as u32
    }

    /// The matrix's phase number: the scene's number of phases.
    pub fn matrix_phase(&self) -> u32 {
        self.phases as u32
    }
}
