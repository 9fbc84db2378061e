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
//! This file also holds the input validation, the power-of-two rescaling and the
//! coefficients of `det` and `adj` of a matrix pencil that [`super::wang`] reuses.

use super::scale::{in_safe_range, ldexp, rescale, validate};
use super::sym::pencil_coefficients;
use super::{Contact, ContactError, Stop, Sym3, Vec3};

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
/// # Errors
/// [`ContactError::NotFinite`] or [`ContactError::NotPositiveDefinite`] for bad input;
/// [`ContactError::Overflow`] if μ² or an intermediate is out of double range (e.g. sizes
/// differing by a factor ~1e75, whose determinants underflow).
pub fn contact_function_rational(
    r12: &Vec3,
    q1: &Sym3,
    q2: &Sym3,
) -> Result<Contact, ContactError> {
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

/// The maximiser of `f` from the coefficients of `a`, `b` in the basis `(1−λ)^{n−k} λ^k`:
/// the root of `c(λ)` in `[0, 1]`, with why the search stopped and its iterations.
fn maximiser(ha: &[f64; 3], hb: &[f64; 4], guess: f64) -> (f64, Stop, u32) {
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

#[cfg(test)]
pub(super) mod tests {
    use super::*;
    use crate::contact::sym::{adjugate, det, quadratic_form};
    use nalgebra::{Matrix3, Rotation3, Vector3};
    use rand::rngs::StdRng;
    use rand::{Rng, SeedableRng};

    pub(crate) type Pair = (Vec3, Sym3, Sym3);

    pub(crate) fn sphere(radius: f64) -> Sym3 {
        let s = radius * radius;
        [s, 0.0, 0.0, s, 0.0, s]
    }

    pub(crate) fn random_rotation(rng: &mut StdRng) -> Rotation3<f64> {
        Rotation3::from_scaled_axis(Vector3::from_fn(|_, _| rng.random_range(-2.0..2.0)))
    }

    /// The pair turned by `rot`: `r → R r`, `Q → R Q Rᵀ`.
    pub(crate) fn rotate(rot: &Rotation3<f64>, (r, q1, q2): &Pair) -> Pair {
        let m = rot.matrix();
        let turn = |q: &Sym3| {
            let f = m * Matrix3::new(q[0], q[1], q[2], q[1], q[3], q[4], q[2], q[4], q[5]);
            let f = f * m.transpose();
            [
                f[(0, 0)],
                f[(0, 1)],
                f[(0, 2)],
                f[(1, 1)],
                f[(1, 2)],
                f[(2, 2)],
            ]
        };
        ((m * Vector3::from(*r)).into(), turn(q1), turn(q2))
    }

    /// Random pairs: semi-axes log-uniform in `[0.1, 10]`, random orientations, `r12` of
    /// random direction and length in `[0, 25]`, each with `κ = (a_max / a_min)²`, a bound
    /// on the condition number of every `(1−λ)Q1 + λQ2`.
    pub(crate) fn random_pairs(seed: u64, n: usize) -> Vec<(Pair, f64)> {
        let mut rng = StdRng::seed_from_u64(seed);
        let mut one = |_| {
            let a: [f64; 6] = std::array::from_fn(|_| 10f64.powf(rng.random_range(-1.0..1.0)));
            let r = [rng.random_range(0.0..25.0), 0.0, 0.0];
            let diag = |a: &[f64]| [a[0] * a[0], 0.0, 0.0, a[1] * a[1], 0.0, a[2] * a[2]];
            let (r, q1, _) = rotate(&random_rotation(&mut rng), &(r, diag(&a[..3]), sphere(1.0)));
            let q2 = rotate(&random_rotation(&mut rng), &(r, diag(&a[3..]), sphere(1.0))).1;
            let (lo, hi) = a
                .iter()
                .fold((f64::MAX, 0.0_f64), |(l, h), &x| (l.min(x), h.max(x)));
            ((r, q1, q2), (hi / lo).powi(2))
        };
        (0..n).map(&mut one).collect()
    }

    fn run((r, q1, q2): &Pair) -> Contact {
        let c = contact_function_rational(r, q1, q2).unwrap();
        assert_eq!(c.stop, Stop::Converged, "{c:?}");
        c
    }

    /// `f(λ)` from `adj` and `det` of `(1−λ)Q1 + λQ2` itself (no polynomial coefficients).
    fn f_direct((r, q1, q2): &Pair, lambda: f64) -> f64 {
        let q: Sym3 = std::array::from_fn(|i| (1.0 - lambda) * q1[i] + lambda * q2[i]);
        let adj = adjugate(&q);
        lambda * (1.0 - lambda) * quadratic_form(&adj, r) / det(&q, &adj)
    }

    // Accuracy model for random pairs: the adjugates and determinants in the coefficients
    // cancel in proportion to the condition number κ of Q(λ), and so does μ² itself under
    // a rounding of its input. Against 40-digit references (mpmath) on 400 random pairs
    // the errors were |Δμ²|/μ² ≤ 0.4 κε and |Δλ| ≤ 4.5 κε; the tolerances allow ~10×
    // that, counting both sides of each comparison.
    const MU2_TOL: f64 = 8.0 * f64::EPSILON;
    const LAMBDA_TOL_PER_KAPPA: f64 = 64.0 * f64::EPSILON;

    #[test]
    fn spheres_give_squared_ratio_of_distance_to_sum_of_radii() {
        let mut rng = StdRng::seed_from_u64(1);
        for _ in 0..1000 {
            let (r1, r2) = (rng.random_range(0.1..10.0), rng.random_range(0.1..10.0));
            let d = rng.random_range(0.01..3.0) * (r1 + r2);
            let pair = rotate(
                &random_rotation(&mut rng),
                &([d, 0.0, 0.0], sphere(r1), sphere(r2)),
            );
            let (c, expected) = (run(&pair), (d / (r1 + r2)).powi(2));
            // The start is the exact root for spheres, and μ² is a positive sum of a few
            // products: a few ulps (measured ≤ 1e-15 relative).
            assert!(
                (c.mu2 - expected).abs() <= 1e-14 * expected,
                "{} vs {expected}",
                c.mu2
            );
            assert!((c.lambda - r1 / (r1 + r2)).abs() <= 1e-14);
        }
    }

    #[test]
    fn worked_example_of_pw85_is_reproduced() {
        let r12 = [0.2 - (-0.5), -0.3 - 0.4, 0.4 - (-0.7)];
        let c = run(&(
            r12,
            [100.0, 0.0, 0.0, 100.0, 0.0, 0.01],
            [25.0, 0.0, 0.0, 0.25, 0.0, 0.25],
        ));
        // μ² and λ of these double inputs to 50 digits (mpmath), rounded to doubles. The
        // pair is well conditioned (λ far from the ends); measured error: 0 ulps. Allow 8ε.
        let (mu2, lambda) = (3.362_706_040_638_629, 0.166_858_955_340_554_8);
        assert!((c.mu2 - mu2).abs() <= 8.0 * f64::EPSILON * mu2, "{c:?}");
        assert!((c.lambda - lambda).abs() <= 8.0 * f64::EPSILON, "{c:?}");
        // pw85's published values are themselves 1.3e-14 (μ²) and 3.6e-14 (λ) off.
        assert!((c.mu2 - 3.362706040638343).abs() <= 1e-12 * mu2);
        assert!((c.lambda - 0.1668589553405904).abs() <= 1e-12);
    }

    #[test]
    fn swapping_the_ellipsoids_keeps_mu2_and_maps_lambda_to_one_minus_lambda() {
        for ((r, q1, q2), kappa) in random_pairs(2, 1000) {
            let (c, s) = (run(&(r, q1, q2)), run(&(r.map(|x| -x), q2, q1)));
            assert!(
                (c.mu2 - s.mu2).abs() <= MU2_TOL * kappa * c.mu2,
                "{c:?} {s:?}"
            );
            let lambda_tol = LAMBDA_TOL_PER_KAPPA * kappa;
            assert!(
                (c.lambda - (1.0 - s.lambda)).abs() <= lambda_tol,
                "{c:?} {s:?}"
            );
        }
    }

    #[test]
    fn contact_function_is_invariant_under_rotation() {
        let mut rng = StdRng::seed_from_u64(3);
        for (pair, kappa) in random_pairs(3, 1000) {
            let (c, d) = (run(&pair), run(&rotate(&random_rotation(&mut rng), &pair)));
            // The rotated inputs carry a few ε of rounding, which μ² amplifies by ≤ κ.
            assert!(
                (c.mu2 - d.mu2).abs() <= 2.0 * MU2_TOL * kappa * c.mu2,
                "{c:?} {d:?}"
            );
            assert!((c.lambda - d.lambda).abs() <= 2.0 * LAMBDA_TOL_PER_KAPPA * kappa);
        }
    }

    #[test]
    fn mu2_is_the_maximum_of_the_directly_evaluated_f() {
        for (pair, kappa) in random_pairs(4, 1000) {
            let c = run(&pair);
            let (at, tol) = (f_direct(&pair, c.lambda), MU2_TOL * kappa * c.mu2);
            assert!((c.mu2 - at).abs() <= tol, "{c:?} vs {at}");
            for i in 0..=100 {
                let other = f_direct(&pair, f64::from(i) / 100.0);
                assert!(other <= at + tol, "f({i}/100) = {other} > {at}");
            }
        }
    }

    #[test]
    fn coincident_centres_give_zero_exactly() {
        let c = contact_function_rational(&[0.0; 3], &sphere(1.0), &sphere(2.0)).unwrap();
        assert_eq!((c.mu2, c.stop, c.iterations), (0.0, Stop::Exact, 0));
    }

    #[test]
    fn extreme_scales_give_exactly_scaled_mu2() {
        let (r, q1) = ([0.7, -0.7, 1.1], [100.0, 1.0, 0.0, 100.0, 0.0, 0.01]);
        let q2 = [25.0, 0.0, 0.0, 0.25, 0.1, 0.25];
        let base = run(&(r, q1, q2)).mu2;
        for (kr, kq) in [
            (300, 0),
            (-300, 0),
            (0, 600),
            (0, -600),
            (250, 500),
            (-250, -500),
        ] {
            let (sr, sq) = (ldexp(1.0, kr), ldexp(1.0, kq));
            let c = run(&(r.map(|x| x * sr), q1.map(|x| x * sq), q2.map(|x| x * sq)));
            // Power-of-two scalings are exact, and μ² scales by sr²/sq exactly.
            assert_eq!(c.mu2, base * sr * sr / sq, "2^{kr}, 2^{kq}");
        }
    }

    #[test]
    fn bad_input_gives_typed_error_not_panic() {
        let (r, q) = ([1.0, 2.0, 3.0], sphere(1.0));
        match contact_function_rational(&[1.0, f64::NAN, 0.0], &q, &q) {
            Err(ContactError::NotFinite {
                what: "r12",
                index: 1,
                value,
            }) => assert!(value.is_nan()),
            other => panic!("{other:?}"),
        }
        assert_eq!(
            contact_function_rational(&r, &[1.0, 0.0, 0.0, f64::INFINITY, 0.0, 1.0], &q),
            Err(ContactError::NotFinite {
                what: "q1",
                index: 3,
                value: f64::INFINITY
            })
        );
        for (q1, q2, what, pivot) in [
            (q, q.map(|x| -x), "q2", 0),                     // negative definite
            ([1.0, 0.0, 0.0, 1.0, 0.0, 0.0], q, "q1", 2),    // singular
            ([1.0, 1.0, 0.0, 1.0, 0.0, 1.0], q, "q1", 1),    // singular 2×2 block
            ([1.0, 0.0, 0.0, -1.0, 0.0, 1.0], q, "q1", 1),   // indefinite
            (q, [1.0, 0.0, 0.0, 1.0, 0.0, 1e-300], "q2", 2), // singular to rounding
        ] {
            match contact_function_rational(&r, &q1, &q2) {
                Err(ContactError::NotPositiveDefinite {
                    what: w, pivot: p, ..
                }) => {
                    assert_eq!((w, p), (what, pivot));
                }
                other => panic!("{q1:?} {q2:?}: {other:?}"),
            }
        }
    }
}
