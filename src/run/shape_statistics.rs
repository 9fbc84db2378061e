//! Statistics of triaxial shapes and 3D orientations: the semi-axis ratios `b/a`, `c/a`,
//! `c/b` of the packed grains against their laws, and for von Mises–Fisher phases the
//! angle of the first axis to the mean direction and the spin about it.

use super::quantity::{quantity, QuantityStatistics};
use crate::contact::rotation_column;
use crate::laws::{ks_distance, Distribution, EmpiricalLaw, Moments, VonMisesCdf};
use crate::packing::PackedGrain;
use crate::scene::{aspect_ratio as aspect_ratio_of, Orientation, Phase, Spin, ThirdRatio};
use serde::Serialize;
use std::f64::consts::PI;

/// The three semi-axis ratios of a triaxial phase's packed grains (`a1 ≥ a2 ≥ a3`).
#[derive(Debug, Clone, Copy, Serialize)]
pub struct ShapeStatistics {
    /// `a2/a1` against the `b_over_a` law.
    pub b_over_a: QuantityStatistics,
    /// `a3/a1`: against the `c_over_a` law if given; else its moments only (`target`
    /// and `ks_distance` `null`).
    pub c_over_a: RatioStatistics,
    /// `a3/a2`: against the `c_over_b` law if given; else its moments only.
    pub c_over_b: RatioStatistics,
}

/// A ratio that has a law in the scene, or is derived from the two that do.
#[derive(Debug, Clone, Copy, Serialize)]
pub struct RatioStatistics {
    /// Mean and standard deviation of the law; `null` for a derived ratio.
    pub target: Option<Moments>,
    /// Of the packed grains; `null` without grains.
    pub achieved: Option<Moments>,
    /// KS distance to the law; `null` for a derived ratio or without grains.
    pub ks_distance: Option<f64>,
}

impl From<QuantityStatistics> for RatioStatistics {
    fn from(q: QuantityStatistics) -> Self {
        Self {
            target: Some(q.target),
            achieved: q.achieved,
            ks_distance: q.ks_distance,
        }
    }
}

/// The first axis and spin of a von Mises–Fisher phase's packed grains, in degrees.
#[derive(Debug, Clone, Copy, Serialize)]
pub struct OrientationStatistics {
    /// Angle between the first axis and the mean direction, against its law.
    pub axis_angle_deg: QuantityStatistics,
    /// Spin about the first axis against its law (uniform or von Mises).
    pub spin_deg: QuantityStatistics,
}

/// Intervals of Simpson's rule for the moments of `a1/a2 = 1/β`: the densities are
/// smooth on their support and `1/β` is bounded there (β ≥ its lower cutoff > 0), so
/// 2000 intervals are exact to far below the sampling error of any packing.
const SIMPSON_INTERVALS: usize = 2000;

/// The aspect ratio `a1/a2` of a phase's packed grains against its law: the phase's
/// `aspect_ratio` law for spheroids; for triaxial grains the law of `1/β`, `β = b/a`:
/// `P(a1/a2 ≤ x) = 1 − F_β(1/x)`, moments by Simpson's rule over `β`'s density.
pub(crate) fn aspect_ratio(phase: &Phase, sample: &[f64]) -> QuantityStatistics {
    // A measured table with semi-axes: the grains' shapes are the table's, so their
    // law is the table's own (empirical) law of a1/a2.
    if let Some(m) = phase.measured.as_ref().filter(|m| m.has_semi_axes()) {
        let ratios: Vec<f64> = m
            .grains
            .iter()
            .filter_map(|g| g.semi_axes.map(aspect_ratio_of))
            .collect();
        return quantity(&Distribution::Empirical(EmpiricalLaw::new(&ratios)), sample);
    }
    let Some(t) = &phase.triaxial else {
        return quantity(&phase.aspect_ratio, sample);
    };
    let beta = &t.b_over_a;
    match beta {
        Distribution::Constant { value } => {
            quantity(&Distribution::Constant { value: 1.0 / value }, sample)
        }
        Distribution::Empirical(e) => {
            let inv: Vec<f64> = e.sorted.iter().map(|b| 1.0 / b).collect();
            quantity(&Distribution::Empirical(EmpiricalLaw::new(&inv)), sample)
        }
        _ => {
            let (lo, hi) = beta.support();
            let h = (hi - lo) / SIMPSON_INTERVALS as f64;
            let (mut m1, mut m2) = (0.0, 0.0);
            for i in 0..=SIMPSON_INTERVALS {
                let w = match i {
                    0 => 1.0,
                    _ if i == SIMPSON_INTERVALS => 1.0,
                    _ if i % 2 == 1 => 4.0,
                    _ => 2.0,
                };
                let x = lo + i as f64 * h;
                let f = beta.pdf(x) * w * h / 3.0;
                m1 += f / x;
                m2 += f / (x * x);
            }
            QuantityStatistics {
                target: Moments {
                    mean: m1,
                    std: (m2 - m1 * m1).max(0.0).sqrt(),
                },
                achieved: Moments::of_sample(sample),
                ks_distance: ks_distance(sample, |x| 1.0 - beta.cdf(1.0 / x)),
            }
        }
    }
}

/// Shape statistics of a triaxial phase; `None` for spheroids.
pub(crate) fn shape(phase: &Phase, grains: &[&PackedGrain]) -> Option<ShapeStatistics> {
    let t = phase.triaxial.as_ref()?;
    let ratio = |i: usize, j: usize| -> Vec<f64> {
        grains
            .iter()
            .map(|g| g.semi_axes[i] / g.semi_axes[j])
            .collect()
    };
    let derived = |sample: &[f64]| RatioStatistics {
        target: None,
        achieved: Moments::of_sample(sample),
        ks_distance: None,
    };
    let (ca, cb) = (ratio(2, 0), ratio(2, 1));
    let (c_over_a, c_over_b) = match &t.third {
        ThirdRatio::OverA(law) => (quantity(law, &ca).into(), derived(&cb)),
        ThirdRatio::OverB(law) => (derived(&ca), quantity(law, &cb).into()),
    };
    Some(ShapeStatistics {
        b_over_a: quantity(&t.b_over_a, &ratio(1, 0)),
        c_over_a,
        c_over_b,
    })
}

/// Orientation statistics of a `fisher` phase; `None` for other kinds.
pub(crate) fn orientation(phase: &Phase, grains: &[&PackedGrain]) -> Option<OrientationStatistics> {
    let Orientation::Fisher(law) = phase.orientation else {
        return None;
    };
    let degrees = |m: Moments| Moments {
        mean: m.mean.to_degrees(),
        std: m.std.to_degrees(),
    };
    let angles: Vec<f64> = grains
        .iter()
        .map(|g| law.axis_angle(rotation_column(g.quaternion, 0)))
        .collect();
    let (mean, std) = law.fisher.angle_moments();
    let axis_angle_deg = QuantityStatistics {
        target: degrees(Moments { mean, std }),
        achieved: Moments::of_sample(&angles).map(degrees),
        ks_distance: ks_distance(&angles, |t| law.fisher.angle_cdf(t)),
    };
    let spins: Vec<f64> = grains
        .iter()
        .map(|g| {
            law.spin_angle(
                rotation_column(g.quaternion, 0),
                rotation_column(g.quaternion, 1),
            )
        })
        .collect();
    let spin_deg = match law.spin {
        Spin::Uniform => QuantityStatistics {
            // Uniform on [−π, π): mean 0, std π/√3.
            target: degrees(Moments {
                mean: 0.0,
                std: PI / 3f64.sqrt(),
            }),
            achieved: Moments::of_sample(&spins).map(degrees),
            ks_distance: ks_distance(&spins, |t| ((t + PI) / (2.0 * PI)).clamp(0.0, 1.0)),
        },
        Spin::VonMises { angle, .. } => {
            let cdf = VonMisesCdf::new(&angle);
            QuantityStatistics {
                target: degrees(cdf.moments()),
                achieved: Moments::of_sample(&spins).map(degrees),
                ks_distance: ks_distance(&spins, |t| cdf.cdf(t)),
            }
        }
    };
    Some(OrientationStatistics {
        axis_angle_deg,
        spin_deg,
    })
}
