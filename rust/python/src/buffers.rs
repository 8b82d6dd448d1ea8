//! Output buffers and array views at the boundary: fallible allocation (MemoryError
//! naming the sizes), contiguous input slices, and (M, N) arrays handed to NumPy without
//! a copy.

use numpy::ndarray::{Array2, Array3};
use numpy::{
    IntoPyArray, PyArray1, PyArray2, PyArray3, PyArrayMethods, PyReadonlyArray1, PyReadonlyArray2, PyReadwriteArray2,
    PyUntypedArrayMethods,
};
use pyo3::exceptions::PyMemoryError;
use pyo3::prelude::*;

use crate::errors::{array, err};

pub(crate) type Arr1<'py, T> = Bound<'py, PyArray1<T>>;
pub(crate) type Arr2<'py, T> = Bound<'py, PyArray2<T>>;
pub(crate) type Arr3<'py, T> = Bound<'py, PyArray3<T>>;

/// `len` zeros, or MemoryError naming what and how many.
pub(crate) fn zeros<T: planarkin_core::error::Zeroed>(what: &str, len: usize) -> PyResult<Vec<T>> {
    planarkin_core::error::try_zeros_advised(|| format!("{what} of {len} values"), len, huge_pages).map_err(err)
}

/// `len` zeros, or MemoryError with the description `what` as given.
pub(crate) fn zeros_named<T: planarkin_core::error::Zeroed>(what: &str, len: usize) -> PyResult<Vec<T>> {
    planarkin_core::error::try_zeros_advised(|| what.to_string(), len, huge_pages).map_err(err)
}

/// Buffers at least this large are backed by transparent huge pages where the system
/// allows it (NumPy asks the same for its arrays of 4 MiB and more).
const HUGE_PAGE_MIN: usize = 4 << 20;

/// Asks Linux to back the 2 MiB-aligned part of a large, not yet written buffer with
/// transparent huge pages (`madvise(MADV_HUGEPAGE)`): a batch's outputs are tens of
/// megabytes, and writing them first costs a page fault every 4 KiB otherwise, which on a
/// virtual machine can take longer than computing the values (BENCHMARKS.md). Only advice:
/// where huge pages are off, or on other systems, nothing changes.
fn huge_pages<T>(v: &mut Vec<T>) {
    #[cfg(target_os = "linux")]
    {
        const HUGE: usize = 2 << 20;
        let bytes = v.capacity() * std::mem::size_of::<T>();
        if bytes < HUGE_PAGE_MIN {
            return;
        }
        let start = v.as_mut_ptr() as usize;
        let (lo, hi) = (start.next_multiple_of(HUGE), (start + bytes) / HUGE * HUGE);
        if hi > lo {
            // SAFETY: [lo, hi) lies inside the buffer `v` owns; MADV_HUGEPAGE changes only
            // how the kernel backs those pages, never their contents or their mapping.
            unsafe { libc::madvise(lo as *mut libc::c_void, hi - lo, libc::MADV_HUGEPAGE) };
        }
    }
    #[cfg(not(target_os = "linux"))]
    let _ = (v, HUGE_PAGE_MIN);
}

/// m * n for an (m, n) output, or MemoryError when it does not fit in memory's address space.
pub(crate) fn grid_len(what: &str, m: usize, n: usize) -> PyResult<usize> {
    m.checked_mul(n).ok_or_else(|| PyMemoryError::new_err(format!("{what}: {m} x {n} values do not fit in memory")))
}

/// An (m, n) output array given by the caller, borrowed for writing: a ValueError naming it
/// when its shape differs or it is read-only or shares memory with another argument.
pub(crate) fn writable<'py>(
    name: &str,
    a: &Arr2<'py, f64>,
    m: usize,
    n: usize,
) -> PyResult<PyReadwriteArray2<'py, f64>> {
    if a.shape() != [m, n] {
        return Err(array(name, format!("must have shape ({m}, {n}), got {:?}", a.shape())));
    }
    a.try_readwrite()
        .map_err(|e| array(name, format!("must be a writable array that shares no memory with another argument ({e})")))
}

/// The values of a borrowed output array, in row-major order: it must be C-contiguous
/// (`as_slice_mut` alone also takes a Fortran-ordered array, whose values it would give in
/// the other order).
pub(crate) fn contiguous<'a>(name: &str, a: &'a mut PyReadwriteArray2<'_, f64>) -> PyResult<&'a mut [f64]> {
    let fail = || array(name, "must be a C-contiguous float64 array");
    if !a.is_c_contiguous() {
        return Err(fail());
    }
    a.as_slice_mut().map_err(|_| fail())
}

/// The contiguous values of a 1-D float64 array.
pub(crate) fn slice<'a>(name: &str, a: &'a PyReadonlyArray1<'_, f64>) -> PyResult<&'a [f64]> {
    a.as_slice().map_err(|_| array(name, "must be a contiguous 1-D float64 array"))
}

/// The rows of a (P, 2) array as points.
pub(crate) fn points_of(name: &str, a: &PyReadonlyArray2<'_, f64>) -> PyResult<Vec<[f64; 2]>> {
    let v = a.as_array();
    if v.ncols() != 2 {
        return Err(array(name, "must have shape (P, 2)"));
    }
    Ok(v.rows().into_iter().map(|r| [r[0], r[1]]).collect())
}

/// `v` (m * n values, row-major) as an (m, n) array.
pub(crate) fn grid<'py, T: numpy::Element>(py: Python<'py>, m: usize, n: usize, v: Vec<T>) -> Arr2<'py, T> {
    Array2::from_shape_vec((m, n), v).expect("m * n values").into_pyarray(py)
}

/// `v` (a * b * c values, row-major) as an (a, b, c) array.
pub(crate) fn cube<T: numpy::Element>(py: Python<'_>, shape: (usize, usize, usize), v: Vec<T>) -> Arr3<'_, T> {
    Array3::from_shape_vec(shape, v).expect("a * b * c values").into_pyarray(py)
}

/// Several outputs of one element type in one zeroed allocation (MemoryError naming
/// `what` and the values, where it fails or their count overflows): the kernel writes
/// them as consecutive slices ([`carve`]), and NumPy takes them as views of one array
/// ([`Slab::view`]). One allocation and one array owner, where a buffer per output cost
/// about as much as a small sweep's own work (BENCHMARKS.md, issue 36).
pub(crate) struct Slab<'py, T: numpy::Element> {
    base: Arr1<'py, T>,
    at: usize,
}

/// `lens.iter().sum()` zeros, or MemoryError naming `what`.
pub(crate) fn slab_zeros<T: planarkin_core::error::Zeroed>(what: &str, lens: &[usize]) -> PyResult<Vec<T>> {
    let total = lens.iter().try_fold(0usize, |a, &l| a.checked_add(l));
    let total = total.ok_or_else(|| PyMemoryError::new_err(format!("{what}: the values do not fit in memory")))?;
    zeros(what, total)
}

/// `v` cut into consecutive slices of `lens` (which sum to at most its length).
pub(crate) fn carve<T, const K: usize>(mut v: &mut [T], lens: [usize; K]) -> [&mut [T]; K] {
    lens.map(|len| {
        let (head, rest) = std::mem::take(&mut v).split_at_mut(len);
        v = rest;
        head
    })
}

impl<'py, T: numpy::Element> Slab<'py, T> {
    /// The values of `v`, handed to NumPy without a copy, to be viewed in order.
    pub(crate) fn new(py: Python<'py>, v: Vec<T>) -> Self {
        Slab { base: v.into_pyarray(py), at: 0 }
    }

    /// The next `shape`'s worth of values, as an array of that shape viewing the slab.
    pub(crate) fn view<D: numpy::ndarray::Dimension>(
        &mut self,
        shape: impl numpy::ndarray::IntoDimension<Dim = D>,
    ) -> Bound<'py, numpy::PyArray<T, D>> {
        let shape = shape.into_dimension();
        let len = shape.size();
        // SAFETY: the slab's array is contiguous, owned by this module's container and never
        // resized; no Rust reference to its values outlives this call.
        let all = unsafe { self.base.as_slice() }.expect("a slab is contiguous");
        let values = &all[self.at..self.at + len];
        self.at += len;
        let view = numpy::ndarray::ArrayView::from_shape(shape, values).expect("the shape's values");
        // SAFETY: the view's values live in the slab's array, which the new array keeps
        // alive as its base, and which is never reallocated.
        unsafe { numpy::PyArray::borrow_from_array(&view, self.base.clone().into_any()) }
    }
}
