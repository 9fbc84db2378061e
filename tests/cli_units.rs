//! The scene's `[units]`, end to end through `pack`: one composite written in MPa and
//! µm, in Pa and m and in GPa and mm gives the same SI files for DAMASK and decks
//! scaled as declared; implausible values are warned about by key and the run goes on;
//! a unit that is not one is exit 2 naming its key and value.

mod support;

use std::path::Path;
use support::files::{files_in, pack_in, pack_ok, scratch};

/// The composite with lengths in `length` (`um_per_unit` micrometres each, a power of
/// ten) and moduli in `stress`.
fn composite(length: &str, um_per_unit: f64, stress: &str) -> String {
    let (particles, matrix) = moduli(stress);
    // Divided by an exact power of ten: the double nearest the decimal, as a user
    // would write it.
    let len = |um: f64| format!("{:e}", um / um_per_unit);
    format!(
        r#"
seed = 3
grains = 20
[units]
length = "{length}"
stress = "{stress}"
[box]
size = [{}, {}, {}]
[[phase]]
name = "particles"
size = {{ distribution = "uniform", min = {}, max = {} }}
aspect_ratio = {{ distribution = "constant", value = 1.3 }}
elastic = {{ E = {particles:?}, nu = 0.2 }}
[matrix]
elastic = {{ E = {matrix:?}, nu = 0.33 }}
[output]
dir = "out"
rve_resolution = [10, 10, 8]
rve_fill = "matrix"
damask = true
abaqus = true
"#,
        len(20.0),
        len(20.0),
        len(16.0),
        len(4.0),
        len(6.0),
    )
}

/// The particles' and the matrix's Young's moduli, 400 and 70 GPa, in `stress`.
fn moduli(stress: &str) -> (f64, f64) {
    match stress {
        "MPa" => (400000.0, 70000.0),
        "Pa" => (400e9, 70e9),
        "GPa" => (400.0, 70.0),
        other => panic!("{other}"),
    }
}

/// The numbers of the deck's `*Node` block and of each `*Elastic` line, in order.
fn deck_numbers(deck: &str) -> (Vec<f64>, Vec<f64>) {
    let lines: Vec<&str> = deck.lines().collect();
    let numbers = |line: &str| -> Vec<f64> {
        line.split(',')
            .map(|v| v.trim().parse::<f64>().unwrap())
            .collect()
    };
    let start = lines.iter().position(|l| *l == "*Node").unwrap() + 1;
    let nodes = lines[start..]
        .iter()
        .take_while(|l| !l.starts_with('*'))
        .flat_map(|l| numbers(l).into_iter().skip(1))
        .collect();
    let elastic = lines
        .iter()
        .enumerate()
        .filter(|(_, l)| **l == "*Elastic")
        .flat_map(|(i, _)| numbers(lines[i + 1]))
        .collect();
    (nodes, elastic)
}

/// A node coordinate is `i·(L/N)`, computed in each scene's own unit: converted, the
/// two differ by the rounding of `L/N` and of the product, a few ulp.
const COORDINATE_ULPS: f64 = 4.0 * f64::EPSILON;

#[test]
fn one_scene_in_three_unit_systems_gives_the_same_damask_files_and_scaled_decks() {
    let cases = [("um", 1.0, "MPa"), ("m", 1e6, "Pa"), ("mm", 1e3, "GPa")];
    let mut outputs = Vec::new();
    for (length, um_per_unit, stress) in cases {
        let dir = scratch("units", &format!("{length}_{stress}"));
        std::fs::write(
            dir.join("scene.toml"),
            composite(length, um_per_unit, stress),
        )
        .unwrap();
        let run = pack_in(&dir, &["scene.toml", "--quiet"]);
        let err = String::from_utf8_lossy(&run.stderr);
        assert_eq!(run.status.code(), Some(0), "{err}");
        assert!(!err.contains("warning"), "{length}, {stress}: {err}");
        let read = |name: &str| std::fs::read(dir.join("out").join(name)).unwrap();
        let summary: serde_json::Value = serde_json::from_slice(&read("summary.json")).unwrap();
        assert_eq!(summary["units"]["length"], length);
        assert_eq!(summary["units"]["stress"], stress);
        assert_eq!(summary["warnings"].as_array().map(Vec::len), Some(0));
        let (material, vti) = (read("material.yaml"), read("rve.vti"));
        outputs.push((dir, um_per_unit, stress, material, vti));
    }
    let (first, rest) = outputs.split_first().unwrap();
    for other in rest {
        assert!(first.3 == other.3, "material.yaml differs in {:?}", other.0);
        assert!(first.4 == other.4, "rve.vti differs in {:?}", other.0);
    }

    // DAMASK's files in SI: C_11 = E(1 − ν)/((1 + ν)(1 − 2ν)) of 400 GPa in Pa, and
    // the grid's spacing in metres (20 µm over 10 cells).
    let material = String::from_utf8(first.3.clone()).unwrap();
    let c11 = 400e9 * 0.8 / (1.2 * 0.6);
    let written: f64 = material
        .split("C_11: ")
        .nth(1)
        .unwrap()
        .split(',')
        .next()
        .unwrap()
        .parse()
        .unwrap();
    // E(1 − ν)/((1 + ν)(1 − 2ν)) against K + 4μ/3: a few roundings apart.
    assert!(
        (written / c11 - 1.0).abs() < 8.0 * f64::EPSILON,
        "{written}"
    );
    let vti = String::from_utf8(first.4.clone()).unwrap();
    let spacing: f64 = vti
        .split("Spacing=\"")
        .nth(1)
        .unwrap()
        .split(' ')
        .next()
        .unwrap()
        .parse()
        .unwrap();
    assert_eq!(spacing, 2e-5 / 10.0); // 20 µm in metres over 10 cells

    // The decks in each scene's own units: coordinates scaled by the length unit, the
    // moduli by the stress unit, and the header says which.
    let deck = |dir: &Path| std::fs::read_to_string(dir.join("out/rve.inp")).unwrap();
    let reference = deck(&first.0);
    assert!(
        reference.contains("** units (the scene's [units]): lengths in um, stresses and E in MPa")
    );
    let (nodes, elastic) = deck_numbers(&reference);
    assert_eq!(elastic, [400000.0, 0.2, 70000.0, 0.33]);
    for (dir, um_per_unit, stress, _, _) in rest {
        let text = deck(dir);
        let (their_nodes, their_elastic) = deck_numbers(&text);
        assert_eq!(their_nodes.len(), nodes.len());
        for (a, b) in nodes.iter().zip(&their_nodes) {
            let want = a / um_per_unit;
            // The largest coordinate is the box's 20 µm.
            assert!(
                (b - want).abs() <= COORDINATE_ULPS * 20.0 / um_per_unit,
                "{dir:?}: node coordinate {b}, want {want}"
            );
        }
        let (particles, matrix) = moduli(stress);
        assert_eq!(their_elastic, [particles, 0.2, matrix, 0.33], "{dir:?}");
        let header = format!("lengths in {}, stresses and E in {stress}", text_unit(dir));
        assert!(text.contains(&header), "{dir:?}: no {header:?}");
    }
}

/// The length unit of the scene in `dir` (its `[units]`).
fn text_unit(dir: &Path) -> String {
    let scene = std::fs::read_to_string(dir.join("scene.toml")).unwrap();
    let line = scene.lines().find(|l| l.starts_with("length = ")).unwrap();
    line.trim_start_matches("length = ")
        .trim_matches('"')
        .to_owned()
}

/// A scene of two small grains with `extra` appended and only the summary written.
fn small(extra: &str) -> String {
    format!(
        r#"
grains = 2
[box]
size = [40.0, 40.0, 40.0]
[[phase]]
size = {{ distribution = "constant", value = 5.0 }}
{extra}
[output]
dir = "out"
grains_csv = false
vtk = false
centers = false
statistics_png = false
"#
    )
}

#[test]
fn implausible_values_are_warned_about_by_key_and_the_run_goes_on() {
    let cases = [
        (
            "modulus_in_pa",
            small("elastic = { E = 200.0, nu = 0.3 }\n[units]\nstress = \"Pa\""),
            vec!["phase[0].elastic.E = 200.0", "200 Pa, outside", "units.stress (\"Pa\")"],
        ),
        (
            "modulus_in_pa_under_the_default_mpa",
            small("elastic = { E = 210e9, nu = 0.3 }"),
            vec!["phase[0].elastic.E = 210e9", "2.1e17 Pa"],
        ),
        (
            "box_of_40_km",
            small("[units]\nlength = \"m\"").replace("[40.0, 40.0, 40.0]", "[40e3, 40e3, 40e3]"),
            vec!["box.size = [40e3, 40e3, 40e3]", "[40000.0, 40000.0, 40000.0] m, outside", "units.length (\"m\")"],
        ),
        (
            "damask_stiffness_in_mpa",
            small("damask = { lattice = \"cF\", mechanical = { elastic = { type = \"Hooke\", C_11 = 250000.0, C_12 = 150000.0, C_44 = 1e11 } } }"),
            vec![
                "phase[0].damask.mechanical.elastic.C_11",
                "2.5e5 Pa",
                "DAMASK reads it in pascals",
            ],
        ),
    ];
    for (name, text, wanted) in cases {
        let dir = scratch("units", name);
        std::fs::write(dir.join("scene.toml"), &text).unwrap();
        let run = pack_in(&dir, &["scene.toml", "--quiet"]);
        let err = String::from_utf8_lossy(&run.stderr);
        assert_eq!(run.status.code(), Some(0), "{name}: {err}");
        let summary: serde_json::Value =
            serde_json::from_slice(&std::fs::read(dir.join("out/summary.json")).unwrap()).unwrap();
        let listed: Vec<&str> = summary["warnings"]
            .as_array()
            .unwrap()
            .iter()
            .map(|w| w.as_str().unwrap())
            .collect();
        for w in &wanted {
            assert!(err.contains(w), "{name}: {w:?} not in\n{err}");
            assert!(
                listed.iter().any(|l| l.contains(w)),
                "{name}: {w:?} not in summary.json's {listed:?}"
            );
        }
        // Each warning on stderr as "pack: warning: scene.toml:line:column: ...".
        for l in &listed {
            assert!(
                err.contains(&format!("pack: warning: {l}")),
                "{name}: {err}"
            );
            assert!(l.starts_with("scene.toml:"), "{l}");
        }
        // C_44 = 1e11 Pa is plausible, C_12 (off-diagonal) never checked.
        assert!(
            !err.contains("C_44") && !err.contains("C_12"),
            "{name}: {err}"
        );
    }
    // Plausible values in the default units: no warning at all.
    let dir = scratch("units", "plausible");
    std::fs::write(
        dir.join("scene.toml"),
        small("elastic = { E = 210000.0, nu = 0.3 }"),
    )
    .unwrap();
    let run = pack_in(&dir, &["scene.toml"]);
    let err = String::from_utf8_lossy(&run.stderr);
    assert_eq!(run.status.code(), Some(0), "{err}");
    assert!(!err.contains("warning"), "{err}");
}

#[test]
fn a_unit_that_is_not_one_is_an_error_naming_its_key_and_value() {
    for (name, units, wanted) in [
        (
            "length",
            "length = \"microns\"",
            [
                "units.length = \"microns\"",
                "must be one of \"m\", \"mm\", \"um\"",
            ],
        ),
        (
            "stress",
            "stress = \"mpa\"",
            ["units.stress = \"mpa\"", "(case matters)"],
        ),
        (
            "unknown_key",
            "time = \"s\"",
            ["units.time", "unknown field"],
        ),
    ] {
        let dir = scratch("units", &format!("bad_{name}"));
        std::fs::write(dir.join("scene.toml"), small(&format!("[units]\n{units}"))).unwrap();
        let run = pack_in(&dir, &["scene.toml", "--quiet"]);
        let err = String::from_utf8_lossy(&run.stderr);
        assert_eq!(run.status.code(), Some(2), "{name}: {err}");
        assert!(!err.contains("panicked"), "{name}: {err}");
        for w in wanted {
            assert!(err.contains(w), "{name}: {w:?} not in\n{err}");
        }
        assert!(err.contains("scene.toml:"), "{name}: {err}");
        assert!(files_in(&dir.join("out")).is_empty(), "{name}: written");
    }
    // Every spelling of a unit packs.
    let dir = scratch("units", "good");
    std::fs::write(
        dir.join("scene.toml"),
        small("[units]\nlength = \"µm\"\nstress = \"GPa\""),
    )
    .unwrap();
    pack_ok(&dir, &["scene.toml", "--quiet"]);
}

#[test]
fn the_placeholder_phase_is_in_pascals_whatever_the_units() {
    // A phase without [phase.elastic] or [phase.damask]: DAMASK's placeholder, E = 200
    // GPa and ν = 0.3, so C_11 = E(1 − ν)/((1 + ν)(1 − 2ν)) = 2.69e11 Pa in every case.
    let mut files = Vec::new();
    for (length, stress) in [("um", "MPa"), ("mm", "GPa"), ("m", "Pa")] {
        let dir = scratch("units", &format!("placeholder_{length}_{stress}"));
        let text = small(&format!(
            "[units]\nlength = \"{length}\"\nstress = \"{stress}\""
        ))
        .replace("[output]", "[output]\nrve_resolution = 4\ndamask = true")
        .replace("[40.0, 40.0, 40.0]", "[40e-6, 40e-6, 40e-6]")
        .replace("value = 5.0", "value = 5e-6");
        // The same box and grains in every unit: scaled from metres.
        let per_metre = match length {
            "um" => 1e6,
            "mm" => 1e3,
            _ => 1.0,
        };
        let text = text
            .replace("40e-6", &format!("{:e}", 40e-6 * per_metre))
            .replace("5e-6", &format!("{:e}", 5e-6 * per_metre));
        std::fs::write(dir.join("scene.toml"), text).unwrap();
        pack_ok(&dir, &["scene.toml", "--quiet"]);
        files.push(std::fs::read_to_string(dir.join("out/material.yaml")).unwrap());
    }
    let c11: f64 = files[0]
        .split("C_11: ")
        .nth(1)
        .unwrap()
        .split(',')
        .next()
        .unwrap()
        .parse()
        .unwrap();
    let want = 200e9 * 0.7 / (1.3 * 0.4);
    // E(1 − ν)/((1 + ν)(1 − 2ν)) against K + 4μ/3: a few roundings apart.
    assert!((c11 / want - 1.0).abs() < 8.0 * f64::EPSILON, "{c11}");
    assert!(files[0].contains("PLACEHOLDER"));
    assert!(
        files
            .iter()
            .all(|f| f.split("C_11: ").nth(1) == files[0].split("C_11: ").nth(1)),
        "the placeholder differs between unit systems"
    );
}
