//! Voxelises kanapy's scene (about 1000 elongated grains in a periodic 92³ box) at 69³
//! and 256³ cells, both fills, and times each step.
//!
//! `VOXEL_BENCH_GRAINS=path/to/grains.csv cargo bench --bench voxel` takes the grains of
//! an earlier `pack configs/kanapy_elongated.toml` run; without it the scene is packed
//! first (about 90 s). The box and the phases come from the scene file either way.
//! Prints the table and rewrites the `voxel-bench` section of `BENCHMARKS.md`
//! (`VOXEL_BENCH_DRY=1`: print only). `VOXEL_BENCH_OUT=dir` also writes
//! `rve_<cells>_<fill>.vti` and `sections_<cells>_<fill>.png` there, to look at.

mod common;

use grainpack::io::voxel::{grain_report, voxelise, write_sections_png, write_vti};
use grainpack::packing::PackedGrain;
use grainpack::scene::Scene;
use grainpack::scene::{LengthUnit, RveFill};
use std::time::Instant;

const SCENE: &str = "configs/kanapy_elongated.toml";

/// Repetitions of each timing; the median is reported.
const REPEATS: usize = 5;

fn main() {
    let root = env!("CARGO_MANIFEST_DIR");
    let scene = Scene::from_path(format!("{root}/{SCENE}").as_ref()).unwrap();
    let (grains, source) = match std::env::var("VOXEL_BENCH_GRAINS") {
        Ok(path) => (
            read_grains(&path),
            "grains.csv of an earlier run".to_string(),
        ),
        Err(_) => (
            common::pack_scene(&scene).0.grains,
            "packed here".to_string(),
        ),
    };
    let phases = scene.phases.len();
    let threads = rayon::current_num_threads();
    let mut report = format!(
        "Machine: {}; {threads} threads.\n\n`cargo bench --bench voxel` on {SCENE} ({} grains, {source}, packing fraction {:.3}), box {:?}, {}; median of {REPEATS}. Split grains: grains in more than one 6-connected piece; stray voxels: voxels outside their grain's largest piece.\n\n",
        common::machine(),
        grains.len(),
        fraction(&grains, scene.domain.volume()),
        scene.domain.size,
        if scene.domain.boundary == grainpack::scene::Boundary::Periodic { "periodic" } else { "reflecting" },
    );
    report.push_str("| cells | fill | voxelise (s) | write_vti (s) | .vti size (MB) | grain_report (s) | matrix fraction | max / mean \\|volume deviation\\| | split grains | stray voxels | empty grains |\n");
    report.push_str("|---|---|---:|---:|---:|---:|---:|---|---:|---:|---:|\n");
    for n in [69, 256] {
        for fill in [RveFill::Matrix, RveFill::Grains] {
            let cells = [n; 3];
            let t_vox = median(|| {
                voxelise(&grains, &scene.domain, cells, fill, phases).unwrap();
            });
            let grid = voxelise(&grains, &scene.domain, cells, fill, phases).unwrap();
            let mut bytes = Vec::new();
            let t_vti = median(|| {
                bytes.clear();
                write_vti(&grid, LengthUnit::Micrometre, None, &mut bytes).unwrap();
            });
            if let Ok(dir) = std::env::var("VOXEL_BENCH_OUT") {
                let name = format!("{n}_{fill:?}").to_lowercase();
                std::fs::write(format!("{dir}/rve_{name}.vti"), &bytes).unwrap();
                let png = std::path::PathBuf::from(format!("{dir}/sections_{name}.png"));
                write_sections_png(&grid, &png).unwrap();
            }
            let mut report_out = None;
            let t_rep = median(|| report_out = Some(grain_report(&grid, &grains).unwrap()));
            let r = report_out.unwrap();
            let line = format!(
                "| {n}³ | {fill:?} | {t_vox:.3} | {t_vti:.3} | {:.1} | {t_rep:.3} | {:.4} | {:.3} / {:.3} | {} | {} | {} |\n",
                bytes.len() as f64 / 1e6,
                r.matrix_fraction,
                r.max_abs_volume_deviation,
                r.mean_abs_volume_deviation,
                r.split_grains.len(),
                r.stray_voxels,
                r.empty_grains.len(),
            );
            print!("{line}");
            report.push_str(&line);
        }
    }
    print!("\n{report}");
    if std::env::var_os("VOXEL_BENCH_DRY").is_none() {
        common::update_section(&format!("{root}/BENCHMARKS.md"), "voxel-bench", &report);
    }
}

/// Total ellipsoid volume over the box volume.
fn fraction(grains: &[PackedGrain], box_volume: f64) -> f64 {
    let v: f64 = grains
        .iter()
        .map(|g| 4.0 / 3.0 * std::f64::consts::PI * g.semi_axes.iter().product::<f64>())
        .sum();
    v / box_volume
}

/// Median wall time of [`REPEATS`] runs of `f`, in seconds.
fn median(mut f: impl FnMut()) -> f64 {
    let mut times: Vec<f64> = (0..REPEATS)
        .map(|_| {
            let t = Instant::now();
            f();
            t.elapsed().as_secs_f64()
        })
        .collect();
    times.sort_by(f64::total_cmp);
    times[REPEATS / 2]
}

/// `grains.csv` as `pack` writes it: id, phase, centre, semi-axes, quaternion.
fn read_grains(path: &str) -> Vec<PackedGrain> {
    let mut reader = csv::Reader::from_path(path).unwrap();
    reader
        .records()
        .map(|r| {
            let r = r.unwrap();
            let f = |k: usize| r[k].parse::<f64>().unwrap();
            PackedGrain {
                id: r[0].parse().unwrap(),
                phase: r[1].parse().unwrap(),
                centre: [f(2), f(3), f(4)],
                semi_axes: [f(5), f(6), f(7)],
                quaternion: [f(8), f(9), f(10), f(11)],
            }
        })
        .collect()
}
