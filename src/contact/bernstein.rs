//! `f(λ) = λ(1−λ) a(λ) / b(λ)` in Bernstein form, for a cheap scalar Halley iteration.
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
//!
//! The coefficients of `a` and of `b` are each scaled by a power of two to a largest
//! coefficient in `[1, 2)`, which leaves `φ′, φ″, φ‴` unchanged and keeps the products
//! of [`Rational::halley`] in range.

use super::scale::{exponent, ldexp, pow2};
use super::sym::{frobenius, larger, quadratic_form, Arith, PencilParts};
use super::{Sym3, Vec3};

/// Smallest `P = t s a b` (scaled coefficients) at which [`Rational::halley`] multiplies
/// through by `P`: its terms are of order `P⁴`, and `2^-200` keeps them above
/// `2^-800`, far from underflow. Below it (sizes or λ at the edge of double range),
/// [`Rational::log_derivatives`] divides term by term instead.
pub(crate) const MIN_SCALED_PRODUCT: f64 = f64::from_bits((1023 - 200) << 52);

/// The seven Bernstein coefficients of `a` and `b`, each set scaled by a power of two,
/// with the coefficients of their derivatives (differences of neighbours, formed once).
#[derive(Debug, Clone, Copy)]
pub(crate) struct Rational {
    pub poly: Poly,
    /// `log2` of the scale taken out of the coefficients of `a`.
    a_exp: i32,
    /// `log2` of the scale taken out of the coefficients of `b`.
    b_exp: i32,
}

/// The scaled coefficients of [`Rational`] and their derivatives; generic so that
/// eight pairs can be evaluated at once ([`super::lanes::F`]).
#[derive(Debug, Clone, Copy)]
pub(crate) struct Poly<T = f64> {
    /// `a = A0 s² + A1 st + A2 t²`.
    pub a: [T; 3],
    /// `b = B0 s³ + B1 s²t + B2 st² + B3 t³`.
    pub b: [T; 4],
    /// `a′ = α0 s + α1 t` and the constant `a″`.
    pub da: [T; 2],
    pub dda: T,
    /// `b′ = β0 s² + β1 st + β2 t²`, `b″ = γ0 s + γ1 t` and the constant `b‴`.
    pub db: [T; 3],
    pub ddb: [T; 2],
    pub dddb: T,
}

/// What a Halley step on `φ′` needs at one λ: `Dk = P^k φ^(k)` with `P = t s a b > 0`,
/// so that the step `−2φ′φ″ / (2φ″² − φ′φ‴) = −2 D1 D2 P / (2 D2² − D1 D3)` costs one
/// division, and the Newton gain `φ′² / (2|φ″|) = D1² / (2|D2|)`.
#[derive(Debug, Clone, Copy)]
pub(crate) struct Halley<T = f64> {
    pub d1: T,
    pub d2: T,
    pub d3: T,
    pub p: T,
}

impl Rational {
    /// The coefficients of the pair. The end coefficients come from the caller's
    /// stable factorisations: `det1 = det Q1`, `det2 = det Q2`, `a = rᵀQ1⁻¹r`,
    /// `b = rᵀQ2⁻¹r` (so `A0 = det1 · a`, `A2 = det2 · b`); by cofactors they would
    /// err by `ε cond²`. The mixed ones are sums of positive terms and err by
    /// `ε cond` at worst.
    #[inline(always)]
    pub fn new(r: &Vec3, q1: &Sym3, q2: &Sym3, parts: &PencilParts, ends: [f64; 4]) -> Self {
        let (a, b) = coefficients(r, q1, q2, parts, ends);
        Self::from_coefficients(a, b)
    }

    /// From the unscaled coefficients of [`coefficients`].
    #[inline(always)]
    pub fn from_coefficients(a: [f64; 3], b: [f64; 4]) -> Self {
        let (a_exp, sa) = scale_of(largest(&a));
        let (b_exp, sb) = scale_of(largest(&b));
        Self {
            poly: Poly::from_scaled(a.map(|x| x * sa), b.map(|x| x * sb)),
            a_exp,
            b_exp,
        }
    }

    /// `f(λ)`.
    #[inline(always)]
    pub fn f(&self, t: f64) -> f64 {
        ldexp(self.poly.ratio(t, 1.0 - t), self.a_exp - self.b_exp)
    }

    /// `det Q(λ) = b(λ)`, unscaled.
    #[cfg(test)]
    pub fn det_at(&self, t: f64) -> f64 {
        self.det_scaled_at(t) * self.det_unit()
    }

    /// `det Q(λ)` in units of [`Rational::det_unit`]: of order 1 on most of `[0, 1]`.
    #[cfg(test)]
    pub fn det_scaled_at(&self, t: f64) -> f64 {
        self.poly.b_at(t, 1.0 - t)
    }

    /// The power of two taken out of the coefficients of `b`.
    #[cfg(test)]
    pub fn det_unit(&self) -> f64 {
        pow2(self.b_exp)
    }

    /// `1 / det_unit`, exactly (a power of two in the normal range), without a division.
    #[inline(always)]
    pub fn inv_det_unit(&self) -> f64 {
        pow2(-self.b_exp)
    }

    /// `φ′`, `φ″` and `φ‴` multiplied by `P`, `P²`, `P³` (see [`Halley`]), or `None`
    /// when `P` is below [`MIN_SCALED_PRODUCT`].
    #[inline(always)]
    pub fn halley(&self, t: f64) -> Option<Halley> {
        let h = self.poly.halley_terms(t, 1.0 - t);
        (h.p >= MIN_SCALED_PRODUCT).then_some(h)
    }

    /// `φ′`, `φ″` and `φ‴` of `φ = ln f` at λ, term by term (no range limit).
    #[inline(always)]
    pub fn log_derivatives(&self, t: f64) -> [f64; 3] {
        let s = 1.0 - t;
        let [a, da, dda, b, db, ddb, dddb] = self.poly.polynomials(t, s);
        // 1/t = s/(ts) and 1/s = t/(ts): one division for both. (Not so for a and b,
        // whose product may underflow.)
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

impl<T: Arith> Poly<T> {
    /// From the scaled coefficients of `a` and `b`, with those of their derivatives.
    #[inline(always)]
    pub fn from_scaled(a: [T; 3], b: [T; 4]) -> Self {
        let [a0, a1, a2] = a;
        let [b0, b1, b2, b3] = b;
        // d/dt of c0 s² + c1 st + c2 t² is (c1 − 2c0) s + (2c2 − c1) t, and of c0 s + c1 t
        // is c1 − c0 (s = 1 − t).
        let db = [b1 - b0.times(3.0), (b2 - b1).times(2.0), b3.times(3.0) - b2];
        let ddb = [db[1] - db[0].times(2.0), db[2].times(2.0) - db[1]];
        let da = [a1 - a0.times(2.0), a2.times(2.0) - a1];
        Self {
            a,
            b,
            da,
            dda: da[1] - da[0],
            db,
            ddb,
            dddb: ddb[1] - ddb[0],
        }
    }

    #[inline(always)]
    pub fn a_at(&self, t: T, s: T) -> T {
        let [a0, a1, a2] = self.a;
        (a0 * s + a1 * t) * s + a2 * t * t
    }

    #[inline(always)]
    pub fn b_at(&self, t: T, s: T) -> T {
        cubic(&self.b, t, s)
    }

    /// `st a / b` at λ = `t` (`s = 1 − t`): `f` in the coefficients' scaled units.
    #[inline(always)]
    pub fn ratio(&self, t: T, s: T) -> T {
        s * t * self.a_at(t, s) / self.b_at(t, s)
    }

    /// `a, a′, a″, b, b′, b″, b‴` at λ (scaled coefficients).
    #[inline(always)]
    pub fn polynomials(&self, t: T, s: T) -> [T; 7] {
        let (ss, st, tt) = (s * s, s * t, t * t);
        let [a0, a1, a2] = self.a;
        let [b0, b1, b2, b3] = self.b;
        let [da0, da1] = self.da;
        let [db0, db1, db2] = self.db;
        let [ddb0, ddb1] = self.ddb;
        let a = a0 * ss + a1 * st + a2 * tt;
        let b = s * (b0 * ss + b1 * st + b2 * tt) + b3 * tt * t;
        let da = da0 * s + da1 * t;
        let db = db0 * ss + db1 * st + db2 * tt;
        let ddb = ddb0 * s + ddb1 * t;
        [a, da, self.dda, b, db, ddb, self.dddb]
    }

    /// `φ′`, `φ″` and `φ‴` at λ = `t` (`s = 1 − t`) multiplied by `P`, `P²`, `P³`
    /// (see [`Halley`]), whatever the size of `P`.
    ///
    /// With `X1 = P/t`, `X2 = P/s`, `Ya = P a′/a`, `Yb = P b′/b`, `Za = P a″/a`,
    /// `Zb = P b″/b`, `W = P b‴/b` (each a product of polynomials, no division):
    /// `D1 = X1 − X2 + Ya − Yb`,
    /// `D2 = −X1² − X2² + P(Za − Zb) − Ya² + Yb²`,
    /// `D3 = 2(X1³ − X2³) + Ya(2Ya² − 3P Za) − P² W − Yb(2Yb² − 3P Zb)`.
    #[inline(always)]
    pub fn halley_terms(&self, t: T, s: T) -> Halley<T> {
        let [a, da, dda, b, db, ddb, dddb] = self.polynomials(t, s);
        let ts = t * s;
        let ab = a * b;
        let p = ts * ab;
        let (x1, x2) = (s * ab, t * ab);
        let (tsa, tsb) = (ts * a, ts * b);
        let (ya, yb) = (tsb * da, tsa * db);
        let (za, zb, w) = (tsb * dda, tsa * ddb, tsa * dddb);
        let d1 = x1 - x2 + ya - yb;
        let d2 = -x1 * x1 - x2 * x2 + p * (za - zb) - ya * ya + yb * yb;
        let d3 = (x1 * x1 * x1 - x2 * x2 * x2).times(2.0)
            + ya * (ya.times(2.0) * ya - p.times(3.0) * za)
            - p * p * w
            - yb * (yb.times(2.0) * yb - p.times(3.0) * zb);
        Halley { d1, d2, d3, p }
    }
}

/// The unscaled coefficients `[A0, A1, A2]`, `[B0, B1, B2, B3]` (see [`Rational::new`]).
#[inline(always)]
pub(crate) fn coefficients<T: Arith>(
    r: &[T; 3],
    q1: &[T; 6],
    q2: &[T; 6],
    parts: &PencilParts<T>,
    ends: [T; 4],
) -> ([T; 3], [T; 4]) {
    let [det1, det2, a_end, b_end] = ends;
    let a = [det1 * a_end, quadratic_form(&parts.mixed, r), det2 * b_end];
    let b = [
        det1,
        frobenius(&parts.adj1, q2),
        frobenius(q1, &parts.adj2),
        det2,
    ];
    (a, b)
}

/// The largest of a set of coefficients, in the order [`Rational::new`] compares them
/// (finite: they come from factored forms).
#[inline(always)]
pub(crate) fn largest(c: &[f64]) -> f64 {
    c[1..].iter().fold(c[0], |m, &x| larger(m, x))
}

/// `e` such that `2^-e` brings the largest coefficient `max` of a set into `[1, 2)`,
/// and that power of two.
#[inline(always)]
pub(crate) fn scale_of(max: f64) -> (i32, f64) {
    let e = normal_exponent(max);
    (e, pow2(-e))
}

/// `b0 s³ + b1 s²t + b2 st² + b3 t³`, as `b(λ)` is evaluated everywhere.
#[inline(always)]
pub(crate) fn cubic<T: Arith>(b: &[T; 4], t: T, s: T) -> T {
    let [b0, b1, b2, b3] = *b;
    ((b0 * s + b1 * t) * s + b2 * t * t) * s + b3 * t * t * t
}

/// `floor(log2 x)` of a positive normal `x`, clamped to `[-1022, 1022]` so that
/// `2^-e` is normal; 0 for anything else (zero, subnormal, NaN, infinity), which then
/// goes through unscaled and is caught downstream.
#[inline(always)]
fn normal_exponent(x: f64) -> i32 {
    if x.is_normal() {
        exponent(x).clamp(f64::MIN_EXP - 1, f64::MAX_EXP - 2)
    } else {
        0
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::contact::ldl::Ldl;

    fn example() -> Rational {
        let r = [0.7, -0.7, 1.1];
        let q1 = [4.0, 1.0, 0.5, 3.0, -0.2, 2.0];
        let q2 = [1.0, -0.3, 0.1, 2.0, 0.4, 0.5];
        let l1 = Ldl::factor(&q1).unwrap();
        let l2 = Ldl::factor(&q2).unwrap();
        let ends = [
            l1.det(),
            l2.det(),
            l1.quadratic_form(&r),
            l2.quadratic_form(&r),
        ];
        Rational::new(&r, &q1, &q2, &PencilParts::new(&q1, &q2), ends)
    }

    /// φ′, φ″ and φ‴ against central differences of φ = ln f.
    #[test]
    fn log_derivatives_match_finite_differences() {
        let rat = example();
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

    /// The scaled derivatives divided by `P^k` are the log-derivatives.
    #[test]
    fn halley_terms_are_scaled_log_derivatives() {
        let rat = example();
        for t in [1e-9, 0.2, 0.5, 0.8, 1.0 - 1e-9] {
            let d = rat.log_derivatives(t);
            let h = rat.halley(t).unwrap();
            let e = [h.d1 / h.p, h.d2 / (h.p * h.p), h.d3 / (h.p * h.p * h.p)];
            // Both sides are sums of the same terms with a few roundings each; the terms
            // cancel in φ′ near its root only (not at these λ), so 1e-12 is generous.
            for k in 0..3 {
                assert!(
                    (d[k] - e[k]).abs() <= 1e-12 * d[k].abs(),
                    "{t}: {d:?} {e:?}"
                );
            }
        }
    }

    #[test]
    fn det_at_is_the_determinant_of_the_pencil() {
        let rat = example();
        let (q1, q2) = (
            [4.0, 1.0, 0.5, 3.0, -0.2, 2.0],
            [1.0, -0.3, 0.1, 2.0, 0.4, 0.5],
        );
        for t in [0.0, 0.3, 1.0] {
            let q: Sym3 = std::array::from_fn(|k| (1.0 - t) * q1[k] + t * q2[k]);
            let d = Ldl::factor(&q).unwrap().det();
            // Well-conditioned matrices (cond < 10): a few ulps.
            assert!((rat.det_at(t) - d).abs() <= 1e-14 * d, "{t}");
        }
    }

    /// Two spheres of radii 1 and 2^-40: at their maximiser λ = 1 − 2^-40 the scaled
    /// product `P = t s a b ≈ 2^-240` is below [`MIN_SCALED_PRODUCT`], so
    /// [`Rational::halley`] declines and the term-by-term derivatives, still finite,
    /// take over; at λ = ½ both agree.
    #[test]
    fn halley_terms_decline_out_of_range_products() {
        let r = [1.0, 0.0, 0.0];
        let tiny = 2f64.powi(-80);
        let (q1, q2) = (
            [1.0, 0.0, 0.0, 1.0, 0.0, 1.0],
            [tiny, 0.0, 0.0, tiny, 0.0, tiny],
        );
        let ends = [1.0, tiny * tiny * tiny, 1.0, 1.0 / tiny];
        let rat = Rational::new(&r, &q1, &q2, &PencilParts::new(&q1, &q2), ends);
        let t = 1.0 - 2f64.powi(-40);
        assert!(rat.halley(t).is_none());
        assert!(rat.log_derivatives(t).iter().all(|d| d.is_finite()));
        let (h, d) = (rat.halley(0.5).unwrap(), rat.log_derivatives(0.5));
        // Same terms, a few roundings apart.
        assert!(
            (h.d1 / h.p - d[0]).abs() <= 1e-12 * d[0].abs().max(1.0),
            "{h:?} {d:?}"
        );
    }
}
