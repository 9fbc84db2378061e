//! The yes/no overlap decision, with early exits.

use super::perram_wertheim::{condition_bound, contact_function, Newton, MAX_ITERATIONS};
use super::scale::Prepared;
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
    let rr = r[0] * r[0] + r[1] * r[1] + r[2] * r[2];
    let bound = (p.q1[0] + p.q1[3] + p.q1[5]).sqrt() + (p.q2[0] + p.q2[3] + p.q2[5]).sqrt();
    if rr > bound * bound * (1.0 + DECISION_SAFETY * f64::EPSILON) {
        return Ok(false);
    }
    if rr == 0.0 {
        return Ok(true);
    }
    let (a, b) = (p.l1.quadratic_form(r), p.l2.quadratic_form(r));
    let cond = condition_bound(&p.q1, &p.l1).max(condition_bound(&p.q2, &p.l2));
    let (sa, sb) = (a.sqrt(), b.sqrt());
    let line = a * b / ((sa + sb) * (sa + sb));
    if line < 1.0 - DECISION_SAFETY * f64::EPSILON * cond {
        return Ok(true);
    }
    // Tangent lines of f at the ends of the bracket: (λ, f, f′).
    let (mut lo, mut hi) = ((0.0, 0.0, a), (1.0, 0.0, -b));
    let mut newton = Newton::new(&p, a, b);
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
