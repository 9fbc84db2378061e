use super::*;
use crate::contact::test_pairs::{random_pairs, reference_rows};

struct Setup {
    p: Prepared,
    parts: PencilParts,
    rational: Rational,
}

fn setup(r: &Vec3, q1: &Sym3, q2: &Sym3) -> Setup {
    let p = Prepared::new(r, q1, q2).unwrap();
    let (a, b) = (p.l1.quadratic_form(&p.r), p.l2.quadratic_form(&p.r));
    let parts = PencilParts::new(&p.q1, &p.q2);
    let ends = [p.l1.det(), p.l2.det(), a, b];
    let rational = Rational::new(&p.r, &p.q1, &p.q2, &parts, ends);
    Setup { p, parts, rational }
}

/// `η² = ρᵀQ⁻¹ρ / rᵀQ⁻¹r` of the adjugate start at λ.
fn eta2(refiner: &Refiner, lambda: f64) -> f64 {
    let (t, s) = (lambda, 1.0 - lambda);
    let (r, q1, q2) = (&refiner.p.r, &refiner.p.q1, &refiner.p.q2);
    let beta = refiner.rational.det_scaled_at(t);
    let [v0, vm, v2] = &refiner.start.v;
    let x: Vec3 = std::array::from_fn(|i| s * s * v0[i] + s * t * vm[i] + t * t * v2[i]);
    let rho = scaled_residual(beta, r, s, t, q1, q2, &x);
    let adj = refiner
        .parts
        .adjugate_at(s, t)
        .map(|a| a * refiner.start.inv_unit);
    let e0 = sym_mul(&adj, &rho);
    dot(&e0, &rho) / beta / (beta * dot(r, &x))
}

/// At the reference maximiser (50 digits, rounded to a double, so f is within
/// ~1e-32 of μ² there), both refinements give μ² to a few ulps: 4 ε allows the
/// last few roundings of the double-double sums. The adjugate start is accepted on
/// every typical row; on some extreme rows (nearly identical needles) it declines, and
/// the LDLᵀ refinement answers, never with a wrong f.
#[test]
fn refined_f_at_the_reference_maximiser_is_the_reference_mu2() {
    for name in ["contact_typical.csv", "contact_extreme.csv"] {
        for (c, mu2, lambda) in reference_rows(name) {
            if c.r12 == [0.0; 3] {
                continue;
            }
            let s = setup(&c.r12, &c.q1, &c.q2);
            let refiner = Refiner::new(&s.p, &s.parts, &s.rational);
            let by_ldl =
                s.p.finish(
                    refined_ldl(lambda, &s.p.r, &s.p.q1, &s.p.q2).unwrap().f,
                    lambda,
                    crate::contact::Stop::Converged,
                    0,
                )
                .unwrap()
                .mu2;
            assert!(
                (by_ldl - mu2).abs() <= 4.0 * f64::EPSILON * mu2,
                "{name} line {}: {by_ldl} vs {mu2}",
                c.line
            );
            let Some(v) = refiner.at(lambda) else {
                assert_ne!(name, "contact_typical.csv", "line {}", c.line);
                continue;
            };
            let by_adj =
                s.p.finish(v.f, lambda, crate::contact::Stop::Converged, 0)
                    .unwrap()
                    .mu2;
            assert!(
                (by_adj - mu2).abs() <= 4.0 * f64::EPSILON * mu2,
                "{name} line {}: {by_adj} vs {mu2}",
                c.line
            );
        }
    }
}

/// The adjugate start is far better than its `ε cond²` worst case: on random pairs
/// with condition numbers up to 1e4, `η²` stays below 1e-20 (measured ≤ 3e-27 on
/// the typical reference set, 3e-18 on the extreme one), far inside
/// [`REFINEMENT_TOL`].
#[test]
fn adjugate_start_is_accurate_to_second_order() {
    for ((r, q1, q2), _) in random_pairs(31, 500) {
        let s = setup(&r, &q1, &q2);
        let refiner = Refiner::new(&s.p, &s.parts, &s.rational);
        for lambda in [1e-6, 0.1, 0.5, 0.9, 1.0 - 1e-6] {
            let e = eta2(&refiner, lambda);
            assert!(e.abs() <= 1e-20, "η² = {e} at λ = {lambda}");
        }
    }
}

/// Both ways of refining give the same f to a few ulps and the same derivatives to
/// the accuracy of double precision with condition numbers up to 1e4 (the
/// derivatives are evaluated in double from slightly different `s`): 1e-9
/// relative to the size of the terms.
#[test]
fn adjugate_and_ldl_refinements_agree() {
    for ((r, q1, q2), _) in random_pairs(32, 500) {
        let s = setup(&r, &q1, &q2);
        let refiner = Refiner::new(&s.p, &s.parts, &s.rational);
        for lambda in [0.03, 0.3, 0.7, 0.97] {
            let (a, l) = (
                refiner.at(lambda).unwrap(),
                refined_ldl(lambda, &r, &q1, &q2).unwrap(),
            );
            assert!((a.f - l.f).abs() <= 4.0 * f64::EPSILON * l.f, "{a:?} {l:?}");
            let scale = l.f / (lambda * (1.0 - lambda));
            for (x, y) in [(a.g, l.g), (a.gp, l.gp), (a.gpp, l.gpp)] {
                assert!((x - y).abs() <= 1e-9 * (scale + y.abs()), "{a:?} {l:?}");
            }
        }
    }
}

/// The checks of `g` (module `gain`) decide alike whatever the pair's scale: the
/// common path takes `r12` anywhere in `2^±200` as it is, and multiplied through by
/// `β num` they were of degree 5 in μ²'s scale, which underflowed to `0 ≤ 0` and
/// trusted a `g` 0.4 % off (defect 18 of `docs/reliability.md`, `crash-84c8707d` of
/// fuzz target `contact_bits`, here at unit scale: a needle of `κ(Q)` 1.7e7 against a
/// form 1e8 smaller, at the predictor's λ, where the adjugate start is not good enough).
#[test]
fn the_checks_of_g_decide_alike_at_any_scale_of_the_pair() {
    let r = [
        9.153422967943061e-246,
        1.0039071594400752,
        4.119040321368615e-245,
    ];
    let q1 = [
        0.00039672851562500005,
        5.532909939407137e-222,
        0.0,
        1.0000001192092896,
        0.5000000001164153,
        0.25000000057480065,
    ];
    let q2 = [
        3.051757823158141e-05,
        5.565e-320,
        7.283052908189356e-304,
        4.656616758858119e-10,
        1.4916681476076414e-154,
        6.82121026331578e-12,
    ];
    for k in [-190, -100, 0, 100, 190] {
        let scaled = r.map(|x| x * 2f64.powi(k));
        let s = setup(&scaled, &q1, &q2);
        assert_eq!(s.p.mu2_exp, 0, "2^{k}: taken as it is");
        let refiner = Refiner::new(&s.p, &s.parts, &s.rational);
        let v = refiner.at_checking::<true>(0.940_012_264_399_94);
        assert!(v.is_none(), "2^{k}: {v:?}");
    }
}
