//! The conforming mesh's keys (`output.mesh`, `mesh_size`, `mesh_order`, `mesh_fill`, and the
//! `packing.gap` the mesh needs): edits that make a meshable scene and then set one of
//! them at or past its limits, and the property the scene checks hold them to. The
//! mesh itself needs gmsh, which the fuzz targets never run: `run::run` packs, only
//! the CLI meshes.

use grainpack::io::scene::SceneError;
use grainpack::scene::{RveFill, Scene, MESH_SIZE_RANGE, MIN_MESH_GAP};

/// What a mesh edit sets first (table, key, value; `phase.elastic` on every phase): a
/// scene that validates with a mesh of the default size and order.
pub const MESHABLE: [(&str, &str, &str); 6] = [
    ("output", "mesh", "true"),
    ("packing", "gap", "0.05"),
    ("phase.elastic", "E", "200.0"),
    ("phase.elastic", "nu", "0.3"),
    ("matrix.elastic", "E", "3.0"),
    ("matrix.elastic", "nu", "0.35"),
];

/// The keys a mesh edit then sets (or removes, with an empty value), with values at
/// and past their documented limits (`docs/config.md`, "Conforming mesh"):
/// `mesh_size` in [0.05, 1], `mesh_order` 1 or 2, `mesh_fill` "matrix" or "grains"
/// (which refuses the `[matrix]` the first edits set), `gap` at least 0.02, wrong
/// types, and the materials the mesh needs.
pub const MESH_EDITS: [(&str, &str, &[&str]); 7] = [
    (
        "output",
        "mesh_size",
        &[
            "0.05", "0.0499", "1.0", "1.0001", "1", "0.3", "0", "-0.3", "nan", "inf", "1e308",
            "5e-324", "\"0.3\"", "[0.3]", "",
        ],
    ),
    (
        "output",
        "mesh_order",
        &[
            "1",
            "2",
            "0",
            "3",
            "-1",
            "1.0",
            "2.5",
            "\"2\"",
            "true",
            "9223372036854775807",
            "-9223372036854775808",
            "",
        ],
    ),
    (
        "packing",
        "gap",
        &[
            "0.02",
            "0.0199",
            "0.019999999999999997",
            "0",
            "-0.0",
            "-0.05",
            "nan",
            "inf",
            "0.5",
            "10",
            "1e308",
            "\"0.05\"",
            "",
        ],
    ),
    (
        "output",
        "mesh",
        &["true", "false", "1", "\"true\"", "[]", ""],
    ),
    (
        "output",
        "mesh_fill",
        &[
            "\"matrix\"",
            "\"grains\"",
            "\"voids\"",
            "\"Grains\"",
            "\"\"",
            "1",
            "[]",
            "",
        ],
    ),
    ("matrix.elastic", "E", &["3.0", "0", "-1", "nan", ""]),
    ("phase.elastic", "nu", &["0.3", "0.5", "-1", "nan", ""]),
];

/// The mesh keys of `[output]`, as a refusal's key path names them.
const MESH_KEYS: [&str; 4] = ["mesh", "mesh_size", "mesh_order", "mesh_fill"];

/// The mesh's part of the scene checks. A valid scene with a mesh has a `packing.gap`
/// of at least [`MIN_MESH_GAP`], a `mesh_size` in [`MESH_SIZE_RANGE`], an order of 1 or
/// 2, and elastic constants on every phase and, with the matrix fill, on the matrix
/// (the grains fill has no matrix) (3D and 2D alike: 2D
/// scenes are meshed as triangles since issue 29's second round); a refusal whose
/// line is a mesh key's (`mesh_size = …` under `[output]`) names that key
/// (`output.mesh_size`), and a refusal naming a mesh key or `packing.gap` because of
/// the mesh points at a line that holds it (what the mesh needs and is missing, such
/// as the gap or a phase's material, is refused at `mesh`'s line).
pub fn check_mesh(result: &Result<Scene, SceneError>, text: &str) {
    match result {
        Ok(scene) => {
            let Some(mesh) = scene.output.mesh else {
                return;
            };
            let (lo, hi) = MESH_SIZE_RANGE;
            assert!(
                scene.packing.gap >= MIN_MESH_GAP
                    && (lo..=hi).contains(&mesh.size)
                    && matches!(mesh.order, 1 | 2)
                    && scene.phases.iter().all(|p| p.elastic.is_some())
                    && (mesh.fill == RveFill::Grains) != scene.matrix.elastic.is_some(),
                "a mesh accepted outside its limits: {mesh:?}, gap {}: {text:?}",
                scene.packing.gap
            );
        }
        Err(
            SceneError::Value {
                key, line, value, ..
            }
            | SceneError::Shape {
                key, line, value, ..
            },
        ) => {
            let held = text.lines().nth(line - 1).unwrap_or("");
            let lhs = held.split('=').next().unwrap_or("").trim();
            let table = table_of(text, *line);
            // What the mesh needs and is missing (`packing.gap`, `[phase.elastic]`,
            // `[matrix.elastic]`) is refused at `mesh = true`, naming what is missing.
            let missing = value == "(missing)" && lhs == "mesh";
            if table == "output" && MESH_KEYS.contains(&lhs) && !missing {
                assert_eq!(
                    key,
                    &format!("output.{lhs}"),
                    "a refusal at {held:?} names another key: {result:?}: {text:?}"
                );
            }
            if let Some(k) = key
                .strip_prefix("output.")
                .filter(|k| MESH_KEYS.contains(k))
            {
                assert!(
                    lhs == k && table == "output",
                    "{key} refused at line {line} ({held:?}): {text:?}"
                );
            }
        }
        Err(_) => {}
    }
}

/// The table whose header last precedes line `line` (1-based) of `text`: `""` for the
/// top level, `output` under `[output]`.
fn table_of(text: &str, line: usize) -> String {
    (text.lines().take(line).filter_map(|l| {
        let l = l.trim();
        (l.starts_with('[') && l.ends_with(']'))
            .then(|| l.trim_matches(['[', ']']).trim().to_owned())
    }))
    .last()
    .unwrap_or_default()
}
