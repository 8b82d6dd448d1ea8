//! Bindings of the scene solver: convert, release the GIL, map errors.

use numpy::ndarray::{Array2, Array3};
use numpy::{IntoPyArray, PyArray2, PyArray3, PyReadonlyArray1};
use planarkin_core::scene::{Plan, Scene, SceneSpec, SceneSweepOptions, SceneSweepOut};
use planarkin_core::NewtonOptions;
use pyo3::prelude::*;

use crate::{err, slice, Arr1};

/// A validated scene (see `planarkin.Scene`, which wraps it).
#[pyclass(frozen, module = "planarkin._core", name = "Scene")]
pub struct PyScene {
    inner: Scene,
}

type Named = (String, String);

#[pymethods]
impl PyScene {
    #[new]
    #[pyo3(signature = (points, links, ground, input, output=None))]
    fn new(
        points: Vec<(String, (f64, f64))>,
        links: Vec<(String, Vec<String>)>,
        ground: String,
        input: Named,
        output: Option<Named>,
    ) -> PyResult<Self> {
        let spec = SceneSpec {
            points: points.into_iter().map(|(n, (x, y))| (n, [x, y])).collect(),
            links,
            ground,
            input,
            output,
        };
        Ok(Self { inner: Scene::new(spec).map_err(err)? })
    }

    /// The drawn input angle (radians).
    #[getter]
    fn input_angle(&self) -> f64 {
        self.inner.input_angle()
    }

    /// Gruebler's count (1 for a valid scene).
    #[getter]
    fn gruebler(&self) -> i64 {
        self.inner.gruebler()
    }

    /// Number of joints (a point on m links counts m - 1).
    #[getter]
    fn joints(&self) -> usize {
        self.inner.joints()
    }

    /// Compiles the plan for `outputs` (None: every point and link).
    #[pyo3(signature = (outputs=None))]
    fn plan(&self, outputs: Option<Vec<String>>) -> PyResult<PyPlan> {
        Ok(PyPlan { inner: self.inner.plan(outputs.as_deref()).map_err(err)? })
    }
}

/// A compiled plan.
#[pyclass(frozen, module = "planarkin._core", name = "Plan")]
pub struct PyPlan {
    inner: Plan,
}

type Arr2<'py, T> = Bound<'py, PyArray2<T>>;
type Arr3<'py, T> = Bound<'py, PyArray3<T>>;
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
    Option<(Arr3<'py, f64>, Arr2<'py, f64>)>,
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

    /// Sweep: (points (N,P,2), angles (N,L), status, nit, det, limit, step_status (N,S),
    /// step_det (N,S), point_status (N,P), (velocity (N,P,2), angular velocity (N,L))?).
    #[pyo3(signature = (theta, tol, max_iter, max_step, omega))]
    fn sweep<'py>(
        &self,
        py: Python<'py>,
        theta: PyReadonlyArray1<'py, f64>,
        tol: f64,
        max_iter: i64,
        max_step: f64,
        omega: Option<f64>,
    ) -> PyResult<SceneSweepArrays<'py>> {
        let opts =
            SceneSweepOptions::new(NewtonOptions::new(tol, max_iter).map_err(err)?, max_step, omega).map_err(err)?;
        let t = slice("theta", &theta)?;
        let plan = &self.inner;
        let (n, np, nl, ns) = (t.len(), plan.points().len(), plan.links().len(), plan.steps().len());
        let mut points = vec![0.0; n * np * 2];
        let mut angles = vec![0.0; n * nl];
        let (mut status, mut nit, mut det, mut limit) = (vec![0i8; n], vec![0u32; n], vec![0.0; n], vec![0.0; n]);
        let (mut step_status, mut step_det, mut point_status) =
            (vec![0i8; n * ns], vec![0.0; n * ns], vec![0i8; n * np]);
        let mut vel = omega.map(|_| (vec![0.0; n * np * 2], vec![0.0; n * nl]));
        py.detach(|| {
            let out = SceneSweepOut {
                points: &mut points,
                angles: &mut angles,
                status: &mut status,
                nit: &mut nit,
                det: &mut det,
                limit: &mut limit,
                step_status: &mut step_status,
                step_det: &mut step_det,
                point_status: &mut point_status,
                velocity: vel.as_mut().map(|(v, w)| (v.as_mut_slice(), w.as_mut_slice())),
            };
            plan.sweep(t, &opts, out)
        })
        .map_err(err)?;
        let a2 =
            |r: usize, c: usize, v: Vec<f64>| Array2::from_shape_vec((r, c), v).expect("r * c values").into_pyarray(py);
        let a3 = |v: Vec<f64>| Array3::from_shape_vec((n, np, 2), v).expect("n * np * 2 values").into_pyarray(py);
        let i2 =
            |r: usize, c: usize, v: Vec<i8>| Array2::from_shape_vec((r, c), v).expect("r * c values").into_pyarray(py);
        Ok((
            a3(points),
            a2(n, nl, angles),
            status.into_pyarray(py),
            nit.into_pyarray(py),
            det.into_pyarray(py),
            limit.into_pyarray(py),
            i2(n, ns, step_status),
            a2(n, ns, step_det),
            i2(n, np, point_status),
            vel.map(|(v, w)| (a3(v), a2(n, nl, w))),
        ))
    }
}

/// Adds the scene classes to the extension module.
pub fn register(m: &Bound<'_, PyModule>) -> PyResult<()> {
    m.add_class::<PyScene>()?;
    m.add_class::<PyPlan>()?;
    Ok(())
}
