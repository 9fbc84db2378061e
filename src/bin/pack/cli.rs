//! Command-line options.

use clap::{Parser, Subcommand};
use grainpack::contact::Method;
use std::path::PathBuf;

/// Packs ellipsoidal grains into a box without overlaps.
#[derive(Debug, Parser)]
#[command(name = "pack", version, about)]
pub struct Cli {
    #[command(subcommand)]
    pub command: Command,
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
