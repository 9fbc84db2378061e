//! One chunk of the pair list tested: which pairs are due, each due pair's grains
//! fetched into cache a few pairs ahead of its test, and the hits in pair order.

use super::pair::{pair_force, PairForce};
use crate::contact::dot;
use crate::octree::Pair;
use crate::packing::neighbours::relative;
use crate::packing::state::State;
use rayon::prelude::*;

/// What the candidate pairs keep between evaluations, an array each: the scan for due
/// pairs, which visits every candidate every step, reads the allowances alone.
#[derive(Default)]
pub(super) struct Memos {
    /// How far each pair's grains may still move before it must be tested again, as a
    /// bound on the sum of their motions (rounded down; see
    /// [`BOUND_SLACK`](super::BOUND_SLACK)).
    pub allowance: Vec<f32>,
    /// Where each pair's contact function starts next time (`contact::track`); NaN
    /// before its first evaluation.
    pub lambda: Vec<f32>,
}

impl Memos {
    /// `n` pairs, each due and with no start.
    pub fn reset(&mut self, n: usize) {
        self.allowance.clear();
        self.allowance.resize(n, f32::NEG_INFINITY);
        self.lambda.clear();
        self.lambda.resize(n, f32::NAN);
    }
}

/// One task's share of a chunk of the pair list: its overlapping pairs and what they
/// contribute, in pair order, and how many pairs it tested.
#[derive(Default)]
pub(super) struct Found {
    pub hits: Vec<Hit>,
    /// The hits' torques (on the first grain, on the second), when grains turn: kept
    /// apart so that frozen grains write and read half as much.
    pub torques: Vec<[[f64; 3]; 2]>,
    pub tested: u64,
    /// The task's pairs that are due, by their place in the task.
    due: Vec<u16>,
}

/// One overlapping pair: its grains and what it adds to their forces and the totals.
#[derive(Clone, Copy)]
pub(super) struct Hit {
    pub i: u32,
    pub j: u32,
    pub force: [f64; 3],
    pub energy: f64,
    pub mu1: f64,
}

/// What testing a pair needs: the grains, each one's motion since the list was built
/// (what allowances are spent in), and the scales.
pub(super) struct PairTest<'a> {
    pub motion: &'a [f64],
    pub state: &'a State,
    /// `big_s (1 + BOUND_SLACK)`: a pair bounded above it is skipped.
    pub skip_above: f64,
    pub big_s: f64,
}

impl PairTest<'_> {
    /// Whether the pair's allowance is spent: it must be tested.
    #[inline(always)]
    fn due(&self, p: &Pair, allowance: f32) -> bool {
        let spent = self.motion[p.i as usize] + self.motion[p.j as usize];
        spent > f64::from(allowance)
    }

    /// Asks for the pair's grains (centre, and the part of the shape a test reads).
    #[inline(always)]
    fn fetch(&self, p: &Pair) {
        for k in [p.i as usize, p.j as usize] {
            let shape = &self.state.shapes[k];
            prefetch(shape);
            prefetch(&(shape as *const _ as *const u8).wrapping_add(CACHE_LINE));
            prefetch(&self.state.centres[k]);
        }
    }

    /// Tests a due pair: renews its allowance and returns its force if it overlaps,
    /// with the offset `r` it was found at.
    #[inline(always)]
    fn test(
        &self,
        p: &Pair,
        allowance: &mut f32,
        lambda: &mut f32,
    ) -> Option<(PairForce, [f64; 3])> {
        let (i, j) = (p.i as usize, p.j as usize);
        let state = self.state;
        let spent = self.motion[i] + self.motion[j];
        let (ei, ej) = (&state.shapes[i], &state.shapes[j]);
        let inner = ei.inscribed_radius() + ej.inscribed_radius();
        let skip_above = self.skip_above;
        let r = relative(&state.centres, p, &state.box_shape);
        // The gauge of a body inside the ball of radius b_i + b_j is at least
        // |r| / (b_i + b_j), and stays above the threshold while the grains travel
        // less than the bounding spheres' gap at it (turns move no bounding sphere):
        // for grains longer than they are wide, a longer allowance than μ₁'s.
        let outer = ei.bounding_radius() + ej.bounding_radius();
        let distance = dot(&r, &r).sqrt();
        let gap = distance - skip_above * outer;
        let mut allow =
            |m: f64| *allowance = round_down(((m - skip_above) * inner).max(gap) + spent);
        let far = distance / outer;
        if far >= skip_above {
            allow(far);
            return None;
        }
        let radii =
            (state.round[i] && state.round[j]).then(|| (state.axes[i][0], state.axes[j][0]));
        let (mu1, force) = pair_force(&r, (ei, ej), radii, (self.big_s, lambda), p);
        allow(mu1);
        force.map(|f| (f, r))
    }
}

/// Tests one chunk of the pair list, each task into a buffer of its own, kept from step
/// to step: no allocation, and the hits come out in pair order whatever the threads.
/// A task first lists its due pairs, then tests them, asking for the grains of the
/// pair [`AHEAD`] places on before each test.
pub(super) fn test_chunk(
    pairs: &[Pair],
    (allowance, lambda): (&mut [f32], &mut [f32]),
    (found, torques): (&mut [Found], bool),
    test: &PairTest<'_>,
) {
    (pairs.par_chunks(PAIRS_PER_TASK))
        .zip(allowance.par_chunks_mut(PAIRS_PER_TASK))
        .zip(lambda.par_chunks_mut(PAIRS_PER_TASK))
        .zip(found.par_iter_mut())
        .for_each(|(((pairs, allowance), lambda), found)| {
            found.hits.clear();
            found.torques.clear();
            // Every place is written, and the count moves past the due ones: no branch
            // on a due pair, which the allowances make unpredictable.
            found.due.resize(pairs.len(), 0);
            let mut count = 0;
            for (k, (p, &a)) in pairs.iter().zip(allowance.iter()).enumerate() {
                found.due[count] = k as u16;
                count += usize::from(test.due(p, a));
            }
            found.due.truncate(count);
            found.tested = count as u64;
            for (n, &k) in found.due.iter().enumerate() {
                if let Some(&ahead) = found.due.get(n + AHEAD) {
                    test.fetch(&pairs[usize::from(ahead)]);
                }
                let k = usize::from(k);
                let p = &pairs[k];
                if let Some((f, r)) = test.test(p, &mut allowance[k], &mut lambda[k]) {
                    let (i, j, force, energy, mu1) = (p.i, p.j, f.force, f.energy, f.mu1);
                    found.hits.push(Hit {
                        i,
                        j,
                        force,
                        energy,
                        mu1,
                    });
                    if torques {
                        found.torques.push(f.torques(&r));
                    }
                }
            }
        });
}

/// Asks the processor to bring `x`'s cache line in: a hint, with no effect on any
/// result. A test's loads depend on the pair before it, so without the hint a pair's
/// grains are fetched only when its test starts (at 10⁶ grains the shapes miss the
/// cache: BENCHMARKS.md, "Issue 26: contact tracked from step to step").
#[inline(always)]
fn prefetch<T>(x: &T) {
    #[cfg(target_arch = "x86_64")]
    // SAFETY: a prefetch is a hint that never faults, whatever the address; `x` is a
    // valid reference besides. SSE is part of x86_64.
    unsafe {
        use std::arch::x86_64::{_mm_prefetch, _MM_HINT_T0};
        _mm_prefetch::<_MM_HINT_T0>((x as *const T).cast());
    }
    #[cfg(not(target_arch = "x86_64"))]
    let _ = x;
}

/// The bytes of a cache line on the machines the hint is for.
const CACHE_LINE: usize = 64;

/// How many due pairs ahead a task asks for a pair's grains: far enough for a miss to
/// DRAM to land while the pairs between are tested (a tested pair takes about 100 ns).
const AHEAD: usize = 4;

/// `x` in `f32`, rounded down: an allowance never grows by its rounding.
pub(super) fn round_down(x: f64) -> f32 {
    let y = x as f32;
    if f64::from(y) > x {
        y.next_down()
    } else {
        y
    }
}

/// Pairs one rayon task takes: one pair is a single contact-function call, too little
/// work to be worth a task of its own. At most 2¹⁶, the places of [`Found::due`].
pub(super) const PAIRS_PER_TASK: usize = 1024;
