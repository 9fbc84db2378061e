//! The orientation panel of the statistics figure: the angle of each grain's first
//! semi-axis (to z, to a Fisher law's mean, from x in 2D) or its tilt angle, against
//! the target law's density.

use super::panel::Panel;
use super::target::{curve, tilt_curve_window, Target, CURVE_SIGMAS};
use crate::contact::{ellipse_angle, ellipse_quaternion, rotation_column};
use crate::laws::{Moments, VonMisesCdf};
use crate::packing::PackedGrain;
use crate::scene::{tilt_angle, Orientation};
use std::f64::consts::PI;

/// The angle `θ` (radians, in `[0, π/2]`) between the first semi-axis of a grain
/// oriented by the unit quaternion `q` and the z axis: `acos |e·ẑ|`, with `e` column 0
/// of the rotation, computed as `atan2(√(e_x² + e_y²), |e_z|)`, which keeps its accuracy
/// near 0 where `acos` would turn a rounding of `e_z` into an angle of `√(2ε)`. The
/// first semi-axis is the axis of revolution: the long axis of a
/// prolate grain, the normal of an oblate one. An axis has no sign, hence `|e·ẑ|`.
///
/// For uniformly random orientations its density is `sin θ` (an isotropic axis).
///
/// ```
/// use grainpack::io::plots::axis_polar_angle;
/// use std::f64::consts::FRAC_PI_2;
/// assert!((axis_polar_angle([1.0, 0.0, 0.0, 0.0]) - FRAC_PI_2).abs() < 1e-15); // x
/// let h = std::f64::consts::FRAC_1_SQRT_2; // a quarter turn about y takes x to −z
/// assert!(axis_polar_angle([h, 0.0, h, 0.0]).abs() < 1e-15);
/// ```
pub fn axis_polar_angle(q: [f64; 4]) -> f64 {
    let e = rotation_column(q, 0);
    e[0].hypot(e[1]).atan2(e[2].abs())
}

/// The third panel. A tilt law: the tilt angle against the von Mises density. Any other
/// orientation: the angle of the first semi-axis to z ([`axis_polar_angle`]), against
/// `sin θ` for random orientations and as a single value for aligned or fixed ones.
/// Angles are shown in degrees, so densities are per degree.
pub(super) fn angle_panel(orientation: &Orientation, grains: &[&PackedGrain]) -> Panel {
    let per_degree = PI / 180.0;
    let degrees = |m: Moments| Moments {
        mean: m.mean.to_degrees(),
        std: m.std.to_degrees(),
    };
    let polar: Vec<f64> = grains
        .iter()
        .map(|g| axis_polar_angle(g.quaternion).to_degrees())
        .collect();
    let polar_panel = |law: &str, law_moments: Option<Moments>, target: Target| Panel {
        title: "first axis to z".into(),
        x_label: "angle of the first axis to z (degrees)",
        y_label: "probability density (1/degree)",
        law: law.into(),
        law_moments,
        target,
        packed: polar.clone(),
        voxel: None,
        ks_distance: None,
    };
    match *orientation {
        Orientation::Tilt { axis, angle } => {
            let (lo, hi) = tilt_curve_window(&angle);
            // One quadrature for the normalisation, not one per point: the density at
            // a reference angle times the ratio e^{κ (cos(θ − μ) − cos(θ_ref − μ))}.
            let reference = angle.mean.clamp(lo, hi);
            let scale = angle.pdf(reference) * per_degree;
            let shape = |t: f64| angle.kappa * (t - angle.mean).cos();
            Panel {
                title: format!("tilt angle about {}", axis_name(axis.index())),
                x_label: "tilt angle (degrees)",
                y_label: "probability density (1/degree)",
                law: format!("target von Mises, \u{3ba} = {}", angle.kappa),
                law_moments: Some(degrees(VonMisesCdf::new(&angle).moments())),
                target: Target::Curve(curve(lo.to_degrees(), hi.to_degrees(), |t| {
                    scale * (shape(t.to_radians()) - shape(reference)).exp()
                })),
                packed: grains
                    .iter()
                    .map(|g| tilt_angle(g.quaternion, axis, &angle).to_degrees())
                    .collect(),
                voxel: None,
                ks_distance: None,
            }
        }
        Orientation::Fisher(law) => {
            let (mean, std) = law.fisher.angle_moments();
            let hi = (CURVE_SIGMAS / law.fisher.kappa.sqrt()).min(PI);
            Panel {
                title: "first axis to its mean direction".into(),
                x_label: "angle of the first axis to the mean (degrees)",
                y_label: "probability density (1/degree)",
                law: format!(
                    "target von Mises\u{2013}Fisher, \u{3ba} = {}",
                    law.fisher.kappa
                ),
                law_moments: Some(degrees(Moments { mean, std })),
                target: Target::Curve(curve(0.0, hi.to_degrees(), |t| {
                    law.fisher.angle_pdf(t.to_radians()) * per_degree
                })),
                packed: grains
                    .iter()
                    .map(|g| {
                        law.axis_angle(rotation_column(g.quaternion, 0))
                            .to_degrees()
                    })
                    .collect(),
                voxel: None,
                ks_distance: None,
            }
        }
        Orientation::Random => {
            // θ with density sin θ on [0, π/2]: E θ = 1 rad, E θ² = π − 2.
            let moments = degrees(Moments {
                mean: 1.0,
                std: (PI - 3.0).sqrt(),
            });
            polar_panel(
                "isotropic, sin \u{3b8}",
                Some(moments),
                Target::Curve(curve(0.0, 90.0, |t| t.to_radians().sin() * per_degree)),
            )
        }
        Orientation::Aligned { axis } => {
            let value = axis[0].hypot(axis[1]).atan2(axis[2].abs()).to_degrees();
            polar_panel("target aligned", None, Target::Value(value))
        }
        Orientation::Fixed { quaternion } => {
            let value = axis_polar_angle(quaternion).to_degrees();
            polar_panel("target fixed", None, Target::Value(value))
        }
    }
}

/// The third panel of a 2D phase without a tilt law (whose tilt about z is the
/// ellipse's angle, [`angle_panel`]): the angle of the first semi-axis from x in
/// `(−90°, 90°]` ([`ellipse_angle`]), against the uniform density `1/180°` for random
/// orientations and as a single value for aligned (the axis's angle in the plane) or
/// fixed ones.
pub(super) fn plane_angle_panel(orientation: &Orientation, grains: &[&PackedGrain]) -> Panel {
    let (law, law_moments, target) = match *orientation {
        // Uniform on (−90°, 90°]: mean 0, standard deviation 180°/√12. (A 2D scene has
        // no fisher law: the uniform density is then only a reference.)
        Orientation::Random | Orientation::Fisher(_) => (
            "uniform",
            Some(Moments {
                mean: 0.0,
                std: 180.0 / 12f64.sqrt(),
            }),
            Target::Curve(vec![
                (-90.0, 0.0),
                (-90.0, 1.0 / 180.0),
                (90.0, 1.0 / 180.0),
                (90.0, 0.0),
            ]),
        ),
        Orientation::Aligned { axis } => (
            "target aligned",
            None,
            Target::Value(ellipse_angle(ellipse_quaternion(axis[1].atan2(axis[0]))).to_degrees()),
        ),
        Orientation::Fixed { quaternion } => (
            "target fixed",
            None,
            Target::Value(ellipse_angle(quaternion).to_degrees()),
        ),
        Orientation::Tilt { .. } => unreachable!("a tilt law has its own panel"),
    };
    Panel {
        title: "first axis from x".into(),
        x_label: "angle of the first axis from x (degrees)",
        y_label: "probability density (1/degree)",
        law: law.into(),
        law_moments,
        target,
        packed: grains
            .iter()
            .map(|g| ellipse_angle(g.quaternion).to_degrees())
            .collect(),
        voxel: None,
        ks_distance: None,
    }
}

/// `"x"`, `"y"` or `"z"`.
fn axis_name(index: usize) -> &'static str {
    ["x", "y", "z"][index.min(2)]
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::io::plots::target::distribution_target;
    use crate::laws::{Distribution, VonMises};

    /// The isotropic density integrates to 1 over [0°, 90°]: the trapezoid rule on 399
    /// intervals of sin errs by (π/2)³/(12·399²) ≈ 2.4e-6 (the drops to 0 at the ends
    /// add no area).
    #[test]
    fn isotropic_curve_is_a_density_in_degrees() {
        let a = area(&angle_panel(&Orientation::Random, &[]).target);
        assert!((a - 1.0).abs() < 1e-5, "{a}");
    }

    /// The area under a curve by the trapezoid rule, its end points at 0 included.
    fn area(target: &Target) -> f64 {
        let Target::Curve(points) = target else {
            panic!("a density")
        };
        points
            .windows(2)
            .map(|w| 0.5 * (w[0].1 + w[1].1) * (w[1].0 - w[0].0))
            .sum()
    }

    /// A law far narrower than its cutoffs: its curve still integrates to 1. With 400
    /// points over ±8 spreads, the trapezoid rule is good to ~1e-4 of the mass.
    #[test]
    fn narrow_laws_get_their_curve_points_where_the_mass_is() {
        let normal = Distribution::Normal {
            mean: 5.0,
            std: 0.001,
            min: 1.0,
            max: 10.0,
        };
        let a = area(&distribution_target(&normal));
        assert!((a - 1.0).abs() < 1e-3, "{a}");
        let tilt = Orientation::Tilt {
            axis: crate::scene::Axis::Z,
            angle: VonMises::new(1.0, 1e6),
        };
        let a = area(&angle_panel(&tilt, &[]).target);
        assert!((a - 1.0).abs() < 1e-3, "{a}");
    }

    #[test]
    fn aligned_along_z_is_a_point_mass_at_zero_degrees() {
        let panel = angle_panel(
            &Orientation::Aligned {
                axis: [0.0, 0.0, 1.0],
            },
            &[],
        );
        assert_eq!(panel.target, Target::Value(0.0));
    }

    #[test]
    fn plane_angles_are_uniform_or_the_aligned_axis_folded_into_a_half_turn() {
        let a = area(&plane_angle_panel(&Orientation::Random, &[]).target);
        assert!((a - 1.0).abs() < 1e-15, "{a}");
        // An axis at 120° is the axis at −60°.
        let t = 120f64.to_radians();
        let aligned = Orientation::Aligned {
            axis: [t.cos(), t.sin(), 0.0],
        };
        let Target::Value(v) = plane_angle_panel(&aligned, &[]).target else {
            panic!("a value")
        };
        assert!((v + 60.0).abs() < 1e-12, "{v}");
    }
}
