//! Command-line options.

use clap::{Args, CommandFactory, Parser, Subcommand};
use grainpack::contact::Method;
use std::num::NonZeroUsize;
use std::path::PathBuf;

/// Exit codes, as `pack --help` lists them.
const EXIT_CODES: &str = "\
Exit codes:
  0  the target was reached; the outputs are written and verified overlap-free
  1  an internal error, or the outputs could not be written (a packing that
     fails its final overlap check is such an error, and is never written)
  2  bad input: the scene file or the command line (the message names the file,
     line, key and value); nothing is written
  3  the target was not reached (jammed, step limit, or Ctrl-C): the best
     overlap-free state is written, and the message says why";

/// Packs ellipsoidal grains into a box without overlaps.
///
/// `pack SCENE.toml` draws the grains the scene describes, packs them, and writes
/// grains.csv and summary.json into the output directory. See docs/config.md for the
/// scene format.
#[derive(Debug, Parser)]
#[command(
    name = "pack",
    version,
    about,
    long_about,
    args_conflicts_with_subcommands = true,
    after_help = EXIT_CODES
)]
pub struct Cli {
    #[command(flatten)]
    pub scene: SceneArgs,
    #[command(subcommand)]
    pub command: Option<Command>,
}

/// Options of `pack SCENE.toml`.
#[derive(Debug, Args)]
pub struct SceneArgs {
    /// The scene file (TOML; see docs/config.md).
    #[arg(value_name = "SCENE.toml")]
    pub scene: Option<PathBuf>,
    /// Output directory (overrides the scene's output.dir); created if missing.
    #[arg(long, value_name = "DIR")]
    pub out: Option<PathBuf>,
    /// Seed of the random generator (overrides the scene's seed).
    #[arg(long, value_name = "N")]
    pub seed: Option<u64>,
    /// Threads of the packing loop (default: one per core). The result does not
    /// depend on it.
    #[arg(long, value_name = "N")]
    pub threads: Option<NonZeroUsize>,
    /// A time budget for packing, in seconds (overrides the scene's
    /// packing.time_limit): the densest overlap-free state found by then is kept.
    #[arg(long, value_name = "SECONDS", value_parser = positive_seconds)]
    pub time_limit: Option<f64>,
    /// No progress bar and no closing report on stderr; errors and the reason a
    /// target was not reached are still printed.
    #[arg(long, short)]
    pub quiet: bool,
}

#[derive(Debug, Subcommand)]
pub enum Command {
    /// Evaluates the contact function (or an overlap test) on pairs of ellipsoids read
    /// from a CSV file.
    ///
    /// Input columns: r0,r1,r2 (c2 − c1), q1_0..q1_5 and q2_0..q2_5 (upper triangles of
    /// the quadratic forms, row-major); other columns are copied through. Output: the
    /// input columns plus mu2,lambda,stop (or overlap for yes/no methods) with 17
    /// significant digits. A bad row does not stop the run: it gets empty results and a
    /// message in an `error` column, is reported on stderr with its line, and makes
    /// the exit code 2.
    Contact {
        /// CSV file of cases (`-` for standard input).
        cases: PathBuf,
        /// accurate | fast | rational | overlap | wang.
        #[arg(long, default_value = "accurate")]
        method: Method,
        /// Output CSV (standard output if absent). Written to a temporary name and
        /// renamed when complete.
        #[arg(short, long)]
        output: Option<PathBuf>,
        /// Also time the method over the whole set (I/O excluded; at least 5 rounds
        /// and 0.2 s) and print one JSON line to stderr.
        #[arg(long)]
        time: bool,
    },
}

/// What to run.
#[derive(Debug)]
pub enum Invocation {
    /// `pack SCENE.toml ...`: the scene file and the options.
    Scene(PathBuf, SceneArgs),
    /// A subcommand.
    Command(Command),
}

/// Parses the command line; exits with clap's message and code 2 when it is wrong,
/// including when neither a scene nor a subcommand is given.
pub fn parse() -> Invocation {
    let cli = Cli::parse();
    match (cli.command, cli.scene.scene.clone()) {
        (Some(command), _) => Invocation::Command(command),
        (None, Some(path)) => Invocation::Scene(path, cli.scene),
        (None, None) => Cli::command()
            .error(
                clap::error::ErrorKind::MissingRequiredArgument,
                "give a scene file (pack SCENE.toml) or a subcommand (pack contact CASES.csv)",
            )
            .exit(),
    }
}

/// A positive, finite number of seconds.
fn positive_seconds(text: &str) -> Result<f64, String> {
    match text.parse::<f64>() {
        Ok(t) if t.is_finite() && t > 0.0 => Ok(t),
        _ => Err(format!("{text:?} is not a positive number of seconds")),
    }
}
