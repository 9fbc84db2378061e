//! `Scene`: a validated scene, read from TOML (a file or text) or from a dict, with the
//! CLI's validation and its messages.

use crate::errors::{chain, SceneError};
use grainpack::io::scene::SceneError as LibSceneError;
use grainpack::scene::{Boundary, GrainCount, Scene};
use pyo3::exceptions::PyValueError;
use pyo3::prelude::*;
use pyo3::types::PyTuple;
use std::path::PathBuf;

/// The name scenes given as dicts have in error messages (as a file name would).
const DICT_NAME: &str = "<dict>";

/// The name scenes given as TOML text have in error messages.
const TEXT_NAME: &str = "<string>";

/// A scene: the box, the phases and their laws, the packing parameters and the outputs.
///
/// Made by `Scene.from_toml` or `Scene.from_dict`, validated as `pack SCENE.toml`
/// validates a file; every key is documented in docs/config.md. Immutable.
#[pyclass(name = "Scene", module = "grainpack", frozen)]
pub struct PyScene {
    pub inner: Scene,
    /// The TOML it was read from and its name, so that it pickles (for Dask and
    /// multiprocessing) as the text and is validated again when unpickled.
    source: String,
    name: String,
}

impl PyScene {
    fn read(py: Python<'_>, text: String, name: String) -> PyResult<Self> {
        let inner = Scene::from_str(&text, &name).map_err(|e| scene_error(py, &e))?;
        Ok(Self {
            inner,
            source: text,
            name,
        })
    }
}

/// The Python exception for a scene error: the CLI's message, with `file`, `line`,
/// `column`, `key` and `value` attributes (None where the error has none: a file that
/// cannot be read).
pub fn scene_error(py: Python<'_>, error: &LibSceneError) -> PyErr {
    let err = SceneError::new_err(chain(error));
    let (file, line, column, key, value) = match error {
        LibSceneError::Syntax {
            file, line, column, ..
        } => (Some(file.clone()), Some(*line), Some(*column), None, None),
        LibSceneError::Shape {
            file,
            key,
            line,
            column,
            value,
            ..
        }
        | LibSceneError::Value {
            file,
            key,
            line,
            column,
            value,
            ..
        } => (
            Some(file.clone()),
            Some(*line),
            Some(*column),
            Some(key.clone()),
            Some(value.clone()),
        ),
        // A bad row of a data file the scene names (orientations, a measured table):
        // the data file and its line; the key is the scene's key that names it.
        LibSceneError::DataFile(e) => (
            Some(e.path.clone()),
            Some(e.line),
            None,
            Some(e.key.clone()),
            Some(e.value.clone()),
        ),
        LibSceneError::Read { path, .. } => {
            (Some(path.display().to_string()), None, None, None, None)
        }
        _ => (None, None, None, None, None),
    };
    let instance = err.value(py);
    // Setting attributes on a fresh exception instance does not fail.
    let _ = instance.setattr("file", file);
    let _ = instance.setattr("line", line);
    let _ = instance.setattr("column", column);
    let _ = instance.setattr("key", key);
    let _ = instance.setattr("value", value);
    err
}

#[pymethods]
impl PyScene {
    /// Reads a scene file (a path) and validates it; errors name the file.
    #[staticmethod]
    fn _from_path(py: Python<'_>, path: PathBuf) -> PyResult<Self> {
        // As `Scene::from_path`: the text, then validated under the path's name.
        let text = std::fs::read_to_string(&path).map_err(|source| {
            let error = LibSceneError::Read {
                path: path.clone(),
                source,
            };
            scene_error(py, &error)
        })?;
        Self::read(py, text, path.display().to_string())
    }

    /// Validates a scene given as TOML text; errors name it `name` (default
    /// `<string>`).
    #[staticmethod]
    #[pyo3(signature = (text, name=None))]
    fn _from_text(py: Python<'_>, text: String, name: Option<String>) -> PyResult<Self> {
        Self::read(py, text, name.unwrap_or_else(|| TEXT_NAME.to_owned()))
    }

    /// Validates a scene given as JSON text (the wrapper's `json.dumps` of a dict):
    /// turned into TOML and read as a file named `<dict>` would be.
    #[staticmethod]
    fn _from_json(py: Python<'_>, json: &str) -> PyResult<Self> {
        let value: serde_json::Value = serde_json::from_str(json)
            .map_err(|e| PyValueError::new_err(format!("the scene is not a plain dict: {e}")))?;
        if !value.is_object() {
            return Err(PyValueError::new_err("a scene must be a dict"));
        }
        let text = toml::to_string(&value).map_err(|e| {
            PyValueError::new_err(format!("the scene cannot be written as TOML: {e}"))
        })?;
        Self::read(py, text, DICT_NAME.to_owned())
    }

    /// Pickles as `(Scene._from_text, (toml, name))`: the scene is validated again when
    /// unpickled, and its errors keep their file name.
    fn __reduce__<'py>(slf: &Bound<'py, Self>) -> PyResult<(Bound<'py, PyAny>, (String, String))> {
        let this = slf.get();
        let make = slf.get_type().getattr("_from_text")?;
        Ok((make, (this.source.clone(), this.name.clone())))
    }

    /// The scene's TOML: the file's text, the text given, or the dict written as TOML.
    #[getter]
    fn toml(&self) -> &str {
        &self.source
    }

    /// Seed of the random generator (`seed`).
    #[getter]
    fn seed(&self) -> u64 {
        self.inner.seed
    }

    /// Box edges `(Lx, Ly, Lz)`, or the rectangle's `(Lx, Ly)` in a 2D scene.
    #[getter]
    fn box_size<'py>(&self, py: Python<'py>) -> PyResult<Bound<'py, PyTuple>> {
        PyTuple::new(py, self.inner.domain.sides())
    }

    /// 2 for a scene of ellipses in a rectangle (`box.size = [Lx, Ly]`), 3 for
    /// ellipsoids in a box.
    #[getter]
    fn dimension(&self) -> i32 {
        self.inner.domain.dimension.exponent()
    }

    /// `"periodic"` or `"reflecting"`.
    #[getter]
    fn boundary(&self) -> &'static str {
        match self.inner.domain.boundary {
            Boundary::Periodic => "periodic",
            Boundary::Reflecting => "reflecting",
        }
    }

    /// Phase names, in file order (a grain's `phase` is its index here).
    #[getter]
    fn phases(&self) -> Vec<String> {
        self.inner.phases.iter().map(|p| p.name.clone()).collect()
    }

    /// The expected number of grains (exact when the scene gives `grains = N`).
    #[getter]
    fn expected_count(&self) -> f64 {
        self.inner.expected_count()
    }

    /// The scene's units (`[units]`): `{"length": "um", "stress": "MPa"}` by default.
    #[getter]
    fn units(&self) -> std::collections::HashMap<&'static str, &'static str> {
        let units = self.inner.units;
        std::collections::HashMap::from([
            ("length", units.length.symbol()),
            ("stress", units.stress.symbol()),
        ])
    }

    /// Values the scene's units make implausible (a modulus or a box side far outside
    /// what they make likely), each naming the key and value as `pack` prints them;
    /// the scene is valid all the same.
    #[getter]
    fn warnings(&self) -> Vec<String> {
        self.inner.warnings.clone()
    }

    /// The output directory of the scene (`output.dir`).
    #[getter]
    fn output_dir(&self) -> PathBuf {
        self.inner.output.dir.clone()
    }

    fn __repr__(&self) -> String {
        let s = &self.inner;
        let count = match s.count {
            GrainCount::Exactly(n) => format!("grains={n}"),
            GrainCount::Fraction(f) => format!("target_fraction={f}"),
        };
        let sides: Vec<String> = s.domain.sides().iter().map(f64::to_string).collect();
        format!(
            "Scene({count}, box=({}), boundary={:?}, phases={:?}, seed={})",
            sides.join(", "),
            self.boundary(),
            self.phases(),
            s.seed
        )
    }
}
