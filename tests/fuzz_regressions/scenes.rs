//! Scene and run defects: defects 2, 8, 10 and 13 of `docs/reliability.md`.

/// hypothesis (python/tests/test_arguments_hypothesis.py): `pack(threads=100000)` (and
/// `pack --threads 100000`) started a rayon pool of that many threads, which took
/// minutes and gigabytes. Now a typed error, at once, before anything is drawn.
#[test]
fn a_hundred_thousand_threads_is_a_typed_error_not_a_pool() {
    use grainpack::run::{run, RunError, RunOptions, MAX_THREADS};
    use grainpack::scene::Scene;
    use std::num::NonZeroUsize;
    let text = "grains = 4\n[box]\nsize = [20.0, 20.0, 20.0]\n[[phase]]\n\
                size = { distribution = \"constant\", value = 3.0 }\n";
    let scene = Scene::from_str(text, "tiny.toml").unwrap();
    let options = RunOptions {
        threads: NonZeroUsize::new(100_000),
        ..RunOptions::default()
    };
    let err = run(&scene, options).unwrap_err();
    assert!(matches!(err, RunError::TooManyThreads { .. }), "{err}");
    assert!(err.to_string().contains(&MAX_THREADS.to_string()), "{err}");
    let out = std::process::Command::new(env!("CARGO_BIN_EXE_pack"))
        .args(["--threads", "100000", "--quiet", "configs/grains.toml"])
        .current_dir(env!("CARGO_MANIFEST_DIR"))
        .output()
        .unwrap();
    let stderr = String::from_utf8_lossy(&out.stderr);
    assert_eq!(out.status.code(), Some(2), "{stderr}");
    assert!(stderr.contains("threads = 100000"), "{stderr}");
}

/// fuzz target measured_table: a measured grain of diameter 1.2e141 (1e150, 3e203 in
/// 2D), `mode = "exact"`, `target_fraction = 0.2`: the grains' volume overflowed, the
/// box scaled to it was infinite, the scene validated, and packing it failed
/// (`RunError::Pack`). Now an error naming `target_fraction`, in 3D and in 2D; a table
/// of 1e100 still validates (volume 5e299).
#[test]
fn measured_grains_beyond_the_double_range_are_refused_not_given_an_infinite_box() {
    use grainpack::scene::Scene;
    let dir = std::env::temp_dir().join(format!("grainpack-huge-grain-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    let name = dir.join("scene.toml").display().to_string();
    for (box_size, d, refused) in [
        ("[40.0, 40.0, 40.0]", "1.2e141", true),
        ("[40.0, 40.0]", "3.3e203", true),
        ("[40.0, 40.0, 40.0]", "1e100", false),
    ] {
        std::fs::write(dir.join("grains.csv"), format!("d\n1.0\n{d}\n")).unwrap();
        let scene = format!(
            "target_fraction = 0.2\n[box]\nsize = {box_size}\n[[phase]]\n\
             measured = {{ file = \"grains.csv\", mode = \"exact\" }}\n"
        );
        match Scene::from_str(&scene, &name) {
            Ok(s) if !refused => assert!(s.domain.size.iter().all(|l| l.is_finite()), "{s:?}"),
            Err(e) if refused => {
                let message = e.to_string();
                assert!(message.contains(": target_fraction = 0.2: "), "{message}");
                assert!(message.contains("beyond the range"), "{message}");
            }
            other => panic!("d = {d}: {other:?}"),
        }
    }
    std::fs::remove_dir_all(&dir).unwrap();
}

/// fuzz target scene_keys (open defect 3 of the second round): `grains = 4` of constant
/// size 1e-300 (and 5e-324) in a box of 20, in 3D and in 2D, validated; packing them
/// failed (`RunError::Pack`: the squared semi-axes underflowed, and a pivot of the
/// grain's factorisation was 0 or NaN; the volumes and fractions were 0). Now refused,
/// naming the size and its value; sizes just above the limits still validate and pack.
#[test]
fn grains_too_small_for_doubles_are_refused_naming_their_size_not_left_to_fail_packing() {
    use grainpack::run::{run, RunOptions};
    use grainpack::scene::Scene;
    let scene = |size: &str, d: &str| {
        format!(
            "seed = 1\ngrains = 4\n[box]\nsize = {size}\n[[phase]]\n[phase.size]\n\
             distribution = \"constant\"\nvalue = {d}\n"
        )
    };
    let (cube, square) = ("[20.0, 20.0, 20.0]", "[20.0, 20.0]");
    for (size, d) in [
        (cube, "1e-300"),
        (cube, "5e-324"),
        (square, "1e-300"),
        (cube, "1e-103"),
    ] {
        let e = Scene::from_str(&scene(size, d), "tiny.toml").unwrap_err();
        let message = e.to_string();
        assert!(
            message.contains(&format!("tiny.toml:8:9: phase[0].size.value = {d}: ")),
            "{message}"
        );
        assert!(
            message.contains("below what the packing resolves"),
            "{message}"
        );
    }
    // The limits: a volume of at least 2.2e-308 in 3D, semi-axes of 6.7e-139 in 2D. The
    // 3D grains in a box of 1: four of them fill 2.6e-310 of the box of 20, below the
    // normal doubles, which is refused naming box.size
    // (a_box_the_grains_fill_less_than_a_double_resolves_is_refused_naming_box_size).
    for (size, d) in [("[1.0, 1.0, 1.0]", "1e-102"), (square, "1e-137")] {
        let s = Scene::from_str(&scene(size, d), "tiny.toml").unwrap();
        let options = RunOptions {
            threads: std::num::NonZeroUsize::new(1),
            ..RunOptions::default()
        };
        let packed = run(&s, options).unwrap();
        assert!(packed.packing.verification.is_clean(), "d = {d}");
    }
}

/// A box of 1e100 given with 4 grains of 1e-100 validated, and every output said the
/// grains filled 0 of it (1e-600 underflows; `packing_fraction = 0` in the summary).
/// Such a fraction is meaningless in doubles: now refused naming `box.size` and its
/// value, in 3D and 2D, with a count and with an exact measured table, wherever the
/// fraction is below the normal doubles (grains of 1e-102 in a box of 20: 2.6e-310);
/// grains that fill a normal double of the same box (1e-2 across: 2e-306) still
/// validate.
#[test]
fn a_box_the_grains_fill_less_than_a_double_resolves_is_refused_naming_box_size() {
    use grainpack::scene::Scene;
    let dir = std::env::temp_dir().join(format!("grainpack-huge-box-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    let name = dir.join("scene.toml").display().to_string();
    let counted = |size: &str, d: &str| {
        format!(
            "grains = 4\n[box]\nsize = {size}\n[[phase]]\n\
             [phase.size]\ndistribution = \"constant\"\nvalue = {d}\n"
        )
    };
    std::fs::write(dir.join("grains.csv"), "d\n1e-100\n2e-100\n").unwrap();
    let measured = "[box]\nsize = [1e100, 1e100, 1e100]\n[[phase]]\n\
                    measured = { file = \"grains.csv\", mode = \"exact\" }\n";
    for (scene, size) in [
        (
            counted("[1e100, 1e100, 1e100]", "1e-100"),
            "[1e100, 1e100, 1e100]",
        ),
        (counted("[1e150, 1e150]", "1e-100"), "[1e150, 1e150]"),
        (
            counted("[20.0, 20.0, 20.0]", "1e-102"),
            "[20.0, 20.0, 20.0]",
        ),
        (measured.to_string(), "[1e100, 1e100, 1e100]"),
    ] {
        let message = Scene::from_str(&scene, &name).unwrap_err().to_string();
        assert!(
            message.contains(&format!("box.size = {size}: ")),
            "{message}"
        );
        assert!(message.contains("below the smallest fraction"), "{message}");
    }
    let s = Scene::from_str(&counted("[1e100, 1e100, 1e100]", "1e-2"), &name).unwrap();
    assert!(s.domain.volume() > 0.0);
    std::fs::remove_dir_all(&dir).unwrap();
}
