//! The predictor: Halley's method on `(ln f)′` in the Bernstein form of
//! [`crate::contact::bernstein`], bracketed on the sign of `f′`.

use super::{GAIN_TOL, MAX_ITERATIONS};
use crate::contact::bernstein::{Halley, Rational};
use crate::contact::{ContactError, Stop};

/// Halley's method on `φ′ = (ln f)′` from `t`, bracketed. Stops once the gain predicted
/// at an evaluation is below [`GAIN_TOL`], or below `switch` where the Halley step is
/// accepted (the step is taken, with no evaluation after it). Returns the last iterate,
/// why it stopped and the evaluations done.
#[inline(always)]
pub(super) fn predict(
    rational: &Rational,
    t: f64,
    switch: f64,
) -> Result<(f64, Stop, u32), ContactError> {
    predict_with(rational, t, switch, false)
}

/// [`predict`], where the Halley step from a gain below `switch` ends the iteration
/// only if, when `remainder`, the gain it leaves is estimated below [`GAIN_TOL`] too
/// (see [`step_leaves_little`]).
#[inline(always)]
pub(super) fn predict_with(
    rational: &Rational,
    mut t: f64,
    switch: f64,
    remainder: bool,
) -> Result<(f64, Stop, u32), ContactError> {
    let (mut lo, mut hi) = (0.0, 1.0);
    let mut iterations = 0;
    while iterations < MAX_ITERATIONS {
        iterations += 1;
        // Scaled terms where P is in range; term by term (P = 1) where it is not.
        let Halley { d1, d2, d3, p } = rational.halley(t).unwrap_or_else(|| {
            let [d1, d2, d3] = rational.log_derivatives(t);
            Halley { d1, d2, d3, p: 1.0 }
        });
        // One test for all three: a NaN or infinity in any makes the sum non-finite.
        if !(d1 + d2 + d3).is_finite() {
            return Err(ContactError::Overflow {
                what: "the derivatives of ln f(λ)",
            });
        }
        // Branches: selects and `&`, `|` made the fast path 2 ns longer (BENCHMARKS.md).
        if d1 > 0.0 {
            lo = t;
        } else if d1 < 0.0 {
            hi = t;
        }
        // φ is concave: φ″ < 0 unless rounding flattened it.
        let curvature = -d2;
        let halley_denominator = 2.0 * d2 * d2 - d1 * d3;
        let halley = t - 2.0 * d1 * d2 * p / halley_denominator;
        let halley_ok = halley_denominator > 0.0 && halley >= lo && halley <= hi;
        let next = if halley_ok {
            halley
        } else {
            let newton = t + d1 * p / curvature;
            if curvature > 0.0 && newton >= lo && newton <= hi {
                newton
            } else {
                0.5 * (lo + hi)
            }
        };
        // The Newton model's gain in φ, φ′²/(2|φ″|) = D1²/(2|D2|), is the relative gain
        // in f still to come.
        let gain2 = d1 * d1; // 2 |D2| × gain

        let converged = d1 == 0.0
            || (curvature > 0.0
                && (gain2 <= 2.0 * GAIN_TOL * curvature
                    || (halley_ok
                        && gain2 <= 2.0 * switch * curvature
                        && (!remainder || step_leaves_little(d1, d2, d3)))));
        let stalled = next == t || hi - lo <= f64::EPSILON * hi;
        t = next;
        if converged || stalled {
            return Ok((t, Stop::Converged, iterations));
        }
    }
    Ok((t, Stop::MaxIterations, iterations))
}

/// Whether a Halley step from a point of predicted gain `G ≤ HALLEY_FINAL_GAIN` leaves
/// a gain of at most [`GAIN_TOL`]. Halley's error after the step is about `C δ³`,
/// `δ = φ′/φ″` the Newton step and `C ≈ φ‴² / (4φ″²)` (the term in `φ⁗` left out is of
/// the same order and of opposite sign where the poles dominate, so this overestimates
/// there), which leaves the gain `|φ″| C² δ⁶ / 2 = x⁴ G / 16` with
/// `x = φ′φ‴ / φ″² = D1 D3 / D2²`. Away from the ends `x ~ δ`; within `1/ρ` of an end,
/// for sizes in ratio ρ, the poles of `1/s` and of `b′/b` nearly cancel in φ″,
/// `x ~ √(ρ G)`, and the step from `G = 1e-6` left up to 8e-8 before this test (the
/// `size_ratio` reference pairs). With `G ≤ HALLEY_FINAL_GAIN`, `|x| ≤ STEP_X_MAX`
/// suffices, and is tested as `|D1 D3| ≤ STEP_X_MAX · D2²`, without a division.
#[inline(always)]
fn step_leaves_little(d1: f64, d2: f64, d3: f64) -> bool {
    (d1 * d3).abs() <= STEP_X_MAX * (d2 * d2)
}

/// The bound on `x` of [`step_leaves_little`]: `x⁴ G / 16 ≤ 0.11⁴ · 1e-6 / 16 =
/// 9.15e-12 ≤ GAIN_TOL` for `G ≤ HALLEY_FINAL_GAIN`.
pub(super) const STEP_X_MAX: f64 = 0.11;
