//! The contact functions on arbitrary input: an answer is finite and obeys the
//! symmetries to the bounds `tests/contact_properties.rs` documents, or it is a
//! typed error.

use grainpack::contact::{
    contact_function, contact_function_2d, contact_function_fast, contact_function_fast_2d,
    contact_functions_2d, contact_geometry, embed_pair, lambda_bound, mu2_bound, overlaps,
    overlaps_2d, Contact, ContactError, Stop, Sym2, Sym3, Vec2, Vec3,
};

/// Relative bound on identities exact in real arithmetic that the accurate method
/// reproduces to a few ulps: 16 ε, as `IDENTITY_TOL` in `tests/contact_properties.rs`.
pub const IDENTITY_TOL: f64 = 16.0 * f64::EPSILON;

/// Bound on `|λ(1, 2) − (1 − λ(2, 1))|` beyond λ's own documented bound
/// (`contact::lambda_bound`, for each order), as in `tests/contact_properties.rs`
/// (`swapping_the_ellipsoids_keeps_mu2_and_mirrors_lambda`), where the typical pairs'
/// `lambda_bound` is ~1e-8 but λ agrees to 1e-12. Checked where that test draws its
/// pairs: inputs and μ² without subnormal numbers (subnormal inputs carry fewer than
/// 53 bits). `lambda_bound` is added because a flat maximum leaves λ ill-conditioned:
/// on the 21 inputs of defect 11 (`docs/reliability.md`) λ of the two orders differed
/// by up to 1.6e-8, and one ulp in the data moved λ* by up to 7.3e-8; on the robust
/// path's pairs (defect 17) by up to 1.5e-3, within its bound there (0.38).
pub const LAMBDA_SWAP_TOL: f64 = 1e-12;

/// Zero or a normal double (not subnormal, not NaN or infinite).
fn plain(x: f64) -> bool {
    x == 0.0 || x.is_normal()
}

fn close(a: f64, b: f64, tol: f64) -> bool {
    (a - b).abs() <= tol * a.abs().max(b.abs())
}

/// [`close`], with one ulp of the subnormal numbers more: a μ² below the normal
/// doubles is rounded once more, to fewer than 53 bits, as it is scaled back (half that
/// ulp in each order: `5.47472818784314e-310` and `5.4747281878431e-310` by order, fuzz
/// target `contact_bits_2d`, `crash-d22b8c1e`).
fn close_or_subnormal_ulp(a: f64, b: f64, tol: f64) -> bool {
    (a - b).abs() <= tol * a.abs().max(b.abs()) + f64::from_bits(1)
}

/// An answer that may be compared: the accurate method met its stopping test (or
/// needed none). [`Stop::MaxIterations`] is a best estimate, not held to the bounds.
fn settled(c: &Contact) -> bool {
    matches!(c.stop, Stop::Converged | Stop::Exact)
}

/// Checks every contact function on one pair in relative form, and the symmetries:
/// the swapped pair (`−r12`, `q2`, `q1`) and `r12` scaled by `2^k`.
pub fn check_pair(r: &Vec3, q1: &Sym3, q2: &Sym3, k: i32) {
    let input = format!("r12 = {r:?}, q1 = {q1:?}, q2 = {q2:?}");
    for method in [contact_function, contact_function_fast] {
        if let Ok(c) = method(r, q1, q2) {
            assert!(
                c.mu2.is_finite() && c.mu2 >= 0.0 && (0.0..=1.0).contains(&c.lambda),
                "{input}: {c:?}"
            );
        }
    }
    if let Ok(g) = contact_geometry(r, q1, q2) {
        let values = [g.mu2, g.lambda, g.gap]
            .into_iter()
            .chain(g.point)
            .chain(g.normal);
        assert!(values.into_iter().all(f64::is_finite), "{input}: {g:?}");
    }
    let decided = overlaps(r, q1, q2);
    let Ok(a) = contact_function(r, q1, q2) else {
        return;
    };
    if let Ok(overlap) = decided {
        // `overlaps` is the sign of μ² − 1: it must agree wherever the accurate μ²
        // is further from 1 than its own error.
        if settled(&a) && (a.mu2 - 1.0).abs() > IDENTITY_TOL * a.mu2.max(1.0) {
            assert_eq!(overlap, a.mu2 < 1.0, "{input}: {a:?}");
        }
    }
    let swapped = contact_function(&r.map(|x| -x), q2, q1);
    let b = swapped.unwrap_or_else(|e| panic!("{input}: answered, but swapped: {e}"));
    if settled(&a) && settled(&b) {
        // The robust path's μ² is as accurate as its coefficients (`mu2_bound`, of
        // order ε but for coefficients that cancel: defect 20, 4.7e-9 between orders).
        let tol = IDENTITY_TOL
            + mu2_bound(r, q1, q2).unwrap_or(0.0)
            + mu2_bound(&r.map(|x| -x), q2, q1).unwrap_or(0.0);
        assert!(
            close_or_subnormal_ulp(a.mu2, b.mu2, tol),
            "{input}: swapped {a:?} {b:?}, allowed {tol:e}"
        );
    }
    let plain_input = r.iter().chain(q1).chain(q2).all(|&x| plain(x));
    if settled(&a) && settled(&b) && plain_input && a.mu2.is_normal() {
        let bound = |r: &Vec3, q1: &Sym3, q2: &Sym3, c: &Contact| {
            lambda_bound(r, q1, q2, c.lambda).unwrap_or(0.0)
        };
        let allowed = LAMBDA_SWAP_TOL + bound(r, q1, q2, &a) + bound(&r.map(|x| -x), q2, q1, &b);
        assert!(
            (a.lambda - (1.0 - b.lambda)).abs() <= allowed,
            "{input}: swapped {a:?} {b:?}, allowed {allowed:e}"
        );
    }
    // Powers of two keep r exact: μ² scales by t² to its rounding, while μ² and t²μ²
    // are normal doubles (a subnormal μ² has fewer than 53 bits).
    let t = 2f64.powi(k);
    let expected = a.mu2 * t * t;
    let exact = r
        .iter()
        .all(|x| *x == 0.0 || (x * t).abs() >= f64::MIN_POSITIVE);
    if exact && a.mu2.is_normal() && expected.is_normal() && settled(&a) {
        let scaled = contact_function(&r.map(|x| x * t), q1, q2);
        let c = scaled.unwrap_or_else(|e| panic!("{input}: answered, but r12 × 2^{k}: {e}"));
        if settled(&c) {
            assert!(
                close(c.mu2, expected, IDENTITY_TOL),
                "{input}: 2^{k}: {a:?} {c:?}"
            );
        }
    }
}

/// Checks the 2D contact functions on one pair of ellipses: an error names a 2D entry
/// that holds the offending value (an index of `r12` below 2, of a form below 3, a
/// pivot below 2), the batch form answers as the scalar one, and the answers are the
/// embedded pair's, which [`check_pair`] then holds to the 3D properties.
pub fn check_pair_2d(r: &Vec2, q1: &Sym2, q2: &Sym2, k: i32) {
    let input = format!("r12 = {r:?}, q1 = {q1:?}, q2 = {q2:?} (2D)");
    let named = |e: &ContactError| match *e {
        ContactError::NotFinite { what, index, value } => {
            let entries: &[f64] = match what {
                "r12" => r,
                "q1" => q1,
                _ => q2,
            };
            let held = entries.get(index).map(|x| x.to_bits() == value.to_bits());
            assert_eq!(held, Some(true), "{input}: {e}");
        }
        ContactError::NotPositiveDefinite { pivot, .. } => assert!(pivot < 2, "{input}: {e}"),
        _ => {}
    };
    let accurate = contact_function_2d(r, q1, q2);
    let batch = contact_functions_2d(&[(*r, *q1, *q2)]);
    match (&accurate, &batch[0]) {
        (Ok(a), Ok(b)) => assert!(a.mu2.to_bits() == b.mu2.to_bits(), "{input}: {a:?} {b:?}"),
        (Err(a), Err(b)) => assert_eq!(a.to_string(), b.to_string(), "{input}"),
        (a, b) => panic!("{input}: scalar {a:?}, batch {b:?}"),
    }
    for e in [&accurate, &contact_function_fast_2d(r, q1, q2)]
        .into_iter()
        .filter_map(|x| x.as_ref().err())
    {
        named(e);
    }
    if let Err(e) = overlaps_2d(r, q1, q2) {
        named(&e);
    }
    let (r3, a, b) = embed_pair(r, q1, q2);
    if let Ok(c) = &accurate {
        let embedded = contact_function(&r3, &a, &b).expect("the embedded pair is answered");
        assert_eq!(c.mu2.to_bits(), embedded.mu2.to_bits(), "{input}");
    }
    check_pair(&r3, &a, &b, k);
}
