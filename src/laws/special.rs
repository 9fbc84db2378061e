//! The few special functions the scene's distributions need: the normal CDF, its mass
//! between two points, and Simpson quadrature.

use std::f64::consts::{FRAC_1_SQRT_2, PI};

/// The complementary error function `erfc(x) = 2/√π ∫ₓ^∞ e^{−t²} dt`, with a fractional
/// error below 1.2·10⁻⁷ for every `x`, the tails included.
///
/// Chebyshev fit of Press et al., *Numerical Recipes* (2nd ed., §6.2, `erfcc`). That
/// accuracy is ample here: it decides whether cutoffs keep at least
/// [`MIN_ACCEPTED_MASS`](super::MIN_ACCEPTED_MASS) = 10⁻³ of a distribution, and tests
/// compare sample CDFs with it at tolerances of 10⁻², so a more accurate fit would
/// change no outcome. `erfc(±∞)` is `0` and `2`.
pub(crate) fn erfc(x: f64) -> f64 {
    let z = x.abs();
    let t = 1.0 / (1.0 + 0.5 * z);
    let poly = -1.265_512_23
        + t * (1.000_023_68
            + t * (0.374_091_96
                + t * (0.096_784_18
                    + t * (-0.186_288_06
                        + t * (0.278_868_07
                            + t * (-1.135_203_98
                                + t * (1.488_515_87 + t * (-0.822_152_23 + t * 0.170_872_77))))))));
    let tail = t * (-z * z + poly).exp();
    if x >= 0.0 {
        tail
    } else {
        2.0 - tail
    }
}

/// The standard normal CDF `Φ(x) = erfc(−x/√2)/2`.
pub(crate) fn normal_cdf(x: f64) -> f64 {
    0.5 * erfc(-x * FRAC_1_SQRT_2)
}

/// The standard normal density `φ(x) = e^{−x²/2}/√(2π)`.
pub(crate) fn normal_pdf(x: f64) -> f64 {
    (-0.5 * x * x).exp() / (2.0 * PI).sqrt()
}

/// `Φ(b) − Φ(a)` for `a ≤ b`, computed from the nearer tail so that a window far out in
/// either tail keeps its relative accuracy (no `1 − (1 − ε)`). Infinite ends are allowed.
pub(crate) fn normal_mass(a: f64, b: f64) -> f64 {
    let upper_tail = |x: f64| 0.5 * erfc(x * FRAC_1_SQRT_2);
    if a > 0.0 {
        upper_tail(a) - upper_tail(b)
    } else {
        normal_cdf(b) - normal_cdf(a)
    }
}

/// `∫ₐᵇ f` by the composite Simpson rule on `intervals` (rounded up to even, at least 2)
/// equal intervals.
pub(crate) fn simpson(f: impl Fn(f64) -> f64, a: f64, b: f64, intervals: usize) -> f64 {
    let n = intervals.max(2).next_multiple_of(2);
    let h = (b - a) / n as f64;
    let mut sum = f(a) + f(b);
    for i in 1..n {
        let weight = if i % 2 == 1 { 4.0 } else { 2.0 };
        sum += weight * f(a + h * i as f64);
    }
    sum * h / 3.0
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The fit's documented fractional error, with a little room for the rounding of
    /// the reference values (printed with 17 digits).
    const FIT_TOL: f64 = 1.3e-7;

    #[test]
    fn erfc_matches_reference_values_in_the_body_and_the_tails() {
        // Reference values of erfc (mpmath, rounded to f64).
        let cases = [
            (0.0, 1.0),
            (0.5, 0.479_500_122_186_953_5),
            (1.0, 0.157_299_207_050_285_13),
            (-1.0, 1.842_700_792_949_715),
            (3.0, 2.209_049_699_858_544e-5),
            (6.0, 2.151_973_671_249_891e-17),
        ];
        for (x, want) in cases {
            let got = erfc(x);
            assert!(
                ((got - want) / want).abs() < FIT_TOL,
                "erfc({x}) = {got}, want {want}"
            );
        }
        assert_eq!(erfc(f64::INFINITY), 0.0);
        assert_eq!(erfc(f64::NEG_INFINITY), 2.0);
    }

    #[test]
    fn normal_mass_keeps_relative_accuracy_far_in_the_upper_tail() {
        // Φ(9) − Φ(8) ≈ 6.22e-16: 1 − Φ would lose it entirely.
        let m = normal_mass(8.0, 9.0);
        let want = 0.5 * (erfc(8.0 * FRAC_1_SQRT_2) - erfc(9.0 * FRAC_1_SQRT_2));
        assert!(m > 6.0e-16 && m < 6.3e-16, "{m}");
        assert_eq!(m, want);
        assert!((normal_mass(f64::NEG_INFINITY, f64::INFINITY) - 1.0).abs() < FIT_TOL);
    }

    #[test]
    fn simpson_is_exact_for_cubics() {
        // Simpson's rule integrates cubics exactly; 1e-12 allows for rounding only.
        let got = simpson(|x| x * x * x - 2.0 * x + 1.0, -1.0, 3.0, 4);
        assert!((got - 16.0).abs() < 1e-12, "{got}");
    }
}
