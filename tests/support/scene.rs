//! Helpers shared by the scene-file tests.

use grainpack::scene::Scene;

/// The message of the error that the scene `text` must give.
pub fn scene_error(text: &str) -> String {
    match Scene::from_str(text, "scene.toml") {
        Ok(scene) => panic!("accepted:\n{text}\n{scene:?}"),
        Err(e) => e.to_string(),
    }
}

/// Asserts that `message` starts with `prefix`, showing both otherwise.
#[track_caller]
pub fn assert_starts(message: &str, prefix: &str) {
    assert!(
        message.starts_with(prefix),
        "\n  got: {message}\n want: {prefix}…"
    );
}
