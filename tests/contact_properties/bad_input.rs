//! Bad and extreme input: a typed error or the tiny true value, never a panic or NaN.

use super::*;

#[test]
fn bad_input_is_a_typed_error_never_a_panic_or_nan() {
    let q = [1.0, 0.0, 0.0, 1.0, 0.0, 1.0];
    let r = [1.0, 0.5, 0.25];
    let nan_r = contact_function(&[f64::NAN, 0.0, 0.0], &q, &q).unwrap_err();
    assert!(
        matches!(
            nan_r,
            ContactError::NotFinite {
                what: "r12",
                index: 0,
                ..
            }
        ),
        "{nan_r}"
    );
    let inf_q = contact_function(&r, &q, &[1.0, 0.0, f64::INFINITY, 1.0, 0.0, 1.0]).unwrap_err();
    assert!(
        matches!(
            inf_q,
            ContactError::NotFinite {
                what: "q2",
                index: 2,
                ..
            }
        ),
        "{inf_q}"
    );
    let bad_forms: [(Sym3, usize); 2] = [
        ([-1.0, 0.0, 0.0, -1.0, 0.0, -1.0], 0), // negative definite
        ([1.0, 2.0, 0.0, 1.0, 0.0, 1.0], 1),    // indefinite
    ];
    for (bad, pivot) in bad_forms {
        for method in [contact_function, contact_function_fast] {
            let err = method(&r, &bad, &q).unwrap_err();
            assert!(
                matches!(err, ContactError::NotPositiveDefinite { what: "q1", pivot: p, .. } if p == pivot),
                "{err}"
            );
        }
        assert!(overlaps(&r, &q, &bad).is_err());
    }
    // Semi-definite forms (a flat disc, a point) are answered by the contact functions
    // (their accuracy: src/contact/perram_wertheim/robust_tests.rs and the references)
    // and decided by `overlaps` as the contact function decides them.
    for flat in [[1.0, 0.0, 0.0, 1.0, 0.0, 0.0], [0.0; 6]] {
        for method in [contact_function, contact_function_fast] {
            let c = method(&r, &flat, &q).unwrap();
            assert!(c.mu2.is_finite() && c.mu2 > 0.0, "{c:?}");
        }
        for scale in [0.1, 1.0, 10.0] {
            let r = r.map(|x| x * scale);
            let mu2 = contact_function(&r, &q, &flat).unwrap().mu2;
            assert_eq!(overlaps(&r, &q, &flat), Ok(mu2 < 1.0), "μ² = {mu2}");
        }
    }
    // Two discs in one plane: μ² is not defined, and `overlaps` says so.
    let disc = [1.0, 0.0, 0.0, 1.0, 0.0, 0.0];
    let both = overlaps(&[0.5, 0.5, 0.0], &disc, &disc);
    assert_eq!(both, Err(ContactError::CommonNullDirection), "{both:?}");
    // Too far apart for a double: overflow is an error, not infinity.
    let far = contact_function(
        &[1e200, 0.0, 0.0],
        &[1e-150, 0.0, 0.0, 1e-150, 0.0, 1e-150],
        &q,
    );
    assert!(matches!(far, Err(ContactError::Overflow { .. })), "{far:?}");
    // Sizes 1e100 apart: a ball of radius 1e-100 against a unit ball, μ² = |r|²/(1 +
    // 1e-100)² = |r|² in doubles (to the 4 ε of its rounding).
    let tiny = contact_function(&r, &[1e-200, 0.0, 0.0, 1e-200, 0.0, 1e-200], &q).unwrap();
    let r2 = r.iter().map(|x| x * x).sum::<f64>();
    assert!((tiny.mu2 - r2).abs() <= 4.0 * f64::EPSILON * r2, "{tiny:?}");
}

#[test]
fn coincident_or_nearly_coincident_centres_give_zero_or_the_tiny_true_value() {
    let q1 = random_ellipsoid(&mut StdRng::seed_from_u64(6)).q;
    let q2 = random_ellipsoid(&mut StdRng::seed_from_u64(7)).q;
    let zero = contact_function(&[0.0; 3], &q1, &q2).unwrap();
    assert_eq!((zero.mu2, zero.stop), (0.0, Stop::Exact));
    assert!(overlaps(&[0.0; 3], &q1, &q2).unwrap());
    let r = [0.3, -0.2, 0.9];
    let base = contact_function(&r, &q1, &q2).unwrap().mu2;
    let tiny = contact_function(&r.map(|x| x * 1e-160), &q1, &q2)
        .unwrap()
        .mu2;
    assert!(close(tiny, base * 1e-320, 1e-3), "{tiny:e}"); // subnormal: ~1e-3 relative
    let smaller = contact_function(&r.map(|x| x * 1e-200), &q1, &q2).unwrap();
    assert_eq!(smaller.mu2, 0.0); // underflows, as the true value ~1e-400 must
}
