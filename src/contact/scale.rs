//! Input checks and power-of-two rescaling shared by the contact queries.
//!
//! μ² is homogeneous: `μ²(t r, s Q1, s Q2) = t²/s · μ²(r, Q1, Q2)`. Inputs far from 1
//! are rescaled by powers of two (exact), so that no intermediate overflows or
//! underflows, and the result is scaled back.

use super::ldl::Ldl;
use super::sym::larger;
use super::{Contact, ContactError, Stop, Sym3, Vec3};

/// Inputs whose largest |r| and all diagonal entries of Q lie within
/// `[2^-SAFE_EXP, 2^SAFE_EXP]` are used as they are. With `SAFE_EXP = 200` every
/// intermediate stays below `2^(2·200 + 200 + 50) < 2^1023` (50 bits of condition
/// number) and above the normal range.
const SAFE_EXP: i32 = 200;

/// A validated pair, possibly rescaled, with both quadratic forms factored (which is
/// how positive definiteness is checked).
#[derive(Debug, Clone, Copy)]
pub(crate) struct Prepared {
    pub r: Vec3,
    pub q1: Sym3,
    pub q2: Sym3,
    pub l1: Ldl,
    pub l2: Ldl,
    /// `log2` of the factor that turns μ² of the scaled pair into μ² of the input.
    pub mu2_exp: i32,
}

impl Prepared {
    /// The pair as it stands, for input that [`needs_no_rescaling`] and whose forms
    /// factor as `l1`, `l2`.
    #[inline(always)]
    pub fn unscaled(r12: &Vec3, q1: &Sym3, q2: &Sym3, l1: Ldl, l2: Ldl) -> Self {
        Self {
            r: *r12,
            q1: *q1,
            q2: *q2,
            l1,
            l2,
            mu2_exp: 0,
        }
    }

    /// Validates the pair (typed errors naming the input, index and value) and rescales
    /// it if needed.
    pub fn new(r12: &Vec3, q1: &Sym3, q2: &Sym3) -> Result<Self, ContactError> {
        check_finite("r12", r12)?;
        check_finite("q1", q1)?;
        check_finite("q2", q2)?;
        let qmax = q1[0].max(q1[3]).max(q1[5]).max(q2[0]).max(q2[3]).max(q2[5]);
        let qmin = q1[0].min(q1[3]).min(q1[5]).min(q2[0]).min(q2[3]).min(q2[5]);
        let rmax = r12[0].abs().max(r12[1].abs()).max(r12[2].abs());
        let in_range = |x: f64| x >= pow2(-SAFE_EXP) && x <= pow2(SAFE_EXP);
        if in_range(qmax) && in_range(qmin) && (rmax == 0.0 || in_range(rmax)) {
            return Self::factor(*r12, *q1, *q2, 0);
        }
        Self::rescaled(r12, q1, q2, qmax, rmax)
    }

    #[cold]
    fn rescaled(
        r12: &Vec3,
        q1: &Sym3,
        q2: &Sym3,
        qmax: f64,
        rmax: f64,
    ) -> Result<Self, ContactError> {
        if !(qmax > 0.0) {
            // Some diagonal entry is ≤ 0: the factorisation names it.
            return Self::factor(*r12, *q1, *q2, 0);
        }
        let k = (exponent(qmax) + 1).div_euclid(2);
        let j = if rmax > 0.0 { exponent(rmax) } else { 0 };
        let r = r12.map(|x| ldexp(x, -j));
        let q1s = q1.map(|x| ldexp(ldexp(x, -k), -k));
        let q2s = q2.map(|x| ldexp(ldexp(x, -k), -k));
        // Determinants cube the diagonal entries: one below 2^-300 after scaling means
        // the two sizes differ by more than double precision can handle together.
        let tiny = pow2(-300);
        for (q, qs) in [(q1, &q1s), (q2, &q2s)] {
            if [0, 3, 5].iter().any(|&i| q[i] > 0.0 && qs[i] < tiny) {
                return Err(ContactError::Overflow {
                    what: "the ratio of the two quadratic forms (beyond double range)",
                });
            }
        }
        Self::factor(r, q1s, q2s, 2 * j - 2 * k)
    }

    #[inline(always)]
    fn factor(r: Vec3, q1: Sym3, q2: Sym3, mu2_exp: i32) -> Result<Self, ContactError> {
        let l1 = factor(&q1, "q1")?;
        let l2 = factor(&q2, "q2")?;
        Ok(Self {
            r,
            q1,
            q2,
            l1,
            l2,
            mu2_exp,
        })
    }

    /// The same pair, standing for an input scaled by `2^mu2_exp` in μ².
    pub fn with_mu2_exp(self, mu2_exp: i32) -> Self {
        Self { mu2_exp, ..self }
    }

    /// Scales μ² back to the input's units and packages the result.
    #[inline(always)]
    pub fn finish(
        &self,
        mu2: f64,
        lambda: f64,
        stop: Stop,
        iterations: u32,
    ) -> Result<Contact, ContactError> {
        finish(self.mu2_exp, mu2, lambda, stop, iterations)
    }
}

/// The [`Contact`] of a pair rescaled so that μ² must be multiplied by `2^mu2_exp`,
/// or an overflow error.
#[inline(always)]
pub(crate) fn finish(
    mu2_exp: i32,
    mu2: f64,
    lambda: f64,
    stop: Stop,
    iterations: u32,
) -> Result<Contact, ContactError> {
    let mu2 = if mu2_exp == 0 {
        mu2
    } else {
        ldexp(mu2, mu2_exp)
    };
    if !mu2.is_finite() {
        return Err(ContactError::Overflow { what: "μ²" });
    }
    Ok(Contact {
        mu2,
        lambda,
        stop,
        iterations,
    })
}

/// Whether every diagonal entry of `q1`, `q2` and the largest `|r12_i|` (unless all are
/// 0) lie within `[2^-SAFE_EXP, 2^SAFE_EXP]`, so that the pair needs no rescaling.
/// False for NaN or infinite `r12` and infinite diagonal entries. The diagonal is
/// tested by its extremes (one `minsd` or `maxsd` per entry, where testing each entry
/// twice took twice the instructions), which may skip a NaN entry: a NaN on the
/// diagonal makes a pivot NaN, so [`Ldl::factor`], which every caller runs next,
/// rejects the form and the caller takes its validating path. Off-diagonal entries are
/// the factorisation's business too.
#[inline(always)]
pub(crate) fn needs_no_rescaling(r12: &Vec3, q1: &Sym3, q2: &Sym3) -> bool {
    let d = [q1[0], q1[3], q1[5], q2[0], q2[3], q2[5]];
    let (mut min, mut max) = (d[0], d[0]);
    for &x in &d[1..] {
        min = if x < min { x } else { min };
        max = larger(max, x);
    }
    (min >= pow2(-SAFE_EXP)) & (max <= pow2(SAFE_EXP)) & offset_in_safe_range(r12)
}

/// The part of [`needs_no_rescaling`] about one quadratic form.
#[inline(always)]
pub(crate) fn diagonal_in_safe_range(q: &Sym3) -> bool {
    let (lo, hi) = (pow2(-SAFE_EXP), pow2(SAFE_EXP));
    let in_range = |x: f64| (x >= lo) & (x <= hi);
    in_range(q[0]) & in_range(q[3]) & in_range(q[5])
}

/// The part of [`needs_no_rescaling`] about `r12`.
#[inline(always)]
pub(crate) fn offset_in_safe_range(r12: &Vec3) -> bool {
    let r = r12.map(f64::abs);
    let rmax = if r[0] > r[1] { r[0] } else { r[1] };
    let rmax = if rmax > r[2] { rmax } else { r[2] };
    let (lo, hi) = (pow2(-SAFE_EXP), pow2(SAFE_EXP));
    (r[0] <= hi) & (r[1] <= hi) & (r[2] <= hi) & ((rmax >= lo) | (rmax == 0.0))
}

#[inline(always)]
fn factor(q: &Sym3, what: &'static str) -> Result<Ldl, ContactError> {
    Ldl::factor(q).map_err(|(pivot, value)| ContactError::NotPositiveDefinite {
        what,
        pivot,
        value,
    })
}

/// Checks that `r12`, `q1`, `q2` are finite and that `q1`, `q2` are positive definite, by
/// the crate's LDLᵀ rule ([`super::MIN_RELATIVE_PIVOT`]).
pub(crate) fn validate(r12: &Vec3, q1: &Sym3, q2: &Sym3) -> Result<(), ContactError> {
    for (what, x) in [("r12", &r12[..]), ("q1", &q1[..]), ("q2", &q2[..])] {
        if let Some(index) = x.iter().position(|v| !v.is_finite()) {
            return Err(ContactError::NotFinite {
                what,
                index,
                value: x[index],
            });
        }
    }
    for (what, q) in [("q1", q1), ("q2", q2)] {
        Ldl::factor(q).map_err(|(pivot, value)| ContactError::NotPositiveDefinite {
            what,
            pivot,
            value,
        })?;
    }
    Ok(())
}

/// Inputs of the polynomial methods (rational form, Wang) whose largest diagonal entry
/// of `Q` and largest `|r12_i|` lie in `[2^-POLY_SAFE_EXP, 2^POLY_SAFE_EXP]` are used as
/// they are: the coefficients of `c(λ)` (degree 2 in `r`, 5 in `Q`) then stay within
/// `2^±700`. Others are rescaled by powers of two.
pub(crate) const POLY_SAFE_EXP: i32 = 100;

/// The same pair seen at scale `1/σ`, `σ = 2^j`: `r → r/σ`, `Q → Q/σ²`; returns it and `j`.
/// Unless the largest diagonal entry of `Q1`, `Q2` is within [`POLY_SAFE_EXP`] (then `σ = 1`),
/// `σ` brings it into `[1, 4)`. Exact (powers of two), it keeps determinants away from
/// overflow and underflow; separation and μ² are unchanged.
pub(crate) fn rescale(r12: &Vec3, q1: &Sym3, q2: &Sym3) -> (Vec3, Sym3, Sym3, i32) {
    let q_max = [q1[0], q1[3], q1[5], q2[0], q2[3], q2[5]]
        .into_iter()
        .fold(0.0, f64::max);
    if in_safe_range(q_max) {
        return (*r12, *q1, *q2, 0);
    }
    let j = (q_max.log2().floor() as i32).div_euclid(2);
    let shrink = |q: &Sym3| q.map(|x| ldexp(x, -2 * j));
    (r12.map(|x| ldexp(x, -j)), shrink(q1), shrink(q2), j)
}

pub(crate) fn in_safe_range(x: f64) -> bool {
    (ldexp(1.0, -POLY_SAFE_EXP)..=ldexp(1.0, POLY_SAFE_EXP)).contains(&x)
}

#[inline(always)]
fn check_finite(what: &'static str, values: &[f64]) -> Result<(), ContactError> {
    if values.iter().all(|x| x.is_finite()) {
        return Ok(());
    }
    let index = values.iter().position(|x| !x.is_finite()).unwrap_or(0);
    Err(ContactError::NotFinite {
        what,
        index,
        value: values[index],
    })
}

/// `2^k` for `k` in the normal range, `[-1022, 1023]`.
#[inline(always)]
pub(crate) fn pow2(k: i32) -> f64 {
    f64::from_bits(((k + 1023) as u64) << 52)
}

/// `x · 2^e`, exact unless the result leaves the double range.
#[inline]
pub(crate) fn ldexp(mut x: f64, mut e: i32) -> f64 {
    while e > 1000 {
        x *= pow2(1000);
        e -= 1000;
    }
    while e < -1000 {
        x *= pow2(-1000);
        e += 1000;
    }
    x * pow2(e)
}

/// `floor(log2 |x|)` for finite non-zero `x`, subnormals included.
pub(crate) fn exponent(x: f64) -> i32 {
    let bits = x.abs().to_bits();
    let biased = (bits >> 52) as i32;
    if biased == 0 {
        // Subnormal: 64 − 12 leading bits belong to sign and exponent.
        let lz = (bits << 12).leading_zeros() as i32;
        -1023 - lz
    } else {
        biased - 1023
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn exponent_matches_log2_for_normal_and_subnormal_numbers() {
        for x in [
            1.0,
            1.5,
            0.75,
            1e300,
            1e-300,
            3e-320,
            f64::MIN_POSITIVE,
            5e-324,
        ] {
            assert_eq!(exponent(x), x.log2().floor() as i32, "{x:e}");
        }
    }

    #[test]
    fn ldexp_reaches_across_the_whole_range() {
        assert_eq!(ldexp(1.0, -1074), 5e-324);
        assert_eq!(ldexp(ldexp(3.0, 1000), -1000), 3.0);
        assert_eq!(ldexp(ldexp(3.0, -1060), 1060), 3.0); // subnormal, still exact
    }
}
