//! Narrow phase and response: the overlap energy of the grains at scale `S` and its
//! gradient (forces, and torques when the grains may rotate).
//!
//! A pair with contact factor μ < 1 at scale `S` (μ = μ₁/S, μ₁ its contact factor at
//! target size) has energy `w (1 − μ)²` with `w = (S (ρ_i + ρ_j))²`, ρ the smallest
//! semi-axis: for two spheres that is `(σ − d)²`, the harmonic overlap energy of
//! soft-sphere jamming (O'Hern et al., *Phys. Rev. E* 68, 011306, 2003), and μ is the
//! Perram–Wertheim generalisation of `d/σ` (Donev et al., *J. Comput. Phys.* 202, 737,
//! 2005, use the same μ). Its gradient needs no derivative of λ (λ maximises f):
//! `∇_r μ² = 2 λ(1−λ) Q(λ)⁻¹ r = 2 μ² n / (r·n)` with `n` the contact normal, and a
//! rotation ω of grain 2 changes μ² by `2 μ² (p₂ × n)·ω / (r·n)`, `p₂` the contact
//! point from its centre: the torque of the contact force about the centre.
//! A grain crossing a wall of a walled box has energy `δ²` per wall, δ its
//! penetration.

use super::grains::turn_angle;
use super::neighbours::relative;
use super::state::State;
use crate::contact::{contact_geometry_fast_prepared, dot, ContactGeometry, PreparedEllipsoid};
use crate::octree::Pair;
use crate::scene::Boundary;
use rayon::prelude::*;
use std::sync::atomic::{AtomicU64, Ordering};

/// The energy, forces and torques of a state, and what the narrow phase found.
#[derive(Default)]
pub(crate) struct Forces {
    /// Force on each grain (minus the gradient of the energy by its centre).
    pub force: Vec<[f64; 3]>,
    /// Torque on each grain (minus the gradient by a rotation); zero unless asked for.
    pub torque: Vec<[f64; 3]>,
    /// Total energy.
    pub energy: f64,
    /// Pairs with μ < 1 at scale `S`.
    pub overlaps: usize,
    /// Smallest μ₁ (contact factor at target size) over the overlapping pairs; ∞ when
    /// there are none.
    pub min_mu1: f64,
    /// Grains crossing a wall at scale `S`.
    pub wall_hits: usize,
    /// Pairs the narrow phase tested.
    pub tested: u64,
    /// The overlapping pairs of one chunk of the pair list and what they contribute,
    /// in pair order.
    hits: Vec<(u32, u32, PairForce)>,
    /// Per candidate pair: how far its grains may still move before it must be tested
    /// again, as a bound on the sum of their [`motion`](Self::motion) (rounded down);
    /// valid until the list is rebuilt or the scale changes (see [`BOUND_SLACK`]).
    allowance: Vec<f32>,
    /// Distance each grain has moved since the list was built, summed step by step,
    /// and where it was at the last evaluation.
    travel: Vec<f64>,
    last: Vec<[f64; 3]>,
    /// For turning grains: how far any point of each grain (at target size) has been
    /// swept by its turns since the list was built (angle × largest semi-axis, summed),
    /// and its orientation at the last evaluation.
    sweep: Vec<f64>,
    last_turn: Vec<[f64; 4]>,
    /// For turning grains, each one's travel plus the skip threshold times its sweep:
    /// what the allowances are spent in (grains that do not turn spend travel alone).
    motion: Vec<f64>,
    /// The skip threshold the allowances were made for, and whether turns counted.
    skip_above: f64,
    turning: bool,
    /// The list build the bounds refer to.
    build: u64,
}

/// μ₁ is the gauge function of the Minkowski sum `K = E_i ⊕ (−E_j)`, which contains
/// the ball of radius `ρ = ρ_i + ρ_j` (smallest semi-axes): it is Lipschitz in `r`
/// with constant `1/ρ`. So a pair whose μ₁ was `m` when the two grains had travelled
/// `t` in total is still at `μ₁ ≥ m − (t' − t)/ρ` after travelling `t'`. Turning grains
/// change `K` itself: turns that sweep no point of either grain further than `h` in
/// total keep `K` inside `K ⊕ B(h) ⊆ (1 + h/ρ) K`, which divides the bound by
/// `1 + h/ρ`. A pair is skipped while that bound exceeds `S (1 + BOUND_SLACK)`; the
/// slack covers the fast contact function's error (≤ 1e-8 relative even on the extreme
/// reference set) with room to spare. Multiplied out, with `T = S (1 + BOUND_SLACK)`:
/// the pair is skipped while `t' + T h' ≤ (m − T) ρ + t + T h`, its grains' motions
/// (travel plus `T` times sweep) summed now against then, which is what each pair
/// stores (its allowance, in `f32` rounded down: a pair is only ever tested sooner).
pub const BOUND_SLACK: f64 = 1e-6;

/// Added to every turn angle in the sweep of [`BOUND_SLACK`]'s bound, for the rounding
/// of [`turn_angle`] (a few ε).
const TURN_ROUNDING: f64 = 16.0 * f64::EPSILON;

/// What one overlapping pair contributes.
#[derive(Clone, Copy)]
struct PairForce {
    /// Force on the second grain (the first gets its opposite).
    force: [f64; 3],
    torque_i: [f64; 3],
    torque_j: [f64; 3],
    energy: f64,
    mu1: f64,
}

impl Forces {
    /// Evaluates the state at scale `big_s` over the candidate pairs of list build
    /// `build`, with `torques` when grains turn. Pairs whose μ₁ is bounded above
    /// `big_s` since their last evaluation are skipped (see [`BOUND_SLACK`]).
    pub fn evaluate(
        &mut self,
        state: &State,
        pairs: &[Pair],
        build: u64,
        big_s: f64,
        torques: bool,
    ) {
        let n = state.len();
        self.force.clear();
        self.force.resize(n, [0.0; 3]);
        self.torque.clear();
        if torques {
            self.torque.resize(n, [0.0; 3]);
        }
        let skip_above = big_s * (1.0 + BOUND_SLACK);
        let fresh = build != self.build
            || self.allowance.len() != pairs.len()
            || skip_above != self.skip_above
            || torques != self.turning;
        if fresh {
            (self.build, self.skip_above, self.turning) = (build, skip_above, torques);
            self.allowance.clear();
            self.allowance.resize(pairs.len(), f32::NEG_INFINITY);
            self.travel.clear();
            self.travel.resize(n, 0.0);
            self.last.clone_from(&state.centres);
            self.sweep.clear();
            self.sweep.resize(n, 0.0);
            if torques {
                self.last_turn.clone_from(&state.quaternions);
            }
        } else {
            self.advance(state, torques);
        }
        // Grains that do not turn spend their allowances in travel alone.
        let motion: &[f64] = if torques {
            self.motion.clear();
            let summed = self.travel.iter().zip(&self.sweep);
            self.motion.extend(summed.map(|(t, h)| t + skip_above * h));
            &self.motion
        } else {
            &self.travel
        };
        let (centres, shapes) = (&state.centres, &state.shapes);
        let (round, axes, shape) = (&state.round, &state.axes, &state.box_shape);
        let tested = AtomicU64::new(0);
        (self.energy, self.overlaps, self.min_mu1) = (0.0, 0, f64::INFINITY);
        let chunks = pairs.chunks(CHUNK).zip(self.allowance.chunks_mut(CHUNK));
        for (pairs, allowance) in chunks {
            let found = pairs
                .par_iter()
                .zip(allowance.par_iter_mut())
                .with_min_len(PAIRS_PER_TASK)
                .filter_map(|(p, allowance)| {
                    let (i, j) = (p.i as usize, p.j as usize);
                    let spent = motion[i] + motion[j];
                    if spent <= f64::from(*allowance) {
                        return None;
                    }
                    tested.fetch_add(1, Ordering::Relaxed);
                    let (ei, ej) = (&shapes[i], &shapes[j]);
                    let inner = ei.inscribed_radius() + ej.inscribed_radius();
                    let mut allow =
                        |m: f64| *allowance = round_down((m - skip_above) * inner + spent);
                    let r = relative(centres, p, shape);
                    // The gauge of a body inside the ball of radius b_i + b_j is at least
                    // |r| / (b_i + b_j).
                    let outer = ei.bounding_radius() + ej.bounding_radius();
                    let far = dot(&r, &r).sqrt() / outer;
                    if far >= skip_above {
                        allow(far);
                        return None;
                    }
                    let radii = (round[i] && round[j]).then(|| (axes[i][0], axes[j][0]));
                    let (mu1, force) = pair_force(&r, (ei, ej), radii, big_s, p);
                    allow(mu1);
                    force.map(|f| (p.i, p.j, f))
                });
            // Collected in pair order whatever the threads (rayon keeps the order).
            self.hits.clear();
            self.hits.par_extend(found);
            for &(i, j, h) in &self.hits {
                let (i, j) = (i as usize, j as usize);
                self.overlaps += 1;
                self.min_mu1 = self.min_mu1.min(h.mu1);
                self.energy += h.energy;
                for k in 0..3 {
                    self.force[i][k] -= h.force[k];
                    self.force[j][k] += h.force[k];
                }
                if torques {
                    for k in 0..3 {
                        self.torque[i][k] += h.torque_i[k];
                        self.torque[j][k] += h.torque_j[k];
                    }
                }
            }
        }
        self.tested = tested.into_inner();
        self.wall_hits = 0;
        if state.domain.boundary == Boundary::Reflecting {
            self.walls(state, big_s, torques);
        }
    }

    /// Adds each grain's move (and sweep, when grains turn) since the last evaluation.
    fn advance(&mut self, state: &State, torques: bool) {
        for ((t, a), b) in self
            .travel
            .iter_mut()
            .zip(&mut self.last)
            .zip(&state.centres)
        {
            *t += ((a[0] - b[0]).powi(2) + (a[1] - b[1]).powi(2) + (a[2] - b[2]).powi(2)).sqrt();
            *a = *b;
        }
        if torques {
            for (((h, a), b), e) in (self.sweep.iter_mut())
                .zip(&mut self.last_turn)
                .zip(&state.quaternions)
                .zip(&state.shapes)
            {
                if a != b {
                    *h += (turn_angle(*a, *b) + TURN_ROUNDING) * e.bounding_radius();
                    *a = *b;
                }
            }
        }
    }

    /// Each wall pushes back a grain crossing it with energy `δ²`.
    fn walls(&mut self, state: &State, big_s: f64, torques: bool) {
        let size = state.domain.size;
        for i in 0..state.len() {
            let (c, w) = (state.centres[i], state.half_widths[i]);
            let mut hit = false;
            for k in 0..3 {
                let half = big_s * w[k];
                // Penetration below the low wall (positive pushes up), above the high one.
                let low = half - c[k];
                let high = c[k] + half - size[k];
                for (depth, sign) in [(low, 1.0), (high, -1.0)] {
                    if depth <= 0.0 {
                        continue;
                    }
                    hit = true;
                    self.energy += depth * depth;
                    self.force[i][k] += sign * 2.0 * depth;
                    if torques {
                        // d(half)/dω = S (Q e_k × e_k) / √Q_kk, Q at target size.
                        let q = state.shapes[i].q();
                        let col = match k {
                            0 => [q[0], q[1], q[2]],
                            1 => [q[1], q[3], q[4]],
                            _ => [q[2], q[4], q[5]],
                        };
                        let mut e = [0.0; 3];
                        e[k] = 1.0;
                        let d = cross(&col, &e);
                        let t = &mut self.torque[i];
                        t.iter_mut()
                            .zip(d)
                            .for_each(|(t, d)| *t -= 2.0 * depth * big_s * d / w[k]);
                    }
                }
            }
            self.wall_hits += usize::from(hit);
        }
    }
}

/// μ₁ of one candidate pair, and its force and torques at scale `big_s` (`None` when
/// it does not overlap there). `radii` are given when both grains are spheres.
fn pair_force(
    r: &[f64; 3],
    (ei, ej): (&PreparedEllipsoid, &PreparedEllipsoid),
    radii: Option<(f64, f64)>,
    big_s: f64,
    p: &Pair,
) -> (f64, Option<PairForce>) {
    let reach = big_s * (ei.inscribed_radius() + ej.inscribed_radius());
    let w = reach * reach;
    let g = if let Some((ri, rj)) = radii {
        sphere_geometry(r, ri, rj)
    } else {
        contact_geometry_fast_prepared(r, ei, ej).ok()
    };
    let Some(g) = g.filter(|g| g.mu2.is_finite()) else {
        // Coincident centres (or a pair the contact function cannot handle, which
        // the scene's validated shapes do not produce): push apart along a fixed
        // direction with the force of a full overlap.
        let n = fallback_direction(p.i, p.j);
        let force = PairForce {
            force: n.map(|x| 2.0 * reach * x),
            torque_i: [0.0; 3],
            torque_j: [0.0; 3],
            energy: w,
            mu1: 0.0,
        };
        return (0.0, Some(force));
    };
    let mu1 = g.mu2.sqrt();
    let mu = mu1 / big_s;
    if mu >= 1.0 {
        return (mu1, None);
    }
    let rn = dot(r, &g.normal);
    // −∂U/∂r = 2 w (1 − μ) ∇μ, ∇μ = μ n / (r·n).
    let scale = 2.0 * w * (1.0 - mu) * mu / rn;
    let force = g.normal.map(|x| scale * x);
    let pj = [0, 1, 2].map(|k| g.point[k] - r[k]);
    let force = PairForce {
        force,
        torque_i: cross(&g.point, &force.map(|x| -x)),
        torque_j: cross(&pj, &force),
        energy: pair_energy(reach, mu),
        mu1,
    };
    (mu1, Some(force))
}

/// The overlap energy of a pair whose bodies, scaled by `big_s`, overlap with gauge
/// `μ = μ₁ / big_s < 1`: `w (1 − μ)²` with `w = reach²`, `reach = big_s (ρ_i + ρ_j)`
/// (inscribed radii). The swap moves (`unjam`) judge with the same energy.
pub(crate) fn pair_energy(reach: f64, mu: f64) -> f64 {
    reach * reach * (1.0 - mu) * (1.0 - mu)
}

/// Two spheres need no contact function: `μ = d / (R_i + R_j)`, normal `r/d`, and
/// they touch at `R_i r / (R_i + R_j)` from the first centre. `None` at `d = 0`.
fn sphere_geometry(r: &[f64; 3], ri: f64, rj: f64) -> Option<ContactGeometry> {
    let d = dot(r, r).sqrt();
    if d == 0.0 {
        return None;
    }
    let mu = d / (ri + rj);
    Some(ContactGeometry {
        mu2: mu * mu,
        lambda: ri / (ri + rj),
        point: r.map(|x| x * ri / (ri + rj)),
        normal: r.map(|x| x / d),
        gap: d - (ri + rj),
    })
}

pub(crate) fn cross(a: &[f64; 3], b: &[f64; 3]) -> [f64; 3] {
    [
        a[1] * b[2] - a[2] * b[1],
        a[2] * b[0] - a[0] * b[2],
        a[0] * b[1] - a[1] * b[0],
    ]
}

/// `x` in `f32`, rounded down: an allowance never grows by its rounding.
fn round_down(x: f64) -> f32 {
    let y = x as f32;
    if f64::from(y) > x {
        y.next_down()
    } else {
        y
    }
}

/// Pairs evaluated before their forces are added up: bounds the memory of the
/// overlapping pairs' contributions (about 100 bytes each) whatever the scene's size.
const CHUNK: usize = 1 << 18;

/// Pairs one rayon task takes at least: one pair is a single contact-function call, too
/// little work to be worth a task of its own.
const PAIRS_PER_TASK: usize = 256;

/// `2^64 / φ` (odd): multiplying by it spreads consecutive ids over all 64 bits.
const GOLDEN_GAMMA: u64 = 0x9E37_79B9_7F4A_7C15;
/// splitmix64's first mixing multiplier (Steele, Lea and Flood 2014).
const SPLITMIX_MUL: u64 = 0xBF58_476D_1CE4_E5B9;

/// A unit vector that depends only on the pair's ids (a hash), for coincident centres.
fn fallback_direction(i: u32, j: u32) -> [f64; 3] {
    let mut h = (u64::from(i) << 32 | u64::from(j)).wrapping_mul(GOLDEN_GAMMA);
    let mut coord = || {
        h ^= h >> 29;
        h = h.wrapping_mul(SPLITMIX_MUL);
        (h >> 11) as f64 / (1u64 << 53) as f64 - 0.5
    };
    let v = [coord(), coord(), coord()];
    let n = dot(&v, &v).sqrt().max(f64::MIN_POSITIVE);
    v.map(|x| x / n)
}

#[cfg(test)]
mod tests;
