//! [`Refiner::at`] for eight pairs at once.

use super::*;
use crate::contact::lanes::{Mask, F, LANES};

/// [`Refiner::at`] for eight pairs at once, lane `k` at `lambda[k]` and checking `g`
/// where `check_g` is set: bitwise the same values, with both of its ways computed and
/// the one that applies kept. The mask is clear where `at` gives `None`.
#[inline(always)]
pub(crate) fn at_lanes(
    pair: &RefinedPair<F>,
    lambda: F,
    check_g: Mask,
) -> ([Refined; LANES], Mask) {
    let k = Terms::new(pair, lambda);
    let (bound, negligible) = k.second_order_bound();
    let plain = k.plain();
    // The checks only where a lane needs them (none on typical pairs).
    let (mut g_ok, mut trusted) = (Mask::splat(true), Mask::splat(true));
    if check_g.any() {
        let [(e, second), (e_g2, first)] = k.plain_g_checks(&plain, bound);
        let unchecked = check_g.not();
        (g_ok, trusted) = (unchecked.or(e.le(second)), unchecked.or(e_g2.le(first)));
    }
    let negligible = bound.le(negligible);
    let (e0, second) = k.second_order();
    let accepted = second.abs().le(REFINEMENT_TOL * k.num.hi);
    let refined = k.with_second_order(&e0, second);
    let pick = |a: F, b: F| negligible.select(a, b).to_array();
    let (f, h, su) = (
        pick(plain.0, refined.0),
        pick(plain.1, refined.1),
        pick(plain.2, refined.2),
    );
    let (uw, wdw) = k.derivative_terms();
    let [t, p, uw, wdw] = [k.t, k.p, uw, wdw].map(F::to_array);
    let values = std::array::from_fn(|j| Refined {
        g_trusted: trusted.get(j),
        ..Refined::new(f[j], t[j], p[j], h[j], su[j], uw[j], wdw[j])
    });
    (values, g_ok.and(negligible.or(accepted)))
}
