//! The plane-strain deck and the load case of a 2D pixel RVE, read back line by line:
//! CPE4 elements counter-clockwise on the pixels, nodes in the plane, one equation per
//! far node and in-plane component, sections of thickness 1, F_zz held in load.yaml.
//! CalculiX solves these decks in CI (tools/ccx_solve.py). And `pack` on a 2D scene:
//! its rve.vti one cell thick, areas in rve_grains.csv, the deck and the load case.

mod support;

use grainpack::contact::{ellipse_quaternion, ellipse_semi_axes};
use grainpack::io::decks::{write_abaqus_deck, write_load_yaml, PLANE_THICKNESS};
use grainpack::io::voxel::voxelise;
use grainpack::packing::PackedGrain;
use grainpack::scene::{Boundary, Domain, RveFill, Scene};
use std::collections::{HashMap, HashSet};

const SCENE: &str = r#"
grains = 2
[box]
size = [6.0, 4.0, 6.0]
[[phase]]
name = "fibre"
size = { distribution = "constant", value = 1.0 }
elastic = { E = 70.0, nu = 0.2 }
[matrix]
elastic = { E = 3.0, nu = 0.35 }
[output]
rve = true
rve_fill = "matrix"
"#;

/// The deck's lines between `*keyword` and the next keyword.
fn block<'a>(lines: &[&'a str], keyword: &str) -> Vec<&'a str> {
    let start = lines.iter().position(|l| l.starts_with(keyword)).unwrap() + 1;
    lines[start..]
        .iter()
        .take_while(|l| !l.starts_with('*'))
        .copied()
        .collect()
}

fn deck(periodic: bool) -> (String, String, [usize; 3]) {
    let boundary = if periodic {
        Boundary::Periodic
    } else {
        Boundary::Reflecting
    };
    let mut scene = Scene::from_str(SCENE, "plane.toml").unwrap();
    scene.domain = Domain::plane([6.0, 4.0], boundary);
    let z = scene.domain.plane_z();
    let grains: Vec<PackedGrain> = [([1.5, 2.0], 1.2, 0.6, 0.4), ([4.5, 2.0], 1.0, 0.8, -1.0)]
        .iter()
        .enumerate()
        .map(|(id, &([x, y], a1, a2, theta))| PackedGrain {
            id: id as u32,
            phase: 0,
            centre: [x, y, z],
            semi_axes: ellipse_semi_axes(a1, a2),
            quaternion: ellipse_quaternion(theta),
        })
        .collect();
    let cells = [12, 8, 1];
    let grid = voxelise(&grains, &scene.domain, cells, RveFill::Matrix, 1).unwrap();
    let (mut inp, mut load) = (Vec::new(), Vec::new());
    write_abaqus_deck(&mut inp, &scene, &grid).unwrap();
    write_load_yaml(&mut load, &grid).unwrap();
    (
        String::from_utf8(inp).unwrap(),
        String::from_utf8(load).unwrap(),
        cells,
    )
}

#[test]
fn the_plane_deck_is_cpe4_on_the_pixels_with_nodes_in_the_plane() {
    let (text, _, [nx, ny, _]) = deck(true);
    let lines: Vec<&str> = text.lines().collect();
    assert!(lines[1].contains("12 x 8 CPE4 elements (plane strain, thickness 1)"));
    let nodes: HashMap<usize, [f64; 2]> = block(&lines, "*Node")
        .iter()
        .map(|l| {
            let f: Vec<f64> = l.split(", ").map(|v| v.parse().unwrap()).collect();
            assert_eq!(f.len(), 3, "a node in the plane: {l}");
            (f[0] as usize, [f[1], f[2]])
        })
        .collect();
    assert_eq!(nodes.len(), (nx + 1) * (ny + 1) + 2);
    let elements = block(&lines, "*Element, type=CPE4");
    assert_eq!(elements.len(), nx * ny);
    for (e, line) in elements.iter().enumerate() {
        let ids: Vec<usize> = line.split(", ").map(|v| v.parse().unwrap()).collect();
        assert_eq!(ids[0], e + 1);
        let p: Vec<[f64; 2]> = ids[1..].iter().map(|i| nodes[i]).collect();
        // Shoelace: counter-clockwise, one pixel (0.5 × 0.5) in area.
        let area: f64 = (0..4)
            .map(|k| p[k][0] * p[(k + 1) % 4][1] - p[(k + 1) % 4][0] * p[k][1])
            .sum::<f64>()
            / 2.0;
        assert!(
            (area - 0.25).abs() < 1e-12,
            "element {}: area {area}",
            e + 1
        );
        // Element 1 + i + Nx j lies over pixel (i, j).
        let (i, j) = (e % nx, e / nx);
        let centre = p
            .iter()
            .fold([0.0; 2], |c, q| [c[0] + q[0] / 4.0, c[1] + q[1] / 4.0]);
        assert!((centre[0] - (i as f64 + 0.5) * 0.5).abs() < 1e-12);
        assert!((centre[1] - (j as f64 + 0.5) * 0.5).abs() < 1e-12);
    }
    let sections: Vec<usize> = lines
        .iter()
        .enumerate()
        .filter(|(_, l)| l.starts_with("*Solid Section"))
        .map(|(k, _)| k)
        .collect();
    assert_eq!(sections.len(), 2, "the fibres' and the matrix's");
    for k in sections {
        assert_eq!(lines[k + 1].parse::<f64>().unwrap(), PLANE_THICKNESS);
    }
    let sets: HashSet<&str> = lines
        .iter()
        .filter_map(|l| l.strip_prefix("*Nset, nset="))
        .collect();
    let want = [
        "X0", "X1", "Y0", "Y1", "X0Y0", "X1Y0", "X0Y1", "X1Y1", "RPX", "RPY", "RP",
    ];
    assert_eq!(sets, want.into_iter().collect());
}

#[test]
fn each_far_node_is_tied_once_per_in_plane_component() {
    let (text, _, [nx, ny, _]) = deck(true);
    let lines: Vec<&str> = text.lines().collect();
    let eqs = block(&lines, "*Equation");
    let (rpx, rpy) = ((nx + 1) * (ny + 1) + 1, (nx + 1) * (ny + 1) + 2);
    let mut dependent = HashSet::new();
    let mut k = 0;
    while k < eqs.len() {
        let terms: usize = eqs[k].parse().unwrap();
        let f: Vec<&str> = eqs[k + 1].split(", ").collect();
        assert_eq!(f.len(), 3 * terms, "{}", eqs[k + 1]);
        let node = |t: usize| f[3 * t].parse::<usize>().unwrap();
        let dof: usize = f[1].parse().unwrap();
        assert!(dof == 1 || dof == 2, "an in-plane component: {dof}");
        let me = node(0);
        let (i, j) = ((me - 1) % (nx + 1), (me - 1) / (nx + 1));
        // The image at the near edges, then the reference node of each far edge.
        assert_eq!(node(1), 1 + i % nx + (nx + 1) * (j % ny));
        let rps: Vec<usize> = (2..terms).map(node).collect();
        let mut want = Vec::new();
        if i == nx {
            want.push(rpx);
        }
        if j == ny {
            want.push(rpy);
        }
        assert_eq!(rps, want, "{}", eqs[k + 1]);
        assert!(
            dependent.insert((me, dof)),
            "node {me} dof {dof} tied twice"
        );
        k += 2;
    }
    let far = (nx + 1) * (ny + 1) - nx * ny;
    assert_eq!(dependent.len(), 2 * far);
}

#[test]
fn a_walled_plane_deck_has_no_equations_and_a_uniaxial_step() {
    let (text, _, _) = deck(false);
    assert!(!text.contains("*Equation"));
    let step = text.split("** ---- step template").nth(1).unwrap();
    assert!(
        step.contains("X0, 1, 1, 0.0\nY0, 2, 2, 0.0\nX1, 1, 1, 0.006"),
        "{step}"
    );
}

#[test]
fn the_plane_load_case_holds_f_zz() {
    let (_, load, _) = deck(true);
    assert!(
        load.contains("dot_F: [[1.0e-3, 0, 0], [0, x, 0], [0, 0, 0]]"),
        "{load}"
    );
    assert!(
        load.contains("P: [[x, x, x], [x, 0, x], [x, x, x]]"),
        "{load}"
    );
    assert!(load.contains("12 x 8 x 1 cells, a 2D grid"));
}

#[test]
fn pack_writes_a_2d_scene_as_pixels_one_cell_thick_with_its_deck_and_load_case() {
    let dir = support::files::scratch("deck_plane", "pack");
    let scene = r#"
seed = 4
grains = 6
[box]
size = [20.0, 12.0]
[[phase]]
name = "fibre"
size = { distribution = "uniform", min = 2.5, max = 4.0 }
aspect_ratio = { distribution = "uniform", min = 1.0, max = 2.0 }
elastic = { E = 70.0, nu = 0.2 }
[matrix]
elastic = { E = 3.0, nu = 0.35 }
[output]
dir = "out"
rve_resolution = [40, 24]
rve_fill = "matrix"
damask = true
abaqus = true
"#;
    std::fs::write(dir.join("scene.toml"), scene).unwrap();
    support::files::pack_ok(&dir, &["scene.toml", "--quiet"]);
    let out = dir.join("out");
    let read = |name: &str| std::fs::read_to_string(out.join(name)).unwrap();
    // Pixels of 0.5 µm, and the layer as thick: 5e-7 m each way.
    let vti = read("rve.vti");
    assert!(vti.contains(r#"WholeExtent="0 40 0 24 0 1""#));
    let spacing: Vec<f64> = vti
        .split("Spacing=\"")
        .nth(1)
        .unwrap()
        .split('"')
        .next()
        .unwrap()
        .split(' ')
        .map(|v| v.parse().unwrap())
        .collect();
    for h in spacing {
        assert!((h - 5e-7).abs() < 1e-21, "{h}");
    }
    let summary: serde_json::Value = serde_json::from_str(&read("summary.json")).unwrap();
    assert_eq!(summary["rve"]["layer_thickness"], 0.5);
    // rve_grains.csv in areas: pixels × 0.25 µm², against π a1 a2 of grains.csv.
    // The semi-axes by their column names (a 2D table has no z, a3).
    let table = read("grains.csv");
    let header: Vec<&str> = table.lines().next().unwrap().split(',').collect();
    let [a1, a2] = ["a1", "a2"].map(|c| header.iter().position(|h| *h == c).unwrap());
    let grains: Vec<Vec<f64>> = table
        .lines()
        .skip(1)
        .map(|l| l.split(',').map(|v| v.parse().unwrap()).collect())
        .collect();
    let mut pixels = 0.0;
    for (row, g) in read("rve_grains.csv").lines().skip(1).zip(&grains) {
        let f: Vec<f64> = row.split(',').map(|v| v.parse().unwrap()).collect();
        assert_eq!(f[3], f[2] * 0.25, "{row}");
        let area = std::f64::consts::PI * g[a1] * g[a2];
        // Written to 10 significant digits.
        assert!((f[4] / area - 1.0).abs() < 1e-9, "{row}: not {area}");
        // A coarse pixel image: each area within a pixel or two per unit of perimeter.
        assert!((f[3] / area - 1.0).abs() < 0.15, "{row}");
        pixels += f[2];
    }
    let matrix = summary["rve"]["matrix_fraction"].as_f64().unwrap();
    assert!(((pixels + matrix * 960.0) - 960.0).abs() < 1e-9);
    let deck = read("rve.inp");
    let lines: Vec<&str> = deck.lines().collect();
    assert_eq!(block(&lines, "*Element, type=CPE4").len(), 960);
    assert!(read("load.yaml").contains("[0, 0, 0]]"));
}
