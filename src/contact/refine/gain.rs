//! Whether `g` is good enough for the gain the corrector adds, and `g` to double-double
//! accuracy where it is not.
//!
//! The corrector adds the Newton gain `g²/(2g′)` to `f`, and `g = (2λ−1) h + p sᵀu`
//! (`h = rᵀs`, `u = (Q2−Q1)s`, `p = λ(1−λ)`) cancels: near λ* its two terms are equal
//! and opposite, up to `3e7` times larger than `g` on the reference sets. An error `δg`
//! moves the gain by `δg (|g| + δg/2) / g′`. In [`Terms::plain`] two errors make `δg`:
//! - the adjugate start errs by `η` in the norm of `Q` (`η² ≤ bound / (β num)`,
//!   [`Terms::second_order_bound`]), which moves `sᵀu` by at most `2η √(h uᵀQ⁻¹u)`
//!   (Cauchy–Schwarz in that norm). For two nearly identical, elongated ellipsoids
//!   `uᵀQ⁻¹u` is `(δ cond)²` times `h` (`δ` their relative difference): the gain
//!   was off by 1.2e-14 of μ² at aspect ratio 100 and `δ = 1e-2`;
//! - rounding: `sᵀu` from the entries of `Q2 − Q1` errs by up to `8ε |s|ᵀ|Q2−Q1||s|`,
//!   which is `ε cond` times `sᵀu` when `s` lies along a thin axis, and `g` itself by
//!   `4ε |(2λ−1)h|`.
//!
//! If `δg²/(2g′)` may exceed [`GAIN_ROUNDING_TOL`]` · f`, the corrector takes the LDLᵀ
//! refinement ([`super::refined_ldl`]), which refines `s` twice and forms `g` in
//! double-double ([`g_double_double`]). If only `δg|g|/g′` may, it evaluates `f` at the
//! Newton point instead of adding the gain, where that term is gone.

use super::*;

/// Largest relative error of μ² that the error of `g` may add through the gain:
/// `ε/8`, as for the truncation ([`CUBIC_TERM_TOL`](crate::contact::CUBIC_TERM_TOL)).
pub const GAIN_ROUNDING_TOL: f64 = f64::EPSILON / 8.0;

/// The rounding of `sᵀ(Q2−Q1)s` in doubles, in units of `ε |s|ᵀ|Q2−Q1||s|`: the
/// difference of the entries, three products and two sums in `(Q2−Q1)s`, three and two
/// in the dot product, with room (first order: 6).
const SU_ROUNDING: f64 = 8.0;

/// The rounding of `(2λ−1)h + p sᵀu` given its terms, in units of `ε |(2λ−1)h|`.
const G_ROUNDING: f64 = 4.0;

impl<T: Arith> Terms<'_, T> {
    /// Two pairs `(lhs, rhs)` for the plain values (`plain`, with `bound` of
    /// [`Terms::second_order_bound`]): `g` is good enough to second order where the
    /// first holds (`lhs ≤ rhs`), to first order where the second does (module docs).
    /// With `δg ≤ A + B`, `A² = 4p² η² h uᵀQ⁻¹u` (the start, `η² ≤ bound / (β num)`) and
    /// `B = ε(8p |s|ᵀ|Q2−Q1||s| + 4|(2λ−1)h|)` (rounding, with
    /// `|s|ᵀ|Q2−Q1||s| ≤ (Σ|s_i|)² Σ|(Q2−Q1)_ij|`), `E = A² + B²` and the budget
    /// `T = GAIN_ROUNDING_TOL · f g′`: `δg²/2 ≤ E ≤ T/2` and `δg|g| ≤ √(2E)|g| ≤ T/2`,
    /// with every term in units of `f` (`E/f²`, `T/f²`, `g/f`), so that no side
    /// leaves the double range whatever the pair's scale. (Multiplied through by
    /// `β num` instead, to spare the two divisions, the second test is of degree 5 in
    /// μ²'s scale: for μ² of 1e-110 it underflowed to `0 ≤ 0` (and left the range
    /// upwards at 1e121), pairs the common path takes as they are (`r12` and the forms
    /// within `2^±200`), and passed a `g` 0.4 % off as trusted:
    /// μ² of such pairs missed its symmetries by up to 1.7e-13, defect 18 of
    /// `docs/reliability.md`. The checks run only on pairs whose `κ` is above
    /// [`FAST_MAX_CONDITION`](crate::contact::FAST_MAX_CONDITION).)
    #[inline(always)]
    pub fn plain_g_checks(&self, plain: &(T, T, T), bound: T) -> [(T, T); 2] {
        let (f, h, su) = *plain;
        let one = T::constant(1.0);
        // Every term in units of f, and η² of β num: free of the pair's scale.
        let inv_f = f.recip();
        let eta2 = bound * (self.beta * self.num.hi).recip();
        let (h, su) = (h * inv_f, su * inv_f);
        let uw = self.uw * self.inv * self.inv * self.inv * inv_f;
        let a = self.t.times(2.0) - one;
        let g = a * h + self.p * su;
        let gp = (h + (one - self.t.times(2.0)) * su - self.p * uw).times(2.0);
        let half = gp.times(0.5 * GAIN_ROUNDING_TOL);
        // A² / f².
        let a2 = (self.p * self.p * eta2 * h * uw).times(4.0);
        let xs = self.x[0].abs() + self.x[1].abs() + self.x[2].abs();
        // Σ_ij |(Q2−Q1)_ij|, here only: the checks run on few pairs.
        let q = self.q12;
        let q12_abs = (q[0].abs() + q[3].abs() + q[5].abs())
            + (q[1].abs() + q[2].abs() + q[4].abs()).times(2.0);
        let s_m_s = xs * xs * q12_abs * self.i2 * inv_f;
        let b = (self.p * s_m_s).times(SU_ROUNDING * f64::EPSILON)
            + (a * h).abs().times(G_ROUNDING * f64::EPSILON);
        let e = a2 + b * b;
        [(e, half), (e.times(2.0) * g * g, half * half)]
    }
}

/// `g = (2λ−1) h + p sᵀ(Q2−Q1)s` at λ = `t` (`s = 1 − t` as the pencil takes it),
/// in double-double from `h = rᵀs` and `p = t s` as double-doubles: `Q2 − Q1` entry by
/// entry and every product exact, rounded once.
pub(super) fn g_double_double(
    t: f64,
    h: (f64, f64),
    p: (f64, f64),
    q1: &Sym3,
    q2: &Sym3,
    s: &Vec3,
) -> f64 {
    const UPPER: [(usize, usize); 6] = [(0, 0), (0, 1), (0, 2), (1, 1), (1, 2), (2, 2)];
    let mut su = Acc::new(0.0);
    for (k, &(i, j)) in UPPER.iter().enumerate() {
        let weight = if i == j { 1.0 } else { 2.0 };
        let (m, me) = two_sum(q2[k], -q1[k]);
        let (ss, sse) = two_prod(s[i], s[j]);
        su.add_prod(weight * m, ss);
        su.lo += weight * (m * sse + me * ss);
    }
    let (su_hi, su_lo) = su.pair();
    let (a, ae) = two_sum(2.0 * t, -1.0);
    let mut g = Acc::from_prod(a, h.0);
    g.lo += a * h.1 + ae * h.0;
    g.add_prod(p.0, su_hi);
    g.lo += p.0 * su_lo + p.1 * su_hi;
    g.value()
}
