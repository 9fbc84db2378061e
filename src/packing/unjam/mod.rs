//! Unjamming moves between effort's recompression cycles (`packing.unjam`): a way past
//! a premature jam that the compress-and-relax protocol alone does not take.
//!
//! Once the bisection has found a jamming point and effort asks for another cycle, the
//! loop compresses the state (by [`RECOMPRESSION`](super::effort::RECOMPRESSION), slender
//! grains by [`DEEP_RECOMPRESSION`](super::effort::DEEP_RECOMPRESSION)) and relaxes it
//! there. Before that relaxation, with `unjam = "swap"`, grains of similar volume but
//! different size, shape or orientation exchange their positions wherever that lowers
//! the overlap energy at the compressed scale, in rounds of sweeps separated by short
//! relaxations: swap Monte Carlo at zero temperature (Grigera and Parisi, *Phys. Rev.
//! E* 63, 045102, 2001; Ninarello, Berthier and Coslovich, *Phys. Rev. X* 7, 021039,
//! 2017, where swaps reach far denser polydisperse packings than plain dynamics). Each
//! grain keeps its own orientation, so frozen orientations stay exactly as drawn: for
//! frozen ellipsoids a swap is the one way to put a differently oriented grain where
//! another stood.
//!
//! On lognormal spheres (σ = 0.25) the cycle then jams at 0.682–0.683 instead of 0.662,
//! and frozen spheroids of aspect 1.5 near 0.646–0.649 instead of 0.632–0.634
//! (BENCHMARKS.md, "third round"). Equal spheres, and grains whose volumes differ by
//! more than [`SWAP_VOLUME_RATIO`], have nothing to swap: the moves then cost one
//! sweep of comparisons and change nothing. Random shaking of the jammed state (thermal
//! noise at a fixed scale, then a quench) was measured too and bought nothing.
//!
//! With `unjam = "anneal"` a cycle is instead a slow compression from below the jamming
//! point with hard-particle Monte Carlo between its steps (moves, turns, and swaps
//! that carry orientations when grains may turn): module `anneal`. It pays where the
//! swaps above do not, on grains free to turn: Rocks and Hoy's ellipses reach 0.897
//! where swap cycles jam at 0.888.
//!
//! The moves only change the state a cycle starts from: the densest clean state of all
//! cycles is kept by the loop, so the fraction reached never falls below that of the
//! first search. They draw from their own random stream ([`UNJAM_STREAM`]) and run
//! in a fixed order, so the result is the same for a seed whatever the thread count.

mod anneal;
mod monte_carlo;
mod swap;

use super::fire::{Context, Fire};
use super::snapshot::{restore, Snapshot};
use super::state::State;
use super::Outcome;
use super::{PackError, ProtocolParams};
use crate::scene::Unjam;
use rand::{Rng, SeedableRng};
use rand_chacha::ChaCha8Rng;

/// The random stream of the moves (the scene's sampling uses stream 0, the starting
/// positions stream 1).
const UNJAM_STREAM: u64 = 2;

/// Most rounds of swap sweeps before a cycle's relaxation, each but the last followed
/// by a relaxation of [`SWAP_RELAX_STEPS`] at the recompressed scale (swap Monte Carlo
/// alternates swaps with ordinary moves). The rounds end earlier, as soon as a round
/// keeps no swap: on 500 frozen spheroids (seeds 1–3) allowing 64 rounds gave the
/// same results as 32, and 4, 8, 16, 32 rounds reached 0.637–0.638, 0.640–0.641,
/// 0.644–0.645, 0.646–0.649 (BENCHMARKS.md, "third round"). The rounds of a cycle grow
/// with effort up to this (see [`swap_rounds`]).
pub(crate) const SWAP_ROUNDS: usize = 32;

/// The rounds of a cycle at the least effort with a cycle
/// ([`MIN_CYCLE_EFFORT`](super::MIN_CYCLE_EFFORT)): the first rounds keep most swaps
/// (on 10 000 lognormal spheres, 8 rounds gave 0.676 in 33 s where 32 gave 0.683 in
/// 74 s), so that a short budget spends its time there.
pub(crate) const FIRST_SWAP_ROUNDS: usize = 8;

/// The most rounds of swap sweeps in each cycle of `cycles` recompression cycles (the
/// cycles of the run's effort): [`FIRST_SWAP_ROUNDS`] with one cycle, doubled with
/// each further cycle, at most [`SWAP_ROUNDS`]: 8 at `effort = 1.5`, 16 at 2, 32
/// from 2.5 on. More effort buys more swaps per cycle as well as more cycles.
pub(crate) fn swap_rounds(cycles: u32) -> usize {
    let doublings = cycles.saturating_sub(1).min(usize::BITS - 1);
    FIRST_SWAP_ROUNDS
        .saturating_mul(1 << doublings)
        .min(SWAP_ROUNDS)
}

/// Most sweeps (one swap attempt per grain each) in a round; a sweep that keeps no
/// swap ends the round.
pub(crate) const SWAP_SWEEPS: usize = 4;

/// FIRE steps of the relaxation between two rounds of swaps: a quarter of a trial's
/// default budget, for the packing to settle around the swapped grains. Sixteen such
/// relaxations without swaps changed nothing (control, BENCHMARKS.md): the density
/// comes from the swaps.
pub(crate) const SWAP_RELAX_STEPS: u64 = 250;

/// Grains swap only with grains whose volume is within this factor of theirs
/// ("similar-size" swaps): a far larger grain never fits where a small one stood, and
/// the window keeps the attempts where they may pay. 2 spans a lognormal size law of
/// σ = 0.25 over about a standard deviation either side.
pub(crate) const SWAP_VOLUME_RATIO: f64 = 2.0;

/// The grains by volume (ties by index), to draw a swap partner of similar volume.
pub(crate) struct Partners {
    by_volume: Vec<usize>,
    sorted: Vec<f64>,
}

impl Partners {
    pub fn of(volumes: &[f64]) -> Self {
        let mut by_volume: Vec<usize> = (0..volumes.len()).collect();
        by_volume.sort_by(|&a, &b| volumes[a].total_cmp(&volumes[b]).then(a.cmp(&b)));
        let sorted = by_volume.iter().map(|&g| volumes[g]).collect();
        Self { by_volume, sorted }
    }

    /// A grain drawn uniformly among those whose volume is within
    /// [`SWAP_VOLUME_RATIO`] of `v` (one draw, whatever the outcome, so that the
    /// stream does not depend on the outcomes).
    pub fn draw(&self, v: f64, rng: &mut ChaCha8Rng) -> usize {
        let lo = self.sorted.partition_point(|&x| x < v / SWAP_VOLUME_RATIO);
        let hi = self.sorted.partition_point(|&x| x <= v * SWAP_VOLUME_RATIO);
        self.by_volume[rng.random_range(lo..hi)]
    }
}

/// The moves of one packing: the mode and its random stream.
pub(crate) struct Unjammer {
    mode: Unjam,
    /// Most rounds of sweeps per cycle ([`swap_rounds`]).
    rounds: usize,
    rng: ChaCha8Rng,
}

impl Unjammer {
    /// The moves of a run with `cycles` recompression cycles.
    pub fn new(mode: Unjam, cycles: u32, seed: u64) -> Self {
        let mut rng = ChaCha8Rng::seed_from_u64(seed);
        rng.set_stream(UNJAM_STREAM);
        Self {
            mode,
            rounds: swap_rounds(cycles),
            rng,
        }
    }

    /// Whether the cycles anneal (`unjam = "anneal"`) instead of compressing through.
    pub fn anneals(&self) -> bool {
        self.mode == Unjam::Anneal
    }

    /// A cycle of `"anneal"`: the densest clean state `best` is annealed from below its
    /// jamming point (module `anneal`) and replaced where the result is denser. Returns
    /// the bisection's next bracket, the densest clean scale and a stuck one: the
    /// anneal's upper bound, and at least two resolutions (`resolution`, relative) above
    /// the densest state, so that one trial lies above it.
    pub fn anneal_cycle(
        &mut self,
        (state, fire, run): (&mut State, &mut Fire, &mut Context<'_>),
        protocol: &ProtocolParams,
        best: &mut Option<Snapshot>,
        resolution: f64,
    ) -> Result<(f64, f64), PackError> {
        let mut above = f64::INFINITY;
        if let Some(b) = best.as_ref() {
            restore(state, b)?;
            let (clean, bound) =
                anneal::anneal(state, fire, run, protocol, b.scale, &mut self.rng)?;
            above = bound;
            if b.scale < clean {
                *best = Some(Snapshot::of(state, clean.min(1.0)));
            }
        }
        let low = best.as_ref().map_or(0.0, |b| b.scale);
        Ok((low, above.max(low * (1.0 + 2.0 * resolution))))
    }

    /// The moves before a recompression cycle: the state is about to be relaxed at
    /// scale `next`. Counts the swaps kept in the counters.
    pub fn before_recompression(
        &mut self,
        state: &mut State,
        fire: &mut Fire,
        run: &mut Context<'_>,
        protocol: &ProtocolParams,
        next: f64,
    ) -> Result<(), PackError> {
        if self.mode != Unjam::Swap {
            return Ok(());
        }
        let big_s = next * (1.0 + protocol.margin);
        for round in 0..self.rounds {
            if run.halted() {
                break;
            }
            let kept = swap_round(state, big_s, &mut self.rng, &|| run.halted())?;
            run.counters.swaps += kept;
            if kept == 0 {
                break;
            }
            if round + 1 < self.rounds {
                // The loop's own relaxation follows the last round.
                run.counters.steps += 1;
                if fire.relax(state, run, next, big_s, SWAP_RELAX_STEPS)? == Outcome::Interrupted {
                    break;
                }
            }
        }
        Ok(())
    }
}

/// Up to [`SWAP_SWEEPS`] sweeps at scale `big_s`, until one keeps no swap or `halt`
/// says so; returns the swaps kept.
pub(crate) fn swap_round(
    state: &mut State,
    big_s: f64,
    rng: &mut ChaCha8Rng,
    halt: &dyn Fn() -> bool,
) -> Result<u64, PackError> {
    let mut kept = 0;
    for _ in 0..SWAP_SWEEPS {
        let (_, swaps) = swap::sweep(state, big_s, rng, halt)?;
        kept += swaps;
        if swaps == 0 || halt() {
            break;
        }
    }
    Ok(kept)
}

/// How often, in grains, a sweep of the unjamming moves asks whether to stop (the
/// caller's stop flag, the time limit). The sweeps did not ask at all: a cycle that
/// began just before the limit ran its swap rounds past it (10⁴ lognormal spheres given
/// 3.94 s packed for 4.22 s), and a sweep of 10⁶ grains takes seconds. The clock is
/// read once per this many attempts, each of which evaluates contact functions with
/// their neighbours, or sooner ([`HALT_WORK`]).
pub(crate) const HALT_EVERY: usize = 1024;

/// A sweep also asks whether to stop once its attempts since the last ask have looked
/// at this many neighbours (each a bounding-sphere test and, for most, a contact
/// function: a few ms in all). Slender grains at a deep cycle's scale have thousands of
/// neighbours each: 573 needles of aspect 12 given 2 s, whose cycle began just before
/// the limit, ran a sweep of 0.3 s past it (BENCHMARKS.md, "Frozen slender grains
/// spread before the search").
pub(crate) const HALT_WORK: usize = 1 << 16;

/// Whether a sweep must stop before grain `i`, the attempts since the last ask having
/// looked at `work` neighbours: asks `halt` every [`HALT_EVERY`] grains and once `work`
/// reaches [`HALT_WORK`] (then counted afresh).
pub(crate) fn halts(i: usize, work: &mut usize, halt: &dyn Fn() -> bool) -> bool {
    if !i.is_multiple_of(HALT_EVERY) && *work < HALT_WORK {
        return false;
    }
    *work = 0;
    halt()
}

#[cfg(test)]
mod tests;
