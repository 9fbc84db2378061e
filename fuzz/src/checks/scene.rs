//! Scenes: every rejection names the file and a line of it; every acceptance that is
//! small enough is packed, overlap-free or stopped with a reason.

use grainpack::io::scene::SceneError;
use grainpack::packing::Progress;
use grainpack::run::{run, RunError, RunOptions};
use grainpack::scene::Scene;
use std::num::NonZeroUsize;
use std::sync::atomic::{AtomicBool, Ordering};

/// The name scenes are validated under (data files resolve beside it).
pub const SCENE_NAME: &str = "fuzz.toml";

/// Valid scenes expecting more grains than this are checked but not packed: the
/// targets must answer well within libFuzzer's one-second timeout.
pub const MAX_PACKED_GRAINS: f64 = 12.0;

/// FIRE steps after which a packing is interrupted (it must then stop with
/// `Interrupted` and an overlap-free state): a few milliseconds for a dozen grains.
pub const MAX_FIRE_STEPS: u64 = 4000;

/// Validates `text` as the scene file `name`; checks the error's place, or packs the
/// scene when it is tiny, and the mesh keys' validation (`mesh::check_mesh`). Returns
/// the scene when valid.
pub fn check_scene(text: &str, name: &str) -> Option<Scene> {
    let result = Scene::from_str(text, name);
    super::mesh::check_mesh(&result, text);
    match result {
        Ok(scene) => {
            pack_small(&scene);
            Some(scene)
        }
        Err(e) => {
            check_error(&e, text, name);
            None
        }
    }
}

/// The error names `name`, and a line and column inside `text` (a data file's error
/// names the data file and a line of it, checked by the tables' targets).
pub fn check_error(e: &SceneError, text: &str, name: &str) {
    let message = e.to_string();
    // A place past the end is the line after the last one (an unclosed table).
    let lines = text.lines().count() + 1;
    let place = |file: &str, line: usize, column: usize| {
        assert!(
            file == name && (1..=lines).contains(&line) && column >= 1,
            "{message:?} does not name a place in {name} ({lines} lines) for {text:?}"
        );
    };
    match e {
        SceneError::Syntax {
            file, line, column, ..
        }
        | SceneError::Shape {
            file, line, column, ..
        }
        | SceneError::Value {
            file, line, column, ..
        } => place(file, *line, *column),
        SceneError::DataFile(d) => assert_eq!(d.file, name, "{message}"),
        other => panic!("{other:?} for a scene given as text: {text:?}"),
    }
    assert!(
        message.starts_with(name) || message.contains(name),
        "{message}"
    );
}

/// Packs a valid scene of at most [`MAX_PACKED_GRAINS`] expected grains on one
/// thread, interrupted after [`MAX_FIRE_STEPS`] steps: the result must pass its exact
/// check and hold only finite numbers, or be a typed error other than a failed check.
pub fn pack_small(scene: &Scene) {
    let expected = scene.expected_count();
    // NaN (a scene this crate cannot estimate) is not packed either.
    if expected.is_nan() || expected > MAX_PACKED_GRAINS {
        return;
    }
    let stop = AtomicBool::new(false);
    let mut progress = |p: &Progress| {
        if p.step >= MAX_FIRE_STEPS {
            stop.store(true, Ordering::Relaxed);
        }
    };
    let options = RunOptions {
        threads: NonZeroUsize::new(1),
        progress: Some(&mut progress),
        interrupt: Some(&stop),
        ..RunOptions::default()
    };
    match run(scene, options) {
        Ok(result) => {
            let p = &result.packing;
            assert!(p.verification.is_clean(), "{:?}", p.verification);
            let numbers = p.grains.iter().flat_map(|g| {
                (g.centre.into_iter())
                    .chain(g.semi_axes)
                    .chain(g.quaternion)
            });
            assert!(
                numbers.chain([p.scale, p.fraction]).all(f64::is_finite),
                "a packed number is not finite: {scene:?}"
            );
        }
        Err(e @ (RunError::NotClean(_) | RunError::Pack(_))) => {
            panic!("a valid scene failed to pack: {e}: {scene:?}")
        }
        Err(e) => assert!(!e.to_string().is_empty()),
    }
}
