//! The semi-definite, thin and far-apart pairs of [`super::robust`], against closed
//! forms and a direct maximisation. The rotated cases are in the reference data
//! (`tests/contact_reference.rs`).

use super::*;

/// A closed form evaluated in doubles rounds two or three times, the method a few
/// more: 4 ε relative.
const CLOSED_FORM_TOL: f64 = 4.0 * f64::EPSILON;

/// [`direct`] sums three positive terms in doubles (3 ε) at a λ within 1e-40 of the
/// maximiser (f is flat there to second order): 8 ε relative covers both methods.
const DIRECT_TOL: f64 = 8.0 * f64::EPSILON;

/// f is flat at its maximum: stopping at a gain of [`GAIN_TOL`] leaves λ off by
/// about `√GAIN_TOL ≈ 3e-6` relative to its distance from the nearer end (far less
/// after the last step, but nothing promises more).
const LAMBDA_TOL: f64 = 1e-5;

/// μ² for diagonal forms `diag(d1)`, `diag(d2)` (either may be singular) by a golden
/// section search of `f(λ) = λ(1−λ) Σ r_i² / ((1−λ) d1_i + λ d2_i)` on `(0, 1)`: f is
/// concave, and 200 sections leave a bracket of 1e-42.
fn direct(r: &Vec3, d1: [f64; 3], d2: [f64; 3]) -> f64 {
    let f = |l: f64| {
        (0..3)
            .map(|i| l * (1.0 - l) * r[i] * r[i] / ((1.0 - l) * d1[i] + l * d2[i]))
            .sum::<f64>()
    };
    let g = (5f64.sqrt() - 1.0) / 2.0;
    let (mut a, mut b) = (0.0f64, 1.0f64);
    for _ in 0..200 {
        let (x, y) = (b - g * (b - a), a + g * (b - a));
        if f(x) < f(y) {
            a = x;
        } else {
            b = y;
        }
    }
    f(0.5 * (a + b))
}

fn diagonal(d: [f64; 3]) -> Sym3 {
    [d[0], 0.0, 0.0, d[1], 0.0, d[2]]
}

/// Both methods, and both in lanes, give `want` within `tol` (relative).
fn assert_all_close(r: &Vec3, q1: &Sym3, q2: &Sym3, want: f64, tol: f64) {
    let batch = vec![(*r, *q1, *q2); 16];
    let methods = [contact_function, contact_function_fast];
    for (k, method) in methods.iter().enumerate() {
        let c = method(r, q1, q2).unwrap();
        assert!(
            (c.mu2 - want).abs() <= tol * want,
            "method {k}: {} vs {want} ({r:?} {q1:?} {q2:?})",
            c.mu2
        );
        assert_ne!(c.stop, Stop::MaxIterations);
        let lanes = [contact_functions(&batch), contact_functions_fast(&batch)];
        assert!(
            lanes[k].iter().all(|l| l.as_ref() == Ok(&c)),
            "lanes, method {k}"
        );
    }
}

#[test]
fn a_flat_disc_against_a_ball_is_answered_to_a_few_ulps() {
    let disc = [1.0, 1.0, 0.0];
    for radius2 in [1.0, 0.3, 1e-6] {
        let ball = [radius2; 3];
        for r in [
            [0.5, 0.2, 2.0],
            [3.0, -1.0, 0.5],
            [0.1, 0.0, 0.0],
            [1e-3, 0.0, 7.0],
        ] {
            let want = direct(&r, disc, ball);
            assert_all_close(&r, &diagonal(disc), &diagonal(ball), want, DIRECT_TOL);
            // The same pair the other way round.
            assert_all_close(&r, &diagonal(ball), &diagonal(disc), want, DIRECT_TOL);
        }
    }
    // Above the disc's centre: the maximum is the limit at λ = 0, μ² = z² exactly.
    let c = contact_function(
        &[0.0, 0.0, 2.0],
        &diagonal([1.0, 1.0, 0.0]),
        &diagonal([1.0; 3]),
    );
    let c = c.unwrap();
    assert_eq!((c.mu2, c.lambda, c.stop), (4.0, 0.0, Stop::Exact));
}

#[test]
fn needles_and_points_against_a_ball() {
    let ball = [4.0, 1.0, 0.25];
    let r = [1.5, -0.7, 0.4];
    // A point: μ² = rᵀQ2⁻¹r, at λ = 0.
    let want: f64 = (0..3).map(|i| r[i] * r[i] / ball[i]).sum();
    assert_all_close(&r, &[0.0; 6], &diagonal(ball), want, CLOSED_FORM_TOL);
    assert_all_close(&r, &diagonal(ball), &[0.0; 6], want, CLOSED_FORM_TOL);
    // Needles of half-length 3 along each axis.
    for k in 0..3 {
        let mut needle = [0.0; 3];
        needle[k] = 9.0;
        let want = direct(&r, needle, ball);
        assert_all_close(&r, &diagonal(needle), &diagonal(ball), want, DIRECT_TOL);
    }
}

/// A needle through a disc's plane, and two discs at right angles: both singular, but
/// in no common direction.
#[test]
fn crossed_singular_forms_are_answered() {
    let r = [0.6, -0.3, 1.2];
    for (d1, d2) in [
        ([0.0, 0.0, 4.0], [1.0, 2.0, 0.0]),
        ([1.0, 0.0, 3.0], [1.0, 2.0, 0.0]),
    ] {
        let want = direct(&r, d1, d2);
        assert_all_close(&r, &diagonal(d1), &diagonal(d2), want, DIRECT_TOL);
    }
}

#[test]
fn forms_singular_in_a_common_direction_are_a_typed_error() {
    let r = [0.6, -0.3, 1.2];
    let disc = diagonal([1.0, 2.0, 0.0]);
    for (q1, q2) in [
        (disc, diagonal([3.0, 0.5, 0.0])), // coplanar discs
        (diagonal([1.0, 0.0, 0.0]), diagonal([0.0, 1.0, 0.0])), // two needles
        ([0.0; 6], disc),                  // a point and a disc
        ([0.0; 6], [0.0; 6]),              // two points
    ] {
        for method in [contact_function, contact_function_fast] {
            let err = method(&r, &q1, &q2).unwrap_err();
            assert_eq!(err, ContactError::CommonNullDirection);
            assert!(err.to_string().contains("not defined"), "{err}");
        }
    }
}

#[test]
fn indefinite_forms_are_still_errors_naming_the_pivot() {
    let ball = diagonal([1.0; 3]);
    let r = [1.0, 0.5, 0.25];
    for (bad, pivot) in [
        ([-1.0, 0.0, 0.0, -1.0, 0.0, -1.0], 0),
        ([1.0, 2.0, 0.0, 1.0, 0.0, 1.0], 1),
        ([1.0, 0.0, 0.0, 1.0, 0.0, -1e-6], 2),
        ([0.0, 1.0, 0.0, 0.0, 0.0, 0.0], 0),
    ] {
        let err = contact_function(&r, &ball, &bad).unwrap_err();
        assert!(
            matches!(err, ContactError::NotPositiveDefinite { what: "q2", pivot: p, .. } if p == pivot),
            "{bad:?}: {err}"
        );
    }
}

/// Two spheres of radii 1 and ρ at distance d: `μ² = (d / (1 + ρ))²`, `λ = 1/(1 + ρ)`,
/// down to ρ = 1e-160 (`Q = 1e-320`, subnormal).
#[test]
fn spheres_of_any_size_ratio() {
    for rho in [1e-4, 1e-8, 1e-12, 1e-20, 1e-50, 1e-100, 1e-150, 1e-160] {
        for d in [1.0, 3.7] {
            let (big, small) = (diagonal([1.0; 3]), diagonal([rho * rho; 3]));
            let r = [0.0, d, 0.0];
            let want = (d / (1.0 + rho)).powi(2);
            assert_all_close(&r, &big, &small, want, CLOSED_FORM_TOL);
            assert_all_close(&r, &small, &big, want, CLOSED_FORM_TOL);
            let c = contact_function(&r, &small, &big).unwrap();
            let lambda = rho / (1.0 + rho);
            assert!(
                (c.lambda - lambda).abs() <= LAMBDA_TOL * lambda,
                "{c:?} vs {lambda}"
            );
        }
    }
}

/// Triaxial forms 1e-100 apart in size, and thin forms (pivots between
/// [`SINGULAR_PIVOT`] and [`MIN_RELATIVE_PIVOT`](crate::contact::MIN_RELATIVE_PIVOT)).
#[test]
fn far_apart_and_very_thin_forms_against_the_direct_maximum() {
    let r = [0.6, -0.3, 1.2];
    for (d1, d2) in [
        ([1.0, 4.0, 9.0], [2e-100, 1e-100, 3e-100]),
        ([1.0, 4.0, 9.0], [2e-250, 1e-260, 3e-255]),
        ([1.0, 1.0, 1e-13], [0.5, 2.0, 1.0]),
        ([1.0, 1e-13, 1e-13], [0.5, 2.0, 1e-13]),
    ] {
        let want = direct(&r, d1, d2);
        assert_all_close(&r, &diagonal(d1), &diagonal(d2), want, DIRECT_TOL);
    }
}

/// A ball 1e-150 across at distance 1e10 from a disc's plane: μ² ≈ 1e320 does not fit
/// in a double, which is an error; at distance 1, μ² ≈ 1e300 does.
#[test]
fn only_an_answer_beyond_double_range_is_an_overflow() {
    let (disc, tiny) = (diagonal([1.0, 1.0, 0.0]), diagonal([1e-300; 3]));
    let near = contact_function(&[0.0, 0.0, 1.0], &disc, &tiny).unwrap();
    assert!(
        (near.mu2 - 1e300).abs() <= CLOSED_FORM_TOL * 1e300,
        "{near:?}"
    );
    let far = contact_function(&[0.0, 0.0, 1e10], &disc, &tiny);
    assert!(matches!(far, Err(ContactError::Overflow { .. })), "{far:?}");
    let centre = contact_function(&[0.0; 3], &disc, &diagonal([1.0; 3])).unwrap();
    assert_eq!((centre.mu2, centre.stop), (0.0, Stop::Exact));
}

/// [`robust_answers`] (which `mu2_bound` reads) names the pairs the robust path
/// answers: a disc (does not factor), sizes 1e8 apart (λ₀ within `NEAR_END` of an end)
/// and a needle of aspect ratio 1e5 at 45° (`κ(Q)` 5e9, beyond `FORM_MAX_CONDITION`),
/// and not two balls, nor a needle of aspect ratio 100 (`κ(Q)` 5e3).
#[test]
fn robust_answers_names_the_pairs_the_robust_path_takes() {
    let ball = [1.0, 0.0, 0.0, 1.0, 0.0, 1.0];
    let disc = [1.0, 0.0, 0.0, 1.0, 0.0, 0.0];
    let tiny = ball.map(|x| x * 1e16);
    let needle = |aspect: f64| {
        let (long, short) = (1.0, 1.0 / (aspect * aspect));
        let (a, b) = ((long + short) / 2.0, (short - long) / 2.0);
        [a, b, 0.0, a, 0.0, short]
    };
    let r = [0.3, 2.0, 0.7];
    assert!(!robust_answers(&r, &ball, &ball));
    assert!(robust_answers(&r, &disc, &ball));
    assert!(robust_answers(&r, &tiny, &ball));
    assert!(robust_answers(&r, &needle(1e5), &ball));
    assert!(!robust_answers(&r, &needle(100.0), &ball));
    assert!(mu2_bound(&r, &needle(1e5), &ball).is_some());
    assert!(mu2_bound(&r, &needle(100.0), &ball).is_none());
}
