//! `f`, `g = −f′` and `g′` in double precision from the LDLᵀ factors of `Q(λ)`, and the
//! bracketed Newton iteration on them that the overlap decision runs.
//!
//! `f(λ) = λ(1−λ) rᵀs`, `g = (2λ−1) rᵀs + λ(1−λ) sᵀu` and
//! `g′ = 2rᵀs + 2(1−2λ) sᵀu − 2λ(1−λ) uᵀQ⁻¹u > 0`, with `s = Q(λ)⁻¹r` and
//! `u = (Q2−Q1)s` (pw85 manual, "Optimization of the function f"). The iteration starts
//! from the maximiser for two spheres, `λ₀ = √b / (√a + √b)` with `a = rᵀQ1⁻¹r`,
//! `b = rᵀQ2⁻¹r`, keeps a bracket `[lo, hi]` on the sign of `g`, and falls back to
//! bisection when a Newton step leaves it.

use super::ldl::Ldl;
use super::perram_wertheim::GAIN_TOL;
use super::scale::Prepared;
use super::sym::{dot, sym_mul};
use super::{ContactError, Sym3, Vec3};

/// One evaluation of `f`, `g` and `g′` at λ, with the factorisation of `Q(λ)`.
#[derive(Debug, Clone, Copy)]
pub(crate) struct Eval {
    pub lambda: f64,
    pub f: f64,
    pub g: f64,
    pub gp: f64,
    pub ldl: Ldl,
    q: Sym3,
}

impl Eval {
    /// Evaluates at `lambda` in double precision.
    #[inline(always)]
    pub fn at(
        lambda: f64,
        r: &Vec3,
        q1: &Sym3,
        q2: &Sym3,
        q12: &Sym3,
    ) -> Result<Self, ContactError> {
        Ok(Half::at(lambda, r, q1, q2)?.derivatives(q12))
    }

    /// The gain `g² / (2g′)` predicted by the Newton model, i.e. how far `f(λ)` is
    /// below its maximum to second order; 0 where rounding made `g′ ≤ 0` (f flat).
    #[inline(always)]
    pub fn gain(&self) -> f64 {
        if self.gp > 0.0 {
            self.g * self.g / (2.0 * self.gp)
        } else {
            0.0
        }
    }

    /// Upper bound of the condition number of `Q(λ)`: `tr · σ₂ / det`, where `σ₂` is
    /// the sum of the principal 2×2 minors (`λ_max ≤ tr`, `λ_min ≥ det / σ₂`).
    pub fn condition_bound(&self) -> f64 {
        condition_bound(&self.q, &self.ldl)
    }
}

/// `f` alone at λ, with what its derivatives need: the first half of an [`Eval`].
#[derive(Debug, Clone, Copy)]
pub(crate) struct Half {
    pub lambda: f64,
    pub f: f64,
    /// `s = Q(λ)⁻¹ r` and `rᵀs`.
    pub s: Vec3,
    rs: f64,
    pub ldl: Ldl,
    q: Sym3,
}

impl Half {
    /// Evaluates `f` at `lambda` in double precision.
    #[inline(always)]
    pub fn at(lambda: f64, r: &Vec3, q1: &Sym3, q2: &Sym3) -> Result<Self, ContactError> {
        let (q, ldl) = factor_at(lambda, q1, q2)?;
        let s = ldl.solve(r);
        let rs = dot(r, &s);
        Ok(Self {
            lambda,
            f: lambda * (1.0 - lambda) * rs,
            s,
            rs,
            ldl,
            q,
        })
    }

    /// `g` and `g′` too, with `q12 = Q2 − Q1`.
    #[inline(always)]
    pub fn derivatives(self, q12: &Sym3) -> Eval {
        let Self {
            lambda,
            f,
            s,
            rs,
            ldl,
            q,
        } = self;
        let u = sym_mul(q12, &s);
        let su = dot(&s, &u);
        let uv = ldl.quadratic_form(&u);
        let lm = lambda * (1.0 - lambda);
        Eval {
            lambda,
            f,
            g: (2.0 * lambda - 1.0) * rs + lm * su,
            gp: 2.0 * rs + 2.0 * (1.0 - 2.0 * lambda) * su - 2.0 * lm * uv,
            ldl,
            q,
        }
    }
}

/// `Q(λ) = (1−λ)Q1 + λQ2` in double precision, and its factors.
///
/// A convex combination of two positive-definite matrices is positive definite, so
/// failure here means rounding at the edge of [`MIN_RELATIVE_PIVOT`](super::MIN_RELATIVE_PIVOT).
#[inline(always)]
pub(crate) fn factor_at(lambda: f64, q1: &Sym3, q2: &Sym3) -> Result<(Sym3, Ldl), ContactError> {
    factor_between(1.0 - lambda, lambda, q1, q2)
}

/// [`factor_at`] with `m = 1 − λ` given, for a λ so near 1 that `1.0 − λ` has lost it.
#[inline(always)]
pub(crate) fn factor_between(
    m: f64,
    lambda: f64,
    q1: &Sym3,
    q2: &Sym3,
) -> Result<(Sym3, Ldl), ContactError> {
    let q: Sym3 = std::array::from_fn(|k| m * q1[k] + lambda * q2[k]);
    let ldl = Ldl::factor(&q).map_err(|(pivot, value)| ContactError::NotPositiveDefinite {
        what: "(1−λ)q1 + λq2",
        pivot,
        value,
    })?;
    Ok((q, ldl))
}

/// `tr · σ₂ / det` of a factored matrix; see [`Eval::condition_bound`].
#[inline(always)]
pub(crate) fn condition_bound(q: &Sym3, ldl: &Ldl) -> f64 {
    let tr = q[0] + q[3] + q[5];
    let s2 = q[0] * q[3] - q[1] * q[1] + q[0] * q[5] - q[2] * q[2] + q[3] * q[5] - q[4] * q[4];
    tr * s2 / (ldl.d[0] * ldl.d[1] * ldl.d[2])
}

/// The bracketed Newton iteration, one evaluation per [`Newton::step`].
pub(crate) struct Newton<'a> {
    pub p: &'a Prepared,
    pub q12: Sym3,
    pub lo: f64,
    pub hi: f64,
    pub lambda: f64,
    pub iterations: u32,
}

impl<'a> Newton<'a> {
    /// Starts from the two-sphere maximiser; `a = rᵀQ1⁻¹r`, `b = rᵀQ2⁻¹r`, both > 0.
    #[inline(always)]
    pub fn new(p: &'a Prepared, a: f64, b: f64) -> Self {
        let (sa, sb) = (a.sqrt(), b.sqrt());
        let q12 = std::array::from_fn(|k| p.q2[k] - p.q1[k]);
        Self {
            p,
            q12,
            lo: 0.0,
            hi: 1.0,
            lambda: sb / (sa + sb),
            iterations: 0,
        }
    }

    /// Evaluates at the current λ, narrows the bracket and moves λ to the next
    /// iterate. Returns the evaluation and where the iteration stands: [`Step::Converged`]
    /// once the predicted gain is below [`GAIN_TOL`] (or `g = 0`), [`Step::Stuck`] when
    /// the Newton step rounds back to λ without that.
    #[inline(always)]
    pub fn step(&mut self) -> Result<(Eval, Step), ContactError> {
        let e = Eval::at(self.lambda, &self.p.r, &self.p.q1, &self.p.q2, &self.q12)?;
        self.iterations += 1;
        if !(e.g.is_finite() && e.gp.is_finite()) {
            return Err(ContactError::Overflow {
                what: "the residual g(λ)",
            });
        }
        if e.g < 0.0 {
            self.lo = e.lambda;
        } else if e.g > 0.0 {
            self.hi = e.lambda;
        } else {
            return Ok((e, Step::Converged));
        }
        let newton = e.lambda - e.g / e.gp;
        let inside = e.gp > 0.0 && newton >= self.lo && newton <= self.hi;
        let step = if e.gp > 0.0 && e.gain() <= GAIN_TOL * e.f {
            Step::Converged
        } else if newton == e.lambda {
            Step::Stuck
        } else {
            Step::Going
        };
        self.lambda = if inside {
            newton
        } else if step != Step::Going {
            e.lambda
        } else {
            0.5 * (self.lo + self.hi)
        };
        Ok((e, step))
    }
}

/// Where [`Newton::step`] left the iteration.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub(crate) enum Step {
    /// Not finished: evaluate again at the new λ.
    Going,
    /// The gain test met: `f + g²/(2g′)` is μ² to [`GAIN_TOL`]'s truncation.
    Converged,
    /// The Newton step rounds back to λ but the gain is not small: λ* lies within
    /// half an ulp of λ where `f` still rises by more than [`GAIN_TOL`] (an end, where
    /// the doubles near 1 are 2^53 times coarser than near 0), so `f + g²/(2g′)` is no
    /// estimate of μ² (`docs/reliability.md`, defect 19).
    Stuck,
}
