//! What a time limit (`packing.time_limit`) changes in the loop: when the relaxations
//! before the first clean state give way to the search, and how many FIRE steps a
//! trial of the search may take of the time left.

use std::time::Duration;

/// Under a time limit, the share of it after which the relaxations above the target
/// before the search (a deep start, an overshoot, a compression of a shallow first
/// jam) give way: the overshoot to the target's relaxation, the others to the search.
/// Until the search's first clean trial, the densest clean state is the current one
/// shrunk until apart, and a relaxation far above the jamming point overlaps by a
/// tenth of the scale for hundreds of steps: a limit that ran out inside the deep start
/// kept 0.41–0.48 on 10 000 grains that reach 0.62–0.70. Given way, the search's first
/// trial (below the jamming point, clean in 60–80 FIRE steps) and the target's follow.
/// 0.35 (with [`GIVE_WAY_TARGET`]) rather than the 0.7 chosen before the search's
/// trials were planned to the time left (`timed_steps`): the family of starts given a
/// quarter of its `effort = 1` time ends 0.020–0.024 below it on the mean instead of
/// 0.040–0.045, given half as before; single scenes given 0.3–0.6 s move by up to 0.04
/// either way (BENCHMARKS.md, "Time limits shorter than the first relaxation, again").
pub(super) const GIVE_WAY: f64 = 0.35;

/// Under a time limit, the share of it after which the target's own relaxation gives
/// way to the search while no state has come out clean and its grains still overlap
/// deeply ([`NEARLY_APART`](super::fire::NEARLY_APART)): the state is shrunk until
/// apart and the search climbs from there in the time left, in trials that clear in
/// tens of steps. 10⁶ grains asked 0.60 and given 30 s kept 0.45–0.47 (the relaxation
/// interrupted, shrunk by its deepest overlap) and now 0.50–0.52; 10⁵ given 3 s 0.49–0.50
/// and now 0.53–0.54. The price: a limit the relaxation would just have fitted keeps
/// the search's 0.99 of the target (10⁵ given 5 s: 0.593–0.599 for 0.600;
/// BENCHMARKS.md, as for [`GIVE_WAY`]).
pub(super) const GIVE_WAY_TARGET: f64 = 0.7;

/// Under a time limit, the share of the FIRE steps left (the time left at the mean cost
/// of a step so far) that one trial of the search may take ([`timed_steps`]), so that a
/// limit shorter than the search still leaves time for its later, finer trials instead
/// of ending inside a trial that runs its whole budget (without a share, 10 000 equal
/// spheres asked 0.70 and given 1.6 or 2 s, two threads, seed 1, ended in the trial at
/// 0.6444 and kept the clean state at 0.598). Shares 0.25, 0.33, 0.5 and 0.7 on those
/// spheres given 1–2 s: 0.5 and 0.7 the densest, within 0.0005 of each other
/// (BENCHMARKS.md, "Issue 26: a time limit that plans its trials").
pub(super) const TIMED_SHARE: f64 = 0.5;

/// The fewest FIRE steps a trial of the search is given under a time limit
/// ([`timed_steps`]), whatever the time left: a trial just below the jamming point comes
/// out clean in 20–80 steps from the state before it, and one cut before then counts
/// as stuck and bounds the search below it (equal spheres asked 0.70, seed 2: a trial
/// at 0.954 cut at 68 steps, the search then held below it). The family of starts
/// given half the time effort 1 takes: 0.0069 below effort 1's densities on the mean
/// with 100, 0.0097 with none, 0.0156 with 200, before the final check's reserve
/// (`fire::FINISH_STEPS`; 0.0078 with it and 100; BENCHMARKS.md, same section).
pub(super) const TIMED_LEAST: u64 = 100;

/// Under a time limit, the most FIRE steps a trial of the search may take: [`TIMED_SHARE`]
/// of those that the time `left` allows at the mean cost of the `steps` taken in
/// `spent`, at least [`TIMED_LEAST`]. No cap before the first step.
pub(super) fn timed_steps(spent: Duration, left: Duration, steps: u64) -> u64 {
    if steps == 0 || spent.is_zero() {
        return u64::MAX;
    }
    let allowed = left.as_secs_f64() / spent.as_secs_f64() * steps as f64;
    ((TIMED_SHARE * allowed).ceil() as u64).max(TIMED_LEAST)
}
