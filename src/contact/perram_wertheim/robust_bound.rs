//! How far λ of the robust path (module [`robust`](super::robust)) may lie from λ*:
//! the part of [`lambda_bound`](crate::contact::lambda_bound) for the pairs whose forms
//! do not factor.
//!
//! The path finds the root of `ψ = dφ/du` (`φ = ln F`, `u = ln y`) to its stopping
//! test, which leaves `|ψ| ≤ √(2 FINAL_GAIN |V|)` (`V = φ″`), so `u` within
//! `√(2 FINAL_GAIN / |V|)` of the root of the computed ψ; and that root is off the exact
//! one by `δψ / |V|`, `δψ` the error of ψ. A relative error `ρ` of the weights
//! `N_k y^k` moves their mean index by at most `4ρ` (indices 0 to 4), so each of
//! `E_N`, `E_C` by `4ρ`, with `ρ` the largest relative error of a coefficient
//! (`exact::coefficient_errors`) plus `ε` for the weighted sums `C_k`; the summation of
//! ψ adds `SLOPE_TOL` of its terms' magnitudes, at most 4. `λ/(1 − λ)` is `y` times a
//! constant, so `dλ = λ(1 − λ) du`.

use super::exact::{coefficient_errors, coefficients, singular_form};
use super::robust::{normalised, vanishing, weighted, SLOPE_TOL};
use super::robust_answers;
use super::robust_root::{psi, FINAL_GAIN};
use crate::contact::scale::{exponent, ldexp};
use crate::contact::{Sym3, Vec3};

/// The relative error of μ² that [`contact_function`](crate::contact::contact_function)
/// answers by its robust path, beyond the rounding of `F` (a few ulps): `2ρ`, with `ρ`
/// the largest relative error of a coefficient of `f` it uses (module docs), which
/// reaches `F = ΣN_k y^k / ΣC_k y^k`, sums of positive terms, once through `N` and once
/// through `C`. Of order `ε` unless a coefficient cancels to far below its terms: a
/// needle of zero thickness with `r12` within 1e-12 of its line, two nearly equal
/// needles (measured: 4.7e-9 between the two orders of such a pair, defect 20 of
/// `docs/reliability.md`; 2.9e-14 between the orders of two nearly equal needles of
/// `κ(Q)` 3e11 and 2e12, beyond [`FORM_MAX_CONDITION`](crate::contact::FORM_MAX_CONDITION),
/// whose bound is 9.3e-8: defect 18). Every pair the robust path answers has it: forms
/// that do not factor, definite forms beyond `FORM_MAX_CONDITION`, and pairs whose λ* is
/// near an end ([`NEAR_END`](crate::contact::NEAR_END)). `None` for a pair the common
/// path answers (a few ulps) or that the robust path refuses.
///
/// The bound is on the robust path's own problem: each form taken as the form of its
/// rank ([`SINGULAR_PIVOT`](crate::contact::SINGULAR_PIVOT)), whose μ² may differ from
/// the exact μ² of the doubles as given by far more where a thickness below that
/// threshold is dropped.
///
/// ```
/// use grainpack::contact::{contact_function, mu2_bound};
/// // A needle of zero thickness along (1, 1, 1) and a ball, r12 across the needle.
/// let (needle, ball) = ([1.0; 6], [1.0, 0.0, 0.0, 1.0, 0.0, 1.0]);
/// let r = [1.0, -1.0, 0.5];
/// let bound = mu2_bound(&r, &needle, &ball).unwrap();
/// assert!(bound < 1e-15);
/// assert!(mu2_bound(&r, &ball, &ball).is_none());
/// # contact_function(&r, &needle, &ball).unwrap();
/// ```
pub fn mu2_bound(r12: &Vec3, q1: &Sym3, q2: &Sym3) -> Option<f64> {
    if !robust_answers(r12, q1, q2) {
        return None;
    }
    let p = pencil(r12, q1, q2)?;
    Some(2.0 * p.rho)
}

/// The coefficients of `F = N/C` as the robust path builds them, their largest relative
/// error `rho`, and the weights of the two forms.
struct Pencil {
    n: [f64; 5],
    c: [f64; 5],
    rho: f64,
    w1: f64,
    w2: f64,
}

fn pencil(r: &Vec3, q1: &Sym3, q2: &Sym3) -> Option<Pencil> {
    if r.iter().chain(q1).chain(q2).any(|x| !x.is_finite()) {
        return None;
    }
    let (e1, q1) = normalised(q1, "q1").ok()?;
    let (e2, q2) = normalised(q2, "q2").ok()?;
    let (k1, q1) = singular_form(&q1)?;
    let (k2, q2) = singular_form(&q2)?;
    let rmax = r[0].abs().max(r[1].abs()).max(r[2].abs());
    if rmax == 0.0 {
        return None;
    }
    let r = r.map(|x| ldexp(x, -exponent(rmax)));
    let (e1, e2) = (e1.or(e2).unwrap_or(0), e2.or(e1).unwrap_or(0));
    let (a, b) = vanishing(coefficients(&r, &q1, &q2), k1, k2);
    let (da, db) = coefficient_errors(&r, &q1, &q2);
    let rho = a
        .iter()
        .zip(&da)
        .chain(b.iter().zip(&db))
        .filter(|(x, _)| **x > 0.0)
        .fold(0.0f64, |m, (_, e)| m.max(*e));
    let (w1, w2, n, c) = weighted(&a, &b, e1, e2);
    Some(Pencil { n, c, rho, w1, w2 })
}

/// `λ(1 − λ) (√(2 FINAL_GAIN / |V|) + δψ / |V|)` at `lambda` (module docs); `None` at an
/// end, for sizes beyond the double range apart, where `φ` is not concave at `lambda`,
/// or for input the robust path refuses.
pub(super) fn robust_lambda_bound(r: &Vec3, q1: &Sym3, q2: &Sym3, lambda: f64) -> Option<f64> {
    if !(lambda > 0.0 && lambda < 1.0) {
        return None;
    }
    let Pencil {
        mut n,
        mut c,
        rho,
        w1,
        w2,
    } = pencil(r, q1, q2)?;
    if w1 == 0.0 || w2 == 0.0 {
        return None;
    }
    // y = λ̂/(1−λ̂) = (λ/(1−λ)) (w1/w2); the path works in y ≤ 1, mirrored above.
    let mut u = lambda.ln() - (1.0 - lambda).ln() + w1.ln() - w2.ln();
    if u > 0.0 {
        n.reverse();
        c.reverse();
        u = -u;
    }
    let (_, v) = psi(&n, &c, u.exp());
    if !(v < 0.0) {
        return None;
    }
    let error_of_psi = 8.0 * (rho + f64::EPSILON) + 4.0 * SLOPE_TOL;
    let du = (2.0 * FINAL_GAIN / -v).sqrt() + error_of_psi / -v;
    Some(lambda * (1.0 - lambda) * du).filter(|x| x.is_finite())
}
