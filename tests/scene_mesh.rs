//! `[output] mesh = true`: its keys, the gap and materials it needs, and `pack`'s refusal
//! before packing when gmsh is missing. The mesh itself is checked by
//! `tools/check_mesh.py` (meshio, CalculiX), which `.ci/run` runs with gmsh installed.

mod support;

use grainpack::scene::{MeshSpec, RveFill, Scene, DEFAULT_MESH_SIZE, MIN_MESH_GAP};
use support::files::{files_in, scratch};
use support::scene::{assert_starts, scene_error};

/// A meshable scene without `[packing]` and `[output]` (lines 1 to 10).
const BASE: &str = r#"seed = 3
target_fraction = 0.3
[box]
size = [20.0, 20.0, 20.0]
[[phase]]
size = { distribution = "constant", value = 4.0 }
aspect_ratio = { distribution = "constant", value = 1.5 }
elastic = { E = 100.0, nu = 0.3 }
[matrix]
elastic = { E = 10.0, nu = 0.35 }
"#;

/// `BASE` with `packing.gap = gap` (line 12) and `[output]` with `keys` (from line 14).
fn scene(gap: f64, keys: &str) -> String {
    format!("{BASE}[packing]\ngap = {gap}\n[output]\n{keys}\n")
}

fn mesh(keys: &str) -> Option<MeshSpec> {
    match Scene::from_str(&scene(0.05, keys), "scene.toml") {
        Ok(scene) => scene.output.mesh,
        Err(e) => panic!("rejected:\n{keys}\n{e}"),
    }
}

#[test]
fn mesh_keys_become_typed_values() {
    assert_eq!(
        mesh("mesh = true"),
        Some(MeshSpec {
            size: DEFAULT_MESH_SIZE,
            order: 1,
            fill: RveFill::Matrix,
        })
    );
    assert_eq!(
        mesh("mesh = true\nmesh_size = 0.15\nmesh_order = 2"),
        Some(MeshSpec {
            size: 0.15,
            order: 2,
            fill: RveFill::Matrix,
        })
    );
}

#[test]
fn a_mesh_without_a_gap_names_packing_gap_and_the_smallest_gap() {
    let message = scene_error(&format!("{BASE}[output]\nmesh = true\n"));
    assert_starts(
        &message,
        "scene.toml:12:8: packing.gap = (missing): output.mesh = true",
    );
    assert!(
        message.contains(&format!("at least {MIN_MESH_GAP}")),
        "{message}"
    );
    let message = scene_error(&scene(0.01, "mesh = true"));
    assert_starts(
        &message,
        "scene.toml:12:7: packing.gap = 0.01: output.mesh = true",
    );
    assert!(
        message.contains(&format!("at least {MIN_MESH_GAP}")),
        "{message}"
    );
    // The smallest gap allowed is allowed.
    assert!(Scene::from_str(&scene(MIN_MESH_GAP, "mesh = true"), "scene.toml").is_ok());
}

#[test]
fn bad_mesh_values_name_key_line_and_column() {
    for (keys, at, message) in [
        (
            "mesh = true\nmesh_size = 0.01",
            "15:13: output.mesh_size = 0.01",
            "must lie in",
        ),
        (
            "mesh = true\nmesh_size = 2.0",
            "15:13: output.mesh_size = 2.0",
            "must lie in",
        ),
        (
            "mesh = true\nmesh_order = 3",
            "15:14: output.mesh_order = 3",
            "must be 1",
        ),
        (
            "mesh_size = 0.2",
            "14:13: output.mesh_size = 0.2",
            "applies only with mesh = true",
        ),
        (
            "mesh_order = 2",
            "14:14: output.mesh_order = 2",
            "applies only with mesh = true",
        ),
        (
            "mesh_fill = \"grains\"",
            "14:13: output.mesh_fill = \"grains\"",
            "applies only with mesh = true",
        ),
    ] {
        assert_starts(
            &scene_error(&scene(0.05, keys)),
            &format!("scene.toml:{at}: {message}"),
        );
    }
}

#[test]
fn a_mesh_needs_the_elastic_constants_of_every_phase_and_the_matrix() {
    let no_matrix =
        scene(0.05, "mesh = true").replace("[matrix]\nelastic = { E = 10.0, nu = 0.35 }\n", "");
    assert_starts(
        &scene_error(&no_matrix),
        "scene.toml:12:8: matrix.elastic = (missing): output.mesh = true",
    );
    let no_phase = scene(0.05, "mesh = true").replace("elastic = { E = 100.0, nu = 0.3 }\n", "");
    assert_starts(
        &scene_error(&no_phase),
        "scene.toml:13:8: phase[0].elastic = (missing): output.mesh = true writes a *Material",
    );
}

#[test]
fn without_gmsh_pack_says_how_to_install_it_before_packing() {
    let dir = scratch("mesh", "no-gmsh");
    std::fs::write(
        dir.join("scene.toml"),
        scene(0.05, "dir = \"out\"\nmesh = true"),
    )
    .unwrap();
    let run = std::process::Command::new(env!("CARGO_BIN_EXE_pack"))
        .arg("scene.toml")
        .env("GRAINPACK_PYTHON", dir.join("no-such-python"))
        .current_dir(&dir)
        .output()
        .unwrap();
    let stderr = String::from_utf8_lossy(&run.stderr);
    assert_eq!(run.status.code(), Some(2), "{stderr}");
    assert!(stderr.contains("pip install gmsh==4.15.2"), "{stderr}");
    // Refused before packing: nothing was written, not even the output directory.
    assert_eq!(files_in(&dir), ["scene.toml"]);
}

#[test]
fn a_2d_scene_takes_the_mesh_keys_and_names_its_elements() {
    let plane =
        |keys: &str| scene(0.05, keys).replace("size = [20.0, 20.0, 20.0]", "size = [20.0, 20.0]");
    let spec = Scene::from_str(&plane("mesh = true\nmesh_order = 2"), "scene.toml")
        .unwrap_or_else(|e| panic!("a 2D mesh rejected: {e}"))
        .output
        .mesh;
    assert_eq!(
        spec,
        Some(MeshSpec {
            size: DEFAULT_MESH_SIZE,
            order: 2,
            fill: RveFill::Matrix,
        })
    );
    assert_starts(
        &scene_error(&plane("mesh = true\nmesh_order = 3")),
        "scene.toml:15:14: output.mesh_order = 3: must be 1 (linear triangles, CPE3) or 2",
    );
    // The gap is needed in 2D as in 3D.
    assert_starts(
        &scene_error(&plane("mesh = true").replace("gap = 0.05", "gap = 0.01")),
        "scene.toml:12:7: packing.gap = 0.01: output.mesh = true",
    );
}

#[test]
fn a_mesh_with_the_grains_fill_has_no_matrix() {
    let keys = "mesh = true\nmesh_fill = \"grains\"";
    let without_matrix =
        scene(0.05, keys).replace("[matrix]\nelastic = { E = 10.0, nu = 0.35 }\n", "");
    let spec = Scene::from_str(&without_matrix, "scene.toml")
        .unwrap_or_else(|e| panic!("the grains fill rejected: {e}"))
        .output
        .mesh;
    assert_eq!(spec.map(|m| m.fill), Some(RveFill::Grains));
    // Its [matrix] would describe nothing.
    assert_starts(
        &scene_error(&scene(0.05, keys)),
        "scene.toml:9:1: matrix = ",
    );
    assert!(
        scene_error(&scene(0.05, "mesh = true\nmesh_fill = \"voids\""))
            .starts_with("scene.toml:15:13: ")
    );
}
