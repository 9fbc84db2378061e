//! The contact function of the pairs the common path does not take: semi-definite
//! forms (flat discs, zero-radius needles, points), forms thinner than
//! [`MIN_RELATIVE_PIVOT`](crate::contact::MIN_RELATIVE_PIVOT) resolves or conditioned
//! beyond [`FORM_MAX_CONDITION`](crate::contact::FORM_MAX_CONDITION), sizes so far
//! apart that λ* lies within [`NEAR_END`] of an end, or that the coefficients of `f`
//! would leave the double range together.
//!
//! **Sizes.** Each form is scaled by a power of two to a largest diagonal entry in
//! `[1, 2)`: `Q1 = σ1 Q̂1`, `Q2 = σ2 Q̂2`. With `Q(λ) = (sσ1 + tσ2) Q̂(λ̂)`,
//! `t̂ = tσ2 / (sσ1 + tσ2)`, a monotone map of `[0, 1]` onto itself,
//! `f(λ) = f̂(λ̂) / (ŝσ2 + t̂σ1)`, `f̂` the contact function of `(r, Q̂1, Q̂2)`. So
//! `μ² = max F / σm`, `σm = max(σ1, σ2)`, with
//! `F = ŝt̂ a(λ̂) / (b(λ̂) (w1 ŝ + w2 t̂))`, `w1 = σ2/σm`, `w2 = σ1/σm`: one weight is 1,
//! the other a power of two that may be tiny (0 when it underflows: the exact limit),
//! and the coefficients of `a` and `b` are those of two forms of size 1.
//!
//! **Degenerate forms.** A form of rank 2 has `det = 0`, of rank 1 also a zero
//! adjugate, of rank 0 (`Q = 0`) nothing at all: [`exact::rank`](super::exact::rank)
//! decides the rank and the coefficients that vanish with it are set to exactly 0.
//! `F = N/C` is then a ratio of two homogeneous quartics in `(ŝ, t̂)` with
//! non-negative coefficients, `N = ŝt̂a`, `C = b (w1 ŝ + w2 t̂)`, which may vanish at an
//! end to the same order: `F` has a finite limit there, and its maximum may be that
//! limit (a point against a ball: `μ² = rᵀQ2⁻¹r` at `λ = 0`), answered in closed form
//! ([`Stop::Exact`]). If both forms are singular along a common direction, `Q(λ)` is
//! singular for every λ and μ² is not defined:
//! [`ContactError::CommonNullDirection`].
//!
//! **The maximum.** In `y = λ̂/(1−λ̂)` the basis `(1−λ̂)^{4−k} λ̂^k` is `(1−λ̂)^4 y^k`, so
//! `F = Σ N_k y^k / Σ C_k y^k`. With `u = ln y` and `E_p`, `Var_p` the mean and the
//! variance of the index `k` weighed by `p_k y^k`, `φ = ln F` has `dφ/du = E_N − E_C
//! =: ψ` and `d²φ/du² = Var_N − Var_C`: ratios of sums of non-negative terms, bounded
//! and free of cancellation whatever the sizes (ψ is summed as one signed double sum).
//! The root of ψ is taken in `y ≤ 1` (the pair mirrored if it lies above, so that `y`
//! keeps its relative precision however close λ* is to an end; in both halves, the
//! larger `F` kept, where the sign of `ψ(½)` is rounding) by Newton's method in
//! `u`, from the maximiser for two spheres, with a bisection of `u` whenever Newton
//! leaves the bracket or fails to halve it. `F` is then a sum of positive terms in
//! coefficients accurate to about `ε²` (module [`exact`](super::exact)), so μ² is
//! accurate to a few ulps.

use super::ends::{end, maximum_at_an_end, reversed, Maximum};
use super::exact::{coefficients, rank, singular_form};
use super::robust_root::{moments, root};
use crate::contact::ldl::Ldl;
use crate::contact::scale::{exponent, finish, ldexp};
use crate::contact::{Contact, ContactError, Stop, Sym3, Vec3};

/// The common path hands a pair over when the maximiser for two spheres,
/// `λ₀ = √b / (√a + √b)`, lies within `NEAR_END = 2^-24 ≈ 6e-8` of 0 or 1: sizes in a
/// ratio above about 1e7. λ* is then near an end too, where the poles of `φ′` nearly
/// cancel, the predictor's scaled products leave their range for larger ratios, and
/// the coefficients of `f` span the cube of the ratio; this path works in the distance
/// to the end itself. The `huge_ratio` references (ratios 1e6 to 1e150) cover both
/// sides of the threshold.
pub const NEAR_END: f64 = 1.0 / (1u64 << 24) as f64;

/// [`contact_function`](super::contact_function) of `(r, q1, q2)` (finite; `q1`, `q2`
/// not known to be definite) by the module's method; `mu2_exp` as in
/// [`Prepared`](crate::contact::scale::Prepared).
pub(super) fn solve_robust(
    r: &Vec3,
    q1: &Sym3,
    q2: &Sym3,
    mu2_exp: i32,
) -> Result<Contact, ContactError> {
    solve_with_complement(r, q1, q2, mu2_exp).map(|(c, _)| c)
}

/// [`solve_robust`], with `1 − λ` to its own relative precision (λ itself rounds to 1
/// when `1 − λ` is below `ε/2`, for sizes ~1e8 or more apart).
pub(super) fn solve_with_complement(
    r: &Vec3,
    q1: &Sym3,
    q2: &Sym3,
    mu2_exp: i32,
) -> Result<(Contact, f64), ContactError> {
    let (e1, q1) = normalised(q1, "q1")?;
    let (e2, q2) = normalised(q2, "q2")?;
    // Each form as the form of its rank (entries a rank decision declares negligible,
    // subnormal ones among them, would otherwise reach the coefficients that do not
    // vanish with the rank, and decide which end F tends to).
    let (k1, q1) = singular_form(&q1).ok_or_else(|| indefinite(&q1, "q1"))?;
    let (k2, q2) = singular_form(&q2).ok_or_else(|| indefinite(&q2, "q2"))?;
    let rmax = r[0].abs().max(r[1].abs()).max(r[2].abs());
    if rmax == 0.0 {
        return Ok((finish(0, 0.0, 0.5, Stop::Exact, 0)?, 0.5));
    }
    if k1 < 3 && k2 < 3 {
        let sum: Sym3 = std::array::from_fn(|k| q1[k] + q2[k]);
        if rank(&sum) != Some(3) {
            return Err(ContactError::CommonNullDirection);
        }
    }
    let j = exponent(rmax);
    let r = r.map(|x| ldexp(x, -j));
    // A zero form has no size of its own: it takes the other's.
    let (e1, e2) = (e1.or(e2).unwrap_or(0), e2.or(e1).unwrap_or(0));
    let (a, b) = vanishing(coefficients(&r, &q1, &q2), k1, k2);
    let (w1, w2, n, c) = weighted(&a, &b, e1, e2);
    let em = e1.max(e2);
    // Where the maximiser for two spheres, λ₀ = √b / (√a + √b) with a = A0/B0 and
    // b = A2/B3 in the original sizes, maps to: t̂/ŝ = √(A2 B0 w1 / (A0 B3 w2)).
    let odds = (a[2] / a[0]).sqrt() * (b[0] / b[3]).sqrt() * (w1.sqrt() / w2.sqrt());
    let m = maximise(&n, &c, odds)?;
    // Back from λ̂ to λ: λ = t̂ w2 / (ŝ w1 + t̂ w2).
    let (s, t) = (m.s * w1, m.t * w2);
    // Both products underflow when one weight did (sizes beyond the double range
    // apart) and λ̂* is at that end: the small form is a point to the large one, and
    // λ* is at its end (for balls, λ* = R1/(R1+R2)).
    let (lambda, complement) = if s + t > 0.0 {
        (t / (s + t), s / (s + t))
    } else if w1 == 0.0 {
        (1.0, 0.0)
    } else if w2 == 0.0 {
        (0.0, 1.0)
    } else {
        (0.5, 0.5)
    };
    let c = finish(mu2_exp + 2 * j - em, m.value, lambda, m.stop, m.iterations)?;
    Ok((c, complement))
}

/// `(log2 σ, Q/σ)` with `σ` the power of two that brings the largest diagonal entry
/// into `[1, 2)`; `None` for `Q = 0`. An error if a diagonal entry is negative, or all
/// are zero and another entry is not.
pub(super) fn normalised(
    q: &Sym3,
    what: &'static str,
) -> Result<(Option<i32>, Sym3), ContactError> {
    let largest = q[0].max(q[3]).max(q[5]);
    if q[0] < 0.0 || q[3] < 0.0 || q[5] < 0.0 || (largest == 0.0 && q.iter().any(|&x| x != 0.0)) {
        return Err(indefinite(q, what));
    }
    if largest == 0.0 {
        return Ok((None, [0.0; 6]));
    }
    let e = exponent(largest);
    Ok((Some(e), q.map(|x| ldexp(x, -e))))
}

/// The weights of the two forms' sizes `e1`, `e2` (powers of two, the larger 1) and
/// the numerator and denominator of `ψ` in `y` from the coefficients `a`, `b`.
pub(super) fn weighted(
    a: &[f64; 3],
    b: &[f64; 4],
    e1: i32,
    e2: i32,
) -> (f64, f64, [f64; 5], [f64; 5]) {
    let em = e1.max(e2);
    let (w1, w2) = (ldexp(1.0, e2 - em), ldexp(1.0, e1 - em));
    let n = [0.0, a[0], a[1], a[2], 0.0];
    let c = [
        w1 * b[0],
        w1 * b[1] + w2 * b[0],
        w1 * b[2] + w2 * b[1],
        w1 * b[3] + w2 * b[2],
        w2 * b[3],
    ];
    (w1, w2, n, c)
}

/// The error for an indefinite form, with the first pivot of its LDLᵀ factorisation
/// (in the given order) that is not positive enough.
fn indefinite(q: &Sym3, what: &'static str) -> ContactError {
    let (pivot, value) = match Ldl::factor(q) {
        Err(bad) => bad,
        Ok(l) => (2, l.d[2]),
    };
    ContactError::NotPositiveDefinite { what, pivot, value }
}

/// The coefficients with those that vanish for forms of ranks `k1`, `k2` set to 0,
/// and rounding below 0 (a singular direction written in doubles) clamped to 0.
pub(super) fn vanishing(
    (a, b): ([f64; 3], [f64; 4]),
    k1: usize,
    k2: usize,
) -> ([f64; 3], [f64; 4]) {
    let (mut a, mut b) = (a.map(|x| x.max(0.0)), b.map(|x| x.max(0.0)));
    // Rank < 3: det = 0; rank < 2: adj = 0 too; rank 0: Q = 0.
    for (k, det, adj_b, adj_a, zero_b) in [(k1, 0, 1, 0, 2), (k2, 3, 2, 2, 1)] {
        if k < 3 {
            b[det] = 0.0;
        }
        if k < 2 {
            b[adj_b] = 0.0;
            a[adj_a] = 0.0;
        }
        if k < 1 {
            b[zero_b] = 0.0;
            a[1] = 0.0;
        }
    }
    (a, b)
}

/// The maximum of `F = N/C` (module docs) on `[0, 1]`, or an overflow error if `F` is
/// unbounded at an end (`N` vanishes there to a lower order than `C`). `odds`, an
/// estimate of `λ̂/(1−λ̂)` at the maximum, is where the search starts if it is usable.
fn maximise(n: &[f64; 5], c: &[f64; 5], odds: f64) -> Result<Maximum, ContactError> {
    let first = |p: &[f64; 5]| p.iter().position(|&x| x > 0.0);
    let last = |p: &[f64; 5]| p.iter().rposition(|&x| x > 0.0);
    let (Some(n_lo), Some(n_hi)) = (first(n), last(n)) else {
        // a ≡ 0 (r in no direction the forms reach... only r = 0): F ≡ 0.
        return Ok(end(0.0, false));
    };
    let infinite = ContactError::Overflow { what: "μ²" };
    let (c_lo, c_hi) = (
        first(c).ok_or(infinite.clone())?,
        last(c).ok_or(infinite.clone())?,
    );
    if n_lo < c_lo || n_hi > c_hi {
        return Err(infinite);
    }
    let same_order = |a: usize, b: usize| (a == b).then_some(a);
    if let Some(m) = maximum_at_an_end(n, c, same_order(n_lo, c_lo), same_order(n_hi, c_hi)) {
        return Ok(m);
    }
    let (nr, cr) = (reversed(n), reversed(c));
    // The root lies above ½ if ψ(½) > 0: mirrored, it lies in (0, ½].
    let (slope, size) = psi_at_half(n, c);
    let half = |mirrored: bool| {
        let (n, c) = if mirrored { (&nr, &cr) } else { (n, c) };
        let (value, y, stop, iterations) = root(n, c, if mirrored { 1.0 / odds } else { odds });
        // λ̂ = y/(1+y) and 1 − λ̂ = 1/(1+y), each to its own relative precision.
        let (x, rest) = (y / (1.0 + y), 1.0 / (1.0 + y));
        let (s, t) = if mirrored { (x, rest) } else { (rest, x) };
        Maximum {
            value,
            s,
            t,
            stop,
            iterations,
        }
    };
    if slope.abs() > SLOPE_TOL * size {
        return Ok(half(slope > 0.0));
    }
    // ψ(½) is rounding: F is flat across the middle to an ulp, and its maximum may lie
    // in either half (within 1e-30 of an end, a few ulps above the middle: fuzz target
    // `contact_bits_2d`). Both are searched; the larger F is the maximum, and two within
    // `F_TIE_TOL` of each other take λ̂ = ½ (between them, where quasi-concave F is at
    // least as large), the same choice for the pair in either order.
    let (below, above) = (half(false), half(true));
    let iterations = below.iterations + above.iterations;
    let stop = match (below.stop, above.stop) {
        (Stop::Converged, Stop::Converged) => Stop::Converged,
        _ => Stop::MaxIterations,
    };
    let larger = below.value.max(above.value);
    let best = if (below.value - above.value).abs() <= F_TIE_TOL * larger {
        Maximum {
            value: larger,
            s: 0.5,
            t: 0.5,
            ..below
        }
    } else if below.value > above.value {
        below
    } else {
        above
    };
    Ok(Maximum {
        stop,
        iterations,
        ..best
    })
}

/// `ψ(½)` (at `y = 1`) when its sign is at most `SLOPE_TOL` of the sum of its terms'
/// magnitudes is rounding, and the half of `[0, 1]` that holds the maximum is not
/// known: each coefficient is a double rounded once from double-double (`ε/2`), each
/// product `N_i C_j` once more (`3ε/2` in all), and the sum of the 25 terms
/// `(i − j) N_i C_j` adds at most `12ε` of their magnitudes. Taking the sign of a
/// rounding-level `ψ(½)` made μ² depend on the order of the pair, by 4.5e-12 (the pair
/// of defect 12 in `docs/reliability.md`).
pub(super) const SLOPE_TOL: f64 = 16.0 * f64::EPSILON;

/// Two maxima of `F`, one from each half, within `F_TIE_TOL = 4ε` of each other are the
/// same value to the rounding of `F` (a sum of positive terms: a few ulps), and their
/// λ̂ is not resolved between them. Taking the larger one's λ̂ instead (exact equality
/// as the tie) answered λ = ½ for a pair and 0.5000000020 for its swap, where `F`
/// was flat to an ulp over 2e-9 and the search of the half without the root stopped
/// short of ½ (fuzz target `contact_bits_2d`, `crash-b3b11fed`).
const F_TIE_TOL: f64 = 4.0 * f64::EPSILON;

/// `ψ(½)` and the sum of the magnitudes of its terms, both as in [`psi`](super::robust_root::psi) at `y = 1`.
fn psi_at_half(n: &[f64; 5], c: &[f64; 5]) -> (f64, f64) {
    let (wn, sn, _) = moments(n, 1.0);
    let (wc, sc, _) = moments(c, 1.0);
    let (mut cross, mut size) = (0.0, 0.0);
    for (i, a) in wn.iter().enumerate() {
        for (j, b) in wc.iter().enumerate() {
            let d = i as f64 - j as f64;
            cross += d * (a * b);
            size += d.abs() * (a * b);
        }
    }
    (cross / sn / sc, size / sn / sc)
}
