//! 2D scene files (`[box] size = [Lx, Ly]`): what they draw (ellipses turned about z,
//! areas instead of volumes, the angle laws), and every key without a meaning in the
//! plane refused with its file, line, key and value.

mod support;

use grainpack::contact::{ellipse_angle, Dimension, PLANE_NORMAL};
use grainpack::laws::{random_close_packing_discs, VonMises, VonMisesCdf};
use grainpack::run::Drawn;
use grainpack::scene::{GrainCount, GrainSpec, Scene};
use std::f64::consts::PI;
use std::path::Path;
use support::scene::{assert_starts, scene_error as error};

/// A valid 2D scene; the tests change one line at a time (line numbers read off here).
const BASE: &str = r#"seed = 4
target_fraction = 0.6
[box]
size = [120.0, 80.0]
boundary = "periodic"
[[phase]]
name = "a"
[phase.size]
distribution = "normal"
mean = 7.0
std = 0.5
min = 6.0
max = 8.0
[phase.aspect_ratio]
distribution = "constant"
value = 1.4
[phase.orientation]
kind = "random"
"#;

/// `BASE` with line `line` (1-based) replaced by `text` (which may span lines).
fn with_line(line: usize, text: &str) -> String {
    let mut lines: Vec<&str> = BASE.lines().collect();
    lines[line - 1] = text;
    lines.join("\n") + "\n"
}

fn scene(text: &str) -> Scene {
    Scene::from_str(text, "scene.toml").unwrap_or_else(|e| panic!("{e}"))
}

fn grains(text: &str) -> Vec<GrainSpec> {
    let s = scene(text);
    s.sample_grains(&mut s.rng()).unwrap()
}

/// Kolmogorov–Smirnov distance of a sample from a CDF.
fn ks_distance(mut xs: Vec<f64>, cdf: impl Fn(f64) -> f64) -> f64 {
    xs.sort_by(f64::total_cmp);
    let n = xs.len() as f64;
    (xs.iter().enumerate())
        .map(|(i, &x)| {
            let f = cdf(x);
            (f - i as f64 / n).abs().max((f - (i + 1) as f64 / n).abs())
        })
        .fold(0.0, f64::max)
}

#[test]
fn two_lengths_make_a_plane_of_ellipses_filled_by_area() {
    let s = scene(BASE);
    assert_eq!(s.domain.dimension, Dimension::Two);
    assert_eq!(s.domain.size, [120.0, 80.0, 120.0]);
    assert_eq!(s.domain.volume(), 120.0 * 80.0);
    assert!(s.phases.iter().all(|p| p.dimension == Dimension::Two));
    // E[d²] of the truncated normal, exactly the law's second moment.
    let area = PI / 4.0 * s.phases[0].size.moment(2);
    assert_eq!(s.expected_grain_volume(), area);
    let drawn = grains(BASE);
    let total: f64 = drawn.iter().map(GrainSpec::volume).sum();
    // Grains are drawn until the area first reaches 0.6 of the rectangle; the last one is
    // kept only if nearer: within half the largest grain's area (d ≤ 8).
    let target = 0.6 * 120.0 * 80.0;
    assert!(
        (total - target).abs() <= 0.5 * PI / 4.0 * 64.0,
        "{total} vs {target}"
    );
    for g in &drawn {
        assert_eq!(g.dimension, Dimension::Two);
        let [a1, a2, a3] = g.semi_axes;
        // Products and roots of a few roundings: 1e-14 relative.
        assert!(
            (2.0 * (a1 * a2).sqrt() / g.diameter - 1.0).abs() < 1e-14,
            "{g:?}"
        );
        assert!((a1 / a2 / 1.4 - 1.0).abs() < 1e-14, "{g:?}");
        assert!((a3 / (a1 * a2).sqrt() - 1.0).abs() < 1e-15, "{g:?}");
        // Turned about z only, free to turn about it.
        assert_eq!([g.quaternion[1], g.quaternion[2]], [0.0, 0.0], "{g:?}");
        assert_eq!(g.turn_axis, Some(PLANE_NORMAL));
        assert!((g.volume() - PI * a1 * a2).abs() < 1e-12 * g.volume());
    }
}

/// Random angles are uniform on a half turn: `cos 2θ` and `sin 2θ` have mean 0 and
/// standard error `1/√(2n)`; 5 of them are allowed. Aligned grains all have the angle.
#[test]
fn random_angles_are_uniform_and_aligned_ones_equal() {
    let text = with_line(2, "grains = 20000").replace("[120.0, 80.0]", "[2000.0, 2000.0]");
    let theta: Vec<f64> = (grains(&text).iter())
        .map(|g| ellipse_angle(g.quaternion))
        .collect();
    let n = theta.len() as f64;
    let (c, s) = theta.iter().fold((0.0, 0.0), |(c, s), t| {
        (c + (2.0 * t).cos() / n, s + (2.0 * t).sin() / n)
    });
    let se = 1.0 / (2.0 * n).sqrt();
    assert!(c.abs() < 5.0 * se && s.abs() < 5.0 * se, "{c} {s}");

    let aligned = with_line(18, "kind = \"aligned\"\nangle = -30");
    for g in grains(&aligned) {
        // sin_cos, atan2 and the half-angle quaternion: a few ulps of the angle.
        let back = ellipse_angle(g.quaternion);
        assert!((back + PI / 6.0).abs() < 1e-14, "{back}");
    }
}

/// `vonmises` and `tilt` about z are the same law of the angle, in degrees: the angles
/// drawn follow its exact truncated CDF (KS at significance 0.001, 1.95/√n), and the
/// grain's first semi-axis lies at the angle drawn.
#[test]
fn von_mises_angles_follow_their_law_with_either_spelling() {
    let n = 20_000;
    let law = VonMises {
        mean: 30f64.to_radians(),
        kappa: 3.0,
        min: -60f64.to_radians(),
        max: 120f64.to_radians(),
    };
    let cdf = VonMisesCdf::new(&law);
    let keys = "mean = 30\nkappa = 3\nmin = -60\nmax = 120";
    for kind in ["kind = \"vonmises\"", "kind = \"tilt\"\naxis = \"z\""] {
        let text = with_line(18, &format!("{kind}\n{keys}"))
            .replace("target_fraction = 0.6", &format!("grains = {n}"))
            .replace("[120.0, 80.0]", "[2000.0, 2000.0]");
        let drawn = grains(&text);
        let theta: Vec<f64> = drawn.iter().map(|g| g.tilt.unwrap()).collect();
        let ks = ks_distance(theta, |t| cdf.cdf(t));
        assert!(ks < 1.95 / (n as f64).sqrt(), "{kind}: KS {ks}");
        for g in &drawn {
            let t = g.tilt.unwrap();
            let turns = (ellipse_angle(g.quaternion) - t) / PI;
            assert!((turns - turns.round()).abs() < 1e-14, "{kind}: {t}");
        }
    }
}

#[test]
fn the_densest_fraction_is_the_ellipses_and_the_gap_counts_in_area() {
    // 0.85 is beyond every ellipsoid packing but below π/√12 = 0.9069.
    assert_eq!(
        scene(&with_line(2, "target_fraction = 0.85"))
            .domain
            .dimension,
        Dimension::Two
    );
    assert_starts(
        &error(&with_line(2, "target_fraction = 0.91")),
        "scene.toml:2:19: target_fraction = 0.91: must lie in (0, 0.9068996821171089]: \
         0.9068996821171089 is the densest known packing of ellipses",
    );
    // 0.6 · 1.25² = 0.9375 > π/√12; at most √(0.9069/0.6) − 1 = 0.2294.
    assert_starts(
        &error(&format!("{BASE}[packing]\ngap = 0.25\n")),
        "scene.toml:20:7: packing.gap = 0.25: the grains inflated by 1 + gap would fill 0.938 of \
         the box (the grains fill 0.600), beyond the densest packing of ellipses \
         (0.9068996821171089): the gap can be at most 0.2294 here",
    );
}

/// Two phases share the area; a gap shrinks the reachable estimate by `(1 + gap)²`,
/// and the estimate is the discs' of the equivalent-circle diameters.
#[test]
fn phases_share_the_area_and_the_estimate_is_of_discs() {
    let text = format!(
        "{}[[phase]]\nname = \"b\"\nshare = 3\nsize = {{ distribution = \"constant\", value = 4.0 }}\n\
         [packing]\ngap = 0.05\n",
        BASE.replace("target_fraction = 0.6", "target_fraction = 0.5")
            .replace("[120.0, 80.0]", "[600.0, 400.0]")
    );
    let s = scene(&text);
    let drawn = s.sample_grains(&mut s.rng()).unwrap();
    let area = |p: usize| -> f64 {
        (drawn.iter().filter(|g| g.phase == p))
            .map(GrainSpec::volume)
            .sum()
    };
    // Each phase within one grain (area ≤ π 8²/4) of its share of the total.
    let total = area(0) + area(1);
    assert!(
        (area(1) - 0.75 * total).abs() < PI / 4.0 * 64.0,
        "{} of {total}",
        area(1)
    );
    let estimate = Drawn::of(&s, &drawn);
    let diameters: Vec<f64> = drawn.iter().map(|g| g.diameter).collect();
    let discs = random_close_packing_discs(&diameters).unwrap();
    // Equivalent-circle diameters recomputed from the semi-axes: a few ulps apart.
    assert!((estimate.reachable_fraction - discs / 1.05f64.powi(2)).abs() < 1e-9);
    assert!(!estimate.spheres);
}

#[test]
fn measured_2d_tables_give_ellipses_at_their_angles() {
    let dir = support::files::scratch("scene-2d", "measured");
    std::fs::write(
        dir.join("fibres.csv"),
        "id,x,y,a1,a2,angle\n0,1,1,3.0,2.0,90\n1,5,5,2.5,2.5,0\n",
    )
    .unwrap();
    let text = "[box]\nsize = [40, 30]\n[[phase]]\nmeasured = { file = \"fibres.csv\", mode = \"exact\" }\n";
    let name = dir.join("scene.toml").display().to_string();
    let s = Scene::from_str(text, &name).unwrap_or_else(|e| panic!("{e}"));
    assert_eq!(s.count, GrainCount::Exactly(2));
    let g = s.sample_grains(&mut s.rng()).unwrap();
    assert_eq!(g[0].semi_axes, [3.0, 2.0, 6f64.sqrt()]);
    assert_eq!(g[0].dimension, Dimension::Two);
    // 90° about z: the first semi-axis along y.
    assert!((ellipse_angle(g[0].quaternion) - 0.5 * PI).abs() < 1e-15);
    assert!((g[0].diameter - 2.0 * 6f64.sqrt()).abs() < 1e-14);
    // The tables' areas fix the fraction: π (6 + 6.25) / 1200.
    let fraction = PI * (6.0 + 6.25) / 1200.0;
    assert!((s.expected_fraction() - fraction).abs() < 1e-15);
    // A 3D scene refuses the same table.
    let solid = text.replace("[40, 30]", "[40, 30, 30]");
    let err = Scene::from_str(&solid, &name).unwrap_err().to_string();
    assert!(err.contains("is a 2D table of ellipses"), "{err}");
}

#[test]
fn rve_cells_are_one_thick() {
    let cells = |output: &str| {
        let s = scene(&format!("{BASE}[output]\nrve = true\n{output}\n"));
        s.output.rve.expect("rve").cells
    };
    assert_eq!(cells("rve_resolution = 60"), [60, 40, 1]);
    assert_eq!(cells("rve_resolution = [30, 20]"), [30, 20, 1]);
    assert_eq!(cells("rve_voxel_size = 2.0"), [60, 40, 1]);
    let s = scene(&format!("{BASE}[output]\nrve = true\n"));
    assert!(!s.output.rve.unwrap().sections_png);
}

/// Every key with no meaning in the plane, refused naming file, line, key and value.
#[test]
fn keys_without_meaning_in_2d_are_refused() {
    let no_meaning = "has no meaning in a 2D scene (box.size = [Lx, Ly])";
    let cases: Vec<(String, String)> = vec![
        (
            format!("{BASE}[phase.c_over_a]\ndistribution = \"constant\"\nvalue = 0.5"),
            format!("scene.toml:19:1: phase[0].c_over_a = [phase.c_over_a]: {no_meaning}: an ellipse has two semi-axes"),
        ),
        (
            with_line(14, "[phase.b_over_a]"),
            format!("scene.toml:14:1: phase[0].b_over_a = [phase.b_over_a]: {no_meaning}: an ellipse has two semi-axes"),
        ),
        (
            with_line(18, "kind = \"fisher\""),
            format!("scene.toml:18:8: phase[0].orientation.kind = \"fisher\": {no_meaning}: a direction on the sphere"),
        ),
        (
            with_line(18, "kind = \"fixed\"\nquaternion = [1, 0, 0, 0]"),
            format!("scene.toml:18:8: phase[0].orientation.kind = \"fixed\": {no_meaning}: a quaternion is a 3D orientation"),
        ),
        (
            with_line(18, "kind = \"aligned\"\naxis = \"x\""),
            format!("scene.toml:19:8: phase[0].orientation.axis = \"x\": {no_meaning}: an ellipse's direction is its angle"),
        ),
        (
            with_line(18, "kind = \"tilt\"\naxis = \"x\"\nkappa = 1"),
            format!("scene.toml:19:8: phase[0].orientation.axis = \"x\": {no_meaning}: grains in the plane turn about z only"),
        ),
        (
            with_line(18, "kind = \"vonmises\"\nkappa = 1\ndirection = \"z\""),
            "scene.toml:20:13: phase[0].orientation.direction = \"z\": does not apply to kind = \"vonmises\", which takes mean, kappa, min, max".into(),
        ),
        (
            with_line(18, "kind = \"vonmises\""),
            "scene.toml:17:1: phase[0].orientation.kappa = (missing): kind = \"vonmises\" needs kappa".into(),
        ),
        (
            with_line(18, "kind = \"aligned\"\nangle = nan"),
            "scene.toml:19:9: phase[0].orientation.angle = nan: must be a finite angle in degrees".into(),
        ),
        (
            format!("{BASE}[packing]\nrotation = \"axis\""),
            format!("scene.toml:20:12: packing.rotation = \"axis\": {no_meaning}: every grain in the plane turns about z"),
        ),
        (
            format!("{BASE}[output]\nrve = true\nrve_resolution = [10, 10, 10]"),
            "scene.toml:21:18: output.rve_resolution = [10, 10, 10]: must be an integer or an array of two integers [nx, ny]".into(),
        ),
        (
            format!("{BASE}[output]\nrve = true\nsections_png = true"),
            format!("scene.toml:21:16: output.sections_png = true: {no_meaning}: the RVE of a 2D scene is one cell thick"),
        ),
        (
            with_line(9, "distribution = \"table\"\nx = [6, 8]\ncdf = [0, 1]\nby = \"volume\"").replace("mean = 7.0\nstd = 0.5\nmin = 6.0\nmax = 8.0\n", ""),
            format!("scene.toml:12:6: phase[0].size.by = \"volume\": {no_meaning}: its grains have areas; give by = \"area\""),
        ),
        (
            format!("{BASE}[output]\nvtk = true\nvtk_resolution = 9"),
            "scene.toml:21:18: output.vtk_resolution = 9: must lie in [1, 6] (a polygon of 8·2^n points per ellipse)".into(),
        ),
        (
            with_line(4, "size = [120.0]"),
            "scene.toml:4:8: box.size = [120.0]: must be [Lx, Ly, Lz] (a box of ellipsoids) or [Lx, Ly] (a 2D scene: a rectangle of ellipses), not 1 lengths".into(),
        ),
        (
            with_line(4, "size = [120.0, -1]"),
            "scene.toml:4:8: box.size = [120.0, -1]: every side must be positive and finite".into(),
        ),
        // 1000 π E[d²]/4 / 9600 with E[d²] = 49 + 0.25 (1 − 4φ(2)/(2Φ(2) − 1)) = 49.1934
        // (the normal truncated at ±2σ): 4.025.
        (
            with_line(2, "grains = 1000"),
            "scene.toml:2:10: grains = 1000: that many grains fill an expected 4.025 of the box, beyond the densest packing of ellipses (0.9068996821171089)".into(),
        ),
    ];
    for (text, want) in &cases {
        assert_starts(&error(text), want);
    }
    // The 2D spellings in a 3D scene.
    let solid = BASE.replace("[120.0, 80.0]", "[120.0, 80.0, 80.0]");
    let solid_line = |line: usize, text: &str| {
        let mut lines: Vec<&str> = solid.lines().collect();
        lines[line - 1] = text;
        lines.join("\n") + "\n"
    };
    assert_starts(
        &error(&solid_line(18, "kind = \"vonmises\"\nkappa = 1")),
        "scene.toml:18:8: phase[0].orientation.kind = \"vonmises\": \"vonmises\" is a 2D scene's law",
    );
    assert_starts(
        &error(&solid_line(18, "kind = \"aligned\"\nangle = 30")),
        "scene.toml:19:9: phase[0].orientation.angle = 30: applies only in a 2D scene",
    );
}

/// Measured tables of the wrong dimension, refused naming the table's header.
#[test]
fn tables_of_the_other_dimension_are_refused() {
    let dir = support::files::scratch("scene-2d", "tables");
    let check = |size: &str, header: &str, want: &str| {
        std::fs::write(dir.join("t.csv"), format!("{header}\n1,1,1,1\n")).unwrap();
        let text = format!(
            "[box]\nsize = {size}\n[[phase]]\nmeasured = {{ file = \"t.csv\" }}\ngrains = 3\n"
        );
        let text = format!("grains = 3\n{}", text.replace("grains = 3\n", ""));
        let name = dir.join("scene.toml").display().to_string();
        let err = Scene::from_str(&text, &name).unwrap_err().to_string();
        assert!(
            err.contains("phase[0].measured.file") && err.contains(want),
            "{err}"
        );
    };
    check(
        "[40, 30]",
        "a1,a2,a3,angle",
        "a3 has no meaning in a 2D scene",
    );
    check("[40, 30]", "a1,a2,qw,qz", "qw has no meaning in a 2D scene");
    check("[40, 30, 30]", "a1,a2,angle,d", "is a 2D table of ellipses");
    check("[40, 30, 30]", "id,a1,a2,x", "is a 2D table of ellipses");
}

#[test]
fn shipped_2d_examples_load_as_2d_scenes() {
    for name in ["fibres_2d.toml", "ellipses_2d.toml"] {
        let path = Path::new(env!("CARGO_MANIFEST_DIR"))
            .join("configs")
            .join(name);
        let s = Scene::from_path(&path).unwrap_or_else(|e| panic!("{e}"));
        assert_eq!(s.domain.dimension, Dimension::Two, "{name}");
        let g = s.sample_grains(&mut s.rng()).unwrap();
        assert!(g.iter().all(|g| g.dimension == Dimension::Two), "{name}");
    }
}
