//! Packs scenes and reports time, density and the verification; then the scaling of
//! kanapy's scene from 10³ to 10⁵ grains (time and peak memory).
//!
//! `cargo bench --bench packing` prints both tables and rewrites the packing sections
//! of `BENCHMARKS.md` (`PACKING_BENCH_DRY=1`: print only; `PACKING_BENCH_MAX=N`: the
//! scaling stops at N grains, default 100 000).

mod common;

use grainpack::packing::sorted_turns;
use grainpack::scene::{GrainCount, Rotation, Scene};
use std::fmt::Write as _;

/// The scaling runs kanapy's grains at this packing fraction (the 10⁵ goal).
const SCALING_FRACTION: f64 = 0.60;

fn main() {
    let dry = std::env::var_os("PACKING_BENCH_DRY").is_some();
    let max: usize = std::env::var("PACKING_BENCH_MAX")
        .ok()
        .and_then(|v| v.parse().ok())
        .unwrap_or(100_000);
    let root = env!("CARGO_MANIFEST_DIR");
    let threads = rayon::current_num_threads();

    let mut report = format!("Machine: {}; {threads} threads.\n\n", common::machine());
    report.push_str("| scene | rotation | max turn (°) | grains | time (s) | fraction | target | stop | median / max turn (°) | relaxations | FIRE steps | pairs tested | overlapping | min μ² | broad / narrow / response (s) |\n");
    report.push_str("|---|---|---:|---:|---:|---:|---:|---|---|---:|---:|---:|---:|---:|---|\n");
    // (scene, override of packing.rotation and max_turn in degrees)
    let scenes = [
        ("configs/grains.toml", None),
        (
            "configs/kanapy_elongated.toml",
            Some((Rotation::None, 180.0)),
        ),
        (
            "configs/kanapy_elongated.toml",
            Some((Rotation::Axis, 20.0)),
        ),
        ("configs/kanapy_elongated.toml", None),
        (
            "configs/kanapy_elongated.toml",
            Some((Rotation::Free, 180.0)),
        ),
        ("configs/density_spheres.toml", None),
        (
            "configs/density_spheroids.toml",
            Some((Rotation::None, 180.0)),
        ),
        ("configs/density_spheroids.toml", None),
    ];
    for (path, rotation) in scenes {
        let mut scene = Scene::from_path(format!("{root}/{path}").as_ref()).unwrap();
        if let Some((r, max_turn)) = rotation {
            scene.packing.rotation = r;
            scene.packing.max_turn = f64::to_radians(max_turn);
        }
        let (p, specs, secs) = common::pack_scene(&scene);
        let turns = sorted_turns(&specs, &p.grains);
        writeln!(
            report,
            "| {path} | {} | {:.0} | {} | {secs:.2} | {:.4} | {:.4} | {} | {:.1} / {:.1} | {} | {} | {} | {} | {:.6} | {:.2} / {:.2} / {:.2} |",
            scene.packing.rotation.name(),
            scene.packing.max_turn.to_degrees(),
            specs.len(),
            p.fraction,
            scene.expected_fraction(),
            p.stop,
            turns[turns.len() / 2].to_degrees(),
            turns[turns.len() - 1].to_degrees(),
            p.counters.steps,
            p.counters.fire_steps,
            p.counters.pairs_tested,
            p.verification.overlapping_pairs,
            p.verification.min_mu2,
            p.counters.broad_phase.as_secs_f64(),
            p.counters.narrow_phase.as_secs_f64(),
            p.counters.response.as_secs_f64()
        )
        .unwrap();
        print!(
            "{}",
            report.lines().last().unwrap_or_default().to_owned() + "\n"
        );
    }
    print!("{report}");
    if !dry {
        common::update_section(&format!("{root}/BENCHMARKS.md"), "packing-bench", &report);
    }

    // Scaling: kanapy's grain laws in a box holding N grains at 0.60. Sizes run in
    // increasing order, so the process's peak resident memory after each run is that
    // run's peak.
    let mut scaling = format!("Machine: {}; {threads} threads.\n\n", common::machine());
    scaling.push_str("| grains | box side | time (s) | ms per 1000 grains per FIRE step | fraction | stop | FIRE steps | pairs tested | overlapping | peak memory (MB) |\n");
    scaling.push_str("|---:|---:|---:|---:|---:|---|---:|---:|---:|---:|\n");
    let base = Scene::from_path(format!("{root}/configs/kanapy_elongated.toml").as_ref()).unwrap();
    let base_grains = base.sample_grains(&mut base.rng()).unwrap().len() as f64;
    let base_side = base.domain.size[0];
    let GrainCount::Fraction(base_fraction) = base.count else {
        panic!("kanapy's scene gives a target fraction");
    };
    for n in [1_000usize, 3_000, 10_000, 30_000, 100_000] {
        if n > max {
            break;
        }
        let mut scene = base.clone();
        // Grains ∝ volume × fraction.
        let side = base_side * (n as f64 / base_grains * base_fraction / SCALING_FRACTION).cbrt();
        scene.domain.size = [side; 3];
        scene.count = GrainCount::Fraction(SCALING_FRACTION);
        let (p, specs, secs) = common::pack_scene(&scene);
        let grains = specs.len();
        let per_step = 1e3 * secs / p.counters.fire_steps.max(1) as f64 / (grains as f64 / 1000.0);
        writeln!(
            scaling,
            "| {grains} | {side:.1} | {secs:.2} | {per_step:.2} | {:.4} | {} | {} | {} | {} | {:.0} |",
            p.fraction,
            p.stop,
            p.counters.fire_steps,
            p.counters.pairs_tested,
            p.verification.overlapping_pairs,
            peak_memory_mb(),
        )
        .unwrap();
        print!(
            "{}",
            scaling.lines().last().unwrap_or_default().to_owned() + "\n"
        );
    }
    print!("{scaling}");
    if !dry {
        common::update_section(
            &format!("{root}/BENCHMARKS.md"),
            "packing-scaling",
            &scaling,
        );
    }
}

/// The process's peak resident memory (`VmHWM`), in MB; 0 where /proc is missing.
fn peak_memory_mb() -> f64 {
    std::fs::read_to_string("/proc/self/status")
        .ok()
        .and_then(|s| {
            s.lines()
                .find(|l| l.starts_with("VmHWM:"))
                .and_then(|l| l.split_whitespace().nth(1)?.parse::<f64>().ok())
        })
        .map_or(0.0, |kb| kb / 1024.0)
}
