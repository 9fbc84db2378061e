//! The files of one output directory, each written atomically.

use super::ReportError;
use crate::io::atomic::write_atomically;
use std::io::{self, Write};
use std::path::{Path, PathBuf};

/// The files written into one output directory, each atomically
/// ([`write_atomically`]), in the order written.
#[derive(Debug)]
pub struct OutputFiles<'a> {
    dir: &'a Path,
    written: Vec<PathBuf>,
}

impl<'a> OutputFiles<'a> {
    /// Nothing written yet into `dir` (which must exist).
    pub fn new(dir: &'a Path) -> Self {
        Self {
            dir,
            written: Vec::new(),
        }
    }

    /// Writes `dir/name` through `write`, to a temporary name renamed when complete;
    /// on error nothing is left under either name.
    pub fn write(
        &mut self,
        name: &str,
        write: impl FnOnce(&mut dyn Write) -> io::Result<()>,
    ) -> Result<(), ReportError> {
        let path = self.dir.join(name);
        write_atomically(&path, |w| write(w)).map_err(|source| ReportError::Write {
            path: path.clone(),
            source,
        })?;
        self.written.push(path);
        Ok(())
    }

    /// `dir/name`.
    pub fn path(&self, name: &str) -> PathBuf {
        self.dir.join(name)
    }

    /// Records a file written (atomically) by someone else.
    pub fn record(&mut self, path: PathBuf) {
        self.written.push(path);
    }

    /// The error of failing to write `dir/name`.
    pub fn error(&self, name: &str, source: io::Error) -> ReportError {
        ReportError::Write {
            path: self.dir.join(name),
            source,
        }
    }

    /// The paths written so far, in order.
    pub fn written(&self) -> &[PathBuf] {
        &self.written
    }

    /// The paths written, in order.
    pub fn into_written(self) -> Vec<PathBuf> {
        self.written
    }
}

/// Creates `dir` and its parents if missing.
pub fn create_dir(dir: &Path) -> Result<(), ReportError> {
    std::fs::create_dir_all(dir).map_err(|source| ReportError::CreateDir {
        path: dir.to_owned(),
        source,
    })
}
