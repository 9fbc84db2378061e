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
    // numpy's C API is loaded on first use, which runs Python code: left to the first
    // result after a pack, a Ctrl-C landing then made that load fail, and the numpy crate
    // panics on it. Loaded here, at import, a late Ctrl-C is a plain KeyboardInterrupt.
    numpy::PyArray1::<f64>::zeros(m.py(), [0], false);
    m.add_class::<scene::PyScene>()?;
    m.add_class::<packing::PyPacking>()?;
    m.add_function(wrap_pyfunction!(contact::contact_function_rows, m)?)?;
    m.add_function(wrap_pyfunction!(contact::overlaps_rows, m)?)?;
    m.add_function(wrap_pyfunction!(contact::contact_geometry_rows, m)?)?;
    m.add_function(wrap_pyfunction!(pack::pack_scene, m)?)?;
    m.add_function(wrap_pyfunction!(contact::_rust_batch_seconds, m)?)?;
    Ok(())
}
