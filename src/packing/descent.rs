//! The descent from the first deep jam to the jamming point
//! ([`ProtocolParams::descent`](super::ProtocolParams::descent), on by default).
//!
//! The search used to bisect the scale between the densest clean state and the
//! smallest jammed one from its first jam on, each trial a relaxation that had to come
//! out clean, jam on a plateau (at least 400 FIRE steps, `jamming::MIN_WINDOWS`) or run
//! out of its budget (1 000 steps) before the next began. Near the jamming point most
//! did one of the last two: 10 000 equal spheres asked for 0.70 took 3.9–6.8 times the
//! FIRE steps of the same spheres asked for a reachable 0.62.
//!
//! The descent decompresses the jammed state instead, the way jammed packings are
//! followed down to their jamming point (O'Hern et al., *Phys. Rev. E* 68, 011306,
//! 2003): in **segments** of [`SEGMENT`] of a trial's budget, FIRE's velocities and
//! step kept from one to the next as in one relaxation whose scale moves, the first at
//! the jam's own scale (a short one, [`SHORT`]) and each next one lower by the state's
//! root-mean-square overlap ([`STEP`]; at most [`MAX_STEP`], at least [`FLOOR`]
//! resolutions). Above the jamming point the relaxed overlaps shrink in proportion to
//! the distance to it, so the steps shrink as the descent nears it. Each segment that
//! does not come out clean bounds the search from above and leaves its state shrunk
//! until apart as a clean one (as every stuck trial does), so the descent ends when a
//! segment comes out clean or the two bounds meet; the bisection closes what is left.
//! The recompression cycles of `effort` ≥ 1.5 start from the densest state as before
//! and bisect.
//!
//! Same spheres, seeds 1–8: 2.2–2.4 times the reachable scene's FIRE steps (2.7–2.9
//! in time, medians of three runs) at the bisection's densities (−0.0007 to +0.0001);
//! the family of starts (`benches/density/start/`) in 0.54 of the steps and 0.69 of
//! the time, +0.00003 on the mean (worst −0.0011). BENCHMARKS.md, "A descent instead
//! of a bisection" and "The descent by default".

use super::effort::trial_steps;
use super::forces::Forces;
use super::ProtocolParams;

/// A segment's FIRE steps, as a share of a search trial's budget (`trial_steps`):
/// 150 at `effort = 1` (75 for a short one, [`SHORT`]). How well each segment
/// relaxes sets how dense the descent ends (figures from before [`SHORT`], with a
/// [`MAX_STEP`] of 2 %): on 10 000 equal spheres, 150 (this) ended 0.00016 below the
/// bisection at 2.8–3.0 times a reachable scene's steps, 100 with steps of 0.3 of the
/// overlap 0.0007 above it at 4.6–5.7 times, 25 with steps of 0.15 of it 0.0018 below
/// (BENCHMARKS.md, "A descent instead of a bisection").
pub(super) const SEGMENT: f64 = 0.15;

/// A segment's scale lies below the last by this many times the grains' root-mean-square
/// overlap there (relative to the scale, the margin's share taken off). 1: the overlaps
/// of a jammed state vanish at about its jamming point.
pub(super) const STEP: f64 = 1.0;

/// The largest step, relative to the scale: from a deep jam (overlaps of 5 % at
/// 1.06) one step would land past the jamming point's neighbourhood in a state
/// relaxed far above it, and a jam relaxed on the way down is denser. 2.5 %: three
/// steps from the deepest start (1.044 for equal spheres asked 0.70) to within 0.6 %
/// of scale of their jamming point; 2 % took one more, 3 % lost 0.0005 on the mean of
/// eight seeds (BENCHMARKS.md, "The descent by default").
pub(super) const MAX_STEP: f64 = 0.025;

/// The smallest step, in units of the bisection's resolution (`jam_resolution`), a
/// little under one so that the last step's bracket closes the search at once.
pub(super) const FLOOR: f64 = 0.9;

/// From above the target, the descent tries the target itself, with a whole trial's
/// budget, as soon as its estimate of the jamming point (the scale less the
/// root-mean-square overlap) lies above the target or below it by at most this many
/// resolutions: a target below the jamming point is then reached in one relaxation
/// from a state relaxed above it (500 equal spheres asked 0.63, 0.979 of their
/// estimated jamming point: 832 FIRE steps with the bisection, 927 with the descent,
/// 1 450 when it stepped down to it), and one just above it is tried once, as the
/// bisection did (`effort::tries_target`). A target that does not come out clean is
/// left for the scale the descent came from, as the bisection's next trial climbs back
/// above a failed target: from the target's state the jam there is deeper, and the
/// descent from it denser (`fuller_concrete.toml`: 0.6796 as the bisection, where
/// going on down from the target ended at 0.6772).
pub(super) const TARGET_BELOW: f64 = 4.0;

/// A segment's share of [`SEGMENT`] when it is *short*: the first, which goes on at
/// the jam's own scale from a relaxation of at least 400 FIRE steps there, and one
/// lower than the last by the least step ([`FLOOR`]), from a state relaxed within a
/// resolution of its scale. On 10 000 equal spheres, seeds 1–8, halving both took
/// 0.84 of the descent's FIRE steps at −0.00006 on the mean (BENCHMARKS.md, "The
/// descent by default").
pub(super) const SHORT: f64 = 0.5;

/// Below this `effort` the segments stay as long as at it, while the search's other
/// budgets shrink with `effort` (`effort::trial_steps`): at `effort = 0.1` segments of
/// 15 steps relax too little, and 10 000 equal spheres asked 0.70 jammed at 0.6291
/// where the bisection reached 0.6370; with segments of 75 steps 0.6377 in 1.4 s
/// against its 1.5 s (one thread), lognormal ones from 0.66 0.6499 against 0.6488
/// (BENCHMARKS.md, "The descent by default").
pub(super) const LEAST_EFFORT: f64 = 0.5;

/// The FIRE steps of a segment at scale `s` at `effort`: at the target itself a whole
/// search trial's budget (`effort::trial_steps`), else [`SEGMENT`] of that budget at
/// `effort` (at least [`LEAST_EFFORT`]), [`SHORT`] of it when `short`.
fn segment(protocol: &ProtocolParams, effort: f64, s: f64, short: bool) -> u64 {
    let share = match (s == 1.0, short) {
        (true, _) => return trial_steps(protocol, effort),
        (false, true) => SEGMENT * SHORT,
        (false, false) => SEGMENT,
    };
    let trial = trial_steps(protocol, effort.max(LEAST_EFFORT));
    ((trial as f64 * share).ceil() as u64).max(1)
}

/// The descent's course through the loop of `pack`: whether it runs, and what its next
/// segment needs to know.
#[derive(Debug, Default)]
pub(super) struct Descent {
    /// From the first deep jam to the first clean state (or the bisection).
    on: bool,
    /// The next segment is the first, at the jam's own scale.
    from_jam: bool,
    /// The scale the descent came from to try the target ([`TARGET_BELOW`]), to go
    /// back to if the target does not come out clean.
    above: Option<f64>,
    /// The next segment is short ([`SHORT`]).
    short: bool,
}

impl Descent {
    /// Whether the descent runs.
    pub fn on(&self) -> bool {
        self.on
    }

    /// Starts it from a deep jam.
    pub fn start(&mut self) {
        (self.on, self.from_jam) = (true, true);
    }

    /// Ends it (a clean state, or the bisection or a recompression cycle takes over).
    pub fn stop(&mut self) {
        self.on = false;
    }

    /// The FIRE steps of its segment at scale `s` ([`segment`]).
    pub fn budget(&self, protocol: &ProtocolParams, effort: f64, s: f64) -> u64 {
        segment(protocol, effort, s, self.short)
    }

    /// The scale of the segment after one at `s` that did not come out clean: its first
    /// goes on at the jam's own scale; a target tried and not clean gives way to the
    /// scale the descent came from; else [`next`], which may try the target unless
    /// `target_tried` (set when it does). `None`, and the descent ends, where the
    /// bisection takes over.
    pub fn next_scale(
        &mut self,
        s: f64,
        relaxed: (&Forces, f64),
        bounds: (f64, f64, f64),
        target_tried: &mut bool,
    ) -> Option<f64> {
        let next = match (std::mem::take(&mut self.from_jam), s == 1.0) {
            (true, _) => Some((s, true)),
            (false, true) if self.above.is_some() => self.above.take().map(|s| (s, false)),
            _ => next(s, relaxed, bounds, !*target_tried),
        };
        let Some((next, short)) = next else {
            self.on = false;
            return None;
        };
        self.short = short;
        if next == 1.0 && s > 1.0 {
            (self.above, *target_tried) = (Some(s), true);
        }
        Some(next)
    }
}

/// The next segment's scale after one at `s` that did not come out clean, from the
/// forces evaluated there at `s (1 + margin)` and the grains' mean squared inscribed
/// radius `rho2` (`State::mean_rho2`); `None` when that would not lie above
/// the densest clean scale `low` by more than the resolution (the bisection takes
/// over). From above the target, the target itself when the step would end near or
/// above it ([`TARGET_BELOW`]) and `target` (not yet tried).
fn next(
    s: f64,
    (forces, rho2): (&Forces, f64),
    (margin, resolution, low): (f64, f64, f64),
    target: bool,
) -> Option<(f64, bool)> {
    // A pair overlapping by `δ` of the scale has energy `(2ρ δ)²`
    // (`fire::Fire::relax`).
    let pairs = forces.overlaps.max(1) as f64;
    let rms = (forces.energy / (pairs * 4.0 * rho2)).sqrt() - s * margin;
    let floor = FLOOR * resolution * s;
    let step = (STEP * rms).max(floor);
    let next = match target && s > 1.0 && s - step >= 1.0 - TARGET_BELOW * resolution {
        true => 1.0,
        false => s - step.min(MAX_STEP * s),
    };
    (next > low * (1.0 + resolution)).then_some((next, step == floor))
}
