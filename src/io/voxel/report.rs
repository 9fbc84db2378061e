//! How faithfully the voxels render each grain: volume, pieces, and the ellipsoid of
//! the same second moments.

use super::moments::{moments, VoxelShape};
use super::pieces::count_pieces;
use super::spans::RowSpans;
use super::{VoxelError, VoxelGrid};
use crate::contact::Dimension;
use crate::packing::PackedGrain;
use crate::scene::RveFill;

use rayon::prelude::*;
use serde::Serialize;

/// One grain as the voxels show it, next to the ellipsoid it came from. In 2D every
/// volume is an area (pixels × `hx hy`, the ellipse's `π a1 a2`), every diameter the
/// equivalent circle's, and the semi-axes are the embedded ellipsoid's
/// `[a1, √(a1 a2), a2]` (so the aspect ratio is the ellipse's `a1/a2`).
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct GrainVoxels {
    /// The grain's id.
    pub id: u32,
    /// Its material number (its index in the grains given).
    pub material: u32,
    /// Its phase index.
    pub phase: usize,
    /// Number of voxels of this material.
    pub voxels: u64,
    /// `voxels ×` the volume of a voxel.
    pub voxel_volume: f64,
    /// `4/3 π a1 a2 a3`.
    pub ellipsoid_volume: f64,
    /// `(voxel_volume − ellipsoid_volume) / ellipsoid_volume`.
    pub volume_deviation: f64,
    /// 6-connected pieces, across periodic faces (1 for a whole grain, 0 for none).
    pub pieces: u32,
    /// Voxels outside the largest piece (0 for a grain in one piece).
    pub stray_voxels: u64,
    /// `(6 V / π)^⅓` of the ellipsoid.
    pub ellipsoid_equivalent_diameter: f64,
    /// Ellipsoid semi-axes, largest first.
    pub ellipsoid_semi_axes: [f64; 3],
    /// Largest over smallest ellipsoid semi-axis.
    pub ellipsoid_aspect_ratio: f64,
    /// The voxel grain's shape from its moments; `None` when it has no voxel.
    pub shape: Option<VoxelShape>,
}

/// Every grain plus the totals.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct VoxelReport {
    /// Cells along x, y, z.
    pub cells: [usize; 3],
    /// How the gaps were filled.
    pub fill: RveFill,
    /// Largest `|volume_deviation|` over the grains.
    pub max_abs_volume_deviation: f64,
    /// Mean `|volume_deviation|` over the grains.
    pub mean_abs_volume_deviation: f64,
    /// Ids of the grains in more than one piece.
    pub split_grains: Vec<u32>,
    /// Voxels outside their grain's largest piece, summed over the grains.
    pub stray_voxels: u64,
    /// Ids of the grains without a voxel.
    pub empty_grains: Vec<u32>,
    /// Fraction of the voxels that are matrix.
    pub matrix_fraction: f64,
    /// Sum of the ellipsoid volumes over the box volume (areas in 2D).
    pub ellipsoid_fraction: f64,
    /// Ellipsoids in a box, or ellipses in a rectangle.
    #[serde(skip)]
    pub dimension: Dimension,
    /// Per grain, in material order.
    pub grains: Vec<GrainVoxels>,
}

/// Compares each voxel grain of `grid` with its ellipsoid. `grains` must be the slice
/// the grid was made from (material `k` is `grains[k]`).
pub fn grain_report(grid: &VoxelGrid, grains: &[PackedGrain]) -> Result<VoxelReport, VoxelError> {
    if grains.len() != grid.grains {
        return Err(VoxelError::GrainCountMismatch {
            grid: grid.grains,
            given: grains.len(),
        });
    }
    let spans = RowSpans::new(grid);
    let moments = moments(grid, grains, &spans);
    let pieces = count_pieces(grid, &spans, grains.len());
    let h = grid.spacing();
    let vv = grid.voxel_volume();
    let dim = grid.dimension;
    let box_volume = match dim {
        Dimension::Two => grid.size[0] * grid.size[1],
        Dimension::Three => grid.size.iter().product(),
    };
    let rows: Vec<GrainVoxels> = grains
        .iter()
        .zip(&moments)
        .zip(&pieces)
        .enumerate()
        .map(|(k, ((g, m), p))| {
            let ellipsoid_volume = dim.measure(g.semi_axes);
            let voxel_volume = m.count as f64 * vv;
            let mut axes = g.semi_axes;
            axes.sort_by(|a, b| b.total_cmp(a));
            GrainVoxels {
                id: g.id,
                material: k as u32,
                phase: g.phase,
                voxels: m.count,
                voxel_volume,
                ellipsoid_volume,
                volume_deviation: (voxel_volume - ellipsoid_volume) / ellipsoid_volume,
                pieces: p.count,
                stray_voxels: m.count - p.largest,
                ellipsoid_equivalent_diameter: dim.diameter_of(ellipsoid_volume),
                ellipsoid_semi_axes: axes,
                ellipsoid_aspect_ratio: axes[0] / axes[2],
                shape: m.shape(g, h, voxel_volume, dim),
            }
        })
        .collect();
    let deviations = rows.iter().map(|r| r.volume_deviation.abs());
    let matrix = grid.matrix_material();
    let matrix_voxels = grid.material.par_iter().filter(|&&m| m == matrix).count();
    Ok(VoxelReport {
        cells: grid.cells,
        fill: grid.fill,
        max_abs_volume_deviation: deviations.clone().fold(0.0, f64::max),
        mean_abs_volume_deviation: deviations.sum::<f64>() / rows.len().max(1) as f64,
        split_grains: rows.iter().filter(|r| r.pieces > 1).map(|r| r.id).collect(),
        stray_voxels: rows.iter().map(|r| r.stray_voxels).sum(),
        empty_grains: rows
            .iter()
            .filter(|r| r.voxels == 0)
            .map(|r| r.id)
            .collect(),
        matrix_fraction: matrix_voxels as f64 / grid.len() as f64,
        ellipsoid_fraction: rows.iter().map(|r| r.ellipsoid_volume).sum::<f64>() / box_volume,
        dimension: dim,
        grains: rows,
    })
}
