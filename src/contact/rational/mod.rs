//! Contact function through its rational form, as in pw85 (theory, eqs. 15–20).
//!
//! With `Q(λ) = (1−λ)Q1 + λQ2`, the function `f(λ) = λ(1−λ) r12ᵀ Q(λ)⁻¹ r12` is
//! `λ(1−λ) a(λ) / b(λ)` with `a(λ) = r12ᵀ adj[Q(λ)] r12` (degree 2) and `b(λ) = det Q(λ)`
//! (degree 3). Then `f'(λ) = c(λ) / b(λ)²` where `c` has degree 6, `c(0) = a0 b0 > 0` and
//! `c(1) = −a(1) b(1) < 0`; since `f` is concave, `c` has a single root in `[0, 1]`: the
//! maximiser. `a` and `b` are first formed in the basis `(1−λ)^{n−k} λ^k`, where all their
//! coefficients are positive; the monomial coefficients of `c` (pw85, eq. 20) lose digits
//! to cancellation, so λ is less accurate than with the main solver, but μ² is evaluated
//! in the positive basis and keeps nearly full precision (it is second order in the error
//! of λ). The method is kept for error-versus-time comparisons.
//!
//! The root finding is in `root.rs`; the coefficients of `det` and `adj` of the pencil
//! come from `sym.rs`, shared with [`super::wang`].

use super::scale::{in_safe_range, ldexp, rescale, validate};
use super::sym::pencil_coefficients;
use super::{contact_function, Contact, ContactError, Stop, Sym3, Vec3, NEAR_END};
use root::maximiser;

mod root;
#[cfg(test)]
mod tests;

/// Iteration cap of the safeguarded Newton–bisection for the root of `c(λ)`. Pure bisection needs
/// `log2(1 / LAMBDA_TOL) ≈ 51` steps, so the cap is never met unless something is wrong.
pub const MAX_ITERATIONS: u32 = 100;

/// Absolute tolerance on `λ ∈ [0, 1]`: stop when the last step or the bracket is below
/// `tol = 4 ε`. The error in μ² is second order in the error in λ.
pub const LAMBDA_TOL: f64 = 4.0 * f64::EPSILON;

/// Relative error of Horner's rule for a degree-`n` polynomial at `x ≥ 0`:
/// `|fl(c(x)) − c(x)| ≤ γ_2n Σ|c_k| x^k` with `γ_2n ≈ n ε` (`u = ε/2`); taken as `2n ε`,
/// `n = 6`. A value `|c(λ)|` below this bound is a root as far as doubles can tell.
pub const HORNER_REL_ERR: f64 = 12.0 * f64::EPSILON;

/// The Perram–Wertheim contact function μ² from the rational form of `f(λ)` (pw85).
///
/// Finds the root of the degree-6 numerator `c(λ)` of `f'(λ)` in `[0, 1]` by Newton's
/// method on `f' = c/b²`, safeguarded by bisection (the bracket `c(lo) > 0 > c(hi)` is
/// kept), started at the exact maximiser for two spheres, `λ0 = √ρ2 / (√ρ1 + √ρ2)` with
/// `ρ1 = f'(0)`, `ρ2 = −f'(1)`. When `λ0 > ½` the mirrored pair is solved instead, so the
/// monomials are always used near `λ = 0`. Then `μ² = λ(1−λ) a(λ) / b(λ)`, with `a`, `b`
/// evaluated in the basis `(1−λ)^{n−k} λ^k` where all their terms are positive.
/// `r12 = 0` gives `μ² = 0`, `λ = ½` ([`Stop::Exact`]).
///
/// Accuracy (against 40-digit references, random pairs with aspect ratios up to 100):
/// `|Δμ²|/μ² ≤ 0.4 κε` and `|Δλ| ≤ 5 κε`, κ the condition number of `(1−λ)Q1 + λQ2`; the
/// pw85 worked example is exact to the last bit.
///
/// ```
/// use grainpack::contact::rational::contact_function_rational;
/// // Spheres of radii 1 and 2, centres 6 apart: μ² = (6 / 3)².
/// let c = contact_function_rational(&[6.0, 0.0, 0.0], &[1.0, 0.0, 0.0, 1.0, 0.0, 1.0],
///     &[4.0, 0.0, 0.0, 4.0, 0.0, 4.0]).unwrap();
/// assert!((c.mu2 - 4.0).abs() < 1e-13);
/// ```
///
/// Pairs the rational form cannot take get [`contact_function`]'s answer (a few ulps,
/// its [`Stop`] and iterations): a semi-definite form (a flat disc, a needle or a
/// point has `det Q = 0`, and `c(0) = 0`), a form thinner than
/// [`MIN_RELATIVE_PIVOT`](super::MIN_RELATIVE_PIVOT) resolves, or sizes so far apart
/// (a factor ~1e25 or more) that `det` and `adj` of the forms leave the double range,
/// or whose maximiser for two spheres lies within [`NEAR_END`] of an end (~1e7 apart).
///
/// # Errors
/// [`ContactError::NotFinite`] for bad input; [`contact_function`]'s errors where μ² is
/// not defined ([`ContactError::NotPositiveDefinite`] for indefinite forms,
/// [`ContactError::CommonNullDirection`]) or out of double range
/// ([`ContactError::Overflow`]).
pub fn contact_function_rational(
    r12: &Vec3,
    q1: &Sym3,
    q2: &Sym3,
) -> Result<Contact, ContactError> {
    match rational(r12, q1, q2) {
        // A semi-definite (or too thin) form, or sizes beyond what det and adj resolve:
        // the contact function answers, or says why μ² is not defined.
        Err(ContactError::NotPositiveDefinite { .. } | ContactError::Overflow { .. }) => {
            contact_function(r12, q1, q2)
        }
        other => other,
    }
}

fn rational(r12: &Vec3, q1: &Sym3, q2: &Sym3) -> Result<Contact, ContactError> {
    validate(r12, q1, q2)?;
    let (r, q1, q2, _) = rescale(r12, q1, q2);
    // f is homogeneous of degree 2 in r12: solve for r/2^k, then multiply μ² by 4^k.
    let r_max = r[0].abs().max(r[1].abs()).max(r[2].abs());
    if r_max == 0.0 {
        let (mu2, lambda, stop, iterations) = (0.0, 0.5, Stop::Exact, 0);
        return Ok(Contact {
            mu2,
            lambda,
            stop,
            iterations,
        });
    }
    let k = if in_safe_range(r_max) {
        0
    } else {
        r_max.log2().floor() as i32
    };
    let r_in = r;
    let r = r.map(|x| ldexp(x, -k));

    // a(λ) = Σ ha_k (1−λ)^{2−k} λ^k and b(λ) = Σ hb_k (1−λ)^{3−k} λ^k: every term is
    // positive (adjugates and mixed adjugates of positive-definite matrices are).
    let (ha, hb) = pencil_coefficients(&q1, &q2, &r);
    // det Qi and r12ᵀ adj(Qi) r12 lost to underflow or rounding: the sizes or aspect
    // ratios are beyond what the adjugate form resolves in double precision.
    if ![ha[0], ha[2], hb[0], hb[3]]
        .iter()
        .all(|x| *x >= f64::MIN_POSITIVE)
    {
        return Err(ContactError::Overflow {
            what: "det and adj of Q1, Q2 (beyond double range)",
        });
    }
    let (rho1, rho2) = (ha[0] / hb[0], ha[2] / hb[3]);
    let guess = rho2.sqrt() / (rho1.sqrt() + rho2.sqrt());
    if !(NEAR_END..=1.0 - NEAR_END).contains(&guess) {
        // Sizes ~1e7 or more apart: the monomials of c lose λ* near the end (measured
        // 6e-14 on a `huge_ratio` reference pair); the contact function's path for them.
        return contact_function(&r_in, &q1, &q2);
    }
    // Monomials lose accuracy far from λ = 0: past ½, solve the mirrored pair (Q1 and Q2
    // swapped, λ → 1 − λ), whose coefficients are the same ones in reverse order.
    let (lambda, stop, iterations) = if guess > 0.5 {
        let (ha_m, hb_m) = ([ha[2], ha[1], ha[0]], [hb[3], hb[2], hb[1], hb[0]]);
        let (lambda, stop, iterations) = maximiser(&ha_m, &hb_m, 1.0 - guess);
        (1.0 - lambda, stop, iterations)
    } else {
        maximiser(&ha, &hb, guess)
    };

    // μ² from the positive (Bernstein-like) form: no cancellation.
    let (l, u) = (lambda, 1.0 - lambda);
    let a_at = (ha[0] * u + ha[1] * l) * u + ha[2] * l * l;
    let b_at = ((hb[0] * u + hb[1] * l) * u + hb[2] * l * l) * u + hb[3] * l * l * l;
    let mu2 = ldexp(l * u * a_at / b_at, 2 * k);
    if !(b_at > 0.0 && mu2.is_finite()) {
        return Err(ContactError::Overflow {
            what: "rational form of the contact function",
        });
    }
    Ok(Contact {
        mu2,
        lambda,
        stop,
        iterations,
    })
}
