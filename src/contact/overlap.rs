//! The yes/no overlap decision, with early exits.

use super::perram_wertheim::{condition_bound, contact_function, Newton, MAX_ITERATIONS};
use super::prepared::PreparedEllipsoid;
use super::scale::Prepared;
use super::sym::dot;
use super::{ContactError, Sym3, Vec3};

/// Safety factor on the rounding error of values computed in double precision: a
/// value `x` computed with `Q` of condition number `κ` is trusted to differ from 1 when
/// `|x − 1| > DECISION_SAFETY · ε · κ`. The backward error of forming `Q(λ)` and
/// factoring it is a few `ε` per entry (3×3, so `n ε` with `n = 3`), which perturbs a
/// quadratic form by at most `n ε κ` relative; 64 leaves a margin of 20 on that.
pub const DECISION_SAFETY: f64 = 64.0;

/// Whether two ellipsoids overlap (their interiors intersect): the sign of `μ² − 1`.
///
/// Cheaper than [`contact_function`]: it stops as soon as the answer is proved.
/// - Bounding spheres (radius `√tr Q`) apart: no overlap.
/// - The two ellipsoids meet on the segment between their centres (`μ ≤ √a√b/(√a+√b)`
///   with `a = rᵀQ1⁻¹r`, `b = rᵀQ2⁻¹r`; this contains the inscribed-sphere test):
///   overlap.
/// - During the Newton iteration, any `f(λ) > 1` proves separation, and the tangents
///   of the concave `f` at the ends of the bracket bound `μ²` from above, which can
///   prove overlap.
///
/// Each test allows for rounding (see [`DECISION_SAFETY`]); when the converged `μ²` is
/// too close to 1 for double precision, the accurate [`contact_function`] decides.
/// Touching ellipsoids (`μ² = 1`) do not overlap.
pub fn overlaps(r12: &Vec3, q1: &Sym3, q2: &Sym3) -> Result<bool, ContactError> {
    let p = Prepared::new(r12, q1, q2)?;
    let r = &p.r;
    let rr = dot(r, r);
    let bound = (p.q1[0] + p.q1[3] + p.q1[5]).sqrt() + (p.q2[0] + p.q2[3] + p.q2[5]).sqrt();
    if rr > bound * bound * (1.0 + DECISION_SAFETY * f64::EPSILON) {
        return Ok(false);
    }
    let cond = [condition_bound(&p.q1, &p.l1), condition_bound(&p.q2, &p.l2)];
    decide(&p, cond, r12, q1, q2)
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
    let p = match Prepared::with_factors(r12, e1, e2) {
        Some(p) => p,
        // Far outside the range where no rescaling is needed, or not finite.
        None => return overlaps(r12, e1.q(), e2.q()),
    };
    decide(&p, [e1.condition, e2.condition], r12, e1.q(), e2.q())
}

/// Relative margin on the bounding-sphere test: the largest semi-axis from an
/// eigen-solver is accurate to a few ulps, and `|r|²` rounds thrice; `16 ε` covers
/// both. (The inscribed-sphere test adds `DECISION_SAFETY · ε · cond`.)
const SPHERE_TEST_MARGIN: f64 = 16.0 * f64::EPSILON;

/// The proofs shared by both entry points, after the sphere tests.
#[inline]
fn decide(
    p: &Prepared,
    cond: [f64; 2],
    r12: &Vec3,
    q1: &Sym3,
    q2: &Sym3,
) -> Result<bool, ContactError> {
    let r = &p.r;
    if *r == [0.0; 3] {
        return Ok(true);
    }
    let (a, b) = (p.l1.quadratic_form(r), p.l2.quadratic_form(r));
    let (sa, sb) = (a.sqrt(), b.sqrt());
    let line = a * b / ((sa + sb) * (sa + sb));
    if line < 1.0 - DECISION_SAFETY * f64::EPSILON * cond[0].max(cond[1]) {
        return Ok(true);
    }
    // Tangent lines of f at the ends of the bracket: (λ, f, f′).
    let (mut lo, mut hi) = ((0.0, 0.0, a), (1.0, 0.0, -b));
    let mut newton = Newton::new(p, a, b);
    while newton.iterations < MAX_ITERATIONS {
        let (e, done) = newton.step()?;
        let margin = DECISION_SAFETY * f64::EPSILON * e.condition_bound();
        if e.f > 1.0 + margin {
            return Ok(false);
        }
        if e.g < 0.0 {
            lo = (e.lambda, e.f, -e.g);
        } else {
            hi = (e.lambda, e.f, -e.g);
        }
        if tangent_bound(lo, hi) < 1.0 - margin {
            return Ok(true);
        }
        if done {
            let mu2 = e.f + e.gain();
            if (mu2 - 1.0).abs() > margin {
                return Ok(mu2 < 1.0);
            }
            return Ok(contact_function(r12, q1, q2)?.mu2 < 1.0);
        }
    }
    Err(ContactError::NotConverged {
        iterations: newton.iterations,
    })
}

/// The height where the tangents `(λ, f, f′)` at the two ends of the bracket cross:
/// an upper bound of the maximum of a concave function.
fn tangent_bound(lo: (f64, f64, f64), hi: (f64, f64, f64)) -> f64 {
    let (l0, f0, s0) = lo;
    let (l1, f1, s1) = hi;
    let denom = s0 - s1;
    if !(denom > 0.0) {
        return f0.max(f1);
    }
    let x = (f1 - f0 + s0 * l0 - s1 * l1) / denom;
    f0 + s0 * (x - l0)
}
