//! The largest value of `det(λA − B)` on the negative axis, mapped onto `[0, 1]`.

use super::BISECTION_STEPS;

/// `(max P(s), size)` over `s ∈ [0, 1]`, where `P(s) = Σ_k p_k (−s)^k (1−s)^{4−k}` is
/// `(1−s)⁴ p(−s/(1−s))` and `size = Σ_k |p_k| s^k (1−s)^{4−k}` at the maximiser.
///
/// `P''` is quadratic: its roots cut `[0, 1]` into pieces on which `P'` is monotone, and
/// each piece where `P'` goes from `+` to `−` holds one local maximum, found by bisection.
pub(super) fn max_on_negative_axis(p: &[f64; 5]) -> (f64, f64) {
    // Monomial coefficients of P: P_m = (−1)^m Σ_{k ≤ m} C(4−k, m−k) p_k.
    const BINOMIAL: [[f64; 5]; 5] = [
        [1.0, 4.0, 6.0, 4.0, 1.0],
        [1.0, 3.0, 3.0, 1.0, 0.0],
        [1.0, 2.0, 1.0, 0.0, 0.0],
        [1.0, 1.0, 0.0, 0.0, 0.0],
        [1.0, 0.0, 0.0, 0.0, 0.0],
    ];
    let big_p: [f64; 5] = std::array::from_fn(|m| {
        let sum: f64 = (0..=m).map(|k| BINOMIAL[k][m - k] * p[k]).sum();
        if m % 2 == 0 {
            sum
        } else {
            -sum
        }
    });
    let slope =
        |s: f64| ((4.0 * big_p[4] * s + 3.0 * big_p[3]) * s + 2.0 * big_p[2]) * s + big_p[1];
    let eval = |s: f64| {
        let t = 1.0 - s;
        let terms = [
            t * t * t * t,
            -s * t * t * t,
            s * s * t * t,
            -s * s * s * t,
            s * s * s * s,
        ];
        let value: f64 = (0..5).map(|k| p[k] * terms[k]).sum();
        let size: f64 = (0..5).map(|k| (p[k] * terms[k]).abs()).sum();
        (value, size)
    };

    // Candidates: both ends, every cut, and the local maxima of P.
    let [x, y] = quadratic_roots(12.0 * big_p[4], 6.0 * big_p[3], 2.0 * big_p[2]);
    let inside = |s: f64| {
        if s.is_finite() {
            s.clamp(0.0, 1.0)
        } else {
            1.0
        }
    };
    let mut cuts = [0.0, inside(x), inside(y), 1.0];
    cuts.sort_by(f64::total_cmp);
    let mut best = eval(0.0);
    for piece in cuts.windows(2) {
        let (mut lo, mut hi) = (piece[0], piece[1]);
        let mut candidate = hi;
        if slope(lo) > 0.0 && slope(hi) < 0.0 {
            for _ in 0..BISECTION_STEPS {
                let mid = 0.5 * (lo + hi);
                if slope(mid) > 0.0 {
                    lo = mid;
                } else {
                    hi = mid;
                }
            }
            candidate = 0.5 * (lo + hi);
        }
        let value = eval(candidate);
        if value.0 > best.0 {
            best = value;
        }
    }
    best
}

/// The real roots of `a x² + b x + c` (NaN where there is none), by the cancellation-free
/// formula `q = −(b + sign(b)√Δ)/2`, roots `q/a` and `c/q`; degree drops are handled.
fn quadratic_roots(a: f64, b: f64, c: f64) -> [f64; 2] {
    if a == 0.0 {
        return [if b == 0.0 { f64::NAN } else { -c / b }, f64::NAN];
    }
    let disc = b * b - 4.0 * a * c;
    if disc < 0.0 {
        return [f64::NAN; 2];
    }
    let q = -0.5 * (b + disc.sqrt().copysign(b));
    if q == 0.0 {
        return [0.0, 0.0];
    }
    [q / a, c / q]
}
