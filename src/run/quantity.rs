//! A grain quantity's target law against the packed grains' values: moments and KS
//! distance, shared by the phase statistics and the shape statistics.

use crate::laws::{ks_distance, ks_distance_to_value, Distribution, Moments};
use serde::Serialize;

/// Relative rounding of a diameter `2 (a1 a2 a3)^{1/3}` or aspect ratio `a1/a2`
/// recomputed from packed semi-axes: the sampler's `a2 = d/(2 α^{1/3})`, `a1 = α a2`,
/// the loop's scaling and the recomputation are under ten operations, each within
/// `ε/2`; `16 ε` bounds their sum. Against a constant law, a value within it of the
/// constant counts as equal to it.
const ROUNDING: f64 = 16.0 * f64::EPSILON;

/// A grain quantity's target law against the packed grains.
#[derive(Debug, Clone, Copy, Serialize)]
pub struct QuantityStatistics {
    /// Mean and standard deviation of the target (truncated) law.
    pub target: Moments,
    /// Mean and standard deviation of the packed grains; `null` without grains.
    pub achieved: Option<Moments>,
    /// Kolmogorov–Smirnov distance between the packed grains and the target law;
    /// `null` without grains.
    pub ks_distance: Option<f64>,
}

/// A quantity's law against its sample.
pub(crate) fn quantity(law: &Distribution, sample: &[f64]) -> QuantityStatistics {
    QuantityStatistics {
        target: Moments {
            mean: law.mean(),
            std: law.std(),
        },
        achieved: Moments::of_sample(sample),
        ks_distance: match *law {
            Distribution::Constant { value } => ks_distance_to_value(sample, value, ROUNDING),
            Distribution::Empirical(ref e) => step_ks_distance(sample, |x| e.cdf(x)),
            _ => ks_distance(sample, |x| law.cdf(x)),
        },
    }
}

/// The KS distance between `sample` and a step CDF (a measured table's): both are
/// right-continuous steps, so `sup |Fₙ − G|` is reached at a value of the sample or
/// just before one; at the table's own values `G` is compared with `Fₙ` at the same
/// point, not with its left limit, so a sample equal to the table is at distance 0.
fn step_ks_distance(sample: &[f64], cdf: impl Fn(f64) -> f64) -> Option<f64> {
    if sample.is_empty() {
        return None;
    }
    let mut sorted = sample.to_vec();
    sorted.sort_by(f64::total_cmp);
    let n = sorted.len() as f64;
    let mut d: f64 = 0.0;
    let mut i = 0;
    while i < sorted.len() {
        let x = sorted[i];
        // Just below x: the sample's CDF is i/n, the table's its left limit.
        d = d.max((i as f64 / n - cdf(x.next_down())).abs());
        let j = sorted.partition_point(|&v| v <= x);
        d = d.max((j as f64 / n - cdf(x)).abs());
        i = j;
    }
    Some(d)
}
