//! Python bindings of planarkin-core, the extension module `planarkin._core`: one module
//! per subject of the core, laid out as the core lays it out (`forces`, `fourbar`, `simd`, and the
//! `scene/` folder: `format`, `sweep`, `branches`, `gradient`), plus the error map
//! (`errors`) and the output buffers (`buffers`). This crate only converts arguments,
//! releases the GIL around kernel calls and maps core errors; every number is computed in
//! planarkin-core.

use numpy::PyArray1;
use planarkin_core::solve::newton::SINGULAR_THRESHOLD;
use planarkin_core::Status;
use pyo3::prelude::*;

mod atlas;
mod buffers;
mod errors;
mod forces;
mod fourbar;
mod scene;
mod simd;

/// The extension module.
#[pymodule]
fn _core(m: &Bound<'_, PyModule>) -> PyResult<()> {
    // Load NumPy's C API now: rust-numpy loads it on the first array made, by running
    // Python code, and a Ctrl-C pending at that moment would turn into a panic.
    PyArray1::<f64>::zeros(m.py(), 0, false);
    atlas::register(m)?;
    forces::register(m)?;
    fourbar::register(m)?;
    scene::register(m)?;
    simd::register(m)?;
    // (code, name, message): planarkin.Status is checked against this table
    let statuses: Vec<(i8, &str, &str)> = Status::ALL.iter().map(|s| (s.code(), s.name(), s.message())).collect();
    m.add("STATUSES", statuses)?;
    m.add("SINGULAR_THRESHOLD", SINGULAR_THRESHOLD)?;
    m.add("BUILD_PROFILE", if cfg!(debug_assertions) { "debug" } else { "release" })?;
    m.add("__version__", env!("CARGO_PKG_VERSION"))?;
    Ok(())
}
