//! The grid as runs: maximal stretches of one material along x, row by row. Grains
//! span many voxels, so runs are far fewer than voxels; connectivity and moments work
//! on them.

use super::VoxelGrid;
use rayon::prelude::*;

/// Cells `start..end` of one row, all of one material.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub(super) struct Run {
    pub start: u32,
    pub end: u32,
    pub material: u32,
}

/// Every row's runs, in row order (row `y + Ny z`).
#[derive(Debug, Clone)]
pub(super) struct Runs {
    pub runs: Vec<Run>,
    /// Row `r`'s runs are `runs[row_start[r]..row_start[r + 1]]`.
    pub row_start: Vec<usize>,
}

impl Runs {
    /// Cuts every row into runs (in parallel over z-layers).
    pub fn new(grid: &VoxelGrid) -> Self {
        let [nx, ny, _] = grid.cells;
        let layers: Vec<(Vec<Run>, Vec<usize>)> = grid
            .material
            .par_chunks(nx * ny)
            .map(|layer| {
                let mut runs = Vec::new();
                let mut counts = Vec::with_capacity(ny);
                for row in layer.chunks_exact(nx) {
                    let before = runs.len();
                    let mut start = 0;
                    for x in 1..=nx {
                        if x == nx || row[x] != row[start] {
                            runs.push(Run {
                                start: start as u32,
                                end: x as u32,
                                material: row[start],
                            });
                            start = x;
                        }
                    }
                    counts.push(runs.len() - before);
                }
                (runs, counts)
            })
            .collect();
        let total = layers.iter().map(|(r, _)| r.len()).sum();
        let mut runs = Vec::with_capacity(total);
        let mut row_start = Vec::with_capacity(grid.cells[1] * grid.cells[2] + 1);
        let mut at = 0;
        for (layer, counts) in layers {
            for c in counts {
                row_start.push(at);
                at += c;
            }
            runs.extend(layer);
        }
        row_start.push(at);
        Self { runs, row_start }
    }

    /// The index range of row `r`'s runs.
    pub fn row(&self, r: usize) -> std::ops::Range<usize> {
        self.row_start[r]..self.row_start[r + 1]
    }
}
