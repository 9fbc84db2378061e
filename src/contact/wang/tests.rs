//! Tests of the Wang–Wang–Kim separation test.

use super::*;
use crate::contact::contact_function;
use crate::contact::rational::contact_function_rational;
use crate::contact::test_pairs::{random_pairs, random_rotation, rotate, sphere, RelativePair};
use rand::rngs::StdRng;
use rand::{Rng, SeedableRng};

fn eval(p: &[f64; 5], x: f64) -> f64 {
    p.iter().rev().fold(0.0, |acc, &c| acc * x + c)
}

fn scale_of(p: &[f64; 5]) -> f64 {
    p.iter().fold(0.0_f64, |m, c| m.max(c.abs()))
}

fn poly((r, q1, q2): &RelativePair) -> [f64; 5] {
    characteristic_polynomial(r, q1, q2).unwrap()
}

fn sep((r, q1, q2): &RelativePair) -> bool {
    separated(r, q1, q2).unwrap()
}

/// Error model for coefficients of `det(λA − B)`: the inverses amplify rounding by the
/// condition number κ, and the translated quadric's constant term `rᵀQ⁻¹r − 1` cancels
/// against the rest in proportion to `ρ = max_i rᵀQi⁻¹r`, so
/// `|Δp_k| ≈ κ (1 + ρ) ε · max_k |p_k|`. Tests allow a multiple of this.
fn coefficient_err((r, q1, q2): &RelativePair, kappa: f64, p: &[f64; 5]) -> f64 {
    let rho = |q: &Sym3| quadratic_form(&adjugate(q), r) / det(q, &adjugate(q));
    kappa * (1.0 + rho(q1).max(rho(q2))) * f64::EPSILON * scale_of(p)
}

/// Spheres of radii 1 and 2 at distance d: apart (4), touching (3), overlapping (2),
/// nested (0.5). By the block determinant, `det(λA − B) = (λ/r1² − 1/r2²)²
/// (−r2²λ² + (r1² + r2² − d²)λ − r1²) / (r1² r2²)`, here `(λ − ¼)² (−4λ² + (5 − d²)λ − 1)/4`.
#[test]
fn characteristic_polynomial_of_two_spheres_matches_closed_form() {
    for d in [4.0, 3.0, 2.0, 0.5_f64] {
        let p = poly(&([0.0, d, 0.0], sphere(1.0), sphere(2.0)));
        let (a, b, c) = (-4.0, 5.0 - d * d, -1.0); // (λ² − λ/2 + 1/16)(aλ² + bλ + c)/4
        let expected = [
            c / 16.0,
            b / 16.0 - c / 2.0,
            a / 16.0 - b / 2.0 + c,
            b - a / 2.0,
            a,
        ];
        for (x, e) in p.iter().zip(expected) {
            // Binary-exact inputs, a few roundings of O(1) numbers.
            assert!(
                (x - e / 4.0).abs() <= 1e-14 * scale_of(&p),
                "d = {d}: {p:?}"
            );
        }
    }
}

/// `A`, `B` built as 4×4 matrices relative to the first centre, `det(λA − B)` by LU.
#[test]
fn characteristic_polynomial_is_det_of_the_4x4_pencil() {
    use nalgebra::{Matrix3, Matrix4, Vector3};
    let canonical = |q: &Sym3, c: &Vec3| {
        let p = Matrix3::new(q[0], q[1], q[2], q[1], q[3], q[4], q[2], q[4], q[5]);
        let (p, c) = (p.try_inverse().unwrap(), Vector3::from(*c));
        let mut m = p.to_homogeneous();
        let pc = -(p * c);
        m.fixed_view_mut::<3, 1>(0, 3).copy_from(&pc);
        m.fixed_view_mut::<1, 3>(3, 0).copy_from(&pc.transpose());
        m[(3, 3)] = c.dot(&(p * c)) - 1.0;
        m
    };
    for (pair @ (r, q1, q2), kappa) in random_pairs(16, 200) {
        let (a, b): (Matrix4<f64>, _) = (canonical(&q1, &[0.0; 3]), canonical(&q2, &r));
        let p = poly(&pair);
        for x in [-3.0, -1.0, -0.3, 0.2, 1.0, 2.5] {
            let (direct, ours) = ((a * x - b).determinant(), eval(&p, x));
            // Within 1× the error model on these pairs; allowed 8×.
            let tol = 8.0 * coefficient_err(&pair, kappa, &p) * (1.0 + x.abs()).powi(4);
            assert!((direct - ours).abs() <= tol, "λ = {x}: {direct} vs {ours}");
        }
    }
}

/// The sign convention, checked rather than assumed: with both interiors negative,
/// `det(λA − B)` keeps a positive double root (`r1²/r2² = ¼`) and the other two roots
/// decide: distinct negative when apart, a negative double root (`−r1/r2`) when
/// touching, a complex pair when overlapping, positive when nested.
#[test]
fn separated_means_two_distinct_negative_roots_of_det_lambda_a_minus_b() {
    let spheres = |d: f64| ([d, 0.0, 0.0], sphere(1.0), sphere(2.0));
    let zero = |p: &[f64; 5], x: f64| eval(p, x).abs() <= 1e-14 * scale_of(p);
    for d in [4.0, 3.0, 2.0, 0.5] {
        assert!(
            zero(&poly(&spheres(d)), 0.25),
            "positive double root, d = {d}"
        );
    }
    let p = poly(&spheres(4.0)); // other roots: those of −4λ² − 11λ − 1
    let (x1, x2) = ((-11.0 - 105f64.sqrt()) / 8.0, (-11.0 + 105f64.sqrt()) / 8.0);
    assert!(zero(&p, x1) && zero(&p, x2) && eval(&p, 0.5 * (x1 + x2)) > 0.0);
    assert!(sep(&spheres(4.0)));
    assert!(zero(&poly(&spheres(3.0)), -0.5) && !sep(&spheres(3.0)));
    for d in [2.0, 0.5] {
        let p = poly(&spheres(d));
        assert!(
            (1..=1000).all(|i| eval(&p, -f64::from(i) / 100.0) < 0.0),
            "d = {d}"
        );
        assert!(!sep(&spheres(d)));
    }
}

#[test]
fn spheres_are_separated_iff_distance_exceeds_sum_of_radii() {
    let mut rng = StdRng::seed_from_u64(11);
    for _ in 0..2000 {
        let (r1, r2) = (rng.random_range(0.1..10.0), rng.random_range(0.1..10.0));
        let ratio: f64 = rng.random_range(0.01..3.0);
        let pair = ([ratio * (r1 + r2), 0.0, 0.0], sphere(r1), sphere(r2));
        // Within 1e-6 of tangency is the documented fragile zone: skipped.
        if (ratio - 1.0).abs() > 1e-6 {
            let pair = rotate(&random_rotation(&mut rng), &pair);
            assert_eq!(sep(&pair), ratio > 1.0, "{ratio}");
        }
    }
}

/// The facts the decision relies on: `p(0) = det B < 0`, leading coefficient
/// `det A < 0`, and at least two positive roots (`p ≥ 0` somewhere on `λ > 0`).
#[test]
fn characteristic_polynomial_has_negative_ends_and_two_positive_roots() {
    for (pair, _) in random_pairs(12, 2000) {
        let p = poly(&pair);
        assert!(p[0] < 0.0 && p[4] < 0.0, "{p:?}");
        let (value, size) = max_on_negative_axis(&[p[0], -p[1], p[2], -p[3], p[4]]);
        assert!(
            value >= -SEPARATION_REL_TOL * size,
            "{p:?}: max {value} on λ > 0"
        );
    }
}

#[test]
fn separated_agrees_with_rational_contact_function_away_from_tangency() {
    let (mut apart, mut overlapping) = (0, 0);
    for (pair @ (r, q1, q2), _) in random_pairs(13, 5000) {
        let mu2 = contact_function_rational(&r, &q1, &q2).unwrap().mu2;
        if (mu2 - 1.0).abs() > 0.1 {
            assert_eq!(sep(&pair), mu2 > 1.0, "μ² = {mu2}, {pair:?}");
            *(if mu2 > 1.0 {
                &mut apart
            } else {
                &mut overlapping
            }) += 1;
        }
    }
    assert!(
        apart > 500 && overlapping > 500,
        "{apart} apart, {overlapping} overlapping"
    );
}

#[test]
fn characteristic_polynomial_is_invariant_under_rotation() {
    let mut rng = StdRng::seed_from_u64(14);
    for (pair, kappa) in random_pairs(14, 1000) {
        let turned = rotate(&random_rotation(&mut rng), &pair);
        let (p, q) = (poly(&pair), poly(&turned));
        // Invariant under the congruence diag(R, 1). R Q Rᵀ rounds each entry by up to
        // ~8 ε‖Q‖ more: measured 12× the model, allowed 64×.
        let tol = 64.0 * coefficient_err(&pair, kappa, &p);
        assert!(
            p.iter().zip(&q).all(|(a, b)| (a - b).abs() <= tol),
            "{p:?} {q:?}"
        );
        assert_eq!(sep(&pair), sep(&turned));
    }
}

/// Swapping gives `det(λB − A) = λ⁴ p(1/λ)` (moving the origin to the other centre has
/// determinant 1): the coefficients come in reverse order.
#[test]
fn swapping_the_ellipsoids_reverses_the_polynomial() {
    for (pair @ (r, q1, q2), kappa) in random_pairs(15, 1000) {
        let swapped = (r.map(|x| -x), q2, q1);
        let (p, q) = (poly(&pair), poly(&swapped));
        let tol = 8.0 * coefficient_err(&pair, kappa, &p); // measured 1.4× the model
        assert!(
            (0..5).all(|k| (p[k] - q[4 - k]).abs() <= tol),
            "{p:?} {q:?}"
        );
        assert_eq!(sep(&pair), sep(&swapped));
    }
}

#[test]
fn extreme_scales_keep_the_decision_and_report_unrepresentable_coefficients() {
    let (q1, q2) = (
        [4.0, 1.0, 0.0, 1.0, 0.0, 0.25],
        [1.0, 0.0, 0.5, 2.0, 0.0, 1.0],
    );
    for (r, expected) in [([3.0, 1.0, 0.5], true), ([1.0, 0.5, 0.2], false)] {
        assert_eq!(separated(&r, &q1, &q2), Ok(expected));
        for k in [-500, -100, 100, 500] {
            let (s, s2) = (ldexp(1.0, k), ldexp(1.0, 2 * k));
            let (r, q1, q2) = (r.map(|x| x * s), q1.map(|x| x * s2), q2.map(|x| x * s2));
            assert_eq!(separated(&r, &q1, &q2), Ok(expected), "2^{k}");
            // The coefficients scale by σ⁻⁶ = 2^(−6k): beyond double range for |k| = 500.
            match characteristic_polynomial(&r, &q1, &q2) {
                Err(ContactError::Overflow { .. }) => assert_eq!(k.abs(), 500),
                Ok(p) => assert!(k.abs() == 100 && p.iter().all(|c| c.is_normal())),
                other => panic!("{other:?}"),
            }
        }
    }
}

#[test]
fn bad_input_gives_typed_error_not_panic() {
    let (r, q) = ([1.0, 2.0, 3.0], sphere(1.0));
    match separated(&[f64::NAN, 0.0, 0.0], &q, &q) {
        Err(ContactError::NotFinite {
            what: "r12",
            index: 0,
            value,
        }) => assert!(value.is_nan()),
        other => panic!("{other:?}"),
    }
    let infinite: Sym3 = [1.0, 0.0, f64::NEG_INFINITY, 1.0, 0.0, 1.0];
    let value = f64::NEG_INFINITY;
    let expected = Err(ContactError::NotFinite {
        what: "q2",
        index: 2,
        value,
    });
    assert_eq!(characteristic_polynomial(&r, &q, &infinite), expected);
    for (q1, q2, what, pivot) in [
        (q.map(|x| -x), q, "q1", 0),                  // negative definite
        (q, [1.0, 0.0, 0.0, 0.0, 0.0, 1.0], "q2", 1), // singular
        (q, [1.0, 0.0, 1.0, 1.0, 0.0, 1.0], "q2", 2), // singular, full diagonal
    ] {
        let expected = |e: ContactError| {
            matches!(e, ContactError::NotPositiveDefinite { what: w, pivot: p, .. }
                if (w, p) == (what, pivot))
        };
        assert!(expected(
            characteristic_polynomial(&r, &q1, &q2).unwrap_err()
        ));
        // Semi-definite forms have no polynomial but a decision (the contact function's).
        match separation(&r, &q1, &q2) {
            Ok((apart, Decided::ContactFunction)) => {
                assert!(pivot > 0);
                assert_eq!(apart, contact_function(&r, &q1, &q2).unwrap().mu2 > 1.0);
            }
            Err(e) => assert!(pivot == 0 && expected(e)),
            other => panic!("{other:?}"),
        }
    }
    // Two needles along one axis: μ² is not defined.
    let needle = [1.0, 0.0, 0.0, 0.0, 0.0, 0.0];
    assert_eq!(
        separated(&r, &needle, &needle),
        Err(ContactError::CommonNullDirection)
    );
}

/// Every decision agrees with the contact function's, and the condition decides every
/// one of these 2000 pairs (aspect ratios up to 100, centres up to 25 apart) itself:
/// its error bound (module `trust`) hands over only pairs near touching, thin and
/// nearly identical forms, and sizes far apart.
#[test]
fn decisions_agree_with_the_contact_function_and_are_the_conditions() {
    let mut handed = 0;
    for (pair @ (r, q1, q2), _) in random_pairs(17, 2000) {
        let mu2 = contact_function(&r, &q1, &q2).unwrap().mu2;
        let (apart, by) = separation(&r, &q1, &q2).unwrap();
        assert_eq!(apart, mu2 > 1.0, "{pair:?}");
        handed += usize::from(by == Decided::ContactFunction);
    }
    assert_eq!(handed, 0);
}
