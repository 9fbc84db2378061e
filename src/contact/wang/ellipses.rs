//! The algebraic separation test of two ellipses, an independent cross-check of the 2D
//! contact function (which solves the embedded 3D pair).
//!
//! Y.-K. Choi, W. Wang, Y. Liu, M.-S. Kim, "Continuous collision detection for two
//! moving elliptic disks", IEEE Transactions on Robotics 22 (2006) 213–224; the
//! condition is the planar case of Wang–Wang–Kim's (module docs of [`super`]), and
//! Etayo, González-Vega and del Río (2006) classify all relative positions by it.
//!
//! Each ellipse is the conic `XᵀAX ≤ 0`, `X = (x, y, 1)`, with the canonical 3×3 matrix
//! `A = [[P, −Pc], [−cᵀP, cᵀPc − 1]]`, `P = Q⁻¹`, built relative to the first centre
//! (`c1 = 0`, `c2 = r12`). With both interiors negative, the cubic `p(λ) = det(λA − B)`
//! has `p(0) = det P2 > 0` and leading coefficient `−det P1 < 0`, so it is positive at
//! both ends of the negative axis and has zero or two negative roots; the ellipses are
//! separated iff it has two distinct negative roots (touch iff a negative double root),
//! as for spheres: two unit circles at distance `d` give
//! `p = (λ − 1)(−λ² + (2 − d²)λ − 1)`, whose other roots are negative and distinct iff
//! `d > 2`. The negative axis is mapped onto `t ∈ (0, 1)` by `λ = −σt/(1−t)` (`σ` the
//! ratio of the sizes, a power of two, so that the roots are of order 1), and the pair is
//! separated iff `P(t) = (1−t)³ p(−σt/(1−t))` is negative at one of its critical points.

use super::super::plane::{Sym2, Vec2};
use super::super::scale::{exponent, ldexp, pow2};
use super::super::ContactError;

/// Relative rounding allowed for each coefficient of `det(λA − B)`, per unit of the
/// condition bound `κ = max_i tr(Qi)² / det(Qi)` and of the sum of the magnitudes of the
/// terms that make it: inverting a form of condition `κ` leaves its entries off by a few
/// `ε κ` relative, and each coefficient is a sum of products of a few such entries
/// (at most 8 roundings each); `32 ε` leaves a margin of 4 on that.
pub const CUBIC_ROUNDING: f64 = 32.0 * f64::EPSILON;

/// Coefficients `[p0, p1, p2, p3]` of `det(λA − B)`, lowest degree first (see the
/// module docs), for two definite forms.
///
/// With `X(λ) = λP1 − P2`, `u = P2 r12`, `k = r12ᵀu`:
/// `p(λ) = (1 − k − λ) det X(λ) − uᵀ adj(X(λ)) u`, and `uᵀ adj(P2) u = k det P2`, so
/// `p0 = det P2` exactly.
///
/// # Errors
/// [`ContactError::NotFinite`] naming the entry, [`ContactError::NotPositiveDefinite`]
/// for a form that is not definite (segments and points have no canonical matrix), and
/// [`ContactError::Overflow`] when a coefficient leaves the double range.
pub fn characteristic_polynomial_2d(
    r12: &Vec2,
    q1: &Sym2,
    q2: &Sym2,
) -> Result<[f64; 4], ContactError> {
    coefficients(r12, q1, q2).map(|(p, _)| p)
}

/// The coefficients and a bound on the rounding of each ([`CUBIC_ROUNDING`]).
fn coefficients(r12: &Vec2, q1: &Sym2, q2: &Sym2) -> Result<([f64; 4], [f64; 4]), ContactError> {
    for (what, x) in [("r12", &r12[..]), ("q1", &q1[..]), ("q2", &q2[..])] {
        if let Some(index) = x.iter().position(|v| !v.is_finite()) {
            let value = x[index];
            return Err(ContactError::NotFinite { what, index, value });
        }
    }
    let inverse = |q: &Sym2, what: &'static str| {
        let det = q[0] * q[2] - q[1] * q[1];
        let (pivot, value) = match q[0] > 0.0 {
            true => (1, det / q[0]),
            false => (0, q[0]),
        };
        match q[0] > 0.0 && det > 0.0 {
            true => Ok((
                [q[2] / det, -q[1] / det, q[0] / det],
                (q[0] + q[2]).powi(2) / det,
            )),
            false => Err(ContactError::NotPositiveDefinite { what, pivot, value }),
        }
    };
    let ((a, kappa1), (b, kappa2)) = (inverse(q1, "q1")?, inverse(q2, "q2")?);
    let r = r12;
    let u = [b[0] * r[0] + b[1] * r[1], b[1] * r[0] + b[2] * r[1]];
    let k = r[0] * u[0] + r[1] * u[1];
    let d2 = a[0] * a[2] - a[1] * a[1];
    let m = a[0] * b[2] + a[2] * b[0] - 2.0 * a[1] * b[1];
    let e = b[0] * b[2] - b[1] * b[1];
    let alpha = a[2] * u[0] * u[0] - 2.0 * a[1] * u[0] * u[1] + a[0] * u[1] * u[1];
    let p = [e, -(1.0 - k) * m - e - alpha, (1.0 - k) * d2 + m, -d2];
    // The magnitudes of the terms of each coefficient.
    let ua = [
        (b[0] * r[0]).abs() + (b[1] * r[1]).abs(),
        (b[1] * r[0]).abs() + (b[2] * r[1]).abs(),
    ];
    let ka = 1.0 + r[0].abs() * ua[0] + r[1].abs() * ua[1];
    let da = (a[0] * a[2]).abs() + a[1] * a[1];
    let ma = (a[0] * b[2]).abs() + (a[2] * b[0]).abs() + 2.0 * (a[1] * b[1]).abs();
    let ea = (b[0] * b[2]).abs() + b[1] * b[1];
    let alpha_a = a[2].abs() * ua[0] * ua[0]
        + 2.0 * (a[1] * ua[0] * ua[1]).abs()
        + a[0].abs() * ua[1] * ua[1];
    let g = CUBIC_ROUNDING * kappa1.max(kappa2);
    let bound = [ea, ka * ma + ea + alpha_a, ka * da + ma, da].map(|x| g * x);
    match p.iter().chain(&bound).all(|c| c.is_finite()) && p[0] > 0.0 && p[3] < 0.0 {
        true => Ok((p, bound)),
        false => Err(ContactError::Overflow {
            what: "coefficients of det(λA − B) (beyond double range)",
        }),
    }
}

/// Whether two ellipses are separated, by the sign pattern of the roots of
/// `det(λA − B)` (two distinct negative roots; see the module docs). The true `P` lies
/// between the cubics whose coefficients are those computed plus and minus their
/// rounding bounds ([`CUBIC_ROUNDING`]): `Some(true)` if the upper one is negative
/// somewhere in `(0, 1)`, `Some(false)` if the lower one is positive on `[0, 1]`, and
/// `None` (undecided) otherwise: within the rounding of tangency, which the condition
/// of the forms and the ratio of their sizes widen. Touching
/// ellipses are not separated. A cross-check, not a decision the packer takes:
/// [`overlaps_2d`] is that, and it decides every pair.
///
/// [`overlaps_2d`]: crate::contact::overlaps_2d
///
/// ```
/// use grainpack::contact::wang::separated_2d;
/// let unit = [1.0, 0.0, 1.0];
/// assert_eq!(separated_2d(&[2.5, 0.0], &unit, &unit).unwrap(), Some(true));
/// assert_eq!(separated_2d(&[1.5, 0.0], &unit, &unit).unwrap(), Some(false));
/// ```
///
/// # Errors
/// As [`characteristic_polynomial_2d`], after rescaling the input by powers of two (the
/// inverses of the forms leave the double range for sizes about `1e75` apart).
pub fn separated_2d(r12: &Vec2, q1: &Sym2, q2: &Sym2) -> Result<Option<bool>, ContactError> {
    // Lengths rescaled by 2^-j so that the larger form is of order 1 (exact; the
    // answer does not change).
    let largest = q1[0].max(q1[2]).max(q2[0]).max(q2[2]);
    let j = match largest > 0.0 && largest.is_finite() {
        true => exponent(largest).div_euclid(2),
        false => 0,
    };
    let r = r12.map(|x| ldexp(x, -j));
    let scale = |q: &Sym2| q.map(|x| ldexp(x, -2 * j));
    let (p, bound) = coefficients(&r, &scale(q1), &scale(q2))?;
    // λ = σμ: the negative roots, near −r1/r2 for touching circles, become of order 1.
    let sigma = pow2((exponent(q1[0].max(q1[2])) - exponent(q2[0].max(q2[2]))).div_euclid(2));
    // In the basis t^k (1−t)^{3−k}, P has the coefficients w_k = (−σ)^k p_k.
    let powers = [1.0, sigma, sigma * sigma, sigma * sigma * sigma];
    let w = [p[0], -powers[1] * p[1], powers[2] * p[2], -powers[3] * p[3]];
    let err: [f64; 4] = std::array::from_fn(|i| powers[i] * bound[i]);
    if !w.iter().chain(&err).all(|x| x.is_finite()) {
        return Err(ContactError::Overflow {
            what: "coefficients of det(λA − B) (beyond double range)",
        });
    }
    // The true P lies between the cubics of coefficients w − err and w + err: it is
    // negative somewhere if the upper one is, positive on [0, 1] if the lower one is.
    let shifted = |sign: f64| -> [f64; 4] { std::array::from_fn(|i| w[i] + sign * err[i]) };
    if min_on_unit(&shifted(1.0)) < 0.0 {
        return Ok(Some(true));
    }
    if min_on_unit(&shifted(-1.0)) > 0.0 {
        return Ok(Some(false));
    }
    Ok(None)
}

/// The sign of the least value on `[0, 1]` of `Σ c_k t^k (1−t)^{3−k}` (at an end or at
/// a root of its derivative), as a value of that sign: the coefficients are first
/// scaled by a power of two to a largest magnitude of order 1, so that the derivative's
/// discriminant cannot overflow (sizes far apart spread them over 1e200).
fn min_on_unit(c: &[f64; 4]) -> f64 {
    let largest = c.iter().fold(0.0f64, |m, x| m.max(x.abs()));
    if !(largest > 0.0) {
        return 0.0;
    }
    let k = exponent(largest);
    let c = c.map(|x| ldexp(x, -k));
    let at = |t: f64| {
        let s = 1.0 - t;
        c[0] * s * s * s + c[1] * t * s * s + c[2] * t * t * s + c[3] * t * t * t
    };
    // The derivative in the power basis: the cubic is c0 + d1 t + d2 t² + d3 t³.
    let d1 = -3.0 * c[0] + c[1];
    let d2 = 3.0 * c[0] - 2.0 * c[1] + c[2];
    let d3 = -c[0] + c[1] - c[2] + c[3];
    (critical_points(d1, 2.0 * d2, 3.0 * d3)
        .into_iter()
        .flatten())
    .filter(|t| *t > 0.0 && *t < 1.0)
    .map(at)
    .fold(c[0].min(c[3]), f64::min)
}

/// The real roots of `a + b t + c t²`, by the formula that avoids cancellation.
fn critical_points(a: f64, b: f64, c: f64) -> [Option<f64>; 2] {
    if c == 0.0 {
        return [(b != 0.0).then(|| -a / b), None];
    }
    let disc = b * b - 4.0 * a * c;
    if disc < 0.0 {
        return [None, None];
    }
    let q = -0.5 * (b + b.signum() * disc.sqrt());
    let first = q / c;
    [Some(first), (q != 0.0).then(|| a / q)]
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn circles_are_separated_beyond_the_sum_of_radii() {
        for (r1, r2) in [(1.0, 1.0), (0.3, 2.0), (1e-4, 10.0)] {
            let (a, b) = ([r1 * r1, 0.0, r1 * r1], [r2 * r2, 0.0, r2 * r2]);
            let d = r1 + r2;
            // 1e-6 relative: far from the rounding of the coefficients.
            let apart = separated_2d(&[0.0, d * (1.0 + 1e-6)], &a, &b).unwrap();
            assert_eq!(apart, Some(true), "{r1} {r2}");
            let touching = separated_2d(&[d * (1.0 - 1e-6), 0.0], &a, &b).unwrap();
            assert_eq!(touching, Some(false), "{r1} {r2}");
        }
    }

    #[test]
    fn unit_circles_have_the_cubic_of_the_module_docs() {
        let d: f64 = 3.0;
        let p = characteristic_polynomial_2d(&[d, 0.0], &[1.0, 0.0, 1.0], &[1.0, 0.0, 1.0]);
        // (λ − 1)(−λ² + (2 − d²)λ − 1) = −λ³ + (3 − d²)λ² + (d² − 3)λ + 1.
        assert_eq!(p.unwrap(), [1.0, d * d - 3.0, 3.0 - d * d, -1.0]);
    }

    #[test]
    fn tangent_circles_are_undecided() {
        let unit = [1.0, 0.0, 1.0];
        assert_eq!(separated_2d(&[2.0, 0.0], &unit, &unit).unwrap(), None);
    }

    #[test]
    fn segments_have_no_canonical_matrix() {
        let e = separated_2d(&[2.0, 0.0], &[1.0, 0.0, 0.0], &[1.0, 0.0, 1.0]).unwrap_err();
        assert!(matches!(
            e,
            ContactError::NotPositiveDefinite {
                what: "q1",
                pivot: 1,
                ..
            }
        ));
    }
}
