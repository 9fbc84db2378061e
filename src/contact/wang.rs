//! Wang–Wang–Kim (2001) algebraic separation test, an independent cross-check.
//!
//! W. Wang, J. Wang, M.-S. Kim, "An algebraic condition for the separation of two
//! ellipsoids", Computer Aided Geometric Design 18 (2001) 531–539.
//!
//! Each ellipsoid is the quadric `XᵀAX ≤ 0`, `X = (x, y, z, 1)`, with the canonical matrix
//! `A = [[Q⁻¹, −Q⁻¹c], [−cᵀQ⁻¹, cᵀQ⁻¹c − 1]]` (so `XᵀAX = (x−c)ᵀQ⁻¹(x−c) − 1`), built
//! relative to the first centre: `c1 = 0`, `c2 = r12`.
//!
//! **Sign convention, checked on spheres** (tests below): with both interiors negative,
//! `p(λ) = det(λA − B)` always has two positive roots (for spheres a double root at
//! `r1²/r2²`), and the ellipsoids are separated iff `p` has two distinct *negative* roots,
//! touch iff it has a negative double root, and overlap otherwise. The paper's statement
//! "two distinct positive roots" is for `det(λA + B)`, whose roots are those of `p` negated.
//!
//! The decision does not locate the roots. `p(0) = det B < 0` and the leading coefficient
//! `det A < 0` (both matrices have one negative eigenvalue), and `p` has at most two
//! negative roots (the paper's theorem: at least two are positive; checked in the tests),
//! so it has two distinct negative roots iff `p(λ) > 0` for some `λ < 0`.
//! The negative axis is mapped onto `s ∈ (0, 1)` by `λ = −s/(1−s)`, and the maximum of
//! `P(s) = (1−s)⁴ p(−s/(1−s))` is taken over the roots of the cubic `P'` in `[0, 1]`.

use super::scale::ldexp;
use super::scale::{rescale, validate};
use super::sym::{adjugate, det, pencil_coefficients, quadratic_form};
use super::{ContactError, Sym3, Vec3};

/// Margin of the decision: separated iff `max P(s) > SEPARATION_REL_TOL · Σ_k |p_k| s^k
/// (1−s)^{4−k}` at the maximiser. The sum is the size of the terms of `P(s)`; the factor
/// `64 ε` covers Horner's `γ_8 ≈ 4ε` plus the rounding of the coefficients (a few dozen
/// operations each, amplified by the conditioning of `Q1`, `Q2`). Within the margin the
/// pair is within rounding of tangency and is reported as not separated.
pub const SEPARATION_REL_TOL: f64 = 64.0 * f64::EPSILON;

/// Bisection steps used to locate each maximiser of `P` on `[0, 1]`: to `2⁻⁴⁰ ≈ 1e-12`.
/// `P` is flat there, so its value is off by `~|P''| 1e-24`, far below the margin
/// [`SEPARATION_REL_TOL`].
pub const BISECTION_STEPS: u32 = 40;

/// Coefficients of `det(λA − B)`, lowest degree first, for the canonical matrices `A`, `B`
/// of the two ellipsoids with `c1 = 0`, `c2 = r12` (see the module docs).
///
/// Writing `Pi = Qi⁻¹`, `u = P2 r12`, `s(λ) = 1 − r12ᵀu − λ` and `X(λ) = λP1 − P2`,
/// `λA − B = [[X, u], [uᵀ, s]]`, whose determinant is `s det X − uᵀ adj(X) u`.
///
/// Accuracy, inherent to the 4×4 form: the inverses and the translated quadric's constant
/// term `r12ᵀP2 r12 − 1` leave each coefficient with an absolute error of about
/// `κ (1 + ρ) ε · max_k |p_k|` (κ: condition number of the `Qi`, `ρ = max_i r12ᵀQi⁻¹r12`).
///
/// # Errors
/// [`ContactError::NotFinite`] or [`ContactError::NotPositiveDefinite`] for bad input;
/// [`ContactError::Overflow`] if a coefficient is out of double range.
pub fn characteristic_polynomial(
    r12: &Vec3,
    q1: &Sym3,
    q2: &Sym3,
) -> Result<[f64; 5], ContactError> {
    validate(r12, q1, q2)?;
    // Computed at a safe scale σ = 2^j: the scaled matrices are A' = DAD and B' = DBD with
    // D = diag(σ, σ, σ, 1), so det(λA' − B') = σ⁶ det(λA − B).
    let (r, q1, q2, j) = rescale(r12, q1, q2);
    let scaled = in_range(quartic(&r, &q1, &q2))?;
    let p = in_range(scaled.map(|c| ldexp(c, -6 * j)))?;
    if p.iter()
        .zip(&scaled)
        .any(|(c, s)| *s != 0.0 && c.abs() < f64::MIN_POSITIVE)
    {
        return Err(ContactError::Overflow { what: OUT_OF_RANGE }); // underflow
    }
    Ok(p)
}

/// Whether the two ellipsoids are separated, by Wang–Wang–Kim's condition: `det(λA − B)`
/// has two distinct negative real roots (two distinct positive roots of `det(λA + B)`).
///
/// Touching pairs, and pairs within [`SEPARATION_REL_TOL`] of touching, are reported as
/// not separated. The test is fragile near tangency; it is a cross-check of
/// [`super::rational::contact_function_rational`] (`μ² > 1`), not the production path.
/// Measured against it on random pairs (aspect ratios up to 100): no disagreement for
/// `|μ² − 1| ≥ 1e-12`, nor for centres up to 1e11 semi-axes apart, nor for size ratios
/// up to 1e6; at size ratio 1e8 the coefficients lose all their digits and about 5% of
/// the decisions are wrong.
///
/// ```
/// use grainpack::contact::wang::separated;
/// let unit = [1.0, 0.0, 0.0, 1.0, 0.0, 1.0];
/// assert!(separated(&[2.5, 0.0, 0.0], &unit, &unit).unwrap());
/// assert!(!separated(&[1.5, 0.0, 0.0], &unit, &unit).unwrap());
/// ```
///
/// # Errors
/// As [`characteristic_polynomial`].
pub fn separated(r12: &Vec3, q1: &Sym3, q2: &Sym3) -> Result<bool, ContactError> {
    validate(r12, q1, q2)?;
    let (r, q1, q2, _) = rescale(r12, q1, q2);
    let p = in_range(quartic(&r, &q1, &q2))?;
    let (value, size) = max_on_negative_axis(&p);
    Ok(value > SEPARATION_REL_TOL * size)
}

const OUT_OF_RANGE: &str = "coefficients of det(λA − B) (beyond double range)";

fn in_range(p: [f64; 5]) -> Result<[f64; 5], ContactError> {
    match p.iter().all(|c| c.is_finite()) {
        true => Ok(p),
        false => Err(ContactError::Overflow { what: OUT_OF_RANGE }),
    }
}

/// `det(λA − B)` for validated input (see [`characteristic_polynomial`]).
fn quartic(r: &Vec3, q1: &Sym3, q2: &Sym3) -> [f64; 5] {
    let inverse = |q: &Sym3| {
        let adj = adjugate(q);
        let d = det(q, &adj);
        adj.map(|x| x / d)
    };
    let (p1, p2) = (inverse(q1), inverse(q2));
    let u = [
        p2[0] * r[0] + p2[1] * r[1] + p2[2] * r[2],
        p2[1] * r[0] + p2[3] * r[1] + p2[4] * r[2],
        p2[2] * r[0] + p2[4] * r[1] + p2[5] * r[2],
    ];
    let s0 = 1.0 - quadratic_form(&p2, r);
    let (a, b) = pencil_coefficients(&p2.map(|x| -x), &p1, &u);
    // (s0 − λ)(b0 + b1λ + b2λ² + b3λ³) − (a0 + a1λ + a2λ²)
    [
        s0 * b[0] - a[0],
        s0 * b[1] - b[0] - a[1],
        s0 * b[2] - b[1] - a[2],
        s0 * b[3] - b[2],
        -b[3],
    ]
}

/// `(max P(s), size)` over `s ∈ [0, 1]`, where `P(s) = Σ_k p_k (−s)^k (1−s)^{4−k}` is
/// `(1−s)⁴ p(−s/(1−s))` and `size = Σ_k |p_k| s^k (1−s)^{4−k}` at the maximiser.
///
/// `P''` is quadratic: its roots cut `[0, 1]` into pieces on which `P'` is monotone, and
/// each piece where `P'` goes from `+` to `−` holds one local maximum, found by bisection.
fn max_on_negative_axis(p: &[f64; 5]) -> (f64, f64) {
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

#[cfg(test)]
mod tests {
    use super::*;
    use crate::contact::rational::contact_function_rational;
    use crate::contact::rational::tests::{random_pairs, random_rotation, rotate, sphere, Pair};
    use rand::rngs::StdRng;
    use rand::{Rng, SeedableRng};

    fn eval(p: &[f64; 5], x: f64) -> f64 {
        p.iter().rev().fold(0.0, |acc, &c| acc * x + c)
    }

    fn scale_of(p: &[f64; 5]) -> f64 {
        p.iter().fold(0.0_f64, |m, c| m.max(c.abs()))
    }

    fn poly((r, q1, q2): &Pair) -> [f64; 5] {
        characteristic_polynomial(r, q1, q2).unwrap()
    }

    fn sep((r, q1, q2): &Pair) -> bool {
        separated(r, q1, q2).unwrap()
    }

    /// Error model for coefficients of `det(λA − B)`: the inverses amplify rounding by the
    /// condition number κ, and the translated quadric's constant term `rᵀQ⁻¹r − 1` cancels
    /// against the rest in proportion to `ρ = max_i rᵀQi⁻¹r`, so
    /// `|Δp_k| ≈ κ (1 + ρ) ε · max_k |p_k|`. Tests allow a multiple of this.
    fn coefficient_err((r, q1, q2): &Pair, kappa: f64, p: &[f64; 5]) -> f64 {
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
            assert!(expected(separated(&r, &q1, &q2).unwrap_err()));
            assert!(expected(
                characteristic_polynomial(&r, &q1, &q2).unwrap_err()
            ));
        }
    }
}
