//! `packing.gap` end to end: the packing keeps it, by an independent brute-force check
//! over every pair and its periodic images (nalgebra and a golden-section search,
//! nothing of grainpack's contact module or octree); it keeps it from the walls; the
//! summary reports it; bad values are refused; and the loop packs exactly as it packs
//! the grains inflated by `1 + gap`.

mod support;

use grainpack::packing::{pack, Job, Packing, Tuning};
use grainpack::run::Drawn;
use grainpack::scene::{GrainSpec, Scene};
use nalgebra::Vector3;
use serde_json::Value;
use std::path::Path;
use std::sync::atomic::AtomicBool;
use support::files::{files_in, pack_in};
use support::packed::{contact_mu2, extent, read_grains, Grain, MU2_TOL};
use support::scene::{assert_starts, scene_error};

/// About 380 spheres of lognormal sizes at 0.45 of a periodic cube, kept 0.1 of each
/// pair's size apart: as grains, the loop packs them at 0.45 · 1.1³ = 0.60, below
/// random close packing, so the target is reached.
const SPHERES: &str = r#"
seed = 3
target_fraction = 0.45
[box]
size = [24.0, 24.0, 24.0]
[[phase]]
size = { distribution = "lognormal", sigma = 0.2, scale = 3.0, min = 2.0, max = 5.0 }
[packing]
gap = 0.1
[output]
vtk = false
centers = false
statistics_png = false
"#;

/// 60 platelets aligned with an oblique axis between walls, about 0.3 full, kept 0.15
/// of each pair's size apart and from the walls.
const PLATELETS: &str = r#"
seed = 11
grains = 60
[box]
size = [30.0, 26.0, 24.0]
boundary = "reflecting"
[[phase]]
size = { distribution = "lognormal", sigma = 0.25, scale = 6.0, min = 4.0, max = 8.0 }
aspect_ratio = { distribution = "uniform", min = 0.5, max = 0.9 }
orientation = { kind = "aligned", axis = [1.0, 1.0, 1.0] }
[packing]
gap = 0.15
[output]
vtk = false
centers = false
statistics_png = false
"#;

/// A fresh, empty directory for one test.
fn scratch(name: &str) -> std::path::PathBuf {
    support::files::scratch("gap", name)
}

/// Packs `text` in `dir` (exit code 0 expected) and reads back the summary and grains.
fn pack_scene(dir: &Path, text: &str) -> (Value, Vec<Grain>) {
    std::fs::write(dir.join("scene.toml"), text).unwrap();
    let run = pack_in(dir, &["scene.toml", "--out", "out", "--quiet"]);
    assert_eq!(
        run.status.code(),
        Some(0),
        "{}",
        String::from_utf8_lossy(&run.stderr)
    );
    let summary = std::fs::read_to_string(dir.join("out/summary.json")).unwrap();
    let summary: Value = serde_json::from_str(&summary).unwrap();
    (summary, read_grains(&dir.join("out/grains.csv")))
}

fn number(v: &Value) -> f64 {
    v.as_f64().unwrap_or_else(|| panic!("not a number: {v}"))
}

/// The 27 shifts of a periodic box: every image a pair can meet at, tried by brute force.
fn images(size: [f64; 3]) -> Vec<Vector3<f64>> {
    let mut shifts = Vec::with_capacity(27);
    for i in -1..=1 {
        for j in -1..=1 {
            for k in -1..=1 {
                let n = [i, j, k].map(f64::from);
                shifts.push(Vector3::new(n[0] * size[0], n[1] * size[1], n[2] * size[2]));
            }
        }
    }
    shifts
}

/// The least gap `d / (r1 + r2) − 1` over every pair of spheres and every grain with its
/// own images, at every image; `each` sees every pair with its distance `d` and
/// `r1 + r2`.
fn least_sphere_gap(
    grains: &[Grain],
    size: [f64; 3],
    mut each: impl FnMut(&Grain, &Grain, f64, f64),
) -> f64 {
    let mut least = f64::INFINITY;
    for (i, gi) in grains.iter().enumerate() {
        assert!(gi.semi_axes.iter().all(|&a| a == gi.semi_axes[0]));
        for gj in &grains[i..] {
            let reach = gi.semi_axes[0] + gj.semi_axes[0];
            for shift in images(size) {
                if gi.id == gj.id && shift == Vector3::zeros() {
                    continue;
                }
                let d = (gj.centre + shift - gi.centre).norm();
                each(gi, gj, d, reach);
                least = least.min(d / reach - 1.0);
            }
        }
    }
    least
}

/// Spheres: every pair (and every grain with its own images), at every image, has its
/// centres at least `(1 + g)(r1 + r2)` apart: the gap, directly, with no contact
/// function. The loop keeps 1e-9 more (`ProtocolParams::contact_gap`), a million times
/// the rounding of a distance, so the comparison needs no tolerance.
#[test]
fn spheres_keep_the_gap_between_every_pair_and_image() {
    let dir = scratch("spheres");
    let (summary, grains) = pack_scene(&dir, SPHERES);
    let gap = 0.1;
    let size = [24.0; 3];
    assert!(grains.len() > 350, "{}", grains.len());
    let least = least_sphere_gap(&grains, size, |gi, gj, d, reach| {
        assert!(
            d >= (1.0 + gap) * reach,
            "{} and {}: {d} < {}",
            gi.id,
            gj.id,
            (1.0 + gap) * reach
        );
    });
    // The gap binds: the loop stops as soon as the inflated grains are apart, so some
    // pairs sit at it (within the loop's margin of 1e-3, at which it takes the forces).
    assert!(least < gap + 2e-3, "least gap {least}");
    assert_eq!(number(&summary["gap"]), gap);
    // The summary's smallest gap is the brute force's: the exact contact function is
    // accurate to 1e-13 on spheres, and 1e-9 is the precision of the comparison.
    let reported = number(&summary["min_gap"]);
    assert!((reported - least).abs() < 1e-9, "{reported} vs {least}");
    // Every fraction is of the grains themselves, not inflated.
    let volume: f64 = grains.iter().map(Grain::volume).sum::<f64>() / 24f64.powi(3);
    let packed = number(&summary["packing_fraction"]);
    assert!(
        (packed - volume).abs() <= 1e-12 * volume,
        "{packed} vs {volume}"
    );
    assert_eq!(summary["stop_reason"], "target_reached");
    assert!((packed - 0.45).abs() < 0.01, "{packed}");
}

/// Ellipsoids between walls: every pair has μ² ≥ (1 + g)², by the golden-section
/// contact function (relative error below 1e-13, so `MU2_TOL` = 1e-10 is a wide
/// margin), and every grain scaled by 1 + g about its centre is inside the walls.
#[test]
fn ellipsoids_keep_the_gap_between_pairs_and_from_the_walls() {
    let dir = scratch("platelets");
    let (summary, grains) = pack_scene(&dir, PLATELETS);
    let gap = 0.15;
    let size = [30.0, 26.0, 24.0];
    let mut least_pair = f64::INFINITY;
    for (i, gi) in grains.iter().enumerate() {
        for gj in &grains[i + 1..] {
            let r = gj.centre - gi.centre;
            let mu2 = contact_mu2(&r, &gi.q, &gj.q);
            assert!(
                mu2 >= (1.0 + gap) * (1.0 + gap) * (1.0 - MU2_TOL),
                "{} and {}: μ² = {mu2}",
                gi.id,
                gj.id
            );
            least_pair = least_pair.min(mu2.sqrt() - 1.0);
        }
    }
    // The walls: the extent √Q_kk scaled by 1 + g, exactly as the gap's definition
    // reads. The loop keeps 8 ε more than that (its wall margin), and nalgebra's Q
    // agrees with grainpack's to a few ε, so no tolerance is needed.
    let mut least_wall = f64::INFINITY;
    for g in &grains {
        for (k, &l) in size.iter().enumerate() {
            let w = extent(g, k);
            let reach = (1.0 + gap) * w;
            assert!(
                g.centre[k] - reach >= 0.0 && g.centre[k] + reach <= l,
                "{g:?} along {k}"
            );
            least_wall = least_wall.min(g.centre[k].min(l - g.centre[k]) / w - 1.0);
        }
    }
    // Both bind: grains start anywhere in the box and are pushed only as far as the gap
    // (and the loop's margin of 1e-3 beyond it, at which it takes the forces).
    assert!(least_pair < gap + 2e-3, "least pair gap {least_pair}");
    assert!(least_wall < gap + 2e-3, "least wall gap {least_wall}");
    let reported = number(&summary["min_gap"]);
    let least = least_pair.min(least_wall);
    assert!((reported - least).abs() < 1e-9, "{reported} vs {least}");
}

/// Without the gap the spheres' scene ends with pairs far closer than 0.1: the tests
/// above would see a loop that ignored it.
#[test]
fn without_the_gap_pairs_come_closer_than_it() {
    let dir = scratch("no-gap");
    let text = SPHERES.replace("gap = 0.1", "gap = 0");
    let (summary, grains) = pack_scene(&dir, &text);
    assert_eq!(number(&summary["gap"]), 0.0);
    let least = least_sphere_gap(&grains, [24.0; 3], |_, _, _, _| {});
    assert!((0.0..0.01).contains(&least), "{least}");
}

/// The drawn grains of `text` and their packing with the scene's parameters.
fn pack_drawn(scene: &Scene, specs: &[GrainSpec]) -> Packing {
    let job = Job {
        specs,
        domain: &scene.domain,
        params: &scene.packing,
        tuning: &Tuning::default(),
        seed: scene.seed,
    };
    pack(&job, &AtomicBool::new(false), &mut |_| {}).unwrap()
}

/// The loop has no path of its own for the gap: packing with gap g is packing the
/// grains inflated by 1 + g, step for step (the same scale, centres and FIRE steps, bit
/// for bit), down to a jammed state; only the grains written and the fraction are the
/// grains' own, and the check is of the gap.
#[test]
fn a_gap_packs_exactly_as_the_grains_inflated_by_it() {
    // 150 spheroids of aspect 1.5 asked for 0.6 with the gap 0.05: as grains, 0.69,
    // beyond what they reach, so the loop bisects to their jamming point.
    let text = r#"
        seed = 9
        grains = 150
        [box]
        size = [9.35, 9.35, 9.35]
        [[phase]]
        size = { distribution = "constant", value = 1.83 }
        aspect_ratio = { distribution = "constant", value = 1.5 }
        [packing]
        gap = 0.05
    "#;
    let gap = 0.05;
    let scene = Scene::from_str(text, "gap.toml").unwrap();
    let specs = scene.sample_grains(&mut scene.rng()).unwrap();
    let with_gap = pack_drawn(&scene, &specs);
    let mut plain = scene.clone();
    plain.packing.gap = 0.0;
    let inflated: Vec<GrainSpec> = (specs.iter())
        .map(|s| GrainSpec {
            semi_axes: s.semi_axes.map(|a| a * (1.0 + gap)),
            ..*s
        })
        .collect();
    let big = pack_drawn(&plain, &inflated);
    assert!(!with_gap.stop.is_success());
    assert_eq!((with_gap.scale, with_gap.stop), (big.scale, big.stop));
    assert_eq!(with_gap.counters.fire_steps, big.counters.fire_steps);
    for ((g, b), s) in with_gap.grains.iter().zip(&big.grains).zip(&specs) {
        assert_eq!((g.centre, g.quaternion), (b.centre, b.quaternion));
        assert_eq!(g.semi_axes, s.semi_axes.map(|a| a * with_gap.scale));
    }
    // Volumes scale by (1 + g)³; 1e-12 covers the roundings of the two sums.
    let ratio = big.fraction / with_gap.fraction;
    assert!((ratio - (1.0 + gap).powi(3)).abs() < 1e-12, "{ratio}");
    let v = &with_gap.verification;
    assert!(v.is_clean() && v.gap == gap && v.min_gap >= gap, "{v:?}");
    // The inflated grains just touch where the real ones keep the gap.
    assert!(v.min_gap < gap + 1e-3, "{v:?}");
}

/// The reachable estimate is the inflated grains': the gap-0 estimate over (1 + g)³.
/// Spheres asked for 0.55 are below it without a gap (0.655) and above it with 0.1, so
/// only then is the target called unreachable before packing.
#[test]
fn the_reachable_estimate_and_its_warning_account_for_the_gap() {
    let text = SPHERES.replace("target_fraction = 0.45", "target_fraction = 0.55");
    let with_gap = Scene::from_str(&text, "gap.toml").unwrap();
    let mut plain = with_gap.clone();
    plain.packing.gap = 0.0;
    let specs = with_gap.sample_grains(&mut with_gap.rng()).unwrap();
    let (a, b) = (Drawn::of(&with_gap, &specs), Drawn::of(&plain, &specs));
    // One division by 1.1³ (itself rounded): 1e-15 covers both roundings.
    let ratio = b.reachable_fraction / a.reachable_fraction;
    assert!((ratio - 1.1f64.powi(3)).abs() < 1e-15, "{ratio}");
    assert_eq!((a.gap, a.drawn_fraction), (0.1, b.drawn_fraction));
    assert!(a.above_reachable() && !b.above_reachable(), "{a:?} {b:?}");
}

#[test]
fn bad_gaps_are_refused_with_the_key_and_value() {
    let with = |gap: &str| SPHERES.replace("gap = 0.1", &format!("gap = {gap}"));
    for (gap, reason) in [
        ("-0.1", "must be a finite number, at least 0"),
        ("nan", "must be a finite number, at least 0"),
        ("inf", "must be a finite number, at least 0"),
    ] {
        assert_starts(
            &scene_error(&with(gap)),
            &format!("scene.toml:9:7: packing.gap = {gap}: {reason}"),
        );
    }
    // 0.45 · 1.3³ = 0.99 of the box as grains: more than any packing holds.
    assert_starts(
        &scene_error(&with("0.3")),
        "scene.toml:9:7: packing.gap = 0.3: the grains inflated by 1 + gap would fill \
         0.989 of the box (the grains fill 0.450), beyond the densest packing of ellipsoids \
         (0.7707): the gap can be at most 0.1964 here",
    );
    // Needles of 16 end to end in a side of 20: 1 + gap = 1.3 makes them 20.8 long.
    let needles = r#"
seed = 1
grains = 5
[box]
size = [20.0, 20.0, 20.0]
[[phase]]
size = { distribution = "constant", value = 4.0 }
aspect_ratio = { distribution = "constant", value = 8.0 }
[packing]
gap = 0.3
"#;
    assert_starts(
        &scene_error(needles),
        "scene.toml:10:7: packing.gap = 0.3: the longest grain (16.0000 end to end) inflated by \
         1 + gap does not fit in the box, whose shortest side is 20: the gap must be below \
         0.2500 here",
    );
}

/// Bad input is exit code 2, names the file, key and value, and writes nothing.
#[test]
fn pack_refuses_a_bad_gap_and_writes_nothing() {
    let dir = scratch("bad");
    std::fs::write(
        dir.join("scene.toml"),
        SPHERES.replace("gap = 0.1", "gap = -1"),
    )
    .unwrap();
    let run = pack_in(&dir, &["scene.toml", "--out", "out", "--quiet"]);
    assert_eq!(run.status.code(), Some(2));
    let stderr = String::from_utf8_lossy(&run.stderr);
    assert!(
        stderr.contains("scene.toml:9:7: packing.gap = -1: must be a finite number"),
        "{stderr}"
    );
    assert_eq!(files_in(&dir), ["scene.toml"]);
}
