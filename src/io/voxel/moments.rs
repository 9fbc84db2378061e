//! Exact second moments of each grain's voxels, summed span by span.

use super::spans::RowSpans;
use super::VoxelGrid;
use crate::contact::{rotation_matrix, Dimension, PLANE_NORMAL};
use crate::packing::PackedGrain;
use nalgebra::{Matrix2, Matrix3, SymmetricEigen, Vector3};
use rayon::prelude::*;
use serde::Serialize;

/// The solid ellipsoid with the same volume centroid and second moments as a voxel
/// grain (each voxel a uniform cube, so its own moment `h²/12` is included).
///
/// A solid ellipsoid's covariance has eigenvalues `a_k² / 5`, so `a_k = √(5 λ_k)`.
/// In 2D, the solid ellipse of the same in-plane moments (eigenvalues `a_k² / 4`, so
/// `a_k = 2 √λ_k`), given as the ellipsoid it embeds in (`[a1, √(a1 a2), a2]`, the
/// third axis along z in the middle), with the circle's equivalent diameter.
/// Voxels are unwrapped around the grain centre (nearest image, per axis): a grain
/// whose voxels span more than half the box along an axis is not unwrapped correctly.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct VoxelShape {
    /// `(6 V / π)^⅓` of the voxel volume (`√(4 A / π)` of the pixel area in 2D).
    pub equivalent_diameter: f64,
    /// Semi-axes `√(5 λ_k)`, largest first.
    pub semi_axes: [f64; 3],
    /// Unit principal directions: `axes[k]` goes with `semi_axes[k]`.
    pub axes: [[f64; 3]; 3],
    /// `semi_axes[0] / semi_axes[2]`.
    pub aspect_ratio: f64,
    /// `b/a = semi_axes[1] / semi_axes[0]` (DREAM.3D's first shape ratio).
    pub b_over_a: f64,
    /// `c/a = semi_axes[2] / semi_axes[0]`.
    pub c_over_a: f64,
    /// `c/b = semi_axes[2] / semi_axes[1]`.
    pub c_over_b: f64,
    /// Angle in degrees (0–90) between the major axes of the voxel grain and of the
    /// ellipsoid; meaningless for a grain with two equal largest semi-axes.
    pub major_axis_angle_deg: f64,
    /// Distance from the voxel centroid to the grain's centre.
    pub centroid_offset: f64,
}

/// Exact integer moments of one grain's unwrapped voxel indices, so that the parallel
/// sum is the same in any order.
#[derive(Debug, Clone, Copy, Default)]
pub(super) struct Moments {
    /// Number of voxels.
    pub count: u64,
    /// `Σ i_a`.
    sum: [i128; 3],
    /// `Σ i_a i_b`, upper triangle row-major.
    sum2: [i128; 6],
    /// The grain centre in index units (cell `i` has its centre at `i + ½`).
    centre: [f64; 3],
}

const PAIRS: [(usize, usize); 6] = [(0, 0), (0, 1), (0, 2), (1, 1), (1, 2), (2, 2)];

impl Moments {
    /// Adds the voxels `x = a..b` (unwrapped indices) of the row at unwrapped `y`, `z`.
    fn add_span(&mut self, a: i64, b: i64, y: i64, z: i64) {
        let (a, b, y, z) = (a as i128, b as i128, y as i128, z as i128);
        let len = b - a;
        // Σx = (a + b − 1) len / 2 and Σx² = f(b) − f(a), f(n) = (n − 1) n (2n − 1) / 6:
        // both products are exactly divisible, for negative indices too.
        let f = |n: i128| (n - 1) * n * (2 * n - 1) / 6;
        let sx = (a + b - 1) * len / 2;
        let sxx = f(b) - f(a);
        self.count += len as u64;
        let sum = [sx, len * y, len * z];
        let sum2 = [sxx, y * sx, z * sx, len * y * y, len * y * z, len * z * z];
        for (s, x) in self.sum.iter_mut().zip(sum) {
            *s += x;
        }
        for (s, x) in self.sum2.iter_mut().zip(sum2) {
            *s += x;
        }
    }

    fn merge(&mut self, o: &Moments) {
        self.count += o.count;
        for (s, x) in self.sum.iter_mut().zip(o.sum) {
            *s += x;
        }
        for (s, x) in self.sum2.iter_mut().zip(o.sum2) {
            *s += x;
        }
    }

    /// The solid ellipsoid (ellipse in 2D) of the same moments; `None` without voxels.
    pub fn shape(
        &self,
        g: &PackedGrain,
        h: [f64; 3],
        volume: f64,
        dimension: Dimension,
    ) -> Option<VoxelShape> {
        if self.count == 0 {
            return None;
        }
        let n = self.count as i128;
        let nf = self.count as f64;
        let mut cov = Matrix3::zeros();
        for (k, &(a, b)) in PAIRS.iter().enumerate() {
            // n Σ i_a i_b − Σ i_a Σ i_b is exact; only the division rounds.
            let c = (n * self.sum2[k] - self.sum[a] * self.sum[b]) as f64 / (nf * nf);
            let own = if a == b { 1.0 / 12.0 } else { 0.0 };
            cov[(a, b)] = (c + own) * h[a] * h[b];
            cov[(b, a)] = cov[(a, b)];
        }
        let (semi_axes, axes) = match dimension {
            Dimension::Three => solid_axes(cov),
            Dimension::Two => plane_axes(cov.fixed_view::<2, 2>(0, 0).into_owned()),
        };
        // In 2D the layer's z says nothing about the grain: the offset is in the plane.
        let offset: f64 = (0..dimension.exponent() as usize)
            .map(|a| {
                let mean = self.sum[a] as f64 / nf + 0.5;
                ((mean - self.centre[a]) * h[a]).powi(2)
            })
            .sum();
        let major = ellipsoid_major_axis(g);
        let cos = (0..3).map(|a| axes[0][a] * major[a]).sum::<f64>().abs();
        Some(VoxelShape {
            equivalent_diameter: dimension.diameter_of(volume),
            semi_axes,
            axes,
            aspect_ratio: semi_axes[0] / semi_axes[2],
            b_over_a: semi_axes[1] / semi_axes[0],
            c_over_a: semi_axes[2] / semi_axes[0],
            c_over_b: semi_axes[2] / semi_axes[1],
            major_axis_angle_deg: cos.min(1.0).acos().to_degrees(),
            centroid_offset: offset.sqrt(),
        })
    }
}

/// Semi-axes `√(5 λ_k)` of the covariance `cov`, largest first, and their directions.
fn solid_axes(cov: Matrix3<f64>) -> ([f64; 3], [[f64; 3]; 3]) {
    let eigen = SymmetricEigen::new(cov);
    let mut order = [0, 1, 2];
    order.sort_by(|&i, &j| eigen.eigenvalues[j].total_cmp(&eigen.eigenvalues[i]));
    let semi_axes = order.map(|k| (5.0 * eigen.eigenvalues[k].max(0.0)).sqrt());
    let axes = order.map(|k| {
        let v = eigen.eigenvectors.column(k);
        [v[0], v[1], v[2]]
    });
    (semi_axes, axes)
}

/// Semi-axes `2 √λ_k` of the in-plane covariance `cov` as the embedded ellipsoid's,
/// `[a1, √(a1 a2), a2]` with `a1 ≥ a2`, and their directions (z for the middle one).
fn plane_axes(cov: Matrix2<f64>) -> ([f64; 3], [[f64; 3]; 3]) {
    let eigen = SymmetricEigen::new(cov);
    let (big, small) = if eigen.eigenvalues[0] >= eigen.eigenvalues[1] {
        (0, 1)
    } else {
        (1, 0)
    };
    let semi = |k: usize| 2.0 * eigen.eigenvalues[k].max(0.0).sqrt();
    let axis = |k: usize| {
        let v = eigen.eigenvectors.column(k);
        [v[0], v[1], 0.0]
    };
    let (a1, a2) = (semi(big), semi(small));
    (
        [a1, (a1 * a2).sqrt(), a2],
        [axis(big), PLANE_NORMAL, axis(small)],
    )
}

/// The direction of the grain's largest semi-axis: that column of its rotation.
fn ellipsoid_major_axis(g: &PackedGrain) -> [f64; 3] {
    let rot = rotation_matrix(g.quaternion);
    let k = (0..3)
        .max_by(|&i, &j| g.semi_axes[i].total_cmp(&g.semi_axes[j]))
        .unwrap_or(0);
    let v: Vector3<f64> = rot.column(k).into();
    [v[0], v[1], v[2]]
}

/// Moments of every grain, voxel indices unwrapped to the image nearest its centre.
pub(super) fn moments(grid: &VoxelGrid, grains: &[PackedGrain], spans: &RowSpans) -> Vec<Moments> {
    let [_, ny, nz] = grid.cells;
    let h = grid.spacing();
    let empty: Vec<Moments> = grains
        .iter()
        .map(|g| Moments {
            centre: [0, 1, 2].map(|a| {
                let c = g.centre[a] / h[a];
                let n = grid.cells[a] as f64;
                if grid.periodic {
                    c.rem_euclid(n)
                } else {
                    c
                }
            }),
            ..Moments::default()
        })
        .collect();
    (0..nz)
        .into_par_iter()
        .fold(
            || empty.clone(),
            |mut acc, z| {
                for y in 0..ny {
                    for span in &spans.spans[spans.row(y + ny * z)] {
                        let Some(m) = acc.get_mut(span.material as usize) else {
                            continue;
                        };
                        let yu = y as i64 + shift(y, m.centre[1], grid, 1);
                        let zu = z as i64 + shift(z, m.centre[2], grid, 2);
                        let (start, end) = (span.start as usize, span.end as usize);
                        // The shift along x changes at most once in a span (at the
                        // point opposite the centre); cut the span there.
                        let mut a = start;
                        while a < end {
                            let k = shift(a, m.centre[0], grid, 0);
                            let mut b = end;
                            if shift(end - 1, m.centre[0], grid, 0) != k {
                                b = (a + 1..end)
                                    .find(|&x| shift(x, m.centre[0], grid, 0) != k)
                                    .unwrap_or(end);
                            }
                            m.add_span(a as i64 + k, b as i64 + k, yu, zu);
                            a = b;
                        }
                    }
                }
                acc
            },
        )
        .reduce(
            || empty.clone(),
            |mut a, b| {
                for (x, y) in a.iter_mut().zip(&b) {
                    x.merge(y);
                }
                a
            },
        )
}

/// The multiple of the cell count to add to index `i` along `axis` so that its centre
/// `i + ½` is within half the box of `centre` (index units); 0 in a walled box. The
/// centre lies in `[0, N)`, so one shift is enough.
fn shift(i: usize, centre: f64, grid: &VoxelGrid, axis: usize) -> i64 {
    if !grid.periodic {
        return 0;
    }
    let n = grid.cells[axis];
    let d = i as f64 + 0.5 - centre;
    let half = 0.5 * n as f64;
    if d > half {
        -(n as i64)
    } else if d < -half {
        n as i64
    } else {
        0
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_span_adds_what_its_voxels_add_one_by_one() {
        for (a, b, y, z) in [
            (0, 1, 0, 0),
            (-7, 5, 3, -2),
            (-20, -11, -1, 9),
            (250, 300, 5, 7),
        ] {
            let mut span = Moments::default();
            span.add_span(a, b, y, z);
            let mut one = Moments::default();
            for x in a..b {
                one.add_span(x, x + 1, y, z);
            }
            let mut direct = Moments::default();
            for x in a..b {
                let i = [x as i128, y as i128, z as i128];
                direct.count += 1;
                for (s, x) in direct.sum.iter_mut().zip(i) {
                    *s += x;
                }
                for (k, &(p, q)) in PAIRS.iter().enumerate() {
                    direct.sum2[k] += i[p] * i[q];
                }
            }
            for m in [span, one] {
                assert_eq!(
                    (m.count, m.sum, m.sum2),
                    (direct.count, direct.sum, direct.sum2)
                );
            }
        }
    }
}
