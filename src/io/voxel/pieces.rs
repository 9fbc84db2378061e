//! Connected pieces of each material: 6-connectivity, across the faces of a periodic box.
//! A 2D grid (one layer along z) has no neighbour along z but the cell itself, so there
//! the same code gives 4-connectivity in the plane.
//!
//! Each row along x is cut into spans of one material; spans are joined (union–find) with
//! the overlapping spans of the same material in the rows below in y and in z, and, in a
//! periodic box, across the x, y and z faces. A material's pieces are its distinct roots.
//! RowSpans are far fewer than voxels, so this takes little time and memory.

use super::spans::{RowSpans, Span};
use super::VoxelGrid;

/// The 6-connected pieces of one material.
#[derive(Debug, Clone, Copy, Default, PartialEq, Eq)]
pub(super) struct Pieces {
    /// How many.
    pub count: u32,
    /// Voxels in the largest.
    pub largest: u64,
}

/// The pieces of each material `0..materials` (periodic-aware).
pub(super) fn count_pieces(grid: &VoxelGrid, all: &RowSpans, materials: usize) -> Vec<Pieces> {
    let [_, ny, nz] = grid.cells;
    let row_spans = |r: usize| all.row(r);
    let spans = &all.spans;
    let mut sets = UnionFind::new(spans.len());
    for z in 0..nz {
        for y in 0..ny {
            let row = y + ny * z;
            let own = row_spans(row);
            if grid.periodic && own.len() > 1 {
                let (first, last) = (own.start, own.end - 1);
                if spans[first].material == spans[last].material {
                    sets.union(first, last);
                }
            }
            let below_y = match y {
                0 if grid.periodic => Some(ny - 1),
                0 => None,
                _ => Some(y - 1),
            };
            let below_z = match z {
                0 if grid.periodic => Some(nz - 1),
                0 => None,
                _ => Some(z - 1),
            };
            if let Some(by) = below_y {
                join_rows(spans, own.clone(), row_spans(by + ny * z), &mut sets);
            }
            if let Some(bz) = below_z {
                join_rows(spans, own.clone(), row_spans(y + ny * bz), &mut sets);
            }
        }
    }
    let mut size = vec![0u64; spans.len()];
    for (r, span) in spans.iter().enumerate() {
        size[sets.find(r)] += u64::from(span.end - span.start);
    }
    let mut pieces = vec![Pieces::default(); materials];
    for (r, span) in spans.iter().enumerate() {
        if sets.find(r) == r {
            if let Some(p) = pieces.get_mut(span.material as usize) {
                p.count += 1;
                p.largest = p.largest.max(size[r]);
            }
        }
    }
    pieces
}

/// Joins the overlapping spans of one material in two rows (each sorted by start).
fn join_rows(
    spans: &[Span],
    a: std::ops::Range<usize>,
    b: std::ops::Range<usize>,
    sets: &mut UnionFind,
) {
    let (mut i, mut j) = (a.start, b.start);
    while i < a.end && j < b.end {
        let (ra, rb) = (spans[i], spans[j]);
        if ra.material == rb.material && ra.start < rb.end && rb.start < ra.end {
            sets.union(i, j);
        }
        if ra.end <= rb.end {
            i += 1;
        } else {
            j += 1;
        }
    }
}

/// Disjoint sets with path halving and union by index (the smaller root wins).
struct UnionFind {
    parent: Vec<u32>,
}

impl UnionFind {
    fn new(n: usize) -> Self {
        Self {
            parent: (0..n as u32).collect(),
        }
    }

    fn find(&mut self, mut x: usize) -> usize {
        while self.parent[x] as usize != x {
            let grand = self.parent[self.parent[x] as usize];
            self.parent[x] = grand;
            x = grand as usize;
        }
        x
    }

    fn union(&mut self, a: usize, b: usize) {
        let (ra, rb) = (self.find(a), self.find(b));
        if ra != rb {
            let (lo, hi) = (ra.min(rb), ra.max(rb));
            self.parent[hi] = lo as u32;
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::scene::RveFill;

    fn grid(cells: [usize; 3], periodic: bool, material: Vec<u32>) -> VoxelGrid {
        VoxelGrid {
            cells,
            size: cells.map(|n| n as f64),
            dimension: crate::contact::Dimension::Three,
            periodic,
            fill: RveFill::Matrix,
            grains: 2,
            phases: 1,
            phase: vec![0; material.len()],
            material,
        }
    }

    fn count_pieces_of(grid: &VoxelGrid, materials: usize) -> Vec<Pieces> {
        count_pieces(grid, &RowSpans::new(grid), materials)
    }

    fn counts(p: Vec<Pieces>) -> Vec<u32> {
        p.iter().map(|p| p.count).collect()
    }

    #[test]
    fn a_run_split_by_another_material_is_two_pieces_unless_it_wraps() {
        // One row: 0 0 1 0. Walled: {0,1} and {3} are apart; periodic: 3 touches 0.
        let m = vec![0, 0, 1, 0];
        assert_eq!(
            counts(count_pieces_of(&grid([4, 1, 1], false, m.clone()), 2)),
            [2, 1]
        );
        assert_eq!(
            counts(count_pieces_of(&grid([4, 1, 1], true, m), 2)),
            [1, 1]
        );
    }

    #[test]
    fn diagonal_neighbours_are_not_connected() {
        // 2×2 in xy: 0 at (0,0) and (1,1), 1 elsewhere; walled, so 0 is two pieces.
        let m = vec![0, 1, 1, 0];
        assert_eq!(
            counts(count_pieces_of(&grid([2, 2, 1], false, m), 2)),
            [2, 2]
        );
    }

    #[test]
    fn pixels_of_one_layer_are_four_connected_even_periodic() {
        // 3×3 periodic pixels: material 0 on the diagonal, 1 elsewhere. The diagonal
        // pixels touch only at corners (also across the faces), so they stay apart;
        // material 1's six pixels join through the faces into one piece.
        let m = vec![0, 1, 1, 1, 0, 1, 1, 1, 0];
        let p = count_pieces_of(&grid([3, 3, 1], true, m), 2);
        assert_eq!(counts(p), [3, 1]);
    }

    #[test]
    fn layers_join_across_z_and_the_periodic_z_face() {
        // 1×1×3 column: 0, 1, 0.
        let m = vec![0, 1, 0];
        assert_eq!(
            counts(count_pieces_of(&grid([1, 1, 3], false, m.clone()), 2)),
            [2, 1]
        );
        assert_eq!(
            counts(count_pieces_of(&grid([1, 1, 3], true, m), 2)),
            [1, 1]
        );
    }

    #[test]
    fn the_largest_piece_counts_its_voxels_across_rows() {
        // 3×2 walled: row 0 = 0 0 1, row 1 = 1 0 1. Material 0 is one piece of 3,
        // material 1 two pieces of 2 and 1.
        let m = vec![0, 0, 1, 1, 0, 1];
        let p = count_pieces_of(&grid([3, 2, 1], false, m), 2);
        assert_eq!(
            p[0],
            Pieces {
                count: 1,
                largest: 3
            }
        );
        assert_eq!(
            p[1],
            Pieces {
                count: 2,
                largest: 2
            }
        );
    }
}
