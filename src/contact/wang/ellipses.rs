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
            true => Ok([q[2] / det, -q[1] / det, q[0] / det]),
            false => Err(ContactError::NotPositiveDefinite { what, pivot, value }),
        }
    };
    let (a, b) = (inverse(q1, "q1")?, inverse(q2, "q2")?);
    let r = r12;
    let u = [b[0] * r[0] + b[1] * r[1], b[1] * r[0] + b[2] * r[1]];
    let k = r[0] * u[0] + r[1] * u[1];
    let d2 = a[0] * a[2] - a[1] * a[1];
    let m = a[0] * b[2] + a[2] * b[0] - 2.0 * a[1] * b[1];
    let e = b[0] * b[2] - b[1] * b[1];
    let alpha = a[2] * u[0] * u[0] - 2.0 * a[1] * u[0] * u[1] + a[0] * u[1] * u[1];
    let p = [e, -(1.0 - k) * m - e - alpha, (1.0 - k) * d2 + m, -d2];
    match p.iter().all(|c| c.is_finite()) && p[0] > 0.0 && p[3] < 0.0 {
        true => Ok(p),
        false => Err(ContactError::Overflow {
            what: "coefficients of det(λA − B) (beyond double range)",
        }),
    }
}

/// Whether two ellipses are separated, by the sign pattern of the roots of
/// `det(λA − B)` (two distinct negative roots; see the module docs). Touching ellipses
/// are not separated.
///
/// The decision is the sign of `P` at its critical points, computed in double precision
/// from rounded coefficients: within their rounding of tangency (`|μ² − 1|` of order
/// `ε` times the condition numbers of the forms) it may go either way, and the
/// inverses of the forms leave the double range for sizes about `1e75` apart. This is
/// a cross-check, not a decision the packer takes: [`overlaps_2d`] is that.
///
/// [`overlaps_2d`]: crate::contact::overlaps_2d
///
/// ```
/// use grainpack::contact::wang::separated_2d;
/// let unit = [1.0, 0.0, 1.0];
/// assert!(separated_2d(&[2.5, 0.0], &unit, &unit).unwrap());
/// assert!(!separated_2d(&[1.5, 0.0], &unit, &unit).unwrap());
/// ```
///
/// # Errors
/// As [`characteristic_polynomial_2d`], after rescaling the input by powers of two.
pub fn separated_2d(r12: &Vec2, q1: &Sym2, q2: &Sym2) -> Result<bool, ContactError> {
    // Lengths rescaled by 2^-j so that the larger form is of order 1 (exact; the
    // answer does not change).
    let largest = q1[0].max(q1[2]).max(q2[0]).max(q2[2]);
    let j = match largest > 0.0 && largest.is_finite() {
        true => exponent(largest).div_euclid(2),
        false => 0,
    };
    let r = r12.map(|x| ldexp(x, -j));
    let scale = |q: &Sym2| q.map(|x| ldexp(x, -2 * j));
    let p = characteristic_polynomial_2d(&r, &scale(q1), &scale(q2))?;
    // λ = σμ: the negative roots, near −r1/r2 for touching circles, become of order 1.
    let sigma = pow2((exponent(q1[0].max(q1[2])) - exponent(q2[0].max(q2[2]))).div_euclid(2));
    // In the basis t^k (1−t)^{3−k}, P has the coefficients w_k = (−σ)^k p_k.
    let w = [
        p[0],
        -sigma * p[1],
        sigma * sigma * p[2],
        -sigma * sigma * sigma * p[3],
    ];
    if !w.iter().all(|x| x.is_finite()) {
        return Err(ContactError::Overflow {
            what: "coefficients of det(λA − B) (beyond double range)",
        });
    }
    let at = |t: f64| {
        let s = 1.0 - t;
        w[0] * s * s * s + w[1] * t * s * s + w[2] * t * t * s + w[3] * t * t * t
    };
    // P′ in the power basis: P = c0 + c1 t + c2 t² + c3 t³.
    let c1 = -3.0 * w[0] + w[1];
    let c2 = 3.0 * w[0] - 2.0 * w[1] + w[2];
    let c3 = -w[0] + w[1] - w[2] + w[3];
    Ok(critical_points(c1, 2.0 * c2, 3.0 * c3)
        .into_iter()
        .flatten()
        .any(|t| t > 0.0 && t < 1.0 && at(t) < 0.0))
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
            assert!(separated_2d(&[0.0, d * (1.0 + 1e-6)], &a, &b).unwrap());
            assert!(!separated_2d(&[d * (1.0 - 1e-6), 0.0], &a, &b).unwrap());
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
