//! End-to-end tests of the VTK exports: `pack` runs on small scenes, and what it wrote
//! is parsed here with a plain XML parser and zlib (not the writer's code) and
//! checked against `grains.csv`, read with nalgebra's rotations.

mod support;

use nalgebra::Vector3;
use std::collections::HashSet;
use std::path::{Path, PathBuf};

use support::files::{files_in, pack_in, scratch};
use support::packed::{extent, read_grains, Grain};
use support::vtk::read_vtk;

/// A point's distance from its ellipsoid, in the ellipsoid's own units
/// `|diag(1/a) Rᵀ (x − c)| − 1`. The points are stored in single precision: each
/// coordinate, up to 32 (a 24 box and its copies), is rounded by at most 32·2⁻²⁴, and
/// over semi-axes down to 1 the three components move the radius by at most
/// √3·32·2⁻²⁴ ≈ 3.3e-6 (the double-precision differences between the writer's and
/// nalgebra's rotations, ~1e-14, do not show); 1e-5 leaves a factor 3.
const ON_SURFACE_TOL: f64 = 1e-5;

/// Relative spread of the mesh/ellipsoid volume ratio between grains: the affine map
/// makes it the same for every grain in exact arithmetic, and a volume (the cube of a
/// length) moves by at most 3 × [`ON_SURFACE_TOL`] when its points move radially by
/// that much.
const VOLUME_RATIO_TOL: f64 = 3.0 * ON_SURFACE_TOL;

/// Relative agreement of figures computed twice in double precision (a product, a
/// cube root, a sum of three terms): a few ulp, with room.
const REL_TOL: f64 = 1e-14;

/// Mesh volume / ellipsoid volume of the level-1 icosphere, as docs/config.md lists it
/// (4 digits).
const LEVEL_1_VOLUME_RATIO: f64 = 0.8735;

/// Two phases in a periodic cube, about 0.3 full, with periodic copies in the VTU.
const PERIODIC: &str = r#"
seed = 4
grains = 40
[box]
size = [24.0, 24.0, 24.0]
[[phase]]
size = { distribution = "lognormal", sigma = 0.3, scale = 6.0, min = 4.0, max = 8.0 }
aspect_ratio = { distribution = "uniform", min = 1.0, max = 2.0 }
[[phase]]
share = 0.5
size = { distribution = "constant", value = 5.0 }
aspect_ratio = { distribution = "constant", value = 0.5 }
[output]
vtk_resolution = 1
periodic_images = true
"#;

/// Needles between walls.
const WALLED: &str = r#"
seed = 9
grains = 30
[box]
size = [24.0, 20.0, 28.0]
boundary = "reflecting"
[[phase]]
size = { distribution = "uniform", min = 4.0, max = 6.0 }
aspect_ratio = { distribution = "constant", value = 3.0 }
orientation = { kind = "aligned", axis = "z" }
"#;

/// Runs `pack scene.toml --out out --quiet` in a fresh directory; returns `out`.
fn pack(name: &str, scene: &str) -> PathBuf {
    let dir = scratch("exports", name);
    std::fs::write(dir.join("scene.toml"), scene).unwrap();
    let run = pack_in(&dir, &["scene.toml", "--out", "out", "--quiet"]);
    let err = String::from_utf8_lossy(&run.stderr);
    assert_eq!(run.status.code(), Some(0), "{err}");
    dir.join("out")
}

fn close(a: f64, b: f64, rel: f64) -> bool {
    (a - b).abs() <= rel * a.abs().max(b.abs())
}

/// Checks `grains.vtu` against the grains; returns how many surfaces are copies.
fn check_surfaces(out: &Path, grains: &[Grain], size: [f64; 3], triangles: usize) -> usize {
    let vtu = read_vtk(&out.join("grains.vtu"));
    assert_eq!(vtu.root["type"], "UnstructuredGrid");
    let (n_points, n_cells) = (vtu.count("NumberOfPoints"), vtu.count("NumberOfCells"));
    let points = vtu.array("Points", "Points", "Float32", 3);
    let conn = vtu.array("connectivity", "Cells", "Int32", 1);
    let offsets = vtu.array("offsets", "Cells", "Int32", 1);
    let types = vtu.array("types", "Cells", "UInt8", 1);
    assert_eq!((points.len(), conn.len()), (3 * n_points, 3 * n_cells));
    assert!(offsets
        .iter()
        .enumerate()
        .all(|(i, &o)| o == 3.0 * (i + 1) as f64));
    assert!(types.iter().all(|&t| t == 5.0), "triangles are VTK type 5");
    let cell = |name, kind| vtu.array(name, "CellData", kind, 1);
    let (ids, image) = (cell("grain_id", "Int32"), cell("periodic_image", "UInt8"));
    let surfaces = n_cells / triangles;
    assert_eq!(surfaces * triangles, n_cells);
    let point = |i: f64| Vector3::from_fn(|k, _| points[3 * i as usize + k]);

    let mut own = HashSet::new();
    let mut copies = vec![0; grains.len()];
    let mut ratios = Vec::new();
    let mut edges = HashSet::new();
    for s in 0..surfaces {
        let cells = s * triangles..(s + 1) * triangles;
        let g = &grains[ids[cells.start] as usize];
        let product: f64 = g.semi_axes.iter().product();
        for c in cells.clone() {
            assert_eq!(ids[c], g.id as f64);
            assert_eq!(image[c], image[cells.start]);
            assert_eq!(cell("phase", "Int32")[c], g.phase as f64);
            assert!(close(cell("volume", "Float64")[c], g.volume(), REL_TOL));
            let d = cell("equivalent_diameter", "Float64")[c];
            assert!(close(d, 2.0 * product.cbrt(), REL_TOL));
            assert_eq!(
                cell("aspect_ratio", "Float64")[c],
                g.semi_axes[0] / g.semi_axes[1]
            );
        }
        // The copy's shift: whole box lengths, into the box across each crossed face.
        let tri = &conn[3 * cells.start..3 * cells.end];
        let mean = tri.iter().map(|&i| point(i)).sum::<Vector3<f64>>() / tri.len() as f64;
        let shift = Vector3::from_fn(|k, _| ((mean[k] - g.centre[k]) / size[k]).round() * size[k]);
        if image[cells.start] == 0.0 {
            assert_eq!(shift, Vector3::zeros(), "grain {}", g.id);
            assert!(own.insert(g.id), "grain {} twice", g.id);
        } else {
            assert_eq!(image[cells.start], 1.0);
            copies[g.id] += 1;
            for k in 0..3 {
                let (low, high) = (
                    g.centre[k] - extent(g, k) < 0.0,
                    g.centre[k] + extent(g, k) > size[k],
                );
                assert!(
                    shift[k] == 0.0
                        || (shift[k] == size[k] && low)
                        || (shift[k] == -size[k] && high)
                );
            }
        }
        // Points on the ellipsoid; the signed volume of the closed surface.
        let mut volume = 0.0;
        for t in tri.chunks(3) {
            let [p, q, r] = [t[0], t[1], t[2]].map(|i| point(i) - shift);
            for x in [p, q, r] {
                let local = g.rotation.transpose() * (x - g.centre);
                let radius = Vector3::from_fn(|k, _| local[k] / g.semi_axes[k]).norm();
                assert!(
                    (radius - 1.0).abs() < ON_SURFACE_TOL,
                    "grain {}: |x| = {radius}",
                    g.id
                );
            }
            // About the centre, so the sum does not cancel large coordinates.
            let [p, q, r] = [p, q, r].map(|x| x - g.centre);
            volume += p.dot(&q.cross(&r)) / 6.0;
            for (a, b) in [(t[0], t[1]), (t[1], t[2]), (t[2], t[0])] {
                assert!(edges.insert((a as u64, b as u64)), "edge ({a}, {b}) twice");
            }
        }
        ratios.push(volume / g.volume());
    }
    // Closed and consistently oriented: each directed edge's reverse is there too.
    assert!(
        edges.iter().all(|&(a, b)| edges.contains(&(b, a))),
        "a surface is open"
    );
    // Outward (positive volume), and the same fraction of every ellipsoid (affine map).
    for r in &ratios {
        assert!(
            (r - ratios[0]).abs() < VOLUME_RATIO_TOL && *r > 0.0 && *r < 1.0,
            "{r} vs {}",
            ratios[0]
        );
    }
    if triangles == 80 {
        assert!(
            (ratios[0] - LEVEL_1_VOLUME_RATIO).abs() < 1e-4,
            "{}",
            ratios[0]
        );
    }
    assert_eq!(own.len(), grains.len(), "every grain once");
    // 2^k − 1 copies of a grain whose bounding box crosses k faces, in a periodic box.
    let periodic = image.contains(&1.0);
    for g in grains {
        let crossed = (0..3)
            .filter(|&k| g.centre[k] - extent(g, k) < 0.0 || g.centre[k] + extent(g, k) > size[k])
            .count();
        let want = if periodic { (1 << crossed) - 1 } else { 0 };
        assert_eq!(copies[g.id], want, "grain {}", g.id);
    }
    copies.iter().sum()
}

/// Checks `centers.vtp` against the grains.
fn check_centres(out: &Path, grains: &[Grain]) {
    let vtp = read_vtk(&out.join("centers.vtp"));
    assert_eq!(vtp.root["type"], "PolyData");
    let n = grains.len();
    assert_eq!(
        (vtp.count("NumberOfPoints"), vtp.count("NumberOfVerts")),
        (n, n)
    );
    let points = vtp.array("Points", "Points", "Float64", 3);
    let conn = vtp.array("connectivity", "Verts", "Int32", 1);
    let offsets = vtp.array("offsets", "Verts", "Int32", 1);
    let ids = vtp.array("grain_id", "PointData", "Int32", 1);
    let phases = vtp.array("phase", "PointData", "Int32", 1);
    let axes = vtp.array("semi_axes", "PointData", "Float64", 3);
    let s = vtp.array("shape_tensor", "PointData", "Float64", 9);
    let q = vtp.array("quadratic_form", "PointData", "Float64", 9);
    for (i, g) in grains.iter().enumerate() {
        assert_eq!((conn[i], offsets[i]), (i as f64, (i + 1) as f64));
        assert_eq!((ids[i], phases[i]), (g.id as f64, g.phase as f64));
        // Doubles pass through the compressed arrays and through the CSV's 17 digits unchanged.
        assert_eq!(&points[3 * i..3 * i + 3], g.centre.as_slice());
        assert_eq!(&axes[3 * i..3 * i + 3], &g.semi_axes[..]);
        let a_max = g.radius();
        for r in 0..3 {
            for c in 0..3 {
                assert_eq!(s[9 * i + 3 * r + c], s[9 * i + 3 * c + r], "symmetric");
                assert!(
                    (q[9 * i + 3 * r + c] - g.q[(r, c)]).abs() < REL_TOL * 16.0 * a_max * a_max
                );
            }
        }
        // S r_k = a_k r_k: the semi-axes are its eigenvalues along their directions.
        for k in 0..3 {
            let axis = g.rotation.column(k);
            for r in 0..3 {
                let sr: f64 = (0..3).map(|c| s[9 * i + 3 * r + c] * axis[c]).sum();
                assert!((sr - g.semi_axes[k] * axis[r]).abs() < REL_TOL * 16.0 * a_max);
            }
        }
    }
}

#[test]
fn a_periodic_packing_exports_closed_surfaces_copies_and_centres_that_match_the_csv() {
    let out = pack("periodic", PERIODIC);
    assert_eq!(
        files_in(&out),
        [
            "centers.vtp",
            "grains.csv",
            "grains.vtu",
            "statistics.png",
            "summary.json"
        ]
    );
    let grains = read_grains(&out.join("grains.csv"));
    let copies = check_surfaces(&out, &grains, [24.0; 3], 80);
    // 40 grains of diameter 4–8 in a box of 24: many cross a face.
    assert!(copies > 0, "no periodic copies were written");
    check_centres(&out, &grains);
}

#[test]
fn a_walled_packing_has_no_copies_and_outputs_turn_off() {
    let out = pack("walled", WALLED);
    let grains = read_grains(&out.join("grains.csv"));
    assert_eq!(check_surfaces(&out, &grains, [24.0, 20.0, 28.0], 320), 0);
    check_centres(&out, &grains);

    let off = format!("{WALLED}[output]\nvtk = false\ncenters = false\n");
    let out = pack("off", &off);
    assert_eq!(
        files_in(&out),
        ["grains.csv", "statistics.png", "summary.json"]
    );
}
