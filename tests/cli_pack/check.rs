//! Everything a written packing must satisfy, checked from its files alone.

use super::*;

pub(super) fn read_summary(path: &Path) -> Value {
    serde_json::from_str(&std::fs::read_to_string(path).unwrap()).unwrap()
}

pub(super) fn number(v: &Value) -> f64 {
    v.as_f64().unwrap_or_else(|| panic!("not a number: {v}"))
}

/// Everything a written packing must satisfy, checked from the files alone. Returns
/// the grains and the summary for further checks.
pub(super) fn check_written_packing(out: &Path, periodic: bool) -> (Vec<Grain>, Value) {
    // What every scene here writes, and what a scene may add; nothing else (no
    // temporary files left behind).
    let files = files_in(out);
    let always = [
        "centers.vtp",
        "grains.csv",
        "grains.vtu",
        "statistics.png",
        "summary.json",
    ];
    let optional = ["rve.vti", "rve_grains.csv", "sections.png"];
    for f in always {
        assert!(files.iter().any(|g| g == f), "{f} missing: {files:?}");
    }
    for f in &files {
        assert!(
            always.contains(&f.as_str()) || optional.contains(&f.as_str()),
            "stray file {f}"
        );
    }
    let grains = read_grains(&out.join("grains.csv"));
    let summary = read_summary(&out.join("summary.json"));
    let size: Vec<f64> = summary["box"]
        .as_array()
        .unwrap()
        .iter()
        .map(number)
        .collect();
    let size = [size[0], size[1], size[2]];
    assert_eq!(
        summary["boundary"],
        if periodic { "periodic" } else { "reflecting" }
    );

    // Ids in order, semi-axes positive, spheroids (a2 = a3, scaled alike).
    for (index, g) in grains.iter().enumerate() {
        assert_eq!(g.id, index);
        assert!(g.semi_axes.iter().all(|&a| a > 0.0), "{g:?}");
        assert_eq!(g.semi_axes[1], g.semi_axes[2], "{g:?}");
        assert!(g.rotation.determinant() > 0.0);
    }

    // Containment: centres in [0, L) when periodic, whole grains inside the walls.
    for g in &grains {
        for (k, &l) in size.iter().enumerate() {
            if periodic {
                assert!((0.0..l).contains(&g.centre[k]), "{g:?}");
            } else {
                let w = extent(g, k);
                assert!(
                    g.centre[k] - w >= 0.0 && g.centre[k] + w <= l,
                    "grain {} crosses a wall along axis {k}",
                    g.id
                );
            }
        }
    }

    // No overlap, by the independent check; and the summary's figures agree with it.
    let check = check_overlaps(&grains, size, periodic);
    assert_eq!(check.overlapping_pairs, 0, "{check:?}");
    assert_eq!(summary["overlapping_pairs"], 0);
    assert_eq!(summary["wall_violations"], 0);
    assert_eq!(
        summary["checked_pairs"].as_u64().unwrap() as usize,
        check.candidate_pairs,
        "{check:?}"
    );
    if check.candidate_pairs > 0 {
        let reported = number(&summary["min_mu2"]);
        assert!(reported >= 1.0, "{reported}");
        // Our golden-section μ² and the loop's exact one: both within 1e-13 of the
        // truth (see support::packed::MU2_TOL); 1e-9 relative is generous.
        assert!(
            (reported - check.min_mu2).abs() <= 1e-9 * check.min_mu2,
            "summary {reported}, independent {}",
            check.min_mu2
        );
    } else {
        assert!(summary["min_mu2"].is_null());
    }

    // The summary describes these grains: count, fraction (a sum of the same 17-digit
    // values in another order: rounding of ~n ε ≈ 1e-14, so 1e-12 relative).
    assert_eq!(summary["grains"].as_u64().unwrap() as usize, grains.len());
    let volume: f64 = size.iter().product();
    let fraction = grains.iter().map(Grain::volume).sum::<f64>() / volume;
    let reported = number(&summary["packing_fraction"]);
    assert!(
        (reported - fraction).abs() <= 1e-12 * fraction,
        "{reported} vs {fraction}"
    );
    let phases = summary["phases"].as_array().unwrap();
    let per_phase: usize = phases
        .iter()
        .map(|p| p["grains"].as_u64().unwrap() as usize)
        .sum();
    assert_eq!(per_phase, grains.len());
    for (index, p) in phases.iter().enumerate() {
        let mine: Vec<&Grain> = grains.iter().filter(|g| g.phase == index).collect();
        assert_eq!(p["grains"].as_u64().unwrap() as usize, mine.len());
        if mine.is_empty() {
            continue;
        }
        // Achieved mean diameter and aspect ratio, recomputed: sums of n ≤ 60 terms,
        // 1e-12 relative.
        let n = mine.len() as f64;
        let d = mine
            .iter()
            .map(|g| 2.0 * g.semi_axes.iter().product::<f64>().cbrt())
            .sum::<f64>()
            / n;
        let got = number(&p["diameter"]["achieved"]["mean"]);
        assert!((got - d).abs() <= 1e-12 * d, "{got} vs {d}");
        let alpha = mine
            .iter()
            .map(|g| g.semi_axes[0] / g.semi_axes[1])
            .sum::<f64>()
            / n;
        let got = number(&p["aspect_ratio"]["achieved"]["mean"]);
        assert!((got - alpha).abs() <= 1e-12 * alpha, "{got} vs {alpha}");
        for q in ["diameter", "aspect_ratio"] {
            let ks = number(&p[q]["ks_distance"]);
            assert!((0.0..=1.0).contains(&ks), "{q}: {ks}");
        }
    }
    let version = summary["version"].as_str().unwrap();
    assert_eq!(version, env!("CARGO_PKG_VERSION"));
    for key in [
        "broad_phase",
        "narrow_phase",
        "response",
        "packing",
        "outputs",
        "total",
    ] {
        assert!(number(&summary["timings"][key]) >= 0.0, "{key}");
    }
    let timings = &summary["timings"];
    assert!(
        number(&timings["total"]) >= number(&timings["packing"]) + number(&timings["outputs"]),
        "{timings}"
    );
    let rotation = &summary["rotation"];
    let (median, largest) = (
        number(&rotation["median_turn_deg"]),
        number(&rotation["largest_turn_deg"]),
    );
    assert!(median >= 0.0 && median <= largest, "{rotation}");
    // The limit holds up to rounding.
    assert!(
        largest <= number(&rotation["max_turn_deg"]) * (1.0 + 1e-12),
        "{rotation}"
    );
    if rotation["mode"] == "none" {
        assert_eq!(largest, 0.0, "{rotation}");
    }
    for key in [
        "steps",
        "fire_steps",
        "list_builds",
        "pairs_tested",
        "swaps",
    ] {
        assert!(summary["counters"][key].is_u64(), "{key}");
    }
    (grains, summary)
}

/// Runs a scene that must reach its target, checks it, and returns grains.csv's text.
pub(super) fn pack_and_check(name: &str, text: &str, periodic: bool, extra: &[&str]) -> String {
    let dir = scratch(name);
    let (run, out) = run_scene(&dir, text, extra);
    assert_eq!(run.status.code(), Some(0), "{}", stderr(&run));
    let (_, summary) = check_written_packing(&out, periodic);
    assert_eq!(summary["stop_reason"], "target_reached");
    assert!((number(&summary["scale"]) - 1.0).abs() < 1e-6);
    eprintln!(
        "{name}: {} grains at {:.4}, {:.3} s in the loop, {:.3} s in all",
        summary["grains"],
        number(&summary["packing_fraction"]),
        number(&summary["timings"]["packing"]),
        number(&summary["timings"]["total"]),
    );
    std::fs::read_to_string(out.join("grains.csv")).unwrap()
}

// ---------------------------------------------------------------------------------
// Packings.
