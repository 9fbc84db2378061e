//! The root of the numerator of `f′` in `[0, 1]`, from the coefficients of `a` and `b`.

use super::{HORNER_REL_ERR, LAMBDA_TOL, MAX_ITERATIONS};
use crate::contact::Stop;

/// The maximiser of `f` from the coefficients of `a`, `b` in the basis `(1−λ)^{n−k} λ^k`:
/// the root of `c(λ)` in `[0, 1]`, with why the search stopped and its iterations.
pub(super) fn maximiser(ha: &[f64; 3], hb: &[f64; 4], guess: f64) -> (f64, Stop, u32) {
    let a = [ha[0], ha[1] - 2.0 * ha[0], ha[0] - ha[1] + ha[2]];
    let b = [
        hb[0],
        hb[1] - 3.0 * hb[0],
        3.0 * hb[0] - 2.0 * hb[1] + hb[2],
        hb[1] - hb[0] - hb[2] + hb[3],
    ];
    root_in_unit_interval(&derivative_numerator(&a, &b), &b, guess)
}

/// Coefficients of the numerator of `f'(λ)`, `c(λ) = Σ c_k λ^k` (pw85, eq. 20).
fn derivative_numerator(a: &[f64; 3], b: &[f64; 4]) -> [f64; 7] {
    [
        a[0] * b[0],
        2.0 * (a[1] - a[0]) * b[0],
        -a[0] * (b[1] + b[2]) + 3.0 * b[0] * (a[2] - a[1]) + a[1] * b[1],
        2.0 * (b[1] * (a[2] - a[1]) - a[0] * b[3]) - 4.0 * a[2] * b[0],
        (a[0] - a[1]) * b[3] + (a[2] - a[1]) * b[2] - 3.0 * a[2] * b[1],
        -2.0 * a[2] * b[2],
        -a[2] * b[3],
    ]
}

/// The root of `c` in `[0, 1]` (where `c(0) > 0 > c(1)`): Newton's method on
/// `f' = c / b²`, which is decreasing (`f` is concave) and so better behaved than `c`
/// itself, kept inside the bracket `[lo, hi]` by bisection when Newton leaves it or
/// stalls (as in Numerical Recipes' `rtsafe`). The Newton step is
/// `−f'/f'' = −c b / (c' b − 2 c b')`. Returns the root, why it stopped, the iterations.
fn root_in_unit_interval(c: &[f64; 7], b: &[f64; 4], guess: f64) -> (f64, Stop, u32) {
    let (mut lo, mut hi) = (0.0, 1.0);
    let mut x = if guess > 0.0 && guess < 1.0 {
        guess
    } else {
        0.5
    };
    let mut last_step = 1.0_f64;
    for iteration in 1..=MAX_ITERATIONS {
        let (value, slope, bound) = horner_with_derivative(c, x);
        if value.abs() <= bound {
            return (x, Stop::Converged, iteration);
        }
        if value > 0.0 {
            lo = x;
        } else {
            hi = x;
        }
        let b_x = ((b[3] * x + b[2]) * x + b[1]) * x + b[0];
        let db_x = (3.0 * b[3] * x + 2.0 * b[2]) * x + b[1];
        let step = -value * b_x / (slope * b_x - 2.0 * value * db_x);
        let newton = x + step;
        let next = if newton > lo && newton < hi && 2.0 * step.abs() <= last_step.abs() {
            newton
        } else {
            0.5 * (lo + hi)
        };
        last_step = next - x;
        x = next;
        if last_step.abs() <= LAMBDA_TOL || hi - lo <= LAMBDA_TOL {
            return (x, Stop::Converged, iteration);
        }
    }
    (x, Stop::MaxIterations, MAX_ITERATIONS)
}

/// `(c(x), c'(x), HORNER_REL_ERR · Σ|c_k| x^k)` by Horner's rule, for `x ≥ 0`.
fn horner_with_derivative(c: &[f64; 7], x: f64) -> (f64, f64, f64) {
    let (mut value, mut slope, mut size) = (c[6], 0.0, c[6].abs());
    for &ck in c[..6].iter().rev() {
        slope = slope * x + value;
        value = value * x + ck;
        size = size * x + ck.abs();
    }
    (value, slope, HORNER_REL_ERR * size)
}
