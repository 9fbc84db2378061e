//! The robust path's search (module [`robust`](super::robust), whose docs derive it):
//! `F = N/C` and `ψ = dφ/du` in `y = λ̂/(1−λ̂) ≤ 1`, and the root of ψ by Newton's
//! method in `u = ln y` with a bisection.

use super::MAX_ITERATIONS;
use crate::contact::Stop;

/// The search stops where the gain its quadratic model predicts in `u = ln y` is at
/// most `FINAL_GAIN = ε/8` relative (after taking that last step), or the step is at
/// the rounding of `u`. Tighter than the predictor's [`GAIN_TOL`](super::GAIN_TOL) on
/// purpose: the model in `u` holds over steps of order 1 only, so a gain of
/// `GAIN_TOL` may leave ~1e-14 (measured on the size ratios up to 1e150), and this
/// path is cold.
pub(super) const FINAL_GAIN: f64 = f64::EPSILON / 8.0;

/// Once `F` is settled, Newton goes on until its step in `u = ln y` is at most
/// `LOG_Y_STEP · (1 + |u|)`: λ* to about that relative precision. Where the sizes are
/// far apart `F` is flat to an ulp over a range of λ (measured: λ off by half on a
/// `huge_ratio` reference pair), and the contact point moves with λ.
const LOG_Y_STEP: f64 = 1e-10;

/// Smallest `y = λ̂/(1−λ̂)` the search considers: below it `F` differs from its limit
/// at 0 by far less than an ulp.
const SMALLEST_Y: f64 = f64::MIN_POSITIVE;

/// The terms `p_k y^{k−l}` (`l` the first index with `p_l > 0`) at `y = x/(1−x)`,
/// their sum, and the variance `Var_p` of the index they weigh: the sums of
/// [`robust`](super::robust)'s module docs divided by `(1−x)^4 y^l`, so that they
/// neither overflow nor underflow to 0 for `y ≤ 1`.
pub(super) fn moments(p: &[f64; 5], y: f64) -> ([f64; 5], f64, f64) {
    let l = p.iter().position(|&x| x > 0.0).unwrap_or(4);
    let mut w = [0.0; 5];
    let mut power = 1.0;
    for k in l..5 {
        w[k] = p[k] * power;
        power *= y;
    }
    let sum: f64 = w.iter().sum();
    let mean = (0..5).map(|k| k as f64 * w[k]).sum::<f64>() / sum;
    let var = (0..5)
        .map(|k| (k as f64 - mean).powi(2) * w[k])
        .sum::<f64>()
        / sum;
    (w, sum, var)
}

/// `ψ = E_N − E_C = dφ/du` and `V = Var_N − Var_C = d²φ/du²` at `y = e^u ≤ 1`
/// (`u = ln y` turns `y d/dy` into `d/du`). ψ is summed as
/// `Σ (i − j) wN_i wC_j / (ΣwN ΣwC)`, whose terms are as large as the cancellation
/// at the root makes necessary (each `E` is an index plus a part that may be far below
/// an ulp of it).
pub(super) fn psi(n: &[f64; 5], c: &[f64; 5], y: f64) -> (f64, f64) {
    let (wn, sn, vn) = moments(n, y);
    let (wc, sc, vc) = moments(c, y);
    let mut cross = 0.0;
    for (i, a) in wn.iter().enumerate() {
        for (j, b) in wc.iter().enumerate() {
            cross += (i as f64 - j as f64) * (a * b);
        }
    }
    (cross / sn / sc, vn - vc)
}

/// `F = N/C` at `y ≤ 1`.
fn ratio(n: &[f64; 5], c: &[f64; 5], y: f64) -> f64 {
    let first = |p: &[f64; 5]| p.iter().position(|&v| v > 0.0).unwrap_or(4) as i32;
    let (sn, sc) = (moments(n, y).1, moments(c, y).1);
    y.powi(first(n) - first(c)) * sn / sc
}

/// The root of ψ in `y ∈ (0, 1]` (ψ > 0 below it), and `F` there: Newton's method on
/// `ψ = dφ/du` in `u = ln y`, where `φ′ = ψ` and `φ″ = V` carry no cancellation,
/// from `ln start` if `start` is in range (from `y = ⅓` if not), kept in the bracket;
/// a bisection of `u` when the Newton point leaves it, `V ≥ 0` (φ not concave there),
/// or the bracket has not halved over two steps. Stops once the gain `ψ²/(2|V|)` is
/// at most [`FINAL_GAIN`] and the Newton step of `u` below [`LOG_Y_STEP`] (after
/// taking that last step), or the step is at rounding level, or the bracket a few ulps
/// wide; [`Stop::MaxIterations`] if [`MAX_ITERATIONS`] pass first, even with `F`
/// settled (λ is not). Returns `F`, `y`, why it stopped and the evaluations.
pub(super) fn root(n: &[f64; 5], c: &[f64; 5], start: f64) -> (f64, f64, Stop, u32) {
    let (mut lo, mut hi) = (SMALLEST_Y.ln(), 0.0f64);
    let mut u = if start > SMALLEST_Y && start < 1.0 {
        start.ln()
    } else {
        (1.0f64 / 3.0).ln()
    };
    let (mut halved_at, mut since) = (hi - lo, 0);
    for iterations in 1..=MAX_ITERATIONS {
        let y = u.exp();
        let (p, v) = psi(n, c, y);
        if p > 0.0 {
            lo = u;
        } else if p < 0.0 {
            hi = u;
        }
        let newton = if v < 0.0 { u - p / v } else { f64::NAN };
        let inside = newton > lo && newton < hi;
        let step_at_rounding = (newton - u).abs() <= 4.0 * f64::EPSILON * (1.0 + u.abs());
        if p == 0.0 || (v < 0.0 && (p * p <= 2.0 * FINAL_GAIN * -v || step_at_rounding)) {
            // The last step, unless it leaves the bracket (where F is flat to far below
            // an ulp and the step is all rounding). F is settled; λ is too once the
            // step is below LOG_Y_STEP (F may be flat over a wide range of y, and the
            // contact point moves with λ), else Newton goes on: out of iterations
            // before λ settles, the answer is not Converged (below the loop).
            let last = if inside { newton.exp() } else { y };
            let settled = (newton - u).abs() <= LOG_Y_STEP * (1.0 + u.abs());
            if !inside || settled || step_at_rounding || p == 0.0 {
                return (ratio(n, c, last), last, Stop::Converged, iterations);
            }
            u = newton;
            continue;
        }
        if hi - lo <= 4.0 * f64::EPSILON * (1.0 + u.abs()) {
            return (ratio(n, c, y), y, Stop::Converged, iterations);
        }
        let width = hi - lo;
        if width <= 0.5 * halved_at {
            (halved_at, since) = (width, 0);
        } else {
            since += 1;
        }
        u = if inside && since < 2 {
            newton
        } else {
            (halved_at, since) = (width, 0);
            0.5 * (lo + hi)
        };
    }
    let y = u.exp();
    (ratio(n, c, y), y, Stop::MaxIterations, MAX_ITERATIONS)
}
