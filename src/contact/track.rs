//! A pair's contact followed from one evaluation to the next, as a relaxation needs it:
//! the bracketed Newton iteration of module `direct`, started where the pair's last
//! answer left it instead of at the two-sphere maximiser. Grains move little between
//! two steps of a relaxation, so one evaluation of `f` (one LDLᵀ of `Q(λ)`) usually
//! answers, where the fast path pays for the rational form's coefficients first.
//!
//! `f(λ)` at any λ is at most μ² (μ² is f's maximum over `[0, 1]`), so every answer is
//! a lower bound of μ², to the rounding of one evaluation (a few `ε κ`): a pair found
//! apart is apart, and a bound on how far the grains may move before they touch stays
//! a bound. How close the bound is, is the caller's choice (`tol`).

use super::direct::Half;
use super::perram_wertheim::{FAST_MAX_CONDITION, NEAR_END};
use super::prepared::PreparedEllipsoid;
use super::scale::offset_in_safe_range;
use super::sym::sym_mul;
use super::Vec3;

/// Evaluations of `f` [`contact_tracked`] spends before it hands the pair back.
/// From a start carried over one step of a relaxation, one or two; from the two-sphere
/// start, three to five on shapes of aspect ratio up to 2 at `tol = 1e-6`.
pub const TRACK_EVALUATIONS: u32 = 4;

/// What [`contact_tracked`] found.
#[derive(Debug, Clone, Copy)]
pub struct Tracked {
    /// `f(λ)` at the last evaluation: at most μ², to its rounding.
    pub mu2_lower: f64,
    /// Where the pair's next evaluation should start: Newton's iterate from the last
    /// one (the bracket's midpoint where Newton's step leaves it).
    pub next: f64,
    /// Given when `f` is at most `apart` and within `tol` of μ².
    pub touch: Option<Touch>,
}

/// Where two ellipsoids touch: at the maximiser λ* of f, to first order in the last
/// Newton step `δ` of a [`Tracked`] answer (an error of `O(δ²)`, `δ² ≈ 2 tol f / g′`).
#[derive(Debug, Clone, Copy)]
pub struct Touch {
    /// `Q(λ*)⁻¹ r12`: a positive multiple of the contact normal (from the first
    /// ellipsoid to the second), and `∇_{r12} μ² = 2λ*(1−λ*) direction`.
    pub direction: Vec3,
    /// The contact point from the first centre, `(1−λ*) Q1 Q(λ*)⁻¹ r12`.
    pub point: Vec3,
}

/// Follows the pair's λ from `start` (a previous answer's `next`; anything outside
/// `(0, 1)`, NaN included, starts from the two-sphere maximiser). Returns as soon as
/// `f(λ) > apart` (the pair is apart at scale `√apart`), or once the Newton model's
/// gain `g²/(2g′)` is at most `tol · f` (μ² is then `mu2_lower` to that relative
/// gain), with the point and normal there. `None` hands the pair back to the general
/// path: forms that needed rescaling or are worse conditioned than
/// [`FAST_MAX_CONDITION`], an offset out of the safe range, λ within [`NEAR_END`] of an
/// end, a factorisation that fails, or no answer in [`TRACK_EVALUATIONS`].
#[inline]
pub fn contact_tracked(
    r12: &Vec3,
    e1: &PreparedEllipsoid,
    e2: &PreparedEllipsoid,
    start: f64,
    (apart, tol): (f64, f64),
) -> Option<Tracked> {
    let usable = e1.unscaled & e2.unscaled & offset_in_safe_range(r12);
    if !usable || e1.condition.max(e2.condition) > FAST_MAX_CONDITION {
        return None;
    }
    let (q1, q2) = (e1.q(), e2.q());
    let q12 = std::array::from_fn(|k| q2[k] - q1[k]);
    let mut lambda = if start > 0.0 && start < 1.0 {
        start
    } else {
        let (a, b) = (e1.ldl.quadratic_form(r12), e2.ldl.quadratic_form(r12));
        let (sa, sb) = (a.sqrt(), b.sqrt());
        sb / (sa + sb)
    };
    let (mut lo, mut hi) = (0.0, 1.0);
    for _ in 0..TRACK_EVALUATIONS {
        if !(NEAR_END..=1.0 - NEAR_END).contains(&lambda) {
            return None;
        }
        let half = Half::at(lambda, r12, q1, q2).ok()?;
        if half.f > apart && half.f.is_finite() {
            let (mu2_lower, next) = (half.f, lambda);
            let touch = None;
            return Some(Tracked {
                mu2_lower,
                next,
                touch,
            });
        }
        let e = half.derivatives(&q12);
        if !(e.f.is_finite() && e.g.is_finite() && e.gp > 0.0 && e.gp.is_finite()) {
            return None;
        }
        if e.g < 0.0 {
            lo = lambda;
        } else if e.g > 0.0 {
            hi = lambda;
        }
        let newton = lambda - e.g / e.gp;
        let next = if newton > lo && newton < hi {
            newton
        } else {
            0.5 * (lo + hi)
        };
        if e.gain() <= tol * e.f {
            // The normal and point at Newton's λ* = λ + δ, to first order in δ:
            // d/dλ Q(λ)⁻¹r = −Q(λ)⁻¹(Q2 − Q1) Q(λ)⁻¹r. So their error is O(δ²), where
            // at λ itself it would be O(δ) = O(√tol).
            let delta = -e.g / e.gp;
            let v = e.ldl.solve(&sym_mul(&q12, &half.s));
            let direction: Vec3 = std::array::from_fn(|k| half.s[k] - delta * v[k]);
            let point = sym_mul(q1, &direction).map(|x| x * (1.0 - (lambda + delta)));
            let touch = Some(Touch { direction, point });
            return Some(Tracked {
                mu2_lower: e.f,
                next,
                touch,
            });
        }
        lambda = next;
    }
    None
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::contact::sym::dot;
    use crate::contact::test_pairs::random_pairs;
    use crate::contact::{contact_function, contact_geometry, GAIN_TOL};

    /// One evaluation's rounding, relative, in units of `ε κ`.
    const ROUNDING: f64 = 64.0;
    /// The tolerance the packing asks for.
    const TOL: f64 = 1e-6;

    fn prepared(q: &[f64; 6]) -> PreparedEllipsoid {
        PreparedEllipsoid::from_quadratic_form(q).unwrap()
    }

    #[test]
    fn a_tracked_answer_is_a_lower_bound_of_mu2_within_its_tolerance() {
        let (mut answered, mut all) = (0, 0);
        for ((r, q1, q2), kappa) in random_pairs(31, 4000) {
            let exact = contact_function(&r, &q1, &q2).unwrap().mu2;
            let round = ROUNDING * f64::EPSILON * kappa;
            all += 1;
            let answer = contact_tracked(
                &r,
                &prepared(&q1),
                &prepared(&q2),
                f64::NAN,
                (f64::INFINITY, TOL),
            );
            let Some(t) = answer else { continue };
            answered += 1;
            assert!(t.touch.is_some(), "{r:?}");
            assert!(t.mu2_lower <= exact * (1.0 + round), "{r:?} {q1:?} {q2:?}");
            // The Newton model's gain is the shortfall to second order.
            assert!(
                t.mu2_lower >= exact * (1.0 - 2.0 * TOL - round),
                "{r:?} {q1:?} {q2:?}"
            );
        }
        // The rest are handed back, never answered wrongly: pairs above
        // FAST_MAX_CONDITION, with λ near an end, or not converged from the two-sphere
        // start in TRACK_EVALUATIONS (3 553 of these 4 000, whose aspect ratios reach
        // 100, are answered).
        assert!(answered * 20 > all * 17, "{answered} of {all}");
    }

    #[test]
    fn a_pair_is_apart_only_where_it_is_and_never_past_its_mu2() {
        for ((r, q1, q2), kappa) in random_pairs(37, 2000) {
            let exact = contact_function(&r, &q1, &q2).unwrap().mu2;
            let round = ROUNDING * f64::EPSILON * kappa;
            let (e1, e2) = (prepared(&q1), prepared(&q2));
            // Asked below μ², a pair is found apart; above it, it never is.
            let below = contact_tracked(&r, &e1, &e2, f64::NAN, (exact * (1.0 - 1e-3), TOL));
            if let Some(t) = below {
                assert!(t.touch.is_none(), "{r:?} {q1:?} {q2:?}");
                assert!(t.mu2_lower <= exact * (1.0 + round));
            }
            let above = contact_tracked(&r, &e1, &e2, f64::NAN, (exact * (1.0 + 1e-3), TOL));
            if let Some(t) = above {
                assert!(t.touch.is_some(), "{r:?} {q1:?} {q2:?}");
            }
        }
    }

    #[test]
    fn started_at_the_maximiser_the_answer_is_the_accurate_geometry() {
        let mut checked = 0;
        for ((r, q1, q2), kappa) in random_pairs(41, 2000) {
            let (e1, e2) = (prepared(&q1), prepared(&q2));
            let Ok(g) = contact_geometry(&r, &q1, &q2) else {
                continue;
            };
            let Some(t) = contact_tracked(&r, &e1, &e2, g.lambda, (f64::INFINITY, GAIN_TOL)) else {
                continue;
            };
            let round = ROUNDING * f64::EPSILON * kappa;
            let touch = t.touch.unwrap();
            assert!((t.mu2_lower - g.mu2).abs() <= round * g.mu2, "{r:?}");
            let d = touch.direction;
            let n = d.map(|x| x / dot(&d, &d).sqrt());
            let off = |a: &Vec3, b: &Vec3| {
                let e: Vec3 = std::array::from_fn(|k| a[k] - b[k]);
                dot(&e, &e).sqrt()
            };
            assert!(off(&n, &g.normal) <= round, "{r:?} {q1:?} {q2:?}");
            assert!(
                off(&touch.point, &g.point) <= round * dot(&r, &r).sqrt(),
                "{r:?}"
            );
            checked += 1;
        }
        assert!(checked > 1800, "{checked}");
    }
}
