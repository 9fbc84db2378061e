//! A 2D pixel RVE and its solver files from ellipses placed by hand, with the library's
//! writers: `rve.vti` (one layer of cells along z), DAMASK's `material.yaml` and
//! `load.yaml`, and the plane-strain Abaqus/CalculiX deck `rve.inp`.
//!
//! ```sh
//! cargo run --release --example plane_rve -- OUT_DIR
//! ```
//!
//! Writes two sets, each with `grains.csv` and a `summary.json` holding the keys the
//! checks read (`box`, `units`, `phases`, `rve`), for `tools/ccx_solve.py --plane` and
//! `tools/check_damask.py`:
//! - `OUT_DIR/homogeneous`: six ellipses of two phases of one material (E = 210,
//!   ν = 0.3) filling a periodic 10 × 10 square, 32 × 32 pixels;
//! - `OUT_DIR/fibres`: glass fibres (E = 72, ν = 0.22, diameter 7) placed by random
//!   sequential addition in an epoxy matrix (E = 3.5, ν = 0.35), periodic 50 × 50 µm, fibre
//!   fraction [`FIBRE_FRACTION`], 64 × 64 pixels, moduli in GPa.

use grainpack::contact::{ellipse_quaternion, ellipse_semi_axes, Dimension};
use grainpack::io::decks::{write_abaqus_deck, write_load_yaml, write_material_yaml};
use grainpack::io::report::write_grains_csv;
use grainpack::io::voxel::{grain_report, voxelise, write_vti};
use grainpack::packing::PackedGrain;
use grainpack::scene::{rve_cells, Boundary, Domain, RveFill, Scene};
use rand::{Rng, SeedableRng};
use rand_chacha::ChaCha8Rng;
use std::fs::File;
use std::io::BufWriter;
use std::path::Path;

/// Fibre area fraction the random sequential addition stops at (its jamming limit for
/// discs is about 0.547).
const FIBRE_FRACTION: f64 = 0.45;

const HOMOGENEOUS: &str = r#"
grains = 6
[box]
size = [10.0, 10.0, 10.0]
[[phase]]
name = "a"
size = { distribution = "constant", value = 3.0 }
elastic = { E = 210.0, nu = 0.3 }
[[phase]]
name = "b"
size = { distribution = "constant", value = 3.0 }
elastic = { E = 210.0, nu = 0.3 }
"#;

const FIBRES: &str = r#"
grains = 1
[units]
stress = "GPa"
[box]
size = [50.0, 50.0, 50.0]
[[phase]]
name = "glass"
size = { distribution = "constant", value = 7.0 }
elastic = { E = 72.0, nu = 0.22 }
[matrix]
elastic = { E = 3.5, nu = 0.35 }
[output]
rve = true
rve_fill = "matrix"
"#;

fn main() -> Result<(), Box<dyn std::error::Error>> {
    let out = std::env::args().nth(1).ok_or("usage: plane_rve OUT_DIR")?;
    let out = Path::new(&out);
    let domain = Domain::plane([10.0, 10.0], Boundary::Periodic);
    let z = domain.plane_z();
    let ellipses = [
        ([2.0, 2.5], [1.8, 1.1], 0.3),
        ([7.0, 2.0], [2.0, 0.9], -0.8),
        ([5.0, 5.5], [1.5, 1.5], 0.0),
        ([1.5, 8.0], [2.2, 0.7], 1.2),
        ([8.5, 7.5], [1.4, 1.0], 2.0),
        ([4.5, 9.0], [1.2, 0.5], -0.2),
    ];
    let grains: Vec<PackedGrain> = ellipses
        .iter()
        .enumerate()
        .map(|(id, &([x, y], [a1, a2], theta))| PackedGrain {
            id: id as u32,
            phase: id % 2,
            centre: [x, y, z],
            semi_axes: ellipse_semi_axes(a1, a2),
            quaternion: ellipse_quaternion(theta),
        })
        .collect();
    let scene = Scene::from_str(HOMOGENEOUS, "homogeneous.toml")?;
    write_set(
        &out.join("homogeneous"),
        scene,
        domain,
        &grains,
        32,
        RveFill::Grains,
    )?;

    let domain = Domain::plane([50.0, 50.0], Boundary::Periodic);
    let fibres = random_discs(&domain, 3.5, FIBRE_FRACTION, 23);
    let scene = Scene::from_str(FIBRES, "fibres.toml")?;
    write_set(
        &out.join("fibres"),
        scene,
        domain,
        &fibres,
        64,
        RveFill::Matrix,
    )
}

/// Discs of radius `r` added at random where they overlap none already placed (nor its
/// periodic images), until their area fraction reaches `fraction`.
fn random_discs(domain: &Domain, r: f64, fraction: f64, seed: u64) -> Vec<PackedGrain> {
    let mut rng = ChaCha8Rng::seed_from_u64(seed);
    let [lx, ly, _] = domain.size;
    let mut out: Vec<PackedGrain> = Vec::new();
    while (out.len() as f64) * std::f64::consts::PI * r * r < fraction * lx * ly {
        let c = [rng.random_range(0.0..lx), rng.random_range(0.0..ly)];
        let clear = out.iter().all(|g| {
            let dx = g.centre[0] - c[0];
            let dy = g.centre[1] - c[1];
            let (dx, dy) = (dx - lx * (dx / lx).round(), dy - ly * (dy / ly).round());
            dx * dx + dy * dy > 4.0 * r * r
        });
        if clear {
            out.push(PackedGrain {
                id: out.len() as u32,
                phase: 0,
                centre: [c[0], c[1], domain.plane_z()],
                semi_axes: ellipse_semi_axes(r, r),
                quaternion: ellipse_quaternion(0.0),
            });
        }
    }
    out
}

/// The RVE of `grains` in `domain` (`longest` pixels along its longer side) and its
/// solver files, in `dir`.
fn write_set(
    dir: &Path,
    mut scene: Scene,
    domain: Domain,
    grains: &[PackedGrain],
    longest: usize,
    fill: RveFill,
) -> Result<(), Box<dyn std::error::Error>> {
    std::fs::create_dir_all(dir)?;
    scene.domain = domain;
    let create = |name: &str| File::create(dir.join(name)).map(BufWriter::new);
    let phases = scene.phases.len();
    let grid = voxelise(grains, &domain, rve_cells(longest, &domain), fill, phases)?;
    let crystals = vec![[1.0, 0.0, 0.0, 0.0]; grains.len()];
    write_grains_csv(&mut create("grains.csv")?, grains, &crystals)?;
    write_vti(
        &grid,
        scene.units.length,
        Some(&crystals),
        &mut create("rve.vti")?,
    )?;
    let material = &mut create("material.yaml")?;
    write_material_yaml(material, &scene, grains, &crystals, &grid)?;
    write_load_yaml(&mut create("load.yaml")?, &grid)?;
    write_abaqus_deck(&mut create("rve.inp")?, &scene, &grid)?;
    let report = grain_report(&grid, grains)?;
    let summary = serde_json::json!({
        "box": domain.size,
        "dimension": Dimension::Two.exponent(),
        "units": {
            "length": scene.units.length.symbol(),
            "stress": scene.units.stress.symbol(),
        },
        "phases": scene.phases.iter().map(|p| serde_json::json!({"name": p.name})).collect::<Vec<_>>(),
        "rve": {
            "cells": grid.cells,
            "fill": fill,
            "materials": grains.len() + usize::from(fill == RveFill::Matrix),
            "matrix_fraction": report.matrix_fraction,
            "layer_thickness": grid.size[2],
        },
    });
    serde_json::to_writer_pretty(create("summary.json")?, &summary)?;
    println!(
        "{}: {} grains, {:?} pixels, matrix fraction {:.4}",
        dir.display(),
        grains.len(),
        grid.cells,
        report.matrix_fraction
    );
    Ok(())
}
