//! The panels beyond a phase's first three, drawn on lines of their own below it: the
//! declared third shape ratio of a triaxial phase (`c/a` or `c/b`), the spin of a
//! `fisher` phase, and the size CDF of a tabulated size law against the table. And the
//! KS distances `summary.json` reports, put in the legends of every panel (taken from
//! the run's statistics, not computed again).

use super::angles::axis_polar_angle;
use super::cdf::CdfPanel;
use super::panel::{Panel, Row};
use super::target::{
    curve, distribution_target, histogram_curve, law_moments, law_name, tilt_curve_window, Target,
};
use super::VoxelSample;
use crate::contact::{ellipsoid_volume, equivalent_diameter, rotation_column};
use crate::laws::{Distribution, Moments, TableBasis, TableInterpolation, VonMisesCdf};
use crate::packing::PackedGrain;
use crate::run::{PhaseStatistics, WeightedCdf};
use crate::scene::{aspect_ratio, Orientation, Phase, Spin, ThirdRatio};
use std::f64::consts::PI;

/// A panel on a phase's extra lines.
#[derive(Debug, Clone)]
pub(super) enum Extra {
    /// A histogram against a density, as in the first three columns.
    Density(Panel),
    /// A CDF against a tabulated one.
    Cdf(CdfPanel),
}

/// Completes the rows of the figure (one per phase, from [`rows`](super::rows::rows)):
/// their panels get the table's targets of a measured phase ([`set_measured`]) and the
/// KS distances of `statistics` ([`set_ks`]); returns each phase's extra panels
/// ([`panels`]).
pub(super) fn complete(
    rows: &mut [Row],
    phases: &[Phase],
    packed: &[PackedGrain],
    voxel: Option<&[VoxelSample]>,
    statistics: Option<&[PhaseStatistics]>,
) -> Vec<Vec<Extra>> {
    rows.iter_mut()
        .zip(phases)
        .enumerate()
        .map(|(index, (row, phase))| {
            let grains: Vec<&PackedGrain> = packed.iter().filter(|g| g.phase == index).collect();
            let samples: Option<Vec<&VoxelSample>> =
                voxel.map(|v| v.iter().filter(|s| s.phase == index).collect());
            let stats = statistics.and_then(|s| s.get(index));
            set_measured(&mut row.panels, phase);
            set_ks(&mut row.panels, phase, stats);
            panels(phase, &grains, samples.as_deref(), stats)
        })
        .collect()
}

/// Puts the KS distances of `stats` (the phase's `summary.json` entry) into the
/// legends of its three panels: diameter, aspect ratio (`b/a` for a triaxial phase),
/// and the tilt angle or the `fisher` first axis's angle.
pub(super) fn set_ks(panels: &mut [Panel; 3], phase: &Phase, stats: Option<&PhaseStatistics>) {
    let Some(s) = stats else { return };
    panels[0].ks_distance = s.diameter.ks_distance;
    panels[1].ks_distance = match (&phase.triaxial, &s.shape) {
        (Some(_), Some(shape)) => shape.b_over_a.ks_distance,
        (Some(_), None) => None,
        (None, _) => s.aspect_ratio.ks_distance,
    };
    panels[2].ks_distance = match (&s.tilt_angle_deg, &s.orientation_3d) {
        (Some(t), _) => t.ks_distance,
        (None, Some(o)) => o.axis_angle_deg.ks_distance,
        (None, None) => None,
    };
}

/// A measured table's phase: its aspect ratios (for a table with semi-axes) and its
/// first axes' angles to z (for a table with orientations) are the table's, so the
/// second and third panels compare with the table's own values, as `summary.json` does.
pub(super) fn set_measured(panels: &mut [Panel; 3], phase: &Phase) {
    let Some(m) = &phase.measured else { return };
    let against_table = |panel: &mut Panel, mut values: Vec<f64>| {
        values.sort_by(f64::total_cmp);
        panel.law = "target: the measured table".into();
        panel.law_moments = Moments::of_sample(&values);
        panel.target = Target::Curve(histogram_curve(&values));
    };
    if m.has_semi_axes() {
        let ratios = m
            .grains
            .iter()
            .filter_map(|g| g.semi_axes.map(aspect_ratio));
        against_table(&mut panels[1], ratios.collect());
    }
    if m.has_orientations() && matches!(phase.orientation, Orientation::Random) {
        let angles = m
            .grains
            .iter()
            .filter_map(|g| g.quaternion.map(|q| axis_polar_angle(q).to_degrees()));
        against_table(&mut panels[2], angles.collect());
    }
}

/// The extra panels of a phase, in this order: the third shape ratio, the spin, the
/// size table's CDF; empty for a phase with none of these laws.
pub(super) fn panels(
    phase: &Phase,
    grains: &[&PackedGrain],
    voxel: Option<&[&VoxelSample]>,
    stats: Option<&PhaseStatistics>,
) -> Vec<Extra> {
    let mut extra = Vec::new();
    if let Some(t) = &phase.triaxial {
        // (name, x label, law, semi-axis divided by, index in the voxel ratios, KS)
        let shape = stats.and_then(|s| s.shape);
        let (name, x_label, law, den, index, ks) = match &t.third {
            ThirdRatio::OverA(law) => (
                "c/a",
                "shape ratio c/a = a3/a1 (dimensionless)",
                law,
                0,
                1,
                shape.and_then(|x| x.c_over_a.ks_distance),
            ),
            ThirdRatio::OverB(law) => (
                "c/b",
                "shape ratio c/b = a3/a2 (dimensionless)",
                law,
                1,
                2,
                shape.and_then(|x| x.c_over_b.ks_distance),
            ),
        };
        extra.push(Extra::Density(Panel {
            title: format!("shape ratio {name}"),
            x_label,
            y_label: "probability density",
            law: law_name(law),
            law_moments: law_moments(law),
            target: distribution_target(law),
            packed: grains
                .iter()
                .map(|g| g.semi_axes[2] / g.semi_axes[den])
                .collect(),
            voxel: voxel.map(|v| {
                v.iter()
                    .filter_map(|s| s.shape_ratios.map(|r| r[index]))
                    .collect()
            }),
            ks_distance: ks,
        }));
    }
    if let Orientation::Fisher(law) = &phase.orientation {
        let per_degree = PI / 180.0;
        let (name, moments, target) = match law.spin {
            Spin::Uniform => (
                "target uniform".to_string(),
                // Uniform on [−180°, 180°): mean 0, std 180°/√3.
                Moments {
                    mean: 0.0,
                    std: 180.0 / 3f64.sqrt(),
                },
                Target::Curve(curve(-180.0, 180.0, |_| 1.0 / 360.0)),
            ),
            Spin::VonMises { angle, .. } => {
                let (lo, hi) = tilt_curve_window(&angle);
                let m = VonMisesCdf::new(&angle).moments();
                (
                    format!("target von Mises, \u{3ba} = {}", angle.kappa),
                    Moments {
                        mean: m.mean.to_degrees(),
                        std: m.std.to_degrees(),
                    },
                    Target::Curve(curve(lo.to_degrees(), hi.to_degrees(), |t| {
                        angle.pdf(t.to_radians()) * per_degree
                    })),
                )
            }
        };
        extra.push(Extra::Density(Panel {
            title: "spin about the first axis".into(),
            x_label: "spin of the second axis from its reference (degrees)",
            y_label: "probability density (1/degree)",
            law: name,
            law_moments: Some(moments),
            target,
            packed: grains
                .iter()
                .map(|g| {
                    law.spin_angle(
                        rotation_column(g.quaternion, 0),
                        rotation_column(g.quaternion, 1),
                    )
                    .to_degrees()
                })
                .collect(),
            voxel: voxel.map(|v| {
                v.iter()
                    .filter_map(|s| s.spin.map(f64::to_degrees))
                    .collect()
            }),
            ks_distance: stats.and_then(|s| s.orientation_3d.and_then(|o| o.spin_deg.ks_distance)),
        }));
    }
    if let Distribution::Table(table) = &phase.size {
        let by_volume = table.basis == TableBasis::Volume;
        let weighted: Vec<(f64, f64)> = grains
            .iter()
            .map(|g| {
                let w = if by_volume {
                    ellipsoid_volume(g.semi_axes)
                } else {
                    1.0
                };
                (equivalent_diameter(g.semi_axes), w)
            })
            .collect();
        let packed = WeightedCdf::new(&weighted);
        let table_stats = stats.and_then(|s| s.size_table.as_ref());
        let (lo, hi) = table.support();
        extra.push(Extra::Cdf(CdfPanel {
            title: if by_volume {
                "size grading: volume passing".into()
            } else {
                "size CDF: number passing".into()
            },
            x_label: "equivalent diameter (box units)",
            y_label: if by_volume {
                "volume fraction passing"
            } else {
                "number fraction passing"
            },
            law: format!(
                "table by {}, {} interpolation",
                if by_volume { "volume" } else { "number" },
                match table.interpolation {
                    TableInterpolation::Linear => "linear",
                    TableInterpolation::Log => "log",
                }
            ),
            // The curve without the drops to 0 at its ends that densities have.
            target: {
                let c = curve(lo, hi, |x| table.given_cdf(x));
                c[1..c.len() - 1].to_vec()
            },
            table_points: table
                .x
                .iter()
                .zip(table.fraction.iter())
                .map(|(&x, &f)| (x, f))
                .collect(),
            packed_steps: packed.map(|c| c.x.into_iter().zip(c.w).collect()),
            packed_at_table: table_stats.and_then(|t| {
                t.achieved
                    .as_ref()
                    .map(|a| t.sizes.iter().copied().zip(a.iter().copied()).collect())
            }),
            grains: grains.len(),
            ks_distance: table_stats.and_then(|t| t.ks_distance),
            max_deviation: table_stats.and_then(|t| t.max_deviation),
        }));
    }
    extra
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::scene::Scene;

    /// A triaxial `fisher` phase with a uniform spin and a number size table.
    const SCENE: &str = r#"
        seed = 5
        grains = 300
        [box]
        size = [60, 60, 60]
        [[phase]]
        size = { distribution = "table", x = [3.0, 5.0, 8.0], cdf = [0.0, 0.6, 1.0] }
        b_over_a = { distribution = "uniform", min = 0.5, max = 0.8 }
        c_over_b = { distribution = "uniform", min = 0.4, max = 0.9 }
        orientation = { kind = "fisher", direction = "z", kappa = 10.0 }
    "#;

    fn extra() -> Vec<Extra> {
        let scene = Scene::from_str(SCENE, "test.toml").unwrap();
        let specs = scene.sample_grains(&mut scene.rng()).unwrap();
        let packed: Vec<PackedGrain> = specs
            .iter()
            .enumerate()
            .map(|(i, s)| PackedGrain::of_spec(i as u32, s, 1.0, [0.0; 3], s.quaternion))
            .collect();
        let grains: Vec<&PackedGrain> = packed.iter().collect();
        panels(&scene.phases[0], &grains, None, None)
    }

    /// The trapezoid area of a density curve.
    fn area(points: &[(f64, f64)]) -> f64 {
        points
            .windows(2)
            .map(|w| 0.5 * (w[0].1 + w[1].1) * (w[1].0 - w[0].0))
            .sum()
    }

    #[test]
    fn triaxial_fisher_table_phase_gets_c_over_b_spin_and_cdf_panels() {
        let [Extra::Density(cb), Extra::Density(spin), Extra::Cdf(cdf)] = &extra()[..] else {
            panic!("c/b, spin, size CDF")
        };
        assert_eq!(cb.title, "shape ratio c/b");
        // a3/a2 of grains drawn with c/b in [0.4, 0.9], to rounding.
        assert!(cb
            .packed
            .iter()
            .all(|&r| (0.4 - 1e-12..=0.9 + 1e-12).contains(&r)));
        // The uniform spin's density is 1/360 per degree over 360°: area 1 up to the
        // drops to 0 at the ends, which add none.
        let Target::Curve(points) = &spin.target else {
            panic!("a density")
        };
        assert!((area(points) - 1.0).abs() < 1e-12, "{}", area(points));
        assert!(spin.packed.iter().all(|s| s.abs() <= 180.0));
        // The packed CDF ends at 1 (by number: 300 grains), the table's curve passes
        // through its points.
        let steps = cdf.packed_steps.as_ref().unwrap();
        assert_eq!(steps.len(), 300);
        assert!((steps[299].1 - 1.0).abs() < 1e-12);
        assert_eq!(cdf.table_points, [(3.0, 0.0), (5.0, 0.6), (8.0, 1.0)]);
        let at5 = cdf.target.iter().find(|p| p.0 >= 5.0).unwrap();
        assert!((at5.1 - 0.6).abs() < 0.01, "{at5:?}");
    }
}
