//! What `pack` wrote, checked from the files alone: overlaps by an independent test,
//! the summary against the grains, statistics, determinism, outputs and interrupts.

use super::check::*;
use super::*;

#[test]
fn a_periodic_scene_packs_overlap_free_and_its_summary_agrees() {
    pack_and_check("periodic", PERIODIC, true, &[]);
}

#[test]
fn a_walled_scene_packs_overlap_free_inside_the_walls() {
    pack_and_check("reflecting", REFLECTING, false, &[]);
}

/// A box barely longer than a grain: pairs meet through several images, and the check
/// takes all 27.
#[test]
fn a_small_periodic_box_packs_overlap_free_through_its_images() {
    let text = r#"
seed = 3
grains = 8
[box]
size = [14.0, 14.0, 14.0]
[[phase]]
size = { distribution = "constant", value = 6.0 }
aspect_ratio = { distribution = "constant", value = 2.0 }
"#;
    pack_and_check("small-box", text, true, &[]);
}

#[test]
fn the_summary_reports_the_tilt_angle_recovered_from_the_quaternions() {
    let dir = scratch("tilt");
    let (run, out) = run_scene(&dir, PERIODIC, &[]);
    assert_eq!(run.status.code(), Some(0), "{}", stderr(&run));
    let grains = read_grains(&out.join("grains.csv"));
    let summary = read_summary(&out.join("summary.json"));
    let tilt = &summary["phases"][1]["tilt_angle_deg"];
    // The first axis (column 0 of R) is (cos θ, sin θ, 0), θ in [0°, 180°].
    let thetas: Vec<f64> = grains
        .iter()
        .filter(|g| g.phase == 1)
        .map(|g| {
            let e = g.rotation.column(0);
            assert!(e[2].abs() < 1e-15, "first axis off the x–y plane: {e:?}");
            e[1].atan2(e[0]).to_degrees()
        })
        .collect();
    assert!(thetas.iter().all(|t| (-1e-12..=180.0 + 1e-12).contains(t)));
    let mean = thetas.iter().sum::<f64>() / thetas.len() as f64;
    let got = number(&tilt["achieved"]["mean"]);
    assert!((got - mean).abs() < 1e-9, "{got} vs {mean}");
    // Von Mises κ = 1 about 90°, cut to [0°, 180°]: symmetric, so the mean is 90°.
    assert!((number(&tilt["target"]["mean"]) - 90.0).abs() < 1e-9);
    assert!(summary["phases"][0].get("tilt_angle_deg").is_none());
    // The constant aspect ratio is met exactly.
    assert_eq!(
        number(&summary["phases"][1]["aspect_ratio"]["ks_distance"]),
        0.0
    );
    // KS distance of the uniform aspect ratio on [1, 2], recomputed by hand.
    let mut alphas: Vec<f64> = grains
        .iter()
        .filter(|g| g.phase == 0)
        .map(|g| g.semi_axes[0] / g.semi_axes[1])
        .collect();
    alphas.sort_by(f64::total_cmp);
    let n = alphas.len() as f64;
    let ks = alphas
        .iter()
        .enumerate()
        .map(|(i, &a)| {
            let f = (a - 1.0).clamp(0.0, 1.0);
            ((i + 1) as f64 / n - f).max(f - i as f64 / n)
        })
        .fold(0.0, f64::max);
    let got = number(&summary["phases"][0]["aspect_ratio"]["ks_distance"]);
    assert!((got - ks).abs() < 1e-12, "{got} vs {ks}");
}

#[test]
fn the_same_seed_gives_the_same_packing_whatever_the_thread_count() {
    let one = pack_and_check("threads-1", PERIODIC, true, &["--threads", "1"]);
    let two = pack_and_check("threads-2", PERIODIC, true, &["--threads", "2"]);
    let again = pack_and_check("threads-2-again", PERIODIC, true, &["--threads", "2"]);
    assert!(one == two, "--threads 1 and --threads 2 differ");
    assert!(two == again, "two runs with the same seed differ");
    // Turning grains (and turning them back) too.
    let turning = PERIODIC.replace("[box]", "[packing]\nrotation = \"axis\"\n\n[box]");
    let one = pack_and_check("turning-1", &turning, true, &["--threads", "1"]);
    let two = pack_and_check("turning-2", &turning, true, &["--threads", "2"]);
    assert!(one == two, "turning: --threads 1 and --threads 2 differ");
}

/// Needles and platelets of 1:20 with sizes spread by 3:1, free to turn: overlap-free,
/// at the target, nothing non-finite (the CSV parser would reject NaN).
#[test]
fn needles_and_platelets_of_one_to_twenty_pack_overlap_free() {
    let scene = r#"
seed = 21
target_fraction = 0.1

[packing]
rotation = true

[box]
size = [60.0, 60.0, 60.0]

[[phase]]
name = "needles"
size = { distribution = "uniform", min = 2.0, max = 6.0 }
aspect_ratio = { distribution = "constant", value = 20.0 }

[[phase]]
name = "platelets"
size = { distribution = "uniform", min = 2.0, max = 6.0 }
aspect_ratio = { distribution = "constant", value = 0.05 }
"#;
    pack_and_check("needles", scene, true, &[]);
}

#[test]
fn the_seed_option_overrides_the_scenes_seed() {
    let dir = scratch("seed");
    let scene_seed = pack_and_check("seed-5", PERIODIC, true, &[]);
    let given = pack_and_check("seed-5-given", PERIODIC, true, &["--seed", "5"]);
    let other = pack_and_check("seed-6", PERIODIC, true, &["--seed", "6"]);
    assert!(
        scene_seed == given,
        "--seed 5 differs from the scene's seed 5"
    );
    assert!(scene_seed != other, "--seed 6 gave the packing of seed 5");
    let (run, out) = run_scene(&dir, PERIODIC, &["--seed", "6"]);
    assert!(run.status.success(), "{}", stderr(&run));
    assert_eq!(read_summary(&out.join("summary.json"))["seed"], 6);
}

#[test]
fn a_step_limit_exits_3_and_writes_the_best_overlap_free_state() {
    let dir = scratch("step-limit");
    let text = format!("{PERIODIC}\n[packing]\nmax_steps = 3\n");
    let (run, out) = run_scene(&dir, &text, &[]);
    let err = stderr(&run);
    assert_eq!(run.status.code(), Some(3), "{err}");
    assert!(err.contains("target not reached: step limit"), "{err}");
    let (_, summary) = check_written_packing(&out, true);
    assert_eq!(summary["stop_reason"], "step_limit");
    assert!(number(&summary["scale"]) < 1.0);
}

#[test]
fn outputs_go_where_the_scene_says_and_only_those_enabled() {
    let dir = scratch("outputs");
    let text = format!("{PERIODIC}\n[output]\ndir = \"results/run1\"\ngrains_csv = false\n");
    write_scene(&dir, "scene.toml", &text);
    let run = pack_in(&dir, &["scene.toml", "--quiet"]);
    assert_eq!(run.status.code(), Some(0), "{}", stderr(&run));
    assert!(stderr(&run).is_empty(), "--quiet printed: {}", stderr(&run));
    assert_eq!(
        files_in(&dir.join("results/run1")),
        [
            "centers.vtp",
            "grains.vtu",
            "statistics.png",
            "summary.json"
        ]
    );
}

#[test]
fn without_quiet_a_closing_line_names_the_files_written() {
    let dir = scratch("loud");
    write_scene(&dir, "scene.toml", REFLECTING);
    let run = pack_in(&dir, &["scene.toml", "--out", "o"]);
    assert_eq!(run.status.code(), Some(0), "{}", stderr(&run));
    let err = stderr(&run);
    assert!(
        err.contains("target_reached") && err.contains("summary.json"),
        "{err}"
    );
    assert!(!err.contains("turned"), "{err}");
    // Grains that may turn: the closing lines say how far they did.
    let turning = PERIODIC.replace("[box]", "[packing]\nrotation = true\n\n[box]");
    write_scene(&dir, "turning.toml", &turning);
    let run = pack_in(&dir, &["turning.toml", "--out", "t"]);
    let err = stderr(&run);
    assert!(
        err.contains("turned from their drawn orientations by a median of"),
        "{err}"
    );
}

/// About 4000 grains filling 64 % of a periodic cube: seconds of work for the loop,
/// so a signal sent half a second in comes mid-run.
const SLOW: &str = r#"
seed = 2
target_fraction = 0.64

[box]
size = [73.0, 73.0, 73.0]

[[phase]]
size = { distribution = "lognormal", sigma = 0.25, scale = 4.5, min = 3.0, max = 7.0 }
aspect_ratio = { distribution = "uniform", min = 1.0, max = 2.0 }
"#;

/// Ctrl-C stops the loop, which writes its best overlap-free state and exits 3.
#[cfg(unix)]
#[test]
fn ctrl_c_writes_the_last_overlap_free_state_and_exits_3() {
    let dir = scratch("interrupt");
    write_scene(&dir, "scene.toml", SLOW);
    let child = Command::new(env!("CARGO_BIN_EXE_pack"))
        .args(["scene.toml", "--out", "out", "--quiet"])
        .current_dir(&dir)
        .stderr(std::process::Stdio::piped())
        .spawn()
        .unwrap();
    std::thread::sleep(std::time::Duration::from_millis(500));
    let kill = Command::new("sh")
        .args(["-c", &format!("kill -INT {}", child.id())])
        .status()
        .unwrap();
    assert!(kill.success());
    let run = child.wait_with_output().unwrap();
    let err = stderr(&run);
    assert_eq!(run.status.code(), Some(3), "{err}");
    assert!(err.contains("target not reached: interrupted"), "{err}");
    let (_, summary) = check_written_packing(&dir.join("out"), true);
    assert_eq!(summary["stop_reason"], "interrupted");
}

/// The shipped example scenes, checked like the small ones (about 2 s): both reach
/// their targets, and what they write
/// follows the requested laws as closely as a sample of that many grains can (every
/// Kolmogorov–Smirnov distance below `1.63/√n`, which a true sample exceeds with
/// probability 0.01), kanapy's tilt angles included although its grains may turn.
#[test]
fn the_shipped_scenes_reach_their_targets_with_the_requested_statistics() {
    for name in ["grains", "kanapy_elongated"] {
        let dir = scratch(&format!("shipped-{name}"));
        let scene = Path::new(env!("CARGO_MANIFEST_DIR")).join(format!("configs/{name}.toml"));
        let run = pack_in(&dir, &[scene.to_str().unwrap(), "--out", "out", "--quiet"]);
        assert_eq!(run.status.code(), Some(0), "{name}: {}", stderr(&run));
        let (_, summary) = check_written_packing(&dir.join("out"), true);
        assert_eq!(summary["stop_reason"], "target_reached", "{name}");
        for phase in summary["phases"].as_array().unwrap() {
            let critical = 1.63 / number(&phase["grains"]).sqrt();
            for law in ["diameter", "aspect_ratio", "tilt_angle_deg"] {
                if let Some(d) = phase[law]["ks_distance"].as_f64() {
                    assert!(d < critical, "{name} {}: {law} KS {d}", phase["name"]);
                }
            }
        }
        eprintln!(
            "{name}: {} grains at {:.4}, {:.2} s in the loop, median turn {:.1}°",
            summary["grains"],
            number(&summary["packing_fraction"]),
            number(&summary["timings"]["packing"]),
            number(&summary["rotation"]["median_turn_deg"]),
        );
    }
}

/// 200 equal spheres asked to fill 0.70 of a periodic cube, above the 0.6435 that
/// Farr and Groot's model gives for equal spheres: `pack` warns before packing,
/// naming the estimate, writes it to the summary, and stops jammed below it within
/// the few percent by which random packings of a small box scatter.
#[test]
fn a_target_above_the_reachable_estimate_is_warned_of_before_packing() {
    let dir = scratch("unreachable");
    let side = (200.0 * std::f64::consts::PI / 6.0 * 8.0 / 0.70f64).cbrt();
    let text = format!(
        "seed = 4\ngrains = 200\n[box]\nsize = [{side}, {side}, {side}]\n[[phase]]\n\
         size = {{ distribution = \"constant\", value = 2.0 }}\n"
    );
    let (run, out) = run_scene(&dir, &text, &[]);
    let err = stderr(&run);
    assert_eq!(run.status.code(), Some(3), "{err}");
    assert!(
        err.contains("warning: the drawn grains fill 0.7000")
            && err.contains("reach about 0.643 (Farr and Groot's estimate"),
        "{err}"
    );
    // Jammed at the default effort: the closing message names the setting that buys more.
    assert!(err.contains("at packing.effort = 1 (from 1.5 on"), "{err}");
    let (_, summary) = check_written_packing(&out, true);
    let reachable = number(&summary["reachable_fraction"]);
    assert!((reachable - 0.6435).abs() < 1e-3, "{reachable}");
    assert_eq!(summary["reachable_exact"], true);
    let reached = number(&summary["packing_fraction"]);
    assert!(reached < 0.70 && reached > 0.60, "{reached}");
    // Below the estimate, no warning.
    let fewer = text.replace("grains = 200", "grains = 150");
    let (run, _) = run_scene(&dir, &fewer, &[]);
    assert!(!stderr(&run).contains("warning"), "{}", stderr(&run));
}
