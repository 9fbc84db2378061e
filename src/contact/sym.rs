//! Small algebra of symmetric 3×3 matrices stored as their upper triangle.

use super::{Sym3, Vec3};
use std::ops::{Add, Div, Mul, Neg, Sub};

/// What the small algebra here and the error-free transformations of [`super::dd`]
/// need of a number: `f64`, or [`super::lanes::F`] for eight pairs at once (the same
/// operations, so the same roundings, lane by lane).
pub(crate) trait Arith:
    Copy
    + Add<Output = Self>
    + Sub<Output = Self>
    + Mul<Output = Self>
    + Div<Output = Self>
    + Neg<Output = Self>
{
    /// `c` itself (in every lane).
    fn constant(c: f64) -> Self;
    /// `c · self`, rounded as that product is.
    fn times(self, c: f64) -> Self;
    /// `self · b + c`, rounded once (for `two_prod`, which uses it only where the
    /// target has FMA).
    #[cfg_attr(not(target_feature = "fma"), allow(dead_code))]
    fn mul_add(self, b: Self, c: Self) -> Self;
    /// `1 / self`.
    fn recip(self) -> Self;
    /// `|self|`.
    fn abs(self) -> Self;
}

impl Arith for f64 {
    #[inline(always)]
    fn constant(c: f64) -> Self {
        c
    }

    #[inline(always)]
    fn times(self, c: f64) -> Self {
        c * self
    }

    #[inline(always)]
    fn mul_add(self, b: Self, c: Self) -> Self {
        f64::mul_add(self, b, c)
    }

    #[inline(always)]
    fn recip(self) -> Self {
        1.0 / self
    }

    #[inline(always)]
    fn abs(self) -> Self {
        f64::abs(self)
    }
}

impl Arith for super::lanes::F {
    #[inline(always)]
    fn constant(c: f64) -> Self {
        Self::splat(c)
    }

    #[inline(always)]
    fn times(self, c: f64) -> Self {
        c * self
    }

    #[inline(always)]
    fn mul_add(self, b: Self, c: Self) -> Self {
        super::lanes::F::mul_add(self, b, c)
    }

    #[inline(always)]
    fn recip(self) -> Self {
        1.0 / self
    }

    #[inline(always)]
    fn abs(self) -> Self {
        super::lanes::F::abs(self)
    }
}

/// `Q u` for a symmetric `Q`.
/// The larger of `a` and `b`, as one `maxsd`: `b` if it is larger, else `a` (so a NaN
/// `b` is skipped, a NaN `a` kept). `f64::max`, which skips a NaN on either side, takes
/// three instructions; on the common path of the contact function, where the values
/// are finite, both give the same.
#[inline(always)]
pub(crate) fn larger(a: f64, b: f64) -> f64 {
    if b > a {
        b
    } else {
        a
    }
}

#[inline(always)]
pub(crate) fn sym_mul<T: Arith>(q: &[T; 6], u: &[T; 3]) -> [T; 3] {
    [
        q[0] * u[0] + q[1] * u[1] + q[2] * u[2],
        q[1] * u[0] + q[3] * u[1] + q[4] * u[2],
        q[2] * u[0] + q[4] * u[1] + q[5] * u[2],
    ]
}

#[inline(always)]
pub(crate) fn dot<T: Arith>(a: &[T; 3], b: &[T; 3]) -> T {
    a[0] * b[0] + a[1] * b[1] + a[2] * b[2]
}

/// Coefficients of the homogeneous forms `a(s, t) = xᵀ adj(sM0 + tM1) x = Σ a_k s^{2−k} t^k`
/// and `b(s, t) = det(sM0 + tM1) = Σ b_k s^{3−k} t^k` for symmetric `M0`, `M1`.
///
/// `det(sM0 + tM1) = s³ det M0 + s²t⟨adj M0, M1⟩ + st²⟨M0, adj M1⟩ + t³ det M1` and
/// `adj(sM0 + tM1) = s² adj M0 + st adj(M0, M1) + t² adj M1`, with `⟨·,·⟩` the Frobenius
/// product and `adj(·,·)` the polarised adjugate (each 2×2 minor differentiated).
/// `s = 1, t = λ` gives monomial coefficients; `s = 1 − λ, t = λ` the pencil between.
#[inline(always)]
pub(crate) fn pencil_coefficients(m0: &Sym3, m1: &Sym3, x: &Vec3) -> ([f64; 3], [f64; 4]) {
    let (adj0, adj1) = (adjugate(m0), adjugate(m1));
    let a = [
        quadratic_form(&adj0, x),
        quadratic_form(&polarised_adjugate(m0, m1), x),
        quadratic_form(&adj1, x),
    ];
    let b = [
        det(m0, &adj0),
        frobenius(&adj0, m1),
        frobenius(m0, &adj1),
        det(m1, &adj1),
    ];
    (a, b)
}

/// The matrix pieces of `adj(sM0 + tM1) = s² adj M0 + st M + t² adj M1`.
#[derive(Debug, Clone, Copy)]
pub(crate) struct PencilParts<T = f64> {
    /// `adj M0`.
    pub adj1: [T; 6],
    /// `adj M1`.
    pub adj2: [T; 6],
    /// The polarised (mixed) adjugate `M`.
    pub mixed: [T; 6],
}

impl<T: Arith> PencilParts<T> {
    #[inline(always)]
    pub fn new(m0: &[T; 6], m1: &[T; 6]) -> Self {
        Self {
            adj1: adjugate(m0),
            adj2: adjugate(m1),
            mixed: polarised_adjugate(m0, m1),
        }
    }

    /// `adj(sM0 + tM1)`.
    #[inline(always)]
    pub fn adjugate_at(&self, s: T, t: T) -> [T; 6] {
        let (ss, st, tt) = (s * s, s * t, t * t);
        let (a, m, b) = (&self.adj1, &self.mixed, &self.adj2);
        [
            ss * a[0] + st * m[0] + tt * b[0],
            ss * a[1] + st * m[1] + tt * b[1],
            ss * a[2] + st * m[2] + tt * b[2],
            ss * a[3] + st * m[3] + tt * b[3],
            ss * a[4] + st * m[4] + tt * b[4],
            ss * a[5] + st * m[5] + tt * b[5],
        ]
    }
}

/// Adjugate of a symmetric matrix, itself symmetric.
#[inline(always)]
pub(crate) fn adjugate<T: Arith>(m: &[T; 6]) -> [T; 6] {
    [
        m[3] * m[5] - m[4] * m[4],
        m[2] * m[4] - m[1] * m[5],
        m[1] * m[4] - m[2] * m[3],
        m[0] * m[5] - m[2] * m[2],
        m[1] * m[2] - m[0] * m[4],
        m[0] * m[3] - m[1] * m[1],
    ]
}

/// The polarised adjugate: the coefficient of `λ` in `adj(A + λB)`.
#[inline(always)]
pub(crate) fn polarised_adjugate<T: Arith>(a: &[T; 6], b: &[T; 6]) -> [T; 6] {
    [
        a[3] * b[5] + b[3] * a[5] - a[4].times(2.0) * b[4],
        a[2] * b[4] + b[2] * a[4] - a[1] * b[5] - b[1] * a[5],
        a[1] * b[4] + b[1] * a[4] - a[2] * b[3] - b[2] * a[3],
        a[0] * b[5] + b[0] * a[5] - a[2].times(2.0) * b[2],
        a[1] * b[2] + b[1] * a[2] - a[0] * b[4] - b[0] * a[4],
        a[0] * b[3] + b[0] * a[3] - a[1].times(2.0) * b[1],
    ]
}

/// `det m`, by cofactor expansion along the first row, given `adj m`.
#[inline(always)]
pub(crate) fn det(m: &Sym3, adj: &Sym3) -> f64 {
    m[0] * adj[0] + m[1] * adj[1] + m[2] * adj[2]
}

/// Frobenius product `⟨s, t⟩ = tr(s t)` of two symmetric matrices.
#[inline(always)]
pub(crate) fn frobenius<T: Arith>(s: &[T; 6], t: &[T; 6]) -> T {
    s[0] * t[0] + s[3] * t[3] + s[5] * t[5] + (s[1] * t[1] + s[2] * t[2] + s[4] * t[4]).times(2.0)
}

/// `xᵀ s x` for a symmetric `s`.
#[inline(always)]
pub(crate) fn quadratic_form<T: Arith>(s: &[T; 6], x: &[T; 3]) -> T {
    s[0] * x[0] * x[0]
        + s[3] * x[1] * x[1]
        + s[5] * x[2] * x[2]
        + (s[1] * x[0] * x[1] + s[2] * x[0] * x[2] + s[4] * x[1] * x[2]).times(2.0)
}
