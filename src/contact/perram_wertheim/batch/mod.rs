//! [`contact_function`] and [`contact_function_fast`] for many pairs, eight at a time
//! in vector lanes.
//!
//! The setup, the predictor and the corrector's refined evaluation run as structure of
//! arrays ([`F`]): the same operations as the scalar code, lane by lane, so every value
//! is bitwise that of the scalar function. A pair the lanes cannot take as they stand
//! (rescaling, `r12 = 0`, a form that does not factor, the predictor's term-by-term
//! fallback or its iteration cap, the corrector's slower paths) goes through the
//! scalar code; its lane computes a stand-in pair, whose result is dropped.

use super::*;
use crate::contact::bernstein::{coefficients, largest, scale_of, Poly, MIN_SCALED_PRODUCT};
use crate::contact::lanes::{gather, Mask, F, IN_REGISTERS, LANES};
use crate::contact::ldl::pivot_floor;
use crate::contact::refine::{at_lanes, RefinedPair, Start};
use crate::contact::scale::pow2;
use crate::contact::scale::{finish, ldexp};

/// [`contact_function`] of every pair `(r12, q1, q2)`, in order: bitwise the same
/// results, computed eight pairs at a time where the build targets AVX-512 or AVX2 with
/// FMA, one by one elsewhere.
///
/// Per pair on the typical reference set, against the scalar code in the same run
/// (`cargo test --release --lib batch_against_scalar -- --ignored --nocapture`): 48 ns
/// against 120 with AVX-512 (`target-cpu=native` here), 56 against 131 with AVX2
/// (`target-cpu=x86-64-v3`). As plain arrays (`target-cpu=x86-64`) the lanes took 237
/// ns against 191, so there the pairs go through the scalar code.
///
/// ```
/// use grainpack::contact::{contact_function, contact_functions, Ellipsoid};
/// let ball = Ellipsoid::sphere(1.0).unwrap();
/// let needle = Ellipsoid::new([5.0, 0.2, 0.2], [1.0, 0.0, 0.0, 0.0]).unwrap();
/// let pairs: Vec<_> = (1..=20)
///     .map(|k| ([0.4 * k as f64, 0.3, 0.0], ball.q, needle.q))
///     .collect();
/// let all = contact_functions(&pairs);
/// for ((r12, q1, q2), c) in pairs.iter().zip(&all) {
///     assert_eq!(c.as_ref().unwrap(), &contact_function(r12, q1, q2).unwrap());
/// }
/// ```
pub fn contact_functions(pairs: &[(Vec3, Sym3, Sym3)]) -> Vec<Result<Contact, ContactError>> {
    many::<true>(pairs)
}

/// [`contact_function_fast`] of every pair, in order, as [`contact_functions`] does
/// for [`contact_function`]: bitwise the same results.
pub fn contact_functions_fast(pairs: &[(Vec3, Sym3, Sym3)]) -> Vec<Result<Contact, ContactError>> {
    many::<false>(pairs)
}

#[inline(always)]
fn many<const ACCURATE: bool>(pairs: &[(Vec3, Sym3, Sym3)]) -> Vec<Result<Contact, ContactError>> {
    if IN_REGISTERS {
        in_lanes::<ACCURATE>(pairs)
    } else {
        pairs
            .iter()
            .map(|(r12, q1, q2)| one::<ACCURATE>(r12, q1, q2))
            .collect()
    }
}

/// The scalar function of the method.
#[inline(always)]
fn one<const ACCURATE: bool>(r12: &Vec3, q1: &Sym3, q2: &Sym3) -> Result<Contact, ContactError> {
    solve(r12, q1, q2, ACCURATE)
}

/// [`many`] in lanes, whatever the target.
pub(super) fn in_lanes<const ACCURATE: bool>(
    pairs: &[(Vec3, Sym3, Sym3)],
) -> Vec<Result<Contact, ContactError>> {
    let mut out = Vec::with_capacity(pairs.len());
    let mut chunks = pairs.chunks_exact(LANES);
    for chunk in &mut chunks {
        out.extend(eight::<ACCURATE>(chunk));
    }
    let rest = chunks.remainder().iter();
    out.extend(rest.map(|(r, q1, q2)| one::<ACCURATE>(r, q1, q2)));
    out
}

/// Two unit spheres two radii apart: what a lane computes when its pair goes scalar.
const STAND_IN: (Vec3, Sym3, Sym3) = (
    [2.0, 0.0, 0.0],
    [1.0, 0.0, 0.0, 1.0, 0.0, 1.0],
    [1.0, 0.0, 0.0, 1.0, 0.0, 1.0],
);

/// [`solve`]'s common path for eight pairs, lane `k` for `pairs[k]`.
#[inline(always)]
fn eight<const ACCURATE: bool>(
    pairs: &[(Vec3, Sym3, Sym3)],
) -> [Result<Contact, ContactError>; LANES] {
    let plain = Mask::from_fn(|k| {
        let (r12, q1, q2) = &pairs[k];
        needs_no_rescaling(r12, q1, q2) && *r12 != [0.0; 3]
    });
    let chosen: [&(Vec3, Sym3, Sym3); LANES] =
        std::array::from_fn(|k| if plain.get(k) { &pairs[k] } else { &STAND_IN });
    let r = gather(&chosen, |p| p.0);
    let (q1, q2) = (gather(&chosen, |p| p.1), gather(&chosen, |p| p.2));
    // Ldl::factor, lane by lane.
    let (l1, l2) = (Ldl::unchecked(&q1), Ldl::unchecked(&q2));
    let floor1 = F::from_fn(|k| pivot_floor(&chosen[k].1));
    let floor2 = F::from_fn(|k| pivot_floor(&chosen[k].2));
    let factored = (0..3).fold(Mask::splat(true), |m, i| {
        m.and(l1.d[i].gt(floor1)).and(l2.d[i].gt(floor2))
    });
    // pieces(p), with Rational::new's scaling lane by lane.
    let (a, b) = (l1.quadratic_form(&r), l2.quadratic_form(&r));
    let parts = PencilParts::new(&q1, &q2);
    let (ca, cb) = coefficients(&r, &q1, &q2, &parts, [l1.det(), l2.det(), a, b]);
    let ((a_exp, a_scale), (b_exp, b_scale)) = (scales(&ca), scales(&cb));
    let poly = Poly::from_scaled(ca.map(|x| x * a_scale), cb.map(|x| x * b_scale));
    let t0 = b.sqrt() / (a.sqrt() + b.sqrt());
    let switch = if ACCURATE {
        CORRECTOR_SWITCH_GAIN
    } else {
        HALLEY_FINAL_GAIN
    };
    // `solve_prepared`'s hand-overs, to the scalar code: λ₀ near an end, and (fast)
    // κ above FAST_MAX_CONDITION. Their lanes do not iterate.
    let inside = t0
        .ge(F::splat(NEAR_END))
        .and(t0.le(F::splat(1.0 - NEAR_END)));
    let all = sizes(&r, &q1, &q2, &parts, &ca, &cb);
    let conditioned = well_conditioned_lanes(&all);
    let candidates = match ACCURATE {
        // A form beyond FORM_MAX_CONDITION: the scalar code's robust path.
        true => plain
            .and(factored)
            .and(inside)
            .and(forms_resolved_lanes(&all)),
        false => plain.and(factored).and(inside).and(conditioned),
    };
    let (t, iterations, predicted) = predict_lanes(&poly, t0, switch, candidates, !ACCURATE);
    let common = candidates.and(predicted);
    let scalar = |k: usize| {
        let (r12, q1, q2) = &pairs[k];
        one::<ACCURATE>(r12, q1, q2)
    };
    if !ACCURATE {
        // Rational::f at the predictor's λ.
        let f = poly.ratio(t, 1.0 - t).to_array();
        let t = t.to_array();
        return std::array::from_fn(|k| match common.get(k) {
            true => finish(
                0,
                ldexp(f[k], a_exp[k] - b_exp[k]),
                t[k],
                Stop::Converged,
                iterations[k],
            ),
            false => scalar(k),
        });
    }
    // Rational::inv_det_unit, lane by lane.
    let inv_unit = F::from_array(b_exp.map(|e| pow2(-e)));
    let start = Start::new(&l1, &l2, &r, &q1, &q2, &parts.mixed, inv_unit);
    let pair = RefinedPair {
        r: &r,
        q1: &q1,
        q2: &q2,
        b: &poly.b,
        parts: &parts,
        start: &start,
    };
    let (refined, accepted) = at_lanes(&pair, t, conditioned.not());
    let t = t.to_array();
    std::array::from_fn(|k| {
        if !common.get(k) {
            return scalar(k);
        }
        if accepted.get(k) && !refined[k].g_trusted {
            return scalar(k);
        }
        if accepted.get(k) {
            if let Some((mu2, polished)) = finished(&refined[k], t[k], (0.0, 1.0)) {
                return finish(0, mu2, polished, Stop::Converged, iterations[k] + 1);
            }
        }
        let (r12, q1, q2) = &pairs[k];
        correct_further(r12, q1, q2, 0, t[k], iterations[k])
    })
}

/// [`well_conditioned`], lane by lane: the same differences and maximum.
#[inline(always)]
fn well_conditioned_lanes(sizes: &[(F, F); 5]) -> Mask {
    let mut worst = F::splat(f64::NEG_INFINITY);
    for &(bound, x) in sizes {
        let excess = bound - FAST_MAX_CONDITION * x;
        worst = excess.gt(worst).select(excess, worst);
    }
    worst.le(F::splat(0.0))
}

/// [`forms_resolved`](super::condition::forms_resolved), lane by lane: the same products
/// and comparisons.
#[inline(always)]
fn forms_resolved_lanes(sizes: &[(F, F); 5]) -> Mask {
    let [(end1, det1), (end2, det2), ..] = *sizes;
    let bound = |det: F| FORM_MAX_CONDITION * det;
    end1.le(bound(det1)).and(end2.le(bound(det2)))
}

/// [`Rational::new`]'s scaling of a set of coefficients, lane by lane: the exponents
/// and the powers of two that bring each lane's largest coefficient into `[1, 2)`.
#[inline(always)]
fn scales<const N: usize>(c: &[F; N]) -> ([i32; LANES], F) {
    let c = c.map(F::to_array);
    let scale = std::array::from_fn(|k| scale_of(largest(&c.map(|x| x[k]))));
    (scale.map(|s| s.0), F::from_array(scale.map(|s| s.1)))
}

/// [`predict_with`] in eight lanes, for the lanes of `start` (the others do not
/// iterate): where each lane stops, its evaluations, and a mask clear for lanes that
/// [`predict_with`] would take elsewhere (the term-by-term derivatives, an error, or
/// the iteration cap).
#[inline(always)]
fn predict_lanes(
    poly: &Poly<F>,
    t0: F,
    switch: f64,
    start: Mask,
    remainder: bool,
) -> (F, [u32; LANES], Mask) {
    let zero = F::splat(0.0);
    let mut t = t0;
    let (mut lo, mut hi) = (zero, F::splat(1.0));
    let mut running = start;
    let mut usable = Mask::splat(true);
    let mut iterations = [0; LANES];
    for _ in 0..MAX_ITERATIONS {
        if !running.any() {
            break;
        }
        let Halley { d1, d2, d3, p } = poly.halley_terms(t, 1.0 - t);
        // `halley` declines (P small or NaN), or the derivatives are not finite:
        // `predict` would take another way.
        let scalar_way = p
            .ge(F::splat(MIN_SCALED_PRODUCT))
            .and((d1 + d2 + d3).is_finite())
            .not();
        usable = usable.and(running.and(scalar_way).not());
        lo = d1.gt(zero).select(t, lo);
        hi = d1.lt(zero).select(t, hi);
        let curvature = -d2;
        let halley_denominator = 2.0 * d2 * d2 - d1 * d3;
        let halley = t - 2.0 * d1 * d2 * p / halley_denominator;
        let halley_ok = halley_denominator
            .gt(zero)
            .and(halley.ge(lo))
            .and(halley.le(hi));
        let newton = t + d1 * p / curvature;
        let newton_ok = curvature.gt(zero).and(newton.ge(lo)).and(newton.le(hi));
        let next = halley_ok.select(halley, newton_ok.select(newton, 0.5 * (lo + hi)));
        let gain2 = d1 * d1;
        let mut final_step = halley_ok.and(gain2.le((2.0 * switch) * curvature));
        if remainder {
            // step_leaves_little, lane by lane.
            final_step = final_step.and((d1 * d3).abs().le(STEP_X_MAX * (d2 * d2)));
        }
        let small_gain = gain2.le((2.0 * GAIN_TOL) * curvature).or(final_step);
        let converged = d1.eq(zero).or(curvature.gt(zero).and(small_gain));
        let stalled = next.eq(t).or((hi - lo).le(f64::EPSILON * hi));
        t = running.select(next, t);
        for (k, n) in iterations.iter_mut().enumerate() {
            *n += u32::from(running.get(k));
        }
        running = running.and(converged.or(stalled).not());
    }
    (t, iterations, usable.and(running.not()))
}

#[cfg(test)]
mod tests;
