//! Scene files end to end: the shipped configs load, every kind of bad input is
//! reported with its file, key, line, column and value, and the grains drawn follow the
//! requested statistics, deterministically for a seed.

mod bad_input;
mod sampling;
#[path = "../support/mod.rs"]
mod support;

use grainpack::contact::rotation_column;
use grainpack::io::scene::SceneError;
use grainpack::laws::{Distribution, VonMises, VonMisesCdf};
use grainpack::scene::{
    Axis, Boundary, GrainCount, GrainSpec, Orientation, OutputSpec, PackingParams, Rotation, Scene,
};
use std::f64::consts::PI;
use std::path::Path;
use support::scene::{assert_starts, scene_error as error};

/// A valid scene; the tests below change one line of it at a time, so that the
/// expected line numbers can be read off here.
const BASE: &str = r#"seed = 3
target_fraction = 0.5
[box]
size = [50.0, 50.0, 50.0]
boundary = "periodic"
[[phase]]
name = "a"
[phase.size]
distribution = "lognormal"
sigma = 0.5
scale = 8.0
min = 4.0
max = 16.0
[phase.aspect_ratio]
distribution = "constant"
value = 1.5
[phase.orientation]
kind = "random"
"#;

/// `BASE` with line `line` (1-based) replaced by `text` (which may span lines).
fn with_line(line: usize, text: &str) -> String {
    let mut lines: Vec<&str> = BASE.lines().collect();
    lines[line - 1] = text;
    lines.join("\n") + "\n"
}

/// `BASE` with `text` appended.
fn with_extra(text: &str) -> String {
    format!("{BASE}{text}\n")
}

fn load(path: &str) -> Scene {
    let path = Path::new(env!("CARGO_MANIFEST_DIR")).join(path);
    Scene::from_path(&path).unwrap_or_else(|e| panic!("{e}"))
}

#[test]
fn base_scene_is_valid() {
    let scene = Scene::from_str(BASE, "scene.toml").unwrap();
    assert_eq!(scene.seed, 3);
    assert_eq!(scene.count, GrainCount::Fraction(0.5));
}

#[test]
fn kanapy_config_expresses_kanapys_packed_grains() {
    let scene = load("configs/kanapy_elongated.toml");
    assert_eq!(scene.domain.size, [92.0; 3]);
    assert_eq!(scene.domain.boundary, Boundary::Periodic);
    assert_eq!(scene.count, GrainCount::Fraction(0.65));
    assert_eq!(scene.phases.len(), 1);
    let p = &scene.phases[0];
    // kanapy's diameters times 0.65^(1/3), to 5 significant digits (see the file).
    let f = 0.65f64.cbrt();
    let Distribution::LogNormal {
        sigma,
        scale,
        loc,
        min,
        max,
    } = p.size
    else {
        panic!("{:?}", p.size)
    };
    assert_eq!((sigma, loc), (0.8, 0.0));
    for (got, kanapy) in [(scale, 14.0), (min, 6.0), (max, 16.0)] {
        assert!(
            (got / (kanapy * f) - 1.0).abs() < 5e-5,
            "{got} vs {kanapy} × {f}"
        );
    }
    assert_eq!(
        p.aspect_ratio,
        Distribution::LogNormal {
            sigma: 0.8,
            scale: 2.5,
            loc: 0.0,
            min: 0.85,
            max: 3.2
        }
    );
    let Orientation::Tilt { axis, angle } = p.orientation else {
        panic!()
    };
    assert_eq!(axis, Axis::Z);
    assert_eq!((angle.kappa, angle.min), (1.0, 0.0));
    assert!((angle.mean - 0.5 * PI).abs() < 1e-15 && (angle.max - PI).abs() < 1e-15);
    // Its grains turn in their tilt plane, and back as far as they can.
    assert_eq!(scene.packing.rotation, Rotation::Axis);
    assert!(scene.packing.restore);
    // kanapy packs about 1050 grains of this scene.
    let n = scene.expected_count();
    assert!((950.0..1100.0).contains(&n), "{n}");
}

#[test]
fn grains_config_is_small_and_two_phase() {
    let scene = load("configs/grains.toml");
    let n = scene.expected_count();
    assert!((300.0..1000.0).contains(&n), "{n}");
    assert_eq!(scene.phases.len(), 2);
    let grains = scene.sample_grains(&mut scene.rng()).unwrap();
    let fraction: f64 = grains.iter().map(GrainSpec::volume).sum::<f64>() / scene.domain.volume();
    assert!(fraction >= 0.6);
}

#[test]
fn defaults_fill_in_everything_but_box_count_and_size() {
    let text = r#"
grains = 10
[box]
size = [30, 30, 30]
[[phase]]
size = { distribution = "constant", value = 5 }
"#;
    let scene = Scene::from_str(text, "minimal.toml").unwrap();
    assert_eq!(scene.seed, 0);
    assert_eq!(scene.domain.boundary, Boundary::Periodic);
    let p = &scene.phases[0];
    assert_eq!((p.name.as_str(), p.share), ("phase0", 1.0));
    assert_eq!(p.aspect_ratio, Distribution::Constant { value: 1.0 });
    assert_eq!(p.orientation, Orientation::Random);
    assert_eq!(scene.packing, PackingParams::default());
    assert_eq!(scene.output, OutputSpec::default());
}

#[test]
fn rotation_takes_false_true_or_axis_and_max_turn_is_in_degrees() {
    for (value, mode) in [
        ("false", Rotation::None),
        ("true", Rotation::Free),
        ("\"axis\"", Rotation::Axis),
    ] {
        let text = with_extra(&format!("[packing]\nrotation = {value}\nmax_turn = 30"));
        let scene = Scene::from_str(&text, "scene.toml").unwrap();
        assert_eq!(scene.packing.rotation, mode, "{value}");
        assert!((scene.packing.max_turn - 30f64.to_radians()).abs() < 1e-15);
    }
    // Grains of a tilt phase turn about its tilt axis; others have none.
    let kanapy = load("configs/kanapy_elongated.toml");
    let grains = kanapy.sample_grains(&mut kanapy.rng()).unwrap();
    assert!(grains.iter().all(|g| g.turn_axis == Some([0.0, 0.0, 1.0])));
    let base = Scene::from_str(BASE, "scene.toml").unwrap();
    let grains = base.sample_grains(&mut base.rng()).unwrap();
    for g in &grains {
        let tilted = matches!(base.phases[g.phase].orientation, Orientation::Tilt { .. });
        assert_eq!(g.turn_axis.is_some(), tilted);
    }
}

#[test]
fn shares_are_normalised_by_their_sum() {
    let scene = Scene::from_str(
        &with_extra(
            "[[phase]]\nname = \"b\"\nshare = 3\nsize = { distribution = \"constant\", value = 6 }",
        ),
        "scene.toml",
    )
    .unwrap();
    assert_eq!(scene.phases[0].share, 0.25);
    assert_eq!(scene.phases[1].share, 0.75);
}

// ---- bad input: every message names file:line:column, the key path and the value ----
