//! The fuzz targets' bodies (`fuzz/src/checks`), run without instrumentation: over the
//! committed corpus (`fuzz/corpus/TARGET/`: seeds, and every input a campaign found
//! that crashed or that libFuzzer kept as covering new code), then over inputs that
//! proptest generates. A regression in what the campaigns explored shows here at once;
//! the long coverage-guided campaigns are run by hand (`fuzz/README.md`).

#[path = "../fuzz/src/checks/mod.rs"]
mod checks;

use proptest::prelude::*;
use std::path::Path;

/// Runs `check` on every file of `fuzz/corpus/{target}`.
fn replay(target: &str, check: fn(&[u8])) {
    let dir = Path::new(env!("CARGO_MANIFEST_DIR"))
        .join("fuzz/corpus")
        .join(target);
    let mut files: Vec<_> = (std::fs::read_dir(&dir).unwrap())
        .map(|e| e.unwrap().path())
        .collect();
    files.sort();
    assert!(!files.is_empty(), "no corpus in {}", dir.display());
    for file in files {
        let data = std::fs::read(&file).unwrap();
        // The file's name in the panic message, if a property fails.
        let outcome = std::panic::catch_unwind(|| check(&data));
        assert!(outcome.is_ok(), "fuzz/corpus/{target}/{}", file.display());
    }
}

#[test]
fn scene_files_of_the_corpus_are_refused_with_their_place_or_packed() {
    replay("scene_bytes", checks::scene_bytes);
}

#[test]
fn generated_scenes_of_the_corpus_are_refused_with_their_place_or_packed() {
    replay("scene_keys", checks::scene_keys);
}

#[test]
fn contact_case_files_of_the_corpus_name_their_bad_lines_and_write_finite_answers() {
    replay("contact_csv", checks::contact_csv);
}

#[test]
fn measured_tables_of_the_corpus_name_their_bad_lines_or_pack() {
    replay("measured_table", checks::measured_table);
}

#[test]
fn orientation_files_of_the_corpus_name_their_bad_lines_or_pack() {
    replay("orientation_file", checks::orientation_file);
}

#[test]
fn contact_bit_patterns_of_the_corpus_answer_finitely_and_symmetrically() {
    replay("contact_bits", checks::contact_bits);
}

/// The generator reaches 2D scenes: of 300 byte strings (up to 24 bytes: a few edits) (ChaCha8, a fixed seed), some
/// make valid 2D scenes (validated and packed by `check_scene`, as every generated
/// scene) and some 2D scenes refused for a key without meaning in the plane.
#[test]
fn generated_scenes_include_valid_and_refused_2d_ones() {
    use grainpack::contact::Dimension;
    use rand::{Rng, SeedableRng};
    let mut rng = rand_chacha::ChaCha8Rng::seed_from_u64(25);
    let (mut valid, mut refused) = (0, 0);
    for _ in 0..300 {
        let n = rng.random_range(0..24);
        let bytes: Vec<u8> = (0..n).map(|_| rng.random()).collect();
        let text = checks::scene_from_choices(&mut checks::Choices::new(&bytes));
        match checks::check_scene(&text, checks::SCENE_NAME) {
            Some(s) if s.domain.dimension == Dimension::Two => valid += 1,
            Some(_) => {}
            None => {
                let e = grainpack::scene::Scene::from_str(&text, checks::SCENE_NAME);
                let message = e.expect_err("refused above").to_string();
                refused += usize::from(message.contains("has no meaning in a 2D scene"));
            }
        }
    }
    assert!(
        valid > 0 && refused > 0,
        "{valid} valid, {refused} refused 2D scenes"
    );
}

/// The generator's 2D edit reaches a size table by area (edit 8, its first box, phase 0,
/// the last set of 2D keys: `by = "area"`, which only a 2D scene takes): a valid 2D
/// scene, packed by `check_scene`.
#[test]
fn generated_2d_scenes_include_a_size_table_by_area() {
    use grainpack::contact::Dimension;
    let text = checks::scene_from_choices(&mut checks::Choices::new(&[8, 0, 0, 10]));
    assert!(text.contains("by = \"area\""), "{text}");
    let scene = checks::check_scene(&text, checks::SCENE_NAME).expect("a valid scene");
    assert_eq!(scene.domain.dimension, Dimension::Two, "{text}");
}

/// Every mesh edit of the generator (`fuzz/src/checks/mesh.rs`: a meshable scene, then
/// one of `mesh`, `mesh_size`, `mesh_order`, `packing.gap` or the materials set to each
/// of its limit values or removed) through `check_scene`, which holds a valid scene's
/// mesh to its documented limits and a refusal to the line of the key it names (the
/// mesh is never made: gmsh is not run). Each key's values give valid scenes and
/// refusals naming that key, in 3D and in 2D (the same edits after edit 8's box of two
/// lengths: a 2D scene is meshed as triangles).
#[test]
fn every_mesh_edit_validates_within_the_limits_or_is_refused_naming_its_key() {
    let mut outcomes = std::collections::BTreeMap::new();
    // Edit 8 with its first box, phase 0 and its first (empty) set of 2D keys.
    let flat = [8, 0, 0, 0];
    for (dimension, prefix) in [("3D", &[][..]), ("2D", &flat[..])] {
        for (i, &(table, key, values)) in checks::MESH_EDITS.iter().enumerate() {
            for (j, value) in values.iter().enumerate() {
                // Edit 9 (the mesh edit), then which key, which value, phase 0.
                let bytes = [prefix, &[9, i as u8, j as u8, 0]].concat();
                let text = checks::scene_from_choices(&mut checks::Choices::new(&bytes));
                assert!(text.contains("mesh = true") || key == "mesh", "{text}");
                assert_eq!(
                    text.contains("size = [20.0, 20.0]\n"),
                    dimension == "2D",
                    "{text}"
                );
                let path = match table {
                    "phase.elastic" => format!("phase[0].elastic.{key}"),
                    t => format!("{t}.{key}"),
                };
                let named = match checks::check_scene(&text, checks::SCENE_NAME) {
                    Some(scene) => scene.output.mesh.is_some(),
                    None => {
                        let e = grainpack::scene::Scene::from_str(&text, checks::SCENE_NAME);
                        let message = e.expect_err("refused above").to_string();
                        // Without a mesh (`mesh = false`), `[matrix]` is what is refused.
                        let matrix = *value == "false" && message.contains(": matrix = ");
                        assert!(
                            value.is_empty() || matrix || message.contains(&format!(": {path}")),
                            "{key} = {value}: {message}"
                        );
                        false
                    }
                };
                let (valid, refused) = outcomes.entry((dimension, path)).or_insert((0, 0));
                *if named { valid } else { refused } += 1;
            }
        }
    }
    for (path, (valid, refused)) in &outcomes {
        assert!(
            *valid > 0 && *refused > 0,
            "{path:?}: {valid} valid, {refused} refused"
        );
    }
    assert_eq!(outcomes.len(), 2 * checks::MESH_EDITS.len(), "{outcomes:?}");
}

#[test]
fn contact_bit_patterns_of_ellipses_in_the_corpus_name_2d_entries_and_answer_as_embedded() {
    replay("contact_bits_2d", checks::contact_bits_2d);
}

/// One double for [`random_pairs_failures_by_dimension`]: raw bits, moderate, subnormal
/// or tiny, zero, any magnitude, or near 1, equally often.
fn extreme_double(rng: &mut rand_chacha::ChaCha8Rng) -> f64 {
    use rand::Rng;
    match rng.random_range(0..6) {
        0 => f64::from_bits(rng.random()),
        1 => rng.random_range(-4.0..4.0),
        2 => f64::from_bits(rng.random_range(0..(1u64 << 52) * 3)),
        3 => 0.0,
        4 => rng.random_range(0.0..4.0) * 2f64.powi(rng.random_range(-1000..1000)),
        _ => rng.random_range(0.5..2.0),
    }
}

/// How many of 300 000 random 3D pairs and 300 000 random pairs of ellipses (a fixed
/// seed, entries from [`extreme_double`]) fail the contact checks: the figures of
/// `docs/reliability.md` (defects 5, 6 and 9: 0 and 0 since defect 9's fix). Ignored:
/// a measurement (6 s).
#[test]
#[ignore = "a measurement for docs/reliability.md"]
fn random_pairs_failures_by_dimension() {
    use rand::{Rng, SeedableRng};
    std::panic::set_hook(Box::new(|_| {}));
    let n = 300_000;
    for dim in [3, 2] {
        let mut rng = rand_chacha::ChaCha8Rng::seed_from_u64(7);
        let mut failed = 0;
        for _ in 0..n {
            let k =
                [-8, -7, -6, -5, -4, -3, -2, -1, 1, 1, 2, 3, 4, 5, 6, 7][rng.random_range(0..16)];
            let ok = if dim == 3 {
                let r: [f64; 3] = std::array::from_fn(|_| extreme_double(&mut rng));
                let q1: [f64; 6] = std::array::from_fn(|_| extreme_double(&mut rng));
                let q2: [f64; 6] = std::array::from_fn(|_| extreme_double(&mut rng));
                std::panic::catch_unwind(|| checks::check_pair(&r, &q1, &q2, k)).is_ok()
            } else {
                let r: [f64; 2] = std::array::from_fn(|_| extreme_double(&mut rng));
                let q1: [f64; 3] = std::array::from_fn(|_| extreme_double(&mut rng));
                let q2: [f64; 3] = std::array::from_fn(|_| extreme_double(&mut rng));
                std::panic::catch_unwind(|| checks::check_pair_2d(&r, &q1, &q2, k)).is_ok()
            };
            failed += usize::from(!ok);
        }
        println!("{dim}D: {failed} of {n} pairs fail the contact checks");
    }
}

/// Doubles of every class (NaN, ±∞, subnormal, zero, huge) half the time, and
/// moderate values the other half, so that definite forms are frequent.
fn double() -> impl Strategy<Value = f64> {
    prop_oneof![any::<f64>(), -4.0..4.0f64]
}

/// The cases `cargo test` draws: a fixed seed, so that CI runs the same 256 cases each
/// time. Fresh draws belong to the fuzz campaigns: with a random seed, a defect still
/// open (as defect 9 of `docs/reliability.md` was, ellipse pairs whose μ² depended on
/// their order, 140 of 300 000 extreme random pairs) fails CI at random, which blocks
/// every change and tells nothing new.
const PROPTEST_SEED: u64 = 20_261_126;

proptest! {
    #![proptest_config(ProptestConfig {
        cases: 256,
        failure_persistence: None,
        rng_seed: proptest::test_runner::RngSeed::Fixed(PROPTEST_SEED),
        ..ProptestConfig::default()
    })]

    #[test]
    fn generated_scenes_are_refused_with_their_place_or_packed(
        bytes in proptest::collection::vec(any::<u8>(), 0..120)
    ) {
        checks::scene_keys(&bytes);
    }

    #[test]
    fn contact_answers_are_finite_and_symmetric_or_typed_errors(
        r in [double(), double(), double()],
        q1 in [double(), double(), double(), double(), double(), double()],
        q2 in [double(), double(), double(), double(), double(), double()],
        k in -8i32..8,
    ) {
        checks::check_pair(&r, &q1, &q2, if k == 0 { 1 } else { k });
    }

    #[test]
    fn contact_answers_of_ellipses_are_the_embedded_pairs_or_name_2d_entries(
        r in [double(), double()],
        q1 in [double(), double(), double()],
        q2 in [double(), double(), double()],
        k in -8i32..8,
    ) {
        checks::check_pair_2d(&r, &q1, &q2, if k == 0 { 1 } else { k });
    }
}
