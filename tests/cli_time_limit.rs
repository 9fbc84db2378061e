//! `packing.time_limit` and `pack --time-limit`: read, refused when not a positive
//! number of seconds (naming the key or the flag), and honoured with the stop reason
//! `time_limit` and exit code 3.

mod support;

use grainpack::scene::{Scene, Unjam};
use serde_json::Value;
use support::files::{pack_in, scratch};

/// 300 spheres asked to fill 0.70 of a periodic cube: they jam near 0.64.
const JAMMING: &str = "seed = 2\ngrains = 300\n[box]\nsize = [12.16, 12.16, 12.16]\n\
    [[phase]]\nsize = { distribution = \"constant\", value = 2.0 }\n\
    [output]\ndir = \"out\"\nvtk = false\nstatistics_png = false\n";

fn with_packing(extra: &str) -> String {
    format!("{JAMMING}[packing]\n{extra}\n")
}

#[test]
fn the_time_limit_is_read_and_bad_values_are_refused_by_name() {
    let scene = Scene::from_str(&with_packing("time_limit = 2.5"), "scene.toml").unwrap();
    assert_eq!(scene.packing.time_limit, Some(2.5));
    // Its cycles run whatever effort, so unjam's moves need no effort of their own.
    let text = with_packing("time_limit = 2.5\nunjam = \"anneal\"");
    let scene = Scene::from_str(&text, "scene.toml").unwrap();
    assert_eq!(scene.packing.unjam, Unjam::Anneal);
    for bad in ["0", "-1", "nan", "inf"] {
        let err = Scene::from_str(&with_packing(&format!("time_limit = {bad}")), "scene.toml")
            .unwrap_err()
            .to_string();
        assert!(
            err.contains(&format!(
                "packing.time_limit = {bad}: must be a positive number of seconds"
            )),
            "{err}"
        );
    }
}

#[test]
fn pack_stops_at_the_time_limit_with_the_densest_clean_state() {
    let dir = scratch("time-limit", "cli");
    std::fs::write(dir.join("scene.toml"), JAMMING).unwrap();
    let run = pack_in(&dir, &["--quiet", "--time-limit", "1.5", "scene.toml"]);
    let err = String::from_utf8_lossy(&run.stderr);
    assert_eq!(run.status.code(), Some(3), "{err}");
    assert!(err.contains("time limit: 1.5 s of packing"), "{err}");
    assert!(
        !err.contains("before any relaxation came out clean"),
        "{err}"
    );
    let summary: Value =
        serde_json::from_str(&std::fs::read_to_string(dir.join("out/summary.json")).unwrap())
            .unwrap();
    assert_eq!(summary["stop_reason"], "time_limit");
    assert_eq!(summary["overlapping_pairs"], 0);
    let fraction = summary["packing_fraction"].as_f64().unwrap();
    assert!(fraction > 0.5 && fraction < 0.70, "{fraction}");
    // A limit over before any relaxation came out clean says what the state kept is.
    let run = pack_in(&dir, &["--quiet", "--time-limit", "1e-6", "scene.toml"]);
    let err = String::from_utf8_lossy(&run.stderr);
    assert_eq!(run.status.code(), Some(3), "{err}");
    assert!(
        err.contains("ran out before any relaxation came out clean")
            && err.contains("a lower target_fraction, or more time"),
        "{err}"
    );
    // A flag that is not a positive number of seconds: bad input, nothing written.
    let bad = scratch("time-limit", "bad");
    std::fs::write(bad.join("scene.toml"), JAMMING).unwrap();
    for value in ["--time-limit=-3", "--time-limit=0", "--time-limit=soon"] {
        let run = pack_in(&bad, &[value, "scene.toml"]);
        let err = String::from_utf8_lossy(&run.stderr);
        assert_eq!(run.status.code(), Some(2), "{err}");
        let given = value.trim_start_matches("--time-limit=");
        assert!(
            err.contains("--time-limit")
                && err.contains(&format!("\"{given}\" is not a positive number of seconds")),
            "{err}"
        );
        assert!(!bad.join("out").exists());
    }
}
