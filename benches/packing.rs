//! Packs scenes and reports time, density and the verification.
//!
//! `cargo bench --bench packing -- [SCENE.toml ...]` (default: the shipped configs)
//! prints a table and rewrites the packing section of `BENCHMARKS.md`
//! (`PACKING_BENCH_DRY=1`: print only).

#[path = "common/mod.rs"]
mod common;

use grainpack::io::scene::Scene;
use grainpack::packing::pack;
use std::fmt::Write as _;
use std::sync::atomic::AtomicBool;
use std::time::Instant;

fn main() {
    let args: Vec<String> = std::env::args()
        .skip(1)
        .filter(|a| !a.starts_with("--"))
        .collect();
    let scenes = if args.is_empty() {
        [
            "configs/grains.toml",
            "configs/kanapy_elongated.toml",
            "configs/density_spheres.toml",
            "configs/density_spheroids.toml",
        ]
        .map(String::from)
        .to_vec()
    } else {
        args
    };
    let mut report = format!("Machine: {}.\n\n", common::machine());
    report.push_str("| scene | grains | time (s) | fraction | target | stop | steps | sweeps | pairs tested | overlapping | min μ² | broad / narrow / response (s) |\n");
    report.push_str("|---|---:|---:|---:|---:|---|---:|---:|---:|---:|---:|---|\n");
    for path in scenes {
        let scene = Scene::from_path(path.as_ref()).unwrap();
        let specs = scene.sample_grains(&mut scene.rng()).unwrap();
        let t = Instant::now();
        let p = pack(
            &specs,
            &scene.domain,
            &scene.packing,
            scene.seed,
            &AtomicBool::new(false),
            &mut |_| {},
        )
        .unwrap();
        let secs = t.elapsed().as_secs_f64();
        writeln!(
            report,
            "| {path} | {} | {secs:.2} | {:.4} | {:.4} | {} | {} | {} | {} | {} | {:.6} | {:.2} / {:.2} / {:.2} |",
            specs.len(),
            p.fraction,
            scene.expected_fraction(),
            p.stop,
            p.counters.steps,
            p.counters.sweeps,
            p.counters.pairs_tested,
            p.verification.overlapping_pairs,
            p.verification.min_mu2,
            p.counters.broad_phase.as_secs_f64(),
            p.counters.narrow_phase.as_secs_f64(),
            p.counters.response.as_secs_f64()
        )
        .unwrap();
    }
    print!("{report}");
    if std::env::var_os("PACKING_BENCH_DRY").is_none() {
        let root = env!("CARGO_MANIFEST_DIR");
        common::update_section(&format!("{root}/BENCHMARKS.md"), "packing-bench", &report);
    }
}
