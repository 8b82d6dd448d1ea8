//! The process-wide switch between the SIMD kernels and the bit-exact scalar path.

use planarkin_core::simd;
use pyo3::prelude::*;

/// Switches the SIMD kernels on (where the CPU has AVX2 and FMA) or off; returns the
/// previous setting.
#[pyfunction]
fn set_simd(enabled: bool) -> bool {
    simd::set_enabled(enabled)
}

/// Whether the SIMD kernels are in use.
#[pyfunction]
fn simd_enabled() -> bool {
    simd::enabled()
}

/// Whether this CPU has the features the SIMD kernels need (AVX2 and FMA).
#[pyfunction]
fn simd_available() -> bool {
    simd::available()
}

pub(crate) fn register(m: &Bound<'_, PyModule>) -> PyResult<()> {
    m.add_function(wrap_pyfunction!(set_simd, m)?)?;
    m.add_function(wrap_pyfunction!(simd_enabled, m)?)?;
    m.add_function(wrap_pyfunction!(simd_available, m)?)?;
    Ok(())
}
