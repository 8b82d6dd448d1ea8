//! Output buffers and array views at the boundary: fallible allocation (MemoryError
//! naming the sizes), contiguous input slices, and (M, N) arrays handed to NumPy without
//! a copy.

use numpy::ndarray::{Array2, Array3};
use numpy::{IntoPyArray, PyArray1, PyArray2, PyArray3, PyReadonlyArray1};
use pyo3::exceptions::{PyMemoryError, PyValueError};
use pyo3::prelude::*;

use crate::errors::err;

pub(crate) type Arr1<'py, T> = Bound<'py, PyArray1<T>>;
pub(crate) type Arr2<'py, T> = Bound<'py, PyArray2<T>>;
pub(crate) type Arr3<'py, T> = Bound<'py, PyArray3<T>>;

/// `len` zeros, or MemoryError naming what and how many.
pub(crate) fn zeros<T: Clone + Default>(what: &str, len: usize) -> PyResult<Vec<T>> {
    planarkin_core::error::try_zeros(|| format!("{what} of {len} values"), len).map_err(err)
}

/// `len` zeros, or MemoryError with the description `what` as given.
pub(crate) fn zeros_named<T: Clone + Default>(what: &str, len: usize) -> PyResult<Vec<T>> {
    planarkin_core::error::try_zeros(|| what.to_string(), len).map_err(err)
}

/// m * n for an (m, n) output, or MemoryError when it does not fit in memory's address space.
pub(crate) fn grid_len(what: &str, m: usize, n: usize) -> PyResult<usize> {
    m.checked_mul(n).ok_or_else(|| PyMemoryError::new_err(format!("{what}: {m} x {n} values do not fit in memory")))
}

/// The contiguous values of a 1-D float64 array.
pub(crate) fn slice<'a>(name: &str, a: &'a PyReadonlyArray1<'_, f64>) -> PyResult<&'a [f64]> {
    a.as_slice().map_err(|_| PyValueError::new_err(format!("{name} must be a contiguous 1-D float64 array")))
}

/// `v` (m * n values, row-major) as an (m, n) array.
pub(crate) fn grid<'py, T: numpy::Element>(py: Python<'py>, m: usize, n: usize, v: Vec<T>) -> Arr2<'py, T> {
    Array2::from_shape_vec((m, n), v).expect("m * n values").into_pyarray(py)
}

/// `v` (a * b * c values, row-major) as an (a, b, c) array.
pub(crate) fn cube<T: numpy::Element>(py: Python<'_>, shape: (usize, usize, usize), v: Vec<T>) -> Arr3<'_, T> {
    Array3::from_shape_vec(shape, v).expect("a * b * c values").into_pyarray(py)
}
