//! The yes/no overlap decision, with early exits.
//!
//! Every proof bounds μ² from one side. With `f(λ) = λ(1−λ) rᵀQ(λ)⁻¹r ≤ μ²`:
//! - separation (`μ² > 1`): any `f(λ) > 1`, or a separating axis `n`,
//!   `n·r > √(nᵀQ1n) + √(nᵀQ2n)` (the ellipsoids' extents along `n` add up to less
//!   than the gap of the centres), tried along `r`, `s1 = Q1⁻¹r` and `s2 = Q2⁻¹r`;
//! - overlap (`μ² < 1`): a common point of the two ellipsoids scaled by `√U`, `U < 1`.
//!   Splitting `r = r1 + r2`, the point `c1 + r1 = c2 − r2` gives
//!   `μ² ≤ U = max(r1ᵀQ1⁻¹r1, r2ᵀQ2⁻¹r2)`. On the segment of the centres
//!   (`r1 ∝ r`) the best split gives `U = ab / (√a + √b)²` with `a = rᵀQ1⁻¹r`,
//!   `b = rᵀQ2⁻¹r`; with `s = Q(λ)⁻¹r`, the split `r1 = (1−λ)Q1 s`, `r2 = λQ2 s` gives
//!   `U = max((1−λ)² sᵀQ1s, λ² sᵀQ2s)`, equal to μ² at `λ = λ*`.
//!
//! A solve by cofactors at the two-sphere `λ₀ = √b / (√a + √b)` yields both `f(λ₀)`
//! and the second bound; with a second one it settles nearly all pairs that the cheaper
//! tests leave open. The rest go to a Newton iteration on LDLᵀ factors with the same
//! two bounds.

use super::direct::{condition_bound, Newton, Step};
use super::perram_wertheim::{contact_function, MAX_ITERATIONS};
use super::prepared::PreparedEllipsoid;
use super::scale::{needs_no_rescaling, offset_in_safe_range, Prepared};
use super::sym::{adjugate, det, dot, quadratic_form, sym_mul};
use super::{ContactError, Sym3, Vec3};
use crate::contact::ldl::Ldl;

/// Safety factor on the rounding error of values computed in double precision: a
/// value `x` computed with `Q` of condition number `κ` is trusted to differ from 1 when
/// `|x − 1| > DECISION_SAFETY · ε · κ`. The backward error of forming `Q(λ)` and
/// factoring it is a few `ε` per entry (3×3, so `n ε` with `n = 3`), which perturbs a
/// quadratic form by at most `n ε κ` relative; 64 leaves a margin of 20 on that.
pub const DECISION_SAFETY: f64 = 64.0;

/// Whether two ellipsoids overlap (their interiors intersect): the sign of `μ² − 1`.
///
/// Cheaper than [`contact_function`]: it stops as soon as the answer is proved (see
/// the module docs): bounding spheres (radius `√tr Q`) apart, a separating axis along
/// the line of the centres, a common point on that line, then one or more evaluations
/// of `f` and of the upper bound at its maximiser's estimate.
///
/// Each test allows for rounding (see [`DECISION_SAFETY`]); when the answer is too
/// close to call in double precision, the accurate [`contact_function`] decides.
/// Touching ellipsoids (`μ² = 1`) do not overlap.
pub fn overlaps(r12: &Vec3, q1: &Sym3, q2: &Sym3) -> Result<bool, ContactError> {
    if needs_no_rescaling(r12, q1, q2) {
        if let (Ok(l1), Ok(l2)) = (Ldl::factor(q1), Ldl::factor(q2)) {
            return overlaps_factored(r12, q1, q2, &l1, &l2, (r12, q1, q2));
        }
    }
    // Rescaled, or invalid input (the typed error comes from here).
    match Prepared::new(r12, q1, q2) {
        // r12 and the forms rescaled alike: μ² unchanged, and compared with 1.
        Ok(p) if p.mu2_exp == 0 => {
            overlaps_factored(&p.r, &p.q1, &p.q2, &p.l1, &p.l2, (r12, q1, q2))
        }
        // Rescaled apart (entries beyond 2^±200), μ² scaled by 2^mu2_exp: the proofs
        // here compare with 1 and misjudged such pairs; the contact function decides.
        Ok(_) => by_contact_function(r12, q1, q2),
        // Semi-definite forms and sizes too far apart to rescale together: the contact
        // function's robust path (its typed error where μ² is not defined).
        Err(ContactError::NotPositiveDefinite { .. } | ContactError::Overflow { .. }) => {
            by_contact_function(r12, q1, q2)
        }
        Err(e) => Err(e),
    }
}

/// The decision from [`contact_function`]'s μ² (a few ulps): for the pairs whose
/// arithmetic the proofs here cannot trust.
#[cold]
#[inline(never)]
fn by_contact_function(r12: &Vec3, q1: &Sym3, q2: &Sym3) -> Result<bool, ContactError> {
    Ok(contact_function(r12, q1, q2)?.mu2 < 1.0)
}

/// [`overlaps`] for a pair that needs no rescaling, factored: the bounding spheres
/// (radius `√tr Q`), then [`decide`].
#[inline(always)]
fn overlaps_factored(
    r: &Vec3,
    q1: &Sym3,
    q2: &Sym3,
    l1: &Ldl,
    l2: &Ldl,
    input: (&Vec3, &Sym3, &Sym3),
) -> Result<bool, ContactError> {
    let rr = dot(r, r);
    let bound = (q1[0] + q1[3] + q1[5]).sqrt() + (q2[0] + q2[3] + q2[5]).sqrt();
    if rr > bound * bound * (1.0 + DECISION_SAFETY * f64::EPSILON) {
        return Ok(false);
    }
    let cond = condition_bound(q1, l1).max(condition_bound(q2, l2));
    decide(r, q1, q2, l1, l2, cond, input.0, input.1, input.2)
}

/// [`overlaps`] for prepared shapes: exact bounding and inscribed spheres first, then
/// the same proofs with the stored factorisations.
///
/// ```
/// use grainpack::contact::{overlaps_prepared, Ellipsoid, PreparedEllipsoid};
/// let a = PreparedEllipsoid::new(&Ellipsoid::new([3.0, 1.0, 1.0], [1.0, 0.0, 0.0, 0.0]).unwrap()).unwrap();
/// assert!(overlaps_prepared(&[5.9, 0.0, 0.0], &a, &a).unwrap());
/// assert!(!overlaps_prepared(&[0.0, 2.1, 0.0], &a, &a).unwrap());
/// ```
#[inline]
pub fn overlaps_prepared(
    r12: &Vec3,
    e1: &PreparedEllipsoid,
    e2: &PreparedEllipsoid,
) -> Result<bool, ContactError> {
    let rr = dot(r12, r12);
    let outer = e1.bounding_radius() + e2.bounding_radius();
    if rr > outer * outer * (1.0 + SPHERE_TEST_MARGIN) && rr.is_finite() {
        return Ok(false);
    }
    // The smallest semi-axis from an eigen-solver errs by ε·cond relative.
    let inner = e1.inscribed_radius() + e2.inscribed_radius();
    let cond = e1.condition.max(e2.condition);
    if rr < inner * inner * (1.0 - SPHERE_TEST_MARGIN - DECISION_SAFETY * f64::EPSILON * cond) {
        return Ok(true);
    }
    let (q1, q2) = (e1.q(), e2.q());
    if !(e1.unscaled & e2.unscaled & offset_in_safe_range(r12)) {
        // Far outside the range where no rescaling is needed, or not finite.
        return overlaps(r12, q1, q2);
    }
    decide(r12, q1, q2, &e1.ldl, &e2.ldl, cond, r12, q1, q2)
}

/// Relative margin on the bounding-sphere test: the largest semi-axis from an
/// eigen-solver is accurate to a few ulps, and `|r|²` rounds thrice; `16 ε` covers
/// both. (The inscribed-sphere test adds `DECISION_SAFETY · ε · cond`.)
const SPHERE_TEST_MARGIN: f64 = 16.0 * f64::EPSILON;

/// The proofs shared by both entry points, after the sphere tests, on a pair `r`, `q1`,
/// `q2` (factored as `l1`, `l2`, condition numbers at most `cond`) that needs no
/// rescaling. `input` is the pair as given, for [`contact_function`] when nothing else
/// decides.
#[allow(clippy::too_many_arguments)]
#[inline(always)]
fn decide(
    r: &Vec3,
    q1: &Sym3,
    q2: &Sym3,
    l1: &Ldl,
    l2: &Ldl,
    cond: f64,
    r12: &Vec3,
    q1_in: &Sym3,
    q2_in: &Sym3,
) -> Result<bool, ContactError> {
    if *r == [0.0; 3] {
        return Ok(true);
    }
    // Quadratic forms of r lose up to `3 ε cond` relative (module docs of DECISION_SAFETY).
    let margin = DECISION_SAFETY * f64::EPSILON * cond;
    let (a, b) = (l1.quadratic_form(r), l2.quadratic_form(r));
    let (sa, sb) = (a.sqrt(), b.sqrt());
    if a * b < (1.0 - margin) * ((sa + sb) * (sa + sb)) {
        return Ok(true);
    }
    // Separating axes along r (|r|² > √(rᵀQ1r) + √(rᵀQ2r)), along s1 = Q1⁻¹r (s1·r =
    // s1ᵀQ1s1 = a, so a > √a + √(s1ᵀQ2s1)) and likewise along s2 = Q2⁻¹r; one branch.
    let (c1, c2) = (quadratic_form(q1, r), quadratic_form(q2, r));
    let (s1, s2) = (l1.solve(r), l2.solve(r));
    let (a2, b1) = (quadratic_form(q2, &s1), quadratic_form(q1, &s2));
    let apart = (dot(r, r) > (c1.sqrt() + c2.sqrt()) * (1.0 + margin))
        | (a > (sa + a2.sqrt()) * (1.0 + margin))
        | (b > (sb + b1.sqrt()) * (1.0 + margin));
    if apart {
        return Ok(false);
    }
    // s = Q(λ)⁻¹r by cofactors (no chain of divisions), which errs by up to ε cond(Q(λ))²
    // relative, and cond(Q(λ)) ≤ max(cond Q1, cond Q2) = cond (λ_max and λ_min of a convex
    // combination lie between the combinations of the ends').
    let margin = margin * cond;
    if margin < ADJUGATE_MAX_MARGIN {
        let mut lambda = sb / (sa + sb);
        for _ in 0..INLINE_EVALUATIONS {
            let m = 1.0 - lambda;
            let q: Sym3 = [
                m * q1[0] + lambda * q2[0],
                m * q1[1] + lambda * q2[1],
                m * q1[2] + lambda * q2[2],
                m * q1[3] + lambda * q2[3],
                m * q1[4] + lambda * q2[4],
                m * q1[5] + lambda * q2[5],
            ];
            let adj = adjugate(&q);
            let det = det(&q, &adj);
            if !(det > 0.0) {
                break;
            }
            let s = sym_mul(&adj, r).map(|x| x / det);
            let f = lambda * m * dot(r, &s);
            let (sq1s, sq2s) = (quadratic_form(q1, &s), quadratic_form(q2, &s));
            if f > 1.0 + margin {
                return Ok(false);
            }
            if (m * m * sq1s).max(lambda * lambda * sq2s) < 1.0 - margin {
                return Ok(true);
            }
            // At the maximiser (1−λ)² sᵀQ1s = λ² sᵀQ2s: solve that with s held fixed.
            let ratio = (sq1s / sq2s).sqrt();
            lambda = ratio / (1.0 + ratio);
        }
    }
    iterate(r12, q1_in, q2_in)
}

/// Largest relative margin `DECISION_SAFETY · ε · cond²` at which the cofactor
/// evaluations are tried: beyond `2^-10`, pairs within 0.1 % of touching would all be
/// left open, and the Newton iteration on LDLᵀ factors (margin `∝ cond`) is the
/// better use of the time.
const ADJUGATE_MAX_MARGIN: f64 = 1.0 / 1024.0;

/// Evaluations of `f` and of the upper bound done in line (at `λ₀`, then where
/// `(1−λ)² sᵀQ1s = λ² sᵀQ2s` for the last `s`) before the Newton iteration: on the
/// typical reference set the first settles 85 % of the pairs that reach it and the
/// second two thirds of the rest.
const INLINE_EVALUATIONS: usize = 2;

/// `f(λ)` and the upper bound `max((1−λ)² sᵀQ1s, λ² sᵀQ2s)` with `s = Q(λ)⁻¹r`, from
/// the factors of `Q(λ)`.
#[inline(always)]
fn bounds_at(lambda: f64, r: &Vec3, q1: &Sym3, q2: &Sym3, ldl: &Ldl) -> (f64, f64) {
    let m = 1.0 - lambda;
    let s = ldl.solve(r);
    let f = lambda * m * dot(r, &s);
    let upper = (m * m * quadratic_form(q1, &s)).max(lambda * lambda * quadratic_form(q2, &s));
    (f, upper)
}

/// The Newton iteration on `f` with both bounds at every step, for the pairs that the
/// first evaluation leaves open; [`contact_function`] for pairs too close to call.
#[cold]
#[inline(never)]
fn iterate(r12: &Vec3, q1: &Sym3, q2: &Sym3) -> Result<bool, ContactError> {
    let p = Prepared::new(r12, q1, q2)?;
    let (a, b) = (p.l1.quadratic_form(&p.r), p.l2.quadratic_form(&p.r));
    let cond = condition_bound(&p.q1, &p.l1).max(condition_bound(&p.q2, &p.l2));
    let mut newton = Newton::new(&p, a, b);
    while newton.iterations < MAX_ITERATIONS {
        let (e, step) = newton.step()?;
        let (f, upper) = bounds_at(e.lambda, &p.r, &p.q1, &p.q2, &e.ldl);
        let margin = DECISION_SAFETY * f64::EPSILON * e.condition_bound().max(cond);
        if f > 1.0 + margin {
            return Ok(false);
        }
        if upper < 1.0 - margin {
            return Ok(true);
        }
        match step {
            Step::Going => {}
            Step::Converged => {
                let mu2 = e.f + e.gain();
                if (mu2 - 1.0).abs() > margin {
                    return Ok(mu2 < 1.0);
                }
                return Ok(contact_function(r12, q1, q2)?.mu2 < 1.0);
            }
            // No estimate of μ² where λ cannot reach λ*: the accurate method decides.
            Step::Stuck => return Ok(contact_function(r12, q1, q2)?.mu2 < 1.0),
        }
    }
    Err(ContactError::NotConverged {
        iterations: newton.iterations,
    })
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::contact::direct::factor_at;
    use crate::contact::test_pairs::random_pairs;
    use crate::contact::Ellipsoid;
    use rand::rngs::StdRng;
    use rand::{Rng, SeedableRng};

    /// `f(λ) ≤ μ² ≤ U(λ)` at every λ, to rounding (`DECISION_SAFETY ε κ`).
    #[test]
    fn bounds_at_any_lambda_bracket_mu2() {
        for ((r, q1, q2), kappa) in random_pairs(41, 300) {
            let mu2 = contact_function(&r, &q1, &q2).unwrap().mu2;
            let tol = DECISION_SAFETY * f64::EPSILON * kappa * mu2;
            for lambda in [0.01, 0.2, 0.5, 0.8, 0.99] {
                let (_, ldl) = factor_at(lambda, &q1, &q2).unwrap();
                let (f, upper) = bounds_at(lambda, &r, &q1, &q2, &ldl);
                assert!(f <= mu2 + tol && upper >= mu2 - tol, "{f} {mu2} {upper}");
            }
        }
    }

    /// Pairs scaled to μ² between ½ and 2 (so that every stage gets used) are decided
    /// as the accurate contact function decides them, by both entry points.
    #[test]
    fn decisions_near_contact_agree_with_the_contact_function() {
        let mut rng = StdRng::seed_from_u64(42);
        let prepare = |q: &Sym3| {
            PreparedEllipsoid::new(&Ellipsoid::from_quadratic_form(*q).unwrap()).unwrap()
        };
        for ((r, q1, q2), _) in random_pairs(42, 3000) {
            let mu2 = contact_function(&r, &q1, &q2).unwrap().mu2;
            if mu2 == 0.0 {
                continue;
            }
            let target: f64 = 2f64.powf(rng.random_range(-1.0..1.0));
            let r = r.map(|x| x * (target / mu2).sqrt());
            let exact = contact_function(&r, &q1, &q2).unwrap().mu2;
            // Pairs within rounding of touching are the accurate method's business.
            if (exact - 1.0).abs() <= 1e-9 {
                continue;
            }
            assert_eq!(overlaps(&r, &q1, &q2).unwrap(), exact < 1.0, "μ² = {exact}");
            let (e1, e2) = (prepare(&q1), prepare(&q2));
            assert_eq!(
                overlaps_prepared(&r, &e1, &e2).unwrap(),
                exact < 1.0,
                "μ² = {exact}"
            );
        }
    }
}
