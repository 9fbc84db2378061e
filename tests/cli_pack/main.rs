//! End-to-end tests of `pack SCENE.toml`: the binary, its exit codes, and what it
//! wrote, read back and checked by an independent overlap test (nalgebra and a
//! golden-section search, nothing of grainpack's contact module or octree).

mod check;
#[path = "../support/mod.rs"]
mod support;
mod written;

use serde_json::Value;
use std::path::{Path, PathBuf};
use std::process::{Command, Output};
use support::files::{files_in, pack_in};
use support::packed::{check_overlaps, extent, read_grains, Grain};

/// A fresh, empty directory for one test.
fn scratch(name: &str) -> PathBuf {
    support::files::scratch("pack", name)
}

fn stderr(run: &Output) -> String {
    String::from_utf8_lossy(&run.stderr).into_owned()
}

/// Two phases in a periodic cube, about 0.3 full: a matrix of randomly oriented
/// grains of aspect ratio 1–2, and prolate grains tilted in the x–y plane (kanapy's
/// tilt law) whose tilt angle the summary reports.
const PERIODIC: &str = r#"
seed = 5
grains = 60

[box]
size = [30.0, 30.0, 30.0]
boundary = "periodic"

[[phase]]
name = "matrix"
share = 0.7
size = { distribution = "lognormal", sigma = 0.3, scale = 6.0, min = 4.0, max = 9.0 }
aspect_ratio = { distribution = "uniform", min = 1.0, max = 2.0 }

[[phase]]
name = "tilted"
share = 0.3
size = { distribution = "normal", mean = 6.0, std = 1.0, min = 4.0, max = 8.0 }
aspect_ratio = { distribution = "constant", value = 2.0 }
orientation = { kind = "tilt", axis = "z", kappa = 1.0, mean = 90.0, min = 0.0, max = 180.0 }
"#;

/// Platelets (aspect ratio 0.5–0.9) aligned with an oblique axis, between walls,
/// about 0.3 full.
const REFLECTING: &str = r#"
seed = 11
grains = 60

[box]
size = [30.0, 26.0, 24.0]
boundary = "reflecting"

[[phase]]
name = "platelets"
size = { distribution = "lognormal", sigma = 0.25, scale = 6.0, min = 4.0, max = 8.0 }
aspect_ratio = { distribution = "uniform", min = 0.5, max = 0.9 }
orientation = { kind = "aligned", axis = [1.0, 1.0, 1.0] }
"#;

fn write_scene(dir: &Path, name: &str, text: &str) -> PathBuf {
    let path = dir.join(name);
    std::fs::write(&path, text).unwrap();
    path
}

/// Runs `pack scene.toml --out out --quiet extra...` in `dir`; returns the run and the
/// output directory.
fn run_scene(dir: &Path, text: &str, extra: &[&str]) -> (Output, PathBuf) {
    write_scene(dir, "scene.toml", text);
    let mut args = vec!["scene.toml", "--out", "out", "--quiet"];
    args.extend(extra);
    (pack_in(dir, &args), dir.join("out"))
}

// ---------------------------------------------------------------------------------
// Bad input and the command line.

/// Each bad scene: the text, the line and key the message must name.
fn bad_scenes() -> Vec<(&'static str, String, &'static str, &'static str)> {
    let base = PERIODIC;
    vec![
        (
            "syntax",
            base.replace("grains = 60", "grains = = 60"),
            ":3:",
            "invalid TOML",
        ),
        (
            "unknown_key",
            base.replace("boundary = \"periodic\"", "boundery = \"periodic\""),
            ":7:",
            "box.boundery",
        ),
        (
            "negative_size",
            base.replace("[30.0, 30.0, 30.0]", "[30.0, -30.0, 30.0]"),
            ":6:",
            "box.size",
        ),
        (
            "reversed_cutoffs",
            base.replace("min = 4.0, max = 9.0", "min = 9.0, max = 4.0"),
            ":12:",
            "phase[0].size.max",
        ),
        (
            "fraction_0_9",
            base.replace("grains = 60", "target_fraction = 0.9"),
            ":3:",
            "target_fraction = 0.9",
        ),
        (
            // A 2D scene (a rectangle of 60 × 60) with a tilt axis it has no use for.
            "plane_tilt_about_x",
            base.replace("[30.0, 30.0, 30.0]", "[60.0, 60.0]")
                .replace("axis = \"z\"", "axis = \"x\""),
            ":20:",
            "phase[1].orientation.axis = \"x\": has no meaning in a 2D scene",
        ),
    ]
}

#[test]
fn bad_scenes_exit_2_name_file_line_and_key_and_write_nothing() {
    for (name, text, line, key) in bad_scenes() {
        let dir = scratch(&format!("bad-{name}"));
        let file = format!("{name}.toml");
        write_scene(&dir, &file, &text);
        let run = pack_in(&dir, &[&file, "--out", "out"]);
        let err = stderr(&run);
        assert_eq!(run.status.code(), Some(2), "{name}: {err}");
        assert!(
            err.starts_with(&format!("pack: error: {file}{line}")),
            "{name}: {err}"
        );
        assert!(err.contains(key), "{name}: {err}");
        assert!(!err.contains("panicked"), "{name}: {err}");
        assert!(!dir.join("out").exists(), "{name}: output directory made");
        assert_eq!(files_in(&dir), [file], "{name}: stray files");
    }
}

#[test]
fn a_missing_scene_file_is_bad_input() {
    let dir = scratch("missing");
    let run = pack_in(&dir, &["absent.toml", "--out", "out"]);
    assert_eq!(run.status.code(), Some(2));
    assert!(stderr(&run).contains("absent.toml"), "{}", stderr(&run));
    assert!(files_in(&dir).is_empty());
}

#[test]
fn help_lists_the_options_the_subcommand_and_the_exit_codes() {
    let run = pack_in(&std::env::temp_dir(), &["--help"]);
    assert!(run.status.success());
    let help = String::from_utf8(run.stdout).unwrap();
    for want in [
        "SCENE.toml",
        "--out",
        "--seed",
        "--threads",
        "--quiet",
        "contact",
        "Exit codes",
        "3  the target was not reached",
    ] {
        assert!(help.contains(want), "missing {want:?} in:\n{help}");
    }
}

#[test]
fn neither_scene_nor_subcommand_nor_both_is_a_usage_error() {
    let dir = scratch("usage");
    let run = pack_in(&dir, &[]);
    assert_eq!(run.status.code(), Some(2));
    assert!(
        stderr(&run).contains("give a scene file"),
        "{}",
        stderr(&run)
    );
    let run = pack_in(&dir, &["scene.toml", "contact", "cases.csv"]);
    assert_eq!(run.status.code(), Some(2));
    let run = pack_in(&dir, &["scene.toml", "--threads", "0"]);
    assert_eq!(run.status.code(), Some(2));
    assert!(files_in(&dir).is_empty());
}
