//! Python bindings of planarkin-core, the extension module `planarkin._core`.
//! This crate only converts arguments, releases the GIL around kernel calls and maps
//! core errors to ValueError; every number is computed in planarkin-core.

use numpy::ndarray::Array2;
use numpy::{IntoPyArray, PyArray1, PyArray2, PyReadonlyArray1, PyReadonlyArray2, PyUntypedArrayMethods};
use std::sync::Mutex;

use planarkin_core as core;
use planarkin_core::interrupt::{Interrupt, Poll};
use planarkin_core::{arrays, batch, sweep, FourBar, Method, Mode, NewtonOptions, Predictor, Status, SweepOptions};
use pyo3::exceptions::{PyKeyboardInterrupt, PyMemoryError, PyValueError};
use pyo3::prelude::*;

mod scene;
mod simd;

/// The one place core errors become Python exceptions: invalid input is ValueError, an
/// output too large MemoryError; an interruption re-raises what the signal handler raised.
pub(crate) fn err(e: core::Error) -> PyErr {
    match e {
        core::Error::Allocation { .. } => PyMemoryError::new_err(e.to_string()),
        core::Error::Interrupted => PyKeyboardInterrupt::new_err("interrupted"),
        _ => PyValueError::new_err(e.to_string()),
    }
}

/// The kernels' [`Interrupt`]: re-attaches to Python and runs its signal handlers
/// (`py.check_signals()`); the exception a handler raised (KeyboardInterrupt for Ctrl-C)
/// is kept and raised once the kernel has stopped.
#[derive(Default)]
pub(crate) struct Signals {
    raised: Mutex<Option<PyErr>>,
}

impl Interrupt for Signals {
    fn interrupted(&self) -> bool {
        match Python::attach(|py| py.check_signals()) {
            Ok(()) => false,
            Err(e) => {
                *self.raised.lock().unwrap_or_else(|p| p.into_inner()) = Some(e);
                true
            }
        }
    }
}

impl Signals {
    /// [`err`], but an interruption raises the handler's own exception.
    pub(crate) fn err(&self, e: core::Error) -> PyErr {
        match e {
            core::Error::Interrupted => {
                self.raised.lock().unwrap_or_else(|p| p.into_inner()).take().unwrap_or_else(|| err(e))
            }
            e => err(e),
        }
    }
}

/// `len` zeros, or MemoryError naming what and how many.
pub(crate) fn zeros<T: Clone + Default>(what: &str, len: usize) -> PyResult<Vec<T>> {
    core::error::try_zeros(|| format!("{what} of {len} values"), len).map_err(err)
}

/// A batch output of `len` values, or MemoryError with the description `what`.
fn out<T: Clone + Default>(what: &str, len: usize) -> PyResult<Vec<T>> {
    core::error::try_zeros(|| what.to_string(), len).map_err(err)
}

/// m * n for an (m, n) output, or MemoryError when it does not fit in memory's address space.
pub(crate) fn grid_len(what: &str, m: usize, n: usize) -> PyResult<usize> {
    m.checked_mul(n).ok_or_else(|| PyMemoryError::new_err(format!("{what}: {m} x {n} values do not fit in memory")))
}

pub(crate) type Arr1<'py, T> = Bound<'py, PyArray1<T>>;
type Arr2<'py, T> = Bound<'py, PyArray2<T>>;

pub(crate) fn slice<'a>(name: &str, a: &'a PyReadonlyArray1<'_, f64>) -> PyResult<&'a [f64]> {
    a.as_slice().map_err(|_| PyValueError::new_err(format!("{name} must be a contiguous 1-D float64 array")))
}

fn sweep_options(mode: &str, tol: f64, max_iter: i64, predictor: &str, method: &str) -> PyResult<SweepOptions> {
    Ok(SweepOptions {
        mode: Mode::parse(mode).map_err(err)?,
        newton: NewtonOptions::new(tol, max_iter).map_err(err)?,
        predictor: Predictor::parse(predictor).map_err(err)?,
        method: Method::parse(method).map_err(err)?,
    })
}

/// A four-bar linkage with validated lengths (r1 ground, r2 crank, r3 coupler, r4 rocker).
#[pyclass(frozen, module = "planarkin._core", name = "FourBar")]
struct PyFourBar {
    inner: FourBar,
}

type SolveOut<'py> = (f64, f64, i8, u32, f64, Option<Arr1<'py, f64>>);
type SweepArrays<'py> = (
    Arr1<'py, f64>,
    Arr1<'py, f64>,
    Arr1<'py, i8>,
    Arr1<'py, u32>,
    Arr1<'py, f64>,
    Option<(Arr1<'py, f64>, Arr1<'py, f64>)>,
    Option<(Arr1<'py, f64>, Arr1<'py, f64>)>,
);
type LimitsOut = (Vec<f64>, Vec<f64>, Vec<(f64, f64)>, bool, Option<((f64, f64), (f64, f64))>);
type Triple<'py, T> = (Arr1<'py, T>, Arr1<'py, T>, Arr1<'py, i8>);

#[pymethods]
impl PyFourBar {
    #[new]
    fn new(r1: f64, r2: f64, r3: f64, r4: f64) -> PyResult<Self> {
        Ok(Self { inner: FourBar::new(r1, r2, r3, r4).map_err(err)? })
    }

    /// (r1, r2, r3, r4)
    #[getter]
    fn lengths(&self) -> (f64, f64, f64, f64) {
        let [a, b, c, d] = self.inner.lengths();
        (a, b, c, d)
    }

    /// Newton-Raphson at one crank angle: (theta3, theta4, status, nit, residual, history).
    #[pyo3(signature = (theta2, mode, guess, tol, max_iter, history))]
    #[allow(clippy::too_many_arguments)]
    fn solve<'py>(
        &self,
        py: Python<'py>,
        theta2: f64,
        mode: &str,
        guess: Option<(f64, f64)>,
        tol: f64,
        max_iter: i64,
        history: bool,
    ) -> PyResult<SolveOut<'py>> {
        let mode = Mode::parse(mode).map_err(err)?;
        let opts = NewtonOptions::new(tol, max_iter).map_err(err)?;
        let mut hist = history.then(Vec::new);
        let fb = self.inner;
        let signals = Signals::default();
        let p = py
            .detach(|| {
                let poll = Poll::new(&signals);
                fb.solve_polled(theta2, mode, guess.map(|(a, b)| [a, b]), &opts, hist.as_mut(), &poll)
            })
            .map_err(|e| signals.err(e))?;
        Ok((p.theta3, p.theta4, p.status.code(), p.nit, p.residual, hist.map(|h| h.into_pyarray(py))))
    }

    /// Continuation sweep: (theta3, theta4, status, nit, residual, (omega3, omega4)?, (alpha3, alpha4)?).
    #[pyo3(signature = (theta2, mode, guess, tol, max_iter, predictor, method, omega2, alpha2))]
    #[allow(clippy::too_many_arguments)]
    fn sweep<'py>(
        &self,
        py: Python<'py>,
        theta2: PyReadonlyArray1<'py, f64>,
        mode: &str,
        guess: Option<(f64, f64)>,
        tol: f64,
        max_iter: i64,
        predictor: &str,
        method: &str,
        omega2: Option<f64>,
        alpha2: Option<f64>,
    ) -> PyResult<SweepArrays<'py>> {
        let opts = sweep_options(mode, tol, max_iter, predictor, method)?;
        let t2 = slice("theta2", &theta2)?;
        let n = t2.len();
        let fb = self.inner;
        let what = "sweep outputs";
        let (mut t3, mut t4, mut st, mut nit, mut res) =
            (zeros(what, n)?, zeros(what, n)?, zeros(what, n)?, zeros(what, n)?, zeros(what, n)?);
        let pair = || -> PyResult<(Vec<f64>, Vec<f64>)> { Ok((zeros(what, n)?, zeros(what, n)?)) };
        let mut w = omega2.map(|_| pair()).transpose()?;
        let mut a = alpha2.filter(|_| omega2.is_some()).map(|_| pair()).transpose()?;
        let signals = Signals::default();
        py.detach(|| {
            let out = sweep::SweepOut {
                theta3: &mut t3,
                theta4: &mut t4,
                status: &mut st,
                nit: &mut nit,
                residual: &mut res,
            };
            let motion = match (omega2, w.as_mut()) {
                (Some(omega2), Some((w3, w4))) => Some(sweep::MotionOut {
                    omega2,
                    omega3: w3,
                    omega4: w4,
                    alpha: a.as_mut().map(|(a3, a4)| (alpha2.unwrap_or(0.0), a3.as_mut_slice(), a4.as_mut_slice())),
                }),
                _ => None,
            };
            sweep::sweep_into(&fb, t2, guess.map(|(x, y)| [x, y]), &opts, out, motion, &signals)
        })
        .map_err(|e| signals.err(e))?;
        let pair = |p: Option<(Vec<f64>, Vec<f64>)>| p.map(|(x, y)| (x.into_pyarray(py), y.into_pyarray(py)));
        Ok((
            t3.into_pyarray(py),
            t4.into_pyarray(py),
            st.into_pyarray(py),
            nit.into_pyarray(py),
            res.into_pyarray(py),
            pair(w),
            pair(a),
        ))
    }

    /// Closed form of `mode`: (theta3, theta4, status).
    fn closed_form<'py>(
        &self,
        py: Python<'py>,
        theta2: PyReadonlyArray1<'py, f64>,
        mode: &str,
    ) -> PyResult<Triple<'py, f64>> {
        let mode = Mode::parse(mode).map_err(err)?;
        let t2 = slice("theta2", &theta2)?;
        let n = t2.len();
        let (mut t3, mut t4, mut st) = (zeros("theta3", n)?, zeros("theta4", n)?, zeros("status", n)?);
        let fb = self.inner;
        let signals = Signals::default();
        py.detach(|| {
            let singular = core::newton::SINGULAR_THRESHOLD;
            arrays::closed_form_into(&fb, t2, mode, singular, &mut t3, &mut t4, &mut st, &signals)
        })
        .map_err(|e| signals.err(e))?;
        Ok((t3.into_pyarray(py), t4.into_pyarray(py), st.into_pyarray(py)))
    }

    /// (omega3, omega4, status) at given positions.
    fn velocity<'py>(
        &self,
        py: Python<'py>,
        theta2: PyReadonlyArray1<'py, f64>,
        theta3: PyReadonlyArray1<'py, f64>,
        theta4: PyReadonlyArray1<'py, f64>,
        omega2: PyReadonlyArray1<'py, f64>,
    ) -> PyResult<Triple<'py, f64>> {
        let (t2, t3, t4, w2) = (
            slice("theta2", &theta2)?,
            slice("theta3", &theta3)?,
            slice("theta4", &theta4)?,
            slice("omega2", &omega2)?,
        );
        let n = t2.len();
        let (mut w3, mut w4, mut st) = (zeros("omega3", n)?, zeros("omega4", n)?, zeros("status", n)?);
        let fb = self.inner;
        let signals = Signals::default();
        py.detach(|| {
            let singular = core::newton::SINGULAR_THRESHOLD;
            arrays::velocity_into(&fb, t2, t3, t4, w2, singular, &mut w3, &mut w4, &mut st, &signals)
        })
        .map_err(|e| signals.err(e))?;
        Ok((w3.into_pyarray(py), w4.into_pyarray(py), st.into_pyarray(py)))
    }

    /// (alpha3, alpha4, status) at given positions.
    #[allow(clippy::too_many_arguments)]
    fn acceleration<'py>(
        &self,
        py: Python<'py>,
        theta2: PyReadonlyArray1<'py, f64>,
        theta3: PyReadonlyArray1<'py, f64>,
        theta4: PyReadonlyArray1<'py, f64>,
        omega2: PyReadonlyArray1<'py, f64>,
        alpha2: PyReadonlyArray1<'py, f64>,
    ) -> PyResult<Triple<'py, f64>> {
        let (t2, t3, t4) = (slice("theta2", &theta2)?, slice("theta3", &theta3)?, slice("theta4", &theta4)?);
        let (w2, a2) = (slice("omega2", &omega2)?, slice("alpha2", &alpha2)?);
        let n = t2.len();
        let (mut a3, mut a4, mut st) = (zeros("alpha3", n)?, zeros("alpha4", n)?, zeros("status", n)?);
        let fb = self.inner;
        let signals = Signals::default();
        py.detach(|| {
            arrays::acceleration_into(
                &fb,
                t2,
                t3,
                t4,
                w2,
                a2,
                core::newton::SINGULAR_THRESHOLD,
                &mut a3,
                &mut a4,
                &mut st,
                &signals,
            )
        })
        .map_err(|e| signals.err(e))?;
        Ok((a3.into_pyarray(py), a4.into_pyarray(py), st.into_pyarray(py)))
    }

    /// (x, y) of a coupler point at distance p from the crank pin, angle delta from the coupler.
    fn coupler_point<'py>(
        &self,
        py: Python<'py>,
        theta2: PyReadonlyArray1<'py, f64>,
        theta3: PyReadonlyArray1<'py, f64>,
        p: f64,
        delta: f64,
    ) -> PyResult<(Arr1<'py, f64>, Arr1<'py, f64>)> {
        let (t2, t3) = (slice("theta2", &theta2)?, slice("theta3", &theta3)?);
        let n = t2.len();
        let (mut x, mut y) = (zeros("x", n)?, zeros("y", n)?);
        let fb = self.inner;
        let signals = Signals::default();
        py.detach(|| arrays::coupler_into(&fb, t2, t3, p, delta, &mut x, &mut y, &signals))
            .map_err(|e| signals.err(e))?;
        Ok((x.into_pyarray(py), y.into_pyarray(py)))
    }

    /// (toggles, dead_points, intervals, full_rotation, rocker) with rocker =
    /// ((theta2_min, theta4_min), (theta2_max, theta4_max)) or None.
    fn limits(&self, mode: &str) -> PyResult<LimitsOut> {
        let l = self.inner.limits(Mode::parse(mode).map_err(err)?);
        let rocker = l.rocker.map(|(a, b)| ((a.theta2, a.theta4), (b.theta2, b.theta4)));
        Ok((l.toggles, l.dead_points, l.intervals.iter().map(|&[a, b]| (a, b)).collect(), l.full_rotation, rocker))
    }

    /// (class, barker code, kind, description, s, l, p, q)
    fn grashof(&self) -> (&'static str, &'static str, &'static str, &'static str, f64, f64, f64, f64) {
        let g = core::grashof::classify(self.inner.lengths());
        let class = match g.class {
            core::GrashofClass::Grashof => "grashof",
            core::GrashofClass::ChangePoint => "change-point",
            core::GrashofClass::NonGrashof => "non-grashof",
        };
        (class, g.barker.code(), g.barker.kind(), g.barker.description(), g.s, g.l, g.p, g.q)
    }
}

/// (mu, sin(theta4 - theta3)) elementwise.
#[pyfunction]
fn transmission<'py>(
    py: Python<'py>,
    theta3: PyReadonlyArray1<'py, f64>,
    theta4: PyReadonlyArray1<'py, f64>,
) -> PyResult<(Arr1<'py, f64>, Arr1<'py, f64>)> {
    let (t3, t4) = (slice("theta3", &theta3)?, slice("theta4", &theta4)?);
    let n = t3.len();
    let (mut mu, mut s) = (zeros("mu", n)?, zeros("sin34", n)?);
    let signals = Signals::default();
    py.detach(|| arrays::transmission_into(t3, t4, &mut mu, &mut s, &signals)).map_err(|e| signals.err(e))?;
    Ok((mu.into_pyarray(py), s.into_pyarray(py)))
}

fn links_of(links: &PyReadonlyArray2<'_, f64>) -> PyResult<Vec<FourBar>> {
    let shape = links.shape();
    if shape[1] != 4 {
        return Err(PyValueError::new_err(format!("links must have shape (M, 4), got {shape:?}")));
    }
    let flat = links.as_slice().map_err(|_| PyValueError::new_err("links must be a C-contiguous float64 array"))?;
    batch::validate_links(flat).map_err(err)
}

fn grid<'py, T: numpy::Element>(py: Python<'py>, m: usize, n: usize, v: Vec<T>) -> Arr2<'py, T> {
    Array2::from_shape_vec((m, n), v).expect("m * n values").into_pyarray(py)
}

type BatchArrays<'py> = (Arr2<'py, f64>, Arr2<'py, f64>, Arr2<'py, i8>, Arr2<'py, u32>, Arr2<'py, f64>);

/// Sweeps M linkages over N crank angles in parallel: (M, N) arrays.
#[pyfunction]
#[pyo3(signature = (links, theta2, mode, tol, max_iter, predictor, method, threads))]
#[allow(clippy::too_many_arguments)]
fn sweep_batch<'py>(
    py: Python<'py>,
    links: PyReadonlyArray2<'py, f64>,
    theta2: PyReadonlyArray1<'py, f64>,
    mode: &str,
    tol: f64,
    max_iter: i64,
    predictor: &str,
    method: &str,
    threads: Option<usize>,
) -> PyResult<BatchArrays<'py>> {
    let opts = sweep_options(mode, tol, max_iter, predictor, method)?;
    let fbs = links_of(&links)?;
    let t2 = slice("theta2", &theta2)?;
    let (m, n) = (fbs.len(), t2.len());
    let mn = grid_len("sweep_batch", m, n)?;
    // five (M, N) outputs of 29 bytes a point in all, allocated fallibly, before any work
    let sizes = (mn as u128) * 29;
    let what = format!("sweep_batch: 5 output arrays of {m} x {n} points ({sizes} bytes in all)");
    let (mut t3, mut t4, mut st, mut nit, mut res) =
        (out(&what, mn)?, out(&what, mn)?, out(&what, mn)?, out(&what, mn)?, out(&what, mn)?);
    let signals = Signals::default();
    py.detach(|| {
        let out =
            batch::BatchOut { theta3: &mut t3, theta4: &mut t4, status: &mut st, nit: &mut nit, residual: &mut res };
        batch::sweep_batch(&fbs, t2, &opts, out, threads, &signals)
    })
    .map_err(|e| signals.err(e))?;
    Ok((grid(py, m, n, t3), grid(py, m, n, t4), grid(py, m, n, st), grid(py, m, n, nit), grid(py, m, n, res)))
}

/// Closed form for M linkages at N crank angles in parallel: (theta3, theta4) (M, N) arrays.
#[pyfunction]
#[pyo3(signature = (links, theta2, mode, threads))]
fn closed_form_batch<'py>(
    py: Python<'py>,
    links: PyReadonlyArray2<'py, f64>,
    theta2: PyReadonlyArray1<'py, f64>,
    mode: &str,
    threads: Option<usize>,
) -> PyResult<(Arr2<'py, f64>, Arr2<'py, f64>)> {
    let mode = Mode::parse(mode).map_err(err)?;
    let fbs = links_of(&links)?;
    let t2 = slice("theta2", &theta2)?;
    let (m, n) = (fbs.len(), t2.len());
    let mn = grid_len("closed_form_batch", m, n)?;
    let what = || format!("closed_form_batch: 2 output arrays of {m} x {n} points ({} bytes in all)", mn as u128 * 16);
    let what = what();
    let (mut t3, mut t4) = (out(&what, mn)?, out(&what, mn)?);
    let signals = Signals::default();
    py.detach(|| {
        let singular = core::newton::SINGULAR_THRESHOLD;
        batch::closed_form_batch(&fbs, t2, mode, singular, &mut t3, &mut t4, None, threads, &signals)
    })
    .map_err(|e| signals.err(e))?;
    Ok((grid(py, m, n, t3), grid(py, m, n, t4)))
}

/// The extension module.
#[pymodule]
fn _core(m: &Bound<'_, PyModule>) -> PyResult<()> {
    m.add_class::<PyFourBar>()?;
    scene::register(m)?;
    simd::register(m)?;
    m.add_function(wrap_pyfunction!(transmission, m)?)?;
    m.add_function(wrap_pyfunction!(sweep_batch, m)?)?;
    m.add_function(wrap_pyfunction!(closed_form_batch, m)?)?;
    let statuses: Vec<(i8, String, &str)> =
        Status::ALL.iter().map(|s| (s.code(), format!("{s:?}"), s.message())).collect();
    m.add("STATUSES", statuses)?;
    m.add("SINGULAR_THRESHOLD", core::newton::SINGULAR_THRESHOLD)?;
    m.add("BUILD_PROFILE", if cfg!(debug_assertions) { "debug" } else { "release" })?;
    m.add("__version__", env!("CARGO_PKG_VERSION"))?;
    Ok(())
}
