//! The exact check of a packed state: every pair whose bounding spheres meet, and the
//! walls of a walled box.

use super::{PackError, PackedGrain, Verification};
use crate::contact::{contact_function, Ellipsoid};
use crate::octree::{Octree, Params, Sphere};
use crate::scene::{Boundary, Domain};
use rayon::prelude::*;

/// Checks a packed state exactly: the accurate contact function on every pair whose
/// bounding spheres meet (periodic images included), and each grain's extent
/// `√Q_kk` along every axis against the walls of a walled box.
///
/// Fails only on input that is not a packing: an invalid grain, an id that is not its
/// index, or a box the octree rejects.
pub fn verify(grains: &[PackedGrain], domain: &Domain) -> Result<Verification, PackError> {
    let mut shapes = Vec::with_capacity(grains.len());
    for (index, g) in grains.iter().enumerate() {
        if g.id as usize != index {
            return Err(PackError::Misnumbered { index, id: g.id });
        }
        let bad = |source| PackError::Grain { id: index, source };
        shapes.push(Ellipsoid::new(g.semi_axes, g.quaternion).map_err(bad)?);
    }
    let spheres: Vec<Sphere> = grains
        .iter()
        .map(|g| Sphere {
            id: g.id,
            centre: g.centre,
            radius: g.semi_axes.iter().fold(0.0f64, |m, &a| m.max(a)),
        })
        .collect();
    let tree = Octree::build(&spheres, domain.box_shape()?, Params::default())?;
    let mut pairs = Vec::new();
    tree.pairs(&mut pairs);
    // A grain against its own image: the bounding spheres only say it may.
    let self_images = pairs
        .iter()
        .filter(|p| p.i == p.j)
        .filter(|p| {
            let q = &shapes[p.i as usize].q;
            contact_function(&p.shift, q, q).map_or(true, |c| c.mu2 < 1.0)
        })
        .count();
    let mu2: Vec<f64> = pairs
        .par_iter()
        .filter(|p| p.i != p.j)
        .map(|p| {
            let (ci, cj) = (grains[p.i as usize].centre, grains[p.j as usize].centre);
            let r = [0, 1, 2].map(|k| cj[k] + p.shift[k] - ci[k]);
            // An error here (overflow) counts as an overlap: it is not a proof of
            // separation.
            contact_function(&r, &shapes[p.i as usize].q, &shapes[p.j as usize].q)
                .map_or(0.0, |c| c.mu2)
        })
        .collect();
    let wall_violations = match domain.boundary {
        Boundary::Periodic => 0,
        Boundary::Reflecting => grains
            .iter()
            .zip(&shapes)
            .filter(|(g, e)| {
                let diag = [e.q[0], e.q[3], e.q[5]];
                (0..3).any(|k| {
                    let w = diag[k].sqrt();
                    g.centre[k] - w < 0.0 || g.centre[k] + w > domain.size[k]
                })
            })
            .count(),
    };
    Ok(Verification {
        checked_pairs: mu2.len(),
        overlapping_pairs: mu2.iter().filter(|&&m| m < 1.0).count(),
        min_mu2: mu2.iter().copied().fold(f64::INFINITY, f64::min),
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
        Domain {
            size: [10.0, 10.0, 10.0],
            boundary,
        }
    }

    #[test]
    fn verify_finds_an_overlap_across_a_periodic_face() {
        // Needles along x, 2.2 apart through the x face, reaching 1.2 each: they overlap.
        let grains = [
            grain(0, [0.5, 5.0, 5.0], [1.2, 0.2, 0.2]),
            grain(1, [8.3, 5.0, 5.0], [1.2, 0.2, 0.2]),
        ];
        let v = verify(&grains, &domain(Boundary::Periodic)).unwrap();
        assert_eq!((v.checked_pairs, v.overlapping_pairs), (1, 1));
        assert!(v.min_mu2 < 1.0 && !v.is_clean());
        // Walls: no image, so the same two are far apart.
        let v = verify(&grains, &domain(Boundary::Reflecting)).unwrap();
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
        let v = verify(&grains, &domain(Boundary::Reflecting)).unwrap();
        assert_eq!((v.checked_pairs, v.overlapping_pairs), (1, 0));
        assert!((v.min_mu2 - (1.0 + 1e-9f64).powi(2)).abs() < 1e-15);
        assert!(v.is_clean());
    }

    #[test]
    fn verify_finds_a_grain_through_a_wall_and_one_meeting_its_image() {
        let through = [grain(0, [0.5, 5.0, 5.0], [1.0, 0.5, 0.5])];
        let v = verify(&through, &domain(Boundary::Reflecting)).unwrap();
        assert_eq!(v.wall_violations, 1);
        let long = [grain(0, [5.0, 5.0, 5.0], [5.5, 0.5, 0.5])];
        let v = verify(&long, &domain(Boundary::Periodic)).unwrap();
        assert_eq!(v.self_images, 1);
        assert!(!v.is_clean());
    }

    #[test]
    fn verify_rejects_what_is_not_a_packing() {
        let misnumbered = [grain(3, [5.0; 3], [1.0; 3])];
        assert!(matches!(
            verify(&misnumbered, &domain(Boundary::Periodic)),
            Err(PackError::Misnumbered { index: 0, id: 3 })
        ));
        let flat = [grain(0, [5.0; 3], [1.0, 0.0, 1.0])];
        assert!(verify(&flat, &domain(Boundary::Periodic)).is_err());
    }
}
