//! `pack SCENE.toml`: draw the scene's grains, pack them, check the result, write it.

use crate::cli::SceneArgs;
use crate::exit::{Exit, Failure};
use anyhow::{anyhow, Context};
use grainpack::contact::Dimension;
use grainpack::io::mesh::{gmsh_version, python};
use grainpack::io::report::{create_dir, write_outputs};
use grainpack::packing::{Outcome, Packing, Progress, StopReason, Trial};
use grainpack::run::{Drawn, RunError, RunOptions};
use grainpack::scene::{OutputSpec, Scene, Unjam};
use indicatif::{ProgressBar, ProgressDrawTarget, ProgressStyle};
use std::io::IsTerminal;
use std::path::{Path, PathBuf};
use std::sync::atomic::{AtomicBool, Ordering};
use std::time::{Duration, Instant};

/// Set by Ctrl-C; the loop polls it once per sweep and then returns its best
/// overlap-free state.
static STOP: AtomicBool = AtomicBool::new(false);

/// Exit status of a process ended by a second Ctrl-C (128 + SIGINT, as shells report).
const EXIT_SIGINT: i32 = 130;

/// Shortest time between two progress-bar updates: the bar redraws at most 20 times a
/// second, so formatting a message for every step would be wasted.
const PROGRESS_INTERVAL: Duration = Duration::from_millis(50);

/// Runs a scene: bad input is exit code 2 (nothing written), a target not reached is
/// 3 (the best overlap-free state written), anything else that fails is 1.
pub fn run(path: &Path, options: &SceneArgs) -> Result<Exit, Failure> {
    let name = path.display().to_string();
    let mut scene = Scene::from_path(path).map_err(Failure::bad_input)?;
    // Printed even with --quiet, as the other warnings: the run goes on.
    for warning in &scene.warnings {
        eprintln!("pack: warning: {warning}");
    }
    if let Some(dir) = &options.out {
        scene.output.dir.clone_from(dir);
    }
    if options.time_limit.is_some() {
        scene.packing.time_limit = options.time_limit;
    }
    // The mesher's gmsh is looked for before packing, not after a long run.
    if scene.output.mesh.is_some() {
        gmsh_version(&python()).map_err(|e| Failure::bad_input(anyhow!(e)))?;
    }
    // Made before packing, so that a directory that cannot be made fails at once
    // rather than after a long run; removed again if nothing is written to it.
    let new_dir = prepare_dir(&scene.output)?;
    ctrlc::set_handler(|| {
        if STOP.swap(true, Ordering::SeqCst) {
            std::process::exit(EXIT_SIGINT);
        }
    })
    .context("cannot install the Ctrl-C handler")?;

    let mut bar = Bar::new(options.quiet, scene.expected_count().round() as usize);
    let mut progress = |p: &Progress| bar.update(p);
    let swaps = scene.packing.unjam != Unjam::None
        && (scene.packing.effort >= grainpack::packing::MIN_CYCLE_EFFORT
            || scene.packing.time_limit.is_some());
    let mut drawn = |d: &Drawn| {
        if d.above_reachable() {
            warn_unreachable(d, swaps);
        }
    };
    let result = grainpack::run::run(
        &scene,
        RunOptions {
            seed: options.seed,
            threads: options.threads,
            progress: Some(&mut progress),
            interrupt: Some(&STOP),
            drawn: Some(&mut drawn),
            ..RunOptions::default()
        },
    );
    bar.finish();
    let result = match result {
        Ok(result) => result,
        Err(error) => {
            if let Some(dir) = new_dir {
                // Only an empty directory is removed; failing to is harmless.
                let _ = std::fs::remove_dir(dir);
            }
            return Err(run_failure(error, &name));
        }
    };
    if scene.output.mesh.is_some() && !options.quiet {
        eprintln!(
            "pack: meshing {} grains with gmsh (minutes for hundreds of grains)",
            result.packing.grains.len()
        );
    }
    let written = write_outputs(&scene, &result).map_err(anyhow::Error::from)?;
    let wrote = describe(&written.files);
    let (packing, statistics) = (&result.packing, &result.statistics);
    if !options.quiet {
        let d = &result.drawn;
        let v = &packing.verification;
        let kept = if v.gap > 0.0 {
            format!(
                "none closer than packing.gap = {} (smallest gap {:.4})",
                v.gap, v.min_gap
            )
        } else {
            "none overlapping".to_owned()
        };
        // The round grains of the estimate, and the grains' bounding shapes.
        let (round, bounds) = match d.dimension {
            Dimension::Three => ("spheres", "spheres"),
            Dimension::Two => ("discs", "circles"),
        };
        eprintln!(
            "pack: {} grains, packing fraction {:.4} reached (requested {:.4}, drawn {:.4}; \
             random close packing of {round} of these sizes ≈ {:.3}), {} after {} steps in \
             {:.2} s; {} pairs whose bounding {bounds} meet checked exactly, {kept}",
            packing.grains.len(),
            statistics.packing_fraction,
            d.requested_fraction,
            d.drawn_fraction,
            d.reachable_fraction,
            packing.stop,
            packing.counters.steps,
            result.timings.packing.as_secs_f64(),
            packing.verification.checked_pairs,
        );
        let r = &statistics.rotation;
        if r.mode != "none" {
            eprintln!(
                "pack: grains turned from their drawn orientations by a median of {:.1}° \
                 (largest {:.1}°)",
                r.median_turn_deg, r.largest_turn_deg
            );
        }
    }
    if packing.stop.is_success() {
        if !options.quiet {
            eprintln!("pack: {wrote}");
        }
        return Ok(Exit::Success);
    }
    eprintln!(
        "pack: target not reached: {}. The best overlap-free state (scale {:.4}, packing \
         fraction {:.4} of {:.4}) is kept; {wrote}",
        why(packing, &scene),
        packing.scale,
        statistics.packing_fraction,
        statistics.full_size_fraction,
    );
    Ok(Exit::NotReached)
}

/// Warns, before packing, that the drawn grains are denser than the reachable
/// estimate; printed even with `--quiet`, as the message of a target not reached is.
/// `swaps`: effort's cycles will swap grains (`"swap"` or `"anneal"`), which packs
/// spread sizes past the estimate (lognormal σ = 0.25: 0.683 against 0.664, BENCHMARKS.md "third round").
fn warn_unreachable(d: &Drawn, swaps: bool) {
    let plane = d.dimension == Dimension::Two;
    let (what, mut caveat) = match (d.spheres, plane) {
        (true, false) => ("these spheres", String::new()),
        (true, true) => ("these discs", String::new()),
        (false, false) => (
            "spheres of the same volumes",
            "; ellipsoids free to turn can pack a few percent denser, frozen or slender \
             ones much less"
                .to_string(),
        ),
        (false, true) => (
            "discs of the same areas",
            "; ellipses free to turn pack denser (aspect 1.3–1.4: about 0.89 quenched, \
             0.897 annealed), frozen or slender ones less"
                .to_string(),
        ),
    };
    if swaps {
        caveat.push_str(
            "; the moves of packing.unjam can pass it by a few percent where sizes differ",
        );
    }
    if d.gap > 0.0 {
        let power = d.dimension.exponent();
        caveat.push_str(&format!(
            ", divided by (1 + packing.gap){} = {:.4}: the grains pack as if inflated by \
             1 + {}",
            if plane { "²" } else { "³" },
            (1.0 + d.gap).powi(power),
            d.gap
        ));
    }
    eprintln!(
        "pack: warning: the drawn grains fill {:.4} of the box at full size, but random \
         packings of {what} reach about {:.3} (Farr and Groot's estimate{caveat}): the \
         target is unlikely to be reached, and the loop will stop jammed below it",
        d.drawn_fraction, d.reachable_fraction
    );
}

/// Creates the output directory if any output is enabled; returns it if it is new.
fn prepare_dir(output: &OutputSpec) -> Result<Option<PathBuf>, Failure> {
    let dir = &output.dir;
    if !output.writes_anything() || dir.is_dir() {
        return Ok(None);
    }
    create_dir(dir).map_err(anyhow::Error::from)?;
    Ok(Some(dir.clone()))
}

/// A failed run, as the user reads it: errors of this scene are prefixed with its
/// file name. Each is internal (exit code 1): a validated scene always packs; too many
/// `--threads` is bad input (exit code 2).
fn run_failure(error: RunError, name: &str) -> Failure {
    match error {
        RunError::TooManyThreads { .. } => return Failure::bad_input(error),
        RunError::Sample(_) | RunError::Pack(_) => anyhow!(error).context(name.to_owned()),
        _ => anyhow!(error),
    }
    .into()
}

/// Why the loop stopped short, in words.
fn why(packing: &Packing, scene: &Scene) -> String {
    match packing.stop {
        StopReason::TargetReached => "the target was reached".to_owned(),
        StopReason::Jammed if scene.packing.effort < grainpack::packing::MIN_CYCLE_EFFORT => {
            format!(
                "jammed: the grains cannot grow any further at packing.effort = {} \
                 (from {} on, the jammed state is compressed again and searched anew, \
                 for more density in more time)",
                scene.packing.effort,
                grainpack::packing::MIN_CYCLE_EFFORT
            )
        }
        StopReason::Jammed => "jammed: the grains cannot grow any further".to_owned(),
        StopReason::StepLimit => format!(
            "step limit: {} steps made (packing.max_steps)",
            scene.packing.max_steps
        ),
        StopReason::Interrupted => format!("interrupted (Ctrl-C){}", unfinished(&packing.trials)),
        StopReason::TimeLimit => format!(
            "time limit: {} s of packing (packing.time_limit or --time-limit) ran out{}",
            scene.packing.time_limit.unwrap_or(f64::NAN),
            unfinished(&packing.trials)
        ),
    }
}

/// What a stop before any relaxation came out clean or jammed means: the state kept is
/// the last one shrunk until no grains overlap, sized by its deepest overlap (10 000
/// grains given 0.3–1 s kept 0.57–0.60 of 0.60 that way, nearly apart; before the
/// target's relaxation gave way, 0.0000–0.59: BENCHMARKS.md, "Time limits shorter than
/// the first relaxation, again"). After a jam the states kept are relaxed ones near the
/// jamming point (the descent's, shrunk until apart), which need no such note.
fn unfinished(trials: &[Trial]) -> &'static str {
    let settled = |t: &Trial| matches!(t.outcome, Outcome::Clean | Outcome::Stuck);
    if trials.iter().any(settled) {
        return "";
    }
    " before any relaxation came out clean or jammed, so the state kept is the last one \
     shrunk until its deepest overlap is gone; a lower target_fraction, or more time, \
     keeps a denser one"
}

/// "wrote a, b" or "wrote nothing".
fn describe(written: &[PathBuf]) -> String {
    if written.is_empty() {
        "wrote nothing (every file of [output] is turned off)".to_owned()
    } else {
        let names: Vec<String> = written.iter().map(|p| p.display().to_string()).collect();
        format!("wrote {}", names.join(", "))
    }
}

/// The progress bar on stderr: growth (the scale, 0 to 1) as the bar; the step, scale,
/// packing fraction and overlapping pairs of the last sweep as its message, cut to the
/// terminal's width. Hidden with `--quiet` or when stderr is not
/// a terminal.
struct Bar {
    bar: ProgressBar,
    last: Option<Instant>,
}

impl Bar {
    fn new(quiet: bool, grains: usize) -> Self {
        let bar = if quiet || !std::io::stderr().is_terminal() {
            ProgressBar::hidden()
        } else {
            let style =
                ProgressStyle::with_template("{spinner} {elapsed:>3} [{bar:20}] {wide_msg}")
                    .unwrap_or_else(|_| ProgressStyle::default_bar())
                    .progress_chars("=> ");
            ProgressBar::with_draw_target(Some(1000), ProgressDrawTarget::stderr())
                .with_style(style)
                .with_message(format!("{grains} grains"))
        };
        Self { bar, last: None }
    }

    fn update(&mut self, p: &Progress) {
        if self.bar.is_hidden() || self.last.is_some_and(|t| t.elapsed() < PROGRESS_INTERVAL) {
            return;
        }
        self.last = Some(Instant::now());
        self.bar
            .set_position((p.scale.clamp(0.0, 1.0) * 1000.0) as u64);
        self.bar.set_message(format!(
            "step {}  scale {:.4}  fraction {:.4}  overlaps {}",
            p.step, p.scale, p.fraction, p.overlaps
        ));
    }

    fn finish(&self) {
        self.bar.finish_and_clear();
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn trials(outcomes: &[Outcome]) -> Vec<Trial> {
        let trial = |&outcome| Trial {
            scale: 1.0,
            fraction: 0.6,
            outcome,
            fire_steps: 100,
            energy_per_grain: 1e-3,
        };
        outcomes.iter().map(trial).collect()
    }

    /// A stop before any relaxation settled says what the state kept is; one after a jam
    /// (the descent's segments run out of their steps, then the limit) or a clean
    /// relaxation does not.
    #[test]
    fn only_a_stop_before_any_relaxation_settled_is_noted() {
        use Outcome::{Budget, Clean, Interrupted, Stuck};
        assert!(!unfinished(&trials(&[Interrupted])).is_empty());
        assert!(!unfinished(&trials(&[Budget, Budget, Interrupted])).is_empty());
        assert!(unfinished(&trials(&[Stuck, Budget, Budget, Interrupted])).is_empty());
        assert!(unfinished(&trials(&[Budget, Clean, Interrupted])).is_empty());
    }
}
