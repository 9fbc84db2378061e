//! For [`super::robust`]: the seven Bernstein coefficients of `f` in double-double,
//! and the rank of a quadratic form that may be singular.
//!
//! The coefficients (see [`crate::contact::bernstein`]) are polynomials of degree 3 in
//! `Q` (and 2 in `r`). Every product of two doubles is taken exactly ([`two_prod`]) and
//! every sum in double-double, so each coefficient errs by about `ε²` times the size
//! of its terms before it is rounded to a double: `ε² cond(Q)` relative for the end
//! coefficients, `ε² κ` for the mixed ones (`κ` as in [`super::condition`]), far
//! below an ulp for every form the crate accepts. `f` is a sum of positive terms in
//! them, so it is then as accurate as its coefficients.

use crate::contact::dd::two_prod;
use crate::contact::{Sym3, Vec3};

/// Pivots of a form within `SINGULAR_PIVOT` times its largest diagonal entry of zero
/// count as zero: `2^-46 ≈ 1.4e-14` (64 ε), above the rounding of the pivots of a
/// singular form written in doubles (a few ε) and of the elimination (multipliers at
/// most 1 with diagonal pivoting). Such a form is taken as exactly singular: it is
/// thinner than its own rounding resolves, about `√SINGULAR_PIVOT ≈ 1.2e-7` of its size.
/// A pivot below `−SINGULAR_PIVOT` times the largest diagonal entry makes the form
/// indefinite.
pub const SINGULAR_PIVOT: f64 = 1.0 / (1u64 << 46) as f64;

/// What the rank decision of a form drops from it (`singular_form`): the entries its
/// factorisation leaves once the pivots run out that are at most `UNRESOLVED = ε²`
/// times its largest diagonal entry. The coefficients of `f` carry about `ε²` of the
/// size of their terms (module docs), so such entries cannot be part of a coefficient
/// that does not vanish with the rank; they can only be the whole of one that does
/// (a disc 1e-110 thick, a needle whose other entries are subnormal), where they would
/// decide which end `F` tends to (fuzz target `contact_bits`: μ² depended on the
/// order of the pair, λ was at the wrong end). The rounding of a singular form written
/// in doubles leaves entries of order ε, which are kept: the answers of the reference
/// pairs are unchanged, bitwise.
const UNRESOLVED: f64 = f64::EPSILON * f64::EPSILON;

/// A coefficient within `COEFFICIENT_RESOLUTION = 64 ε²` of the sum of its terms'
/// magnitudes is 0 to what its evaluation resolves: each of the ten or so double-double
/// operations on a path to it errs by a few `ε²` of their operands' magnitudes, and the
/// entries that [`singular_form`] drops (below [`UNRESOLVED`]) move a term of degree 3
/// in `Q` by `3ε²`. Its sign and size are rounding there, and they decided which order
/// `N` and `C` vanish to at an end: the same pair answered μ² in one order and an
/// overflow in the other (a needle of zero thickness with `r12` along it, the mixed
/// coefficient 3.9e-31 in one order and 0 in the other; defect 20 of
/// `docs/reliability.md`).
pub(super) const COEFFICIENT_RESOLUTION: f64 = 64.0 * f64::EPSILON * f64::EPSILON;

/// A double-double `hi + lo`, with `mag`, the sum of the magnitudes of the terms it was
/// summed from (in doubles: a bound on its own rounding, not a value).
#[derive(Debug, Clone, Copy)]
struct Dd {
    hi: f64,
    lo: f64,
    mag: f64,
}

impl Dd {
    const ZERO: Dd = Dd {
        hi: 0.0,
        lo: 0.0,
        mag: 0.0,
    };

    /// `a · b`, exactly.
    fn prod(a: f64, b: f64) -> Dd {
        let (hi, lo) = two_prod(a, b);
        Dd {
            hi,
            lo,
            mag: hi.abs(),
        }
    }

    /// `hi + lo` renormalised (`|lo| ≤ ulp(hi)/2`).
    fn norm(hi: f64, lo: f64, mag: f64) -> Dd {
        let s = hi + lo;
        Dd {
            hi: s,
            lo: lo - (s - hi),
            mag,
        }
    }

    fn add(self, o: Dd) -> Dd {
        let s = self.hi + o.hi;
        let bb = s - self.hi;
        let e = (self.hi - (s - bb)) + (o.hi - bb);
        Dd::norm(s, e + self.lo + o.lo, self.mag + o.mag)
    }

    fn sub(self, o: Dd) -> Dd {
        self.add(Dd {
            hi: -o.hi,
            lo: -o.lo,
            mag: o.mag,
        })
    }

    fn mul(self, o: Dd) -> Dd {
        let (p, e) = two_prod(self.hi, o.hi);
        Dd::norm(p, e + (self.hi * o.lo + self.lo * o.hi), self.mag * o.mag)
    }

    fn times(self, x: f64) -> Dd {
        let (p, e) = two_prod(self.hi, x);
        Dd::norm(p, e + self.lo * x, self.mag * x.abs())
    }

    fn value(self) -> f64 {
        self.hi + self.lo
    }

    /// [`Dd::value`], or 0 where that is within [`COEFFICIENT_RESOLUTION`] of `mag`.
    fn resolved(self) -> f64 {
        let v = self.value();
        if v.abs() <= COEFFICIENT_RESOLUTION * self.mag {
            0.0
        } else {
            v
        }
    }
}

/// `a·b − c·d`.
fn minor(a: f64, b: f64, c: f64, d: f64) -> Dd {
    Dd::prod(a, b).sub(Dd::prod(c, d))
}

/// The adjugate of a symmetric matrix (as [`crate::contact::sym`]'s `adjugate`).
fn adjugate(m: &Sym3) -> [Dd; 6] {
    [
        minor(m[3], m[5], m[4], m[4]),
        minor(m[2], m[4], m[1], m[5]),
        minor(m[1], m[4], m[2], m[3]),
        minor(m[0], m[5], m[2], m[2]),
        minor(m[1], m[2], m[0], m[4]),
        minor(m[0], m[3], m[1], m[1]),
    ]
}

/// The polarised adjugate: the coefficient of `λ` in `adj(a + λb)`.
fn polarised_adjugate(a: &Sym3, b: &Sym3) -> [Dd; 6] {
    let two = |x: Dd| x.times(2.0);
    let p = Dd::prod;
    [
        p(a[3], b[5]).add(p(b[3], a[5])).sub(two(p(a[4], b[4]))),
        p(a[2], b[4])
            .add(p(b[2], a[4]))
            .sub(p(a[1], b[5]))
            .sub(p(b[1], a[5])),
        p(a[1], b[4])
            .add(p(b[1], a[4]))
            .sub(p(a[2], b[3]))
            .sub(p(b[2], a[3])),
        p(a[0], b[5]).add(p(b[0], a[5])).sub(two(p(a[2], b[2]))),
        p(a[1], b[2])
            .add(p(b[1], a[2]))
            .sub(p(a[0], b[4]))
            .sub(p(b[0], a[4])),
        p(a[0], b[3]).add(p(b[0], a[3])).sub(two(p(a[1], b[1]))),
    ]
}

/// `⟨s, t⟩ = tr(s t)` of a symmetric matrix in double-double and one in doubles.
fn frobenius(s: &[Dd; 6], t: &Sym3) -> Dd {
    let diagonal = s[0].times(t[0]).add(s[3].times(t[3])).add(s[5].times(t[5]));
    let off = s[1].times(t[1]).add(s[2].times(t[2])).add(s[4].times(t[4]));
    diagonal.add(off.times(2.0))
}

/// `xᵀ s x`.
fn quadratic_form(s: &[Dd; 6], x: &Vec3) -> Dd {
    let w = [
        Dd::prod(x[0], x[0]),
        Dd::prod(x[0], x[1]),
        Dd::prod(x[0], x[2]),
        Dd::prod(x[1], x[1]),
        Dd::prod(x[1], x[2]),
        Dd::prod(x[2], x[2]),
    ];
    let diagonal = s[0].mul(w[0]).add(s[3].mul(w[3])).add(s[5].mul(w[5]));
    let off = s[1].mul(w[1]).add(s[2].mul(w[2])).add(s[4].mul(w[4]));
    diagonal.add(off.times(2.0))
}

/// `[A0, A1, A2]`, `[B0, B1, B2, B3]` of `f = λ(1−λ) a / b` (module docs), each
/// rounded once from double-double, and 0 where not resolved ([`COEFFICIENT_RESOLUTION`]).
pub(super) fn coefficients(r: &Vec3, q1: &Sym3, q2: &Sym3) -> ([f64; 3], [f64; 4]) {
    let (a, b) = coefficient_sums(r, q1, q2);
    (a.map(Dd::resolved), b.map(Dd::resolved))
}

/// The relative error of each of [`coefficients`] (`∞` for one that is 0): its rounding
/// to a double, `ε/2`, and its evaluation, [`COEFFICIENT_RESOLUTION`] of its terms.
pub(super) fn coefficient_errors(r: &Vec3, q1: &Sym3, q2: &Sym3) -> ([f64; 3], [f64; 4]) {
    let error = |d: Dd| 0.5 * f64::EPSILON + COEFFICIENT_RESOLUTION * d.mag / d.resolved().abs();
    let (a, b) = coefficient_sums(r, q1, q2);
    (a.map(error), b.map(error))
}

fn coefficient_sums(r: &Vec3, q1: &Sym3, q2: &Sym3) -> ([Dd; 3], [Dd; 4]) {
    let (adj1, adj2) = (adjugate(q1), adjugate(q2));
    let mixed = polarised_adjugate(q1, q2);
    let det = |m: &Sym3, adj: &[Dd; 6]| (0..3).fold(Dd::ZERO, |acc, k| acc.add(adj[k].times(m[k])));
    let a = [
        quadratic_form(&adj1, r),
        quadratic_form(&mixed, r),
        quadratic_form(&adj2, r),
    ];
    let b = [
        det(q1, &adj1),
        frobenius(&adj1, q2),
        frobenius(&adj2, q1),
        det(q2, &adj2),
    ];
    (a, b)
}

/// The rank of a symmetric positive semi-definite `q` whose largest diagonal entry is
/// in `[1, 2)` (or `q = 0`): the number of pivots of its LDLᵀ factorisation with
/// diagonal pivoting above [`SINGULAR_PIVOT`]. `None` if `q` is indefinite: a pivot
/// below `−SINGULAR_PIVOT`, or, once the remaining diagonal is negligible, an entry
/// beside it that is not.
pub(crate) fn rank(q: &Sym3) -> Option<usize> {
    singular_form(q).map(|(k, _)| k)
}

/// [`rank`], and the form of that rank `q` is taken for: `q` less the entries of the
/// part its factorisation leaves once the pivots run out (the Schur complement of the
/// pivots taken, at most [`SINGULAR_PIVOT`] in every entry) that are below what the
/// coefficients of `f` resolve, [`UNRESOLVED`]. `q` itself, bitwise, if it has full
/// rank, or that part is exactly 0 (a disc or needle written along the axes) or all of
/// it above `UNRESOLVED` (the rounding of a rotated one).
pub(crate) fn singular_form(q: &Sym3) -> Option<(usize, Sym3)> {
    let mut m = [[q[0], q[1], q[2]], [q[1], q[3], q[4]], [q[2], q[4], q[5]]];
    let scale = q[0].max(q[3]).max(q[5]).max(1.0);
    let tol = SINGULAR_PIVOT * scale;
    // An entry beside the diagonal is at most the geometric mean of its diagonal
    // neighbours in a semi-definite form; beyond that (and rounding) it is indefinite,
    // and the elimination below stays within the size of the diagonal.
    let bounded = |i: usize, j: usize| m[i][j] * m[i][j] <= m[i][i] * m[j][j] + tol;
    if !(bounded(0, 1) && bounded(0, 2) && bounded(1, 2)) {
        return None;
    }
    let (mut left, mut n) = ([0, 1, 2], 3);
    for k in 0..3 {
        let p = (0..n)
            .map(|i| left[i])
            .max_by(|&i, &j| m[i][i].total_cmp(&m[j][j]))
            .expect("one index left per pivot");
        let d = m[p][p];
        if !(d >= -tol) {
            return None;
        }
        let rest = &left[..n];
        if d <= tol {
            let negligible = rest
                .iter()
                .all(|&i| rest.iter().all(|&j| m[i][j].abs() <= tol));
            // The rows and columns of the pivots taken are those of q; the block of
            // the rest was q's less the Schur complement m left in it.
            let mut projected = *q;
            for &i in rest {
                for &j in rest.iter().filter(|&&j| j >= i) {
                    let at = SYM_INDEX[i][j];
                    if m[i][j].abs() <= UNRESOLVED * scale {
                        projected[at] = q[at] - m[i][j];
                    }
                }
            }
            return negligible.then_some((k, projected));
        }
        let at = rest.iter().position(|&i| i == p).expect("p is left");
        left.copy_within(at + 1..n, at);
        n -= 1;
        for &i in &left[..n] {
            for &j in &left[..n] {
                m[i][j] -= m[i][p] * m[p][j] / d;
            }
        }
    }
    Some((3, *q))
}

/// The index in a [`Sym3`] of the entry at row `i`, column `j`.
const SYM_INDEX: [[usize; 3]; 3] = [[0, 1, 2], [1, 3, 4], [2, 4, 5]];

#[cfg(test)]
mod tests {
    use super::*;
    use crate::contact::sym::pencil_coefficients;

    /// On a well-conditioned pair the double-double coefficients are those of the same
    /// algebra in doubles (`pencil_coefficients`, whose homogeneous coefficients are
    /// these) to a few ulps: cond < 10 here, so 8 ε covers the rounding of the doubles.
    #[test]
    fn coefficients_match_the_double_algebra_on_a_tame_pair() {
        let r = [0.7, -0.7, 1.1];
        let q1 = [4.0, 1.0, 0.5, 3.0, -0.2, 2.0];
        let q2 = [1.0, -0.3, 0.1, 2.0, 0.4, 0.5];
        let (a, b) = coefficients(&r, &q1, &q2);
        let (a_ref, b_ref) = pencil_coefficients(&q1, &q2, &r);
        for (x, y) in a.iter().zip(&a_ref).chain(b.iter().zip(&b_ref)) {
            assert!((x - y).abs() <= 8.0 * f64::EPSILON * y.abs(), "{x} {y}");
        }
    }

    /// A flat disc written exactly has `det = 0` exactly and a rank-one adjugate; a
    /// needle `v vᵀ` with short mantissas has a zero adjugate, exactly.
    #[test]
    fn singular_forms_give_exact_zeros() {
        let r = [0.3, 0.5, -0.25];
        let disc = [1.0, 0.0, 0.0, 1.0, 0.0, 0.0];
        let ball = [1.0, 0.0, 0.0, 1.0, 0.0, 1.0];
        let (a, b) = coefficients(&r, &disc, &ball);
        assert_eq!(b[0], 0.0);
        assert_eq!(a[0], r[2] * r[2]);
        let v = [0.75, -0.5, 0.375];
        let needle = [
            v[0] * v[0],
            v[0] * v[1],
            v[0] * v[2],
            v[1] * v[1],
            v[1] * v[2],
            v[2] * v[2],
        ];
        let (a, b) = coefficients(&r, &needle, &ball);
        assert_eq!((a[0], b[0], b[1]), (0.0, 0.0, 0.0));
        assert!(b[2] > 0.0 && a[1] > 0.0);
    }

    /// The entries a rank decision drops are those below [`UNRESOLVED`]: a needle's
    /// subnormal entries and a disc's 1e-221 thickness go, the rounding of a rotated
    /// needle (entries of order ε off its rank) stays, bitwise.
    #[test]
    fn singular_form_drops_only_what_the_coefficients_cannot_resolve() {
        let needle = [2.7e-315, 2.6e-315, 0.0, 0.0, 1.8e-317, 1.0];
        assert_eq!(
            singular_form(&needle),
            Some((1, [0.0, 0.0, 0.0, 0.0, 1.8e-317, 1.0]))
        );
        let disc = [1.0, 0.0, 0.0, 1e-8, 1.25e-221, 1.25e-221];
        let (k, flat) = singular_form(&disc).unwrap();
        assert_eq!((k, flat[5]), (2, 0.0));
        assert_eq!(flat[..5], disc[..5]);
        let h = 0.5;
        let rounded = [h, h, 0.0, h + f64::EPSILON, 0.0, 0.0];
        assert_eq!(singular_form(&rounded), Some((1, rounded)));
    }

    #[test]
    fn rank_counts_the_pivots_above_rounding() {
        assert_eq!(rank(&[1.0, 0.0, 0.0, 1.0, 0.0, 1.0]), Some(3));
        assert_eq!(rank(&[1.0, 0.0, 0.0, 1.0, 0.0, 0.0]), Some(2));
        assert_eq!(rank(&[1.0, 0.0, 0.0, 0.0, 0.0, 0.0]), Some(1));
        assert_eq!(rank(&[0.0; 6]), Some(0));
        // A needle along (1, 1, 0)/√2, rounded: rank one to rounding.
        let h = 0.5;
        assert_eq!(rank(&[h, h, 0.0, h, 0.0, 0.0]), Some(1));
        // A thin but definite form: pivot 1e-12 ≫ SINGULAR_PIVOT.
        assert_eq!(rank(&[1.0, 0.0, 0.0, 1.0, 0.0, 1e-12]), Some(3));
        // Indefinite: a negative pivot, or a zero diagonal beside a non-zero entry.
        assert_eq!(rank(&[1.0, 2.0, 0.0, 1.0, 0.0, 1.0]), None);
        assert_eq!(rank(&[1.0, 0.0, 0.0, 0.0, 0.5, 0.0]), None);
        assert_eq!(rank(&[1.0, 0.0, 0.0, 1.0, 0.0, -1e-3]), None);
    }
}
