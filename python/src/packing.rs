//! `Packing`: a run's result, with its grain table as numpy columns, its summary, and
//! the CLI's outputs on request.

use crate::errors::chain;
use grainpack::contact::Dimension;
use grainpack::io::mesh::{gmsh_version, write_mesh};
use grainpack::io::report::{
    crystal_orientations, texture_summaries, write_grains_csv, write_outputs, Summary,
};
use grainpack::io::texture::measure_textures;
use grainpack::io::voxel::voxelise;
use grainpack::run::RunResult;
use grainpack::scene::{rve_cells, MeshSpec, RveFill, Scene, MESH_SIZE_RANGE, MIN_MESH_GAP};
use numpy::{IntoPyArray, PyArray1};
use pyo3::exceptions::{PyOSError, PyRuntimeError, PyValueError};
use pyo3::prelude::*;
use pyo3::types::PyDict;
use std::path::PathBuf;
use std::sync::Mutex;

/// Material and phase of each voxel (flat, x fastest), and the cells along x, y, z.
type Voxels<'py> = (
    Bound<'py, PyArray1<u32>>,
    Bound<'py, PyArray1<u32>>,
    [usize; 3],
);

/// The result of `grainpack.pack`: the packed grains and the run's figures.
#[pyclass(name = "_Packing", module = "grainpack._grainpack", frozen)]
pub struct PyPacking {
    scene: Scene,
    result: RunResult,
    /// `summary.json` as last written by `write`, so that `summary` then matches it.
    written_summary: Mutex<Option<String>>,
}

impl PyPacking {
    pub fn new(scene: Scene, result: RunResult) -> Self {
        Self {
            scene,
            result,
            written_summary: Mutex::new(None),
        }
    }

    fn summary_json(&self) -> String {
        if let Some(written) = &*self.written_summary.lock().expect("never poisoned") {
            return written.clone();
        }
        let crystals = crystal_orientations(&self.scene, &self.result);
        let measures = measure_textures(&self.scene, &self.result, &crystals);
        let textures = texture_summaries(&self.scene, &measures);
        let summary = Summary::new(&self.scene, &self.result, None, textures, 0.0);
        serde_json::to_string(&summary).expect("a summary serializes")
    }
}

/// One column of the grain table: integers where every value is one, else floats,
/// else text.
fn column<'py>(py: Python<'py>, values: &[&str]) -> Bound<'py, PyAny> {
    if let Ok(ints) = values
        .iter()
        .map(|v| v.parse::<i64>())
        .collect::<Result<Vec<_>, _>>()
    {
        return ints.into_pyarray(py).into_any();
    }
    if let Ok(floats) = values
        .iter()
        .map(|v| v.parse::<f64>())
        .collect::<Result<Vec<_>, _>>()
    {
        return floats.into_pyarray(py).into_any();
    }
    let strings: Vec<String> = values.iter().map(|v| v.to_string()).collect();
    strings
        .into_pyobject(py)
        .map(|l| l.into_any())
        .expect("a list of strings converts")
}

#[pymethods]
impl PyPacking {
    /// The grain table, column by column, as `grains.csv` holds it: a dict from column
    /// name to a numpy array (int64 for integer columns, float64 otherwise), in the
    /// file's column order. Built from the same writer, so every column the CLI writes
    /// is here, with the same doubles.
    fn _grain_table<'py>(&self, py: Python<'py>) -> PyResult<Bound<'py, PyDict>> {
        let mut text = Vec::new();
        let crystals = crystal_orientations(&self.scene, &self.result);
        write_grains_csv(
            &mut text,
            &self.result.packing.grains,
            &crystals,
            self.scene.domain.dimension,
        )
        .map_err(|e| PyOSError::new_err(e.to_string()))?;
        let mut reader = csv::Reader::from_reader(text.as_slice());
        let header: Vec<String> = reader
            .headers()
            .map_err(|e| PyOSError::new_err(e.to_string()))?
            .iter()
            .map(str::to_owned)
            .collect();
        let records = reader
            .records()
            .collect::<Result<Vec<_>, _>>()
            .map_err(|e| PyOSError::new_err(e.to_string()))?;
        let table = PyDict::new(py);
        for (k, name) in header.iter().enumerate() {
            let values: Vec<&str> = records.iter().map(|r| &r[k]).collect();
            table.set_item(name, column(py, &values))?;
        }
        Ok(table)
    }

    /// The run's summary as JSON text (`summary.json`'s content).
    fn _summary_json(&self) -> String {
        self.summary_json()
    }

    /// Writes what `pack SCENE.toml --seed SEED --out DIR` writes, as the scene's
    /// `[output]` asks, into `dir`; returns the paths written, in order.
    fn _write(&self, py: Python<'_>, dir: PathBuf) -> PyResult<Vec<PathBuf>> {
        let mut scene = self.scene.clone();
        scene.output.dir = dir;
        let result = &self.result;
        let written = py
            .detach(|| write_outputs(&scene, result))
            .map_err(|e| PyOSError::new_err(chain(&e)))?;
        if scene.output.summary_json {
            let mut summary = Summary::new(
                &scene,
                result,
                written.rve.as_ref(),
                written.textures.clone(),
                written.seconds,
            );
            summary.mesh = written.mesh.as_ref();
            let json = serde_json::to_string(&summary).expect("a summary serializes");
            *self.written_summary.lock().expect("never poisoned") = Some(json);
        }
        Ok(written.files)
    }

    /// Writes the conforming mesh (`mesh.msh`, `mesh.inp`, `mesh.vtu`) into `dir`, as
    /// `[output] mesh = true` with `mesh_size = size`, `mesh_order = order`, `mesh_fill =
    /// fill` ("matrix" or "grains"); returns the
    /// paths and the summary's `mesh` entry as JSON. gmsh runs in the Python `python`
    /// (the caller's own interpreter).
    fn _mesh(
        &self,
        py: Python<'_>,
        dir: PathBuf,
        size: f64,
        order: u8,
        fill: &str,
        python: String,
    ) -> PyResult<(Vec<PathBuf>, String)> {
        let (lo, hi) = MESH_SIZE_RANGE;
        if !(lo..=hi).contains(&size) {
            return Err(PyValueError::new_err(format!(
                "size = {size}: must lie in [{lo}, {hi}] (as output.mesh_size)"
            )));
        }
        if !(1..=2).contains(&order) {
            return Err(PyValueError::new_err(format!(
                "order = {order}: must be 1 (C3D4, CPE3 in 2D) or 2 (C3D10, CPE6 in 2D)"
            )));
        }
        let fill = fill_of(fill, "output.mesh_fill")?;
        let gap = self.scene.packing.gap;
        if gap < MIN_MESH_GAP {
            return Err(PyValueError::new_err(format!(
                "packing.gap = {gap}: a mesh needs a gap between the grains, at least \
                 {MIN_MESH_GAP}: pack the scene with a gap"
            )));
        }
        gmsh_version(&python).map_err(|e| PyRuntimeError::new_err(chain(&e)))?;
        let mut scene = self.scene.clone();
        scene.output.mesh = Some(MeshSpec { size, order, fill });
        let (grains, threads) = (&self.result.packing.grains, self.result.threads);
        let stats = py
            .detach(|| {
                std::fs::create_dir_all(&dir)
                    .map_err(|e| format!("cannot create {}: {e}", dir.display()))?;
                write_mesh(&scene, grains, &dir, threads, &python).map_err(|e| chain(&e))
            })
            .map_err(PyRuntimeError::new_err)?;
        let files = ["mesh.msh", "mesh.inp", "mesh.vtu"].map(|n| dir.join(n));
        let json = serde_json::to_string(&stats).expect("mesh stats serialize");
        Ok((files.to_vec(), json))
    }

    /// The voxel grid: `(material, phase, cells)`, both flat in x-fastest order.
    /// `cells` is an int (along the longest edge, the others proportional, as
    /// `rve_resolution = N`) or three counts (two in 2D, whose grid is one cell
    /// thick); `fill` is `"grains"` or `"matrix"`.
    fn _voxelise<'py>(
        &self,
        py: Python<'py>,
        cells: Vec<usize>,
        fill: &str,
    ) -> PyResult<Voxels<'py>> {
        let fill = fill_of(fill, "output.rve_fill")?;
        let domain = &self.scene.domain;
        let plane = domain.dimension == Dimension::Two;
        let cells = match cells.as_slice() {
            [n] => rve_cells(*n, domain),
            [x, y] if plane => [*x, *y, 1],
            [x, y, z] if !plane => [*x, *y, *z],
            other => {
                let want = if plane {
                    "two (a 2D scene's grid is one cell thick)"
                } else {
                    "three"
                };
                return Err(PyValueError::new_err(format!(
                    "resolution = {other:?}: must be one int or {want}"
                )));
            }
        };
        let (grains, domain, phases) = (
            &self.result.packing.grains,
            &self.scene.domain,
            self.scene.phases.len(),
        );
        let grid = py
            .detach(|| voxelise(grains, domain, cells, fill, phases))
            .map_err(|e| PyValueError::new_err(chain(&e)))?;
        Ok((
            grid.material.into_pyarray(py),
            grid.phase.into_pyarray(py),
            grid.cells,
        ))
    }

    /// Box edges `(Lx, Ly, Lz)`.
    #[getter]
    fn box_size(&self) -> (f64, f64, f64) {
        let [x, y, z] = self.scene.domain.size;
        (x, y, z)
    }

    /// The seed used.
    #[getter]
    fn seed(&self) -> u64 {
        self.result.seed
    }

    /// Why the loop stopped: `target_reached`, `jammed`, `step_limit`, `interrupted` or
    /// `time_limit` (`packing.time_limit`).
    #[getter]
    fn stop_reason(&self) -> &'static str {
        self.result.packing.stop.name()
    }

    /// The scene's phase names (a grain's `phase` indexes them).
    #[getter]
    fn phase_names(&self) -> Vec<String> {
        self.scene.phases.iter().map(|p| p.name.clone()).collect()
    }

    fn __len__(&self) -> usize {
        self.result.packing.grains.len()
    }
}

/// `fill` as the scene's `key` takes it.
fn fill_of(fill: &str, key: &str) -> PyResult<RveFill> {
    match fill {
        "grains" => Ok(RveFill::Grains),
        "matrix" => Ok(RveFill::Matrix),
        other => Err(PyValueError::new_err(format!(
            "fill = {other:?}: must be \"grains\" or \"matrix\" (as {key})"
        ))),
    }
}
