//! `f(λ) = λ(1−λ) a(λ) / b(λ)` in Bernstein form, for a cheap scalar Newton iteration.
//!
//! With `s = 1−λ`, `t = λ` and `Q(λ) = s Q1 + t Q2`:
//! - `b(λ) = det Q(λ) = B0 s³ + B1 s²t + B2 st² + B3 t³`, with `B0 = det Q1`,
//!   `B1 = tr(adj Q1 · Q2)`, `B2 = tr(Q1 · adj Q2)`, `B3 = det Q2`;
//! - `a(λ) = rᵀ adj Q(λ) r = A0 s² + A1 st + A2 t²`, with `A0 = rᵀ adj Q1 r`,
//!   `A2 = rᵀ adj Q2 r` and `A1 = rᵀ M r`, `M` the mixed adjugate (bilinear part of
//!   `adj(Q1 + Q2)`).
//!
//! Mixed discriminants of positive-definite matrices are positive, so every coefficient
//! is, and `a`, `b` evaluate without cancellation on `[0, 1]`. The iteration works on
//! `φ = ln f`, concave like `f`, whose derivative
//! `φ′ = 1/t − 1/s + a′/a − b′/b` carries the poles at both ends exactly.

use super::sym::pencil_coefficients;
use super::{Sym3, Vec3};

/// The seven Bernstein coefficients of `a` and `b`.
#[derive(Debug, Clone, Copy)]
pub(crate) struct Rational {
    a: [f64; 3],
    b: [f64; 4],
}

impl Rational {
    /// The coefficients of the pair. The end coefficients come from the caller's
    /// stable factorisations: `det1 = det Q1`, `det2 = det Q2`, `a = rᵀQ1⁻¹r`,
    /// `b = rᵀQ2⁻¹r` (so `A0 = det1 · a`, `A2 = det2 · b`); by cofactors they would
    /// err by `ε cond²`. The mixed ones are sums of positive terms and err by
    /// `ε cond` at worst.
    #[inline(always)]
    pub fn new(r: &Vec3, q1: &Sym3, q2: &Sym3, ends: [f64; 4]) -> Self {
        let [det1, det2, a_end, b_end] = ends;
        let (mut a, mut b) = pencil_coefficients(q1, q2, r);
        (a[0], a[2], b[0], b[3]) = (det1 * a_end, det2 * b_end, det1, det2);
        Self { a, b }
    }

    /// `f(λ)`.
    #[inline(always)]
    pub fn f(&self, t: f64) -> f64 {
        let s = 1.0 - t;
        let [a0, a1, a2] = self.a;
        let [b0, b1, b2, b3] = self.b;
        let a = (a0 * s + a1 * t) * s + a2 * t * t;
        let b = ((b0 * s + b1 * t) * s + b2 * t * t) * s + b3 * t * t * t;
        s * t * a / b
    }

    /// `φ′`, `φ″` and `φ‴` of `φ = ln f` at λ.
    #[inline(always)]
    pub fn log_derivatives(&self, t: f64) -> [f64; 3] {
        let s = 1.0 - t;
        let [a0, a1, a2] = self.a;
        let [b0, b1, b2, b3] = self.b;
        let a = (a0 * s + a1 * t) * s + a2 * t * t;
        let da = 2.0 * (a2 * t - a0 * s) + a1 * (s - t);
        let dda = 2.0 * (a0 - a1 + a2);
        let b = ((b0 * s + b1 * t) * s + b2 * t * t) * s + b3 * t * t * t;
        let db = 3.0 * (b3 * t * t - b0 * s * s) + b1 * s * (s - 2.0 * t) + b2 * t * (2.0 * s - t);
        let ddb = 6.0 * (b0 * s + b3 * t) + b1 * (2.0 * t - 4.0 * s) + b2 * (2.0 * s - 4.0 * t);
        let dddb = 6.0 * (b1 - b0 - b2 + b3);
        // 1/t = s/(ts) and 1/s = t/(ts): one division for both. (Not so for a and b,
        // whose product may overflow.)
        let its = 1.0 / (t * s);
        let (it, is, ia, ib) = (s * its, t * its, 1.0 / a, 1.0 / b);
        let (ra, raa) = (da * ia, dda * ia);
        let (rb, rbb, rbbb) = (db * ib, ddb * ib, dddb * ib);
        let d1 = it - is + ra - rb;
        let d2 = -it * it - is * is + raa - ra * ra - rbb + rb * rb;
        let d3 = 2.0 * (it * it * it - is * is * is) + ra * (2.0 * ra * ra - 3.0 * raa)
            - rbbb
            - rb * (2.0 * rb * rb - 3.0 * rbb);
        [d1, d2, d3]
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// φ′, φ″ and φ‴ against central differences of φ = ln f.
    #[test]
    fn log_derivatives_match_finite_differences() {
        let r = [0.7, -0.7, 1.1];
        let q1 = [4.0, 1.0, 0.5, 3.0, -0.2, 2.0];
        let q2 = [1.0, -0.3, 0.1, 2.0, 0.4, 0.5];
        let l1 = crate::contact::ldl::Ldl::factor(&q1).unwrap();
        let l2 = crate::contact::ldl::Ldl::factor(&q2).unwrap();
        let ends = [
            l1.det(),
            l2.det(),
            l1.quadratic_form(&r),
            l2.quadratic_form(&r),
        ];
        let rat = Rational::new(&r, &q1, &q2, ends);
        let phi = |t: f64| rat.f(t).ln();
        let h = 1e-4;
        for t in [0.2, 0.5, 0.8] {
            let [d1, d2, d3] = rat.log_derivatives(t);
            let fd1 = (phi(t + h) - phi(t - h)) / (2.0 * h);
            let fd2 = (phi(t + h) - 2.0 * phi(t) + phi(t - h)) / (h * h);
            let fd3 = (phi(t + 2.0 * h) - 2.0 * phi(t + h) + 2.0 * phi(t - h) - phi(t - 2.0 * h))
                / (2.0 * h * h * h);
            // Central differences of step h err by O(h²) ≈ 1e-8 relative, plus rounding
            // ε/h^k; 1e-5 relative (1e-3 for the third derivative) covers both.
            assert!(
                (d1 - fd1).abs() < 1e-5 * (1.0 + d1.abs()),
                "{t}: {d1} {fd1}"
            );
            assert!(
                (d2 - fd2).abs() < 1e-5 * (1.0 + d2.abs()),
                "{t}: {d2} {fd2}"
            );
            assert!(
                (d3 - fd3).abs() < 1e-3 * (1.0 + d3.abs()),
                "{t}: {d3} {fd3}"
            );
        }
    }
}
