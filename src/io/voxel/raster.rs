//! The fast voxeliser: grains scattered onto z-slabs, row by row, in growing shells.

use super::geometry::{image_range, prepare, reach_bound, scaled_dist2, Form, Lattice, UNASSIGNED};
use super::{VoxelError, VoxelGrid};
use crate::packing::PackedGrain;
use crate::scene::Domain;
use crate::scene::RveFill;
use rayon::prelude::*;

/// Each pass of `RveFill::Grains` scales the grains by this factor more than the last. The
/// work is the grains' volume at the final scale, which overshoots the largest `t` in
/// the box by up to this factor; a smaller one costs more passes, each with a fixed
/// cost per grain and row.
pub const GROWTH: f64 = 1.25;

/// Voxels added at each end of every interval found in closed form (rows, bounding
/// boxes). The endpoints are computed to about `√(64 ε) · (a_max / a_min) · a_max`,
/// far below one voxel unless a grain is millions of voxels long or its aspect ratio is
/// beyond 10⁶; each voxel in the widened interval is then judged by its exact `t²`.
pub const MARGIN_VOXELS: f64 = 1.0;

/// Relative rounding allowed when deciding that a row misses a grain: the row's least
/// `t²`, `m = C − B²/A`, is computed to within a few ε of `|C| + B²/A + s²`, so a row is
/// skipped only when `m − s² > 64 ε (|C| + B²/A + s²)`.
pub const ROW_ROUNDING: f64 = 64.0 * f64::EPSILON;

/// About this many slabs, so that rayon has work to balance on a few cores.
const TARGET_SLABS: usize = 64;

/// Voxelises `grains` in `domain` on a grid of `cells`; `phases` is the scene's number of
/// phases (the matrix's phase number). See the [module docs](super) for the rules and
/// the numbering.
///
/// Fails on zero or too many cells, an invalid box, an invalid grain (shape, centre,
/// phase ≥ `phases`), or `RveFill::Grains` with no grain.
pub fn voxelise(
    grains: &[PackedGrain],
    domain: &Domain,
    cells: [usize; 3],
    fill: RveFill,
    phases: usize,
) -> Result<VoxelGrid, VoxelError> {
    let lattice = Lattice::new(domain, cells)?;
    let forms = prepare(grains, &lattice, phases)?;
    if fill == RveFill::Grains && forms.is_empty() {
        return Err(VoxelError::NoGrains);
    }
    let [nx, ny, nz] = cells;
    let layers = nz.div_ceil(TARGET_SLABS);
    // Zeroed memory comes lazily from the system; each slab writes its own part.
    let mut material = vec![0; nx * ny * nz];
    let scales = Scales::new(fill, reach_bound(&forms, &lattice));
    material
        .par_chunks_mut(nx * ny * layers)
        .enumerate()
        .try_for_each_init(Buffers::default, |buffers, (s, chunk)| {
            let mut slab = Slab::new(&lattice, s * layers, chunk, buffers);
            slab.fill(&forms, scales, forms.len() as u32)
        })?;
    Ok(lattice.into_grid(fill, &forms, phases, material))
}

/// The scales of the passes: 1, then (for `RveFill::Grains`) growing by [`GROWTH`] up to
/// a scale that reaches every voxel.
#[derive(Debug, Clone, Copy)]
struct Scales {
    fill: RveFill,
    last: f64,
}

impl Scales {
    fn new(fill: RveFill, reach: f64) -> Self {
        Self {
            fill,
            last: reach.max(1.0),
        }
    }

    /// The scale after `s`, or `None` when `s` was the last.
    fn next(&self, s: f64) -> Option<f64> {
        match self.fill {
            RveFill::Matrix => None,
            RveFill::Grains if s >= self.last => None,
            RveFill::Grains => Some((s * GROWTH).min(self.last)),
        }
    }
}

/// Half-open ranges of voxel indices per axis.
type Block = [[usize; 2]; 3];

/// A slab's scratch space, reused by the slabs that one rayon task fills in turn.
#[derive(Debug, Default)]
struct Buffers {
    /// Best `t²` so far per voxel.
    best: Vec<f64>,
    /// Per row (y, z), the range of x that holds its undecided voxels (empty: none).
    open_rows: Vec<[usize; 2]>,
}

/// Whole z-layers `z0..z0 + nz` of the grid and the best `t²` found so far per voxel.
struct Slab<'a> {
    lattice: &'a Lattice,
    z0: usize,
    nz: usize,
    material: &'a mut [u32],
    best: &'a mut [f64],
    open_rows: &'a mut [[usize; 2]],
    /// Bounding block of the undecided voxels (global indices).
    open: Option<Block>,
}

impl<'a> Slab<'a> {
    fn new(
        lattice: &'a Lattice,
        z0: usize,
        material: &'a mut [u32],
        buffers: &'a mut Buffers,
    ) -> Self {
        let [nx, ny, _] = lattice.cells;
        let nz = material.len() / (nx * ny);
        material.fill(UNASSIGNED);
        buffers.best.clear();
        buffers.best.resize(material.len(), f64::INFINITY);
        buffers.open_rows.clear();
        buffers.open_rows.resize(ny * nz, [0, nx]);
        Self {
            lattice,
            z0,
            nz,
            best: &mut buffers.best,
            material,
            open_rows: &mut buffers.open_rows,
            open: Some([[0, nx], [0, ny], [z0, z0 + nz]]),
        }
    }

    /// Runs the passes until every voxel is decided; for `RveFill::Matrix`, one pass at
    /// scale 1, after which every voxel outside all grains becomes `matrix`.
    fn fill(&mut self, forms: &[Form], scales: Scales, matrix: u32) -> Result<(), VoxelError> {
        let (mut prev, mut s) = (0.0, 1.0);
        loop {
            self.pass(forms, prev, s);
            let Some(next) = scales.next(s) else { break };
            self.close(s);
            if self.open.is_none() {
                return Ok(());
            }
            (prev, s) = (s, next);
        }
        let s2 = s * s;
        let outside = self.best.iter().zip(self.material.iter_mut());
        match scales.fill {
            RveFill::Matrix => outside
                .filter(|(&b, _)| b > s2)
                .for_each(|(_, m)| *m = matrix),
            RveFill::Grains => {
                let count = outside.filter(|(&b, _)| b > s2).count();
                if count > 0 {
                    return Err(VoxelError::Unassigned { count, scale: s });
                }
            }
        }
        Ok(())
    }

    /// Evaluates every grain image at the voxels of its shell `prev < t ≤ s` that lie in
    /// the open block.
    fn pass(&mut self, forms: &[Form], prev: f64, s: f64) {
        let Some(open) = self.open else { return };
        let lat = *self.lattice;
        for (g, form) in forms.iter().enumerate() {
            let reach = [0, 1, 2].map(|a| s * form.half[a] + MARGIN_VOXELS * lat.h[a]);
            let ranges = [0, 1, 2].map(|a| {
                let lo = lat.coord(a, open[a][0]);
                let hi = lat.coord(a, open[a][1] - 1);
                image_range(&lat, a, form.centre[a], reach[a], lo, hi)
            });
            for kz in ranges[2].clone() {
                for ky in ranges[1].clone() {
                    for kx in ranges[0].clone() {
                        let c = [
                            lat.image(0, form.centre[0], kx),
                            lat.image(1, form.centre[1], ky),
                            lat.image(2, form.centre[2], kz),
                        ];
                        self.rasterise(g as u32, form, c, reach, &open, prev, s);
                    }
                }
            }
        }
    }

    /// One grain image at centre `c`, over the rows of `open` within `reach` of `c`.
    #[allow(clippy::too_many_arguments)]
    fn rasterise(
        &mut self,
        g: u32,
        form: &Form,
        c: [f64; 3],
        reach: [f64; 3],
        open: &Block,
        prev: f64,
        s: f64,
    ) {
        let lat = self.lattice;
        let [nx, ny, _] = lat.cells;
        let p = &form.p;
        let (s2, prev2) = (s * s, prev * prev);
        let [zs, ys] = [2, 1].map(|a| index_span(c[a] - reach[a], c[a] + reach[a], lat.h[a]));
        let z_lo = zs[0].max(open[2][0]);
        let z_hi = zs[1].min(open[2][1]);
        let y_lo = ys[0].max(open[1][0]);
        let y_hi = ys[1].min(open[1][1]);
        for z in z_lo..z_hi {
            let dz = lat.coord(2, z) - c[2];
            for y in y_lo..y_hi {
                let row = y + ny * (z - self.z0);
                let [row_lo, row_hi] = self.open_rows[row];
                if row_lo >= row_hi {
                    continue;
                }
                let dy = lat.coord(1, y) - c[1];
                // Along the row t² = A dx² + 2 B dx + C, least at dx = −B/A, where it is m.
                let a = p[0];
                let b = p[1] * dy + p[2] * dz;
                let cc = dy * (p[3] * dy + p[4] * dz) + dz * (p[4] * dy + p[5] * dz);
                let b2a = b * b / a;
                let m = cc - b2a;
                let slack = ROW_ROUNDING * (cc.abs() + b2a + s2);
                if m - s2 > slack {
                    continue;
                }
                let x0 = c[0] - b / a;
                let w = ((s2 - m).max(0.0) / a).sqrt();
                let [x_lo, x_hi] = index_span(x0 - w, x0 + w, lat.h[0]);
                let (x_lo, x_hi) = (x_lo.max(row_lo), x_hi.min(row_hi));
                // The core t ≤ prev (shrunk by the margin) was decided in earlier passes.
                let [in_lo, in_hi] = if prev2 - m > slack {
                    let wi = ((prev2 - m) / a).sqrt();
                    inner_span(x0 - wi, x0 + wi, lat.h[0])
                } else {
                    [0, 0]
                };
                let base = nx * row;
                for xs in [x_lo..x_hi.min(in_lo), x_lo.max(in_hi)..x_hi] {
                    for x in xs {
                        let v = base + x;
                        let best = self.best[v];
                        if best <= prev2 {
                            continue;
                        }
                        let t2 = scaled_dist2(p, [lat.coord(0, x) - c[0], dy, dz]);
                        if t2 < best || (t2 == best && g < self.material[v]) {
                            self.best[v] = t2;
                            self.material[v] = g;
                        }
                    }
                }
            }
        }
    }

    /// Marks the voxels with best `t ≤ s` as decided and shrinks the open rows and block.
    fn close(&mut self, s: f64) {
        let [nx, ny, _] = self.lattice.cells;
        let s2 = s * s;
        let mut block: Option<Block> = None;
        for z in 0..self.nz {
            for y in 0..ny {
                let row = y + ny * z;
                let [lo, hi] = self.open_rows[row];
                if lo >= hi {
                    continue;
                }
                let best = &self.best[nx * row + lo..nx * row + hi];
                let Some(first) = best.iter().position(|&b| b > s2) else {
                    self.open_rows[row] = [0, 0];
                    continue;
                };
                let last = best.iter().rposition(|&b| b > s2).unwrap_or(first);
                let (first, last) = (lo + first, lo + last);
                self.open_rows[row] = [first, last + 1];
                let gz = z + self.z0;
                let b = block.get_or_insert([[first, last + 1], [y, y + 1], [gz, gz + 1]]);
                b[0] = [b[0][0].min(first), b[0][1].max(last + 1)];
                b[1] = [b[1][0].min(y), b[1][1].max(y + 1)];
                b[2] = [b[2][0].min(gz), b[2][1].max(gz + 1)];
            }
        }
        self.open = block;
    }
}

/// Indices of the cells whose centres may lie in `[lo, hi]`, widened by
/// [`MARGIN_VOXELS`], as a half-open range (possibly empty, unclamped above).
fn index_span(lo: f64, hi: f64, h: f64) -> [usize; 2] {
    let first = (lo / h - 0.5).ceil() - MARGIN_VOXELS;
    let last = (hi / h - 0.5).floor() + MARGIN_VOXELS;
    [to_index(first), to_index(last + 1.0)]
}

/// Indices of the cells whose centres surely lie in `[lo, hi]`: shrunk by
/// [`MARGIN_VOXELS`].
fn inner_span(lo: f64, hi: f64, h: f64) -> [usize; 2] {
    let first = (lo / h - 0.5).ceil() + MARGIN_VOXELS;
    let last = (hi / h - 0.5).floor() - MARGIN_VOXELS;
    let [a, b] = [to_index(first), to_index(last + 1.0)];
    [a, b.max(a)]
}

/// A cell index from a float: negative values give 0, and huge ones saturate.
fn to_index(x: f64) -> usize {
    if x <= 0.0 {
        0
    } else {
        x as usize
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn index_span_holds_every_cell_centre_in_the_interval_plus_a_margin() {
        // Cells of width 0.5: centres at 0.25, 0.75, 1.25, ...
        let [lo, hi] = index_span(0.7, 1.3, 0.5);
        // Centres 0.75 and 1.25 (cells 1, 2) lie inside; one more each side.
        assert_eq!([lo, hi], [0, 4]);
        // An interval below zero clamps to an empty range at 0.
        assert_eq!(index_span(-9.0, -5.0, 0.5), [0, 0]);
    }

    #[test]
    fn inner_span_holds_only_cells_whose_centres_are_inside() {
        let [lo, hi] = inner_span(0.2, 2.3, 0.5);
        // Centres inside: 0.25 ... 2.25 (cells 0–4); shrunk by one each side.
        assert_eq!([lo, hi], [1, 4]);
        for i in lo..hi {
            let x = (i as f64 + 0.5) * 0.5;
            assert!((0.2..=2.3).contains(&x));
        }
        let [lo, hi] = inner_span(0.2, 0.3, 0.5);
        assert!(lo >= hi, "too narrow to hold a cell for sure: {lo}..{hi}");
    }

    #[test]
    fn scales_grow_to_the_last_and_stop_there() {
        assert_eq!(Scales::new(RveFill::Matrix, 10.0).next(1.0), None);
        let s = Scales::new(RveFill::Grains, 2.0);
        let mut seq = vec![1.0];
        while let Some(next) = s.next(*seq.last().unwrap()) {
            seq.push(next);
        }
        assert_eq!(seq, [1.0, GROWTH, GROWTH * GROWTH, GROWTH.powi(3), 2.0]);
        // A bound below 1 still runs the pass at 1.
        assert_eq!(Scales::new(RveFill::Grains, 0.5).next(1.0), None);
    }
}
