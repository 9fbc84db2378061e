//! The `[output]` table of a scene: defaults, typed values, the RVE's cells resolved
//! against the box, and every bad value reported with its file, line, column and key.

mod support;

use grainpack::scene::{
    OutputSpec, RveFill, RveSpec, Scene, VtkSpec, DEFAULT_RVE_CELLS, DEFAULT_VTK_RESOLUTION,
    MAX_RVE_CELLS, MAX_RVE_CELLS_PER_EDGE, MAX_VTK_RESOLUTION,
};
use support::scene::{assert_starts, scene_error};

/// A valid scene in a 50 × 40 × 25 periodic box, 8 lines; `[output]` goes on line 9
/// and its keys from line 10 on.
const BASE: &str = r#"seed = 3
target_fraction = 0.3
[box]
size = [50.0, 40.0, 25.0]
boundary = "periodic"
[[phase]]
size = { distribution = "constant", value = 6.0 }
aspect_ratio = { distribution = "constant", value = 1.5 }
"#;

/// The box of `BASE`.
const SIZE: [f64; 3] = [50.0, 40.0, 25.0];

/// `BASE` with `[output]` and `keys` (one per line, from line 10).
fn with_output(keys: &str) -> String {
    format!("{BASE}[output]\n{keys}\n")
}

fn output(keys: &str) -> OutputSpec {
    match Scene::from_str(&with_output(keys), "scene.toml") {
        Ok(scene) => scene.output,
        Err(e) => panic!("rejected:\n{keys}\n{e}"),
    }
}

fn rve(keys: &str) -> RveSpec {
    output(&format!("rve = true\n{keys}"))
        .rve
        .expect("rve = true gives an RveSpec")
}

/// The message of the error `[output]` with `keys` must give.
fn error(keys: &str) -> String {
    scene_error(&with_output(keys))
}

#[test]
fn by_default_the_vtk_files_and_statistics_are_written_and_no_rve() {
    let spec = Scene::from_str(BASE, "scene.toml").unwrap().output;
    assert_eq!(spec, OutputSpec::default());
    assert_eq!(
        spec.vtk,
        Some(VtkSpec {
            resolution: DEFAULT_VTK_RESOLUTION,
            periodic_images: false
        })
    );
    assert!(spec.centers && spec.statistics_png && spec.rve.is_none());
    // An empty [output] is the same.
    assert_eq!(output(""), spec);
}

#[test]
fn output_keys_become_typed_values() {
    let spec = output(
        "vtk_resolution = 4\nperiodic_images = true\ncenters = false\nstatistics_png = false\n\
         rve = true\nrve_resolution = [10, 20, 30]\nrve_fill = \"matrix\"\nsections_png = false",
    );
    assert_eq!(
        spec.vtk,
        Some(VtkSpec {
            resolution: 4,
            periodic_images: true
        })
    );
    assert!(!spec.centers && !spec.statistics_png);
    assert_eq!(
        spec.rve,
        Some(RveSpec {
            cells: [10, 20, 30],
            fill: RveFill::Matrix,
            sections_png: false
        })
    );
    assert_eq!(output("vtk = false").vtk, None);
    assert_eq!(
        output(&format!("vtk_resolution = {MAX_VTK_RESOLUTION}"))
            .vtk
            .unwrap()
            .resolution,
        MAX_VTK_RESOLUTION
    );
}

#[test]
fn an_rve_defaults_to_grains_fill_with_sections() {
    let spec = rve("");
    assert_eq!(spec.fill, RveFill::Grains);
    assert!(spec.sections_png);
    assert_eq!(rve("rve_fill = \"grains\"").fill, RveFill::Grains);
}

#[test]
fn rve_cells_follow_the_longest_edge_the_array_or_the_voxel_size() {
    let proportional = |n: usize| SIZE.map(|l| (n as f64 * l / SIZE[0]).round() as usize);
    // The box's longest edge is x: it gets the count, the others proportionally.
    assert_eq!(rve("").cells, proportional(DEFAULT_RVE_CELLS));
    assert_eq!(rve("rve_resolution = 100").cells, [100, 80, 50]);
    assert_eq!(rve("rve_resolution = [7, 8, 9]").cells, [7, 8, 9]);
    for h in [3.0, 0.7, 12.5] {
        let want = SIZE.map(|l| (l / h).round() as usize);
        assert_eq!(
            rve(&format!("rve_voxel_size = {h:?}")).cells,
            want,
            "h = {h}"
        );
    }
    // A voxel larger than the box still leaves one cell along every edge.
    assert_eq!(rve("rve_voxel_size = 60").cells, [1, 1, 1]);
    // An integer voxel size is a number like any other.
    assert_eq!(rve("rve_voxel_size = 5").cells, [10, 8, 5]);
    let spec = rve("rve_resolution = [7, 8, 9]");
    let h = spec.spacing(SIZE);
    for i in 0..3 {
        // One division and one product: 2 ulp.
        let back = h[i] * spec.cells[i] as f64;
        assert!((back - SIZE[i]).abs() <= 2.0 * f64::EPSILON * SIZE[i]);
    }
}

#[test]
fn bad_vtk_values_name_key_line_and_column() {
    for bad in ["0", "7", "-1"] {
        assert_starts(
            &error(&format!("vtk_resolution = {bad}")),
            &format!("scene.toml:10:18: output.vtk_resolution = {bad}: must lie in [1, 6]"),
        );
    }
    assert_starts(
        &error("vtk_resolution = 2.5"),
        "scene.toml:10:18: output.vtk_resolution: invalid type",
    );
    assert_starts(
        &error("vtk = false\nvtk_resolution = 3"),
        "scene.toml:11:18: output.vtk_resolution = 3: applies only with vtk = true",
    );
    assert_starts(
        &error("vtk = false\nperiodic_images = false"),
        "scene.toml:11:19: output.periodic_images = false: applies only with vtk = true",
    );
    assert_starts(
        &error("vtk = \"yes\""),
        "scene.toml:10:7: output.vtk: invalid type",
    );
}

#[test]
fn periodic_images_need_a_periodic_box() {
    let walled = BASE.replace("\"periodic\"", "\"reflecting\"");
    let text = format!("{walled}[output]\nperiodic_images = true\n");
    let e = Scene::from_str(&text, "scene.toml")
        .unwrap_err()
        .to_string();
    assert_starts(
        &e,
        "scene.toml:10:19: output.periodic_images = true: applies only to a periodic box",
    );
    // false is what a walled box does anyway.
    let text = format!("{walled}[output]\nperiodic_images = false\n");
    assert!(Scene::from_str(&text, "scene.toml").is_ok());
}

#[test]
fn bad_rve_resolutions_name_key_line_and_column() {
    let shape = format!(
        "must be an integer or an array of three integers, each in [1, {MAX_RVE_CELLS_PER_EDGE}]"
    );
    for bad in [
        "0",
        "-3",
        "5000",
        "[10, 20]",
        "[10, 20, 0]",
        "[10, 20, 5000]",
        "\"fine\"",
        "64.0",
        "[1.0, 2.0, 3.0]",
    ] {
        assert_starts(
            &error(&format!("rve = true\nrve_resolution = {bad}")),
            &format!("scene.toml:11:18: output.rve_resolution = {bad}: {shape}"),
        );
    }
    // Each edge within its limit, too many cells in all.
    let n = MAX_RVE_CELLS_PER_EDGE;
    assert_starts(
        &error(&format!("rve = true\nrve_resolution = [{n}, {n}, {n}]")),
        &format!(
            "scene.toml:11:18: output.rve_resolution = [{n}, {n}, {n}]: gives {n} × {n} × {n} = {} \
             cells, more than the limit {MAX_RVE_CELLS}",
            n * n * n
        ),
    );
}

#[test]
fn bad_voxel_sizes_name_key_line_and_column() {
    for bad in ["0", "-1.5", "nan", "inf"] {
        assert_starts(
            &error(&format!("rve = true\nrve_voxel_size = {bad}")),
            &format!(
                "scene.toml:11:18: output.rve_voxel_size = {bad}: must be positive and finite"
            ),
        );
    }
    assert_starts(
        &error("rve = true\nrve_voxel_size = 0.01"),
        "scene.toml:11:18: output.rve_voxel_size = 0.01: gives 5000 cells along x (box side 50), \
         more than the limit 4096",
    );
    // round(50/0.03) × round(40/0.03) × round(25/0.03): each edge fits, the total
    // (1.85e9) does not.
    assert_starts(
        &error("rve = true\nrve_voxel_size = 0.03"),
        "scene.toml:11:18: output.rve_voxel_size = 0.03: gives 1667 × 1333 × 833 = 1851018463 \
         cells, more than the limit",
    );
    assert_starts(
        &error("rve = true\nrve_resolution = 10\nrve_voxel_size = 2"),
        "scene.toml:12:18: output.rve_voxel_size = 2: give either rve_resolution or \
         rve_voxel_size, not both",
    );
}

#[test]
fn rve_keys_without_an_rve_are_errors() {
    for (keys, line, column, key) in [
        ("sections_png = true", 10, 16, "sections_png = true"),
        ("rve_fill = \"matrix\"", 10, 12, "rve_fill = \"matrix\""),
        ("rve_resolution = 32", 10, 18, "rve_resolution = 32"),
        (
            "rve = false\nrve_voxel_size = 1.5",
            11,
            18,
            "rve_voxel_size = 1.5",
        ),
    ] {
        assert_starts(
            &error(keys),
            &format!("scene.toml:{line}:{column}: output.{key}: applies only with rve = true"),
        );
    }
    // Turning off what is off is no error.
    assert_eq!(output("sections_png = false").rve, None);
}

#[test]
fn an_unknown_fill_names_the_choices() {
    assert_starts(
        &error("rve = true\nrve_fill = \"void\""),
        "scene.toml:11:12: output.rve_fill: unknown variant `void`, expected `grains` or `matrix`",
    );
}

#[test]
fn packing_png_applies_only_to_a_2d_scene() {
    assert!(!output("").packing_png);
    assert_starts(
        &error("packing_png = true"),
        "scene.toml:10:15: output.packing_png = true: applies only to a 2D scene (a box with \
         two lengths)",
    );
    // Turning off what is off is no error.
    assert!(!output("packing_png = false").packing_png);
}
