//! Every kind of bad input is reported with its file, key, line, column and value.

use super::*;

#[test]
fn syntax_error_names_file_and_line() {
    assert_starts(
        &error(&with_line(10, "sigma = = 0.5")),
        "scene.toml:10:9: invalid TOML: ",
    );
    // An unclosed array is noticed where the next line fails to continue it.
    assert_starts(
        &error(&with_line(4, "size = [50.0, 50.0, 50.0")),
        "scene.toml:5:1: invalid TOML: ",
    );
}

#[test]
fn unknown_keys_are_rejected_with_their_path() {
    assert_starts(
        &error(&with_line(10, "sgma = 0.5")),
        "scene.toml:10:1: phase[0].size.sgma: unknown field `sgma`",
    );
    assert_starts(
        &error(&with_line(1, "sed = 3")),
        "scene.toml:1:1: sed: unknown field `sed`",
    );
    // Future outputs are not silently ignored.
    assert_starts(
        &error(&with_extra("[output]\nvtu = true")),
        "scene.toml:20:1: output.vtu: unknown field `vtu`",
    );
}

#[test]
fn wrong_types_name_key_and_value() {
    let m = error(&with_line(10, "sigma = \"wide\""));
    assert_starts(
        &m,
        "scene.toml:10:9: phase[0].size.sigma: invalid type: string \"wide\", expected f64",
    );
    assert_starts(
        &error(&with_line(1, "seed = -3")),
        "scene.toml:1:8: seed: invalid value: integer `-3`",
    );
    assert_starts(
        &error(&with_line(4, "size = [50.0, 50.0, 50.0, 50.0]")),
        "scene.toml:4:8: box.size = [50.0, 50.0, 50.0, 50.0]: must be [Lx, Ly, Lz] (a box of ellipsoids) or [Lx, Ly] (a 2D scene: a rectangle of ellipses), not 4 lengths",
    );
    assert_starts(
        &error(&with_line(5, "boundary = \"peridic\"")),
        "scene.toml:5:12: box.boundary: unknown variant `peridic`",
    );
    assert_starts(
        &error(&with_line(9, "distribution = \"gamma\"")),
        "scene.toml:9:16: phase[0].size.distribution: unknown variant `gamma`",
    );
}

#[test]
fn missing_required_keys_name_their_table() {
    let without_size = "grains = 1\n[box]\nsize = [9, 9, 9]\n[[phase]]\nname = \"a\"\n";
    assert_starts(
        &error(without_size),
        "scene.toml:4:1: phase[0].size = (missing): each phase needs size (a law) or [phase.measured]",
    );
    assert_starts(
        &error("grains = 1\n"),
        "scene.toml:1:1: <top level>: missing field `box`",
    );
    assert_starts(
        &error(&with_line(11, "")),
        "scene.toml:8:1: phase[0].size.scale = (missing): distribution = \"lognormal\" needs sigma, scale, loc, min, max",
    );
}

#[test]
fn impossible_sizes_are_rejected() {
    assert_starts(
        &error(&with_line(10, "sigma = -0.5")),
        "scene.toml:10:9: phase[0].size.sigma = -0.5: must be positive",
    );
    assert_starts(
        &error(&with_line(12, "min = -4.0")),
        "scene.toml:12:7: phase[0].size.min = -4.0: must be positive",
    );
    assert_starts(
        &error(&with_line(12, "min = nan")),
        "scene.toml:12:7: phase[0].size.min = nan: must be a finite number",
    );
    assert_starts(
        &error(&with_line(16, "value = 0")),
        "scene.toml:16:9: phase[0].aspect_ratio.value = 0: must be positive",
    );
    // A key of another family.
    assert_starts(
        &error(&with_line(11, "std = 8.0")),
        "scene.toml:11:7: phase[0].size.std = 8.0: does not apply to distribution = \"lognormal\"",
    );
}

#[test]
fn reversed_cutoffs_are_rejected() {
    let text = with_line(12, "min = 16.0\nmax = 4.0");
    let text = text.replacen("max = 16.0\n", "", 1);
    assert_starts(&error(&text), "scene.toml:13:7: phase[0].size.max = 4.0: cutoffs reversed or empty: max = 4 must be above min = 16");
}

#[test]
fn cutoffs_that_exclude_almost_all_mass_are_rejected() {
    // lognormal σ = 0.5, median 8: P(15.99 < d < 16) is about 2e-4.
    let m = error(&with_line(12, "min = 15.99"));
    assert_starts(
        &m,
        "scene.toml:12:7: phase[0].size.min = 15.99: the cutoffs [15.99, 16] keep only",
    );
    assert!(m.contains("at least 1e-3 is needed"), "{m}");
}

#[test]
fn packing_fraction_out_of_range_is_rejected() {
    for bad in ["0", "-0.1", "0.8", "1.5"] {
        assert_starts(
            &error(&with_line(2, &format!("target_fraction = {bad}"))),
            &format!("scene.toml:2:19: target_fraction = {bad}: must lie in (0, 0.7707]"),
        );
    }
}

#[test]
fn grains_and_target_fraction_are_exclusive_and_one_is_required() {
    assert_starts(
        &error(&with_line(1, "grains = 100")),
        "scene.toml:2:19: target_fraction = 0.5: give either grains or target_fraction, not both",
    );
    assert_starts(
        &error(&with_line(2, "")),
        "scene.toml:1:1: grains = (missing): give grains (a count) or target_fraction",
    );
    assert_starts(
        &error(&with_line(2, "grains = 0")),
        "scene.toml:2:10: grains = 0: must lie in [1, 10000000]",
    );
    // 20 000 grains of mean volume ~500 in 50³: an expected fraction of ~80.
    let m = error(&with_line(2, "grains = 20000"));
    assert_starts(
        &m,
        "scene.toml:2:10: grains = 20000: that many grains fill an expected",
    );
}

#[test]
fn a_box_smaller_than_a_grain_is_rejected() {
    // The longest grain: d = 16 at aspect 1.5 is 16 × 1.5^(2/3) = 20.97 end to end.
    let m = error(&with_line(4, "size = [50.0, 20.0, 50.0]"));
    assert_starts(
        &m,
        "scene.toml:13:7: phase[0].size.max = 16.0: the longest grain (20.96",
    );
    assert!(m.contains("shortest side is 20"), "{m}");
    assert_starts(
        &error(&with_line(4, "size = [50.0, -2.0, 50.0]")),
        "scene.toml:4:8: box.size = [50.0, -2.0, 50.0]: every side must be positive",
    );
}

#[test]
fn phases_must_exist_have_positive_shares_and_distinct_names() {
    let no_phase = "grains = 1\n[box]\nsize = [9, 9, 9]\n";
    assert_starts(
        &error(no_phase),
        "scene.toml:1:1: phase = (missing): at least one [[phase]] is needed",
    );
    for bad in ["0", "-1", "inf"] {
        assert_starts(
            &error(&with_line(7, &format!("name = \"a\"\nshare = {bad}"))),
            &format!("scene.toml:8:9: phase[0].share = {bad}: must be positive and finite"),
        );
    }
    let twin =
        with_extra("[[phase]]\nname = \"a\"\nsize = { distribution = \"constant\", value = 6 }");
    assert_starts(
        &error(&twin),
        "scene.toml:20:8: phase[1].name = \"a\": two phases have this name",
    );
}

#[test]
fn bad_orientations_are_rejected() {
    let o = |lines: &str| error(&with_line(18, lines));
    assert_starts(
        &o("kind = \"tilt\""),
        "scene.toml:17:1: phase[0].orientation.kappa = (missing): kind = \"tilt\" needs kappa",
    );
    assert_starts(
        &o("kind = \"tilt\"\nkappa = -1"),
        "scene.toml:19:9: phase[0].orientation.kappa = -1: must lie in [0, 1e6]",
    );
    assert_starts(
        &o("kind = \"tilt\"\nkappa = 1\naxis = [1, 0, 0]"),
        "scene.toml:20:8: phase[0].orientation.axis = [1, 0, 0]: the tilt axis must be",
    );
    assert_starts(
        &o("kind = \"tilt\"\nkappa = 1\nmin = 100\nmax = 10"),
        "scene.toml:21:7: phase[0].orientation.max = 10: cutoffs reversed or empty",
    );
    assert_starts(
        &o("kind = \"fixed\"\nquaternion = [2, 0, 0, 0]"),
        "scene.toml:19:14: phase[0].orientation.quaternion = [2, 0, 0, 0]: must be a unit quaternion",
    );
    assert_starts(
        &o("kind = \"aligned\"\naxis = [0, 0, 0]"),
        "scene.toml:19:8: phase[0].orientation.axis = [0, 0, 0]: must be",
    );
    assert_starts(
        &o("kind = \"random\"\nkappa = 1"),
        "scene.toml:19:9: phase[0].orientation.kappa = 1: does not apply to kind = \"random\", which takes no other key",
    );
}

#[test]
fn bad_packing_and_output_values_are_rejected() {
    assert_starts(
        &error(&with_extra("[packing]\njam_resolution = 0")),
        "scene.toml:20:18: packing.jam_resolution = 0: must lie in (0, 0.1]",
    );
    assert_starts(
        &error(&with_extra("[packing]\nmax_steps = 0")),
        "scene.toml:20:13: packing.max_steps = 0: must be at least 1",
    );
    assert_starts(
        &error(&with_extra("[packing]\nrotation = \"sideways\"")),
        "scene.toml:20:12: packing.rotation = \"sideways\": must be false",
    );
    assert_starts(
        &error(&with_extra("[packing]\nrotation = 1")),
        "scene.toml:20:12: packing.rotation = 1: must be false",
    );
    assert_starts(
        &error(&with_extra("[packing]\nmax_turn = 200")),
        "scene.toml:20:12: packing.max_turn = 200: must lie in (0, 180] degrees",
    );
    assert_starts(
        &error(&with_extra("[output]\ndir = \"\"")),
        "scene.toml:20:7: output.dir = \"\": must not be empty",
    );
}

#[test]
fn unreadable_file_names_its_path() {
    let e = Scene::from_path(Path::new("/nonexistent/scene.toml")).unwrap_err();
    assert!(matches!(e, SceneError::Read { .. }));
    assert_eq!(
        e.to_string(),
        "cannot read scene file /nonexistent/scene.toml"
    );
}
