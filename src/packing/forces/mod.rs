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
use super::state::{State, GRAINS_PER_TASK};
use crate::octree::Pair;
use crate::scene::Boundary;
use rayon::prelude::*;

mod chunk;
mod pair;
use chunk::{test_chunk, Found, Memos, PairTest, PAIRS_PER_TASK};
pub(crate) use pair::{cross, pair_energy};

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
    /// What each task of one chunk of the pair list found, and of the chunk before
    /// (being added up meanwhile).
    found: Vec<Found>,
    found_next: Vec<Found>,
    /// What each candidate pair keeps between steps; valid until the list is rebuilt
    /// or the scale changes.
    memo: Memos,
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
/// slack covers the error of the μ₁ the narrow phase found (a lower bound to the
/// rounding of one evaluation when tracked; the fast contact function's error, ≤ 1e-8
/// relative even on the extreme reference set, otherwise) with room to spare.
/// Multiplied out, with `T = S (1 + BOUND_SLACK)`: the pair is skipped while
/// `t' + T h' ≤ (m − T) ρ + t + T h`, its grains' motions (travel plus `T` times
/// sweep) summed now against then, which is what each pair stores (its allowance, in
/// `f32` rounded down: a pair is only ever tested sooner). The bounding spheres give a
/// second bound, `μ₁ ≥ (|r| − t)/(b_i + b_j)` after a travel `t` (turns move no bounding
/// sphere), which lasts longer for grains longer than they are wide: a pair keeps the
/// larger of the two allowances.
pub const BOUND_SLACK: f64 = 1e-6;

/// Added to every turn angle in the sweep of [`BOUND_SLACK`]'s bound, for the rounding
/// of [`turn_angle`] (a few ε).
const TURN_ROUNDING: f64 = 16.0 * f64::EPSILON;

/// The forces, torques and totals the hits add up to.
struct Sums<'a> {
    force: &'a mut [[f64; 3]],
    torque: &'a mut [[f64; 3]],
    torques: bool,
    energy: f64,
    overlaps: usize,
    min_mu1: f64,
    tested: u64,
}

impl Sums<'_> {
    fn add(&mut self, found: &[Found]) {
        for found in found {
            self.tested += found.tested;
            for (n, h) in found.hits.iter().enumerate() {
                let (i, j) = (h.i as usize, h.j as usize);
                self.overlaps += 1;
                self.min_mu1 = self.min_mu1.min(h.mu1);
                self.energy += h.energy;
                for k in 0..3 {
                    self.force[i][k] -= h.force[k];
                    self.force[j][k] += h.force[k];
                }
                if self.torques {
                    let [ti, tj] = found.torques[n];
                    for k in 0..3 {
                        self.torque[i][k] += ti[k];
                        self.torque[j][k] += tj[k];
                    }
                }
            }
        }
    }
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
        self.force.truncate(n);
        (self.force.par_iter_mut())
            .with_min_len(GRAINS_PER_TASK)
            .for_each(|f| *f = [0.0; 3]);
        self.force.resize(n, [0.0; 3]);
        self.torque.clear();
        if torques {
            self.torque.resize(n, [0.0; 3]);
        }
        let skip_above = big_s * (1.0 + BOUND_SLACK);
        let fresh = build != self.build
            || self.memo.allowance.len() != pairs.len()
            || skip_above != self.skip_above
            || torques != self.turning;
        if fresh {
            (self.build, self.skip_above, self.turning) = (build, skip_above, torques);
            self.memo.reset(pairs.len());
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
        let pair_test = PairTest {
            motion,
            state,
            skip_above,
            big_s,
        };
        let mut sums = Sums {
            force: &mut self.force,
            torque: &mut self.torque,
            torques,
            energy: 0.0,
            overlaps: 0,
            min_mu1: f64::INFINITY,
            tested: 0,
        };
        // Each chunk's hits are added while the next chunk is tested (a second thread
        // has the rest of the tests meanwhile), in pair order whatever the threads.
        let (mut testing, mut adding) = (&mut self.found, &mut self.found_next);
        let mut pending = 0;
        let memo = (self.memo.allowance.chunks_mut(CHUNK)).zip(self.memo.lambda.chunks_mut(CHUNK));
        for (pairs, memo) in pairs.chunks(CHUNK).zip(memo) {
            let tasks = pairs.len().div_ceil(PAIRS_PER_TASK);
            if testing.len() < tasks {
                testing.resize_with(tasks, Found::default);
            }
            let found = &mut testing[..tasks];
            rayon::join(
                || test_chunk(pairs, memo, (found, torques), &pair_test),
                || sums.add(&adding[..pending]),
            );
            std::mem::swap(&mut testing, &mut adding);
            pending = tasks;
        }
        sums.add(&adding[..pending]);
        let Sums {
            energy,
            overlaps,
            min_mu1,
            tested,
            ..
        } = sums;
        (self.energy, self.overlaps, self.min_mu1, self.tested) =
            (energy, overlaps, min_mu1, tested);
        self.wall_hits = 0;
        if state.domain.boundary == Boundary::Reflecting {
            self.walls(state, big_s, torques);
        }
    }

    /// Adds each grain's move (and sweep, when grains turn) since the last evaluation.
    fn advance(&mut self, state: &State, torques: bool) {
        (self.travel.par_iter_mut())
            .zip(&mut self.last)
            .zip(&state.centres)
            .with_min_len(GRAINS_PER_TASK)
            .for_each(|((t, a), b)| {
                *t +=
                    ((a[0] - b[0]).powi(2) + (a[1] - b[1]).powi(2) + (a[2] - b[2]).powi(2)).sqrt();
                *a = *b;
            });
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

/// Pairs evaluated before their forces are added up: bounds the memory of the
/// overlapping pairs' contributions (48 bytes each, 96 when grains turn) whatever the
/// scene's size. Two chunks' contributions are held at once (one tested while the
/// other is added up): 2^17 was chosen when a hit took 96 bytes for every scene, to
/// keep both within what one chunk of 2^18 held (1.44 GB peak on 1.17 M grains then;
/// 1.51 GB with two of 2^18).
const CHUNK: usize = 1 << 17;

#[cfg(test)]
mod tests;
