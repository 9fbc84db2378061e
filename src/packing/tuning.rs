//! The engine's tunables, each with the value every shipped figure was measured with as
//! its default. A scene does not set them; a library user may, through
//! [`Job::tuning`](super::Job::tuning), and [`Tuning::check`] refuses values the loop
//! cannot work with.

use crate::octree;
use thiserror::Error;

/// FIRE, the integrator (Bitzek et al. 2006, FIRE 2.0 of Guénolé et al. 2020).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct FireParams {
    /// Time step at the start (grains have unit mass; a pair's stiffness is about 2).
    /// Default 0.05.
    pub dt_start: f64,
    /// Largest time step, below the stability limit `2/√k` of a grain with ten
    /// contacts. Default 0.4.
    pub dt_max: f64,
    /// Smallest time step. Default 0.002.
    pub dt_min: f64,
    /// Steps with positive power before the time step may grow (FIRE's `N_delay`).
    /// Default 5.
    pub n_delay: u32,
    /// Growth of the time step after `n_delay` steps of positive power. Default 1.1.
    pub dt_grow: f64,
    /// Shrinking of the time step when the power turns negative. Default 0.5.
    pub dt_shrink: f64,
    /// Initial mixing of the velocity toward the force direction. Default 0.1.
    pub alpha_start: f64,
    /// Decay of the mixing after each step of positive power. Default 0.99.
    pub alpha_decay: f64,
    /// The most a grain moves in one step, as a share of `S ×` its smallest
    /// semi-axis: it keeps a grain from passing through a thin neighbour in one step.
    /// Default 0.1.
    pub max_move: f64,
    /// The jamming test (`packing/jamming.rs`) judges a relaxation every `window`
    /// steps, by the least energy per grain of each window. Default 100.
    pub window: u64,
    /// A relaxation is jammed when its energy per grain is on a positive plateau: the
    /// log-log slope `−d ln E / d ln(steps)`, measured between the latest window and
    /// the window at half as many steps, below `plateau_slope`. Any decay toward zero
    /// steeper than `t^−plateau_slope` goes on. Default 0.1 (the energy falls by less
    /// than 7 % while the steps double).
    pub plateau_slope: f64,
}

impl Default for FireParams {
    fn default() -> Self {
        Self {
            dt_start: 0.05,
            dt_max: 0.4,
            dt_min: 0.002,
            n_delay: 5,
            dt_grow: 1.1,
            dt_shrink: 0.5,
            alpha_start: 0.1,
            alpha_decay: 0.99,
            max_move: 0.1,
            window: 100,
            plateau_slope: 0.1,
        }
    }
}

/// The compress-and-relax protocol around FIRE (module docs of [`packing`](super)).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct ProtocolParams {
    /// Pairs are kept at least this far apart, relatively: a relaxation is clean when
    /// every pair has `μ ≥ 1 + contact_gap` at the true sizes. 1e-9 (the default) is
    /// far above the error of the fast contact function on the shapes of a scene and
    /// far below anything a user can see.
    pub contact_gap: f64,
    /// The energy is taken at the scale inflated by `1 + margin`: the relaxation can
    /// stop when the overlaps at the inflated size are below `margin`, since the true
    /// sizes are then apart. 10⁻³ (the default) costs at most 0.3 % of packing fraction
    /// at jamming.
    pub margin: f64,
    /// FIRE steps the relaxation at the target scale (and each compression of a
    /// shallow first jam, module docs of `packing`) may take before it counts as
    /// stuck; a shallow one stops at its patience ([`trial_steps`](Self::trial_steps))
    /// first. Default 20 000.
    pub stage_steps: u64,
    /// FIRE steps a relaxation below the target scale (a trial of the bisection) may
    /// take at `packing.effort = 1`, before it counts as jammed at that scale.
    /// Default 1000. On 10 000 periodic spheres, equal or lognormal, 300 to 3000 give
    /// the same density to 0.001 (BENCHMARKS.md, "Dense packing"), and 20 000, the
    /// budget of the target's own relaxation, took ten times as long for 0.0003 more
    /// (125 s against 13 s, measured during development with a first form of the
    /// plateau test). It is also the patience of the relaxations before the search
    /// (the target's own and its compressions, module `jamming`): one still shallow
    /// after that many steps counts as jammed.
    pub trial_steps: u64,
    /// The state shrunk by its smallest μ is shrunk by this much more, so that it keeps
    /// the `contact_gap` after rounding. Default `4 · contact_gap`.
    pub shrink_margin: f64,
    /// Stiffness of the pull back toward the drawn orientations once grains that may
    /// turn are packed: strong enough to turn them back through small overlaps (it is
    /// measured against the overlap energy of a pair, `(S(ρ_i + ρ_j))²(1 − μ)²`), after
    /// which a plain relaxation clears those overlaps. On kanapy's scene 0.1 (the
    /// default) halves the median turn (21° to 9–10°); 0.01–1 do about as well.
    pub restore_stiffness: f64,
    /// FIRE steps of the pull; more turn the grains back little further (200, the
    /// default: median turn 9.7°, 500: 8.2° on kanapy's scene, at 1.5 times the cost).
    pub restore_steps: u64,
    /// From the first deep jam, lower the scale in short relaxations that keep FIRE's
    /// velocities, each by the state's root-mean-square overlap (module `descent`),
    /// before bisecting what is left, instead of bisecting from there (on by default;
    /// off, the bisection alone, as until 2026-11-28). 10 000 equal spheres asked 0.70
    /// jam as dense in 2.7–2.9 times the time of a reachable 0.62 instead of 3.9–6.5,
    /// the family of starts (`benches/density/start/`) in 0.69 of the time at +0.00003
    /// of packing fraction on the mean; grains that relax slowly near their jamming
    /// point lose a little (lognormal spheres 0.0009 at `effort = 1`, in half the time;
    /// BENCHMARKS.md, "The descent by default").
    pub descent: bool,
}

impl Default for ProtocolParams {
    fn default() -> Self {
        let contact_gap = 1e-9;
        Self {
            contact_gap,
            margin: 1e-3,
            stage_steps: 20_000,
            trial_steps: 1000,
            shrink_margin: 4.0 * contact_gap,
            restore_stiffness: 0.1,
            restore_steps: 200,
            descent: true,
        }
    }
}

/// The broad phase of the loop: a Verlet list of candidate pairs from the octree.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct NeighbourParams {
    /// Candidate pairs are found for bounding spheres grown by a skin of
    /// `skin · S · (mean bounding radius)`, and kept while no pair can have come into
    /// reach. A pair in the list costs almost nothing while its μ bound keeps it out of
    /// reach, so a thick skin that halves the octree builds pays: on
    /// `configs/kanapy_elongated.toml` (one thread, user time of 3 runs) 0.15 took
    /// 0.86–1.09 s, 0.3 0.80–1.02 s, 0.6 (the default) 0.74–0.83 s.
    pub skin: f64,
    /// The octree's limits ([`octree::Params::default`]).
    pub octree: octree::Params,
}

impl Default for NeighbourParams {
    fn default() -> Self {
        Self {
            skin: 0.6,
            octree: octree::Params::default(),
        }
    }
}

/// Everything of the engine that is not the scene.
#[derive(Debug, Clone, Copy, PartialEq, Default)]
pub struct Tuning {
    /// The integrator.
    pub fire: FireParams,
    /// The protocol around it.
    pub protocol: ProtocolParams,
    /// The broad phase.
    pub neighbours: NeighbourParams,
}

/// A tunable the loop cannot work with.
#[derive(Debug, Clone, PartialEq, Error)]
#[error("tuning: {name} = {value} is out of range: {expected}")]
pub struct TuningError {
    /// The field, as `fire.dt_max`.
    pub name: &'static str,
    /// Its value.
    pub value: String,
    /// What it must be.
    pub expected: &'static str,
}

/// What a tunable must be.
#[derive(Clone, Copy)]
enum Range {
    Positive,
    NonNegative,
    AtLeastOne,
    Unit,
}

impl Range {
    fn holds(self, x: f64) -> bool {
        x.is_finite()
            && match self {
                Range::Positive => x > 0.0,
                Range::NonNegative => x >= 0.0,
                Range::AtLeastOne => x >= 1.0,
                Range::Unit => x > 0.0 && x < 1.0,
            }
    }

    fn text(self) -> &'static str {
        match self {
            Range::Positive => "positive and finite",
            Range::NonNegative => "non-negative and finite",
            Range::AtLeastOne => "at least 1 and finite",
            Range::Unit => "in (0, 1)",
        }
    }
}

impl Tuning {
    /// Checks every field: time steps positive with `dt_min ≤ dt_start ≤ dt_max`,
    /// growth at least 1, ratios in `(0, 1)`, step counts and window at least 1,
    /// margins and the skin positive, the gap and the pull non-negative, all finite.
    /// The octree's limits are checked by the octree when the loop first builds it.
    ///
    /// ```
    /// use grainpack::packing::Tuning;
    /// assert!(Tuning::default().check().is_ok());
    /// let mut t = Tuning::default();
    /// t.fire.dt_min = 1.0;
    /// assert!(t.check().unwrap_err().to_string().contains("fire.dt_min = 1"));
    /// ```
    pub fn check(&self) -> Result<(), TuningError> {
        use Range::*;
        let (f, p, n) = (&self.fire, &self.protocol, &self.neighbours);
        let fields = [
            ("fire.dt_start", f.dt_start, Positive),
            ("fire.dt_max", f.dt_max, Positive),
            ("fire.dt_min", f.dt_min, Positive),
            ("fire.n_delay", f64::from(f.n_delay), NonNegative),
            ("fire.dt_grow", f.dt_grow, AtLeastOne),
            ("fire.dt_shrink", f.dt_shrink, Unit),
            ("fire.alpha_start", f.alpha_start, Unit),
            ("fire.alpha_decay", f.alpha_decay, Unit),
            ("fire.max_move", f.max_move, Positive),
            ("fire.window", f.window as f64, AtLeastOne),
            ("fire.plateau_slope", f.plateau_slope, Positive),
            ("protocol.contact_gap", p.contact_gap, NonNegative),
            ("protocol.margin", p.margin, Positive),
            ("protocol.stage_steps", p.stage_steps as f64, AtLeastOne),
            ("protocol.trial_steps", p.trial_steps as f64, AtLeastOne),
            ("protocol.shrink_margin", p.shrink_margin, Unit),
            (
                "protocol.restore_stiffness",
                p.restore_stiffness,
                NonNegative,
            ),
            (
                "protocol.restore_steps",
                p.restore_steps as f64,
                NonNegative,
            ),
            ("neighbours.skin", n.skin, Positive),
        ];
        let out_of_range = fields.into_iter().find(|(_, x, range)| !range.holds(*x));
        if let Some((name, value, range)) = out_of_range {
            return Err(TuningError {
                name,
                value: value.to_string(),
                expected: range.text(),
            });
        }
        let ordered = [
            (
                "fire.dt_min",
                f.dt_min,
                f.dt_min <= f.dt_start,
                "at most fire.dt_start",
            ),
            (
                "fire.dt_start",
                f.dt_start,
                f.dt_start <= f.dt_max,
                "at most fire.dt_max",
            ),
        ];
        match ordered.into_iter().find(|c| !c.2) {
            Some((name, value, _, expected)) => Err(TuningError {
                name,
                value: value.to_string(),
                expected,
            }),
            None => Ok(()),
        }
    }
}
