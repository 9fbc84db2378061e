//! The terms of the refined `f(λ)` at one λ, for one pair or eight in lanes.

use super::*;

/// A pair as the refinement reads it: what a [`Refiner`] refers to, or eight of them
/// in lanes.
pub(crate) struct RefinedPair<'a, T> {
    pub r: &'a [T; 3],
    pub q1: &'a [T; 6],
    pub q2: &'a [T; 6],
    /// The scaled coefficients of `b(λ) = det Q(λ)`.
    pub b: &'a [T; 4],
    pub parts: &'a PencilParts<T>,
    pub start: &'a Start<T>,
}

/// The terms of [`Refiner::at`] at one λ, up to its test of the second-order term.
pub(crate) struct Terms<'a, T> {
    pub(super) q12: &'a [T; 6],
    pub(super) t: T,
    pub(super) p: T,
    pub(super) beta: T,
    pub(super) inv: T,
    pub(super) i2: T,
    pub(super) x: [T; 3],
    pub(super) rho: [T; 3],
    pub(super) adj: [T; 6],
    pub(super) u: [T; 3],
    pub(super) uw: T,
    pub(super) wdw: T,
    pub(super) scale: Acc<T>,
    pub(super) rx: Acc<T>,
    pub num: Acc<T>,
}

impl<'a, T: Arith> Terms<'a, T> {
    /// Works with `x = adj Q(λ) r ≈ Q⁻¹(βr)`, `β = det Q(λ)` (both in units of
    /// [`Rational::det_unit`]), so that nothing waits for a division:
    /// `β² rᵀQ⁻¹r = β rᵀx + xᵀρ + ρᵀQ⁻¹ρ` with `ρ = βr − Q x`.
    #[inline(always)]
    pub fn new(pair: &RefinedPair<'a, T>, lambda: T) -> Self {
        let one = T::constant(1.0);
        let (t, s) = (lambda, one - lambda);
        let (r, start) = (pair.r, pair.start);
        let beta = cubic(pair.b, t, one - t);
        let (ss, st, tt) = (s * s, s * t, t * t);
        let [v0, vm, v2] = &start.v;
        let x = std::array::from_fn(|i| ss * v0[i] + st * vm[i] + tt * v2[i]);
        let rho = scaled_residual(beta, r, s, t, pair.q1, pair.q2, &x);
        // Off the path of the refinement: 1/β as a double-double and λ(1−λ)/β².
        let inv = beta.recip();
        // 1 − β·inv exactly (β·inv = p + e exactly, and 1 − p is exact since p ≈ 1).
        let (bi, bie) = two_prod(beta, inv);
        let inv_lo = ((one - bi) - bie) * inv;
        let adj = pair.parts.adjugate_at(s, t).map(|a| a * start.inv_unit);
        let (p, pe) = two_prod(t, s);
        let once = Acc::from_prod(p, inv);
        let mut scale = Acc::from_prod(once.hi, inv);
        scale.lo = scale.lo + ((once.lo + p * inv_lo + pe * inv) * inv + once.hi * inv_lo);
        // g′ and g″ set the size of a gain of at most GAIN_TOL and of the term after
        // it, so a few digits do: from x.
        let q12 = &start.q12;
        let u = sym_mul(q12, &x);
        let w = sym_mul(&adj, &u);
        let (uw, wdw) = (dot(&u, &w), dot(&w, &sym_mul(q12, &w)));
        let mut rx = Acc::from_prod(r[0], x[0]);
        rx.add_prod(r[1], x[1]);
        rx.add_prod(r[2], x[2]);
        let mut num = Acc::from_prod(beta, rx.hi);
        num.lo = num.lo + (beta * rx.lo + dot(&x, &rho));
        Self {
            q12,
            t,
            p,
            beta,
            inv,
            i2: inv * inv,
            x,
            rho,
            adj,
            u,
            uw,
            wdw,
            scale,
            rx,
            num,
        }
    }

    /// `|ρ|² tr(adj Q)/β` (scaled by β), a bound on `ρᵀQ⁻¹ρ ≤ |ρ|² λ_max(adj Q)/β`, and
    /// the size below which that is negligible: [`NEGLIGIBLE_SECOND_ORDER`]` · β²rᵀQ⁻¹r`.
    /// Below it, the second-order term and the refinement of s for g are below an ulp:
    /// they are skipped, and nothing waits for adj ρ.
    #[inline(always)]
    pub fn second_order_bound(&self) -> (T, T) {
        let tr_adj = self.adj[0] + self.adj[3] + self.adj[5];
        let bound = dot(&self.rho, &self.rho) * tr_adj;
        (
            bound,
            self.beta.times(NEGLIGIBLE_SECOND_ORDER) * self.num.hi,
        )
    }

    /// `f`, `rᵀQ⁻¹r` and `sᵀu` without the second-order term.
    #[inline(always)]
    pub fn plain(&self) -> (T, T, T) {
        let f = self.f(&self.num);
        let su = dot(&self.x, &self.u) * self.i2;
        (f, self.rx.hi * self.inv, su)
    }

    /// `e₀ = adj ρ` and the second-order term `ρᵀQ⁻¹ρ ≈ e₀ᵀρ / β`.
    #[inline(always)]
    pub fn second_order(&self) -> ([T; 3], T) {
        let e0 = sym_mul(&self.adj, &self.rho);
        (e0, dot(&e0, &self.rho) * self.inv)
    }

    /// [`Terms::plain`] with the second-order term; `g` cancels near λ* and near the
    /// ends, so it comes from the refined `x + e₀/β` and `rᵀQ⁻¹r`.
    #[inline(always)]
    pub fn with_second_order(&self, e0: &[T; 3], second: T) -> (T, T, T) {
        let mut num = self.num;
        num.lo = num.lo + second;
        let x1: [T; 3] = std::array::from_fn(|i| self.x[i] + e0[i] * self.inv);
        let su = dot(&x1, &sym_mul(self.q12, &x1)) * self.i2;
        (self.f(&num), num.hi * self.i2, su)
    }

    /// `λ(1−λ)/β² · num`, rounded once from its double-double parts.
    #[inline(always)]
    pub(super) fn f(&self, num: &Acc<T>) -> T {
        let mut f = Acc::from_prod(self.scale.hi, num.hi);
        f.lo = f.lo + (self.scale.hi * num.lo + self.scale.lo * num.hi);
        f.value()
    }

    /// `uᵀw / β³` and `wᵀ(Q2−Q1)w / β⁴`, for g′ and g″.
    #[inline(always)]
    pub fn derivative_terms(&self) -> (T, T) {
        let i3 = self.inv * self.inv * self.inv;
        (self.uw * i3, self.wdw * self.i2 * self.i2)
    }
}

impl Terms<'_, f64> {
    /// The [`Refined`] values from `(f, rᵀQ⁻¹r, sᵀu)`.
    #[inline(always)]
    pub(super) fn refined(&self, (f, h, su): (f64, f64, f64)) -> Refined {
        let (uw, wdw) = self.derivative_terms();
        Refined::new(f, self.t, self.p, h, su, uw, wdw)
    }
}

/// Relative size `2^-80 ≈ 8e-25` below which the second-order term `ρᵀQ⁻¹ρ` of the
/// refinement (module docs) is dropped: then `s₀` errs by `η ≤ 2^-40` in the norm of
/// `Q`, which moves `g` by far less than the corrector's tests can see, and the term
/// itself is 1e-8 ulps.
const NEGLIGIBLE_SECOND_ORDER: f64 = 1.0 / (1u128 << 80) as f64;
