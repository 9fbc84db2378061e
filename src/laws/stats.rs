//! Sample statistics against a target law: mean, standard deviation and the
//! Kolmogorov–Smirnov distance.

use serde::Serialize;

/// Mean and standard deviation of a law or of a sample.
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
pub struct Moments {
    /// Mean.
    pub mean: f64,
    /// Standard deviation (of a sample: of its empirical law, dividing by `n`).
    pub std: f64,
}

impl Moments {
    /// The mean and standard deviation of the empirical law of `sample` (two passes:
    /// the mean, then the mean squared deviation from it); `None` for an empty sample.
    ///
    /// ```
    /// use grainpack::laws::Moments;
    /// let m = Moments::of_sample(&[1.0, 3.0]).unwrap();
    /// assert_eq!((m.mean, m.std), (2.0, 1.0));
    /// ```
    pub fn of_sample(sample: &[f64]) -> Option<Self> {
        if sample.is_empty() {
            return None;
        }
        let n = sample.len() as f64;
        let mean = sample.iter().sum::<f64>() / n;
        let var = sample.iter().map(|x| (x - mean).powi(2)).sum::<f64>() / n;
        Some(Self {
            mean,
            std: var.sqrt(),
        })
    }
}

/// The Kolmogorov–Smirnov distance `D = sup_x |Fₙ(x) − F(x)|` between the empirical law
/// `Fₙ` of `sample` and a continuous CDF `F`; `None` for an empty sample.
///
/// With the sample sorted, `x₁ ≤ … ≤ xₙ`, the supremum is reached at a sample point or
/// just below one: `D = maxᵢ max(i/n − F(xᵢ), F(xᵢ) − (i−1)/n)`. Ties need no care: of
/// equal values, the last gives the largest `i/n` and the first the smallest `(i−1)/n`.
///
/// ```
/// use grainpack::laws::ks_distance;
/// // Uniform on [0, 1]: the worst gap is 1 − F(0.7) = 0.3, just below 1 at x = 0.7.
/// let d = ks_distance(&[0.4, 0.1, 0.7], |x| x.clamp(0.0, 1.0)).unwrap();
/// assert!((d - 0.3).abs() < 1e-15);
/// ```
pub fn ks_distance(sample: &[f64], cdf: impl Fn(f64) -> f64) -> Option<f64> {
    if sample.is_empty() {
        return None;
    }
    let mut sorted = sample.to_vec();
    sorted.sort_by(f64::total_cmp);
    let n = sorted.len() as f64;
    Some(
        sorted
            .iter()
            .enumerate()
            .map(|(i, &x)| {
                let f = cdf(x);
                ((i + 1) as f64 / n - f).max(f - i as f64 / n)
            })
            .fold(0.0, f64::max),
    )
}

/// The Kolmogorov–Smirnov distance between the empirical law of `sample` and the point
/// mass at `value` (the law of a constant): the larger of the shares of the sample
/// below and above `value`. Values within `rel_tol · |value|` of it count as equal to
/// it, since a quantity recomputed from packed semi-axes carries rounding.
/// `None` for an empty sample.
///
/// ```
/// use grainpack::laws::ks_distance_to_value;
/// let d = ks_distance_to_value(&[3.0, 3.0 + 1e-15, 2.0, 3.0], 3.0, 1e-12).unwrap();
/// assert_eq!(d, 0.25); // one value in four below 3, none above
/// ```
pub fn ks_distance_to_value(sample: &[f64], value: f64, rel_tol: f64) -> Option<f64> {
    if sample.is_empty() {
        return None;
    }
    let tol = rel_tol * value.abs();
    let below = sample.iter().filter(|&&x| x < value - tol).count();
    let above = sample.iter().filter(|&&x| x > value + tol).count();
    Some(below.max(above) as f64 / sample.len() as f64)
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::laws::{sample_laws, Distribution};
    use rand::SeedableRng;
    use rand_chacha::ChaCha8Rng;

    fn draw(law: &Distribution, n: usize, seed: u64) -> Vec<f64> {
        let mut rng = ChaCha8Rng::seed_from_u64(seed);
        (0..n).map(|_| law.sample(&mut rng).unwrap()).collect()
    }

    /// For n draws from the law itself, `P(√n D > 1.63) ≈ 0.01` (Kolmogorov's limit
    /// law); the seed is fixed, so the test is deterministic and the bound is generous.
    #[test]
    fn ks_distance_of_a_sample_from_its_own_law_is_small() {
        let n = 5000;
        let laws = sample_laws();
        for (seed, law) in laws.iter().enumerate() {
            let d = ks_distance(&draw(law, n, seed as u64), |x| law.cdf(x)).unwrap();
            assert!(d < 1.63 / (n as f64).sqrt(), "{law:?}: D = {d}");
        }
    }

    #[test]
    fn ks_distance_of_a_shifted_sample_is_large() {
        let law = Distribution::Normal {
            mean: 7.0,
            std: 1.5,
            min: 4.0,
            max: 10.0,
        };
        let shifted: Vec<f64> = draw(&law, 2000, 9).iter().map(|x| x + 1.5).collect();
        let d = ks_distance(&shifted, |x| law.cdf(x)).unwrap();
        // A shift of one std moves the CDF by about 0.38 near the mean.
        assert!(d > 0.3, "D = {d}");
    }

    #[test]
    fn ks_distance_of_a_small_sample_is_the_hand_computed_value() {
        // Uniform [0, 1], sample 0.2, 0.5, 0.5, 0.9: the steps are at 1/4, 3/4, 1.
        // Gaps: x=0.2: 0.25−0.2 = 0.05, 0.2−0 = 0.2; x=0.5: 0.75−0.5 = 0.25,
        // 0.5−0.25 = 0.25; x=0.9: 1−0.9 = 0.1, 0.9−0.75 = 0.15. D = 0.25.
        let d = ks_distance(&[0.9, 0.5, 0.2, 0.5], |x| x.clamp(0.0, 1.0)).unwrap();
        assert!((d - 0.25).abs() < 1e-15, "{d}");
        // A single point: D = max(F(x), 1 − F(x)).
        assert_eq!(ks_distance(&[0.25], |x| x).unwrap(), 0.75);
        assert_eq!(ks_distance(&[], |x| x), None);
    }

    #[test]
    fn ks_distance_to_a_constant_counts_values_off_it() {
        assert_eq!(ks_distance_to_value(&[2.0; 5], 2.0, 0.0), Some(0.0));
        assert_eq!(
            ks_distance_to_value(&[1.0, 2.0, 2.0, 3.0, 3.0], 2.0, 1e-12),
            Some(0.4)
        );
        assert_eq!(ks_distance_to_value(&[], 2.0, 0.0), None);
    }

    #[test]
    fn moments_of_a_sample_are_those_of_its_empirical_law() {
        let m = Moments::of_sample(&[2.0, 4.0, 4.0, 4.0, 5.0, 5.0, 7.0, 9.0]).unwrap();
        assert_eq!((m.mean, m.std), (5.0, 2.0));
        assert_eq!(Moments::of_sample(&[]), None);
    }
}
