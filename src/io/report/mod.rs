//! What a packing run writes: the grain table (`grains.csv`) and the run's summary
//! (`summary.json`), with the statistics of the packed grains against the scene's laws.
//!
//! Each file is written to a temporary name beside it and renamed when complete
//! ([`write_atomically`]), so a reader never sees a partial file; `summary.json` is
//! written last.
//!
//! ```no_run
//! use grainpack::io::report::{write_outputs, RunInfo, Summary};
//! use grainpack::io::scene::Scene;
//! use grainpack::packing::pack;
//! use std::sync::atomic::AtomicBool;
//! use std::time::Duration;
//!
//! let scene = Scene::from_path("configs/grains.toml".as_ref())?;
//! let specs = scene.sample_grains(&mut scene.rng())?;
//! let stop = AtomicBool::new(false);
//! let packing = pack(&specs, &scene.domain, &scene.packing, scene.seed, &stop, &mut |_| {})?;
//! let run = RunInfo { threads: 1, packing: Duration::ZERO, total: Duration::ZERO };
//! let summary = Summary::new(&scene, &specs, &packing, &run);
//! write_outputs(&scene.output, &packing.grains, &summary)?;
//! # Ok::<(), Box<dyn std::error::Error>>(())
//! ```

pub mod stats;
mod summary;

pub use summary::{
    CounterSummary, PhaseSummary, QuantitySummary, RunInfo, Share, Summary, TimingSummary,
};

use crate::io::atomic::write_atomically;
use crate::io::cases::format_17;
use crate::io::scene::OutputSpec;
use crate::packing::PackedGrain;
use std::io::{self, Write};
use std::path::{Path, PathBuf};

/// File name of the grain table.
pub const GRAINS_CSV: &str = "grains.csv";

/// File name of the summary.
pub const SUMMARY_JSON: &str = "summary.json";

/// Columns of `grains.csv`: id, phase index, centre, semi-axes, unit quaternion
/// `[w, x, y, z]` (Hamilton; semi-axis `k` along column `k` of its rotation matrix).
pub const GRAINS_HEADER: [&str; 12] = [
    "id", "phase", "x", "y", "z", "a1", "a2", "a3", "qw", "qx", "qy", "qz",
];

/// Why the outputs could not be written.
#[derive(Debug, thiserror::Error)]
#[non_exhaustive]
pub enum ReportError {
    /// The output directory could not be created.
    #[error("cannot create the output directory {}", path.display())]
    CreateDir {
        /// The directory.
        path: PathBuf,
        /// What the operating system said.
        #[source]
        source: io::Error,
    },
    /// A file could not be written (nothing was left under its name).
    #[error("cannot write {}", path.display())]
    Write {
        /// The file.
        path: PathBuf,
        /// What went wrong.
        #[source]
        source: io::Error,
    },
}

/// Writes the grain table: [`GRAINS_HEADER`], then one row per grain with integers for
/// `id` and `phase` and 17 significant digits ([`format_17`]) for the rest, which
/// read back to the same doubles.
pub fn write_grains_csv(out: &mut dyn Write, grains: &[PackedGrain]) -> io::Result<()> {
    let mut writer = csv::Writer::from_writer(out);
    writer.write_record(GRAINS_HEADER)?;
    let mut row = Vec::with_capacity(GRAINS_HEADER.len());
    for g in grains {
        row.clear();
        row.push(g.id.to_string());
        row.push(g.phase.to_string());
        row.extend(
            g.centre
                .iter()
                .chain(&g.semi_axes)
                .chain(&g.quaternion)
                .map(|&v| format_17(v)),
        );
        writer.write_record(&row)?;
    }
    writer.flush()
}

/// Writes the summary as pretty-printed JSON, ending with a newline.
pub fn write_summary_json(out: &mut dyn Write, summary: &Summary) -> io::Result<()> {
    serde_json::to_writer_pretty(&mut *out, summary)?;
    out.write_all(b"\n")
}

/// Creates `output.dir` if needed and writes the files `output` enables, each to a
/// temporary name renamed when complete: [`GRAINS_CSV`], then [`SUMMARY_JSON`].
/// Returns the paths written.
pub fn write_outputs(
    output: &OutputSpec,
    grains: &[PackedGrain],
    summary: &Summary,
) -> Result<Vec<PathBuf>, ReportError> {
    let dir = &output.dir;
    if output.grains_csv || output.summary_json {
        create_dir(dir)?;
    }
    let mut written = Vec::new();
    let mut write = |name: &str, f: &dyn Fn(&mut dyn Write) -> io::Result<()>| {
        let path = dir.join(name);
        write_atomically(&path, |w| f(w)).map_err(|source| ReportError::Write {
            path: path.clone(),
            source,
        })?;
        written.push(path);
        Ok::<(), ReportError>(())
    };
    if output.grains_csv {
        write(GRAINS_CSV, &|w| write_grains_csv(w, grains))?;
    }
    if output.summary_json {
        write(SUMMARY_JSON, &|w| write_summary_json(w, summary))?;
    }
    Ok(written)
}

/// Creates `dir` and its parents if missing.
pub fn create_dir(dir: &Path) -> Result<(), ReportError> {
    std::fs::create_dir_all(dir).map_err(|source| ReportError::CreateDir {
        path: dir.to_owned(),
        source,
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn grains_csv_has_the_header_and_17_digit_values_that_read_back_exactly() {
        let grain = PackedGrain {
            id: 0,
            phase: 1,
            centre: [0.1, 2.0 / 3.0, 1e-300],
            semi_axes: [3.0, 1.5, 1.5],
            quaternion: [0.5f64.sqrt(), 0.0, 0.0, -(0.5f64.sqrt())],
        };
        let mut out = Vec::new();
        write_grains_csv(&mut out, &[grain]).unwrap();
        let text = String::from_utf8(out).unwrap();
        let mut lines = text.lines();
        assert_eq!(lines.next(), Some("id,phase,x,y,z,a1,a2,a3,qw,qx,qy,qz"));
        let row: Vec<&str> = lines.next().unwrap().split(',').collect();
        assert_eq!(&row[..2], ["0", "1"]);
        let values: Vec<f64> = row[2..].iter().map(|v| v.parse().unwrap()).collect();
        let want: Vec<f64> = grain
            .centre
            .iter()
            .chain(&grain.semi_axes)
            .chain(&grain.quaternion)
            .copied()
            .collect();
        assert_eq!(values, want);
        assert_eq!(row[3], "6.6666666666666663e-1");
        assert_eq!(lines.next(), None);
    }
}
