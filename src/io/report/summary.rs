//! `summary.json`: the run's figures, and per phase the target statistics against
//! those of the packed grains. A serialization of a [`RunResult`] and of what the
//! writers measured, built once when everything else is written.

use super::texture::TextureSummary;
use super::RveSummary;
use crate::io::mesh::MeshStats;
use crate::run::{PhaseStatistics, PlaneStatistics, RunResult, TurnStatistics};
use crate::scene::{Boundary, Scene};
use serde::Serialize;

/// The contents of `summary.json`. Field names are the JSON keys; `min_mu2`, `min_gap`
/// and the statistics of a phase without grains may be `null`.
#[derive(Debug, Clone, Serialize)]
pub struct Summary<'a> {
    /// `CARGO_PKG_VERSION` of the program that wrote it.
    pub version: &'static str,
    /// The seed used (the scene's, or `--seed`).
    pub seed: u64,
    /// The scene's units (`[units]`): every length here, in `grains.csv`, the VTK
    /// files and the deck is in `length`, every modulus in `stress`; DAMASK's
    /// `material.yaml` and `rve.vti` are in SI.
    pub units: UnitsSummary,
    /// Box size `[Lx, Ly, Lz]`, in `units.length`.
    #[serde(rename = "box")]
    pub box_size: [f64; 3],
    /// `"periodic"` or `"reflecting"`.
    pub boundary: &'static str,
    /// Number of grains.
    pub grains: usize,
    /// The scene's `target_fraction`, or for a `grains` count its expected fraction.
    pub target_fraction: f64,
    /// Fraction the drawn grains fill at full size (scale 1).
    pub full_size_fraction: f64,
    /// Fraction the written grains fill: `Σ (4π/3) a1 a2 a3 / (Lx Ly Lz)`, or the area
    /// fraction `Σ π a1 a2 / (Lx Ly)` in 2D.
    pub packing_fraction: f64,
    /// Estimate of the densest random packing of the drawn grains, made before
    /// packing: Farr and Groot's model for spheres of their equivalent diameters
    /// ([`Drawn::reachable_fraction`](crate::run::Drawn)).
    pub reachable_fraction: f64,
    /// Whether every grain is a sphere, the case the estimate is made for.
    pub reachable_exact: bool,
    /// Global scale of the grains reached (1: target sizes).
    pub scale: f64,
    /// `target_reached`, `jammed`, `step_limit` or `interrupted`.
    pub stop_reason: &'static str,
    /// Pairs with μ² < 1 among the checked pairs (0 in anything written).
    pub overlapping_pairs: usize,
    /// Pairs whose bounding spheres meet, each checked with the exact contact function.
    pub checked_pairs: usize,
    /// Smallest μ² over the checked pairs; `null` when there are none.
    pub min_mu2: Option<f64>,
    /// The gap asked for (`packing.gap`), checked by the final verification: every
    /// pair has μ ≥ 1 + `gap`, every grain scaled by 1 + `gap` is inside the walls.
    pub gap: f64,
    /// The smallest gap reached ([`Verification::min_gap`](crate::packing::Verification)):
    /// the least `√μ² − 1` over the pairs and, in a walled box, the least room to a
    /// wall; at least `gap`, exact up to 5 % beyond it. `null` when no pair is that close
    /// and there is no wall.
    pub min_gap: Option<f64>,
    /// Grains crossing a wall of a walled box (0 in anything written).
    pub wall_violations: usize,
    /// Threads the loop ran on.
    pub threads: usize,
    /// Seconds spent, per stage.
    pub timings: TimingSummary,
    /// What the loop did.
    pub counters: CounterSummary,
    /// Its relaxations at the trial scales, in order: where the FIRE steps went.
    pub trials: Vec<TrialSummary>,
    /// Whether and how far grains turned from their drawn orientations.
    pub rotation: &'a TurnStatistics,
    /// Per phase, in scene order.
    pub phases: &'a [PhaseStatistics],
    /// In 2D: the hexatic order ψ6 and the nearest-neighbour distances.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub plane: Option<&'a PlaneStatistics>,
    /// The voxel RVE, when one was written.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub rve: Option<&'a RveSummary>,
    /// The conforming mesh, when one was written (`output.mesh`).
    #[serde(skip_serializing_if = "Option::is_none")]
    pub mesh: Option<&'a MeshStats>,
    /// Each phase's crystal orientations against its texture.
    pub textures: Vec<TextureSummary>,
    /// The scene's warnings ([`Scene::warnings`]): values its units make implausible.
    pub warnings: &'a [String],
}

/// The scene's units, by name (`"um"`, `"MPa"`, …).
#[derive(Debug, Clone, Copy, Serialize)]
pub struct UnitsSummary {
    /// Unit of every length: `"m"`, `"mm"`, `"um"` or `"nm"`.
    pub length: &'static str,
    /// Unit of every stress and modulus: `"Pa"`, `"kPa"`, `"MPa"` or `"GPa"`.
    pub stress: &'static str,
}

/// Seconds spent: the loop's stages, the loop as a whole, and the run.
#[derive(Debug, Clone, Copy, Serialize)]
pub struct TimingSummary {
    /// Broad phase, as the loop's counters measure it.
    pub broad_phase: f64,
    /// Narrow phase.
    pub narrow_phase: f64,
    /// Response.
    pub response: f64,
    /// The packing loop with its final check.
    pub packing: f64,
    /// Writing the outputs before `summary.json` (grain table, VTK, voxel RVE, plots).
    pub outputs: f64,
    /// The whole run: drawing the grains, packing, statistics and the outputs (all but
    /// `summary.json` itself).
    pub total: f64,
}

/// The loop's counters.
#[derive(Debug, Clone, Copy, Serialize)]
pub struct CounterSummary {
    /// Relaxations (one per trial scale).
    pub steps: u64,
    /// FIRE steps over all relaxations.
    pub fire_steps: u64,
    /// Builds of the candidate-pair list.
    pub list_builds: u64,
    /// Candidate pairs tested by the narrow phase.
    pub pairs_tested: u64,
    /// Swaps of grains kept by the unjamming moves (`packing.unjam = "swap"`).
    pub swaps: u64,
}

/// One relaxation of the loop ([`Trial`](crate::packing::Trial)).
#[derive(Debug, Clone, Copy, Serialize)]
pub struct TrialSummary {
    /// The trial scale (1 = target sizes).
    pub scale: f64,
    /// The packing fraction at that scale.
    pub fraction: f64,
    /// How it ended: `"clean"` (every pair apart), `"stuck"` (jammed: the energy sat on
    /// a plateau, or a shallow relaxation ran out of patience), `"budget"` (out of
    /// steps) or `"interrupted"`.
    pub outcome: &'static str,
    /// Its FIRE steps.
    pub fire_steps: u64,
    /// Overlap energy per grain at its last step.
    pub energy_per_grain: f64,
}

impl<'a> Summary<'a> {
    /// The summary of `result`, a run of `scene`, whose other outputs took `outputs`
    /// seconds to write and rendered the RVE as `rve` (when one was written), with its
    /// phases' `textures` ([`texture_summaries`](super::texture_summaries)).
    pub fn new(
        scene: &'a Scene,
        result: &'a RunResult,
        rve: Option<&'a RveSummary>,
        textures: Vec<TextureSummary>,
        outputs: f64,
    ) -> Self {
        let packing = &result.packing;
        let statistics = &result.statistics;
        let v = &packing.verification;
        let c = &packing.counters;
        Self {
            version: env!("CARGO_PKG_VERSION"),
            seed: result.seed,
            units: UnitsSummary {
                length: scene.units.length.symbol(),
                stress: scene.units.stress.symbol(),
            },
            box_size: scene.domain.size,
            boundary: match scene.domain.boundary {
                Boundary::Periodic => "periodic",
                Boundary::Reflecting => "reflecting",
            },
            grains: packing.grains.len(),
            target_fraction: statistics.target_fraction,
            full_size_fraction: statistics.full_size_fraction,
            packing_fraction: statistics.packing_fraction,
            reachable_fraction: result.drawn.reachable_fraction,
            reachable_exact: result.drawn.spheres,
            scale: packing.scale,
            stop_reason: packing.stop.name(),
            overlapping_pairs: v.overlapping_pairs,
            checked_pairs: v.checked_pairs,
            min_mu2: v.min_mu2.is_finite().then_some(v.min_mu2),
            gap: v.gap,
            min_gap: v.min_gap.is_finite().then_some(v.min_gap),
            wall_violations: v.wall_violations,
            threads: result.threads,
            timings: TimingSummary {
                broad_phase: c.broad_phase.as_secs_f64(),
                narrow_phase: c.narrow_phase.as_secs_f64(),
                response: c.response.as_secs_f64(),
                packing: result.timings.packing.as_secs_f64(),
                outputs,
                total: result.timings.total.as_secs_f64() + outputs,
            },
            counters: CounterSummary {
                steps: c.steps,
                fire_steps: c.fire_steps,
                list_builds: c.list_builds,
                pairs_tested: c.pairs_tested,
                swaps: c.swaps,
            },
            trials: (packing.trials.iter())
                .map(|t| TrialSummary {
                    scale: t.scale,
                    fraction: t.fraction,
                    outcome: t.outcome.name(),
                    fire_steps: t.fire_steps,
                    energy_per_grain: t.energy_per_grain,
                })
                .collect(),
            rotation: &statistics.rotation,
            phases: &statistics.phases,
            plane: statistics.plane.as_ref(),
            rve,
            mesh: None,
            textures,
            warnings: &scene.warnings,
        }
    }
}
