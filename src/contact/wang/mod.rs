//! Wang–Wang–Kim (2001) algebraic separation test, an independent cross-check.
//!
//! W. Wang, J. Wang, M.-S. Kim, "An algebraic condition for the separation of two
//! ellipsoids", Computer Aided Geometric Design 18 (2001) 531–539.
//!
//! Each ellipsoid is the quadric `XᵀAX ≤ 0`, `X = (x, y, z, 1)`, with the canonical matrix
//! `A = [[Q⁻¹, −Q⁻¹c], [−cᵀQ⁻¹, cᵀQ⁻¹c − 1]]` (so `XᵀAX = (x−c)ᵀQ⁻¹(x−c) − 1`), built
//! relative to the first centre: `c1 = 0`, `c2 = r12`.
//!
//! **Sign convention, checked on spheres** (tests below): with both interiors negative,
//! `p(λ) = det(λA − B)` always has two positive roots (for spheres a double root at
//! `r1²/r2²`), and the ellipsoids are separated iff `p` has two distinct *negative* roots,
//! touch iff it has a negative double root, and overlap otherwise. The paper's statement
//! "two distinct positive roots" is for `det(λA + B)`, whose roots are those of `p` negated.
//!
//! The decision does not locate the roots. `p(0) = det B < 0` and the leading coefficient
//! `det A < 0` (both matrices have one negative eigenvalue), and `p` has at most two
//! negative roots (the paper's theorem: at least two are positive; checked in the tests),
//! so it has two distinct negative roots iff `p(λ) > 0` for some `λ < 0`.
//! The negative axis is mapped onto `s ∈ (0, 1)` by `λ = −s/(1−s)`, and the maximum of
//! `P(s) = (1−s)⁴ p(−s/(1−s))` is taken over the roots of the cubic `P'` in `[0, 1]`.
//!
//! The coefficients are rounded, at times badly (inverses of thin forms, sizes far
//! apart): the decision is taken only where `P` minus a bound on its error (module
//! `trust`) is positive somewhere, or `P` plus it negative everywhere; otherwise, and
//! for semi-definite forms, the contact function decides (see [`separated`]).

use super::scale::{exponent, ldexp, pow2};
use super::scale::{rescale, validate};
use super::sym::{adjugate, det, pencil_coefficients, quadratic_form};
use super::{contact_function, ContactError, Stop, Sym3, Vec3};
pub use ellipses::{characteristic_polynomial_2d, separated_2d, CUBIC_ROUNDING};
use negative_axis::max_on_negative_axis;

mod ellipses;
mod negative_axis;
#[cfg(test)]
mod tests;
mod trust;

/// Margin of the evaluation: `max P(s)` counts as above (below) zero only beyond
/// `SEPARATION_REL_TOL · Σ_k |p_k| s^k (1−s)^{4−k}` at the maximiser, on top of the
/// error bound of module `trust`: Horner's `γ_8 ≈ 4ε` and the location of the maximum
/// to `2⁻⁴⁰`, with a margin of 16.
pub const SEPARATION_REL_TOL: f64 = 64.0 * f64::EPSILON;

/// Bisection steps used to locate each maximiser of `P` on `[0, 1]`: to `2⁻⁴⁰ ≈ 1e-12`.
/// `P` is flat there, so its value is off by `~|P''| 1e-24`, far below the margin
/// [`SEPARATION_REL_TOL`].
pub const BISECTION_STEPS: u32 = 40;

/// Coefficients of `det(λA − B)`, lowest degree first, for the canonical matrices `A`, `B`
/// of the two ellipsoids with `c1 = 0`, `c2 = r12` (see the module docs).
///
/// Writing `Pi = Qi⁻¹`, `u = P2 r12`, `s(λ) = 1 − r12ᵀu − λ` and `X(λ) = λP1 − P2`,
/// `λA − B = [[X, u], [uᵀ, s]]`, whose determinant is `s det X − uᵀ adj(X) u`.
///
/// Accuracy, inherent to the 4×4 form: the inverses and the translated quadric's constant
/// term `r12ᵀP2 r12 − 1` leave each coefficient with an absolute error of about
/// `κ (1 + ρ) ε · max_k |p_k|` (κ: condition number of the `Qi`, `ρ = max_i r12ᵀQi⁻¹r12`).
///
/// # Errors
/// [`ContactError::NotFinite`] or [`ContactError::NotPositiveDefinite`] for bad input;
/// [`ContactError::Overflow`] if a coefficient is out of double range.
pub fn characteristic_polynomial(
    r12: &Vec3,
    q1: &Sym3,
    q2: &Sym3,
) -> Result<[f64; 5], ContactError> {
    validate(r12, q1, q2)?;
    // Computed at a safe scale σ = 2^j: the scaled matrices are A' = DAD and B' = DBD with
    // D = diag(σ, σ, σ, 1), so det(λA' − B') = σ⁶ det(λA − B).
    let (r, q1, q2, j) = rescale(r12, q1, q2);
    let scaled = in_range(quartic(&r, &q1, &q2))?;
    let p = in_range(scaled.map(|c| ldexp(c, -6 * j)))?;
    if p.iter()
        .zip(&scaled)
        .any(|(c, s)| *s != 0.0 && c.abs() < f64::MIN_POSITIVE)
    {
        return Err(ContactError::Overflow { what: OUT_OF_RANGE }); // underflow
    }
    Ok(p)
}

/// Whether the two ellipsoids are separated, by Wang–Wang–Kim's condition: `det(λA − B)`
/// has two distinct negative real roots (two distinct positive roots of `det(λA + B)`).
/// Touching pairs are not separated.
///
/// The condition decides only where the rounding of the coefficients cannot have
/// turned it: the computed `P(s)` minus a bound on its error (module `trust`: first
/// order in `ε` with a margin of two, growing with the condition numbers of `Q1`, `Q2`,
/// with `r12ᵀQ2⁻¹r12` and with the ratio of the sizes) is above 0 at the maximiser
/// found, or `P(s)` plus the bound is below 0 at every maximum the search of `[0, 1]`
/// finds. Pairs within that bound of touching, coefficients beyond double range, and
/// semi-definite forms (a flat disc, a needle or a point has no canonical matrix
/// `Q⁻¹`) are decided by the sign of [`contact_function`]`'s μ² − 1`
/// ([`Decided::ContactFunction`], see [`separation`]), never by a condition within
/// its rounding. Measured (`tests/contact_degenerate.rs`): the condition
/// decides all 1000 pairs of the typical reference set itself and 1295 of the 1745
/// extreme ones (it hands over most near-tangent pairs, aspect ratios near 1e4 and
/// nearly identical thin pairs), and 33 of the 430 degenerate ones (the rest are
/// semi-definite, or sizes ~1e7 or more apart).
///
/// ```
/// use grainpack::contact::wang::separated;
/// let unit = [1.0, 0.0, 0.0, 1.0, 0.0, 1.0];
/// assert!(separated(&[2.5, 0.0, 0.0], &unit, &unit).unwrap());
/// assert!(!separated(&[1.5, 0.0, 0.0], &unit, &unit).unwrap());
/// // A flat disc of radius 1 (Q = diag(1, 1, 0)) above a unit ball: the contact function.
/// let disc = [1.0, 0.0, 0.0, 1.0, 0.0, 0.0];
/// assert!(separated(&[0.0, 0.0, 1.5], &unit, &disc).unwrap());
/// ```
///
/// # Errors
/// [`ContactError::NotFinite`]; where μ² is not defined, [`contact_function`]'s
/// errors ([`ContactError::NotPositiveDefinite`] for indefinite forms,
/// [`ContactError::CommonNullDirection`] for two forms singular along one direction).
pub fn separated(r12: &Vec3, q1: &Sym3, q2: &Sym3) -> Result<bool, ContactError> {
    separation(r12, q1, q2).map(|(apart, _)| apart)
}

/// What decided [`separated`].
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Decided {
    /// Wang–Wang–Kim's condition, with the rounding of its coefficients bounded.
    Algebraic,
    /// The sign of `μ² − 1` from [`contact_function`]: the condition was within its
    /// error bound of touching, its coefficients out of range, or a form semi-definite.
    ContactFunction,
}

/// [`separated`], and what decided it.
///
/// # Errors
/// As [`separated`].
pub fn separation(r12: &Vec3, q1: &Sym3, q2: &Sym3) -> Result<(bool, Decided), ContactError> {
    match validate(r12, q1, q2) {
        Ok(()) => {}
        Err(ContactError::NotPositiveDefinite { .. }) => return by_contact_function(r12, q1, q2),
        Err(e) => return Err(e),
    }
    let (r, q1s, q2s, _) = rescale(r12, q1, q2);
    let p = quartic(&r, &q1s, &q2s);
    let bound = trust::error_bound(&r, &q1s, &q2s);
    // λ → σλ with σ ≈ the ratio of the sizes, a power of two, brings the negative
    // roots (−r1/r2 for touching spheres) to order 1, where the search of
    // max_on_negative_axis resolves them: p_k σ^k, and the bound likewise.
    let sigma = pow2(
        (exponent(q1s[0].max(q1s[3]).max(q1s[5])) - exponent(q2s[0].max(q2s[3]).max(q2s[5])))
            .div_euclid(2),
    );
    let balance = |c: [f64; 5]| -> [f64; 5] {
        let mut power = 1.0;
        c.map(|x| {
            let y = x * power;
            power *= sigma;
            y
        })
    };
    let p = balance(p);
    let bound = bound.map(balance);
    if let (Ok(p), Some(e)) = (in_range(p), bound) {
        // In the basis s^k (1−s)^{4−k} the terms of P carry the sign (−1)^k.
        let shifted = |sign: f64| -> [f64; 5] {
            std::array::from_fn(|k| p[k] + sign * if k % 2 == 0 { e[k] } else { -e[k] })
        };
        let (low, size) = max_on_negative_axis(&shifted(-1.0));
        if low > SEPARATION_REL_TOL * size {
            return Ok((true, Decided::Algebraic));
        }
        let (high, size) = max_on_negative_axis(&shifted(1.0));
        if high < -SEPARATION_REL_TOL * size {
            return Ok((false, Decided::Algebraic));
        }
    }
    by_contact_function(r12, q1, q2)
}

/// The decision from [`contact_function`]'s μ² (a few ulps).
#[cold]
fn by_contact_function(r12: &Vec3, q1: &Sym3, q2: &Sym3) -> Result<(bool, Decided), ContactError> {
    let c = contact_function(r12, q1, q2)?;
    if c.stop == Stop::MaxIterations {
        return Err(ContactError::NotConverged {
            iterations: c.iterations,
        });
    }
    Ok((c.mu2 > 1.0, Decided::ContactFunction))
}

const OUT_OF_RANGE: &str = "coefficients of det(λA − B) (beyond double range)";

fn in_range(p: [f64; 5]) -> Result<[f64; 5], ContactError> {
    match p.iter().all(|c| c.is_finite()) {
        true => Ok(p),
        false => Err(ContactError::Overflow { what: OUT_OF_RANGE }),
    }
}

/// `det(λA − B)` for validated input (see [`characteristic_polynomial`]).
fn quartic(r: &Vec3, q1: &Sym3, q2: &Sym3) -> [f64; 5] {
    let inverse = |q: &Sym3| {
        let adj = adjugate(q);
        let d = det(q, &adj);
        adj.map(|x| x / d)
    };
    let (p1, p2) = (inverse(q1), inverse(q2));
    let u = [
        p2[0] * r[0] + p2[1] * r[1] + p2[2] * r[2],
        p2[1] * r[0] + p2[3] * r[1] + p2[4] * r[2],
        p2[2] * r[0] + p2[4] * r[1] + p2[5] * r[2],
    ];
    let s0 = 1.0 - quadratic_form(&p2, r);
    let (a, b) = pencil_coefficients(&p2.map(|x| -x), &p1, &u);
    // (s0 − λ)(b0 + b1λ + b2λ² + b3λ³) − (a0 + a1λ + a2λ²)
    [
        s0 * b[0] - a[0],
        s0 * b[1] - b[0] - a[1],
        s0 * b[2] - b[1] - a[2],
        s0 * b[3] - b[2],
        -b[3],
    ]
}
