//! Defects the fuzz targets found (`fuzz/README.md`), each a test named after what
//! broke, with the input that showed it.

use grainpack::contact::{contact_function, contact_function_fast, Stop};

/// fuzz target contact_bits: a form 2^1800 times the size of the other (beyond the
/// double range apart) put λ at ½ with `Stop::Exact`, while the swapped pair answered
/// 0. The small form is a point to the large one: λ* → 1 (for balls, λ* = R1/(R1+R2)).
#[test]
fn lambda_is_one_not_one_half_when_the_second_form_is_beyond_double_range_smaller() {
    let r = [0.3, 0.1, 0.0];
    let q1 = [
        3.75375841440235e255,
        4.669816313723274e-308,
        0.0,
        3.75375841440235e255,
        4.669816313723274e-308,
        3.753758421011899e255,
    ];
    let q2 = [
        7.291121767158173e-304,
        2.2673059898236077e-306,
        0.0,
        1.35675105885e-312,
        0.0,
        8.669768950612022e-280,
    ];
    let balls = (
        [1e300, 0.0, 0.0, 1e300, 0.0, 1e300],
        [1e-300, 0.0, 0.0, 1e-300, 0.0, 1e-300],
    );
    for (q1, q2) in [(q1, q2), balls] {
        for method in [contact_function, contact_function_fast] {
            let a = method(&r, &q1, &q2).unwrap();
            let b = method(&r.map(|x| -x), &q2, &q1).unwrap();
            assert_eq!(a.mu2, b.mu2, "{a:?} {b:?}");
            assert!(matches!(a.stop, Stop::Exact | Stop::Converged), "{a:?}");
            assert_eq!((a.lambda, b.lambda), (1.0, 0.0), "{a:?} {b:?}");
        }
    }
}

/// fuzz target contact_bits, open: a point against a flat disc whose null directions
/// are subnormal (1e-317, 8e-320) rather than zero answers μ² = 0.25 in one order and
/// 1/576 in the other (with exact zeros, both orders give `CommonNullDirection`). The
/// robust path's rank decision on subnormal entries is the suspect; not fixed yet.
#[test]
#[ignore = "open defect: the robust path on forms with subnormal entries (docs/reliability.md)"]
fn swapping_a_point_and_a_disc_with_subnormal_entries_keeps_mu2() {
    let r = [0.5000152587890625, 0.0, 1.0609978955e-314];
    let q1 = [0.0, 0.0, 0.0, 2.070238e-317, 0.0, 1.2325910294356204e-308];
    let q2 = [
        1.0,
        5.222099017e-315,
        4.450147717014403e-308,
        8.079e-320,
        8.087e-320,
        3.4332275390625e-5,
    ];
    let a = contact_function(&r, &q1, &q2);
    let b = contact_function(&r.map(|x| -x), &q2, &q1);
    match (a, b) {
        (Ok(a), Ok(b)) => assert_eq!(a.mu2, b.mu2, "{a:?} {b:?}"),
        (a, b) => assert_eq!(a.is_ok(), b.is_ok(), "{a:?} {b:?}"),
    }
}

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
