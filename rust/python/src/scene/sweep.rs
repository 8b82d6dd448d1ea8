//! Bindings of the core's `scene/sweep`: the compiled `Plan` (made by `Scene.plan`), its
//! steps and reported columns, a linear input's stroke and the sweep itself, whose one
//! buffers type becomes NumPy arrays without a copy.

use numpy::{IntoPyArray, PyReadonlyArray1};
use planarkin_core::scene::{Plan, Scene, ScenePredictor, SceneSweepBuffers, SceneSweepOptions};
use planarkin_core::NewtonOptions;
use pyo3::prelude::*;

use crate::buffers::{cube, grid, grid_len, slice, Arr1, Arr2, Arr3, HugePages};
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
        let named = |len: usize| format!("{what} of {len} values");
        let mut b = SceneSweepBuffers::advised(plan, n, omega.is_some(), &named, &HugePages).map_err(err)?;
        Signals::detach(py, |signals| plan.sweep(t, &opts, b.out(), signals))?;
        let SceneSweepBuffers {
            points,
            angles,
            status,
            nit,
            det,
            limit,
            step_status,
            step_det,
            point_status,
            velocity: vel,
            acceleration: acc,
        } = b;
        Ok((
            cube(py, (n, np, 2), points),
            grid(py, n, nl, angles),
            status.into_pyarray(py),
            nit.into_pyarray(py),
            det.into_pyarray(py),
            limit.into_pyarray(py),
            grid(py, n, ns, step_status),
            grid(py, n, ns, step_det),
            grid(py, n, np, point_status),
            vel.zip(acc).map(|((v, w), (a, al))| {
                (cube(py, (n, np, 2), v), grid(py, n, nl, w), cube(py, (n, np, 2), a), grid(py, n, nl, al))
            }),
        ))
    }
}
