//! The exact check of a packed state: every pair whose bounding spheres meet, and the
//! walls of a walled box, with the gap asked for (`packing.gap`).

use super::{PackError, PackedGrain, Verification};
use crate::contact::{contact_function, Ellipsoid};
use crate::octree::{spheres_intersect, Octree, Params, Sphere};
use crate::scene::{Boundary, Domain};
use rayon::prelude::*;

/// How far beyond the gap the smallest gap reached is still measured: every pair
/// whose bounding spheres, scaled by `(1 + gap)(1 + MIN_GAP_REACH)`, meet is tested,
/// so [`Verification::min_gap`] is exact whenever some pair is closer than
/// `(1 + gap)(1 + MIN_GAP_REACH) − 1` (μ is at least the centres' distance over the
/// sum of the bounding radii). 5 % reaches the pairs of a jammed packing, which the
/// loop leaves a hair beyond the gap, and costs a few more contact functions per grain.
pub const MIN_GAP_REACH: f64 = 0.05;

/// Checks a packed state exactly, with a gap `gap ≥ 0` (a fraction of each pair's
/// size): the accurate contact function on every pair whose bounding spheres, scaled by
/// `1 + gap`, meet (periodic images included), which must have `μ ≥ 1 + gap`; and in a
/// walled box each grain's extent `√Q_kk` along every axis, scaled by `1 + gap`,
/// against the walls. A pair not checked is further apart than the gap: μ is at least
/// the centres' distance over the sum of the bounding radii. The smallest gap reached
/// is measured a little further out ([`MIN_GAP_REACH`]).
///
/// Fails only on input that is not a packing: an invalid grain, an id that is not its
/// index, or a box the octree rejects.
pub fn verify(
    grains: &[PackedGrain],
    domain: &Domain,
    gap: f64,
) -> Result<Verification, PackError> {
    let mut shapes = Vec::with_capacity(grains.len());
    for (index, g) in grains.iter().enumerate() {
        if g.id as usize != index {
            return Err(PackError::Misnumbered { index, id: g.id });
        }
        let bad = |source| PackError::Grain { id: index, source };
        shapes.push(Ellipsoid::new(g.semi_axes, g.quaternion).map_err(bad)?);
    }
    let inflation = 1.0 + gap;
    // μ² below this breaks the gap.
    let least_mu2 = inflation * inflation;
    // The bounding radii scaled by 1 + gap: the pairs they meet are the checked ones.
    let radii: Vec<f64> = (grains.iter())
        .map(|g| g.semi_axes.iter().fold(0.0f64, |m, &a| m.max(a)) * inflation)
        .collect();
    let spheres: Vec<Sphere> = (grains.iter().zip(&radii))
        .map(|(g, r)| Sphere {
            id: g.id,
            centre: g.centre,
            radius: r * (1.0 + MIN_GAP_REACH),
        })
        .collect();
    let shape = domain.box_shape()?;
    let tree = Octree::build(&spheres, shape, Params::default())?;
    let mut pairs = Vec::new();
    tree.pairs(&mut pairs);
    let checked = |i: usize, j: usize, shift: [f64; 3]| {
        spheres_intersect(
            grains[i].centre,
            radii[i],
            grains[j].centre,
            radii[j],
            shift,
        )
    };
    // A grain against its own image: the bounding spheres only say it may.
    let self_images = pairs
        .iter()
        .filter(|p| p.i == p.j)
        .filter(|p| {
            let q = &shapes[p.i as usize].q;
            contact_function(&p.shift(&shape), q, q).map_or(true, |c| c.mu2 < least_mu2)
        })
        .count();
    // μ² of every pair within reach, and whether it is a checked one.
    let mu2: Vec<(f64, bool)> = pairs
        .par_iter()
        .filter(|p| p.i != p.j)
        .map(|p| {
            let (i, j) = (p.i as usize, p.j as usize);
            let (ci, cj) = (grains[i].centre, grains[j].centre);
            let shift = p.shift(&shape);
            let r = [0, 1, 2].map(|k| cj[k] + shift[k] - ci[k]);
            // An error here (overflow) counts as an overlap: it is not a proof of
            // separation.
            let m = contact_function(&r, &shapes[i].q, &shapes[j].q).map_or(0.0, |c| c.mu2);
            (m, checked(i, j, shift))
        })
        .collect();
    // Per grain of a walled box, the scale about its centre at which it would touch a
    // wall: its room to the walls.
    let rooms: Vec<f64> = match domain.boundary {
        Boundary::Periodic => Vec::new(),
        Boundary::Reflecting => grains
            .iter()
            .zip(&shapes)
            .map(|(g, e)| {
                let diag = [e.q[0], e.q[3], e.q[5]];
                (0..3)
                    .map(|k| g.centre[k].min(domain.size[k] - g.centre[k]) / diag[k].sqrt())
                    .fold(f64::INFINITY, f64::min)
            })
            .collect(),
    };
    let wall_violations = match domain.boundary {
        Boundary::Periodic => 0,
        Boundary::Reflecting => grains
            .iter()
            .zip(&shapes)
            .filter(|(g, e)| {
                let diag = [e.q[0], e.q[3], e.q[5]];
                (0..3).any(|k| {
                    let w = diag[k].sqrt() * inflation;
                    g.centre[k] - w < 0.0 || g.centre[k] + w > domain.size[k]
                })
            })
            .count(),
    };
    let min_mu2 = (mu2.iter())
        .filter(|m| m.1)
        .fold(f64::INFINITY, |least, m| least.min(m.0));
    let least_mu2_reached = mu2.iter().fold(f64::INFINITY, |least, m| least.min(m.0));
    let min_room = rooms.iter().copied().fold(f64::INFINITY, f64::min);
    // Pairs beyond the checked ones cannot break the gap unless the contact function
    // failed on them: they are counted too.
    Ok(Verification {
        gap,
        checked_pairs: mu2.iter().filter(|m| m.1).count(),
        overlapping_pairs: mu2.iter().filter(|m| m.0 < 1.0).count(),
        gap_violations: mu2.iter().filter(|m| m.0 < least_mu2).count(),
        min_mu2,
        min_gap: least_mu2_reached.sqrt().min(min_room) - 1.0,
        wall_violations,
        self_images,
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    fn grain(id: u32, centre: [f64; 3], semi_axes: [f64; 3]) -> PackedGrain {
        PackedGrain {
            id,
            phase: 0,
            centre,
            semi_axes,
            quaternion: [1.0, 0.0, 0.0, 0.0],
        }
    }

    fn domain(boundary: Boundary) -> Domain {
        Domain::new([10.0, 10.0, 10.0], boundary)
    }

    #[test]
    fn verify_finds_an_overlap_across_a_periodic_face() {
        // Needles along x, 2.2 apart through the x face, reaching 1.2 each: they overlap.
        let grains = [
            grain(0, [0.5, 5.0, 5.0], [1.2, 0.2, 0.2]),
            grain(1, [8.3, 5.0, 5.0], [1.2, 0.2, 0.2]),
        ];
        let v = verify(&grains, &domain(Boundary::Periodic), 0.0).unwrap();
        assert_eq!((v.checked_pairs, v.overlapping_pairs), (1, 1));
        assert!(v.min_mu2 < 1.0 && !v.is_clean());
        // Walls: no image, so the same two are far apart.
        let v = verify(&grains, &domain(Boundary::Reflecting), 0.0).unwrap();
        assert_eq!(v.overlapping_pairs, 0);
    }

    #[test]
    fn verify_passes_grains_that_only_nearly_touch() {
        // Prolate grains along x, side by side along y with centres 2(1 + 1e-9) apart:
        // their bounding spheres meet, and μ² = (1 + 1e-9)² (y is a principal axis).
        let grains = [
            grain(0, [5.0, 4.0, 5.0], [2.0, 1.0, 1.0]),
            grain(1, [5.0, 6.000000002, 5.0], [2.0, 1.0, 1.0]),
        ];
        let v = verify(&grains, &domain(Boundary::Reflecting), 0.0).unwrap();
        assert_eq!((v.checked_pairs, v.overlapping_pairs), (1, 0));
        assert!((v.min_mu2 - (1.0 + 1e-9f64).powi(2)).abs() < 1e-15);
        assert!(v.is_clean());
    }

    #[test]
    fn verify_finds_a_grain_through_a_wall_and_one_meeting_its_image() {
        let through = [grain(0, [0.5, 5.0, 5.0], [1.0, 0.5, 0.5])];
        let v = verify(&through, &domain(Boundary::Reflecting), 0.0).unwrap();
        assert_eq!(v.wall_violations, 1);
        let long = [grain(0, [5.0, 5.0, 5.0], [5.5, 0.5, 0.5])];
        let v = verify(&long, &domain(Boundary::Periodic), 0.0).unwrap();
        assert_eq!(v.self_images, 1);
        assert!(!v.is_clean());
    }

    /// Two unit spheres and the gap 0.1: the surface gap must be 0.1 · (1 + 1) = 0.2.
    /// A millionth short of it is a violation; a millionth beyond is clean, and the
    /// smallest gap reached is the gap, to that millionth.
    #[test]
    fn verify_refuses_a_pair_closer_than_the_gap() {
        let gap = 0.1;
        let at = |d: f64| {
            [
                grain(0, [3.0, 5.0, 5.0], [1.0; 3]),
                grain(1, [3.0 + d, 5.0, 5.0], [1.0; 3]),
            ]
        };
        let v = verify(&at(2.2 * (1.0 - 1e-6)), &domain(Boundary::Periodic), gap).unwrap();
        assert_eq!(
            (v.checked_pairs, v.overlapping_pairs, v.gap_violations),
            (1, 0, 1)
        );
        assert!(!v.is_clean());
        // Without the gap the same pair is clean.
        assert!(
            verify(&at(2.2 * (1.0 - 1e-6)), &domain(Boundary::Periodic), 0.0)
                .unwrap()
                .is_clean()
        );
        // Beyond the gap, the spheres' bounding spheres scaled by 1.1 are apart: the pair
        // is not a checked one, but within MIN_GAP_REACH its gap is measured (to the
        // accurate function's 1e-13).
        let v = verify(&at(2.2 * (1.0 + 1e-6)), &domain(Boundary::Periodic), gap).unwrap();
        assert!(v.is_clean() && v.checked_pairs == 0, "{v:?}");
        assert!(
            (v.min_gap - (1.1 * (1.0 + 1e-6) - 1.0)).abs() < 1e-12,
            "{v:?}"
        );
        assert_eq!(v.gap, gap);
        // Further than that, no gap is reached.
        let v = verify(&at(2.2 * 1.06), &domain(Boundary::Periodic), gap).unwrap();
        assert_eq!(v.min_gap, f64::INFINITY, "{v:?}");
        // Prolate grains side by side along a principal axis: μ = d / 2 exactly, and
        // their bounding spheres (radius 2) meet, so the pair is checked.
        let d = 2.0 * 1.1 * (1.0 + 1e-6);
        let side = [
            grain(0, [5.0, 3.0, 5.0], [2.0, 1.0, 1.0]),
            grain(1, [5.0, 3.0 + d, 5.0], [2.0, 1.0, 1.0]),
        ];
        let v = verify(&side, &domain(Boundary::Periodic), gap).unwrap();
        assert!(v.is_clean() && v.checked_pairs == 1, "{v:?}");
        // min_gap = d / 2 − 1; the contact function is accurate to 1e-13 here.
        assert!((v.min_gap - (d / 2.0 - 1.0)).abs() < 1e-12, "{v:?}");
    }

    /// Bounding spheres scaled by 1 + gap must meet for the pair to be checked: at
    /// 2.15 apart, unit spheres' bounding spheres are apart but breaking the gap 0.1.
    #[test]
    fn verify_checks_pairs_within_the_gap_of_their_bounding_spheres() {
        let grains = [
            grain(0, [3.0, 5.0, 5.0], [1.0; 3]),
            grain(1, [5.15, 5.0, 5.0], [1.0; 3]),
        ];
        let v = verify(&grains, &domain(Boundary::Periodic), 0.1).unwrap();
        assert_eq!((v.checked_pairs, v.gap_violations), (1, 1));
    }

    /// A grain scaled by 1 + gap must stay inside the walls, and the smallest gap
    /// reached counts its room to them; a grain must keep the gap from its own image.
    #[test]
    fn verify_refuses_a_grain_within_the_gap_of_a_wall_or_its_image() {
        let gap = 0.2;
        // Extent 1 along x: 1.2 from the wall keeps the gap, 1.2 (1 − 1e-6) does not.
        let near = [grain(0, [1.2 * (1.0 - 1e-6), 5.0, 5.0], [1.0, 0.5, 0.5])];
        let v = verify(&near, &domain(Boundary::Reflecting), gap).unwrap();
        assert_eq!(v.wall_violations, 1);
        let kept = [grain(0, [1.2 * (1.0 + 1e-6), 5.0, 5.0], [1.0, 0.5, 0.5])];
        let v = verify(&kept, &domain(Boundary::Reflecting), gap).unwrap();
        assert!(v.is_clean(), "{v:?}");
        // Room 1.2 (1 + 1e-6): the smallest gap, to rounding (a few ε).
        assert!(
            (v.min_gap - (1.2 * (1.0 + 1e-6) - 1.0)).abs() < 1e-14,
            "{v:?}"
        );
        // A needle of length 9 in a periodic side of 10: 1 apart from its image without
        // a gap, but the gap 0.2 asks for 0.2 · 9 = 1.8.
        let long = [grain(0, [5.0, 5.0, 5.0], [4.5, 0.5, 0.5])];
        assert!(verify(&long, &domain(Boundary::Periodic), 0.0)
            .unwrap()
            .is_clean());
        let v = verify(&long, &domain(Boundary::Periodic), gap).unwrap();
        assert_eq!(v.self_images, 1);
    }

    #[test]
    fn verify_rejects_what_is_not_a_packing() {
        let misnumbered = [grain(3, [5.0; 3], [1.0; 3])];
        assert!(matches!(
            verify(&misnumbered, &domain(Boundary::Periodic), 0.0),
            Err(PackError::Misnumbered { index: 0, id: 3 })
        ));
        let flat = [grain(0, [5.0; 3], [1.0, 0.0, 1.0])];
        assert!(verify(&flat, &domain(Boundary::Periodic), 0.0).is_err());
    }
}
