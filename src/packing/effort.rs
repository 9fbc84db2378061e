//! How much a packing may spend for density (`packing.effort`): the step budget of a
//! trial below the target, and the recompression cycles that follow the first jamming
//! point; and how deep the first jam must be before the search starts from it.

#[cfg(doc)]
use super::FireParams;
use super::ProtocolParams;
use crate::contact::Dimension;
use crate::scene::{affine_slenderness, sphere_close_packing, GrainSpec};

/// How far past the scale of a jammed state a recompression cycle compresses it,
/// relatively: 0.1 of scale is a third more packing fraction (0.64 to 0.85 for
/// spheres), far enough that the relaxation there rearranges the whole packing
/// rather than settling back into the jammed state. On 10 000 equal spheres (seed 1,
/// three cycles) 0.1 reached 0.6451 and 0.2 0.6452, 0.02 and 0.05 less on 500
/// (BENCHMARKS.md, "Effort"); 0.3 and 1.0 lost density on every compact class
/// (lognormal spheres, frozen spheroids, kanapy's grains: BENCHMARKS.md, "fourth
/// round"). Slender grains take [`DEEP_RECOMPRESSION`].
pub(super) const RECOMPRESSION: f64 = 0.1;

/// The recompression of slender grains (mean slenderness at least [`SLENDER`]): twice
/// the scale, eight times the packing fraction, so that the relaxation there spreads
/// the grains afresh and the cycle's bisection starts from that state instead of a
/// jammed one. Frozen needles and platelets of aspect 12 (573, effort 3, seed 1)
/// reached 0.250, 0.269, 0.281 and the asked 0.30 with 0.1, 0.3, 0.5 and 1.0; frozen
/// spheroids of aspect 6 0.441 with 0.1 and 0.531 with 1.0 (BENCHMARKS.md, "fourth
/// round").
pub(super) const DEEP_RECOMPRESSION: f64 = 1.0;

/// The mean slenderness (longest over shortest semi-axis) from which the cycles
/// recompress by [`DEEP_RECOMPRESSION`]: between the classes measured, grains of
/// aspect ratio up to 3.2 (kanapy's, mean about 2.3) lost density with it and grains
/// of aspect 6 and 12 gained.
pub(super) const SLENDER: f64 = 4.0;

/// The recompression of a cycle for these grains: [`DEEP_RECOMPRESSION`] if their
/// mean slenderness is at least [`SLENDER`], else [`RECOMPRESSION`].
pub(super) fn recompression(specs: &[GrainSpec]) -> f64 {
    if mean_slenderness(specs) >= SLENDER {
        DEEP_RECOMPRESSION
    } else {
        RECOMPRESSION
    }
}

/// Whether the first jam is spread before the search: grains that do not turn and are
/// slender ([`recompression`] deep), from `effort` [`QUENCH_MIN_EFFORT`] on. Jammed from
/// random positions they lock into a loose arrangement the search cannot undo; compressed
/// by [`DEEP_RECOMPRESSION`] (as a cycle's start) and relaxed there, they spread afresh,
/// and the search bisects from that jam (no descent: 2.5 % steps from twice the scale took
/// twice as long for the same density; under a time limit, only before the relaxations
/// above the target give way, `time_limit::GIVE_WAY`, as the spread is one of them). At
/// `effort = 1`, one or two threads, seeds 1–3: 300 frozen ellipses of aspect 5 asked 0.86
/// reach 0.748–0.758 instead of 0.661–0.674 in 3–4 times the time (0.4–0.6 s); 573 frozen
/// needles and platelets of aspect 12 (`needles_platelets_frozen.toml`) 0.278–0.287 instead
/// of 0.236–0.243 (3–4 times, about 5 s), 4 584 of them 0.285 instead of 0.238 (60 s
/// against 22 s), where `effort = 1.5` reaches 0.30 in 13 s; 1 146 frozen spheroids of
/// aspect 6 asked 0.60 0.503–0.504 instead of 0.443–0.446 (5 times, 11 s; BENCHMARKS.md,
/// "Frozen slender grains spread before the search").
///
/// `depth` is the grains' [`recompression`], which `pack` has at hand.
pub(super) fn spreads_first(depth: f64, turning: bool, effort: f64) -> bool {
    !turning && effort >= QUENCH_MIN_EFFORT && depth == DEEP_RECOMPRESSION
}

/// Whether the spread of [`spreads_first`] keeps the candidate list within
/// [`SPREAD_MAX_PAIRS`]: at twice the scale the bounding spheres meet about `2^d` times
/// as many others (`d` the dimension) as at the jam, which lists `pairs`.
pub(super) fn spread_fits(pairs: usize, dimension: Dimension) -> bool {
    (pairs as f64) * 2f64.powi(dimension.exponent()) <= SPREAD_MAX_PAIRS
}

/// The most candidate pairs a spread may list: 5·10⁷, about 1 GB (20 bytes a pair: the
/// pair, its allowance and its λ). Slender grains' bounding spheres hold many others:
/// 4 584 needles of aspect 12 took 131 MB at the spread against 28 MB without, so
/// about 40 000 of them spread, and larger scenes search from their first jam as
/// before.
pub(super) const SPREAD_MAX_PAIRS: f64 = 5e7;

/// The grains' mean slenderness: longest over shortest semi-axis, 1 for spheres.
fn mean_slenderness(specs: &[GrainSpec]) -> f64 {
    let slenderness = |s: &GrainSpec| {
        let [a, b, c] = s.semi_axes;
        a.max(b).max(c) / a.min(b).min(c)
    };
    specs.iter().map(slenderness).sum::<f64>() / specs.len().max(1) as f64
}

/// The first scale of a recompression cycle, from the jamming point `low` just found:
/// the current state (the last trial's) is compressed by `depth` (see
/// [`recompression`]) past it and its jamming point found again from there (see
/// [`recompression_cycles`]). The unjamming moves (module `unjam`) follow, at the
/// scale returned.
pub(super) fn start_cycle(low: f64, depth: f64) -> f64 {
    low * (1.0 + depth)
}

/// The jamming test's window in the relaxations of a recompression cycle, as a share
/// of [`FireParams::window`]: each starts from a state relaxed at a nearby scale, not
/// from random positions, so FIRE needs no long start and its plateau is recognised
/// in half the steps. On 500 equal spheres (seeds 1–5) a cycle then took about half
/// its FIRE steps, for a mean density within the seeds' spread (three cycles: 0.6446
/// against 0.6454, 37 % fewer steps), so that seven cycles cost about what three did
/// and reached 0.6463 (BENCHMARKS.md, "third round"). In the search at effort 1 it
/// lost 0.0002–0.0006 on the mean and is not used there.
pub(super) const CYCLE_WINDOW: f64 = 0.5;

/// The step budget of a relaxation below the target scale:
/// [`ProtocolParams::trial_steps`] times `effort` up to 1 (more buys no density: see
/// [`recompression_cycles`]), at least one step. It is also the patience of the
/// relaxations before the search (the target's and its compressions, module
/// `jamming`): at `effort = 0.1`, 10 000 equal spheres at full size 0.66 took 1 141 FIRE
/// steps to 0.6362 instead of 2 075 to 0.6369 with the patience of effort 1, fewer than
/// the 1 731 of the same spheres from 0.70 (BENCHMARKS.md, issue 27, second round).
pub(super) fn trial_steps(protocol: &ProtocolParams, effort: f64) -> u64 {
    ((protocol.trial_steps as f64 * effort.min(1.0)).ceil() as u64).max(1)
}

/// The patience of a deep relaxation before the search (module `jamming`): below
/// `effort = 1`, [`DEEP_PATIENCE`] trials' budgets ([`trial_steps`]); below
/// [`QUENCH_MIN_EFFORT`], where a target far above the jamming point is relaxed at
/// itself and not deeper ([`first_relaxation`]), none: jammed at the test's first
/// judgement (400 FIRE steps, as at `effort = 0.1`). With four budgets of 0.25 there,
/// 10 000 equal spheres asked 0.70 took 2.7 s where 0.5 took 1.6–1.9 s, to the same
/// 0.640 (now 1.7 s to 0.638–0.639: BENCHMARKS.md, "Effort below 0.5 no slower than
/// 0.5"). From 1 on none, and a deep relaxation runs to its plateau.
pub(super) fn deep_patience(protocol: &ProtocolParams, effort: f64) -> u64 {
    if effort < QUENCH_MIN_EFFORT {
        0
    } else if effort < 1.0 {
        DEEP_PATIENCE * trial_steps(protocol, effort)
    } else {
        u64::MAX
    }
}

/// Below `effort = 1`, a deep relaxation before the search (the target far above the
/// jamming point) counts as jammed after this many trials' budgets ([`trial_steps`]:
/// 400 FIRE steps at `effort = 0.1`), plateau or not: the search needs a jammed state
/// to shrink and start from, not its plateau, which takes 1 300–2 300 steps from
/// random positions at 0.70. 10 000 grains at full size 0.70, `effort = 0.1`, one
/// thread, seeds 1 and 2: equal spheres 0.6368–0.6369 in 938–1 000 FIRE steps
/// instead of 0.6401–0.6405 in 1 731–1 881, lognormal spheres (σ 0.25) 0.6528–0.6534
/// in 926–1 031 instead of 0.6562–0.6571 in 1 953–2 597, frozen spheroids of aspect
/// 1.5 0.6258 in 1 134 instead of 0.6283 in 1 593 (BENCHMARKS.md, "Issue 27, fourth
/// round"): half the time for 0.003 of density, where `effort = 0.1` is asked for
/// the fastest answer. Starts just above the jamming point (shallow) are untouched.
pub(super) const DEEP_PATIENCE: u64 = 4;

/// The recompression cycles of `effort`: `⌊CYCLES_PER_EFFORT · (effort − 1)⌋`, none
/// below 1.5. Once the bisection has found the jamming point, the state is compressed
/// (by [`recompression`]), relaxed, and the jamming point bisected again from there, the
/// densest clean state of all cycles kept. Each lets the packing rearrange from a
/// denser start than random positions, which is what raises its jamming point (a
/// jammed packing's density depends on its history: Chaudhuri, Berthier and Sastry,
/// *Phys. Rev. Lett.* 104, 165701, 2010). Longer relaxations per trial, instead, bought
/// nothing (0.6406–0.6408 on 10 000 spheres from 0.3 to 10 times the budget).
pub(super) fn recompression_cycles(effort: f64) -> u32 {
    (CYCLES_PER_EFFORT * (effort.max(1.0) - 1.0))
        .floor()
        .min(f64::from(u32::MAX)) as u32
}

/// Recompression cycles per unit of `effort` above 1. A cycle (with its half window,
/// [`CYCLE_WINDOW`]) costs about 0.8 of the search at effort 1 on 10 000 equal
/// spheres (2 250 FIRE steps against 2 900), so that two per unit keep `effort = E`
/// at about what it cost when it meant E − 1 cycles of the full window, for more
/// density (BENCHMARKS.md, "third round").
const CYCLES_PER_EFFORT: f64 = 2.0;

/// The least `effort` with a recompression cycle (and so with unjamming moves).
pub const MIN_CYCLE_EFFORT: f64 = 1.0 + 1.0 / CYCLES_PER_EFFORT;

/// How far a shallow first jam is compressed, relatively to its scale, before the
/// search: when the relaxation at the target (or at a scale it was compressed to) ends
/// jammed but shallow (energy per grain below [`DEEP`](super::jamming::DEEP) times the
/// margin's: just above its jamming point), the state is compressed by this much, and
/// at once to at least [`DEEP_START`], and relaxed again, until a relaxation ends deep
/// (or [`QUENCH_LIMIT`]); the shallow jams set no bound on the search. (Compressing by
/// 2 % at a time, 10 000 frozen spheroids of aspect 1.5 asked 0.62 crept at 1.0 and
/// 1.02 before jamming deep at 1.0404: 2 508–2 794 FIRE steps to the target; straight
/// to 1.06, 1 504–1 505.) Just above its jamming point, a relaxation from random
/// positions creeps for thousands of steps and leaves a state whose search jams low:
/// 10 000 equal spheres at 0.66 took 4 000 steps to a plateau and their search found
/// 0.6390, where from 0.70 (1.02 times the scale) the plateau came at 1 300 steps and
/// the search found 0.6418 (BENCHMARKS.md, "issue 27"). So a start just above jamming
/// is searched as one at 0.70 would be.
pub(super) const QUENCH_STEP: f64 = 0.02;

/// The largest scale a shallow first jam is compressed to ([`QUENCH_STEP`]): the
/// recompression of a cycle, [`RECOMPRESSION`] past the target, beyond which any
/// jam counts as deep enough.
pub(super) const QUENCH_LIMIT: f64 = 1.0 + RECOMPRESSION;

/// The least `effort` at which a shallow first jam is compressed before the search
/// ([`QUENCH_STEP`]). Below it the search starts from the first jam, however shallow:
/// the fastest answer, a little less dense just above the jamming point. 10 000
/// lognormal spheres (σ 0.25) at full size 0.66, `effort = 0.1`, one thread: 1 020 FIRE
/// steps to 0.6488 instead of 2 048 to 0.6563; equal spheres 894 to 0.6327 instead of
/// 1 141 to 0.6362 (BENCHMARKS.md, "Issue 27, third round"). The price: a target
/// just below the jamming point may be missed (frozen spheroids of aspect 1.5 asked
/// 0.62: 0.6168 in 1 262 steps, where the compression before the search reached 0.62
/// in 2 400).
pub(super) const QUENCH_MIN_EFFORT: f64 = 0.5;

/// The scale of the first relaxation when the target lies near the jamming point (see
/// [`first_relaxation`]): a fifth more packing fraction than the target's in 3D,
/// so that the relaxation from random positions jams deep within a few hundred steps
/// instead of creeping. The search then starts from that jam, and tries the target
/// itself as soon as the bracket holds it (`tries_target`): relaxed from a state jammed
/// that deep, the target clears in 60–600 steps. 10 000 grains at their jamming point,
/// seeds 1 and 2, one thread (equal spheres asked 0.64, lognormal ones 0.657, frozen
/// spheroids of aspect 1.5 0.62; BENCHMARKS.md, "Issue 27, sixth round"): 1.0404 took
/// 953–4 251 FIRE steps, 1.06 671–4 004, where relaxing at the target first took
/// 2 508–6 500; 1.02 1 596–4 956 (and one target missed).
pub(super) const DEEP_START: f64 = 1.06;

/// How close to the jamming point estimated for the grains (Farr and Groot's random
/// close packing of spheres of their sizes, [`sphere_close_packing`], lowered for
/// frozen non-spheres by [`frozen_share`]) a target must be for the first relaxation to
/// start at [`DEEP_START`], as the ratio of the two fractions.
/// Below it the relaxation at the target clears by itself in a few hundred steps (equal
/// and lognormal spheres at 0.963 and 0.964 of the estimate: 602–969 FIRE steps); at
/// 0.99 (equal spheres asked 0.64, lognormal ones 0.657) it creeps for thousands.
pub(super) const NEAR_JAMMING: f64 = 0.97;

/// The ratio of the target's fraction to the spheres' estimated jamming point (as for
/// [`NEAR_JAMMING`]) where the band of [`DEEP_START`] ends. Below it a relaxation at the
/// target creeps (at 1.026, equal spheres and frozen spheroids of aspect 1.5 at full size
/// 0.66, for 1 000 steps); above it, it jams by itself, but late: at 1.054 and 1.088
/// (lognormal and equal spheres at 0.70) in 900–1 500 steps, where one at the band's
/// deepest fraction (`DEEP_START³ × FAR_ABOVE_JAMMING` of the estimate, 0.797 for equal
/// spheres) jams in 400–500 and the search from there reaches denser states. So in 3D
/// a target above the band starts at that fraction, or at the target where it is
/// denser; the first relaxation's fraction then no longer depends on the start. On the
/// family of starts (`benches/density/start/`, seeds 1 and 2) the 16 runs above the band
/// pack 0.0009 denser on the mean (equal spheres 0.6419–0.6427 from every start, frozen
/// spheroids 0.6310–0.6317 where they reached 0.6282–0.6305) in 11 % fewer FIRE steps;
/// six seeds of `mono_periodic.toml` 0.0006–0.0025 denser in 4 % more time (BENCHMARKS.md,
/// "Issue 27: the first relaxation at the band's deepest fraction"). In 2D (fibres at
/// 0.90, bidisperse discs) it gained nothing measurable, and the target is kept.
pub(super) const FAR_ABOVE_JAMMING: f64 = 1.04;

/// The first relaxation's scale above the band of [`DEEP_START`] is rounded up to a
/// multiple of this (2.4·10⁻⁴, 7·10⁻⁴ of the packing fraction, relative), so that inputs equal but for
/// their rounding start at the same scale bit for bit: grains with a gap and the same
/// grains inflated by it (`tests/gap.rs`) reach their fractions and estimates by
/// different sums.
pub(super) const FIRST_SCALE_STEP: f64 = 1.0 / 4096.0;

/// How much lower than spheres of their sizes grains that do not turn jam, per unit of
/// slenderness above 1, the slenderness taken after the linear map that makes their
/// mean shape round ([`affine_slenderness`]: aligned grains of one shape jam as spheres
/// do): their jamming point is taken as the sphere estimate times
/// `1 − FROZEN_JAMMING_SLOPE (s − 1)`, `s` up to [`SLENDER`]. 10 000 spheroids of aspect
/// 1.5 turned at random and frozen jam at 0.630, 0.979 of the estimate 0.6435: a slope
/// of 0.042 (BENCHMARKS.md, "Issues 26 and 27: ten million grains again").
pub(super) const FROZEN_JAMMING_SLOPE: f64 = 0.042;

/// The jamming point estimated for grains that do not turn, as a share of the random
/// close packing of spheres of their sizes ([`FROZEN_JAMMING_SLOPE`]); 1 for spheres,
/// and in 2D (not measured there).
fn frozen_share(specs: &[GrainSpec], dimension: Dimension) -> f64 {
    if dimension == Dimension::Two || mean_slenderness(specs) == 1.0 {
        return 1.0;
    }
    1.0 - FROZEN_JAMMING_SLOPE * (affine_slenderness(specs).min(SLENDER) - 1.0)
}

/// How far past the target the grains are first relaxed, for [`OVERSHOOT_STEPS`], when
/// frozen grains are asked a target from [`NEAR_FROZEN_JAMMING`] to [`NEAR_JAMMING`] of
/// their own estimated jamming point: 9 % more packing fraction, just past that point.
/// There a relaxation from random positions is a slow collective release of a contact
/// network that overlaps almost everywhere at the target (BENCHMARKS.md, "Issues 26 and
/// 27: ten million grains again"); pushed past it for a while, the network opens
/// faster once the target is relaxed. `benches/scale/hundred_thousand.toml` (frozen
/// ellipsoids of aspect 1–2 at 0.925 of their own point), seed 1, two threads: 226
/// FIRE steps (120 of them here) instead of 275, 1.04 218, 1.06 215 (but each step at
/// 1.06 costs more: more contacts); frozen spheroids of aspect 1.5 at 0.60 (0.953)
/// 239 instead of 376 (BENCHMARKS.md, "Issue 26: frozen grains overshoot").
pub(super) const OVERSHOOT: f64 = 1.03;

/// FIRE steps of the relaxation at [`OVERSHOOT`]. On hundred_thousand (seed 1) 90
/// steps took 250 in all, 120 226, 150 219; on 10 000 frozen spheroids at 0.60 and 0.58,
/// 80 took 341 and 187, 120 239 and 181, 160 240 and 204.
pub(super) const OVERSHOOT_STEPS: u64 = 120;

/// The least ratio of a frozen grains' target to their own estimated jamming point
/// (as for [`NEAR_JAMMING`]) at which the first relaxation overshoots ([`OVERSHOOT`]).
/// Further below it the relaxation at the target is short by itself: 10 000 frozen
/// spheroids asked 0.55 (0.873) took 153 FIRE steps at the target and 143 with an
/// overshoot, in the same time.
pub(super) const NEAR_FROZEN_JAMMING: f64 = 0.9;

/// How a packing's first relaxation goes.
#[derive(Debug, Clone, Copy, PartialEq)]
pub(super) struct First {
    /// Its scale.
    pub scale: f64,
    /// `Some(n)`: it is relaxed for at most `n` FIRE steps and the target relaxed next,
    /// whatever it reached ([`OVERSHOOT`]); `None`: it is the search's first trial.
    pub steps: Option<u64>,
}

impl First {
    pub(super) const TARGET: Self = Self {
        scale: 1.0,
        steps: None,
    };
}

/// The first relaxation: at [`DEEP_START`] when the grains at their target size,
/// inflated by the gap, fill at least [`NEAR_JAMMING`] of their own estimated jamming
/// point (the random close packing of spheres, discs in 2D, of their equivalent
/// diameters, lowered for grains that do not turn by [`frozen_share`]) and less than
/// [`FAR_ABOVE_JAMMING`] of the spheres' (frozen spheroids of aspect 1.5 at 1.048 of
/// their own, full size 0.66, still creep at the target), and `effort` lets the search
/// start from a deep jam ([`QUENCH_MIN_EFFORT`]); above that band, in 3D, at the band's
/// deepest fraction or the target, whichever is denser; at [`OVERSHOOT`] for a while when
/// frozen non-spheres fill from [`NEAR_FROZEN_JAMMING`] to [`NEAR_JAMMING`] of theirs;
/// else at the target itself. `fraction` is the inflated grains' at the target size.
/// Grains that turn (`turning`: not all spheres, and free to rotate) start at the
/// target: they pack denser than spheres of their sizes (spheroids of aspect 1.5 near
/// 0.70–0.716), so the estimate does not tell how near their jamming point is
/// (kanapy's example, at 0.98 of it, clears at its target in 461 FIRE steps, and took
/// 1 251 started deep).
pub(super) fn first_relaxation(
    specs: &[GrainSpec],
    dimension: Dimension,
    fraction: f64,
    (effort, turning): (f64, bool),
) -> First {
    // Grains that turn start at the target: known before the estimate, which takes
    // 15–90 ms from 10³ to 10⁶ grains.
    if turning {
        return First::TARGET;
    }
    let Some(spheres) = sphere_close_packing(specs, dimension) else {
        return First::TARGET;
    };
    let own = spheres * frozen_share(specs, dimension);
    if fraction >= NEAR_JAMMING * own {
        if effort < QUENCH_MIN_EFFORT {
            return First::TARGET;
        }
        let edge = FAR_ABOVE_JAMMING * spheres;
        let scale = if fraction < edge {
            DEEP_START
        } else if dimension == Dimension::Three {
            let deepest = DEEP_START * (edge / fraction).cbrt();
            ((deepest / FIRST_SCALE_STEP).ceil() * FIRST_SCALE_STEP).clamp(1.0, DEEP_START)
        } else {
            1.0
        };
        First { scale, steps: None }
    } else if own < spheres && fraction >= NEAR_FROZEN_JAMMING * own {
        First {
            scale: OVERSHOOT,
            steps: Some(OVERSHOOT_STEPS),
        }
    } else {
        First::TARGET
    }
}

/// Whether the bisection between the densest clean scale `low` and the smallest stuck
/// one `stuck` should try the target (scale 1) instead of their midpoint: where it lies
/// between `low` and the midpoint. The loop does so once: a clean relaxation there
/// ends the run (a target just below the jamming point is then reached without the
/// bisection narrowing down to it); one jammed on a plateau bounds the search as any
/// trial; one that runs out of steps bounds nothing: from a state jammed far above the
/// target, one trial there may run out of steps where the bisection's smaller steps
/// reach it (lognormal spheres at full size 0.659, seed 2: BENCHMARKS.md, "Issue 27,
/// fifth round"), and the bisection goes on from its midpoint.
pub(super) fn tries_target(low: f64, stuck: f64) -> bool {
    low < 1.0 && 1.0 < 0.5 * (low + stuck)
}
