//! What the fast and the brute-force voxelisers share, so that both compute every
//! `t²` from the same numbers in the same order and agree to the last bit.

use super::{VoxelError, VoxelGrid};
use crate::contact::{rotation_matrix, Dimension, Ellipsoid};
use crate::octree::wrap_coordinate;
use crate::packing::PackedGrain;
use crate::scene::RveFill;
use crate::scene::{Boundary, Domain};
use nalgebra::{Matrix3, Vector3};

/// At most this many cells in all, so that every cell index fits a 32-bit signed
/// integer (VTK readers built with 32-bit ids, Fortran default integers).
pub const MAX_CELLS: usize = i32::MAX as usize;

/// Material of a voxel no grain has reached yet.
pub(super) const UNASSIGNED: u32 = u32::MAX;

/// The grid over the box.
#[derive(Debug, Clone, Copy)]
pub(super) struct Lattice {
    pub cells: [usize; 3],
    pub size: [f64; 3],
    /// Cell edge `L/N`.
    pub h: [f64; 3],
    pub periodic: bool,
    pub dimension: Dimension,
}

impl Lattice {
    pub fn new(domain: &Domain, cells: [usize; 3]) -> Result<Self, VoxelError> {
        for (axis, &value) in domain.size.iter().enumerate() {
            if !(value.is_finite() && value > 0.0) {
                return Err(VoxelError::InvalidDomain { axis, value });
            }
        }
        for (axis, &n) in cells.iter().enumerate() {
            if n == 0 {
                return Err(VoxelError::ZeroCells { axis });
            }
        }
        // A 2D grid is one layer, centred on the grains' plane z = Lz/2.
        if domain.dimension == Dimension::Two && cells[2] != 1 {
            return Err(VoxelError::PlaneLayers { cells: cells[2] });
        }
        let total = cells
            .iter()
            .try_fold(1usize, |acc, &n| acc.checked_mul(n))
            .filter(|&t| t <= MAX_CELLS);
        if total.is_none() {
            return Err(VoxelError::TooManyCells {
                cells,
                max: MAX_CELLS,
            });
        }
        Ok(Self {
            cells,
            size: domain.size,
            h: [0, 1, 2].map(|a| domain.size[a] / cells[a] as f64),
            periodic: domain.boundary == Boundary::Periodic,
            dimension: domain.dimension,
        })
    }

    /// Coordinate of the centre of cell `i` along `axis`.
    #[inline]
    pub fn coord(&self, axis: usize, i: usize) -> f64 {
        (i as f64 + 0.5) * self.h[axis]
    }

    /// Centre of image `k` along `axis` of a grain centred at `c`.
    #[inline]
    pub fn image(&self, axis: usize, c: f64, k: i64) -> f64 {
        c + k as f64 * self.size[axis]
    }

    /// The grid with its materials, phases filled in from `forms`; in 2D its z edge is
    /// the layer's thickness ([`layer_thickness`](super::layer_thickness)).
    pub fn into_grid(
        self,
        fill: RveFill,
        forms: &[Form],
        phases: usize,
        material: Vec<u32>,
    ) -> VoxelGrid {
        use rayon::prelude::*;
        let matrix_phase = phases as u32;
        let phase = material
            .par_iter()
            .map(|&m| forms.get(m as usize).map_or(matrix_phase, |f| f.phase))
            .collect();
        let mut size = self.size;
        if self.dimension == Dimension::Two {
            size[2] = super::layer_thickness(self.h[0], self.h[1]);
        }
        VoxelGrid {
            cells: self.cells,
            size,
            dimension: self.dimension,
            periodic: self.periodic,
            fill,
            grains: forms.len(),
            phases,
            material,
            phase,
        }
    }
}

/// One grain, prepared for voxel queries.
#[derive(Debug, Clone, Copy)]
pub(super) struct Form {
    /// Centre, wrapped into `[0, L)` in a periodic box.
    pub centre: [f64; 3],
    /// `Q⁻¹ = R diag(1/a²) Rᵀ`, upper triangle row-major.
    pub p: [f64; 6],
    /// Half-widths of the axis-aligned bounding box at scale 1: `√Q_aa`.
    pub half: [f64; 3],
    /// Smallest semi-axis: `t ≤ |x − c| / inscribed`.
    pub inscribed: f64,
    pub phase: u32,
}

/// `t² = dᵀ P d` for `P = Q⁻¹` stored as an upper triangle: the one formula every
/// voxeliser uses.
#[inline(always)]
pub(super) fn scaled_dist2(p: &[f64; 6], d: [f64; 3]) -> f64 {
    let [x, y, z] = d;
    x * (p[0] * x + p[1] * y + p[2] * z)
        + y * (p[1] * x + p[3] * y + p[4] * z)
        + z * (p[2] * x + p[4] * y + p[5] * z)
}

/// Checks the grains and prepares them (in slice order: material `k` is `grains[k]`).
pub(super) fn prepare(
    grains: &[PackedGrain],
    lattice: &Lattice,
    phases: usize,
) -> Result<Vec<Form>, VoxelError> {
    if grains.len() >= i32::MAX as usize || phases >= i32::MAX as usize {
        return Err(VoxelError::TooManyGrains {
            count: grains.len(),
        });
    }
    grains
        .iter()
        .map(|g| {
            let shape = |source| VoxelError::Shape { id: g.id, source };
            let ellipsoid = Ellipsoid::new(g.semi_axes, g.quaternion).map_err(shape)?;
            if !g.centre.iter().all(|x| x.is_finite()) {
                return Err(VoxelError::NonFiniteCentre {
                    id: g.id,
                    centre: g.centre,
                });
            }
            if g.phase >= phases {
                return Err(VoxelError::PhaseOutOfRange {
                    id: g.id,
                    phase: g.phase,
                    phases,
                });
            }
            let rot = rotation_matrix(g.quaternion);
            let inv = Vector3::from(g.semi_axes.map(|a| 1.0 / (a * a)));
            let p: Matrix3<f64> = rot * Matrix3::from_diagonal(&inv) * rot.transpose();
            let q = ellipsoid.q;
            let centre = if lattice.periodic {
                [0, 1, 2].map(|a| wrap_coordinate(g.centre[a], lattice.size[a]))
            } else {
                g.centre
            };
            Ok(Form {
                centre,
                p: [
                    p[(0, 0)],
                    p[(0, 1)],
                    p[(0, 2)],
                    p[(1, 1)],
                    p[(1, 2)],
                    p[(2, 2)],
                ],
                half: [q[0].sqrt(), q[3].sqrt(), q[5].sqrt()],
                inscribed: g.semi_axes.iter().copied().fold(f64::INFINITY, f64::min),
                phase: g.phase as u32,
            })
        })
        .collect()
}

/// Relative slack on [`reach_bound`]: it only has to absorb the rounding of `t`, a few ε.
pub(super) const REACH_SLACK: f64 = 1e3 * f64::EPSILON;

/// A scale at which some grain reaches every voxel centre: for each grain, the farthest
/// voxel centre (its nearest image in a periodic box) over its inscribed radius, the
/// smallest of those, plus [`REACH_SLACK`].
pub(super) fn reach_bound(forms: &[Form], lattice: &Lattice) -> f64 {
    let far = |f: &Form| -> f64 {
        let d2: f64 = (0..3)
            .map(|a| {
                let d = if lattice.periodic {
                    0.5 * lattice.size[a]
                } else {
                    let lo = lattice.coord(a, 0);
                    let hi = lattice.coord(a, lattice.cells[a] - 1);
                    (f.centre[a] - lo).abs().max((hi - f.centre[a]).abs())
                };
                d * d
            })
            .sum();
        d2.sqrt() / f.inscribed
    };
    forms.iter().map(far).fold(f64::INFINITY, f64::min) * (1.0 + REACH_SLACK)
}

/// Image numbers `k` along `axis` whose interval `[c + kL − half, c + kL + half]` meets
/// `[lo, hi]`; only `0` (if it meets) in a walled box.
pub(super) fn image_range(
    lattice: &Lattice,
    axis: usize,
    c: f64,
    half: f64,
    lo: f64,
    hi: f64,
) -> std::ops::RangeInclusive<i64> {
    if lattice.periodic {
        let l = lattice.size[axis];
        let first = ((lo - half - c) / l).ceil();
        let last = ((hi + half - c) / l).floor();
        // Both are small: |c| < L and half is a bounded multiple of the box.
        first as i64..=last as i64
    } else if c - half <= hi && c + half >= lo {
        0..=0
    } else {
        #[allow(clippy::reversed_empty_ranges)]
        {
            1..=0
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn lattice(periodic: bool) -> Lattice {
        let boundary = if periodic {
            Boundary::Periodic
        } else {
            Boundary::Reflecting
        };
        let domain = Domain::new([2.0, 3.0, 4.0], boundary);
        Lattice::new(&domain, [4, 6, 8]).unwrap()
    }

    #[test]
    fn scaled_dist2_is_the_quadratic_form_of_the_inverse_of_q() {
        let g = PackedGrain {
            id: 0,
            phase: 0,
            centre: [0.3, 0.2, 0.1],
            semi_axes: [0.9, 0.4, 0.2],
            quaternion: [0.5, 0.5, -0.5, 0.5],
        };
        let form = prepare(&[g], &lattice(false), 1).unwrap()[0];
        let q = Ellipsoid::new(g.semi_axes, g.quaternion).unwrap().matrix();
        let inv = q.try_inverse().unwrap();
        let d = Vector3::new(0.3, -0.7, 0.25);
        let want = (d.transpose() * inv * d)[0];
        let got = scaled_dist2(&form.p, [d[0], d[1], d[2]]);
        // Two routes to Q⁻¹ (inverting Q, or R diag(1/a²) Rᵀ), each good to a few ε·cond.
        assert!((got - want).abs() < 1e-12 * want, "{got} vs {want}");
        // At the tip of each semi-axis (column k of R, length a_k), t = 1.
        let r = rotation_matrix([0.5, 0.5, -0.5, 0.5]);
        for (k, a) in g.semi_axes.iter().enumerate() {
            let tip = r.column(k) * *a;
            let t2 = scaled_dist2(&form.p, [tip[0], tip[1], tip[2]]);
            assert!((t2 - 1.0).abs() < 1e-14, "semi-axis {k}: t² = {t2}");
        }
    }

    #[test]
    fn periodic_centres_are_wrapped_into_the_box() {
        let g = PackedGrain {
            id: 3,
            phase: 0,
            centre: [-0.5, 3.5, -1e-300],
            semi_axes: [0.1; 3],
            quaternion: [1.0, 0.0, 0.0, 0.0],
        };
        let form = prepare(&[g], &lattice(true), 1).unwrap()[0];
        assert_eq!(form.centre, [1.5, 0.5, 0.0]);
        let walled = prepare(&[g], &lattice(false), 1).unwrap()[0];
        assert_eq!(walled.centre, g.centre);
    }

    #[test]
    fn image_range_lists_the_images_that_meet_the_interval() {
        let lat = lattice(true);
        // A grain at x = 0.1 of half-width 0.3 in a box of 2: its images at 2.1 and
        // −1.9 reach [1.8, 2.4] and [−2.2, −1.6]; only image 1 meets [1.9, 1.95].
        assert_eq!(image_range(&lat, 0, 0.1, 0.3, 1.9, 1.95), 1..=1);
        // A half-width above the box meets the whole box through several images.
        assert_eq!(image_range(&lat, 0, 0.1, 2.5, 0.25, 1.75), -1..=2);
        assert!(image_range(&lattice(false), 0, 0.1, 0.3, 1.9, 1.95).is_empty());
    }
}
