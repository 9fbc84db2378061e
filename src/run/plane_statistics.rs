//! What a 2D packing looks like as a whole: how the ellipses' angles spread, whether
//! their centres order like a hexagonal crystal (the hexatic order parameter ψ6), and
//! how far each grain is from its nearest neighbour. A fibre composite's cross-section
//! should be random: ψ6 near 0 over the whole packing, nearest-neighbour distances
//! spread out rather than all equal.

use crate::contact::{contact_function, ellipse_angle, Ellipsoid, Sym3};
use crate::octree::{Octree, OctreeError, Pair, Params, Sphere};
use crate::packing::PackedGrain;
use crate::scene::Domain;
use rayon::prelude::*;
use serde::Serialize;
use std::f64::consts::PI;

/// Neighbours, for ψ6 and the nearest-neighbour distances, are the pairs (periodic
/// images included) whose centres are at most `NEIGHBOUR_REACH (R_i + R_j)` apart, `R`
/// the equivalent-circle radius `√(a1 a2)`. 1.4 is the first minimum of the radial
/// distribution of dense random disc packings: it takes in the six touching
/// neighbours of a hexagonal crystal (at 1) and leaves out its second shell (at √3).
pub const NEIGHBOUR_REACH: f64 = 1.4;

/// Angles of a phase's ellipses, as axes (an ellipse turned by 180° is the same):
/// statistics of the doubled angles `2θ` (Mardia and Jupp 2000, §9.3).
#[derive(Debug, Clone, Copy, Serialize)]
pub struct AngleStatistics {
    /// Circular mean of the first semi-axis's angle from x, degrees in `(−90, 90]`:
    /// `arg(⟨e^{2iθ}⟩)/2`; `null` when the angles have no mean direction (order 0).
    pub mean_deg: Option<f64>,
    /// Circular standard deviation, degrees: `√(−2 ln R)/2`; `null` when `R = 0`.
    pub spread_deg: Option<f64>,
    /// `R = |⟨e^{2iθ}⟩|`, the 2D orientational order: 1 when every ellipse has the
    /// same angle, near 0 for uniformly random angles (`~1/√n`).
    pub order: f64,
}

impl AngleStatistics {
    /// The statistics of the angles of `grains`; `None` without grains.
    pub fn of(grains: &[&PackedGrain]) -> Option<Self> {
        if grains.is_empty() {
            return None;
        }
        let (mut c, mut s) = (0.0, 0.0);
        for g in grains {
            let (sin, cos) = (2.0 * ellipse_angle(g.quaternion)).sin_cos();
            (c, s) = (c + cos, s + sin);
        }
        let n = grains.len() as f64;
        let order = (c / n).hypot(s / n);
        let defined = order > 0.0;
        Some(Self {
            mean_deg: defined.then(|| fold_half_turn(0.5 * s.atan2(c)).to_degrees()),
            spread_deg: defined.then(|| (0.5 * (-2.0 * order.ln()).sqrt()).to_degrees()),
            order,
        })
    }
}

/// An axis angle folded into `(−π/2, π/2]`.
fn fold_half_turn(theta: f64) -> f64 {
    if theta <= -0.5 * PI {
        theta + PI
    } else {
        theta
    }
}

/// Summary figures of a sample: its extremes, mean and percentiles (linear between
/// the closest ranks, numpy's default).
#[derive(Debug, Clone, Copy, Serialize)]
pub struct Spread {
    /// Smallest value.
    pub min: f64,
    /// 10th percentile.
    pub p10: f64,
    /// Median.
    pub median: f64,
    /// 90th percentile.
    pub p90: f64,
    /// Largest value.
    pub max: f64,
    /// Mean.
    pub mean: f64,
}

impl Spread {
    /// The figures of `values`; `None` when empty.
    pub fn of(mut values: Vec<f64>) -> Option<Self> {
        if values.is_empty() {
            return None;
        }
        values.sort_by(f64::total_cmp);
        let at = |p: f64| {
            let x = p * (values.len() - 1) as f64;
            let (k, t) = (x.floor() as usize, x.fract());
            let next = values[(k + 1).min(values.len() - 1)];
            values[k] + t * (next - values[k])
        };
        Some(Self {
            min: values[0],
            p10: at(0.1),
            median: at(0.5),
            p90: at(0.9),
            max: values[values.len() - 1],
            mean: values.iter().sum::<f64>() / values.len() as f64,
        })
    }
}

/// The arrangement of a 2D packing's centres (`summary.json`'s `plane`).
#[derive(Debug, Clone, Copy, Serialize)]
pub struct PlaneStatistics {
    /// [`NEIGHBOUR_REACH`]: neighbours are centres at most this times `R_i + R_j`
    /// apart.
    pub neighbour_reach: f64,
    /// Mean number of neighbours per grain.
    pub mean_neighbours: f64,
    /// Grains without a neighbour (left out of ψ6 and the distances).
    pub isolated_grains: usize,
    /// `|⟨ψ6⟩|`, the global hexatic order: `ψ6_i = (1/n_i) Σ_j e^{6iφ_ij}` over grain
    /// i's neighbours j, `φ_ij` the angle of the vector between the centres, averaged
    /// over the grains. 1 for a hexagonal crystal, `~1/√n` for a random packing.
    pub psi6_global: f64,
    /// `⟨|ψ6_i|⟩`, the local hexatic order: 1 when every grain sits in a regular
    /// hexagon of neighbours, whatever the crystal's orientation from place to place.
    pub psi6_local: f64,
    /// Each grain's distance to its nearest neighbour's centre, in the scene's length
    /// unit; `null` without neighbours.
    pub nearest_centre_distance: Option<Spread>,
    /// Each grain's smallest gap to a neighbour, `√μ² − 1` with μ the factor the
    /// pair must grow by to touch (as `gap` and `min_gap`: for discs, the surface gap
    /// over the sum of the radii); `null` without neighbours.
    pub nearest_gap: Option<Spread>,
}

impl PlaneStatistics {
    /// The statistics of `grains`, 2D grains (ellipses embedded at the same `z`) in
    /// `domain`. Fails only on a box or grain the octree or the contact function
    /// rejects, which a packing never has.
    pub fn of(grains: &[PackedGrain], domain: &Domain) -> Result<Self, OctreeError> {
        let radius = |g: &PackedGrain| (g.semi_axes[0] * g.semi_axes[1]).sqrt();
        let spheres: Vec<Sphere> = grains
            .iter()
            .enumerate()
            .map(|(i, g)| Sphere {
                id: i as u32,
                centre: g.centre,
                radius: NEIGHBOUR_REACH * radius(g),
            })
            .collect();
        let shape = domain.box_shape()?;
        // The octree's shifts refer to the centres wrapped into the box.
        let centres: Vec<[f64; 3]> = grains.iter().map(|g| shape.wrap(g.centre)).collect();
        let tree = Octree::build(&spheres, shape, Params::default())?;
        let mut pairs = Vec::new();
        tree.pairs(&mut pairs);
        // The slab's z images and a grain's own images are not neighbours in the plane.
        pairs.retain(|p: &Pair| p.i != p.j && p.image[2] == 0);
        let n = grains.len();
        let forms: Vec<Option<Sym3>> = grains
            .iter()
            .map(|g| Ellipsoid::new(g.semi_axes, g.quaternion).ok().map(|e| e.q))
            .collect();
        let mut psi = vec![(0.0, 0.0); n];
        let mut count = vec![0usize; n];
        let mut nearest = vec![f64::INFINITY; n];
        let mut gap = vec![f64::INFINITY; n];
        // The contact functions in parallel; the sums in pair order, so the figures do
        // not depend on the thread count.
        let measured: Vec<([f64; 3], f64)> = pairs
            .par_iter()
            .map(|p| {
                let (i, j) = (p.i as usize, p.j as usize);
                let shift = p.shift(&shape);
                let r = [0, 1, 2].map(|k| centres[j][k] + shift[k] - centres[i][k]);
                (r, pair_mu(forms[i].as_ref(), forms[j].as_ref(), r))
            })
            .collect();
        for (p, &(r, mu)) in pairs.iter().zip(&measured) {
            let (i, j) = (p.i as usize, p.j as usize);
            let distance = r[0].hypot(r[1]);
            let (sin, cos) = (6.0 * r[1].atan2(r[0])).sin_cos();
            // φ_ji = φ_ij + π: e^{6iφ} is the same from both ends.
            for k in [i, j] {
                psi[k] = (psi[k].0 + cos, psi[k].1 + sin);
                count[k] += 1;
                nearest[k] = nearest[k].min(distance);
                gap[k] = gap[k].min(mu - 1.0);
            }
        }
        let placed: Vec<usize> = (0..n).filter(|&k| count[k] > 0).collect();
        let local: Vec<(f64, f64)> = placed
            .iter()
            .map(|&k| (psi[k].0 / count[k] as f64, psi[k].1 / count[k] as f64))
            .collect();
        let m = placed.len().max(1) as f64;
        let (c, s) = local
            .iter()
            .fold((0.0, 0.0), |(c, s), l| (c + l.0, s + l.1));
        Ok(Self {
            neighbour_reach: NEIGHBOUR_REACH,
            mean_neighbours: count.iter().sum::<usize>() as f64 / n.max(1) as f64,
            isolated_grains: n - placed.len(),
            psi6_global: (c / m).hypot(s / m),
            psi6_local: local.iter().map(|l| l.0.hypot(l.1)).sum::<f64>() / m,
            nearest_centre_distance: Spread::of(placed.iter().map(|&k| nearest[k]).collect()),
            nearest_gap: Spread::of(placed.iter().map(|&k| gap[k]).collect()),
        })
    }
}

/// μ of two grains of forms `a` and `b`, `r` apart (from `a` to `b`), by the
/// accurate contact function; NaN (left out of the minima) if a form or the function
/// fails, which they do not on the grains of a packing.
fn pair_mu(a: Option<&Sym3>, b: Option<&Sym3>, r: [f64; 3]) -> f64 {
    match (a, b) {
        (Some(qa), Some(qb)) => contact_function(&r, qa, qb).map_or(f64::NAN, |c| c.mu2.sqrt()),
        _ => f64::NAN,
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::contact::{ellipse_quaternion, ellipse_semi_axes};
    use crate::scene::Boundary;

    /// Sums of a few dozen terms of size 1 through atan2 and sin_cos of rounded
    /// coordinates: a few hundred ε.
    const TOL: f64 = 1e-12;

    fn disc(id: usize, x: f64, y: f64, r: f64, domain: &Domain) -> PackedGrain {
        PackedGrain {
            id: id as u32,
            phase: 0,
            centre: [x, y, domain.plane_z()],
            semi_axes: ellipse_semi_axes(r, r),
            quaternion: ellipse_quaternion(0.0),
        }
    }

    /// Discs of radius `r` on a lattice of spacing 1 with rows `h` apart, every other
    /// row shifted by `offset`, in a periodic box of `m` by `k` sites.
    fn lattice(m: usize, k: usize, h: f64, offset: f64, r: f64) -> (Vec<PackedGrain>, Domain) {
        let domain = Domain::plane([m as f64, k as f64 * h], Boundary::Periodic);
        let grains = (0..m * k)
            .map(|n| {
                let (i, j) = (n % m, n / m);
                let x = i as f64 + 0.5 + offset * (j % 2) as f64;
                disc(n, x, (j as f64 + 0.5) * h, r, &domain)
            })
            .collect();
        (grains, domain)
    }

    #[test]
    fn a_hexagonal_crystal_has_full_hexatic_order_and_equal_distances() {
        let (grains, domain) = lattice(8, 10, 0.75f64.sqrt(), 0.5, 0.45);
        let s = PlaneStatistics::of(&grains, &domain).unwrap();
        assert_eq!(s.isolated_grains, 0);
        assert_eq!(s.mean_neighbours, 6.0);
        assert!((s.psi6_global - 1.0).abs() < TOL, "{s:?}");
        assert!((s.psi6_local - 1.0).abs() < TOL, "{s:?}");
        let d = s.nearest_centre_distance.unwrap();
        assert!(
            (d.min - 1.0).abs() < TOL && (d.max - 1.0).abs() < TOL,
            "{d:?}"
        );
        // Discs 1 apart with radii 0.45 grow by 1/0.9 to touch.
        let gap = s.nearest_gap.unwrap();
        assert!((gap.median - (1.0 / 0.9 - 1.0)).abs() < TOL, "{gap:?}");
    }

    #[test]
    fn a_square_lattice_has_no_hexatic_order() {
        let (grains, domain) = lattice(8, 8, 1.0, 0.0, 0.45);
        let s = PlaneStatistics::of(&grains, &domain).unwrap();
        // Four neighbours at 0°, 90°, 180°, 270°: e^{6iφ} = ±1 cancel.
        assert_eq!(s.mean_neighbours, 4.0);
        assert!(s.psi6_local < TOL && s.psi6_global < TOL, "{s:?}");
    }

    #[test]
    fn a_walled_box_does_not_count_neighbours_across_its_faces() {
        let domain = Domain::plane([10.0, 10.0], Boundary::Reflecting);
        let grains = [
            disc(0, 0.5, 5.0, 0.45, &domain),
            disc(1, 9.5, 5.0, 0.45, &domain),
        ];
        let s = PlaneStatistics::of(&grains, &domain).unwrap();
        assert_eq!(s.isolated_grains, 2);
        assert!(s.nearest_centre_distance.is_none());
        let periodic = Domain::plane([10.0, 10.0], Boundary::Periodic);
        let s = PlaneStatistics::of(&grains, &periodic).unwrap();
        assert_eq!(s.isolated_grains, 0);
        assert!((s.nearest_centre_distance.unwrap().max - 1.0).abs() < TOL);
    }

    fn at_angles(degrees: &[f64]) -> AngleStatistics {
        let domain = Domain::plane([10.0, 10.0], Boundary::Periodic);
        let grains: Vec<PackedGrain> = degrees
            .iter()
            .map(|&t| PackedGrain {
                quaternion: ellipse_quaternion(t.to_radians()),
                ..disc(0, 5.0, 5.0, 1.0, &domain)
            })
            .collect();
        AngleStatistics::of(&grains.iter().collect::<Vec<_>>()).unwrap()
    }

    #[test]
    fn angle_statistics_treat_angles_as_axes() {
        let same = at_angles(&[30.0; 5]);
        assert!((same.order - 1.0).abs() < TOL);
        assert!((same.mean_deg.unwrap() - 30.0).abs() < 1e-10);
        // √(−2 ln R) for R = 1 − δ is √(2δ): rounding of 1e-16 gives 1e-8 rad.
        assert!(same.spread_deg.unwrap() < 1e-6);
        // 89° and −89° are 2° apart as axes: their mean is 90°, not 0°.
        let across = at_angles(&[89.0, -89.0]);
        assert!(
            (across.mean_deg.unwrap() - 90.0).abs() < 1e-10,
            "{across:?}"
        );
        assert!((across.order - 2f64.to_radians().cos()).abs() < TOL);
        // Axes 0°, 60°, 120° are evenly spread: no mean direction.
        let even = at_angles(&[0.0, 60.0, 120.0]);
        assert!(even.order < TOL, "{even:?}");
    }

    #[test]
    fn spread_interpolates_between_ranks() {
        let s = Spread::of(vec![4.0, 0.0, 1.0, 2.0, 3.0]).unwrap();
        assert_eq!((s.min, s.median, s.max, s.mean), (0.0, 2.0, 4.0, 2.0));
        assert!((s.p10 - 0.4).abs() < TOL && (s.p90 - 3.6).abs() < TOL);
        assert!(Spread::of(Vec::new()).is_none());
    }
}
