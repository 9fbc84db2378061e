//! What goes into [`pack`](super::pack) and what comes out: the job, the progress it
//! reports, its counters, its result and its errors.

use super::PackedGrain;
use super::{StopReason, Tuning, TuningError};
use crate::contact::ShapeError;
use crate::octree::OctreeError;
use crate::scene::{Domain, GrainSpec, PackingParams};
use std::time::Duration;

/// What the loop reports while it runs, for a progress bar.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Progress {
    /// FIRE steps done.
    pub step: u64,
    /// The trial scale being relaxed (1 = target sizes).
    pub scale: f64,
    /// Packing fraction at that scale.
    pub fraction: f64,
    /// Pairs overlapping in the last step (at the scale inflated by
    /// [`margin`](super::ProtocolParams::margin)).
    pub overlaps: usize,
}

/// Counters and timers of the loop's stages.
#[derive(Debug, Clone, Copy, Default, PartialEq)]
pub struct Counters {
    /// Relaxations (one per trial scale).
    pub steps: u64,
    /// FIRE steps over all relaxations (each a broad, narrow phase and response).
    pub fire_steps: u64,
    /// Builds of the candidate-pair list.
    pub list_builds: u64,
    /// Candidate pairs tested by the narrow phase.
    pub pairs_tested: u64,
    /// Time in the broad phase.
    pub broad_phase: Duration,
    /// Time in the narrow phase.
    pub narrow_phase: Duration,
    /// Time in the response (forces, moves).
    pub response: Duration,
    /// Swaps of grains kept by the unjamming moves (`packing.unjam = "swap"`).
    pub swaps: u64,
}

/// How a relaxation ended.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Outcome {
    /// Every pair apart at the real scale (μ ≥ 1 + contact gap), every grain inside.
    Clean,
    /// The grains are jammed at this scale: the energy per grain converged to a
    /// positive plateau, or a relaxation before the search ran out of its patience
    /// (the jamming test of `packing/jamming.rs`).
    Stuck,
    /// The step budget ran out, or under a time limit a relaxation before the first
    /// clean state gave way (`packing::time_limit::GIVE_WAY`, `GIVE_WAY_TARGET`).
    Budget,
    /// The caller asked to stop, or the time limit ran out.
    Interrupted,
}

impl Outcome {
    /// Its name in `summary.json`: `"clean"`, `"stuck"`, `"budget"`, `"interrupted"`.
    pub fn name(self) -> &'static str {
        match self {
            Outcome::Clean => "clean",
            Outcome::Stuck => "stuck",
            Outcome::Budget => "budget",
            Outcome::Interrupted => "interrupted",
        }
    }
}

/// One relaxation of the loop at a trial scale (the recompression cycles' unjamming
/// moves and the turn back are not trials).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Trial {
    /// The trial scale (1 = target sizes).
    pub scale: f64,
    /// The packing fraction at that scale.
    pub fraction: f64,
    /// How the relaxation ended.
    pub outcome: Outcome,
    /// Its FIRE steps.
    pub fire_steps: u64,
    /// The overlap energy per grain at its last step (at the scale inflated by the
    /// [`margin`](super::ProtocolParams::margin)).
    pub energy_per_grain: f64,
}

/// The outcome of [`pack`](super::pack).
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
    /// Its relaxations at the trial scales, in order: where the FIRE steps went.
    pub trials: Vec<Trial>,
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
    #[error("grain {id}: {source}")]
    Grain {
        /// Its index.
        id: usize,
        /// What is wrong with its shape.
        source: ShapeError,
    },
    /// A packed grain's id is not its index in the slice.
    #[error("grain {index}: id {id} is not its index")]
    Misnumbered {
        /// Its index.
        index: usize,
        /// Its id.
        id: u32,
    },
    /// The box or the grains' bounding spheres were rejected by the broad phase.
    #[error("broad phase: {0}")]
    Domain(#[from] OctreeError),
    /// More grains than ids can name.
    #[error("{0} grains: at most 2^32 − 1 are supported")]
    TooMany(usize),
    /// A tunable is out of range.
    #[error(transparent)]
    Tuning(#[from] TuningError),
}

/// What to pack: the grains, the box, the scene's packing parameters, the engine's
/// tunables and the seed of the starting positions.
#[derive(Debug, Clone, Copy)]
pub struct Job<'a> {
    /// The grains as drawn (id = index).
    pub specs: &'a [GrainSpec],
    /// The box.
    pub domain: &'a Domain,
    /// The scene's `[packing]` table.
    pub params: &'a PackingParams,
    /// The engine's tunables ([`Tuning::default`] for the shipped behaviour).
    pub tuning: &'a Tuning,
    /// Seed of the starting positions.
    pub seed: u64,
}

/// What [`verify`](super::verify) found.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Verification {
    /// The gap checked (`packing.gap`): every pair needs μ ≥ 1 + `gap`, every grain
    /// scaled by 1 + `gap` about its centre must stay inside the walls.
    pub gap: f64,
    /// Pairs whose bounding spheres, scaled by 1 + `gap`, meet, each tested exactly.
    pub checked_pairs: usize,
    /// Pairs with μ² < 1 (must be 0).
    pub overlapping_pairs: usize,
    /// Pairs closer than the gap, μ² < (1 + `gap`)², overlapping ones included (must
    /// be 0; the same as `overlapping_pairs` when `gap` is 0).
    pub gap_violations: usize,
    /// Smallest μ² over the checked pairs (∞ when there are none).
    pub min_mu2: f64,
    /// The smallest gap reached, in the units of `gap`: the least of `√μ² − 1` over the
    /// pairs whose bounding spheres, scaled by `(1 + gap)(1 +`
    /// [`MIN_GAP_REACH`](super::MIN_GAP_REACH)`)`, meet (the checked pairs and a few
    /// more) and, in a walled box, of `t − 1` over the grains, `t` the scale about its
    /// centre at which a grain would touch a wall. Exact whenever it is below
    /// `(1 + gap)(1 + MIN_GAP_REACH) − 1`; ∞ when no pair is that close and there is no
    /// wall.
    pub min_gap: f64,
    /// Grains scaled by 1 + `gap` crossing a wall of a walled box (must be 0; always 0
    /// when periodic).
    pub wall_violations: usize,
    /// Grains closer than the gap to their own periodic image (must be 0).
    pub self_images: usize,
}

impl Verification {
    /// No overlap of any kind, and the gap kept everywhere.
    pub fn is_clean(&self) -> bool {
        self.overlapping_pairs == 0
            && self.gap_violations == 0
            && self.wall_violations == 0
            && self.self_images == 0
    }
}
