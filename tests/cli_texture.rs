//! Crystal orientations and the solver input sets, end to end through `pack`: bad
//! textures, orientation files and elastic constants are exit 2 with the file, line,
//! key and value named and nothing written; good ones give the files, with the
//! orientations of the texture asked for.

mod support;

use std::path::PathBuf;
use support::files::{files_in, pack_in};

fn scratch(name: &str) -> PathBuf {
    support::files::scratch("texture", name)
}

/// A small scene of one phase with `texture` (a TOML table body) and `extra` appended.
fn scene(texture: &str, extra: &str) -> String {
    format!(
        r#"
seed = 2
grains = 12
[box]
size = [20.0, 20.0, 20.0]
[[phase]]
name = "ferrite"
size = {{ distribution = "constant", value = 5.0 }}
aspect_ratio = {{ distribution = "constant", value = 1.5 }}
elastic = {{ E = 200.0, nu = 0.3 }}
[phase.texture]
{texture}
{extra}
[output]
dir = "out"
rve_resolution = 8
damask = true
abaqus = true
"#
    )
}

/// Runs `pack` on `text` (and `files`) in a fresh directory; asserts exit 2, nothing
/// written, and a message containing every one of `wanted`.
#[track_caller]
fn rejects(name: &str, text: &str, files: &[(&str, &str)], wanted: &[&str]) {
    let dir = scratch(name);
    std::fs::write(dir.join("scene.toml"), text).unwrap();
    for (file, content) in files {
        std::fs::write(dir.join(file), content).unwrap();
    }
    let run = pack_in(&dir, &["scene.toml", "--quiet"]);
    let err = String::from_utf8_lossy(&run.stderr);
    assert_eq!(run.status.code(), Some(2), "{name}: {err}");
    assert!(!err.contains("panicked"), "{name}: {err}");
    for w in wanted {
        assert!(err.contains(w), "{name}: {w:?} not in\n{err}");
    }
    assert!(
        files_in(&dir.join("out")).is_empty(),
        "{name}: something written"
    );
}

#[test]
fn bad_orientation_files_name_the_file_line_column_and_value() {
    let texture = "kind = \"file\"\nfile = \"o.csv\"";
    let text = scene(texture, "");
    rejects(
        "malformed",
        &text,
        &[("o.csv", "q0,q1,q2,q3\n1,0,0,0\n0.5,0.5,zero,0.5\n")],
        &[
            "o.csv:3",
            "q2 = zero",
            "not a finite number",
            "phase[0].texture.file",
        ],
    );
    rejects(
        "non_unit",
        &text,
        &[("o.csv", "# EBSD\nq0,q1,q2,q3,weight\n0.5,0.5,0.5,0.6,1\n")],
        &[
            "o.csv:3",
            "q0,q1,q2,q3 = [0.5, 0.5, 0.5, 0.6]",
            "unit quaternion",
        ],
    );
    rejects(
        "euler_range",
        &text,
        &[("o.csv", "x,y,phi1,Phi,phi2\n0,0,10,190,30\n")],
        &["o.csv:2", "phi1,Phi,phi2 = [10, 190, 30]", "[0, 180]"],
    );
    rejects(
        "negative_weight",
        &text,
        &[("o.csv", "phi1,Phi,phi2,weight\n10,20,30,-1\n")],
        &["o.csv:2", "weight = -1", "negative"],
    );
    rejects(
        "no_columns",
        &text,
        &[("o.csv", "a,b,c\n1,2,3\n")],
        &["o.csv:1", "q0,q1,q2,q3", "phi1,Phi,phi2"],
    );
    rejects("missing", &text, &[], &["o.csv:0", "cannot read it"]);
}

#[test]
fn bad_texture_and_elastic_keys_are_named_with_their_values() {
    rejects(
        "foreign_key",
        &scene("kind = \"fixed\"\neuler = [10, 20, 30]\nkappa = 3.0", ""),
        &[],
        &[
            "scene.toml:14:9",
            "phase[0].texture.kappa = 3.0",
            "does not apply",
        ],
    );
    rejects(
        "euler_out_of_range",
        &scene("kind = \"fixed\"\neuler = [10, 200, 30]", ""),
        &[],
        &["phase[0].texture.euler = [10, 200, 30]", "[0, 180]"],
    );
    rejects(
        "non_unit_fixed",
        &scene("kind = \"fixed\"\nquaternion = [1, 1, 0, 0]", ""),
        &[],
        &[
            "phase[0].texture.quaternion = [1, 1, 0, 0]",
            "unit quaternion",
        ],
    );
    rejects(
        "random_relative",
        &scene("kind = \"random\"\nrelative_to_shape = true", ""),
        &[],
        &["phase[0].texture.relative_to_shape = true", "random"],
    );
    let not_positive = scene("kind = \"random\"", "").replace("nu = 0.3", "nu = 0.5");
    rejects(
        "nu",
        &not_positive,
        &[],
        &["phase[0].elastic.nu = 0.5", "positive definite"],
    );
    let no_elastic =
        scene("kind = \"random\"", "").replace("elastic = { E = 200.0, nu = 0.3 }", "");
    rejects(
        "abaqus_needs_elastic",
        &no_elastic,
        &[],
        &["phase[0].elastic", "abaqus"],
    );
    rejects(
        "matrix_without_matrix_fill",
        &scene(
            "kind = \"random\"",
            "[matrix]\nelastic = { E = 1.0, nu = 0.2 }",
        ),
        &[],
        &["matrix", "rve_fill"],
    );
}

/// The files of a textured run, and the crystal orientations of a file texture drawn
/// only from its rows (each a row's quaternion, to the last bit).
#[test]
fn a_file_texture_gives_its_rows_and_the_solver_files_are_written() {
    let dir = scratch("good");
    let rows = [[0.5, 0.5, 0.5, 0.5], [1.0, 0.0, 0.0, 0.0]];
    let mut csv = String::from("q0,q1,q2,q3,weight\n");
    for r in rows {
        csv += &format!("{},{},{},{},1\n", r[0], r[1], r[2], r[3]);
    }
    std::fs::write(dir.join("o.csv"), csv).unwrap();
    let text = scene("kind = \"file\"\nfile = \"o.csv\"", "");
    std::fs::write(dir.join("scene.toml"), text).unwrap();
    let run = pack_in(&dir, &["scene.toml", "--quiet"]);
    assert_eq!(
        run.status.code(),
        Some(0),
        "{}",
        String::from_utf8_lossy(&run.stderr)
    );
    let files = files_in(&dir.join("out"));
    for f in [
        "material.yaml",
        "load.yaml",
        "rve.inp",
        "rve_umat.inp",
        "rve.vti",
    ] {
        assert!(files.contains(&f.to_owned()), "{f} not in {files:?}");
    }
    let table = std::fs::read_to_string(dir.join("out/grains.csv")).unwrap();
    let mut lines = table.lines();
    let header: Vec<&str> = lines.next().unwrap().split(',').collect();
    assert_eq!(
        &header[12..],
        ["o0", "o1", "o2", "o3", "phi1", "Phi", "phi2"]
    );
    let mut seen = [0; 2];
    for line in lines {
        let v: Vec<f64> = line.split(',').map(|x| x.parse().unwrap()).collect();
        let o = [v[12], v[13], v[14], v[15]];
        let row = rows
            .iter()
            .position(|r| *r == o)
            .expect("a row of the file");
        seen[row] += 1;
    }
    // 12 grains from two rows of equal weight: both drawn (probability 1 − 2⁻¹¹).
    assert!(seen[0] > 0 && seen[1] > 0, "{seen:?}");
    let material = std::fs::read_to_string(dir.join("out/material.yaml")).unwrap();
    assert_eq!(material.matches("O: [").count(), 12);
    let deck = std::fs::read_to_string(dir.join("out/rve.inp")).unwrap();
    assert_eq!(deck.matches("*Elset, elset=GRAIN_").count(), 12);
    assert!(deck.contains("*Equation") && deck.contains("*Material, name=PHASE0_FERRITE"));
    // The file's law of the rotation angle: atoms at 0 (identity) and 120° (the other
    // row), 1/2 each; the grains' empirical law differs from it by |n₀/12 − 1/2| at
    // both atoms.
    let summary: serde_json::Value =
        serde_json::from_str(&std::fs::read_to_string(dir.join("out/summary.json")).unwrap())
            .unwrap();
    let texture = &summary["textures"][0];
    assert_eq!(texture["measure"], "rotation angle");
    assert_eq!(texture["file_rows"], 2);
    let ks = texture["ks_distance"].as_f64().unwrap();
    // Rotation angles of exact rows: 2·atan2(√3/2, 1/2) = 120° up to rounding.
    assert!(
        (ks - (seen[1] as f64 / 12.0 - 0.5).abs()).abs() < 1e-12,
        "{ks} {seen:?}"
    );
    let mean = texture["target_mean_deg"].as_f64().unwrap();
    assert!((mean - 60.0).abs() < 1e-12, "{mean}");
    // statistics.png has the texture panel on a line below the phase's three: three
    // panels of 600 pixels across, a 60-pixel title and two lines of 470.
    let png = std::fs::read(dir.join("out/statistics.png")).unwrap();
    let width = u32::from_be_bytes(png[16..20].try_into().unwrap());
    let height = u32::from_be_bytes(png[20..24].try_into().unwrap());
    assert_eq!((width, height), (3 * 600, 60 + 2 * 470));
}

#[test]
fn the_scene_homogenization_goes_to_material_yaml_and_bad_ones_are_named() {
    let random = "kind = \"random\"";
    let homogenization = "[homogenization]\nname = \"direct\"\nmechanical = { type = \"pass\" }";
    let dir = scratch("homogenization");
    std::fs::write(dir.join("scene.toml"), scene(random, homogenization)).unwrap();
    let run = pack_in(&dir, &["scene.toml", "--quiet"]);
    let err = String::from_utf8_lossy(&run.stderr);
    assert_eq!(run.status.code(), Some(0), "{err}");
    let material = std::fs::read_to_string(dir.join("out/material.yaml")).unwrap();
    // The entry as given, N_constituents added; every material refers to it. In flow
    // style with a blank after each `:` and `,`, which DAMASK's own YAML parser needs
    // (DAMASK_grid 3.0.2 stops with error 705 on compact JSON).
    assert!(
        material.contains(
            "homogenization:\n  \"direct\": {\"N_constituents\": 1, \"mechanical\": {\"type\": \"pass\"}}"
        ),
        "{material}"
    );
    assert_eq!(material.matches("- homogenization: \"direct\"").count(), 12);

    rejects(
        "homogenization_two_constituents",
        &scene(random, "[homogenization]\nN_constituents = 2"),
        &[],
        &["homogenization.N_constituents", "must be 1"],
    );
    rejects(
        "homogenization_without_damask",
        &scene(random, homogenization).replace("damask = true", "damask = false"),
        &[],
        &["homogenization", "output.damask = true"],
    );
}
