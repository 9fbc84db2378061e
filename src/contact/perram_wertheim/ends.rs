//! For [`super::robust`]: whether `F = N/C` is largest at an end of `[0, 1]`, and its
//! limit there.
//!
//! Where `N` and `C` vanish to the same order at an end, `F` has a finite limit there,
//! and `F` rises from that end if the first cross term `n_k c_0 − c_k n_0` (`k ≥ 1`,
//! coefficients counted from the end) is positive. `F` is quasi-concave (λ̂ is a
//! monotone map of λ and `f` is concave), so its maximum is at an end it does not
//! rise from, and it can fail to rise from both only if it is constant.

use crate::contact::scale::{exponent, ldexp};
use crate::contact::Stop;

/// Where `F = N/C` is largest on `[0, 1]`, and its value.
#[derive(Debug, Clone, Copy, PartialEq)]
pub(super) struct Maximum {
    pub value: f64,
    /// `1 − λ̂` and `λ̂`, each with its own relative precision.
    pub s: f64,
    pub t: f64,
    pub stop: Stop,
    pub iterations: u32,
}

/// A cross term `n_k c_0 − c_k n_0` within `CROSS_TERM_TOL · (n_k c_0 + c_k n_0)` of 0 has
/// no sign the coefficients resolve, and the next order decides. Each coefficient is a
/// double rounded once (`ε/2`, module [`exact`](super::exact)), each product rounds once
/// more, so a product is within `3ε/2` of its exact value, and a difference smaller
/// than `2ε` of their sum is rounding. `4ε` leaves room for the double-double error of
/// the coefficients (`ε²` of their terms). Testing the sign of the rounded difference
/// instead made μ² depend on the order of the pair where the first term is 0 in exact
/// arithmetic: two ellipses of sizes 1e150 apart, the limit 1e62 times larger at the
/// end whose test did not resolve (fuzz target `contact_bits_2d`).
const CROSS_TERM_TOL: f64 = 4.0 * f64::EPSILON;

/// The maximum of `F` if it lies at an end (λ̂ = 0 or 1), given the coefficients `n`,
/// `c` of degrees `0..=4`, first and last non-zero at `lo`, `hi` for both (`None` for an
/// end where one vanishes to a higher order than the other: there `F` tends to 0 and
/// rises from it, or is unbounded, which the caller has refused). `None` if `F`
/// rises from both ends: the maximum is inside.
pub(super) fn maximum_at_an_end(
    n: &[f64; 5],
    c: &[f64; 5],
    lo: Option<usize>,
    hi: Option<usize>,
) -> Option<Maximum> {
    let (nr, cr) = (reversed(n), reversed(c));
    let at_zero = lo.map(|k| (n[k] / c[k], rises(&n[k..], &c[k..])));
    let at_one = hi.map(|k| (n[k] / c[k], rises(&nr[4 - k..], &cr[4 - k..])));
    match (at_zero, at_one) {
        // F constant in exact arithmetic, or one test decided by rounding: the larger
        // limit is the maximum. Equal limits: F is flat, and λ̂ = ½ is the choice that
        // is the same for the pair in either order.
        (Some((v0, false)), Some((v1, false))) if v0 == v1 => Some(Maximum {
            value: v0,
            s: 0.5,
            t: 0.5,
            stop: Stop::Exact,
            iterations: 0,
        }),
        (Some((v0, false)), Some((v1, false))) => Some(end(v0.max(v1), v1 > v0)),
        (Some((v, false)), _) => Some(end(v, false)),
        (_, Some((v, false))) => Some(end(v, true)),
        _ => None,
    }
}

/// The maximum at λ̂ = 0 (or 1 if `at_one`), in closed form.
pub(super) fn end(value: f64, at_one: bool) -> Maximum {
    let (s, t) = if at_one { (0.0, 1.0) } else { (1.0, 0.0) };
    Maximum {
        value,
        s,
        t,
        stop: Stop::Exact,
        iterations: 0,
    }
}

pub(super) fn reversed(p: &[f64; 5]) -> [f64; 5] {
    [p[4], p[3], p[2], p[1], p[0]]
}

/// Whether `N/C` rises from `x = 0` when both start at the same index (`n[0], c[0] >
/// 0`): `ψ(x) = k (n_k/n_0 − c_k/c_0) (x/(1−x))^k + …` for the first `k` whose cross
/// term the coefficients resolve ([`CROSS_TERM_TOL`]).
fn rises(n: &[f64], c: &[f64]) -> bool {
    let pad = |p: &[f64], k: usize| p.get(k).copied().unwrap_or(0.0);
    (1..n.len().max(c.len()))
        .map(|k| cross_term(pad(n, k), c[0], pad(c, k), n[0]))
        .find(|&(d, size)| d.abs() > CROSS_TERM_TOL * size)
        .is_some_and(|(d, _)| d > 0.0)
}

/// `(a b − c d, a b + c d)` for non-negative finite doubles, both divided by the same
/// power of two so that neither product underflows (the coefficients of a form
/// 1e-300 thick against one of size 1 multiply to far below the double range).
fn cross_term(a: f64, b: f64, c: f64, d: f64) -> (f64, f64) {
    // The product as a mantissa in [1, 4) and an exponent.
    let split = |x: f64, y: f64| {
        (x > 0.0 && y > 0.0).then(|| {
            let (ex, ey) = (exponent(x), exponent(y));
            (ldexp(x, -ex) * ldexp(y, -ey), ex + ey)
        })
    };
    match (split(a, b), split(c, d)) {
        (None, None) => (0.0, 0.0),
        (Some(_), None) => (1.0, 1.0),
        (None, Some(_)) => (-1.0, 1.0),
        (Some((p, e)), Some((q, f))) => {
            let top = e.max(f);
            let (p, q) = (ldexp(p, e - top), ldexp(q, f - top));
            (p - q, p + q)
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Products far below the double range keep their order: `1e-200 · 1e-200` against
    /// `1e-250 · 1e-160` underflow to 0 both as doubles.
    #[test]
    fn cross_term_has_the_sign_of_products_below_the_double_range() {
        let (d, size) = cross_term(1e-200, 1e-200, 1e-250, 1e-160);
        assert!(d > 0.0 && d <= size);
        let (d, _) = cross_term(1e-250, 1e-160, 1e-200, 1e-200);
        assert!(d < 0.0);
        assert_eq!(cross_term(0.0, 1.0, 5e-324, 0.0), (0.0, 0.0));
    }

    /// A first cross term at the rounding of its products leaves the decision to the
    /// second. The coefficients of fuzz input `crash-66816f1a` (fuzz/corpus/
    /// contact_bits_2d) at its end of size 1: `n_1 c_0 − c_1 n_0` is −1.8e-15 in doubles
    /// (−7.2e-16 for these doubles exactly) against products of 8.9, and the second
    /// term, 8e-243 against 5e-305, says that F rises.
    #[test]
    fn a_first_cross_term_at_rounding_level_leaves_the_sign_to_the_next() {
        let n = [5.005645751956843, 3.671417925508227, 3.336422666426047e-243];
        let c = [
            2.417394518854051,
            1.7730510725966808,
            1.0099634154068553e-305,
        ];
        assert!(n[1] * c[0] - c[1] * n[0] < 0.0);
        assert!(rises(&n, &c));
    }
}
