//! `f(λ)` to a few ulps whatever the conditioning of `Q(λ)`: mixed-precision iterative
//! refinement of `s = Q(λ)⁻¹ r` against the exact residual.
//!
//! With `Q = Q(λ)` formed in double-double (`hi + lo`, exact products), any approximate
//! solution `s₀` and its exact residual `ρ = r − Q s₀`,
//! `rᵀQ⁻¹r = rᵀs₀ + s₀ᵀρ + ρᵀQ⁻¹ρ` (an identity). The first two terms are summed in
//! double-double; the last is of second order in the error of `s₀` and is taken as
//! `e₀ᵀρ` with `e₀ ≈ Q⁻¹ρ` in double. If `s₀` errs by a relative `η` (in the norm of `Q`),
//! `ρᵀQ⁻¹ρ ≈ η² rᵀQ⁻¹r` and the result errs by `η³` plus a few ulps.
//!
//! Two ways to get `s₀`:
//! - [`Refiner::at`]: from the adjugate pieces the Bernstein coefficients were built
//!   from, `s₀ = (s² adj Q1 r + st M r + t² adj Q2 r) / det Q(λ)`, with no
//!   factorisation and no serial chain of divisions. Its `η` grows like `ε cond²` at
//!   worst, so the step checks itself: the refinement is accepted when the measured
//!   `η² = e₀ᵀρ / rᵀs₀` is at most [`REFINEMENT_TOL`].
//! - [`refined_ldl`]: from the LDLᵀ factors of `hi` (`η ~ ε cond`), for the rest.

use super::bernstein::{cubic, Rational};
use super::dd::{two_prod, two_sum, Acc};
use super::ldl::Ldl;
use super::scale::Prepared;
use super::sym::{dot, sym_mul, Arith, PencilParts};
use super::{ContactError, Sym3, Vec3};

mod gain;
mod lanes;
mod terms;

pub use gain::GAIN_ROUNDING_TOL;
pub(crate) use lanes::at_lanes;
pub(crate) use terms::{RefinedPair, Terms};

/// Largest accepted `η² = e₀ᵀρ / rᵀs₀` of the adjugate start (see the module docs):
/// the error left is about `η³ ≤ REFINEMENT_TOL^{3/2}`, and
/// `REFINEMENT_TOL = (ε/8)^{2/3} ≈ 9e-12` makes it at most `ε/8`.
pub const REFINEMENT_TOL: f64 = 9.2e-12;

/// What the corrector needs at one λ: `f(λ)` to a few ulps, and in double, from the
/// refined `s = Q(λ)⁻¹r` with `u = (Q2−Q1)s` and `w = Q(λ)⁻¹u`, the residual
/// `g = −f′ = (2λ−1) rᵀs + λ(1−λ) sᵀu` and its derivatives
/// `g′ = 2rᵀs + 2(1−2λ) sᵀu − 2λ(1−λ) uᵀw` and `g″ = −6 sᵀu − 6(1−2λ) uᵀw + 6λ(1−λ) wᵀ(Q2−Q1)w`
/// (from `h = rᵀs`: `h′ = −sᵀu`, `h″ = 2uᵀw`, `h‴ = −6wᵀ(Q2−Q1)w`).
#[derive(Debug, Clone, Copy, PartialEq)]
pub(crate) struct Refined {
    pub f: f64,
    pub g: f64,
    pub gp: f64,
    pub gpp: f64,
    /// Whether `g` is accurate enough for the gain `g²/(2g′)` to be added to `f`
    /// (module [`gain`]); if not, the corrector evaluates `f` at the Newton point
    /// instead, where the gain is second order in the error of `g`.
    pub g_trusted: bool,
}

impl Refined {
    /// From `rᵀs`, `sᵀu`, `uᵀw`, `wᵀ(Q2−Q1)w` at λ (`p = λ(1−λ)`).
    #[inline(always)]
    fn new(f: f64, t: f64, p: f64, h: f64, su: f64, uw: f64, wdw: f64) -> Self {
        Self {
            f,
            g: (2.0 * t - 1.0) * h + p * su,
            gp: 2.0 * h + 2.0 * (1.0 - 2.0 * t) * su - 2.0 * p * uw,
            gpp: -6.0 * su - 6.0 * (1.0 - 2.0 * t) * uw + 6.0 * p * wdw,
            g_trusted: true,
        }
    }
}

const IDX: [[usize; 3]; 3] = [[0, 1, 2], [1, 3, 4], [2, 4, 5]];

/// The pieces of `adj Q(λ) r` and `adj Q(λ)`, fixed for a pair.
#[derive(Debug, Clone, Copy)]
pub(crate) struct Refiner<'a> {
    p: &'a Prepared,
    parts: &'a PencilParts,
    rational: &'a Rational,
    start: Start,
}

/// The pieces of the adjugate start that depend on the pair only.
#[derive(Debug, Clone, Copy)]
pub(crate) struct Start<T = f64> {
    /// `adj Q1 r = det Q1 · Q1⁻¹ r`, `M r`, `adj Q2 r = det Q2 · Q2⁻¹ r` (the end
    /// vectors from the LDLᵀ factors, which err by `ε cond` rather than `ε cond²`), in
    /// units of the determinant's [`Rational::det_unit`], like `adj Q(λ)` below: so
    /// that `det Q(λ)` is of order 1 and its square in range.
    v: [[T; 3]; 3],
    /// `1 / det_unit`, exact (a power of two).
    inv_unit: T,
    q12: [T; 6],
}

impl<T: Arith> Start<T> {
    /// From the factors of both forms, the mixed adjugate and `1 / det_unit`.
    #[inline(always)]
    pub fn new(
        l1: &Ldl<T>,
        l2: &Ldl<T>,
        r: &[T; 3],
        q1: &[T; 6],
        q2: &[T; 6],
        mixed: &[T; 6],
        inv_unit: T,
    ) -> Self {
        let (s1, s2) = (l1.solve(r), l2.solve(r));
        let (d1, d2) = (l1.det() * inv_unit, l2.det() * inv_unit);
        let vm = sym_mul(mixed, r);
        let q12: [T; 6] = std::array::from_fn(|k| q2[k] - q1[k]);
        Self {
            v: [
                s1.map(|x| x * d1),
                vm.map(|x| x * inv_unit),
                s2.map(|x| x * d2),
            ],
            inv_unit,
            q12,
        }
    }
}

impl<'a> Refiner<'a> {
    #[inline(always)]
    pub fn new(p: &'a Prepared, parts: &'a PencilParts, rational: &'a Rational) -> Self {
        let inv_unit = rational.inv_det_unit();
        let start = Start::new(&p.l1, &p.l2, &p.r, &p.q1, &p.q2, &parts.mixed, inv_unit);
        Self {
            p,
            parts,
            rational,
            start,
        }
    }

    /// The [`Refined`] values at λ from the adjugate start, or `None` if that start
    /// was too far off to finish in one step (`η² > REFINEMENT_TOL`).
    ///
    /// Works with `x = adj Q(λ) r ≈ Q⁻¹(βr)`, `β = det Q(λ)` (both in units of
    /// [`Rational::det_unit`]), so that nothing waits for a division:
    /// `β² rᵀQ⁻¹r = β rᵀx + xᵀρ + ρᵀQ⁻¹ρ` with `ρ = βr − Q x`.
    #[inline(always)]
    #[cfg(test)]
    pub fn at(&self, lambda: f64) -> Option<Refined> {
        self.at_checking::<false>(lambda)
    }

    /// [`Refiner::at`], and if `CHECK_G` also the checks of `g` (module [`gain`]): `None`
    /// where the error of `g` may spoil the gain to second order, and
    /// [`Refined::g_trusted`] clear where it may to first order. The common path checks
    /// pairs whose coefficients may cancel (`κ` above
    /// [`FAST_MAX_CONDITION`](crate::contact::FAST_MAX_CONDITION)), where that error
    /// made the gain wrong by 1.2e-14 (nearly identical needles), in a separate cold copy
    /// of itself; below it the bound is pessimistic (it fails on a few elongated
    /// reference pairs whose gain is right), the accurate method stays within 1e-15 of
    /// every reference without it (`tests/contact_reference.rs`), and the checks in the
    /// common path cost 17 ns.
    #[inline(always)]
    pub fn at_checking<const CHECK_G: bool>(&self, lambda: f64) -> Option<Refined> {
        let pair = RefinedPair {
            r: &self.p.r,
            q1: &self.p.q1,
            q2: &self.p.q2,
            b: &self.rational.poly.b,
            parts: self.parts,
            start: &self.start,
        };
        let k = Terms::new(&pair, lambda);
        let (bound, negligible) = k.second_order_bound();
        let plain = k.plain();
        // g good enough for the gain (module gain): to second order, or the LDLᵀ
        // refinement; to first order, or the corrector steps before it adds it.
        let mut g_trusted = true;
        if CHECK_G {
            let [(e, second), (e_g2, first)] = k.plain_g_checks(&plain, bound);
            if !(e <= second) {
                return None;
            }
            g_trusted = e_g2 <= first;
        }
        if bound <= negligible {
            return Some(Refined {
                g_trusted,
                ..k.refined(plain)
            });
        }
        let (e0, second) = k.second_order();
        if !(second.abs() <= REFINEMENT_TOL * k.num.hi) {
            return None;
        }
        Some(Refined {
            g_trusted,
            ..k.refined(k.with_second_order(&e0, second))
        })
    }
}

/// `β r − Q(λ) x` with `Q(λ) = s q1 + t q2` formed entry by entry as `hi + lo` (exact
/// products), `β r` and `hi x` exact, and the four terms of each row summed in a tree of
/// error-free additions.
#[inline(always)]
fn scaled_residual<T: Arith>(
    beta: T,
    r: &[T; 3],
    s: T,
    t: T,
    q1: &[T; 6],
    q2: &[T; 6],
    x: &[T; 3],
) -> [T; 3] {
    let (hi, lo) = pencil_dd(s, t, q1, q2);
    // Row by row rather than through `std::array::from_fn`, which was left a call in
    // the middle of the accurate path (every live register spilled around it).
    let row = |i: usize| residual_row(beta, r[i], IDX[i], &hi, &lo, x);
    [row(0), row(1), row(2)]
}

/// One row of [`scaled_residual`]: `ri` its entry of `r`, `k` the entries of `Q(λ)` in it.
#[inline(always)]
fn residual_row<T: Arith>(
    beta: T,
    ri: T,
    k: [usize; 3],
    hi: &[T; 6],
    lo: &[T; 6],
    x: &[T; 3],
) -> T {
    let [k0, k1, k2] = k;
    let (br, e0) = two_prod(beta, ri);
    let (p0, e1) = two_prod(hi[k0], x[0]);
    let (p1, e2) = two_prod(hi[k1], x[1]);
    let (p2, e3) = two_prod(hi[k2], x[2]);
    let (a, ea) = two_sum(br, -p0);
    let (b, eb) = two_sum(-p1, -p2);
    let (c, ec) = two_sum(a, b);
    let small = lo[k0] * x[0] + lo[k1] * x[1] + lo[k2] * x[2];
    c + ((ea + eb + ec) + (e0 - e1 - e2 - e3) - small)
}

/// `Q(λ) = s q1 + t q2` as `hi + lo`, exact up to `ε²` relative.
#[inline(always)]
fn pencil_dd<T: Arith>(s: T, t: T, q1: &[T; 6], q2: &[T; 6]) -> ([T; 6], [T; 6]) {
    let parts: [(T, T); 6] = std::array::from_fn(|k| {
        let (p1, e1) = two_prod(s, q1[k]);
        let (p2, e2) = two_prod(t, q2[k]);
        let (h, e3) = two_sum(p1, p2);
        (h, e1 + e2 + e3)
    });
    (parts.map(|p| p.0), parts.map(|p| p.1))
}

/// `r − (hi + lo) s₀` with exact products and compensated sums.
#[inline(always)]
fn residual(r: &Vec3, hi: &Sym3, lo: &Sym3, s0: &Vec3) -> Vec3 {
    let mut rho = [0.0; 3];
    for i in 0..3 {
        let mut acc = Acc::new(r[i]);
        for j in 0..3 {
            acc.add_prod(-hi[IDX[i][j]], s0[j]);
            acc.lo -= lo[IDX[i][j]] * s0[j];
        }
        rho[i] = acc.value();
    }
    rho
}

/// The [`Refined`] values at λ from the LDLᵀ factors of `hi` (any conditioning
/// accepted by [`MIN_RELATIVE_PIVOT`](super::MIN_RELATIVE_PIVOT)).
#[inline(always)]
pub(crate) fn refined_ldl(
    lambda: f64,
    r: &Vec3,
    q1: &Sym3,
    q2: &Sym3,
) -> Result<Refined, ContactError> {
    let (t, s) = (lambda, 1.0 - lambda);
    let (hi, lo) = pencil_dd(s, t, q1, q2);
    let ldl = Ldl::factor(&hi).map_err(|(pivot, value)| ContactError::NotPositiveDefinite {
        what: "(1−λ)q1 + λq2",
        pivot,
        value,
    })?;
    // Two steps of refinement: s₁ = s₀ + Q⁻¹ρ₀ errs by (ε cond)², and g, which may
    // cancel far more than f, is taken from s₁ + Q⁻¹ρ₁ (module refine::gain).
    let s0 = ldl.solve(r);
    let rho0 = residual(r, &hi, &lo, &s0);
    let e0 = ldl.solve(&rho0);
    let s1 = [s0[0] + e0[0], s0[1] + e0[1], s0[2] + e0[2]];
    let rho = residual(r, &hi, &lo, &s1);
    let e1 = ldl.solve(&rho);
    let mut rs = Acc::from_prod(r[0], s1[0]);
    rs.add_prod(r[1], s1[1]);
    rs.add_prod(r[2], s1[2]);
    rs.lo += dot(&s1, &rho) + dot(&e1, &rho);
    let (rs_hi, rs_lo) = rs.pair();
    let (p, pe) = two_prod(t, s);
    let mut f = Acc::from_prod(p, rs_hi);
    f.lo += p * rs_lo + pe * rs_hi;
    let sol = [s1[0] + e1[0], s1[1] + e1[1], s1[2] + e1[2]];
    let q12: Sym3 = std::array::from_fn(|k| q2[k] - q1[k]);
    let u = sym_mul(&q12, &sol);
    let w = ldl.solve(&u);
    let (su, uw, wdw) = (dot(&sol, &u), dot(&u, &w), dot(&w, &sym_mul(&q12, &w)));
    let mut refined = Refined::new(f.value(), t, p, rs_hi, su, uw, wdw);
    refined.g = gain::g_double_double(t, (rs_hi, rs_lo), (p, pe), q1, q2, &sol);
    Ok(refined)
}

#[cfg(test)]
mod tests;
