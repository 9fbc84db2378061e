//! Tests of the rational-form contact function.

use super::*;
use crate::contact::sym::{adjugate, det, quadratic_form};
use crate::contact::test_pairs::{random_pairs, random_rotation, rotate, sphere, RelativePair};
use rand::rngs::StdRng;
use rand::{Rng, SeedableRng};

fn run((r, q1, q2): &RelativePair) -> Contact {
    let c = contact_function_rational(r, q1, q2).unwrap();
    assert_eq!(c.stop, Stop::Converged, "{c:?}");
    c
}

/// `f(λ)` from `adj` and `det` of `(1−λ)Q1 + λQ2` itself (no polynomial coefficients).
fn f_direct((r, q1, q2): &RelativePair, lambda: f64) -> f64 {
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
        (q, q.map(|x| -x), "q2", 0),                   // negative definite
        ([1.0, 0.0, 0.0, -1.0, 0.0, 1.0], q, "q1", 1), // indefinite
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
    // Semi-definite forms (and one singular to rounding): the contact function's answer.
    for (q1, q2) in [
        ([1.0, 0.0, 0.0, 1.0, 0.0, 0.0], q),
        ([1.0, 1.0, 0.0, 1.0, 0.0, 1.0], q),
        (q, [1.0, 0.0, 0.0, 1.0, 0.0, 1e-300]),
    ] {
        assert_eq!(
            contact_function_rational(&r, &q1, &q2),
            crate::contact::contact_function(&r, &q1, &q2)
        );
    }
}
