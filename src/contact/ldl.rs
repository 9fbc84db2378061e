//! LDLᵀ factorisation of a symmetric 3×3 matrix, without square roots.
//!
//! `Q = L D Lᵀ` with `L` unit lower triangular and `D = diag(d0, d1, d2)`. For a
//! positive-definite `Q` all pivots are positive; this is how positive definiteness is
//! checked everywhere in the crate.

#[cfg(test)]
use super::sym::sym_mul;
use super::sym::{larger, Arith};
use super::Sym3;

/// Smallest accepted pivot relative to the largest diagonal entry of `Q`:
/// `d_k > MIN_RELATIVE_PIVOT · max_i Q_ii`. This bounds the condition number of an
/// accepted `Q` by about `1 / MIN_RELATIVE_PIVOT ≈ 1.1e12` (aspect ratios up to ~1e6).
/// Beyond that, `Q` is numerically singular for this purpose: rounding of order
/// `ε · cond` would swamp μ² (and the refined evaluation would not converge), so such
/// a matrix is rejected as not positive definite. `2^-40` is far above the rounding of
/// the pivots themselves (a few `ε · max Q_ii`). Definite forms within reach of it
/// (condition above [`FORM_MAX_CONDITION`](super::FORM_MAX_CONDITION)) are factored,
/// but the contact functions answer them by their robust path, as those below it.
pub const MIN_RELATIVE_PIVOT: f64 = 1.0 / (1u64 << 40) as f64;

/// The factors of `Q = L D Lᵀ`, with the reciprocals of the pivots.
#[derive(Debug, Clone, Copy)]
pub(crate) struct Ldl<T = f64> {
    l10: T,
    l20: T,
    l21: T,
    /// Pivots `d0, d1, d2`.
    pub d: [T; 3],
    inv_d: [T; 3],
}

impl Ldl {
    /// Factors `q`, or returns the index and value of the first pivot that is not
    /// positive (NaN included) or is below [`MIN_RELATIVE_PIVOT`].
    #[inline(always)]
    pub fn factor(q: &Sym3) -> Result<Self, (usize, f64)> {
        let floor = pivot_floor(q);
        let l = Self::unchecked(q);
        match l.d.iter().position(|&d| !(d > floor)) {
            Some(k) => Err((k, l.d[k])),
            None => Ok(l),
        }
    }

    /// The factors of `q` and whether [`Ldl::factor`] accepts them, without its
    /// `Result`: on the contact function's common path that went through memory, and
    /// reading it back stalled on store forwarding.
    #[inline(always)]
    pub fn factor_flagged(q: &Sym3) -> (Self, bool) {
        let floor = pivot_floor(q);
        let l = Self::unchecked(q);
        let [d0, d1, d2] = l.d;
        (l, (d0 > floor) & (d1 > floor) & (d2 > floor))
    }

    /// The factors of `s Q`: `L` is unchanged, the pivots scale by `s`.
    #[inline(always)]
    pub fn scaled(&self, s: f64) -> Self {
        Self {
            d: self.d.map(|d| d * s),
            inv_d: self.inv_d.map(|i| i / s),
            ..*self
        }
    }
}

/// The pivot below which [`Ldl::factor`] rejects `q`. A NaN on the diagonal makes a
/// pivot NaN, which is rejected whatever the floor, so [`larger`] will do.
#[inline(always)]
pub(crate) fn pivot_floor(q: &Sym3) -> f64 {
    MIN_RELATIVE_PIVOT * larger(larger(q[0], q[3]), q[5])
}

impl<T: Arith> Ldl<T> {
    /// The factors of `q` whatever its pivots ([`Ldl::factor`] checks them).
    #[inline(always)]
    pub fn unchecked(q: &[T; 6]) -> Self {
        let d0 = q[0];
        let i0 = d0.recip();
        let l10 = q[1] * i0;
        let l20 = q[2] * i0;
        let d1 = q[3] - l10 * q[1];
        let i1 = d1.recip();
        let e = q[4] - l20 * q[1];
        let l21 = e * i1;
        let d2 = q[5] - l20 * q[2] - l21 * e;
        Self {
            l10,
            l20,
            l21,
            d: [d0, d1, d2],
            inv_d: [i0, i1, d2.recip()],
        }
    }

    /// `det Q = d0 d1 d2`.
    #[inline(always)]
    pub fn det(&self) -> T {
        self.d[0] * self.d[1] * self.d[2]
    }

    /// `xᵀ Q⁻¹ x`, by forward substitution only: `Σ y_k² / d_k` with `L y = x`.
    #[inline(always)]
    pub fn quadratic_form(&self, x: &[T; 3]) -> T {
        let y = self.forward(x);
        y[0] * y[0] * self.inv_d[0] + y[1] * y[1] * self.inv_d[1] + y[2] * y[2] * self.inv_d[2]
    }

    /// `Q⁻¹ x`.
    #[inline(always)]
    pub fn solve(&self, x: &[T; 3]) -> [T; 3] {
        let y = self.forward(x);
        let z2 = y[2] * self.inv_d[2];
        let z1 = y[1] * self.inv_d[1] - self.l21 * z2;
        let z0 = y[0] * self.inv_d[0] - self.l10 * z1 - self.l20 * z2;
        [z0, z1, z2]
    }

    /// `y` with `L y = x`.
    #[inline(always)]
    fn forward(&self, x: &[T; 3]) -> [T; 3] {
        let y0 = x[0];
        let y1 = x[1] - self.l10 * y0;
        let y2 = x[2] - self.l20 * y0 - self.l21 * y1;
        [y0, y1, y2]
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn solve_inverts_a_positive_definite_matrix() {
        let q = [4.0, 1.0, 0.5, 3.0, -0.2, 2.0];
        let x = [1.0, -2.0, 0.25];
        let s = Ldl::factor(&q).unwrap().solve(&x);
        let back = sym_mul(&q, &s);
        // Q is well conditioned (cond < 4), so a few ulps of |x| is the right tolerance.
        for k in 0..3 {
            assert!(
                (back[k] - x[k]).abs() < 8.0 * f64::EPSILON * 4.0,
                "{back:?}"
            );
        }
    }

    #[test]
    fn factor_rejects_indefinite_singular_and_nan_matrices() {
        assert_eq!(
            Ldl::factor(&[-1.0, 0.0, 0.0, 1.0, 0.0, 1.0]).unwrap_err().0,
            0
        );
        assert_eq!(
            Ldl::factor(&[1.0, 2.0, 0.0, 1.0, 0.0, 1.0]).unwrap_err().0,
            1
        );
        assert_eq!(
            Ldl::factor(&[1.0, 0.0, 0.0, 1.0, 0.0, 0.0]).unwrap_err().0,
            2
        );
        // Rank one: pivots beyond the first are rounding noise.
        let v = [0.3, 0.7, 0.1];
        let rank_one = [
            v[0] * v[0],
            v[0] * v[1],
            v[0] * v[2],
            v[1] * v[1],
            v[1] * v[2],
            v[2] * v[2],
        ];
        assert!(Ldl::factor(&rank_one).is_err());
        assert!(Ldl::factor(&[f64::NAN, 0.0, 0.0, 1.0, 0.0, 1.0]).is_err());
    }
}
