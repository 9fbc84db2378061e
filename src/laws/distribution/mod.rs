//! Distributions of a positive grain quantity (an equivalent diameter or an aspect
//! ratio), truncated to cutoffs and sampled by rejection.

use super::special::{normal_mass, normal_pdf};
use super::table::{EmpiricalLaw, TableLaw};
use super::MIN_ACCEPTED_MASS;

/// A distribution of a positive quantity, truncated to `[min, max]`.
///
/// Every family is bounded, so that the largest grain is known before packing and every
/// value is positive: `0 < min < max` (or `value > 0`). A validated
/// [`Scene`](crate::scene::Scene) guarantees this and that the cutoffs keep at least
/// [`MIN_ACCEPTED_MASS`] of the untruncated law.
///
/// ```
/// use grainpack::laws::Distribution;
/// let d = Distribution::LogNormal { sigma: 0.8, scale: 14.0, loc: 0.0, min: 6.0, max: 16.0 };
/// assert_eq!(d.support(), (6.0, 16.0));
/// assert!(d.mean() > 6.0 && d.mean() < 16.0);
/// ```
#[derive(Debug, Clone, PartialEq)]
pub enum Distribution {
    /// Always `value`.
    Constant {
        /// The value.
        value: f64,
    },
    /// Uniform on `[min, max]`.
    Uniform {
        /// Lower end.
        min: f64,
        /// Upper end.
        max: f64,
    },
    /// Normal with `mean` and standard deviation `std`, truncated to `[min, max]`.
    Normal {
        /// Mean of the untruncated law.
        mean: f64,
        /// Standard deviation of the untruncated law.
        std: f64,
        /// Lower cutoff.
        min: f64,
        /// Upper cutoff.
        max: f64,
    },
    /// Lognormal as scipy's `lognorm(s = sigma, loc, scale)`: `X = loc + scale·e^{σZ}`
    /// with `Z` standard normal, so `scale = e^μ` is the median of `X − loc`; truncated
    /// to `[min, max]`.
    LogNormal {
        /// Standard deviation `σ` of `ln(X − loc)`.
        sigma: f64,
        /// `e^μ`, the median of `X − loc`.
        scale: f64,
        /// Shift of the support: `X > loc`.
        loc: f64,
        /// Lower cutoff.
        min: f64,
        /// Upper cutoff.
        max: f64,
    },
    /// A tabulated CDF, by number or by volume (`distribution = "table"`), cut at the
    /// table's ends.
    Table(TableLaw),
    /// The values of a measured grain table, each with probability `1/n`.
    Empirical(EmpiricalLaw),
}

/// A parameter that makes a distribution impossible, and why.
#[derive(Debug, Clone, PartialEq)]
pub(crate) struct Invalid {
    /// The parameter's key (`"sigma"`, `"min"`, ...).
    pub param: &'static str,
    /// What is wrong with it.
    pub reason: String,
}

impl Invalid {
    pub(crate) fn new(param: &'static str, reason: impl Into<String>) -> Self {
        Self {
            param,
            reason: reason.into(),
        }
    }
}

impl Distribution {
    /// The family's name as written in a scene file.
    pub fn family(&self) -> &'static str {
        match self {
            Self::Constant { .. } => "constant",
            Self::Uniform { .. } => "uniform",
            Self::Normal { .. } => "normal",
            Self::LogNormal { .. } => "lognormal",
            Self::Table(_) => "table",
            Self::Empirical(_) => "measured",
        }
    }

    /// The smallest and largest value that can be drawn.
    pub fn support(&self) -> (f64, f64) {
        match *self {
            Self::Constant { value } => (value, value),
            Self::Uniform { min, max }
            | Self::Normal { min, max, .. }
            | Self::LogNormal { min, max, .. } => (min, max),
            Self::Table(ref t) => t.support(),
            Self::Empirical(ref e) => e.support(),
        }
    }

    /// The probability that the untruncated law falls inside the cutoffs: the
    /// acceptance rate of rejection sampling (1 for `constant` and `uniform`).
    pub fn accepted_mass(&self) -> f64 {
        match *self {
            Self::Constant { .. } | Self::Uniform { .. } | Self::Table(_) | Self::Empirical(_) => {
                1.0
            }
            Self::Normal { .. } | Self::LogNormal { .. } => {
                let (a, b) = self.standard_window();
                normal_mass(a, b)
            }
        }
    }

    /// The cutoffs mapped to the standard normal variable `Z` (normal and lognormal).
    fn standard_window(&self) -> (f64, f64) {
        match *self {
            Self::Normal {
                mean,
                std,
                min,
                max,
            } => ((min - mean) / std, (max - mean) / std),
            Self::LogNormal {
                sigma,
                scale,
                loc,
                min,
                max,
            } => {
                let z = |x: f64| {
                    if x > loc {
                        ((x - loc) / scale).ln() / sigma
                    } else {
                        f64::NEG_INFINITY
                    }
                };
                (z(min), z(max))
            }
            _ => (f64::NEG_INFINITY, f64::INFINITY),
        }
    }

    /// The CDF of the truncated law, `P(X ≤ x)`.
    pub fn cdf(&self, x: f64) -> f64 {
        match self {
            Self::Table(t) => return t.cdf(x),
            Self::Empirical(e) => return e.cdf(x),
            _ => {}
        }
        let (lo, hi) = self.support();
        if x < lo {
            return 0.0;
        }
        if x >= hi {
            return 1.0;
        }
        match *self {
            Self::Constant { .. } => 1.0,
            Self::Uniform { min, max } => (x - min) / (max - min),
            Self::Normal { mean, std, .. } => {
                let (a, _) = self.standard_window();
                normal_mass(a, (x - mean) / std) / self.accepted_mass()
            }
            Self::LogNormal {
                sigma, scale, loc, ..
            } => {
                let (a, _) = self.standard_window();
                let z = if x > loc {
                    ((x - loc) / scale).ln() / sigma
                } else {
                    f64::NEG_INFINITY
                };
                normal_mass(a, z) / self.accepted_mass()
            }
            Self::Table(_) | Self::Empirical(_) => unreachable!("returned above"),
        }
    }

    /// The raw moment `E[Xᵏ]` of the truncated law, in closed form.
    ///
    /// Normal: the recursion for the moments `mⱼ` of a standard normal truncated to
    /// `[α, β]`, `mⱼ = (j−1) mⱼ₋₂ + (α^{j−1}φ(α) − β^{j−1}φ(β))/P`, then the binomial
    /// expansion of `(mean + std·Z)ᵏ`. Lognormal: `E[Yʲ; a<Y<b] = scaleʲ e^{j²σ²/2}
    /// (Φ(β−jσ) − Φ(α−jσ))` for `Y = X − loc`, then the expansion of `(loc + Y)ᵏ`.
    pub fn moment(&self, k: u32) -> f64 {
        match *self {
            Self::Constant { value } => value.powi(k as i32),
            Self::Uniform { min, max } => {
                let k1 = f64::from(k + 1);
                (max.powf(k1) - min.powf(k1)) / (k1 * (max - min))
            }
            Self::Normal { mean, std, .. } => {
                let (a, b) = self.standard_window();
                let p = self.accepted_mass();
                // x^{j-1} φ(x), taken as 0 at an infinite end.
                let edge = |x: f64, j: u32| {
                    if x.is_finite() {
                        x.powi(j as i32 - 1) * normal_pdf(x)
                    } else {
                        0.0
                    }
                };
                let mut m = vec![1.0, (edge(a, 1) - edge(b, 1)) / p];
                for j in 2..=k {
                    let mj = f64::from(j - 1) * m[j as usize - 2] + (edge(a, j) - edge(b, j)) / p;
                    m.push(mj);
                }
                (0..=k)
                    .map(|j| {
                        binomial(k, j)
                            * mean.powi((k - j) as i32)
                            * std.powi(j as i32)
                            * m[j as usize]
                    })
                    .sum()
            }
            Self::LogNormal {
                sigma, scale, loc, ..
            } => {
                let (a, b) = self.standard_window();
                let p = self.accepted_mass();
                (0..=k)
                    .map(|j| {
                        let js = f64::from(j) * sigma;
                        let ey = scale.powi(j as i32)
                            * (0.5 * js * js).exp()
                            * normal_mass(a - js, b - js)
                            / p;
                        binomial(k, j) * loc.powi((k - j) as i32) * ey
                    })
                    .sum()
            }
            Self::Table(ref t) => t.moment(k),
            Self::Empirical(ref e) => e.moment(k),
        }
    }

    /// The mean of the truncated law.
    pub fn mean(&self) -> f64 {
        self.moment(1)
    }

    /// The standard deviation of the truncated law.
    pub fn std(&self) -> f64 {
        let m = self.mean();
        (self.moment(2) - m * m).max(0.0).sqrt()
    }

    /// Checks that the parameters describe a bounded law of positive values that keeps
    /// at least [`MIN_ACCEPTED_MASS`] inside its cutoffs, naming the first parameter
    /// that does not.
    pub(crate) fn check(&self) -> Result<(), Invalid> {
        let params: Vec<(&'static str, f64)> = match *self {
            Self::Constant { value } => vec![("value", value)],
            Self::Uniform { min, max } => vec![("min", min), ("max", max)],
            Self::Normal {
                mean,
                std,
                min,
                max,
            } => vec![("mean", mean), ("std", std), ("min", min), ("max", max)],
            Self::LogNormal {
                sigma,
                scale,
                loc,
                min,
                max,
            } => vec![
                ("sigma", sigma),
                ("scale", scale),
                ("loc", loc),
                ("min", min),
                ("max", max),
            ],
            // Checked when built (TableLaw::new; measured values by their reader).
            Self::Table(_) | Self::Empirical(_) => return Ok(()),
        };
        for &(name, value) in &params {
            if !value.is_finite() {
                return Err(Invalid::new(name, "must be a finite number"));
            }
        }
        for &(name, value) in &params {
            if matches!(name, "value" | "min" | "std" | "sigma" | "scale") && value <= 0.0 {
                return Err(Invalid::new(name, "must be positive"));
            }
        }
        let (min, max) = self.support();
        if min >= max && !matches!(self, Self::Constant { .. }) {
            return Err(Invalid::new(
                "max",
                format!("cutoffs reversed or empty: max = {max} must be above min = {min}"),
            ));
        }
        let mass = self.accepted_mass();
        if !(mass >= MIN_ACCEPTED_MASS) {
            return Err(Invalid::new(
                "min",
                format!(
                    "the cutoffs [{min}, {max}] keep only {mass:.3e} of the {} distribution; \
                     at least {MIN_ACCEPTED_MASS:e} is needed",
                    self.family()
                ),
            ));
        }
        Ok(())
    }
}

/// The binomial coefficient `C(n, k)` as a float (small `n` only).
fn binomial(n: u32, k: u32) -> f64 {
    (0..k).fold(1.0, |c, i| c * f64::from(n - i) / f64::from(i + 1))
}

/// Laws the tests of this module and of [`super::density`] check: kanapy's size law,
/// a shifted lognormal, normals cut on one and on both sides, a uniform.
#[cfg(test)]
pub(crate) fn sample_laws() -> [Distribution; 5] {
    [
        Distribution::LogNormal {
            sigma: 0.8,
            scale: 14.0,
            loc: 0.0,
            min: 6.0,
            max: 16.0,
        },
        Distribution::LogNormal {
            sigma: 0.3,
            scale: 2.0,
            loc: 1.0,
            min: 1.5,
            max: 6.0,
        },
        Distribution::Normal {
            mean: 10.0,
            std: 3.0,
            min: 4.0,
            max: 12.0,
        },
        Distribution::Normal {
            mean: 1.0,
            std: 0.2,
            min: 0.1,
            max: 5.0,
        },
        Distribution::Uniform { min: 2.0, max: 5.0 },
    ]
}

#[cfg(test)]
mod tests;
