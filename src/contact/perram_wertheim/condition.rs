//! When [`contact_function_fast`](super::contact_function_fast) can trust its own
//! evaluation of `f`, and what it does when it cannot.
//!
//! The predictor evaluates `f = st·a/b` from seven Bernstein coefficients, all positive,
//! so a relative error `η_k` in each coefficient moves `f` by at most `max_k η_k`
//! relative (a positive combination cannot amplify it). The coefficients are sums of
//! products whose terms may cancel: for two nearly identical ellipsoids with nearly
//! parallel axes the mixed ones are about twice and three times the end ones while their
//! terms are `cond(Q)` times larger, so rounding leaves `ε cond(Q)²` in `f`. Each
//! coefficient `X_k` has a bound `X̃_k` on the size of its terms that costs a few
//! products (below), and the fast path's rounding error is
//!
//! `|f̂ − f| / f ≤ FAST_ROUNDING · ε · κ`, `κ = max_k X̃_k / X_k`
//!
//! where, with `d(Q) = (Q_00, Q_11, Q_22)` and `c(Q) = (Q_11 Q_22, Q_00 Q_22, Q_00 Q_11)`:
//! - ends (`A0, B0`; `A2, B3`): `κ(Q) = Σ_i Q_ii (adj Q)_ii / det Q = tr(diag(Q) Q⁻¹)`,
//!   the condition number of `Q` scaled to a unit diagonal (≥ 3, 3 for a diagonal `Q`),
//!   which bounds the rounding of the LDLᵀ factors the end coefficients come from;
//! - `A1 = rᵀ M r` (`M` the mixed adjugate): `Ã1 = Σ_i r_i² m_i`, with `m_i` the sum of
//!   the diagonal products in `M_ii` (`m_0 = Q1_11 Q2_22 + Q1_22 Q2_11`, ...);
//! - `B1 = ⟨adj Q1, Q2⟩`: `B̃1 = d(Q2)·c(Q1)`; `B2 = ⟨Q1, adj Q2⟩`: `B̃2 = d(Q1)·c(Q2)`.
//!
//! Each `X̃_k` bounds the absolute terms of `X_k` up to a small factor, because the
//! off-diagonal entries of a positive-definite matrix are at most the geometric mean of
//! their diagonal neighbours.
//!
//! With the truncation of the iteration (the gain it leaves is at most
//! [`GAIN_TOL`](super::GAIN_TOL)), the fast path's error on a pair it answers itself is
//! at most `FAST_ROUNDING · ε · κ + GAIN_TOL`, and it answers a pair itself only if
//! `κ ≤ FAST_MAX_CONDITION`, which keeps that below [`FAST_TOL`]. The others it hands to
//! the accurate path (a few ulps): then `κ` is larger, or the forms do not factor
//! (semi-definite or thinner than [`MIN_RELATIVE_PIVOT`](crate::contact::MIN_RELATIVE_PIVOT)),
//! or λ* is near an end ([`NEAR_END`](super::NEAR_END)). The accurate path itself hands
//! a form whose own `κ(Q)` (the ends' term above) exceeds [`FORM_MAX_CONDITION`] to
//! the robust path.

/// The constant of the rounding bound `|f̂ − f| / f ≤ FAST_ROUNDING · ε · κ` (module
/// docs). On the pairs the fast path answers itself the measured ratio of its error to
/// `ε κ` is at most 0.88 wherever rounding dominates: every category of the reference
/// sets, nearly identical pairs of aspect ratios up to 1e4 and perturbations from 1e-16
/// to 1e-2 included, but `size_ratio`, whose errors (up to 8.7e-14, ratio 4.1) are the
/// truncation that [`GAIN_TOL`](super::GAIN_TOL) bounds. `tests/contact_reference.rs`
/// checks `FAST_ROUNDING · ε · κ + GAIN_TOL` on every row; 4 leaves room for rounding
/// that accumulates differently.
pub const FAST_ROUNDING: f64 = 4.0;

/// The relative error of μ² that [`contact_function_fast`](super::contact_function_fast)
/// guarantees when it reports [`Stop::Converged`](crate::contact::Stop): `2^18 ε ≈
/// 5.8e-11`. Half of it goes to rounding ([`FAST_MAX_CONDITION`]), the rest to the
/// truncation of the iteration (at most [`GAIN_TOL`](super::GAIN_TOL)).
pub const FAST_TOL: f64 = 262_144.0 * f64::EPSILON;

/// The largest `κ` (module docs) the fast path answers itself:
/// `FAST_TOL / (2 · FAST_ROUNDING · ε) = 2^15`. Above it, the pair is answered by the
/// accurate path ([`contact_function`](super::contact_function), a few ulps). On the
/// typical reference set κ stays below 3.6e3, so no typical pair is handed over.
pub const FAST_MAX_CONDITION: f64 = FAST_TOL / (2.0 * FAST_ROUNDING * f64::EPSILON);

/// The largest condition number of either form, `κ(Q) = tr(diag(Q) Q⁻¹)` (module docs:
/// the ends' `κ`), that the common path of [`contact_function`](super::contact_function)
/// answers: `2^27 ≈ 1.3e8`, a needle or a flat disc turned off the axes with an aspect
/// ratio of about 1.6e4 (`κ ≈ α²/2` at 45°). A form beyond it, whose pivots carry a
/// relative rounding of `ε κ(Q)` above `2^-25` that the corrector's refined `f` and
/// `g` start from, goes to the path of module `robust`, which forms the coefficients of
/// `f` in double-double. Measured on 3.2 million random pairs (needles and discs of
/// aspect ratios 10 to 1.6e6 against ellipses and ellipsoids of semi-axes up to 1e8
/// smaller, and nearly identical needles; 2D and 3D), the common path's μ² against the
/// robust one's (itself within 1.6 ε of `tools/contact_exact.py`): at most 3.9 ε below
/// `κ = 1e9`, 14 ε below 1e10, 228 ε (λ 2e-9 off) near `1/MIN_RELATIVE_PIVOT`, where
/// the fuzz target `contact_bits_2d` found μ² of a pair and of its swap 2.9e-12 apart
/// (defect 16 of `docs/reliability.md`). The fuzz targets have since found forms of
/// `κ(Q)` 1e6 to 1.2e8, below the limit, answered up to 1.7e-13 off (defect 18 there):
/// not their conditioning but the corrector's checks of `g`, which underflowed where
/// μ² is far from unit scale (module `refine::gain`); fixed, they are within an ulp.
/// `κ` of the reference sets' forms is at most 6.3e7 (aspect ratios to 1e4), so none
/// of them changes path; the robust path takes about 1.6 µs per pair
/// against the common path's 0.6 µs on such forms.
pub const FORM_MAX_CONDITION: f64 = (1u64 << 27) as f64;

use crate::contact::scale::Prepared;
use crate::contact::sym::{larger, Arith, PencilParts};
use crate::contact::{ContactError, Sym3, Vec3, NEAR_END};

/// The seven coefficients' sizes that [`κ`](self) compares, as five pairs
/// `(X̃_k, X_k)`: both ends (`κ(Q1)`, `κ(Q2)` as `Σ Q_ii (adj Q)_ii` against `det Q`),
/// then `A1`, `B1`, `B2`.
#[inline(always)]
pub(crate) fn sizes<T: Arith>(
    r: &[T; 3],
    q1: &[T; 6],
    q2: &[T; 6],
    parts: &PencilParts<T>,
    a: &[T; 3],
    b: &[T; 4],
) -> [(T, T); 5] {
    let (d1, d2) = ([q1[0], q1[3], q1[5]], [q2[0], q2[3], q2[5]]);
    let (adj1, adj2) = (&parts.adj1, &parts.adj2);
    let end1 = d1[0] * adj1[0] + d1[1] * adj1[3] + d1[2] * adj1[5];
    let end2 = d2[0] * adj2[0] + d2[1] * adj2[3] + d2[2] * adj2[5];
    let c1 = [d1[1] * d1[2], d1[0] * d1[2], d1[0] * d1[1]];
    let c2 = [d2[1] * d2[2], d2[0] * d2[2], d2[0] * d2[1]];
    let m = [
        d1[1] * d2[2] + d1[2] * d2[1],
        d1[0] * d2[2] + d1[2] * d2[0],
        d1[0] * d2[1] + d1[1] * d2[0],
    ];
    let a1 = r[0] * r[0] * m[0] + r[1] * r[1] * m[1] + r[2] * r[2] * m[2];
    let b1 = d2[0] * c1[0] + d2[1] * c1[1] + d2[2] * c1[2];
    let b2 = d1[0] * c2[0] + d1[1] * c2[1] + d1[2] * c2[2];
    [
        (end1, b[0]),
        (end2, b[3]),
        (a1, a[1]),
        (b1, b[1]),
        (b2, b[2]),
    ]
}

/// Whether `κ ≤ FAST_MAX_CONDITION`, from [`sizes`], and every coefficient positive:
/// the largest `X̃_k − FAST_MAX_CONDITION · X_k` at most 0. On the common path every
/// `X̃_k` is positive (sums of products of at most three diagonal entries, each at
/// least `2^-300` once [`Prepared`] has scaled the pair, and of `r_i² ≠ 0`), so a coefficient `X_k ≤ 0` makes its difference positive: the maximum
/// tests both, without a division or a branch per coefficient (five comparisons
/// folded with `&` compiled to code that cost the fast path 25 ns per call). The
/// maximum is taken by [`larger`], one `maxsd` each, which skips a NaN difference as
/// [`contact_functions_fast`]'s lanes do (they take the same differences and maximum).
///
/// [`contact_functions_fast`]: super::contact_functions_fast
#[inline(always)]
pub(crate) fn well_conditioned(sizes: &[(f64, f64); 5]) -> bool {
    let mut worst = f64::NEG_INFINITY;
    for &(bound, x) in sizes {
        let excess = bound - FAST_MAX_CONDITION * x;
        worst = larger(worst, excess);
    }
    worst <= 0.0
}

/// Whether both forms' `κ(Q)` (the ends of [`sizes`]) are at most
/// [`FORM_MAX_CONDITION`], without a division; false for a NaN. Only pairs whose `κ` is
/// above [`FAST_MAX_CONDITION`] need the test: the ends are among the five pairs.
#[inline(always)]
pub(crate) fn forms_resolved(sizes: &[(f64, f64); 5]) -> bool {
    let [(end1, det1), (end2, det2), ..] = *sizes;
    end1 <= FORM_MAX_CONDITION * det1 && end2 <= FORM_MAX_CONDITION * det2
}

/// Whether [`contact_function`](super::contact_function) answers the pair by the robust
/// path (module `robust`), as `solve_in` decides: forms that do not factor or cannot be
/// rescaled together, a maximiser for two spheres within [`NEAR_END`] of an end, or `κ`
/// above [`FAST_MAX_CONDITION`] with a form beyond [`FORM_MAX_CONDITION`]. For
/// [`mu2_bound`](crate::contact::mu2_bound), which bounds that path's answers.
pub(crate) fn robust_answers(r12: &Vec3, q1: &Sym3, q2: &Sym3) -> bool {
    let p = match Prepared::new(r12, q1, q2) {
        Ok(p) => p,
        Err(e) => {
            return matches!(
                e,
                ContactError::NotPositiveDefinite { .. } | ContactError::Overflow { .. }
            )
        }
    };
    if p.r == [0.0; 3] {
        return false;
    }
    let (parts, (a, b), t0) = super::pieces(&p);
    let all = sizes(&p.r, &p.q1, &p.q2, &parts, &a, &b);
    !(NEAR_END..=1.0 - NEAR_END).contains(&t0) || !(well_conditioned(&all) || forms_resolved(&all))
}

/// The condition number `κ` (module docs) that decides whether
/// [`contact_function_fast`](super::contact_function_fast) answers a pair itself: it does
/// when `κ ≤` [`FAST_MAX_CONDITION`], with relative error at most
/// `FAST_ROUNDING · ε · κ + GAIN_TOL ≤ FAST_TOL`, and hands the pair to the accurate path
/// otherwise. Infinite when a coefficient is not positive; a zero coefficient whose terms
/// are all zero (`r12 = 0`) is left out.
///
/// ```
/// use grainpack::contact::{fast_condition, Ellipsoid, FAST_MAX_CONDITION};
/// let ball = Ellipsoid::sphere(1.0).unwrap();
/// assert!(fast_condition(&[3.0, 0.0, 0.0], &ball.q, &ball.q).unwrap() <= 3.0);
/// // Two parallel needles of aspect ratio 1000, turned off the axes: κ ≈ cond(Q)².
/// let needle = Ellipsoid::new([1.0, 1e-3, 1e-3], [0.9, 0.3, 0.3, 0.1]).unwrap();
/// let k = fast_condition(&[0.0, 0.0, 1.0], &needle.q, &needle.q).unwrap();
/// assert!(k > FAST_MAX_CONDITION);
/// ```
pub fn fast_condition(r12: &Vec3, q1: &Sym3, q2: &Sym3) -> Result<f64, ContactError> {
    let p = Prepared::new(r12, q1, q2)?;
    let (parts, (a, b), _) = super::pieces(&p);
    let all = sizes(&p.r, &p.q1, &p.q2, &parts, &a, &b);
    Ok(all.iter().fold(0.0, |k: f64, &(bound, x)| {
        if bound == 0.0 && x == 0.0 {
            return k;
        }
        let ratio = bound / x;
        if ratio >= 0.0 && x > 0.0 {
            k.max(ratio)
        } else {
            f64::INFINITY
        }
    }))
}
