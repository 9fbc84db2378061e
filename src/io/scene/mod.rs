//! Scene files: TOML in, a validated [`Scene`] out.
//!
//! Two layers, as the crate's style asks: `raw` mirrors the file with serde
//! (`deny_unknown_fields`, every value spanned), and `validate` turns it into a
//! [`Scene`] of typed, checked values. Nothing downstream sees a raw string or checks
//! again. Every key and its default is documented in `docs/config.md`.
//!
//! The model itself ([`Scene`], its laws and grains) lives in [`crate::scene`];
//! reading is input, so its constructors are defined here.

mod error;
mod raw;
mod validate;

pub use error::{DataFileError, SceneError, TOP_LEVEL};

use crate::scene::Scene;
use std::path::Path;

impl Scene {
    /// Reads and validates a scene file; errors name `path`.
    pub fn from_path(path: &Path) -> Result<Self, SceneError> {
        let text = std::fs::read_to_string(path).map_err(|source| SceneError::Read {
            path: path.to_owned(),
            source,
        })?;
        Self::from_str(&text, &path.display().to_string())
    }

    /// Validates a scene given as text; errors name the file `name`.
    pub fn from_str(text: &str, name: &str) -> Result<Self, SceneError> {
        validate::scene(text, name)
    }
}
