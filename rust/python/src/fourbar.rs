//! Bindings of the four-bar: `FourBar` (solve, sweep, closed form, velocity,
//! acceleration, coupler points, limits, Grashof), the transmission angle, and the
//! batches over many linkages. Convert, release the GIL, map errors; nothing numeric.

use numpy::{IntoPyArray, PyReadonlyArray1, PyReadonlyArray2, PyUntypedArrayMethods};
use planarkin_core::fourbar::{
    acceleration_into, classify, closed_form_batch, closed_form_into, coupler_into, sweep_batch, sweep_into,
    transmission_into, validate_links, velocity_into, BatchOut, MotionOut, SweepOut,
};
use planarkin_core::interrupt::Poll;
use planarkin_core::parallel;
use planarkin_core::solve::newton::SINGULAR_THRESHOLD;
use planarkin_core::{Error, FourBar, Mode, NewtonOptions, SweepOptions};
use pyo3::prelude::*;

use crate::buffers::{contiguous, grid, grid_len, slice, writable, zeros, zeros_named, Arr1, Arr2};
use crate::errors::{array, err, Signals};

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

/// Three outputs of `n` points named `names` (two angles or rates, then the status),
/// filled by `kernel` with the GIL released.
fn triple<'py>(
    py: Python<'py>,
    names: [&str; 3],
    n: usize,
    kernel: impl FnOnce(&mut [f64], &mut [f64], &mut [i8], &Signals) -> Result<(), Error> + Send,
) -> PyResult<Triple<'py, f64>> {
    let (mut a, mut b, mut st) = (zeros(names[0], n)?, zeros(names[1], n)?, zeros(names[2], n)?);
    Signals::detach(py, |signals| kernel(&mut a, &mut b, &mut st, signals))?;
    Ok((a.into_pyarray(py), b.into_pyarray(py), st.into_pyarray(py)))
}

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
        let p = Signals::detach(py, |signals| {
            let poll = Poll::new(signals);
            fb.solve_polled(theta2, mode, guess.map(|(a, b)| [a, b]), &opts, hist.as_mut(), &poll)
        })?;
        Ok((p.theta3, p.theta4, p.status.code(), p.nit, p.residual, hist.map(|h| h.into_pyarray(py))))
    }

    /// Continuation sweep: (theta3, theta4, status, nit, residual, (omega3, omega4)?, (alpha3, alpha4)?).
    #[pyo3(signature = (theta2, mode, guess, tol, max_iter, predictor, method, omega2, alpha2))]
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
        let opts = SweepOptions::new(mode, tol, max_iter, predictor, method).map_err(err)?;
        let t2 = slice("theta2", &theta2)?;
        let n = t2.len();
        let fb = self.inner;
        let what = "sweep outputs";
        let (mut t3, mut t4, mut st, mut nit, mut res) =
            (zeros(what, n)?, zeros(what, n)?, zeros(what, n)?, zeros(what, n)?, zeros(what, n)?);
        let pair = || -> PyResult<(Vec<f64>, Vec<f64>)> { Ok((zeros(what, n)?, zeros(what, n)?)) };
        let mut w = omega2.map(|_| pair()).transpose()?;
        let mut a = alpha2.filter(|_| omega2.is_some()).map(|_| pair()).transpose()?;
        Signals::detach(py, |signals| {
            let out = SweepOut { theta3: &mut t3, theta4: &mut t4, status: &mut st, nit: &mut nit, residual: &mut res };
            let motion = match (omega2, w.as_mut()) {
                (Some(omega2), Some((w3, w4))) => Some(MotionOut {
                    omega2,
                    omega3: w3,
                    omega4: w4,
                    alpha: a.as_mut().map(|(a3, a4)| (alpha2.unwrap_or(0.0), a3.as_mut_slice(), a4.as_mut_slice())),
                }),
                _ => None,
            };
            sweep_into(&fb, t2, guess.map(|(x, y)| [x, y]), &opts, out, motion, signals)
        })?;
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
        let fb = self.inner;
        triple(py, ["theta3", "theta4", "status"], t2.len(), |t3, t4, st, signals| {
            closed_form_into(&fb, t2, mode, SINGULAR_THRESHOLD, t3, t4, st, signals)
        })
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
        let fb = self.inner;
        triple(py, ["omega3", "omega4", "status"], t2.len(), |w3, w4, st, signals| {
            velocity_into(&fb, t2, t3, t4, w2, SINGULAR_THRESHOLD, w3, w4, st, signals)
        })
    }

    /// (alpha3, alpha4, status) at given positions.
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
        let fb = self.inner;
        triple(py, ["alpha3", "alpha4", "status"], t2.len(), |a3, a4, st, signals| {
            acceleration_into(&fb, t2, t3, t4, w2, a2, SINGULAR_THRESHOLD, a3, a4, st, signals)
        })
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
        Signals::detach(py, |signals| coupler_into(&fb, t2, t3, p, delta, &mut x, &mut y, signals))?;
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
        let g = classify(self.inner.lengths());
        (g.class.name(), g.barker.code(), g.barker.kind(), g.barker.description(), g.s, g.l, g.p, g.q)
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
    Signals::detach(py, |signals| transmission_into(t3, t4, &mut mu, &mut s, signals))?;
    Ok((mu.into_pyarray(py), s.into_pyarray(py)))
}

fn links_of(links: &PyReadonlyArray2<'_, f64>) -> PyResult<Vec<FourBar>> {
    let shape = links.shape();
    if shape[1] != 4 {
        return Err(array("links", format!("must have shape (M, 4), got {shape:?}")));
    }
    // (`as_slice` alone also takes a Fortran-ordered array, its values in the other order)
    let c_order = if links.is_c_contiguous() { links.as_slice().ok() } else { None };
    let flat = c_order.ok_or_else(|| array("links", "must be a C-contiguous float64 array"))?;
    validate_links(flat).map_err(err)
}

type BatchArrays<'py> = (Arr2<'py, f64>, Arr2<'py, f64>, Arr2<'py, i8>, Arr2<'py, u32>, Arr2<'py, f64>);

/// Sweeps M linkages over N crank angles in parallel: (M, N) arrays.
#[pyfunction(name = "sweep_batch")]
#[pyo3(signature = (links, theta2, mode, tol, max_iter, predictor, method, threads))]
fn sweep_batch_py<'py>(
    py: Python<'py>,
    links: PyReadonlyArray2<'py, f64>,
    theta2: PyReadonlyArray1<'py, f64>,
    mode: &str,
    tol: f64,
    max_iter: i64,
    predictor: &str,
    method: &str,
    threads: Option<i64>,
) -> PyResult<BatchArrays<'py>> {
    let opts = SweepOptions::new(mode, tol, max_iter, predictor, method).map_err(err)?;
    let threads = parallel::threads(threads).map_err(err)?;
    let fbs = links_of(&links)?;
    let t2 = slice("theta2", &theta2)?;
    let (m, n) = (fbs.len(), t2.len());
    let mn = grid_len("sweep_batch", m, n)?;
    // five (M, N) outputs of 29 bytes a point in all, allocated fallibly, before any work
    let sizes = (mn as u128) * 29;
    let what = format!("sweep_batch: 5 output arrays of {m} x {n} points ({sizes} bytes in all)");
    let (mut t3, mut t4, mut st, mut nit, mut res) = (
        zeros_named(&what, mn)?,
        zeros_named(&what, mn)?,
        zeros_named(&what, mn)?,
        zeros_named(&what, mn)?,
        zeros_named(&what, mn)?,
    );
    Signals::detach(py, |signals| {
        let out = BatchOut { theta3: &mut t3, theta4: &mut t4, status: &mut st, nit: &mut nit, residual: &mut res };
        sweep_batch(&fbs, t2, &opts, out, threads, signals)
    })?;
    Ok((grid(py, m, n, t3), grid(py, m, n, t4), grid(py, m, n, st), grid(py, m, n, nit), grid(py, m, n, res)))
}

/// Closed form for M linkages at N crank angles in parallel: (theta3, theta4) (M, N) arrays,
/// new or the two writable, C-contiguous float64 arrays of `out`, written in place.
#[pyfunction(name = "closed_form_batch")]
#[pyo3(signature = (links, theta2, mode, threads, out=None))]
fn closed_form_batch_py<'py>(
    py: Python<'py>,
    links: PyReadonlyArray2<'py, f64>,
    theta2: PyReadonlyArray1<'py, f64>,
    mode: &str,
    threads: Option<i64>,
    out: Option<(Arr2<'py, f64>, Arr2<'py, f64>)>,
) -> PyResult<(Arr2<'py, f64>, Arr2<'py, f64>)> {
    let mode = Mode::parse(mode).map_err(err)?;
    let threads = parallel::threads(threads).map_err(err)?;
    let fbs = links_of(&links)?;
    let t2 = slice("theta2", &theta2)?;
    let (m, n) = (fbs.len(), t2.len());
    let mn = grid_len("closed_form_batch", m, n)?;
    let run = |t3: &mut [f64], t4: &mut [f64]| {
        Signals::detach(py, |signals| {
            closed_form_batch(&fbs, t2, mode, SINGULAR_THRESHOLD, t3, t4, None, threads, signals)
        })
    };
    if let Some((a3, a4)) = out {
        {
            let (mut w3, mut w4) = (writable("out[0]", &a3, m, n)?, writable("out[1]", &a4, m, n)?);
            run(contiguous("out[0]", &mut w3)?, contiguous("out[1]", &mut w4)?)?;
        }
        return Ok((a3, a4));
    }
    let what = format!("closed_form_batch: 2 output arrays of {m} x {n} points ({} bytes in all)", mn as u128 * 16);
    let (mut t3, mut t4) = (zeros_named(&what, mn)?, zeros_named(&what, mn)?);
    run(&mut t3, &mut t4)?;
    Ok((grid(py, m, n, t3), grid(py, m, n, t4)))
}

/// Adds the four-bar's class and functions to the extension module.
pub(crate) fn register(m: &Bound<'_, PyModule>) -> PyResult<()> {
    m.add_class::<PyFourBar>()?;
    m.add_function(wrap_pyfunction!(transmission, m)?)?;
    m.add_function(wrap_pyfunction!(sweep_batch_py, m)?)?;
    m.add_function(wrap_pyfunction!(closed_form_batch_py, m)?)?;
    Ok(())
}
