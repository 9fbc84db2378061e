//! Triaxial grains: semi-axes `a ≥ b ≥ c` from two shape-ratio laws (DREAM.3D's `b/a`
//! and `c/a`, or `b/a` and `c/b`), at the volume of the equivalent sphere.
//!
//! With `β = b/a` and `γ = c/a`, `a b c = a³ β γ = (d/2)³` gives `a = (d/2) (βγ)^{−1/3}`,
//! `b = β a`, `c = γ a`. Semi-axis `k` lies along column `k` of the grain's rotation, so
//! the first axis is the longest and the third the shortest (a pancake's normal).

use crate::laws::Distribution;
use rand::Rng;

/// The law of the third semi-axis, relative to the first or to the second.
#[derive(Debug, Clone, PartialEq)]
pub enum ThirdRatio {
    /// `c/a` (DREAM.3D's). Its upper cutoff may not exceed the lower cutoff of `b/a`,
    /// so that every pair drawn has `c ≤ b`.
    OverA(Distribution),
    /// `c/b`, in `(0, 1]`: any pair is valid, and `c/a = (c/b)(b/a)`.
    OverB(Distribution),
}

/// The two shape-ratio laws of a triaxial phase.
#[derive(Debug, Clone, PartialEq)]
pub struct Triaxial {
    /// `β = b/a`, in `(0, 1]`.
    pub b_over_a: Distribution,
    /// `c/a` or `c/b`.
    pub third: ThirdRatio,
}

impl Triaxial {
    /// Draws `(b/a, c/a)`: `b/a` first, then the third law. `None` if a rejection
    /// sampler gave up, with the quantity's name.
    pub fn sample<R: Rng + ?Sized>(&self, rng: &mut R) -> Result<(f64, f64), &'static str> {
        let beta = self.b_over_a.sample(rng).ok_or("shape ratio b/a")?;
        let gamma = match &self.third {
            ThirdRatio::OverA(law) => law.sample(rng).ok_or("shape ratio c/a")?,
            ThirdRatio::OverB(law) => beta * law.sample(rng).ok_or("shape ratio c/b")?,
        };
        Ok((beta, gamma))
    }

    /// The smallest `β γ` any grain can have: it sets the longest first axis.
    pub fn min_product(&self) -> f64 {
        let (b_min, _) = self.b_over_a.support();
        match &self.third {
            ThirdRatio::OverA(law) => b_min * law.support().0,
            ThirdRatio::OverB(law) => b_min * b_min * law.support().0,
        }
    }
}

/// Semi-axes `[a, b, c]` of the grain of equivalent diameter `d` with `b/a = β` and
/// `c/a = γ`: `a = (d/2)(βγ)^{−1/3}`.
pub fn triaxial_semi_axes(diameter: f64, beta: f64, gamma: f64) -> [f64; 3] {
    let a = 0.5 * diameter / (beta * gamma).cbrt();
    [a, beta * a, gamma * a]
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Volume and ratios come back to a few ulps (a cube root, three products).
    #[test]
    fn semi_axes_keep_the_equivalent_volume_and_the_ratios() {
        let (d, beta, gamma) = (6.0, 0.6, 0.25);
        let [a, b, c] = triaxial_semi_axes(d, beta, gamma);
        let tol = 8.0 * f64::EPSILON;
        assert!((a * b * c / 27.0 - 1.0).abs() < tol);
        assert!((b / a - beta).abs() < tol && (c / a - gamma).abs() < tol);
        assert!(a >= b && b >= c);
    }
}
