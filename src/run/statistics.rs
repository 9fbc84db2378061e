//! The packed grains against the scene's laws: packing fractions, per phase the
//! shares, sizes, shapes and tilt angles, and how far grains turned. `summary.json`
//! and the closing report are these values.

use super::plane_statistics::{AngleStatistics, PlaneStatistics};
use super::quantity::{quantity, QuantityStatistics};
use crate::contact::Dimension;
use crate::laws::{ks_distance, Moments, VonMisesCdf};
use crate::packing::{sorted_turns, PackedGrain, Packing};
use crate::scene::{aspect_ratio, tilt_angle, GrainCount, GrainSpec, Orientation, Phase, Scene};
use serde::Serialize;

/// The statistics of a packing of grains drawn from a scene.
#[derive(Debug, Clone, Serialize)]
pub struct Statistics {
    /// The scene's `target_fraction`, or for a `grains` count its expected fraction.
    pub target_fraction: f64,
    /// Fraction the drawn grains fill at full size (scale 1).
    pub full_size_fraction: f64,
    /// Fraction the packed grains fill: `Σ (4π/3) a1 a2 a3 / (Lx Ly Lz)`, or the
    /// area fraction `Σ π a1 a2 / (Lx Ly)` in 2D.
    pub packing_fraction: f64,
    /// Whether and how far grains turned from their drawn orientations.
    pub rotation: TurnStatistics,
    /// Per phase, in scene order.
    pub phases: Vec<PhaseStatistics>,
    /// In 2D, the arrangement of the centres: hexatic order and nearest neighbours.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub plane: Option<PlaneStatistics>,
}

impl Statistics {
    /// The statistics of `packing`, a packing of `specs` drawn from `scene`.
    pub fn new(scene: &Scene, specs: &[GrainSpec], packing: &Packing) -> Self {
        let volume = scene.domain.volume();
        let dimension = scene.domain.dimension;
        let grain_volume = |g: &PackedGrain| dimension.measure(g.semi_axes);
        let packed: f64 = packing.grains.iter().map(grain_volume).sum();
        let full: f64 = specs.iter().map(GrainSpec::volume).sum();
        let count_weight: f64 = scene
            .phases
            .iter()
            .map(|p| p.share / p.expected_volume())
            .sum();
        let phases = scene
            .phases
            .iter()
            .enumerate()
            .map(|(index, phase)| {
                let grains: Vec<&PackedGrain> =
                    packing.grains.iter().filter(|g| g.phase == index).collect();
                let phase_volume: f64 = grains.iter().map(|g| grain_volume(g)).sum();
                let (diameter, aspect_ratio, tilt_angle_deg) =
                    grain_statistics(phase, dimension, &grains);
                PhaseStatistics {
                    name: phase.name.clone(),
                    grains: grains.len(),
                    count_share: Share {
                        target: phase.share / phase.expected_volume() / count_weight,
                        achieved: ratio(grains.len() as f64, packing.grains.len() as f64),
                    },
                    volume_share: Share {
                        target: phase.share,
                        achieved: ratio(phase_volume, packed),
                    },
                    diameter,
                    aspect_ratio,
                    tilt_angle_deg,
                    shape: super::shape_statistics::shape(phase, &grains),
                    orientation_3d: super::shape_statistics::orientation(phase, &grains),
                    size_table: super::size_table::size_table(&phase.size, dimension, &grains),
                    angle_deg: match dimension {
                        Dimension::Two => AngleStatistics::of(&grains),
                        Dimension::Three => None,
                    },
                }
            })
            .collect();
        let turns = sorted_turns(specs, &packing.grains);
        let rotation = TurnStatistics {
            mode: scene.packing.rotation.name(),
            max_turn_deg: scene.packing.max_turn.to_degrees(),
            median_turn_deg: turns.get(turns.len() / 2).map_or(0.0, |t| t.to_degrees()),
            largest_turn_deg: turns.last().map_or(0.0, |t| t.to_degrees()),
        };
        Self {
            target_fraction: match scene.count {
                GrainCount::Fraction(f) => f,
                GrainCount::Exactly(_) => scene.expected_fraction(),
            },
            full_size_fraction: full / volume,
            packing_fraction: packed / volume,
            rotation,
            phases,
            // The octree takes the box the loop packed in: it cannot fail here.
            plane: match dimension {
                Dimension::Two => PlaneStatistics::of(&packing.grains, &scene.domain).ok(),
                Dimension::Three => None,
            },
        }
    }
}

/// `packing.rotation` and `packing.max_turn` as the loop ran them, and the turns of the
/// written grains from their drawn orientations.
#[derive(Debug, Clone, Copy, Serialize)]
pub struct TurnStatistics {
    /// `"none"`, `"free"` or `"axis"`.
    pub mode: &'static str,
    /// The limit on any grain's turn, in degrees (180: none).
    pub max_turn_deg: f64,
    /// Median turn over the grains, in degrees (0 when grains do not turn).
    pub median_turn_deg: f64,
    /// Largest turn, in degrees.
    pub largest_turn_deg: f64,
}

/// A share asked for and the share obtained.
#[derive(Debug, Clone, Copy, Serialize)]
pub struct Share {
    /// Asked for (or expected).
    pub target: f64,
    /// Obtained.
    pub achieved: f64,
}

/// One phase: its shares and its grain statistics.
#[derive(Debug, Clone, Serialize)]
pub struct PhaseStatistics {
    /// The phase's name.
    pub name: String,
    /// Its grains.
    pub grains: usize,
    /// Share of the number of grains: expected `(sₚ/E[vₚ]) / Σ_q (s_q/E[v_q])` for
    /// volume shares `s`, against the count.
    pub count_share: Share,
    /// Share of the grain volume: the scene's share against the packed volumes.
    pub volume_share: Share,
    /// Equivalent-sphere diameter `2 (a1 a2 a3)^{1/3}` of the packed grains (in 2D,
    /// the equivalent-circle diameter `2 √(a1 a2)`).
    pub diameter: QuantityStatistics,
    /// Aspect ratio `a1/a2` of the packed grains.
    pub aspect_ratio: QuantityStatistics,
    /// Tilt angle in degrees, for a tilt orientation: the angle of the first axis in
    /// the plane normal to the tilt axis, recovered from the packed quaternion.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub tilt_angle_deg: Option<QuantityStatistics>,
    /// For triaxial phases: the three semi-axis ratios against their laws.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub shape: Option<super::shape_statistics::ShapeStatistics>,
    /// For `kind = "fisher"`: the first axis's angle to the mean direction and the spin.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub orientation_3d: Option<super::shape_statistics::OrientationStatistics>,
    /// For `distribution = "table"` sizes: the fraction passing each tabulated size,
    /// by number or by volume as the table counts.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub size_table: Option<super::size_table::SizeTableStatistics>,
    /// In 2D, the angles of the ellipses' first semi-axes from x.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub angle_deg: Option<AngleStatistics>,
}

/// `a / b`, or 0 when `b` is 0 (no grains).
fn ratio(a: f64, b: f64) -> f64 {
    if b > 0.0 {
        a / b
    } else {
        0.0
    }
}

/// The diameter, aspect-ratio and (for a tilt orientation) tilt statistics of a phase's
/// packed grains.
fn grain_statistics(
    phase: &Phase,
    dimension: Dimension,
    grains: &[&PackedGrain],
) -> (
    QuantityStatistics,
    QuantityStatistics,
    Option<QuantityStatistics>,
) {
    let diameters: Vec<f64> = grains
        .iter()
        .map(|g| dimension.equivalent_diameter(g.semi_axes))
        .collect();
    let aspects: Vec<f64> = grains.iter().map(|g| aspect_ratio(g.semi_axes)).collect();
    let tilt_angle_deg = match phase.orientation {
        Orientation::Tilt { axis, angle } => {
            let law = VonMisesCdf::new(&angle);
            let thetas: Vec<f64> = grains
                .iter()
                .map(|g| tilt_angle(g.quaternion, axis, &angle))
                .collect();
            let degrees = |m: Moments| Moments {
                mean: m.mean.to_degrees(),
                std: m.std.to_degrees(),
            };
            Some(QuantityStatistics {
                target: degrees(law.moments()),
                achieved: Moments::of_sample(&thetas).map(degrees),
                ks_distance: ks_distance(&thetas, |t| law.cdf(t)),
            })
        }
        _ => None,
    };
    (
        quantity(&phase.size, &diameters),
        super::shape_statistics::aspect_ratio(phase, &aspects),
        tilt_angle_deg,
    )
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::packing::{Counters, StopReason, Verification};

    const SCENE: &str = r#"
        seed = 4
        grains = 200
        [box]
        size = [60, 60, 60]
        [[phase]]
        name = "round"
        share = 3
        size = { distribution = "constant", value = 5 }
        [[phase]]
        name = "tilted"
        size = { distribution = "uniform", min = 4, max = 6 }
        aspect_ratio = { distribution = "constant", value = 2 }
        orientation = { kind = "tilt", axis = "x", kappa = 2, mean = 90, min = 0, max = 180 }
    "#;

    /// The drawn grains as if packed at `scale`, at arbitrary centres.
    fn packing(specs: &[GrainSpec], scale: f64) -> Packing {
        Packing {
            grains: specs
                .iter()
                .enumerate()
                .map(|(i, s)| {
                    PackedGrain::of_spec(i as u32, s, scale, [i as f64 * 0.1; 3], s.quaternion)
                })
                .collect(),
            scale,
            fraction: 0.0,
            stop: StopReason::TargetReached,
            counters: Counters::default(),
            trials: Vec::new(),
            verification: Verification {
                gap: 0.0,
                checked_pairs: 0,
                overlapping_pairs: 0,
                gap_violations: 0,
                min_mu2: f64::INFINITY,
                min_gap: f64::INFINITY,
                wall_violations: 0,
                self_images: 0,
            },
        }
    }

    fn statistics(scale: f64) -> (Statistics, Vec<GrainSpec>) {
        let scene = Scene::from_str(SCENE, "test.toml").unwrap();
        let specs = scene.sample_grains(&mut scene.rng()).unwrap();
        (
            Statistics::new(&scene, &specs, &packing(&specs, scale)),
            specs,
        )
    }

    #[test]
    fn summary_of_grains_at_full_size_meets_the_constant_laws_exactly() {
        let (s, specs) = statistics(1.0);
        // The same volumes summed as (π/6) d³ and as (4π/3) a1 a2 a3: a few ulps each.
        let rel = (s.packing_fraction - s.full_size_fraction).abs() / s.full_size_fraction;
        assert!(rel < 1e-14, "{rel}");
        let [round, tilted] = &s.phases[..] else {
            panic!("two phases")
        };
        assert_eq!(round.grains + tilted.grains, 200);
        assert_eq!(specs.len(), 200);
        assert_eq!(round.diameter.ks_distance, Some(0.0));
        assert_eq!(round.aspect_ratio.ks_distance, Some(0.0));
        assert_eq!(tilted.aspect_ratio.ks_distance, Some(0.0));
        assert!(round.tilt_angle_deg.is_none());
        let tilt = tilted.tilt_angle_deg.unwrap();
        // The recovered angles are the drawn ones, to rounding.
        let drawn: Vec<f64> = specs.iter().filter_map(|g| g.tilt).collect();
        let want = Moments::of_sample(&drawn).unwrap().mean.to_degrees();
        assert!((tilt.achieved.unwrap().mean - want).abs() < 1e-10);
        // A symmetric law about 90°, cut symmetrically.
        assert!((tilt.target.mean - 90.0).abs() < 1e-9);
        // Shares: 3 : 1 by volume, within one grain of it (grains of volume ≤ 113 in
        // a total of about 200 × 70).
        assert_eq!(round.volume_share.target, 0.75);
        assert!((round.volume_share.achieved - 0.75).abs() < 0.01);
        let shares = round.count_share.achieved + tilted.count_share.achieved;
        assert!((shares - 1.0).abs() < 1e-15);
        let json = serde_json::to_value(&s).unwrap();
        assert!(json["phases"][0].get("tilt_angle_deg").is_none());
        assert!(json["phases"][1]["tilt_angle_deg"]["ks_distance"].is_f64());
    }

    #[test]
    fn summary_of_a_shrunk_packing_reports_its_fraction_and_misses_constant_sizes() {
        let (s, _) = statistics(0.5);
        // Halving a semi-axis is exact in binary, so each grain's volume is 1/8 of
        // (4π/3) a1 a2 a3 at full size, which is (π/6) d³ to a few ulps.
        let rel = (8.0 * s.packing_fraction - s.full_size_fraction).abs() / s.full_size_fraction;
        assert!(rel < 1e-14, "{rel}");
        assert_eq!(s.phases[0].diameter.ks_distance, Some(1.0));
        // The aspect ratio does not change with scale.
        assert_eq!(s.phases[1].aspect_ratio.ks_distance, Some(0.0));
    }
}
