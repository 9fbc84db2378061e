//! [`Refiner::at`] for eight pairs at once.

use super::*;
use crate::contact::lanes::{Mask, F, LANES};

/// Eight pairs, one per lane, as [`at_lanes`] reads them: what a [`Refiner`] refers to.
pub(crate) struct LanePairs {
    pub r: [F; 3],
    pub q1: [F; 6],
    pub q2: [F; 6],
    /// The scaled coefficients of `b(λ) = det Q(λ)`.
    pub b: [F; 4],
    pub parts: PencilParts<F>,
    pub start: Start<F>,
}

/// [`Refiner::at`] for eight pairs at once, lane `k` at `lambda[k]`: bitwise the same
/// values, with both of its ways computed and the one that applies kept. The mask is
/// clear where `at` gives `None`.
#[inline(always)]
pub(crate) fn at_lanes(pairs: &LanePairs, lambda: F) -> ([Refined; LANES], Mask) {
    let (t, s) = (lambda, 1.0 - lambda);
    let LanePairs {
        r,
        q1,
        q2,
        b,
        parts,
        start,
    } = pairs;
    let q12 = &start.q12;
    let beta = cubic(b, t, 1.0 - t);
    let (ss, st, tt) = (s * s, s * t, t * t);
    let [v0, vm, v2] = &start.v;
    let x: [F; 3] = std::array::from_fn(|i| ss * v0[i] + st * vm[i] + tt * v2[i]);
    let rho = scaled_residual(beta, r, s, t, q1, q2, &x);
    let inv = 1.0 / beta;
    let (bi, bie) = two_prod(beta, inv);
    let inv_lo = ((1.0 - bi) - bie) * inv;
    let adj = parts.adjugate_at(s, t).map(|a| a * start.inv_unit);
    let (p, pe) = two_prod(t, s);
    let once = Acc::from_prod(p, inv);
    let mut scale = Acc::from_prod(once.hi, inv);
    scale.lo = scale.lo + ((once.lo + p * inv_lo + pe * inv) * inv + once.hi * inv_lo);
    let u = sym_mul(q12, &x);
    let w = sym_mul(&adj, &u);
    let (uw, wdw) = (dot(&u, &w), dot(&w, &sym_mul(q12, &w)));
    let (i2, i3) = (inv * inv, inv * inv * inv);
    let mut rx = Acc::from_prod(r[0], x[0]);
    rx.add_prod(r[1], x[1]);
    rx.add_prod(r[2], x[2]);
    let mut num = Acc::from_prod(beta, rx.hi);
    num.lo = num.lo + (beta * rx.lo + dot(&x, &rho));
    let tr_adj = adj[0] + adj[3] + adj[5];
    let negligible = (dot(&rho, &rho) * tr_adj).le(NEGLIGIBLE_SECOND_ORDER * beta * num.hi);
    // The way of `at` when the second-order term is negligible...
    let mut f = Acc::from_prod(scale.hi, num.hi);
    f.lo = f.lo + (scale.hi * num.lo + scale.lo * num.hi);
    let su = dot(&x, &u) * i2;
    let plain = (f.value(), rx.hi * inv, su);
    // ...and when it is not.
    let e0 = sym_mul(&adj, &rho);
    let second = dot(&e0, &rho) * inv;
    let accepted = second.abs().le(REFINEMENT_TOL * num.hi);
    num.lo = num.lo + second;
    let mut f = Acc::from_prod(scale.hi, num.hi);
    f.lo = f.lo + (scale.hi * num.lo + scale.lo * num.hi);
    let x1: [F; 3] = std::array::from_fn(|i| x[i] + e0[i] * inv);
    let su1 = dot(&x1, &sym_mul(q12, &x1)) * i2;
    let second_order = (f.value(), num.hi * i2, su1);
    let pick = |a: F, b: F| negligible.select(a, b);
    let (f, h, su) = (
        pick(plain.0, second_order.0),
        pick(plain.1, second_order.1),
        pick(plain.2, second_order.2),
    );
    let (uw, wdw) = ((uw * i3).to_array(), (wdw * i2 * i2).to_array());
    let [f, t, p, h, su] = [f, t, p, h, su].map(F::to_array);
    let values =
        std::array::from_fn(|k| Refined::new(f[k], t[k], p[k], h[k], su[k], uw[k], wdw[k]));
    (values, negligible.or(accepted))
}
