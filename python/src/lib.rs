//! `grainpack._grainpack`: the native half of the Python package `grainpack`.
//!
//! Thin bindings over the library: numpy arrays are checked and borrowed, the work runs
//! with the GIL released, and errors become Python exceptions with the CLI's messages.
//! The pure-Python half (`grainpack/__init__.py`) normalises arguments, draws progress
//! and builds the user-facing `Packing`; the stubs are `grainpack/_grainpack.pyi`.

mod contact;
mod errors;
mod pack;
mod packing;
mod scene;

use pyo3::prelude::*;

#[pymodule]
fn _grainpack(m: &Bound<'_, PyModule>) -> PyResult<()> {
    m.add("SceneError", m.py().get_type::<errors::SceneError>())?;
    m.add("__version__", env!("CARGO_PKG_VERSION"))?;
    m.add_class::<scene::PyScene>()?;
    m.add_class::<packing::PyPacking>()?;
    m.add_function(wrap_pyfunction!(contact::contact_function_rows, m)?)?;
    m.add_function(wrap_pyfunction!(contact::overlaps_rows, m)?)?;
    m.add_function(wrap_pyfunction!(contact::contact_geometry_rows, m)?)?;
    m.add_function(wrap_pyfunction!(pack::pack_scene, m)?)?;
    m.add_function(wrap_pyfunction!(contact::_rust_batch_seconds, m)?)?;
    Ok(())
}
