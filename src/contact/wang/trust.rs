//! A bound on the error of `P(s) = det(sA + (1−s)B)` as computed from the coefficients
//! of [`super::quartic`], so that a decision is taken only where the rounding cannot
//! have turned it.
//!
//! `(1−s)⁴ p(−s/(1−s)) = det(−sA − (1−s)B) = det M(s)`, `M(s) = sA + (1−s)B`, with
//! `A = [[P1, 0], [0, −1]]`, `B = [[P2, −u], [−uᵀ, rᵀu − 1]]`, `Pi = Qi⁻¹`, `u = P2 r`.
//! Everything the coefficients are made of is bounded entrywise:
//! - `Pi = adj Qi / det Qi`: each entry of the adjugate errs by `2ε` times the same
//!   minor with absolute values (`[adj]`, which may be `κ` times `|adj|` for a thin
//!   form), and `det Qi` by `4 τ_i ε` relative, `τ_i = per|Qi| / det Qi` (the permanent
//!   of `|Qi|` over the determinant, ≥ 1, a condition number of the determinant). So
//!   `|ΔPi| ≤ ε (ADJUGATE_ERR [adj] + DET_ERR τ_i |adj|) / det Qi` entrywise, around
//!   the computed `Pi`;
//! - `u` and `rᵀu` inherit `ΔP2` through `|r|`, plus their own dot-product roundings.
//!
//! A perturbation `Δ` of the entries of `M` moves its determinant by at most
//! `per(|M| + Δ) − per(|M|)` (every product of the expansion, to all orders), and the
//! polynomial arithmetic on the way (forming the coefficients, the change of basis and
//! the evaluation in [`super::negative_axis`]) errs by at most `ARITH_ERR · ε` times
//! `per(|M| + Δ)`. Both are quartics in `s` with non-negative coefficients in the
//! basis `s^k (1−s)^{4−k}`, computed here.

use crate::contact::sym::{adjugate, det};
use crate::contact::{Sym3, Vec3};

/// Error of an adjugate entry (two products and a difference: `2ε [adj]`), and of
/// its division by the determinant, in units of `ε [adj] / det`, with a margin of two.
const ADJUGATE_ERR: f64 = 6.0;

/// Relative error of `det Qi` (a three-term dot product of the adjugate's first row:
/// `4ε τ`, to first order) passed on to `Pi`, in units of `ε τ |adj| / det`, with a
/// margin of two.
const DET_ERR: f64 = 8.0;

/// Rounding of the polynomial arithmetic in units of `ε · per(|M(s)| + Δ)`: the
/// coefficients of `det(λA − B)` go through about a dozen operations each
/// (`pencil_coefficients`, then the product with `s0 − λ`), the change to the basis of
/// `s` and its evaluation through a dozen more; 64 is twice their sum.
const ARITH_ERR: f64 = 64.0;

/// The coefficients `e_k ≥ 0` of a bound `Σ e_k s^k (1−s)^{4−k}` on the error of the
/// computed `P(s)` for the (rescaled) pair, or `None` where the bound is not finite
/// (a form too ill-conditioned for its inverse to mean anything).
pub(super) fn error_bound(r: &Vec3, q1: &Sym3, q2: &Sym3) -> Option<[f64; 5]> {
    let (p1, e1) = inverse_bounds(q1)?;
    let (p2, e2) = inverse_bounds(q2)?;
    let ra = r.map(f64::abs);
    let mul = |m: &Sym3, x: &Vec3| -> Vec3 {
        [
            m[0] * x[0] + m[1] * x[1] + m[2] * x[2],
            m[1] * x[0] + m[3] * x[1] + m[4] * x[2],
            m[2] * x[0] + m[4] * x[1] + m[5] * x[2],
        ]
    };
    let dot = |a: &Vec3, b: &Vec3| a[0] * b[0] + a[1] * b[1] + a[2] * b[2];
    // |u| ≤ |P2||r|, and its error: ΔP2 through |r|, plus a three-term dot product.
    let (u, du) = (mul(&p2, &ra), mul(&e2, &ra));
    let du: Vec3 = std::array::from_fn(|i| du[i] + 4.0 * f64::EPSILON * u[i]);
    // The corner rᵀP2r − 1: its size and its error (ΔP2, a six-term sum, the 1).
    let rho = dot(&ra, &u);
    let corner = rho + 1.0;
    let d_corner = dot(&ra, &mul(&e2, &ra)) + 8.0 * f64::EPSILON * corner;

    // Entries of |M(s)| as [coefficient of s, coefficient of 1 − s], and with Δ added.
    let mut m = [[[0.0; 2]; 4]; 4];
    let mut md = m;
    let idx = |i: usize, j: usize| [[0, 1, 2], [1, 3, 4], [2, 4, 5]][i][j];
    for i in 0..3 {
        for j in 0..3 {
            let k = idx(i, j);
            m[i][j] = [p1[k], p2[k]];
            md[i][j] = [p1[k] + e1[k], p2[k] + e2[k]];
        }
        m[i][3] = [0.0, u[i]];
        m[3][i] = m[i][3];
        md[i][3] = [0.0, u[i] + du[i]];
        md[3][i] = md[i][3];
    }
    m[3][3] = [1.0, corner];
    md[3][3] = [1.0, corner + d_corner];
    let (plain, perturbed) = (permanent(&m), permanent(&md));
    let bound: [f64; 5] = std::array::from_fn(|k| {
        (perturbed[k] - plain[k]).max(0.0) + ARITH_ERR * f64::EPSILON * perturbed[k]
    });
    bound.iter().all(|e| e.is_finite()).then_some(bound)
}

/// `(|P̂|, ΔP)` entrywise for the computed `P̂ = adj Q / det Q` (module docs), or `None`
/// if `det Q` as computed is not positive or the bounds are not finite.
fn inverse_bounds(q: &Sym3) -> Option<(Sym3, Sym3)> {
    let adj = adjugate(q);
    let d = det(q, &adj);
    let a = q.map(f64::abs);
    let abs_adj = [
        a[3] * a[5] + a[4] * a[4],
        a[2] * a[4] + a[1] * a[5],
        a[1] * a[4] + a[2] * a[3],
        a[0] * a[5] + a[2] * a[2],
        a[1] * a[2] + a[0] * a[4],
        a[0] * a[3] + a[1] * a[1],
    ];
    let per = a[0] * abs_adj[0] + a[1] * abs_adj[1] + a[2] * abs_adj[2];
    if !(d > 0.0) {
        return None;
    }
    let tau = per / d;
    let size = adj.map(|x| x.abs() / d);
    let err: Sym3 = std::array::from_fn(|k| {
        let adj_k = adj[k].abs() + 2.0 * f64::EPSILON * abs_adj[k];
        f64::EPSILON * (ADJUGATE_ERR * abs_adj[k] + DET_ERR * tau * adj_k) / d
    });
    (size.iter().chain(&err).all(|x| x.is_finite())).then_some((size, err))
}

/// The permanent of a 4×4 matrix whose entries are `a s + b (1−s)` (given as
/// `[a, b]`, all ≥ 0), as coefficients of `s^k (1−s)^{4−k}`.
fn permanent(m: &[[[f64; 2]; 4]; 4]) -> [f64; 5] {
    fn walk(m: &[[[f64; 2]; 4]; 4], row: usize, used: u8, poly: [f64; 5], out: &mut [f64; 5]) {
        if row == 4 {
            for k in 0..5 {
                out[k] += poly[k];
            }
            return;
        }
        for (col, &[a, b]) in m[row].iter().enumerate() {
            if used & (1 << col) != 0 || (a == 0.0 && b == 0.0) {
                continue;
            }
            let mut next = [0.0; 5];
            for k in 0..=row {
                next[k] += poly[k] * b;
                next[k + 1] += poly[k] * a;
            }
            walk(m, row + 1, used | (1 << col), next, out);
        }
    }
    let mut out = [0.0; 5];
    walk(m, 0, 0, [1.0, 0.0, 0.0, 0.0, 0.0], &mut out);
    out
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The permanent of `diag(s, s, 1−s, 1−s)`-like and all-ones matrices.
    #[test]
    fn permanent_of_simple_pencils() {
        let mut m = [[[0.0; 2]; 4]; 4];
        for (i, row) in m.iter_mut().enumerate() {
            row[i] = if i < 2 { [1.0, 0.0] } else { [0.0, 1.0] };
        }
        assert_eq!(permanent(&m), [0.0, 0.0, 1.0, 0.0, 0.0]);
        // All entries s + (1−s) = 1: the permanent is 4! = 24, as Σ C(4,k) s^k(1−s)^{4−k}.
        let ones = [[[1.0, 1.0]; 4]; 4];
        assert_eq!(permanent(&ones), [24.0, 96.0, 144.0, 96.0, 24.0]);
    }
}
