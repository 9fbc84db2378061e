//! The growth-and-collision loop: grains grow in a box until they reach their target
//! sizes, pushed apart whenever they overlap, and the result is verified overlap-free.
//!
//! # How
//! Every grain keeps its drawn shape and orientation; one global scale `s` multiplies
//! all target semi-axes. A step:
//! 1. **grow**: `s ← min(1, s · (1 + rate))`;
//! 2. **broad phase**: the octree lists the pairs whose bounding spheres meet;
//! 3. **narrow phase**: the contact function μ of each candidate pair;
//! 4. **response**: each overlapping pair (μ < 1) is pushed apart along its centre line
//!    to the distance `d/μ` at which it would just touch (scaling sizes by μ and the
//!    distance by 1/μ are the same thing), split by volume and summed over a grain's
//!    pairs (Jacobi, so the order of pairs does not matter); walls push grains back
//!    inside a reflecting box;
//! 5. repeat 2–4 until no overlap is left or the sweep budget is spent, then adapt the
//!    rate (faster after an easy step, slower after a hard one).
//!
//! Whatever the state, shrinking every grain by the smallest μ over all pairs gives an
//! overlap-free packing: that is the "best overlap-free state" written when the target
//! cannot be reached. The result is checked afterwards by [`verify`], an exact test of
//! every pair whose bounding spheres meet.

mod grains;
mod state;
mod sweep;
mod verify;

pub use grains::{PackedGrain, StopReason};
pub use sweep::{CONTACT_GAP, OVERSHOOT};
pub use verify::{verify, Verification};

use rand::{Rng, SeedableRng};
use rand_chacha::ChaCha8Rng;
use state::State;
use std::sync::atomic::Ordering;
use sweep::Sweep;

/// Packing fraction the grains start at: small enough that random positions are
/// nearly overlap-free, large enough not to waste steps growing through empty space.
pub const START_FRACTION: f64 = 0.05;
/// Sweeps allowed per step to clear the overlaps that growth created. Measured on
/// `configs/grains.toml` (515 grains, φ = 0.60): 30 jams at 0.591 after 11 s, 100
/// reaches 0.60 in 7.7 s, 300 in 2.2 s (fewer failed steps, fewer rate halvings).
pub const SWEEPS_PER_STEP: u32 = 300;
/// After a step cleared in at most [`EASY_SWEEPS`] sweeps the growth rate is
/// multiplied by `RATE_UP`; after a step that could not be cleared, by `RATE_DOWN`
/// (and the scale steps back).
pub const RATE_UP: f64 = 1.5;
/// See [`RATE_UP`].
pub const RATE_DOWN: f64 = 0.5;
/// A step is easy when it cleared in this many sweeps or fewer.
pub const EASY_SWEEPS: u32 = 3;
/// Largest growth of the scale per step (relative).
pub const RATE_MAX: f64 = 0.05;
/// The loop reports [`StopReason::Jammed`] when the growth rate falls below this.
pub const RATE_FLOOR: f64 = 1e-7;
/// The best overlap-free state of an unfinished packing is shrunk by this much more
/// than its smallest μ, so that it keeps the [`CONTACT_GAP`] margin.
pub const SHRINK_MARGIN: f64 = 4.0 * CONTACT_GAP;
/// The loop also reports [`StopReason::Jammed`] when the scale of the last clean state
/// grew by less than `STALL_GROWTH` (relative) over the last [`STALL_STEPS`] steps.
pub const STALL_GROWTH: f64 = 1e-4;
/// See [`STALL_GROWTH`].
pub const STALL_STEPS: u64 = 200;
/// The random stream used for initial positions (the scene's sampling uses stream 0).
const POSITION_STREAM: u64 = 1;

use crate::io::scene::{Domain, GrainSpec, PackingParams};
use std::sync::atomic::AtomicBool;
use std::time::Duration;

/// What the loop reports while it runs, for a progress bar.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Progress {
    /// Steps done.
    pub step: u64,
    /// Current global scale (1 = target sizes).
    pub scale: f64,
    /// Packing fraction of the current sizes.
    pub fraction: f64,
    /// Overlapping pairs found in the last sweep.
    pub overlaps: usize,
}

/// Counters and timers of the loop's stages.
#[derive(Debug, Clone, Copy, Default, PartialEq)]
pub struct Counters {
    /// Growth steps.
    pub steps: u64,
    /// Relaxation sweeps (broad + narrow phase + response).
    pub sweeps: u64,
    /// Candidate pairs tested by the narrow phase.
    pub pairs_tested: u64,
    /// Overlapping pairs pushed apart.
    pub overlaps_resolved: u64,
    /// Time in the broad phase.
    pub broad_phase: Duration,
    /// Time in the narrow phase.
    pub narrow_phase: Duration,
    /// Time in the response (pushes, walls, wrapping).
    pub response: Duration,
}

/// The outcome of [`pack`].
#[derive(Debug, Clone)]
pub struct Packing {
    /// The grains, overlap-free, in the order of the specs given (id = index).
    pub grains: Vec<PackedGrain>,
    /// The global scale reached: 1 when every grain has its target size.
    pub scale: f64,
    /// Packing fraction: total grain volume over box volume.
    pub fraction: f64,
    /// Why the loop stopped.
    pub stop: StopReason,
    /// What the loop did.
    pub counters: Counters,
    /// The exact check of the written state.
    pub verification: Verification,
}

/// Why packing could not start.
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
#[non_exhaustive]
pub enum PackError {
    /// No grains to pack.
    #[error("no grains to pack")]
    Empty,
    /// A grain is invalid (non-positive semi-axis, non-unit quaternion).
    #[error("grain {id}: {message}")]
    Grain {
        /// Its index.
        id: usize,
        /// What is wrong.
        message: String,
    },
    /// Rotation during packing is not implemented.
    #[error("packing.rotation = true is not supported yet: orientations stay as drawn")]
    RotationUnsupported,
    /// The box or the grains' bounding spheres were rejected by the broad phase.
    #[error("broad phase: {0}")]
    Domain(String),
    /// More grains than ids can name.
    #[error("{0} grains: at most 2^32 − 1 are supported")]
    TooMany(usize),
}

/// Packs the grains into the domain. See the module docs for the algorithm.
///
/// Deterministic for a given `seed`, whatever the number of threads: candidate pairs
/// come in a fixed order, and pushes are summed in that order. `stop` is polled once
/// per sweep; when set, the loop ends with [`StopReason::Interrupted`] and returns the
/// best overlap-free state. `progress` is called once per step.
pub fn pack(
    specs: &[GrainSpec],
    domain: &Domain,
    params: &PackingParams,
    seed: u64,
    stop: &AtomicBool,
    progress: &mut dyn FnMut(&Progress),
) -> Result<Packing, PackError> {
    if params.rotation {
        return Err(PackError::RotationUnsupported);
    }
    let mut state = State::new(specs, domain)?;
    let mut rng = ChaCha8Rng::seed_from_u64(seed);
    rng.set_stream(POSITION_STREAM);
    for c in &mut state.centres {
        *c = [0, 1, 2].map(|k| rng.random::<f64>() * domain.size[k]);
    }
    let mut s = (START_FRACTION / state.fraction(1.0)).cbrt().min(1.0);
    state.confine(s);

    let mut counters = Counters::default();
    let mut sweep = Sweep::default();
    let mut rate = params.growth_rate.min(RATE_MAX);
    // The last scale at which the state was overlap-free, and its centres.
    let mut safe: Option<(f64, Vec<[f64; 3]>)> = None;
    // The clean scale STALL_STEPS ago, and when that window started.
    let (mut stall_scale, mut stall_step) = (0.0, 0);
    let reason = loop {
        if stop.load(Ordering::Relaxed) {
            break StopReason::Interrupted;
        }
        if counters.steps >= params.max_steps {
            break StopReason::StepLimit;
        }
        counters.steps += 1;
        let mut cleared = None;
        let mut overlaps = 0;
        for k in 1..=SWEEPS_PER_STEP {
            let found = sweep.run(&mut state, s, true, &mut counters)?;
            overlaps = found.overlaps;
            if found.overlaps == 0 {
                cleared = Some(k);
                break;
            }
        }
        progress(&Progress {
            step: counters.steps,
            scale: s,
            fraction: state.fraction(s),
            overlaps,
        });
        if counters.steps - stall_step >= STALL_STEPS {
            let clean = safe.as_ref().map_or(0.0, |(safe_s, _)| *safe_s);
            if clean < stall_scale * (1.0 + STALL_GROWTH) {
                break StopReason::Jammed;
            }
            (stall_scale, stall_step) = (clean, counters.steps);
        }
        match cleared {
            Some(sweeps) => {
                safe = Some((s, state.centres.clone()));
                if s >= 1.0 {
                    break StopReason::TargetReached;
                }
                if sweeps <= EASY_SWEEPS {
                    rate = (rate * RATE_UP).min(RATE_MAX);
                }
                s = (s * (1.0 + rate)).min(1.0);
            }
            None => {
                rate *= RATE_DOWN;
                if rate < RATE_FLOOR {
                    break StopReason::Jammed;
                }
                let floor = safe.as_ref().map_or(0.0, |(safe_s, _)| *safe_s);
                s = (s / (1.0 + rate)).max(floor);
            }
        }
    };

    // The state to write: the current one if clean, else the better of the last clean
    // one and the current one shrunk by its smallest μ.
    let (scale, centres) = if reason == StopReason::TargetReached {
        (s, state.centres.clone())
    } else {
        let found = sweep.run(&mut state, s, false, &mut counters)?;
        let shrunk = if found.overlaps == 0 {
            s
        } else {
            s * found.min_mu * (1.0 - SHRINK_MARGIN)
        };
        match safe {
            Some((safe_s, safe_centres)) if safe_s >= shrunk => (safe_s, safe_centres),
            _ => (shrunk, state.centres.clone()),
        }
    };
    // Wrap into the box (the sweeps wrap only when they rebuild their pair list).
    state.centres = centres;
    state.confine(scale);
    let centres = &state.centres;
    let grains: Vec<PackedGrain> = specs
        .iter()
        .zip(centres)
        .enumerate()
        .map(|(id, (spec, c))| PackedGrain {
            id: id as u32,
            phase: spec.phase,
            centre: *c,
            semi_axes: spec.semi_axes.map(|a| a * scale),
            quaternion: spec.quaternion,
        })
        .collect();
    let verification = verify(&grains, domain)?;
    let fraction = state.fraction(scale);
    Ok(Packing {
        grains,
        scale,
        fraction,
        stop: reason,
        counters,
        verification,
    })
}
