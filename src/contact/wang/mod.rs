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

use super::scale::ldexp;
use super::scale::{rescale, validate};
use super::sym::{adjugate, det, pencil_coefficients, quadratic_form};
use super::{ContactError, Sym3, Vec3};
use negative_axis::max_on_negative_axis;

mod negative_axis;
#[cfg(test)]
mod tests;

/// Margin of the decision: separated iff `max P(s) > SEPARATION_REL_TOL · Σ_k |p_k| s^k
/// (1−s)^{4−k}` at the maximiser. The sum is the size of the terms of `P(s)`; the factor
/// `64 ε` covers Horner's `γ_8 ≈ 4ε` plus the rounding of the coefficients (a few dozen
/// operations each, amplified by the conditioning of `Q1`, `Q2`). Within the margin the
/// pair is within rounding of tangency and is reported as not separated.
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
///
/// Touching pairs, and pairs within [`SEPARATION_REL_TOL`] of touching, are reported as
/// not separated. The test is fragile near tangency; it is a cross-check of
/// [`super::rational::contact_function_rational`] (`μ² > 1`), not the production path.
/// Measured against it on random pairs (aspect ratios up to 100): no disagreement for
/// `|μ² − 1| ≥ 1e-12`, nor for centres up to 1e11 semi-axes apart, nor for size ratios
/// up to 1e6; at size ratio 1e8 the coefficients lose all their digits and about 5% of
/// the decisions are wrong.
///
/// ```
/// use grainpack::contact::wang::separated;
/// let unit = [1.0, 0.0, 0.0, 1.0, 0.0, 1.0];
/// assert!(separated(&[2.5, 0.0, 0.0], &unit, &unit).unwrap());
/// assert!(!separated(&[1.5, 0.0, 0.0], &unit, &unit).unwrap());
/// ```
///
/// # Errors
/// As [`characteristic_polynomial`].
pub fn separated(r12: &Vec3, q1: &Sym3, q2: &Sym3) -> Result<bool, ContactError> {
    validate(r12, q1, q2)?;
    let (r, q1, q2, _) = rescale(r12, q1, q2);
    let p = in_range(quartic(&r, &q1, &q2))?;
    let (value, size) = max_on_negative_axis(&p);
    Ok(value > SEPARATION_REL_TOL * size)
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
