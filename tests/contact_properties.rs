//! Properties of the contact layer that hold whatever the reference data.

use grainpack::contact::{
    contact_function, contact_function_fast, contact_geometry, contact_geometry_fast, overlaps,
    overlaps_prepared, ContactError, Ellipsoid, PreparedEllipsoid, ShapeError, Stop, Sym3, Vec3,
};
use nalgebra::{Matrix3, Rotation3, Vector3};
use rand::rngs::StdRng;
use rand::{Rng, SeedableRng};

#[path = "contact_properties/bad_input.rs"]
mod bad_input;

/// Relative tolerance for identities that hold exactly in real arithmetic and that
/// the accurate method reproduces to a few ulps (its error is ≤ 2.2e-16 on the
/// reference sets): 16 ε leaves room for the rounding of the transformed inputs.
const IDENTITY_TOL: f64 = 16.0 * f64::EPSILON;

fn random_ellipsoid(rng: &mut StdRng) -> Ellipsoid {
    let axes = [0; 3].map(|_| 10f64.powf(rng.random_range(-1.0..1.0)));
    let mut quat = [0.0; 4].map(|_| rng.random_range(-1.0..1.0f64));
    let norm = quat.iter().map(|x| x * x).sum::<f64>().sqrt();
    quat.iter_mut().for_each(|x| *x /= norm);
    Ellipsoid::new(axes, quat).unwrap()
}

fn random_pair(rng: &mut StdRng) -> (Vec3, Sym3, Sym3) {
    let r = [0; 3].map(|_| rng.random_range(-5.0..5.0));
    (r, random_ellipsoid(rng).q, random_ellipsoid(rng).q)
}

fn rotate(q: &Sym3, rot: &Matrix3<f64>) -> Sym3 {
    let m = Matrix3::new(q[0], q[1], q[2], q[1], q[3], q[4], q[2], q[4], q[5]);
    let m = rot * m * rot.transpose();
    [
        m[(0, 0)],
        m[(0, 1)],
        m[(0, 2)],
        m[(1, 1)],
        m[(1, 2)],
        m[(2, 2)],
    ]
}

fn close(a: f64, b: f64, tol: f64) -> bool {
    (a - b).abs() <= tol * a.abs().max(b.abs())
}

#[test]
fn worked_example_of_the_pw85_manual_is_reproduced() {
    // pw85's spheroid() rounds Q_zz of the flat spheroid to 0.010000000000005116
    // (a² + (c² − a²) loses the bits); with that exact q the manual prints these values.
    let q1 = [100.0, 0.0, 0.0, 100.0, 0.0, 0.010000000000005116];
    let q2 = [25.0, 0.0, 0.0, 0.25, 0.0, 0.25];
    let r12 = [0.2 - -0.5, -0.3 - 0.4, 0.4 - -0.7];
    let c = contact_function(&r12, &q1, &q2).unwrap();
    assert!(close(c.mu2, 3.362706040638343, IDENTITY_TOL), "{c:?}");
    assert!(close(c.lambda, 0.1668589553405904, 1e-14), "{c:?}");
    // Our spheroid keeps Q_zz = 0.1² exactly; mpmath gives 3.36270604063862922… there.
    let e1 = Ellipsoid::spheroid(10.0, 0.1, [0.0, 0.0, 1.0]).unwrap();
    let c = contact_function(&r12, &e1.q, &q2).unwrap();
    assert!(close(c.mu2, 3.362_706_040_638_629, IDENTITY_TOL), "{c:?}");
}

#[test]
fn two_spheres_give_the_squared_distance_ratio() {
    let mut rng = StdRng::seed_from_u64(1);
    for _ in 0..1000 {
        let (r1, r2) = (rng.random_range(0.01..10.0), rng.random_range(0.01..10.0));
        let r = [0; 3].map(|_| rng.random_range(-20.0..20.0f64));
        let d = (r[0] * r[0] + r[1] * r[1] + r[2] * r[2]).sqrt();
        let (s1, s2) = (
            Ellipsoid::sphere(r1).unwrap(),
            Ellipsoid::sphere(r2).unwrap(),
        );
        let c = contact_function(&r, &s1.q, &s2.q).unwrap();
        let expected = (d / (r1 + r2)).powi(2);
        assert!(
            close(c.mu2, expected, IDENTITY_TOL),
            "{} vs {expected}",
            c.mu2
        );
        assert!(close(c.lambda, r1 / (r1 + r2), 1e-12), "λ = {}", c.lambda);
        assert_eq!(overlaps(&r, &s1.q, &s2.q).unwrap(), d < r1 + r2);
    }
}

#[test]
fn swapping_the_ellipsoids_keeps_mu2_and_mirrors_lambda() {
    let mut rng = StdRng::seed_from_u64(2);
    for _ in 0..1000 {
        let (r, q1, q2) = random_pair(&mut rng);
        let a = contact_function(&r, &q1, &q2).unwrap();
        let b = contact_function(&r.map(|x| -x), &q2, &q1).unwrap();
        assert!(close(a.mu2, b.mu2, IDENTITY_TOL), "{a:?} {b:?}");
        assert!((a.lambda - (1.0 - b.lambda)).abs() < 1e-12, "{a:?} {b:?}");
    }
}

#[test]
fn contact_function_is_invariant_under_a_common_rotation() {
    let mut rng = StdRng::seed_from_u64(3);
    for _ in 0..1000 {
        let (r, q1, q2) = random_pair(&mut rng);
        let axis = Vector3::from([0; 3].map(|_| rng.random_range(-1.0..1.0)));
        let rot = Rotation3::new(axis * rng.random_range(0.0..3.0)).into_inner();
        let rr = rot * Vector3::from(r);
        let a = contact_function(&r, &q1, &q2).unwrap();
        let b = contact_function(
            &[rr[0], rr[1], rr[2]],
            &rotate(&q1, &rot),
            &rotate(&q2, &rot),
        )
        .unwrap();
        // The rotated inputs carry rounding of order ε·cond(Q) ≤ 1e4 ε relative.
        assert!(close(a.mu2, b.mu2, 1e4 * f64::EPSILON), "{a:?} {b:?}");
    }
}

#[test]
fn scaling_r12_by_t_scales_mu2_by_t_squared() {
    let mut rng = StdRng::seed_from_u64(4);
    for _ in 0..300 {
        let (r, q1, q2) = random_pair(&mut rng);
        let base = contact_function(&r, &q1, &q2).unwrap().mu2;
        // Powers of two keep r exact, so the identity holds to rounding of μ² alone.
        for k in [-600, -30, -1, 1, 30, 400] {
            let t = 2f64.powi(k);
            let c = contact_function(&r.map(|x| x * t), &q1, &q2).unwrap();
            let expected = base * t * t;
            if expected.is_finite() && expected > f64::MIN_POSITIVE {
                assert!(
                    close(c.mu2, expected, IDENTITY_TOL),
                    "t = 2^{k}: {} vs {expected}",
                    c.mu2
                );
            }
        }
        // A non-power-of-two factor rounds r, by up to ε relative per component.
        let t = 1.7;
        let c = contact_function(&r.map(|x| x * t), &q1, &q2).unwrap();
        assert!(close(c.mu2, base * t * t, 1e3 * f64::EPSILON));
    }
}

#[test]
fn both_methods_agree_and_every_call_converges() {
    let mut rng = StdRng::seed_from_u64(5);
    for _ in 0..2000 {
        let (r, q1, q2) = random_pair(&mut rng);
        let a = contact_function(&r, &q1, &q2).unwrap();
        let b = contact_function_fast(&r, &q1, &q2).unwrap();
        assert_eq!(a.stop, Stop::Converged);
        assert!(a.iterations < 20, "{a:?}");
        // The fast method errs by ε·cond(Q) with cond ≤ 1e4 here.
        assert!(close(a.mu2, b.mu2, 1e4 * f64::EPSILON), "{a:?} {b:?}");
    }
}

#[test]
fn contact_point_lies_on_both_scaled_ellipsoids_with_a_common_normal() {
    let mut rng = StdRng::seed_from_u64(8);
    for _ in 0..500 {
        let (r, q1, q2) = random_pair(&mut rng);
        let g = contact_geometry(&r, &q1, &q2).unwrap();
        let inv = |q: &Sym3| {
            Matrix3::new(q[0], q[1], q[2], q[1], q[3], q[4], q[2], q[4], q[5])
                .try_inverse()
                .unwrap()
        };
        let x1 = Vector3::from(g.point);
        let x2 = x1 - Vector3::from(r);
        // On the surface of each ellipsoid scaled by μ: (x−c)ᵀ Q⁻¹ (x−c) = μ².
        let (h1, h2) = (
            (x1.transpose() * inv(&q1) * x1)[0],
            (x2.transpose() * inv(&q2) * x2)[0],
        );
        assert!(
            close(h1, g.mu2, 1e-9) && close(h2, g.mu2, 1e-9),
            "{h1} {h2} {}",
            g.mu2
        );
        // Outward normals there: Q1⁻¹(x−c1) and −Q2⁻¹(x−c2) are both along `normal`.
        let n = Vector3::from(g.normal);
        for v in [inv(&q1) * x1, -(inv(&q2) * x2)] {
            assert!(v.normalize().dot(&n) > 1.0 - 1e-9, "{v} vs {n}");
        }
        assert_eq!(g.gap > 0.0, g.mu2 > 1.0);
        // The fast variant differs only by the rounding of μ² (ε·cond(Q), cond ≤ 1e4).
        let f = contact_geometry_fast(&r, &q1, &q2).unwrap();
        assert!(close(f.mu2, g.mu2, 1e4 * f64::EPSILON));
        assert!(Vector3::from(f.normal).dot(&n) > 1.0 - 1e-9);
    }
    assert!(matches!(
        contact_geometry(
            &[0.0; 3],
            &[1.0, 0.0, 0.0, 1.0, 0.0, 1.0],
            &[1.0, 0.0, 0.0, 1.0, 0.0, 1.0]
        ),
        Err(ContactError::CoincidentCentres)
    ));
}

#[test]
fn constructors_reject_what_is_not_an_ellipsoid() {
    assert!(matches!(
        Ellipsoid::sphere(-1.0),
        Err(ShapeError::NonPositiveSemiAxis { .. })
    ));
    assert!(matches!(
        Ellipsoid::sphere(f64::NAN),
        Err(ShapeError::NotFinite { .. })
    ));
    assert!(matches!(
        Ellipsoid::spheroid(1.0, 2.0, [0.0; 3]),
        Err(ShapeError::ZeroAxis)
    ));
    assert!(matches!(
        Ellipsoid::new([1.0, 2.0, 3.0], [2.0, 0.0, 0.0, 0.0]),
        Err(ShapeError::NotUnitQuaternion { .. })
    ));
    assert!(matches!(
        Ellipsoid::from_quadratic_form([1.0, 2.0, 0.0, 1.0, 0.0, 1.0]),
        Err(ShapeError::NotPositiveDefinite { pivot: 1, .. })
    ));
    // Semi-axis k lies along column k of R: a quarter turn about z sends x to y.
    let h = std::f64::consts::FRAC_1_SQRT_2;
    let e = Ellipsoid::new([3.0, 1.0, 2.0], [h, 0.0, 0.0, h]).unwrap();
    let expected = [1.0, 0.0, 0.0, 9.0, 0.0, 4.0];
    for (got, want) in e.q.iter().zip(expected) {
        assert!((got - want).abs() < 1e-14, "{:?}", e.q);
    }
    let axes = e.semi_axes();
    for (k, a) in [1.0, 2.0, 3.0].into_iter().enumerate() {
        // Eigenvalues of a 3×3 by nalgebra's iterative solver: a few ulps.
        assert!(close(axes[k], a, IDENTITY_TOL), "{axes:?}");
    }
}

/// Random bit patterns and random extreme magnitudes: every call returns, with either
/// a typed error or a finite μ² ≥ 0 and λ in [0, 1].
#[test]
fn arbitrary_input_never_panics_loops_or_returns_nan() {
    let mut rng = StdRng::seed_from_u64(9);
    let mut answered = 0;
    for i in 0..100_000 {
        let (r, q1, q2) = if i % 2 == 0 {
            let x = |rng: &mut StdRng| f64::from_bits(rng.random());
            (
                [0; 3].map(|_| x(&mut rng)),
                [0; 6].map(|_| x(&mut rng)),
                [0; 6].map(|_| x(&mut rng)),
            )
        } else {
            // Valid shapes (aspect ratios to 1e5) at one wild scale (1e-140..1e140),
            // at distances from 1e-3 to 1e3 times that scale.
            let scale = 10f64.powf(rng.random_range(-140.0..140.0));
            let e = |rng: &mut StdRng| {
                let axes = [0; 3].map(|_| scale * 10f64.powf(rng.random_range(0.0..5.0)));
                let mut quat = [0.0; 4].map(|_| rng.random_range(-1.0..1.0f64));
                let n = quat.iter().map(|x| x * x).sum::<f64>().sqrt();
                quat.iter_mut().for_each(|x| *x /= n);
                Ellipsoid::new(axes, quat).unwrap().q
            };
            let r = [0; 3].map(|_| {
                scale * rng.random_range(-1.0..1.0) * 10f64.powf(rng.random_range(-3.0..3.0))
            });
            (r, e(&mut rng), e(&mut rng))
        };
        for method in [contact_function, contact_function_fast] {
            if let Ok(c) = method(&r, &q1, &q2) {
                assert!(
                    c.mu2.is_finite() && c.mu2 >= 0.0,
                    "{r:?} {q1:?} {q2:?} -> {c:?}"
                );
                assert!((0.0..=1.0).contains(&c.lambda), "{c:?}");
                answered += 1;
            }
        }
        let _ = overlaps(&r, &q1, &q2);
        let _ = contact_geometry(&r, &q1, &q2);
    }
    assert!(
        answered > 99_000,
        "only {answered} answers: the valid half (100 000 calls) should pass"
    );
}

#[test]
fn prepared_shapes_scale_like_scaled_ellipsoids_and_decide_like_overlaps() {
    let mut rng = StdRng::seed_from_u64(10);
    for _ in 0..2000 {
        let (r, q1, q2) = random_pair(&mut rng);
        let s = rng.random_range(0.2..3.0);
        let e1 = Ellipsoid::from_quadratic_form(q1).unwrap();
        let grown = PreparedEllipsoid::new(&e1).unwrap().scaled(s);
        let direct =
            PreparedEllipsoid::new(&Ellipsoid::from_quadratic_form(q1.map(|x| x * s * s)).unwrap())
                .unwrap();
        assert!(close(
            grown.bounding_radius(),
            direct.bounding_radius(),
            IDENTITY_TOL
        ));
        // The smallest eigenvalue is accurate to ε·cond(Q) relative, cond ≤ 1e4 here.
        assert!(close(
            grown.inscribed_radius(),
            direct.inscribed_radius(),
            1e4 * f64::EPSILON
        ));
        let p2 = PreparedEllipsoid::new(&Ellipsoid::from_quadratic_form(q2).unwrap()).unwrap();
        let mu2 = contact_function(&r, grown.q(), &q2).unwrap().mu2;
        if (mu2 - 1.0).abs() > 1e-12 {
            assert_eq!(overlaps_prepared(&r, &grown, &p2).unwrap(), mu2 < 1.0);
            assert_eq!(overlaps(&r, grown.q(), &q2).unwrap(), mu2 < 1.0);
        }
    }
    let unit = PreparedEllipsoid::new(&Ellipsoid::sphere(1.0).unwrap()).unwrap();
    assert!(overlaps_prepared(&[f64::NAN, 0.0, 0.0], &unit, &unit).is_err());
    assert!(overlaps_prepared(&[f64::INFINITY, 0.0, 0.0], &unit, &unit).is_err());
}
