//! What a 2D run writes, read back independently: ellipses placed by hand on a jittered
//! lattice in a plane box (so the test knows every grain and every nearest neighbour),
//! written by `write_outputs`, and each file checked against the grains placed.

mod support;

use grainpack::io::plots::{packing_png_size, phase_colour, PACKING_PNG_MARGIN};
use grainpack::io::report::write_outputs;
use grainpack::packing::{verify, Counters, PackedGrain, Packing, StopReason};
use grainpack::run::{Drawn, RunResult, RunTimings, Statistics};
use grainpack::scene::{Boundary, Domain, GrainSpec, Scene, VtkSpec};
use rand::{Rng, SeedableRng};
use rand_chacha::ChaCha8Rng;
use serde_json::Value;
use std::f64::consts::PI;
use std::path::Path;
use std::time::Duration;
use support::files::{files_in, pack_in, scratch};
use support::vtk::read_vtk;

/// Lattice spacing, and the cells along x and y.
const SPACING: f64 = 10.0;
const CELLS: [usize; 2] = [6, 5];
/// Equivalent-circle diameter and aspect ratio of every ellipse: `a1 = 4.25 √1.2 ≈
/// 4.66`, so with centres moved at most [`JITTER`] from their sites two ellipses are
/// at least `10 − 2·0.3 = 9.4 > 2 a1` apart. The four nearest sites (`≤ 10.6`) are
/// within the neighbour reach `1.4 d = 11.9`, the diagonal ones (`≥ 13.5`) beyond it.
const DIAMETER: f64 = 8.5;
const ASPECT: f64 = 1.2;
const JITTER: f64 = 0.3;

const SCENE: &str = r#"
seed = 1
grains = 30
[box]
size = [60, 50, 60]
[[phase]]
name = "fibre"
size = { distribution = "constant", value = 8.5 }
[[phase]]
name = "ellipse"
size = { distribution = "constant", value = 8.5 }
aspect_ratio = { distribution = "constant", value = 1.2 }
"#;

/// A run of ellipses on the lattice in a periodic box, shifted so that some cross the
/// box's edges.
fn plane_run(dir: &Path) -> (Scene, RunResult, Vec<f64>) {
    let mut scene = Scene::from_str(SCENE, "plane.toml").unwrap();
    let sides = CELLS.map(|n| n as f64 * SPACING);
    scene.domain = Domain::plane(sides, Boundary::Periodic);
    scene.output.dir = dir.to_owned();
    scene.output.packing_png = true;
    scene.output.vtk = Some(VtkSpec {
        resolution: 2,
        periodic_images: true,
    });
    let mut rng = ChaCha8Rng::seed_from_u64(7);
    let (mut specs, mut grains, mut angles) = (Vec::new(), Vec::new(), Vec::new());
    for n in 0..CELLS[0] * CELLS[1] {
        let site = [n % CELLS[0], n / CELLS[0]].map(|i| (i as f64 + 0.5) * SPACING);
        // Half a cell towards the origin, wrapped: the first row and column cross.
        let wrap = |x: f64, l: f64| if x < 0.0 { x + l } else { x };
        let centre = [0, 1].map(|k| {
            wrap(
                site[k] - 0.5 * SPACING + rng.random_range(-JITTER..JITTER),
                sides[k],
            )
        });
        let theta = rng.random_range(-PI..PI);
        let spec = GrainSpec::ellipse(n % 2, DIAMETER, ASPECT, theta);
        let at = [centre[0], centre[1], scene.domain.plane_z()];
        grains.push(PackedGrain::of_spec(
            n as u32,
            &spec,
            1.0,
            at,
            spec.quaternion,
        ));
        specs.push(spec);
        angles.push(theta);
    }
    let verification = verify(&grains, &scene.domain, 0.0).unwrap();
    assert!(verification.is_clean(), "{verification:?}");
    let packing = Packing {
        grains,
        scale: 1.0,
        fraction: 0.0,
        stop: StopReason::TargetReached,
        counters: Counters::default(),
        trials: Vec::new(),
        verification,
    };
    let statistics = Statistics::new(&scene, &specs, &packing);
    let result = RunResult {
        seed: 1,
        threads: 1,
        drawn: Drawn::of(&scene, &specs),
        specs,
        packing,
        statistics,
        timings: RunTimings {
            packing: Duration::ZERO,
            total: Duration::ZERO,
        },
    };
    (scene, result, angles)
}

/// `theta` as the angle of an axis, in degrees in (−90, 90].
fn axis_degrees(theta: f64) -> f64 {
    let d = theta.to_degrees();
    let folded = d - 180.0 * (d / 180.0).round();
    if folded <= -90.0 {
        folded + 180.0
    } else {
        folded
    }
}

#[test]
fn a_2d_run_writes_the_plane_files() {
    let dir = scratch("outputs_2d", "periodic");
    let (scene, result, angles) = plane_run(&dir);
    write_outputs(&scene, &result).unwrap();
    assert_eq!(
        files_in(&dir),
        [
            "centers.vtp",
            "grains.csv",
            "grains.vtu",
            "packing.png",
            "statistics.png",
            "summary.json"
        ]
    );
    let grains = &result.packing.grains;

    // grains.csv: the plane's columns, the angle as drawn (as an axis).
    let text = std::fs::read_to_string(dir.join("grains.csv")).unwrap();
    let mut lines = text.lines();
    assert_eq!(
        lines.next(),
        Some("id,phase,x,y,a1,a2,angle,o0,o1,o2,o3,phi1,Phi,phi2")
    );
    for ((line, g), theta) in lines.zip(grains).zip(&angles) {
        let v: Vec<f64> = line.split(',').map(|x| x.parse().unwrap()).collect();
        assert_eq!(
            v[..6],
            [
                f64::from(g.id),
                g.phase as f64,
                g.centre[0],
                g.centre[1],
                g.semi_axes[0],
                g.semi_axes[1]
            ]
        );
        // Half-angle sin_cos and atan2: a few ε of 180°.
        assert!((v[6] - axis_degrees(*theta)).abs() < 1e-12, "{line}");
    }

    // grains.vtu: one polygon per ellipse and per copy across an edge.
    let vtu = read_vtk(&dir.join("grains.vtu"));
    let types = vtu.array("types", "Cells", "UInt8", 1);
    let cells = types.len();
    assert!(types.iter().all(|&t| t == 7.0), "VTK_POLYGON");
    assert!(
        cells > grains.len(),
        "copies of the ellipses across the edges"
    );
    let m = VtkSpec::default().polygon_vertices();
    let offsets = vtu.array("offsets", "Cells", "Int32", 1);
    assert!((0..cells).all(|k| offsets[k] == ((k + 1) * m) as f64));
    let points = vtu.array("Points", "Points", "Float32", 3);
    let ids = vtu.array("grain_id", "CellData", "Int32", 1);
    let image = vtu.array("periodic_image", "CellData", "UInt8", 1);
    let area = vtu.array("area", "CellData", "Float64", 1);
    // A regular m-gon inscribed in the unit circle, mapped onto the ellipse.
    let inscribed = m as f64 / (2.0 * PI) * (2.0 * PI / m as f64).sin();
    for k in 0..cells {
        let g = &grains[ids[k] as usize];
        let (c, s) = (
            g.quaternion[0] * g.quaternion[0] - g.quaternion[3] * g.quaternion[3],
            2.0 * g.quaternion[0] * g.quaternion[3],
        );
        let vertices: Vec<[f64; 3]> = (0..m)
            .map(|v| {
                let p = &points[3 * (k * m + v)..3 * (k * m + v) + 3];
                [p[0], p[1], p[2]]
            })
            .collect();
        let mean = [0, 1].map(|i| vertices.iter().map(|p| p[i]).sum::<f64>() / m as f64);
        let shift = [0, 1].map(|i| {
            let l = scene.domain.size[i];
            ((mean[i] - g.centre[i]) / l).round() * l
        });
        assert_eq!(shift != [0.0; 2], image[k] == 1.0, "cell {k}");
        let mut signed = 0.0;
        for (v, p) in vertices.iter().enumerate() {
            assert_eq!(p[2], 0.0);
            let (dx, dy) = (p[0] - shift[0] - g.centre[0], p[1] - shift[1] - g.centre[1]);
            // In the ellipse's frame: on it to single precision (coordinates below 60).
            let (u, w) = (c * dx + s * dy, -s * dx + c * dy);
            let radius = (u / g.semi_axes[0]).hypot(w / g.semi_axes[1]);
            assert!((radius - 1.0).abs() < 1e-5, "cell {k}: {radius}");
            let q = vertices[(v + 1) % m];
            signed += 0.5 * (p[0] * q[1] - q[0] * p[1]);
        }
        let exact = PI * g.semi_axes[0] * g.semi_axes[1];
        assert!((area[k] / exact - 1.0).abs() < 1e-15);
        // Counter-clockwise, enclosing the inscribed share of the ellipse.
        assert!(
            (signed / exact - inscribed).abs() < 1e-4,
            "cell {k}: {}",
            signed / exact
        );
    }

    // centers.vtp: the flat ellipses at z = 0.
    let vtp = read_vtk(&dir.join("centers.vtp"));
    let centres = vtp.array("Points", "Points", "Float64", 3);
    let axes = vtp.array("semi_axes", "PointData", "Float64", 3);
    for (i, g) in grains.iter().enumerate() {
        assert_eq!(centres[3 * i..3 * i + 3], [g.centre[0], g.centre[1], 0.0]);
        assert_eq!(
            axes[3 * i..3 * i + 3],
            [g.semi_axes[0], g.semi_axes[1], 0.0]
        );
    }

    check_summary(&dir, &scene, grains);
    check_picture(&dir, &scene, grains);
}

/// `summary.json`: the area fraction, and the nearest neighbours and ψ6 as a brute-force
/// search over the minimum images finds them.
fn check_summary(dir: &Path, scene: &Scene, grains: &[PackedGrain]) {
    let summary: Value =
        serde_json::from_str(&std::fs::read_to_string(dir.join("summary.json")).unwrap()).unwrap();
    let [lx, ly, _] = scene.domain.size;
    let areas: f64 = grains
        .iter()
        .map(|g| PI * g.semi_axes[0] * g.semi_axes[1])
        .sum();
    let fraction = summary["packing_fraction"].as_f64().unwrap();
    assert!(
        (fraction / (areas / (lx * ly)) - 1.0).abs() < 1e-14,
        "{fraction}"
    );
    let diameter = &summary["phases"][1]["diameter"]["achieved"]["mean"];
    assert!(
        (diameter.as_f64().unwrap() / DIAMETER - 1.0).abs() < 1e-14,
        "{diameter}"
    );
    let order = summary["phases"][1]["angle_deg"]["order"].as_f64().unwrap();
    assert!((0.0..=1.0).contains(&order));
    let plane = &summary["plane"];
    assert_eq!(plane["mean_neighbours"], 4.0);
    assert_eq!(plane["isolated_grains"], 0);
    // Brute force over the minimum images.
    let image = |d: f64, l: f64| d - l * (d / l).round();
    let mut nearest: Vec<f64> = grains
        .iter()
        .map(|a| {
            grains
                .iter()
                .filter(|b| b.id != a.id)
                .map(|b| {
                    image(b.centre[0] - a.centre[0], lx).hypot(image(b.centre[1] - a.centre[1], ly))
                })
                .fold(f64::INFINITY, f64::min)
        })
        .collect();
    nearest.sort_by(f64::total_cmp);
    let spread = &plane["nearest_centre_distance"];
    assert_eq!(spread["min"].as_f64().unwrap(), nearest[0]);
    assert_eq!(spread["max"].as_f64().unwrap(), nearest[nearest.len() - 1]);
    let mean = nearest.iter().sum::<f64>() / nearest.len() as f64;
    assert!((spread["mean"].as_f64().unwrap() - mean).abs() < 1e-12);
    // A jittered square lattice: neighbours at about 0°, 90°, 180°, 270° cancel in ψ6.
    assert!(plane["psi6_local"].as_f64().unwrap() < 0.3, "{plane}");
    let gap = plane["nearest_gap"]["min"].as_f64().unwrap();
    assert!(gap > 0.0 && gap < nearest[0] / DIAMETER, "{plane}");
}

/// `packing.png`: every grain's centre in its phase's colour, the middle of each
/// lattice cell's corner (between four grains) white.
fn check_picture(dir: &Path, scene: &Scene, grains: &[PackedGrain]) {
    let decoder = png::Decoder::new(std::io::BufReader::new(
        std::fs::File::open(dir.join("packing.png")).unwrap(),
    ));
    let mut reader = decoder.read_info().unwrap();
    let mut rgb = vec![0; reader.output_buffer_size()];
    let info = reader.next_frame(&mut rgb).unwrap();
    let [lx, ly, _] = scene.domain.size;
    let (width, height, scale) = packing_png_size([lx, ly]);
    assert_eq!((info.width, info.height), (width, height));
    let pixel = |x: f64, y: f64| {
        let (px, py) = (
            PACKING_PNG_MARGIN as f64 + x * scale,
            f64::from(height - PACKING_PNG_MARGIN) - y * scale,
        );
        let at = 3 * (py as usize * width as usize + px as usize);
        [rgb[at], rgb[at + 1], rgb[at + 2]]
    };
    for g in grains {
        let c = phase_colour(g.phase);
        // 85 % of the colour over white.
        let want = [c.0, c.1, c.2].map(|v| (0.85 * f64::from(v) + 0.15 * 255.0).round());
        // A point one unit inside the box from a centre on an edge (the edge itself is
        // the box's outline): still well inside the grain (a2 ≈ 3.9).
        let inward = |x: f64, l: f64| x.clamp(1.0, l - 1.0);
        let got = pixel(inward(g.centre[0], lx), inward(g.centre[1], ly)).map(f64::from);
        let off = (0..3).map(|i| (got[i] - want[i]).abs()).fold(0.0, f64::max);
        assert!(off <= 2.0, "grain {}: {got:?} vs {want:?}", g.id);
    }
    // Grain centres sit on the corners of the cells; the cells' centres are empty.
    for i in 0..CELLS[0] {
        for j in 0..CELLS[1] {
            let (x, y) = ((i as f64 + 0.5) * SPACING, (j as f64 + 0.5) * SPACING);
            assert_eq!(pixel(x, y), [255; 3], "({x}, {y})");
        }
    }
}

/// 60 ellipses asked past the reachable estimate of discs, with a gap: the warning
/// before packing and the closing report speak of discs and areas, and of the gap's
/// square.
#[test]
fn the_2d_warning_speaks_of_discs_and_the_gap_squared() {
    let dir = scratch("plane", "warning");
    let scene = "seed = 2\ngrains = 60\n[box]\nsize = [15.0, 15.0]\n[[phase]]\n\
        size = { distribution = \"uniform\", min = 1.6, max = 2.2 }\n\
        aspect_ratio = { distribution = \"constant\", value = 1.5 }\n\
        [packing]\ngap = 0.05\n[output]\ndir = \"out\"\n";
    std::fs::write(dir.join("scene.toml"), scene).unwrap();
    let run = pack_in(&dir, &["scene.toml"]);
    let err = String::from_utf8_lossy(&run.stderr);
    assert!(
        err.contains("random packings of discs of the same areas reach about")
            && err.contains("random close packing of discs of these sizes ≈")
            && err.contains("ellipses free to turn pack denser")
            && err.contains("divided by (1 + packing.gap)² = 1.1025"),
        "{err}"
    );
    assert!(!err.contains("spheres") && !err.contains("³"), "{err}");
}
