//! The random close packing estimated for drawn grains: the one estimate behind the
//! reachable fraction a run reports and the packing's first scale near jamming; and how
//! far frozen grains are from an affine image of spheres.

use super::GrainSpec;
use crate::contact::{rotation_matrix, Dimension};
use crate::laws::{random_close_packing, random_close_packing_discs};
use nalgebra::{Matrix3, SymmetricEigen};

/// The random close packing of spheres (discs in 2D) with the equivalent diameters of
/// `specs`, by Farr and Groot's one-dimensional model
/// ([`random_close_packing`], [`random_close_packing_discs`]): 0.6435 for equal
/// spheres, 0.834 for equal discs, more for spread sizes. Exact for spheres only;
/// grains free to turn pack denser. `None` where the model has no answer (no grains,
/// or sizes that are not positive and finite).
pub fn sphere_close_packing(specs: &[GrainSpec], dimension: Dimension) -> Option<f64> {
    let diameters: Vec<f64> = (specs.iter())
        .map(|s| dimension.equivalent_diameter(s.semi_axes))
        .collect();
    match dimension {
        Dimension::Three => random_close_packing(&diameters),
        Dimension::Two => random_close_packing_discs(&diameters),
    }
}

/// How many grains [`affine_slenderness`] looks at: the first ones drawn, a random
/// sample of the scene's laws.
const SHAPE_SAMPLE: usize = 4096;

/// The mean slenderness (longest over shortest semi-axis) of the grains after the one
/// linear map of space that makes their mean shape round. A linear map changes no
/// packing fraction and no overlap, so grains that do not turn jam as their mapped
/// images do: aligned grains of one shape map to spheres (1 here), grains turned at
/// random stay as slender as they are. Shapes are taken at unit volume (the form
/// `R diag(a²) Rᵀ` over `(a₁a₂a₃)^{2/3}`), over the first 4 096 grains
/// (`SHAPE_SAMPLE`). 1 for no grains or forms that are not finite and definite.
pub fn affine_slenderness(specs: &[GrainSpec]) -> f64 {
    let sample = &specs[..specs.len().min(SHAPE_SAMPLE)];
    if sample.is_empty() {
        return 1.0;
    }
    let form = |s: &GrainSpec| {
        let r = rotation_matrix(s.quaternion);
        let [a, b, c] = s.semi_axes;
        let unit = (a * b * c).powf(2.0 / 3.0);
        r * Matrix3::from_diagonal(&[a * a, b * b, c * c].into()) * r.transpose() / unit
    };
    let forms: Vec<Matrix3<f64>> = sample.iter().map(form).collect();
    let mean = forms.iter().sum::<Matrix3<f64>>() / forms.len() as f64;
    let eigen = SymmetricEigen::new(mean);
    if !eigen.eigenvalues.iter().all(|&l| l.is_finite() && l > 0.0) {
        return 1.0;
    }
    // mean^{-1/2}: the map that makes the mean form the identity.
    let root = eigen.eigenvalues.map(|l| 1.0 / l.sqrt());
    let map = eigen.eigenvectors * Matrix3::from_diagonal(&root) * eigen.eigenvectors.transpose();
    let slenderness = |f: &Matrix3<f64>| {
        let l = SymmetricEigen::new(map * f * map).eigenvalues;
        (l.max() / l.min()).sqrt()
    };
    let mean = forms.iter().map(slenderness).sum::<f64>() / forms.len() as f64;
    if mean.is_finite() {
        mean
    } else {
        1.0
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use nalgebra::{UnitQuaternion, Vector3};

    #[test]
    fn equal_spheres_and_discs_take_the_models_values() {
        let spheres = vec![GrainSpec::new(0, 2.0, 1.0, [1.0, 0.0, 0.0, 0.0], None); 10];
        let discs = vec![GrainSpec::ellipse(0, 2.0, 1.0, 0.0); 10];
        let d = [2.0; 10];
        assert_eq!(
            sphere_close_packing(&spheres, Dimension::Three),
            random_close_packing(&d)
        );
        assert_eq!(
            sphere_close_packing(&discs, Dimension::Two),
            random_close_packing_discs(&d)
        );
        assert_eq!(sphere_close_packing(&[], Dimension::Three), None);
    }

    #[test]
    fn aligned_grains_map_to_spheres_and_turned_ones_keep_their_slenderness() {
        let turned = |k: usize| {
            // Orientations spread over the sphere (a golden-angle spiral of first axes),
            // each the shortest turn taking x there.
            let z = 1.0 - 2.0 * (k as f64 + 0.5) / 400.0;
            let phi = 2.399_963_229_728_653 * k as f64;
            let axis = Vector3::new(
                (1.0 - z * z).sqrt() * phi.cos(),
                (1.0 - z * z).sqrt() * phi.sin(),
                z,
            );
            let q = UnitQuaternion::rotation_between(&Vector3::x(), &axis)
                .unwrap_or_else(UnitQuaternion::identity);
            [q.w, q.i, q.j, q.k]
        };
        let aligned = vec![GrainSpec::new(0, 2.0, 2.0, [1.0, 0.0, 0.0, 0.0], None); 50];
        assert!((affine_slenderness(&aligned) - 1.0).abs() < 1e-9);
        let random: Vec<GrainSpec> = (0..400)
            .map(|k| GrainSpec::new(0, 2.0, 2.0, turned(k), None))
            .collect();
        let s = affine_slenderness(&random);
        assert!((s - 2.0).abs() < 0.05, "{s}");
        let spheres = vec![GrainSpec::new(0, 2.0, 1.0, [1.0, 0.0, 0.0, 0.0], None); 5];
        assert!((affine_slenderness(&spheres) - 1.0).abs() < 1e-12);
        assert_eq!(affine_slenderness(&[]), 1.0);
    }
}
