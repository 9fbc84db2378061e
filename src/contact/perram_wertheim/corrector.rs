//! The corrector of [`contact_function`](super::contact_function): Newton steps on the
//! residual `g = −f′` evaluated by [`refine`](crate::contact::refine), from the
//! predictor's λ.

use super::robust_bound::robust_lambda_bound;
use super::GAIN_TOL;
use super::{refined_ldl, PencilParts, Rational, MAX_ITERATIONS};
use super::{Contact, ContactError, Prepared, Refined, Refiner, Stop, Sym3, Vec3};
use crate::contact::GAIN_ROUNDING_TOL;

/// Newton on the refined residual from the predictor's λ, until the refined gain is
/// below [`GAIN_TOL`]; the gain is then added. One step is the rule: it is taken here,
/// and [`correct_further`] takes over when it does not suffice. Where `g` is not
/// accurate enough for the gain to be added (module `refine::gain`), `f` is evaluated
/// at the Newton point instead, whose gain is second order in the error of `g`.
#[inline(always)]
pub(super) fn correct(
    p: &Prepared,
    refiner: &Refiner,
    t: f64,
    iterations: u32,
) -> Result<Contact, ContactError> {
    correct_checking::<false>(p, refiner, t, iterations)
}

/// [`correct`], checking `g` if `CHECK_G` ([`Refiner::at_checking`]).
#[inline(always)]
pub(super) fn correct_checking<const CHECK_G: bool>(
    p: &Prepared,
    refiner: &Refiner,
    t: f64,
    iterations: u32,
) -> Result<Contact, ContactError> {
    if let Some(v) = refiner.at_checking::<CHECK_G>(t) {
        if let Some((mu2, polished)) = finished(&v, t, (0.0, 1.0)) {
            if v.g_trusted {
                return p.finish(mu2, polished, Stop::Converged, iterations + 1);
            }
            return step_first(p, refiner, polished, iterations + 1);
        }
    }
    correct_further(&p.r, &p.q1, &p.q2, p.mu2_exp, t, iterations)
}

/// [`correct`]'s evaluation at the Newton point `t`.
#[cold]
#[inline(never)]
fn step_first(
    p: &Prepared,
    refiner: &Refiner,
    t: f64,
    iterations: u32,
) -> Result<Contact, ContactError> {
    if let Some(v) = refiner.at_checking::<true>(t).filter(|v| v.g_trusted) {
        if let Some((mu2, polished)) = finished(&v, t, (0.0, 1.0)) {
            return p.finish(mu2, polished, Stop::Converged, iterations + 1);
        }
    }
    correct_further(&p.r, &p.q1, &p.q2, p.mu2_exp, t, iterations)
}

/// μ² and the polished λ (kept in `bracket`) if the Newton model at `t` has converged:
/// its gain `g²/(2g′)` is at most [`GAIN_TOL`]` · f` and is added, and the next Taylor
/// term it leaves out, `|g″| Δ³ / 6` with `Δ = g/g′`, is at most [`CUBIC_TERM_TOL`]` · f`.
///
/// λ is polished to second order, `t − Δ − g″Δ²/(2g′)` (the root of `g`'s Taylor
/// quadratic, one Chebyshev step), at no further evaluation. The Newton step alone,
/// `t − Δ`, leaves `g″Δ²/(2g′)` in λ, which the gain test does not bound: μ² is
/// stationary in λ, so a step whose gain is below `GAIN_TOL` may still be 1e-6 long
/// where the maximum is flat (`g′/f` small), and λ kept ~1e-12 of it (fuzz target
/// `contact_bits_2d`, defect 11 of `docs/reliability.md`: λ of the swapped pair
/// 1.1e-12 from `1 − λ`). μ² is unchanged: the gain is that of the Newton model.
#[inline(always)]
pub(super) fn finished(v: &Refined, t: f64, bracket: (f64, f64)) -> Option<(f64, f64)> {
    let step = v.g / v.gp;
    let gain = 0.5 * v.g * step;
    let cubic6 = v.gpp.abs() * (step * step * step).abs(); // 6 × the cubic term
    let second = 0.5 * v.gpp * step * (step / v.gp);
    (v.gp > 0.0 && gain <= GAIN_TOL * v.f && cubic6 <= 6.0 * CUBIC_TERM_TOL * v.f)
        .then(|| (v.f + gain, (t - step - second).clamp(bracket.0, bracket.1)))
}

/// How far λ of [`contact_function`](super::contact_function) may lie from λ*: on its
/// common path, `√(2 GAIN_ROUNDING_TOL · f / g′)` at `lambda`, with `f` and `g′ = −f″`
/// of the refined evaluation. The definite forms beyond
/// [`FORM_MAX_CONDITION`](crate::contact::FORM_MAX_CONDITION) that the robust path
/// takes get that bound too, which their λ (measured: within 5e-15 of
/// `tools/contact_exact.py`'s) meets. Where that evaluation fails (forms that do not
/// factor: the robust path's pairs), the robust path's own bound, `λ(1 − λ) du` with
/// `du = √(2 FINAL_GAIN / |φ″|) + δψ / |φ″|` in `u = ln(λ̂/(1 − λ̂))` (its stopping test,
/// and the error `δψ` of its residual `ψ = φ′`, `φ = ln F`, from the resolution of its
/// coefficients; module `robust_bound`): on the 4 pairs of defect 17 in
/// `docs/reliability.md`, 5.9e-7 to 0.38, against λ 2e-12 to 1.9e-3 from
/// `tools/contact_exact.py`'s λ*. `None` at an end (λ = 0 or 1, a limit in closed form)
/// and where `f` is not curved.
///
/// μ² is stationary in λ, so the corrector needs `g = −f′` only to `δg` with
/// `δg²/(2g′) ≤ GAIN_ROUNDING_TOL · f` for μ² to be right to `ε/8`
/// ([`GAIN_ROUNDING_TOL`](crate::contact::GAIN_ROUNDING_TOL)); λ, the root of `g`,
/// moves by `δg/g′`, up to this bound, which grows as the maximum flattens
/// (`g′/f` small). It is also λ's conditioning: on 16 of the 21 pairs of defect 11
/// (`docs/reliability.md`) a change of one ulp in the entries of `r12`, `q1`, `q2`
/// moves λ* by more than 1e-12, up to 7.3e-8 (`tools/contact_exact.py`), so no method
/// working in doubles holds λ there to the 1e-12 it keeps on typical pairs. Beyond
/// the rounding, the truncation of the polished λ is third order in the last Newton
/// step (`finished`, below).
///
/// ```
/// use grainpack::contact::{contact_function, lambda_bound};
/// let (r, q) = ([2.0, 0.0, 0.0], [1.0, 0.0, 0.0, 1.0, 0.0, 1.0]);
/// let c = contact_function(&r, &q, &q).unwrap();
/// // Two unit balls 2 apart: λ* = ½, f = 4λ(1−λ), g′/f = 8 there.
/// let bound = lambda_bound(&r, &q, &q, c.lambda).unwrap();
/// assert!((bound - (2.0 * grainpack::contact::GAIN_ROUNDING_TOL / 8.0).sqrt()).abs() < 1e-15);
/// ```
pub fn lambda_bound(r12: &Vec3, q1: &Sym3, q2: &Sym3, lambda: f64) -> Option<f64> {
    let common = || {
        let p = Prepared::new(r12, q1, q2).ok()?;
        let v = refined_ldl(lambda, &p.r, &p.q1, &p.q2).ok()?;
        let ratio = v.f / v.gp;
        (v.gp > 0.0 && ratio.is_finite()).then(|| (2.0 * GAIN_ROUNDING_TOL * ratio).sqrt())
    };
    common().or_else(|| robust_lambda_bound(r12, q1, q2, lambda))
}

/// Largest relative size of the third-order Taylor term that the corrector's result may
/// leave out: `ε/8`. The quadratic gain test alone ([`GAIN_TOL`]) bounds it by
/// `GAIN_TOL^{3/2}` only where `f` is curved like its poles; when λ* is within ~1e-6 of
/// 0 or 1 the poles nearly cancel and the term can be ~1e3 times that.
pub const CUBIC_TERM_TOL: f64 = f64::EPSILON / 8.0;

/// The corrector's bracket on λ* is closed when it is at most `BRACKET_CLOSED = 4ε`
/// of its upper end wide: a few ulps of λ.
const BRACKET_CLOSED: f64 = 4.0 * f64::EPSILON;

/// The corrector's Newton iteration, bracketed afresh (the predictor's bracket rests on
/// the rational form's rounding), with the LDLᵀ refinement wherever the adjugate start
/// is not good enough. Takes the (scaled) pair itself and rebuilds what it needs, so
/// that the common path keeps its working values in registers.
#[cold]
#[inline(never)]
pub(super) fn correct_further(
    r: &Vec3,
    q1: &Sym3,
    q2: &Sym3,
    mu2_exp: i32,
    t: f64,
    mut iterations: u32,
) -> Result<Contact, ContactError> {
    let p = Prepared::new(r, q1, q2)?.with_mu2_exp(mu2_exp);
    let (a, b) = (p.l1.quadratic_form(&p.r), p.l2.quadratic_form(&p.r));
    let parts = PencilParts::new(&p.q1, &p.q2);
    let rational = Rational::new(&p.r, &p.q1, &p.q2, &parts, [p.l1.det(), p.l2.det(), a, b]);
    let refiner = Refiner::new(&p, &parts, &rational);
    let evaluate = |lambda: f64| -> Result<Refined, ContactError> {
        match refiner.at_checking::<true>(lambda).filter(|v| v.g_trusted) {
            Some(v) => Ok(v),
            None => refined_ldl(lambda, &p.r, &p.q1, &p.q2),
        }
    };
    let (mut lo, mut hi) = (0.0, 1.0);
    let mut lambda = t;
    for _ in 0..MAX_ITERATIONS {
        iterations += 1;
        let v = evaluate(lambda)?;
        if let Some((mu2, polished)) = finished(&v, lambda, (lo, hi)) {
            return p.finish(mu2, polished, Stop::Converged, iterations);
        }
        if v.g > 0.0 {
            hi = lambda;
        } else if v.g < 0.0 {
            lo = lambda;
        } else {
            return p.finish(v.f, lambda, Stop::Converged, iterations);
        }
        // A curvature lost to rounding (g′ ≤ 0, where f is concave) is no sign of
        // convergence: the bracket goes on closing on the sign of g, the refined part,
        // until it is at rounding. (Taking it as converged answered μ² 2e-5 below the
        // maximum, 3e-6 from it in λ: fuzz target `contact_bits_2d`, defect 14.)
        if !(v.gp > 0.0) && hi - lo <= BRACKET_CLOSED * hi {
            return p.finish(v.f, lambda, Stop::Converged, iterations);
        }
        let next = if v.gp > 0.0 {
            lambda - v.g / v.gp
        } else {
            f64::NAN
        };
        lambda = if next > lo && next < hi {
            next
        } else {
            0.5 * (lo + hi)
        };
    }
    let v = evaluate(lambda)?;
    p.finish(v.f, lambda, Stop::MaxIterations, iterations)
}

#[cfg(test)]
mod tests {
    use super::*;

    fn refined(g: f64, gpp: f64) -> Refined {
        Refined {
            f: 1.0,
            g,
            gp: 1.0,
            gpp,
            g_trusted: true,
        }
    }

    /// A small quadratic gain is accepted and added, and the step polishes λ to second
    /// order: `g + g′Δ + g″Δ²/2 = 0` with `g = 1e-6`, `g′ = g″ = 1` gives
    /// `Δ = −1e-6 − 0.5e-12` (the Newton step alone, `−1e-6`, leaves `0.5e-12`)...
    #[test]
    fn corrector_adds_a_small_gain() {
        let (mu2, lambda) = finished(&refined(1e-6, 1.0), 0.5, (0.0, 1.0)).unwrap();
        assert_eq!((mu2, lambda), (1.0 + 0.5e-12, 0.5 - 1e-6 - 0.5e-12));
    }

    /// Defect 14 of `docs/reliability.md` (fuzz target `contact_bits_2d`): from the
    /// predictor's λ = 1 − 4.1e-7 on a needle of `κ(Q)` 3e11 (which the robust path now
    /// takes, `FORM_MAX_CONDITION`), the refined `g′` is not positive, and taking that
    /// for convergence answered μ² 2.0e-5 below `tools/contact_exact.py`'s
    /// 1.3015266575024577e31; closing the bracket on the sign of `g` leaves 1e-12 (the
    /// pivots' rounding, `ε κ(Q)`, bounds it there, 1e-11 with room).
    #[test]
    fn correct_further_closes_its_bracket_where_the_curvature_is_lost_to_rounding() {
        let r = [7.477750072378836e20, 5.754711558261857e20, 0.0];
        let q1 = [
            7.477080264586548e20,
            7.477080264543605e20,
            0.0,
            7.477080264523472e20,
            0.0,
            7.47708026455501e20,
        ];
        let q2 = [
            0.025132242838541666,
            0.00047679344813029615,
            0.0,
            0.000484719701714185,
            0.0,
            0.012808481270127925,
        ];
        let c = correct_further(&r, &q1, &q2, 0, 0.999_999_588_256_795_9, 1).unwrap();
        let exact = 1.301_526_657_502_457_7e31;
        assert!((c.mu2 - exact).abs() <= 1e-11 * exact, "{c:?}");
        assert_eq!(c.stop, Stop::Converged);
    }

    /// ...unless the third-order term left out is above ε/8 (here 1e10 · 1e-18 / 6),
    /// or the gain is above GAIN_TOL, or the curvature has the wrong sign.
    #[test]
    fn corrector_refuses_large_cubic_terms_and_gains() {
        assert!(finished(&refined(1e-6, 1e10), 0.5, (0.0, 1.0)).is_none());
        assert!(finished(&refined(1e-5, 1.0), 0.5, (0.0, 1.0)).is_none());
        let flat = Refined {
            gp: -1.0,
            ..refined(1e-9, 1.0)
        };
        assert!(finished(&flat, 0.5, (0.0, 1.0)).is_none());
    }
}
