//! Densities of the scene's laws, truncated to their cutoffs and renormalised: what a
//! histogram of drawn values should follow.

use super::distribution::Distribution;
use super::special::normal_pdf;
use super::von_mises::VonMises;

impl Distribution {
    /// The density of the truncated law at `x`: the untruncated density divided by the
    /// mass the cutoffs keep ([`Distribution::accepted_mass`]), 0 outside
    /// [`Distribution::support`]. It is the derivative of [`Distribution::cdf`].
    ///
    /// Normal: `φ((x − mean)/std) / (std P)`. Lognormal:
    /// `φ(ln((x − loc)/scale)/σ) / (σ (x − loc) P)`. Uniform: `1/(max − min)`.
    /// A table's density is exact per interval (see [`TableLaw`](super::TableLaw)).
    /// A measured (empirical) law has no density: 0. A constant law has no density: its mass is a point at `value`, so this returns
    /// `+∞` at `value` and 0 elsewhere.
    ///
    /// ```
    /// use grainpack::laws::Distribution;
    /// let d = Distribution::Uniform { min: 2.0, max: 6.0 };
    /// assert_eq!((d.pdf(3.0), d.pdf(7.0)), (0.25, 0.0));
    /// ```
    pub fn pdf(&self, x: f64) -> f64 {
        let (lo, hi) = self.support();
        match *self {
            Self::Constant { value } => {
                if x == value {
                    f64::INFINITY
                } else {
                    0.0
                }
            }
            _ if !(lo..=hi).contains(&x) => 0.0,
            Self::Uniform { min, max } => 1.0 / (max - min),
            Self::Normal { mean, std, .. } => {
                normal_pdf((x - mean) / std) / (std * self.accepted_mass())
            }
            Self::LogNormal {
                sigma, scale, loc, ..
            } => {
                if x <= loc {
                    return 0.0;
                }
                let z = ((x - loc) / scale).ln() / sigma;
                normal_pdf(z) / (sigma * (x - loc) * self.accepted_mass())
            }
            Self::Table(ref t) => t.pdf(x),
            // Point masses at the measured values: no density, as for a constant.
            Self::Empirical(_) => 0.0,
        }
    }
}

impl VonMises {
    /// The density of the truncated law at `θ` (radians): `e^{κ cos(θ − mean)}`
    /// normalised over [`VonMises::window`] by quadrature (it is the derivative of
    /// [`VonMisesCdf::cdf`](super::VonMisesCdf::cdf)), 0 outside the window.
    ///
    /// ```
    /// use grainpack::laws::VonMises;
    /// use std::f64::consts::PI;
    /// // κ = 0 is uniform on its window.
    /// let flat = VonMises { mean: 0.5 * PI, kappa: 0.0, min: 0.0, max: PI };
    /// assert!((flat.pdf(1.0) - 1.0 / PI).abs() < 1e-12);
    /// assert_eq!(flat.pdf(-0.1), 0.0);
    /// ```
    pub fn pdf(&self, theta: f64) -> f64 {
        let (lo, hi) = self.window();
        if !(lo..=hi).contains(&theta) {
            return 0.0;
        }
        self.density(theta) / self.integral(lo, hi)
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::laws::sample_laws;
    use crate::laws::special::simpson;
    use std::f64::consts::PI;

    fn tilts() -> [VonMises; 4] {
        [
            VonMises {
                mean: 0.5 * PI,
                kappa: 1.0,
                min: 0.0,
                max: PI,
            },
            VonMises::new(-1.0, 50.0),
            VonMises {
                mean: 0.0,
                kappa: 0.0,
                min: -0.5,
                max: 2.0,
            },
            VonMises {
                mean: 0.3,
                kappa: 4.0,
                min: 0.5,
                max: 1.5,
            },
        ]
    }

    /// Simpson on 4000 intervals integrates these smooth densities to ~1e-12; the
    /// accepted mass rests on the erfc fit (fractional error 1.2e-7), so 1e-6.
    #[test]
    fn pdf_integrates_to_one_over_the_support() {
        for d in sample_laws() {
            let (lo, hi) = d.support();
            let total = simpson(|x| d.pdf(x), lo, hi, 4000);
            assert!((total - 1.0).abs() < 1e-6, "{d:?}: {total}");
        }
        // Two quadratures of the same smooth density (the law's own grid and this one),
        // each good to ~1e-10.
        for v in tilts() {
            let (lo, hi) = v.window();
            let total = simpson(|t| v.pdf(t), lo, hi, 4000);
            assert!((total - 1.0).abs() < 1e-9, "{v:?}: {total}");
        }
    }

    /// The absolute rounding of the difference of two CDF values: each is a ratio of
    /// sums of terms at most 2, computed to a few ε, divided by `P ≥ 0.25`; 16 ε covers
    /// both.
    const CDF_ROUNDING: f64 = 16.0 * f64::EPSILON;

    /// The CDF of the normal and lognormal laws rests on an erfc fit whose value is good
    /// to 1.2e-7 but whose slope is not controlled: its derivative is off the exact
    /// density by up to ~5e-4 relative (measured here: 4.1e-4 for the lognormal at
    /// 14), so the central difference `(F(x+h) − F(x−h))/2h` (truncation error
    /// `h² f''/6`, below 1e-6 of `f` for `h` = 1e-4 of the support) is held to 1e-3.
    /// In integral form the fit's own bound applies: `F(x₂) − F(x₁)` against Simpson's
    /// `∫ f` (exact to ~1e-12) to `2 · 1.2e-7 / P` with `P` ≥ 0.25 here, so 1e-6.
    /// Far in a tail, where `F` is within a few ε of 1, the difference also carries
    /// [`CDF_ROUNDING`]`/h`.
    #[test]
    fn pdf_is_the_derivative_of_the_cdf() {
        for d in sample_laws() {
            let (lo, hi) = d.support();
            let h = 1e-4 * (hi - lo);
            for k in 1..20 {
                let x = lo + (hi - lo) * k as f64 / 20.0;
                let slope = (d.cdf(x + h) - d.cdf(x - h)) / (2.0 * h);
                let f = d.pdf(x);
                let tol = 1e-3 * f + CDF_ROUNDING / h;
                assert!((slope - f).abs() < tol, "{d:?} at {x}: {slope} vs {f}");
                let mass = simpson(|t| d.pdf(t), lo, x, 2000);
                assert!((mass - d.cdf(x)).abs() < 1e-6, "{d:?} at {x}: {mass}");
            }
            assert!(d.accepted_mass() >= 0.25, "{d:?}");
            assert_eq!(d.pdf(lo - h), 0.0);
            assert_eq!(d.pdf(hi + h), 0.0);
        }
        // The von Mises CDF is a quadrature good to ~1e-10 (absolute), so the
        // difference quotient carries 1e-10/h; its truncation error h² f''/6 is at most
        // κ²h²/6 of f, since |f''/f| = |κ² sin² − κ cos| ≤ κ² + κ; 1e-6 for rounding.
        for v in tilts() {
            let table = crate::laws::VonMisesCdf::new(&v);
            let (lo, hi) = v.window();
            let h = 1e-4 * (hi - lo);
            let rel = (v.kappa * v.kappa + v.kappa) * h * h / 6.0 + 1e-6;
            for k in 1..20 {
                let t = lo + (hi - lo) * k as f64 / 20.0;
                let slope = (table.cdf(t + h) - table.cdf(t - h)) / (2.0 * h);
                let f = v.pdf(t);
                let tol = rel * f + 1e-10 / h;
                assert!((slope - f).abs() < tol, "{v:?} at {t}: {slope} vs {f}");
            }
            assert_eq!(v.pdf(hi + h), 0.0);
        }
    }

    #[test]
    fn constant_law_is_a_point_mass() {
        let d = Distribution::Constant { value: 3.0 };
        assert_eq!(d.pdf(3.0), f64::INFINITY);
        assert_eq!(d.pdf(2.999), 0.0);
    }
}
