//! The random close packing estimated for drawn grains: the one estimate behind the
//! reachable fraction a run reports and the packing's first scale near jamming.

use super::GrainSpec;
use crate::contact::Dimension;
use crate::laws::{random_close_packing, random_close_packing_discs};

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

#[cfg(test)]
mod tests {
    use super::*;

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
}
