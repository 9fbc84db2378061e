//! Drawing from a [`Distribution`] by rejection.

use super::{Distribution, MAX_DRAWS};
use rand::Rng;
use rand_distr::StandardNormal;

impl Distribution {
    /// Draws one value: untruncated draws are rejected until one falls inside the
    /// cutoffs, at most [`MAX_DRAWS`] times. `None` if none did (probability below
    /// e⁻⁵⁰ for a validated distribution).
    pub fn sample<R: Rng + ?Sized>(&self, rng: &mut R) -> Option<f64> {
        match *self {
            Self::Constant { value } => Some(value),
            Self::Uniform { min, max } => Some(min + (max - min) * rng.random::<f64>()),
            Self::Normal {
                mean,
                std,
                min,
                max,
            } => (0..MAX_DRAWS)
                .map(|_| mean + std * rng.sample::<f64, _>(StandardNormal))
                .find(|x| (min..=max).contains(x)),
            Self::LogNormal {
                sigma,
                scale,
                loc,
                min,
                max,
            } => (0..MAX_DRAWS)
                .map(|_| loc + scale * (sigma * rng.sample::<f64, _>(StandardNormal)).exp())
                .find(|x| (min..=max).contains(x)),
            // Inverse CDF: one uniform per value.
            Self::Table(ref t) => Some(t.quantile(rng.random::<f64>())),
            Self::Empirical(ref e) => Some(e.sorted[rng.random_range(0..e.sorted.len())]),
        }
    }
}
