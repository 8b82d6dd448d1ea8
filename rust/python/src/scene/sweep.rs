//! Bindings of the core's `scene/sweep`: the compiled `Plan` (made by `Scene.plan`), its
//! steps and reported columns, a linear input's stroke and the sweep itself, whose one
//! buffers type becomes NumPy arrays without a copy.

use numpy::{IntoPyArray, PyReadonlyArray1};
use planarkin_core::scene::{Plan, Scene, ScenePredictor, SceneSweepOptions, SceneSweepOut};
use planarkin_core::NewtonOptions;
use pyo3::prelude::*;

use crate::buffers::{carve, grid_len, slab_zeros, slice, zeros, Arr1, Arr2, Arr3, Slab};
use crate::errors::{err, Signals};

/// `Scene.plan`: the plan for `outputs` (None: every point and link).
pub(super) fn plan(scene: &Scene, outputs: Option<Vec<String>>) -> PyResult<PyPlan> {
    Ok(PyPlan { inner: scene.plan(outputs.as_deref()).map_err(err)? })
}

/// A compiled plan.
#[pyclass(frozen, module = "planarkin._core", name = "Plan")]
pub(super) struct PyPlan {
    inner: Plan,
}

type SceneSweepArrays<'py> = (
    Arr3<'py, f64>,
    Arr2<'py, f64>,
    Arr1<'py, i8>,
    Arr1<'py, u32>,
    Arr1<'py, f64>,
    Arr1<'py, f64>,
    Arr2<'py, i8>,
    Arr2<'py, f64>,
    Arr2<'py, i8>,
    Option<(Arr3<'py, f64>, Arr2<'py, f64>, Arr3<'py, f64>, Arr2<'py, f64>)>,
);

#[pymethods]
impl PyPlan {
    /// Steps as (kind, point indices, unknown link indices).
    #[getter]
    fn steps(&self) -> Vec<(&'static str, Vec<usize>, Vec<usize>)> {
        self.inner.steps().iter().map(|s| (s.kind.name(), s.points.clone(), s.unknowns.clone())).collect()
    }

    /// Indices of the points a sweep reports.
    #[getter]
    fn points(&self) -> Vec<usize> {
        self.inner.points().to_vec()
    }

    /// Indices of the links whose angles a sweep reports.
    #[getter]
    fn links(&self) -> Vec<usize> {
        self.inner.links().to_vec()
    }

    /// A linear input's stroke (lo, hi) for a drawing of extent `size` (Plan::stroke).
    #[pyo3(signature = (size, tol, max_iter, max_step))]
    fn stroke(&self, py: Python<'_>, size: f64, tol: f64, max_iter: i64, max_step: f64) -> PyResult<(f64, f64)> {
        let opts =
            SceneSweepOptions::new(NewtonOptions::new(tol, max_iter).map_err(err)?, max_step, None).map_err(err)?;
        let plan = &self.inner;
        Signals::detach(py, |signals| plan.stroke(size, &opts, signals))
    }

    /// Sweep: (points (N,P,2), angles (N,L), status, nit, det, limit, step_status (N,S),
    /// step_det (N,S), point_status (N,P), (velocity (N,P,2), angular velocity (N,L),
    /// acceleration (N,P,2), angular acceleration (N,L))?).
    #[pyo3(signature = (theta, tol, max_iter, max_step, omega, predictor))]
    fn sweep<'py>(
        &self,
        py: Python<'py>,
        theta: PyReadonlyArray1<'py, f64>,
        tol: f64,
        max_iter: i64,
        max_step: f64,
        omega: Option<f64>,
        predictor: &str,
    ) -> PyResult<SceneSweepArrays<'py>> {
        let opts = SceneSweepOptions::new(NewtonOptions::new(tol, max_iter).map_err(err)?, max_step, omega)
            .map_err(err)?
            .with_predictor(ScenePredictor::parse(predictor).map_err(err)?);
        let t = slice("theta", &theta)?;
        let plan = &self.inner;
        let (n, np, nl, ns) = (t.len(), plan.points().len(), plan.links().len(), plan.steps().len());
        let what = "scene sweep outputs";
        // sizes that do not fit the address space are named here, as for every output
        for (m, k) in [(n, 2 * np), (n, nl), (n, ns)] {
            grid_len(what, m, k)?;
        }
        // every output in three allocations (reals, codes, counts) that NumPy views
        let rates = omega.is_some();
        let (pn, ln) = (n * np * 2, n * nl);
        let [v, w] = if rates { [pn, ln] } else { [0; 2] };
        // (their sums checked: a MemoryError where they overflow, never a wrapped size)
        let (real_lens, code_lens) = ([pn, ln, n, n, n * ns, v, w, v, w], [n, n * ns, n * np]);
        let mut reals: Vec<f64> = slab_zeros(what, &real_lens)?;
        let mut codes: Vec<i8> = slab_zeros(what, &code_lens)?;
        let mut nit: Vec<u32> = zeros(what, n)?;
        {
            let [points, angles, det, limit, step_det, v, w, a, al] = carve(&mut reals, real_lens);
            let [status, step_status, point_status] = carve(&mut codes, code_lens);
            let (velocity, acceleration) = if rates { (Some((v, w)), Some((a, al))) } else { (None, None) };
            let out = SceneSweepOut {
                points,
                angles,
                status,
                nit: &mut nit,
                det,
                limit,
                step_status,
                step_det,
                point_status,
                velocity,
                acceleration,
            };
            Signals::detach(py, |signals| plan.sweep(t, &opts, out, signals))?;
        }
        let (mut r, mut c) = (Slab::new(py, reals), Slab::new(py, codes));
        let (points, angles, det, limit, step_det) =
            (r.view((n, np, 2)), r.view((n, nl)), r.view(n), r.view(n), r.view((n, ns)));
        let (status, step_status, point_status) = (c.view(n), c.view((n, ns)), c.view((n, np)));
        let kin = rates.then(|| (r.view((n, np, 2)), r.view((n, nl)), r.view((n, np, 2)), r.view((n, nl))));
        Ok((points, angles, status, nit.into_pyarray(py), det, limit, step_status, step_det, point_status, kin))
    }
}
