//! The Perram–Wertheim (1985) contact function, by safeguarded Newton iteration.
//!
//! `f(λ) = λ(1−λ) rᵀ Q(λ)⁻¹ r` with `Q(λ) = (1−λ)Q1 + λQ2` is concave on `[0, 1]` (a
//! minimum of functions affine in λ) and vanishes at both ends, so its maximiser λ* is
//! the unique root of the residual `g = −f′ = (2λ−1) rᵀs + λ(1−λ) sᵀu`, with
//! `s = Q⁻¹r`, `u = (Q2−Q1)s`, and `g′ = 2rᵀs + 2(1−2λ)sᵀu − 2λ(1−λ)uᵀQ⁻¹u > 0`
//! (pw85 manual, "Optimization of the function f"). The iteration starts from the
//! maximiser for two spheres, `λ₀ = √b / (√a + √b)` with `a = rᵀQ1⁻¹r`, `b = rᵀQ2⁻¹r`,
//! keeps a bracket `[lo, hi]` on the sign of `g`, and falls back to bisection when a
//! Newton step leaves it.

use super::bernstein::Rational;
use super::dd::{two_prod, Acc};
use super::ldl::Ldl;
use super::scale::Prepared;
use super::sym::{dot, sym_mul};
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
/// the iteration ends without evaluating the derivatives again: what is left,
/// `~1e-18` times the local constant, is far below [`GAIN_TOL`].
pub const HALLEY_FINAL_GAIN: f64 = 1e-6;

/// The corrector (Newton on the refined residual) stops when its predicted gain is at
/// most `CORRECTOR_GAIN_TOL · f`. The gain is added, so what is left is the third-order
/// remainder, `K · gain^{3/2}` with `K` up to ~1e3 when λ* is within 1e-6 of 0 or 1
/// (measured on the reference set); `CORRECTOR_GAIN_TOL = ε` keeps that below ε/10.
/// Predictor steps leave the first corrector step far below this on most pairs.
pub const CORRECTOR_GAIN_TOL: f64 = f64::EPSILON;

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
        let m = 1.0 - lambda;
        let (q, ldl) = factor_at(lambda, q1, q2)?;
        let s = ldl.solve(r);
        let rs = dot(r, &s);
        let u = sym_mul(q12, &s);
        let su = dot(&s, &u);
        let uv = ldl.quadratic_form(&u);
        let lm = lambda * m;
        Ok(Self {
            lambda,
            f: lm * rs,
            g: (2.0 * lambda - 1.0) * rs + lm * su,
            gp: 2.0 * rs + 2.0 * (1.0 - 2.0 * lambda) * su - 2.0 * lm * uv,
            ldl,
            q,
        })
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

/// `Q(λ) = (1−λ)Q1 + λQ2` in double precision, and its factors.
///
/// A convex combination of two positive-definite matrices is positive definite, so
/// failure here means rounding at the edge of [`MIN_RELATIVE_PIVOT`](super::MIN_RELATIVE_PIVOT).
#[inline(always)]
pub(crate) fn factor_at(lambda: f64, q1: &Sym3, q2: &Sym3) -> Result<(Sym3, Ldl), ContactError> {
    let m = 1.0 - lambda;
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
    /// iterate. Returns the evaluation and whether the iteration has converged (the
    /// predicted gain is below [`GAIN_TOL`], or λ can no longer move).
    #[inline(always)]
    pub fn step(&mut self) -> Result<(Eval, bool), ContactError> {
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
            return Ok((e, true));
        }
        let newton = e.lambda - e.g / e.gp;
        let inside = e.gp > 0.0 && newton >= self.lo && newton <= self.hi;
        let done = (e.gp > 0.0 && e.gain() <= GAIN_TOL * e.f) || newton == e.lambda;
        self.lambda = if inside {
            newton
        } else if done {
            e.lambda
        } else {
            0.5 * (self.lo + self.hi)
        };
        Ok((e, done))
    }
}

/// The contact function μ² of two ellipsoids and its maximiser λ, in double precision.
///
/// Relative error about `ε · cond(Q(λ*))`: a few ulps for moderate shapes, up to
/// ~1e-8 for aspect ratios of 1e4. Use [`contact_function`] when that matters.
pub fn contact_function_fast(r12: &Vec3, q1: &Sym3, q2: &Sym3) -> Result<Contact, ContactError> {
    solve(r12, q1, q2, false)
}

/// The Perram–Wertheim contact function μ² of two ellipsoids, and its maximiser λ.
///
/// `μ² = max_{λ∈[0,1]} λ(1−λ) r12ᵀ[(1−λ)Q1 + λQ2]⁻¹ r12` (Perram & Wertheim 1985): μ
/// is the common factor by which both ellipsoids must be scaled about their centres to
/// touch, so `μ² < 1` means overlap and `μ² > 1` apart. λ comes from the Newton
/// iteration of [`contact_function_fast`]; `f(λ)` is then re-evaluated with
/// double-double residuals, so the relative error of μ² stays at a few ulps even
/// when `Q(λ*)` is badly conditioned.
///
/// `r12 = 0` gives `μ² = 0`, `λ = ½`, [`Stop::Exact`]. Inputs are rescaled by powers
/// of two, so μ² underflows gracefully towards 0 and overflows as an error.
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

#[inline(always)]
fn solve(r12: &Vec3, q1: &Sym3, q2: &Sym3, accurate: bool) -> Result<Contact, ContactError> {
    let p = Prepared::new(r12, q1, q2)?;
    if p.r == [0.0; 3] {
        return Ok(Contact {
            mu2: 0.0,
            lambda: 0.5,
            stop: Stop::Exact,
            iterations: 0,
        });
    }
    let (a, b) = (p.l1.quadratic_form(&p.r), p.l2.quadratic_form(&p.r));
    let rational = Rational::new(&p.r, &p.q1, &p.q2, [p.l1.det(), p.l2.det(), a, b]);
    let (sa, sb) = (a.sqrt(), b.sqrt());
    let (mut lo, mut hi, mut t) = (0.0, 1.0, sb / (sa + sb));
    let mut iterations = 0;
    let mut stop = Stop::MaxIterations;
    while iterations < MAX_ITERATIONS {
        iterations += 1;
        let [d1, d2, d3] = rational.log_derivatives(t);
        // One test for all three: a NaN or infinity in any makes the sum non-finite.
        if !(d1 + d2 + d3).is_finite() {
            return Err(ContactError::Overflow {
                what: "the derivatives of ln f(λ)",
            });
        }
        if d1 > 0.0 {
            lo = t;
        } else if d1 < 0.0 {
            hi = t;
        }
        // φ = ln f is concave: φ″ < 0 unless rounding flattened it.
        let curvature = -d2;
        let halley_denominator = 2.0 * d2 * d2 - d1 * d3;
        let halley = t - 2.0 * d1 * d2 / halley_denominator;
        let halley_ok = halley_denominator > 0.0 && halley >= lo && halley <= hi;
        let newton = t + d1 / curvature;
        let next = if halley_ok {
            halley
        } else if curvature > 0.0 && newton >= lo && newton <= hi {
            newton
        } else {
            0.5 * (lo + hi)
        };
        // The Newton model's gain in φ, φ′²/(2|φ″|), is the relative gain in f still to
        // come. Below GAIN_TOL the step just computed finishes the job; below
        // HALLEY_FINAL_GAIN so does a Halley step.
        let gain2 = d1 * d1; // 2 |φ″| × gain
        let converged = d1 == 0.0
            || (curvature > 0.0
                && (gain2 <= 2.0 * GAIN_TOL * curvature
                    || (halley_ok && gain2 <= 2.0 * HALLEY_FINAL_GAIN * curvature)));
        let stalled = next == t || hi - lo <= f64::EPSILON * hi;
        t = next;
        if converged || stalled {
            stop = Stop::Converged;
            break;
        }
    }
    if !accurate || stop != Stop::Converged {
        return p.finish(rational.f(t), t, stop, iterations);
    }
    // Corrector: Newton on the refined residual, bracketed afresh (the predictor's
    // bracket rests on the rational form's rounding), until the refined gain is below
    // CORRECTOR_GAIN_TOL. One step is the rule; near λ = 0 or 1 the predictor can be off by a
    // few per cent and it takes two or three.
    let (mut lo, mut hi) = (0.0, 1.0);
    let mut lambda = t;
    for _ in 0..MAX_ITERATIONS {
        iterations += 1;
        let (f, g, gp) = refined(lambda, &p.r, &p.q1, &p.q2)?;
        if !(gp > 0.0) {
            return p.finish(f, lambda, Stop::Converged, iterations);
        }
        let step = g / gp;
        let gain = 0.5 * g * step;
        if gain <= CORRECTOR_GAIN_TOL * f {
            let polished = (lambda - step).clamp(lo, hi);
            return p.finish(f + gain, polished, Stop::Converged, iterations);
        }
        if g > 0.0 {
            hi = lambda;
        } else {
            lo = lambda;
        }
        let next = lambda - step;
        lambda = if next > lo && next < hi {
            next
        } else {
            0.5 * (lo + hi)
        };
    }
    let (f, _, _) = refined(lambda, &p.r, &p.q1, &p.q2)?;
    p.finish(f, lambda, Stop::MaxIterations, iterations)
}

/// `f(λ)` to a few ulps whatever the conditioning of `Q(λ)`, the residual
/// `g(λ) = (2λ−1) rᵀs + λ(1−λ) sᵀu` from the refined `s` (`u = (Q2−Q1)s`), and
/// `g′(λ) = 2rᵀs + 2(1−2λ) sᵀu − 2λ(1−λ) uᵀQ⁻¹u` in double.
///
/// `Q(λ)` is formed in double-double (`hi + lo`, exact products); `s₀ = hi⁻¹ r` (LDLᵀ)
/// is refined against the exact residual `ρ = r − Q s₀` (mixed-precision iterative
/// refinement), so that `rᵀQ⁻¹r = rᵀs₀ + s₀ᵀρ + e₀ᵀρ` with `e₀ = hi⁻¹ρ` errs by
/// `O((ε cond Q)²)` instead of `O(ε cond Q)`.
#[inline(always)]
fn refined(lambda: f64, r: &Vec3, q1: &Sym3, q2: &Sym3) -> Result<(f64, f64, f64), ContactError> {
    let m = 1.0 - lambda;
    let mut hi = [0.0; 6];
    let mut lo = [0.0; 6];
    for k in 0..6 {
        let mut acc = Acc::new(0.0);
        acc.add_prod(m, q1[k]);
        acc.add_prod(lambda, q2[k]);
        (hi[k], lo[k]) = acc.pair();
    }
    let ldl = Ldl::factor(&hi).map_err(|(pivot, value)| ContactError::NotPositiveDefinite {
        what: "(1−λ)q1 + λq2",
        pivot,
        value,
    })?;
    let s0 = ldl.solve(r);
    const IDX: [[usize; 3]; 3] = [[0, 1, 2], [1, 3, 4], [2, 4, 5]];
    let mut rho = [0.0; 3];
    for i in 0..3 {
        let mut acc = Acc::new(r[i]);
        for j in 0..3 {
            acc.add_prod(-hi[IDX[i][j]], s0[j]);
            acc.lo -= lo[IDX[i][j]] * s0[j];
        }
        rho[i] = acc.value();
    }
    let e0 = ldl.solve(&rho);
    let mut rs = Acc::new(0.0);
    for i in 0..3 {
        rs.add_prod(r[i], s0[i]);
    }
    rs.lo += dot(&s0, &rho) + dot(&e0, &rho);
    let (rs_hi, rs_lo) = rs.pair();
    let (p, pe) = two_prod(lambda, m);
    let mut f = Acc::new(0.0);
    f.add_prod(p, rs_hi);
    f.lo += p * rs_lo + pe * rs_hi;
    let s = [s0[0] + e0[0], s0[1] + e0[1], s0[2] + e0[2]];
    let q12: Sym3 = std::array::from_fn(|k| q2[k] - q1[k]);
    let u = sym_mul(&q12, &s);
    let su = dot(&s, &u);
    let g = (2.0 * lambda - 1.0) * rs_hi + p * su;
    let gp = 2.0 * rs_hi + 2.0 * (1.0 - 2.0 * lambda) * su - 2.0 * p * ldl.quadratic_form(&u);
    Ok((f.value(), g, gp))
}

#[cfg(test)]
mod timing {
    use super::*;
    use std::hint::black_box;

    /// Rough split of the cost of `contact_function` (run with `--ignored --nocapture`).
    #[test]
    #[ignore]
    fn split_of_the_cost() {
        let path = concat!(
            env!("CARGO_MANIFEST_DIR"),
            "/tests/data/contact_typical.csv"
        );
        let t = crate::io::cases::CaseTable::read(std::fs::File::open(path).unwrap()).unwrap();
        let cases: Vec<_> = (0..t.rows.len()).map(|i| t.case(i).unwrap()).collect();
        let time = |name: &str, f: &dyn Fn(&crate::io::cases::Case) -> f64| {
            let mut best = f64::MAX;
            for _ in 0..200 {
                let s = std::time::Instant::now();
                for c in &cases {
                    black_box(f(black_box(c)));
                }
                best = best.min(s.elapsed().as_nanos() as f64 / cases.len() as f64);
            }
            println!("{name:>12}: {best:6.1} ns");
        };
        time("prepare", &|c| {
            Prepared::new(&c.r12, &c.q1, &c.q2).unwrap().r[0]
        });
        time("+rational", &|c| {
            let p = Prepared::new(&c.r12, &c.q1, &c.q2).unwrap();
            let (a, b) = (p.l1.quadratic_form(&p.r), p.l2.quadratic_form(&p.r));
            Rational::new(&p.r, &p.q1, &p.q2, [p.l1.det(), p.l2.det(), a, b]).f(0.5)
        });
        time("fast", &|c| {
            contact_function_fast(&c.r12, &c.q1, &c.q2).unwrap().mu2
        });
        time("refined", &|c| {
            refined(0.4, &c.r12, &c.q1, &c.q2).unwrap().0
        });
        time("accurate", &|c| {
            contact_function(&c.r12, &c.q1, &c.q2).unwrap().mu2
        });
    }

    /// A fixed workload for instruction counts (`valgrind --tool=callgrind`): passes of
    /// the method named by `GRAINPACK_COUNT` (accurate or fast) over the typical set.
    #[test]
    #[ignore]
    fn instruction_count_workload() {
        let path = concat!(
            env!("CARGO_MANIFEST_DIR"),
            "/tests/data/contact_typical.csv"
        );
        let t = crate::io::cases::CaseTable::read(std::fs::File::open(path).unwrap()).unwrap();
        let cases: Vec<_> = (0..t.rows.len()).map(|i| t.case(i).unwrap()).collect();
        let passes: usize = std::env::var("GRAINPACK_PASSES").map_or(20, |v| v.parse().unwrap());
        let accurate = std::env::var("GRAINPACK_COUNT").map_or(true, |v| v == "accurate");
        for _ in 0..passes {
            for c in &cases {
                black_box(solve(black_box(&c.r12), &c.q1, &c.q2, accurate).unwrap());
            }
        }
    }
}
