//! The Perram–Wertheim (1985) contact function: a Halley predictor on the rational
//! form of `f`, then (accurate method) a refined corrector.
//!
//! `f(λ) = λ(1−λ) rᵀ Q(λ)⁻¹ r` with `Q(λ) = (1−λ)Q1 + λQ2` is concave on `[0, 1]` (a
//! minimum of functions affine in λ) and vanishes at both ends, so its maximiser λ* is
//! the unique root of `f′`. The predictor runs Halley's method on `(ln f)′` in the
//! Bernstein form of [`super::bernstein`], from the maximiser for two spheres,
//! `λ₀ = √b / (√a + √b)` with `a = rᵀQ1⁻¹r`, `b = rᵀQ2⁻¹r`, inside a bracket `[lo, hi]`
//! on the sign of `f′` (Newton, then bisection, when a step leaves it). The corrector
//! runs Newton on the residual `g = −f′` evaluated by [`super::refine`].

use super::bernstein::{coefficients, Halley, Rational};
use super::ldl::Ldl;
use super::refine::{refined_ldl, Refined, Refiner};
use super::scale::{needs_no_rescaling, offset_in_safe_range, Prepared};
use super::sym::PencilParts;
use super::{Contact, ContactError, Stop, Sym3, Vec3};

/// Iteration cap. Bisection alone shrinks the bracket below one ulp of 1 in 53 steps,
/// so hitting 64 means the residual is not behaving (non-finite or inconsistent signs).
pub const MAX_ITERATIONS: u32 = 64;

/// Newton stops when the gain its quadratic model predicts, `g² / (2g′)`, is at most
/// `GAIN_TOL · f`. The model's maximum is then added to `f`; what is left is third
/// order, about `(g²/(2g′f))^{3/2} ≤ GAIN_TOL^{3/2}`, so `GAIN_TOL = (ε/8)^{2/3} ≈ 9e-12`
/// leaves at most `ε/8` of relative truncation error.
pub const GAIN_TOL: f64 = 9.2e-12;

/// A Halley step taken where the predicted gain is `G` leaves a gain of order `G³`
/// (cubic convergence), so when `G ≤ HALLEY_FINAL_GAIN = 1e-6` the step is taken and
/// [`contact_function_fast`] ends without evaluating the derivatives again: what is
/// left, `~1e-18` times the local constant, is far below [`GAIN_TOL`].
pub const HALLEY_FINAL_GAIN: f64 = 1e-6;

/// [`contact_function`] hands over to its corrector after the Halley step from a point
/// whose predicted gain is at most `CORRECTOR_SWITCH_GAIN = 1e-4`: that step leaves
/// `~1e-12` times the local constant, which the corrector's first evaluation adds (its
/// own tests, [`GAIN_TOL`] and [`CUBIC_TERM_TOL`], verify it). On the typical
/// reference set this saves 0.4 predictor evaluations per pair (2.47 instead of 2.86)
/// and sends 4 pairs in 1000 to a second corrector step.
pub const CORRECTOR_SWITCH_GAIN: f64 = 1e-4;

/// The contact function μ² of two ellipsoids and its maximiser λ, in double precision.
///
/// The predictor of [`contact_function`] alone, with `f` from the Bernstein form. Its
/// error bound is stated in terms of a condition number `κ` it computes from the
/// coefficients of `f` ([`fast_condition`]; `κ ≥ 3`, below 3.6e3 on the typical
/// reference set): the rounding of `f` is at most [`FAST_ROUNDING`]` · ε · κ` and the
/// truncation at most [`GAIN_TOL`]. It answers a pair itself only if
/// `κ ≤` [`FAST_MAX_CONDITION`]` = 2^15`, so that whenever it reports
/// [`Stop::Converged`] the relative error of μ² is at most [`FAST_TOL`]` ≈ 5.8e-11`.
/// Other pairs (`κ` larger: nearly identical elongated ellipsoids, whose coefficients
/// cancel, or aspect ratios near 1e4 and beyond; forms that do not factor; λ* within
/// [`NEAR_END`] of an end) get [`contact_function`]'s answer, a few ulps, bitwise.
/// Measured: 4.3e-14 on the typical set, at most 1.3e-12 on every extreme category
/// (`tests/contact_reference.rs`, BENCHMARKS.md).
///
/// ```
/// use grainpack::contact::{
///     contact_function, contact_function_fast, fast_condition, Ellipsoid, Stop,
///     FAST_MAX_CONDITION,
/// };
/// // Two needles of aspect ratio 100, one a hair longer: the coefficients of f cancel,
/// // κ is above FAST_MAX_CONDITION, and the accurate path answers.
/// let a = Ellipsoid::new([1.0, 0.01, 0.01], [0.9, 0.3, 0.3, 0.1]).unwrap();
/// let mut q2 = a.q;
/// q2[0] *= 1.0 + 1e-9;
/// let r = [0.01, 0.02, 0.005];
/// assert!(fast_condition(&r, &a.q, &q2).unwrap() > FAST_MAX_CONDITION);
/// let fast = contact_function_fast(&r, &a.q, &q2).unwrap();
/// assert_eq!(fast, contact_function(&r, &a.q, &q2).unwrap());
/// assert_eq!(fast.stop, Stop::Converged);
/// ```
pub fn contact_function_fast(r12: &Vec3, q1: &Sym3, q2: &Sym3) -> Result<Contact, ContactError> {
    solve(r12, q1, q2, false)
}

/// [`contact_function_fast`] for forms already factored (`l1`, `l2` are
/// `Ldl::factor` of `q1`, `q2`, whose diagonals need no rescaling): the same answer,
/// bit for bit, without the two factorisations (the packing's prepared shapes keep
/// them).
#[inline]
pub(crate) fn contact_function_fast_factored(
    r12: &Vec3,
    q1: &Sym3,
    q2: &Sym3,
    (l1, l2): (&Ldl, &Ldl),
) -> Result<Contact, ContactError> {
    if offset_in_safe_range(r12) && *r12 != [0.0; 3] {
        let p = Prepared::unscaled(r12, q1, q2, *l1, *l2);
        return solve_prepared(&p, Mode::Fast, (r12, q1, q2));
    }
    contact_function_fast(r12, q1, q2)
}

/// The Perram–Wertheim contact function μ² of two ellipsoids, and its maximiser λ.
///
/// `μ² = max_{λ∈[0,1]} λ(1−λ) r12ᵀ[(1−λ)Q1 + λQ2]⁻¹ r12` (Perram & Wertheim 1985): μ
/// is the common factor by which both ellipsoids must be scaled about their centres to
/// touch, so `μ² < 1` means overlap and `μ² > 1` apart. λ comes from the Halley
/// iteration of [`contact_function_fast`]; Newton steps on the residual `g = −f′`,
/// with `f` from a mixed-precision iterative refinement of `Q(λ)⁻¹r` against the exact
/// residual (see [`REFINEMENT_TOL`](super::REFINEMENT_TOL)), finish it, so the
/// relative error of μ² stays at a few ulps even when `Q(λ*)` is badly conditioned.
///
/// `r12 = 0` gives `μ² = 0`, `λ = ½`, [`Stop::Exact`]. Inputs are rescaled by powers
/// of two, so μ² underflows gracefully towards 0 and overflows as an error.
///
/// Semi-definite forms are accepted where μ² is defined: a flat disc (rank 2), a
/// zero-radius needle (rank 1) or a point (`Q = 0`) against a definite form, or two
/// singular forms with no common null direction. Forms whose pivots are within
/// [`SINGULAR_PIVOT`] of zero count as singular. μ² may then be the limit of `f` at an
/// end (a point against a ball: `rᵀQ2⁻¹r` at `λ = 0`, [`Stop::Exact`]). Two forms
/// singular along a common direction (coplanar discs, two needles) give
/// [`ContactError::CommonNullDirection`], and indefinite ones
/// [`ContactError::NotPositiveDefinite`]. Sizes any distance apart are answered (two
/// balls of radii 1 and 1e-150 at distance 1: μ² = 1). μ² beyond double range is
/// [`ContactError::Overflow`]. These pairs, forms thinner than [`MIN_RELATIVE_PIVOT`]
/// resolves, forms whose condition number is above [`FORM_MAX_CONDITION`] (needles and
/// flat discs of aspect ratio above about 1.6e4, turned off the axes), and pairs whose
/// λ* is within [`NEAR_END`] of an end, go through a slower path with coefficients in
/// double-double (module `robust`), which is as accurate.
///
/// [`MIN_RELATIVE_PIVOT`]: super::MIN_RELATIVE_PIVOT
///
/// ```
/// use grainpack::contact::{contact_function, Ellipsoid};
/// // The worked example of the pw85 manual. Its printed 3.362706040638343 belongs to
/// // pw85's rounded spheroid (Q_zz = 0.010000000000005116); with Q_zz = 0.1² exactly,
/// // mpmath gives 3.36270604063862922…
/// let e1 = Ellipsoid::spheroid(10.0, 0.1, [0.0, 0.0, 1.0]).unwrap();
/// let e2 = Ellipsoid::spheroid(0.5, 5.0, [1.0, 0.0, 0.0]).unwrap();
/// let r12 = [0.2 - -0.5, -0.3 - 0.4, 0.4 - -0.7];
/// let c = contact_function(&r12, &e1.q, &e2.q).unwrap();
/// assert!((c.mu2 - 3.362_706_040_638_629).abs() < 4.0 * f64::EPSILON * c.mu2);
/// ```
pub fn contact_function(r12: &Vec3, q1: &Sym3, q2: &Sym3) -> Result<Contact, ContactError> {
    solve(r12, q1, q2, true)
}

/// How [`solve`] answers: the fast path, the accurate one, or the accurate one with
/// the checks of `g` ([`Refiner::at_checking`]) for pairs whose coefficients may cancel.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
enum Mode {
    Fast,
    Accurate,
    Checked,
}

#[inline(always)]
fn solve(r12: &Vec3, q1: &Sym3, q2: &Sym3, accurate: bool) -> Result<Contact, ContactError> {
    solve_in(
        r12,
        q1,
        q2,
        if accurate { Mode::Accurate } else { Mode::Fast },
    )
}

#[inline(always)]
fn solve_in(r12: &Vec3, q1: &Sym3, q2: &Sym3, mode: Mode) -> Result<Contact, ContactError> {
    if needs_no_rescaling(r12, q1, q2) && *r12 != [0.0; 3] {
        // The same factors either way, each path's form 2–3 ns shorter for it (BENCHMARKS.md).
        if mode == Mode::Fast {
            if let (Ok(l1), Ok(l2)) = (Ldl::factor(q1), Ldl::factor(q2)) {
                let p = Prepared::unscaled(r12, q1, q2, l1, l2);
                return solve_prepared(&p, mode, (r12, q1, q2));
            }
        } else {
            let ((l1, ok1), (l2, ok2)) = (Ldl::factor_flagged(q1), Ldl::factor_flagged(q2));
            if ok1 & ok2 {
                // Built here rather than returned in an `Option`, which costs a copy.
                let p = Prepared::unscaled(r12, q1, q2, l1, l2);
                return solve_prepared(&p, mode, (r12, q1, q2));
            }
        }
    }
    solve_otherwise(r12, q1, q2, mode)
}

/// [`solve`] for input that needs validating in detail, rescaling, or is `r12 = 0`;
/// forms that are not definite enough to factor and sizes too far apart to rescale
/// together go to [`robust::solve_robust`].
#[cold]
#[inline(never)]
fn solve_otherwise(r12: &Vec3, q1: &Sym3, q2: &Sym3, mode: Mode) -> Result<Contact, ContactError> {
    let p = match Prepared::new(r12, q1, q2) {
        Ok(p) => p,
        Err(ContactError::NotPositiveDefinite { .. } | ContactError::Overflow { .. }) => {
            return solve_robust(r12, q1, q2, 0);
        }
        Err(e) => return Err(e),
    };
    if p.r == [0.0; 3] {
        return Ok(Contact {
            mu2: 0.0,
            lambda: 0.5,
            stop: Stop::Exact,
            iterations: 0,
        });
    }
    solve_prepared(&p, mode, (r12, q1, q2))
}

/// The common path for `p`, prepared from `input` (which the hand-overs take, so that
/// `p` can stay in registers).
#[inline(always)]
fn solve_prepared(
    p: &Prepared,
    mode: Mode,
    input: (&Vec3, &Sym3, &Sym3),
) -> Result<Contact, ContactError> {
    let (parts, (a, b), t0) = pieces(p);
    let inside = (NEAR_END..=1.0 - NEAR_END).contains(&t0);
    if mode == Mode::Fast {
        // One branch for both hand-overs (a second cost the fast path 3 ns).
        if !(inside & well_conditioned(&sizes(&p.r, &p.q1, &p.q2, &parts, &a, &b))) {
            return handed_over(input, inside);
        }
        let rational = Rational::from_coefficients(a, b);
        let (t, stop, iterations) = predict_with(&rational, t0, HALLEY_FINAL_GAIN, true)?;
        return p.finish(rational.f(t), t, stop, iterations);
    }
    let all = sizes(&p.r, &p.q1, &p.q2, &parts, &a, &b);
    if !(inside & (well_conditioned(&all) | (mode == Mode::Checked))) {
        return handed_over(input, inside);
    }
    // Checked only: a form beyond FORM_MAX_CONDITION has κ above FAST_MAX_CONDITION.
    if mode == Mode::Checked && !forms_resolved(&all) {
        let (r12, q1, q2) = input;
        return solve_robust(r12, q1, q2, 0);
    }
    let rational = Rational::from_coefficients(a, b);
    // Built before the predictor runs, so that its work fills the predictor's latency.
    let refiner = Refiner::new(p, &parts, &rational);
    let (t, stop, iterations) = predict(&rational, t0, CORRECTOR_SWITCH_GAIN)?;
    if stop != Stop::Converged {
        return p.finish(rational.f(t), t, stop, iterations);
    }
    match mode {
        Mode::Checked => correct_checking::<true>(p, &refiner, t, iterations),
        _ => correct(p, &refiner, t, iterations),
    }
}

/// The answer for a pair [`solve_prepared`] hands over. One whose maximiser for two
/// spheres lies within [`NEAR_END`] of 0 or 1 (`inside` false) goes to
/// [`robust::solve_robust`]. One whose `κ` is above [`FAST_MAX_CONDITION`] gets the
/// accurate answer with the checks of `g` (both methods: the fast one's is bitwise
/// [`contact_function`]'s).
#[cold]
#[inline(never)]
fn handed_over(
    (r12, q1, q2): (&Vec3, &Sym3, &Sym3),
    inside: bool,
) -> Result<Contact, ContactError> {
    match inside {
        true => solve_in(r12, q1, q2, Mode::Checked),
        false => solve_robust(r12, q1, q2, 0),
    }
}

/// The pieces of the rational form of a prepared pair (its coefficients unscaled), and
/// the maximiser for two spheres where the predictor starts.
#[inline(always)]
#[allow(clippy::type_complexity)]
fn pieces(p: &Prepared) -> (PencilParts, ([f64; 3], [f64; 4]), f64) {
    let (a, b) = (p.l1.quadratic_form(&p.r), p.l2.quadratic_form(&p.r));
    let parts = PencilParts::new(&p.q1, &p.q2);
    let ends = [p.l1.det(), p.l2.det(), a, b];
    let coefficients = coefficients(&p.r, &p.q1, &p.q2, &parts, ends);
    (parts, coefficients, b.sqrt() / (a.sqrt() + b.sqrt()))
}

mod batch;
mod condition;
mod corrector;
mod ends;
mod exact;
mod predictor;
mod robust;
mod robust_bound;
mod robust_root;
#[cfg(test)]
mod robust_tests;
#[cfg(test)]
mod timing;

pub use batch::{contact_functions, contact_functions_fast};
pub use condition::{
    fast_condition, FAST_MAX_CONDITION, FAST_ROUNDING, FAST_TOL, FORM_MAX_CONDITION,
};
use condition::{forms_resolved, robust_answers, sizes, well_conditioned};
use corrector::{correct, correct_checking, correct_further, finished};
pub use corrector::{lambda_bound, CUBIC_TERM_TOL};
pub(crate) use exact::rank;
pub use exact::SINGULAR_PIVOT;
use predictor::{predict, predict_with, STEP_X_MAX};
use robust::{solve_robust, solve_with_complement};
pub use robust_bound::mu2_bound;

/// λ* and `1 − λ*`, each to its own relative precision, by the path for sizes far
/// apart (module `robust`), for finite input: the contact geometry of a pair whose λ*
/// is within [`NEAR_END`] of an end needs `1 − λ*`, which λ* no longer carries.
pub(crate) fn lambda_and_complement(
    r12: &Vec3,
    q1: &Sym3,
    q2: &Sym3,
) -> Result<(f64, f64), ContactError> {
    solve_with_complement(r12, q1, q2, 0).map(|(c, m)| (c.lambda, m))
}
pub use robust::NEAR_END;
