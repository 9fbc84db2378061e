//! Scratch directories, their listings, and the `pack` binary run in one.

use std::path::{Path, PathBuf};
use std::process::{Command, Output};

/// A fresh, empty scratch directory `{prefix}-{name}` in cargo's temporary directory for
/// integration tests (`target/tmp`): one per test, emptied when the test starts again and
/// left in place afterwards to look at, so repeated runs do not fill the system's `/tmp`.
pub fn scratch(prefix: &str, name: &str) -> PathBuf {
    let dir = Path::new(env!("CARGO_TARGET_TMPDIR")).join(format!("{prefix}-{name}"));
    let _ = std::fs::remove_dir_all(&dir);
    std::fs::create_dir_all(&dir).unwrap();
    dir
}

/// The names of the entries of `dir`, sorted; none if it does not exist.
pub fn files_in(dir: &Path) -> Vec<String> {
    match std::fs::read_dir(dir) {
        Ok(entries) => {
            let mut names: Vec<String> = entries
                .map(|e| e.unwrap().file_name().to_string_lossy().into_owned())
                .collect();
            names.sort();
            names
        }
        Err(_) => Vec::new(),
    }
}

/// Runs the `pack` binary with `args` in `dir`, and waits for it.
pub fn pack_in(dir: &Path, args: &[&str]) -> Output {
    Command::new(env!("CARGO_BIN_EXE_pack"))
        .args(args)
        .current_dir(dir)
        .output()
        .unwrap()
}

/// `path` (relative to the repository) as an absolute path.
pub fn repo(path: &str) -> String {
    PathBuf::from(env!("CARGO_MANIFEST_DIR"))
        .join(path)
        .display()
        .to_string()
}

/// Runs `pack` with `args` in `dir` and asserts that it succeeded (its stderr shown
/// when not).
pub fn pack_ok(dir: &Path, args: &[&str]) {
    let run = pack_in(dir, args);
    assert_eq!(
        run.status.code(),
        Some(0),
        "{}",
        String::from_utf8_lossy(&run.stderr)
    );
}
