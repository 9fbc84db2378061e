//! The grid as spans (runs): maximal stretches of one material along x, row by row. Grains
//! span many voxels, so spans are far fewer than voxels; connectivity and moments work
//! on them.

use super::VoxelGrid;
use rayon::prelude::*;

/// Cells `start..end` of one row, all of one material.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub(super) struct Span {
    pub start: u32,
    pub end: u32,
    pub material: u32,
}

/// Every row's spans, in row order (row `y + Ny z`).
#[derive(Debug, Clone)]
pub(super) struct RowSpans {
    pub spans: Vec<Span>,
    /// Row `r`'s spans are `spans[row_start[r]..row_start[r + 1]]`.
    pub row_start: Vec<usize>,
}

impl RowSpans {
    /// Cuts every row into spans (in parallel over z-layers).
    pub fn new(grid: &VoxelGrid) -> Self {
        let [nx, ny, _] = grid.cells;
        let layers: Vec<(Vec<Span>, Vec<usize>)> = grid
            .material
            .par_chunks(nx * ny)
            .map(|layer| {
                let mut spans = Vec::new();
                let mut counts = Vec::with_capacity(ny);
                for row in layer.chunks_exact(nx) {
                    let before = spans.len();
                    let mut start = 0;
                    for x in 1..=nx {
                        if x == nx || row[x] != row[start] {
                            spans.push(Span {
                                start: start as u32,
                                end: x as u32,
                                material: row[start],
                            });
                            start = x;
                        }
                    }
                    counts.push(spans.len() - before);
                }
                (spans, counts)
            })
            .collect();
        let total = layers.iter().map(|(r, _)| r.len()).sum();
        let mut spans = Vec::with_capacity(total);
        let mut row_start = Vec::with_capacity(grid.cells[1] * grid.cells[2] + 1);
        let mut at = 0;
        for (layer, counts) in layers {
            for c in counts {
                row_start.push(at);
                at += c;
            }
            spans.extend(layer);
        }
        row_start.push(at);
        Self { spans, row_start }
    }

    /// The index range of row `r`'s spans.
    pub fn row(&self, r: usize) -> std::ops::Range<usize> {
        self.row_start[r]..self.row_start[r + 1]
    }
}
