//! The whole job as one library call: draw a scene's grains, pack them, check the
//! result exactly, and measure it against the scene's laws.
//!
//! [`run`] returns a typed [`RunResult`]; writing files is a separate step
//! ([`crate::io::report::write_outputs`]), so that a program can pack without
//! writing, or write the same result in several ways.
//!
//! ```no_run
//! use grainpack::io::report::write_outputs;
//! use grainpack::run::{run, RunOptions};
//! use grainpack::scene::Scene;
//!
//! let scene = Scene::from_path("configs/grains.toml".as_ref())?;
//! let result = run(&scene, RunOptions::default())?;
//! println!("{} grains at φ = {:.3}", result.packing.grains.len(), result.statistics.packing_fraction);
//! let written = write_outputs(&scene, &result)?;
//! # Ok::<(), Box<dyn std::error::Error>>(())
//! ```

mod plane_statistics;
mod quantity;
mod reachable;
mod shape_statistics;
mod size_table;
mod statistics;

pub use plane_statistics::{AngleStatistics, PlaneStatistics, Spread, NEIGHBOUR_REACH};
pub use quantity::QuantityStatistics;
pub use reachable::Drawn;
pub use shape_statistics::{OrientationStatistics, RatioStatistics, ShapeStatistics};
pub use size_table::SizeTableStatistics;
pub(crate) use size_table::WeightedCdf;
pub use statistics::{PhaseStatistics, Share, Statistics, TurnStatistics};

use crate::packing::{pack, Job, PackError, Packing, Progress, Tuning, Verification};
use crate::scene::{GrainSpec, SampleError, Scene};
use rand::SeedableRng;
use rand_chacha::ChaCha8Rng;
use std::num::NonZeroUsize;
use std::sync::atomic::AtomicBool;
use std::time::{Duration, Instant};
use thiserror::Error;

/// How to run a scene: everything that is not part of the scene itself.
#[derive(Default)]
pub struct RunOptions<'a> {
    /// Seed of the random generator; `None` takes the scene's.
    pub seed: Option<u64>,
    /// Threads of the packing loop; `None` runs on rayon's global pool (one thread per
    /// core unless the program set it up otherwise). The result does not depend on it.
    pub threads: Option<NonZeroUsize>,
    /// Called after every FIRE step with where the loop stands.
    pub progress: Option<&'a mut (dyn FnMut(&Progress) + Send)>,
    /// Polled once per FIRE step: once set, the loop stops and the best overlap-free
    /// state is returned with [`StopReason::Interrupted`](crate::packing::StopReason).
    pub interrupt: Option<&'a AtomicBool>,
    /// The engine's tunables; the default is what every shipped figure used.
    pub tuning: Tuning,
    /// Called once the grains are drawn, before packing starts (to warn of a target
    /// above the reachable estimate before a long run).
    pub drawn: Option<&'a mut (dyn FnMut(&Drawn) + Send)>,
}

/// What a run gives back.
#[derive(Debug, Clone)]
pub struct RunResult {
    /// The seed used.
    pub seed: u64,
    /// Threads the packing loop ran on.
    pub threads: usize,
    /// The grains as drawn, before packing (target sizes and orientations).
    pub specs: Vec<GrainSpec>,
    /// What was drawn: fractions requested and drawn, and the reachable estimate.
    pub drawn: Drawn,
    /// The packed grains, why the loop stopped, its counters, and the exact check of
    /// the result (always clean: [`run`] returns an error otherwise).
    pub packing: Packing,
    /// The packed grains against the scene's laws.
    pub statistics: Statistics,
    /// Wall times.
    pub timings: RunTimings,
}

/// Wall times of a run.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct RunTimings {
    /// The packing loop with its final check.
    pub packing: Duration,
    /// The whole call: drawing, packing, checking, statistics.
    pub total: Duration,
}

/// The most threads a run starts. rayon starts every thread of a pool at once: 10⁵
/// threads took minutes and gigabytes before the pool failed (found by the Python
/// package's hypothesis tests), and no machine this packs on has a thousand cores.
pub const MAX_THREADS: usize = 1024;

/// Why a run failed. No packing is returned with any of these.
#[derive(Debug, Error)]
#[non_exhaustive]
pub enum RunError {
    /// The grains could not be drawn (a probability below e⁻⁵⁰ on a valid scene).
    #[error("cannot draw the grains")]
    Sample(#[source] SampleError),
    /// The thread pool could not be started.
    #[error("cannot start {threads} threads")]
    Threads {
        /// Threads asked for.
        threads: NonZeroUsize,
        /// What rayon said.
        #[source]
        source: rayon::ThreadPoolBuildError,
    },
    /// More threads asked for than [`MAX_THREADS`].
    #[error("threads = {threads}: at most {MAX_THREADS}")]
    TooManyThreads {
        /// Threads asked for.
        threads: NonZeroUsize,
    },
    /// The loop could not start (an internal error on a validated scene).
    #[error("the packing failed")]
    Pack(#[source] PackError),
    /// The exact check found overlaps in the loop's result: a bug, never written.
    #[error(
        "the packing failed its final overlap check ({} overlapping pairs, {} pairs \
         closer than the gap {}, {} wall violations, {} grains meeting their own image; \
         min μ² = {:e}); nothing is written. This is a bug: please report it with the \
         scene and seed",
        .0.overlapping_pairs,
        .0.gap_violations,
        .0.gap,
        .0.wall_violations,
        .0.self_images,
        .0.min_mu2
    )]
    NotClean(Verification),
}

/// Runs `scene`: draws its grains with the seed, packs them, checks the result pair by
/// pair with the accurate contact function, and gathers the statistics.
///
/// Deterministic for a seed, whatever the number of threads.
pub fn run(scene: &Scene, options: RunOptions) -> Result<RunResult, RunError> {
    let started = Instant::now();
    let RunOptions {
        seed,
        threads,
        progress,
        interrupt,
        tuning,
        drawn,
    } = options;
    if let Some(n) = threads.filter(|n| n.get() > MAX_THREADS) {
        return Err(RunError::TooManyThreads { threads: n });
    }
    let seed = seed.unwrap_or(scene.seed);
    let mut specs = scene
        .sample_grains(&mut ChaCha8Rng::seed_from_u64(seed))
        .map_err(RunError::Sample)?;
    scene.sample_crystals(&mut specs, &mut Scene::crystal_rng(seed));
    let drawn_grains = Drawn::of(scene, &specs);
    if let Some(report) = drawn {
        report(&drawn_grains);
    }
    let never = AtomicBool::new(false);
    let stop = interrupt.unwrap_or(&never);
    let mut silent = |_: &Progress| {};
    let progress: &mut (dyn FnMut(&Progress) + Send) = match progress {
        Some(p) => p,
        None => &mut silent,
    };
    let packing_started = Instant::now();
    // A time limit counts from the start of the run: the drawing spent some of it.
    let mut params = scene.packing;
    if let Some(limit) = &mut params.time_limit {
        *limit = (*limit - started.elapsed().as_secs_f64()).max(0.0);
    }
    let job = Job {
        specs: &specs,
        domain: &scene.domain,
        params: &params,
        tuning: &tuning,
        seed,
    };
    let mut pack_scene = move || pack(&job, stop, progress);
    let (packing, threads) = match threads {
        Some(n) => {
            let pool = rayon::ThreadPoolBuilder::new()
                .num_threads(n.get())
                .build()
                .map_err(|source| RunError::Threads { threads: n, source })?;
            (pool.install(pack_scene), n.get())
        }
        None => (pack_scene(), rayon::current_num_threads()),
    };
    let packing = packing.map_err(RunError::Pack)?;
    let packing_time = packing_started.elapsed();
    if !packing.verification.is_clean() {
        return Err(RunError::NotClean(packing.verification));
    }
    let statistics = Statistics::new(scene, &specs, &packing);
    Ok(RunResult {
        seed,
        threads,
        specs,
        drawn: drawn_grains,
        packing,
        statistics,
        timings: RunTimings {
            packing: packing_time,
            total: started.elapsed(),
        },
    })
}
