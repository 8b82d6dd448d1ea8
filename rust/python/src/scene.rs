//! Bindings of the scene solver: `Scene` (validation, assemblies, trace, circuits) and
//! its compiled `Plan` (sweeps). Convert, release the GIL, map errors; nothing numeric.

use numpy::{IntoPyArray, PyReadonlyArray1, PyReadonlyArray2};
use planarkin_core::scene::{
    assemble_sketch, Assemblies, LinearKind, Plan, Scene, ScenePredictor, SceneSpec, SceneSweepOptions, SceneSweepOut,
    Trace, TraceOptions,
};
use planarkin_core::solve::homotopy::HomotopyOptions;
use planarkin_core::{Error, NewtonOptions};
use pyo3::prelude::*;

use crate::buffers::{cube, grid, grid_len, slice, zeros, Arr1, Arr2, Arr3};
use crate::errors::{array, err, Signals};

/// A validated scene (see `planarkin.Scene`, which wraps it).
#[pyclass(frozen, module = "planarkin._core", name = "Scene")]
pub(crate) struct PyScene {
    inner: Scene,
}

type Named = (String, String);
/// A slot (point, guide, line) or a prismatic pair (link, guide, line).
type Joint = (String, String, (String, String));

#[pymethods]
impl PyScene {
    #[new]
    #[pyo3(signature = (points, links, ground, input, output=None, slots=Vec::new(), prismatic=Vec::new(), linear_input=None))]
    #[allow(clippy::too_many_arguments)]
    fn new(
        points: Vec<(String, (f64, f64))>,
        links: Vec<(String, Vec<String>)>,
        ground: String,
        input: Named,
        output: Option<Named>,
        slots: Vec<(String, Joint)>,
        prismatic: Vec<(String, Joint)>,
        linear_input: Option<Named>,
    ) -> PyResult<Self> {
        let spec = spec_of(points, links, ground, input, output, slots, prismatic, linear_input)?;
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
    fn joint_count(&self) -> usize {
        self.inner.joint_count()
    }

    /// Every real assembly at `theta`: ([(points (P,2), label, det, step_det)],
    /// complex counts per group step, failed homotopy paths).
    #[pyo3(signature = (theta, seed, runs))]
    fn assemblies<'py>(&self, py: Python<'py>, theta: f64, seed: u64, runs: i64) -> PyResult<AssembliesOut<'py>> {
        let opts = HomotopyOptions::new(seed, runs).map_err(err)?;
        let a = Signals::detach(py, |signals| self.inner.assemblies(theta, &opts, signals))?;
        assemblies_out(py, a)
    }

    /// Trace from `start` ((P,2) scene coordinates; None: the drawn pose):
    /// (theta, points (M,P,2), det, turning_points, closed).
    #[pyo3(signature = (start, step, max_points))]
    fn trace<'py>(
        &self,
        py: Python<'py>,
        start: Option<PyReadonlyArray2<'py, f64>>,
        step: f64,
        max_points: i64,
    ) -> PyResult<TraceOut<'py>> {
        let opts = TraceOptions::new(step, max_points).map_err(err)?;
        let start = start.map(|a| points_of("start", &a)).transpose()?;
        let t = Signals::detach(py, |signals| self.inner.trace(start.as_deref(), &opts, signals))?;
        trace_out(py, t, self.inner.point_names().len())
    }

    /// Derivatives of solved poses by the free drawn coordinates: `points` (N * P, 2) holds
    /// N poses of every point; the result (N * P, 2 * F) holds d(point, x or y) / d(free)
    /// for each, NaN for a pose that is not finite or singular.
    fn pose_gradient<'py>(
        &self,
        py: Python<'py>,
        points: PyReadonlyArray2<'py, f64>,
        free: Vec<(usize, usize)>,
        relative: bool,
    ) -> PyResult<Arr2<'py, f64>> {
        let np = self.inner.point_names().len();
        let pts = points_of("points", &points)?;
        if np > 0 && pts.len() % np != 0 {
            return Err(array("points", format!("must hold whole poses of {np} points")));
        }
        let nf = free.len();
        if nf == 0 || np == 0 {
            return Ok(grid(py, pts.len(), 2 * nf, Vec::new()));
        }
        let mut out = zeros("pose gradients", pts.len() * 2 * nf)?;
        py.detach(|| self.inner.poses_gradient(&pts, &free, relative, &mut out)).map_err(err)?;
        Ok(grid(py, pts.len(), 2 * nf, out))
    }

    /// Derivatives of the signed conditioning of `plan(outputs)` at the poses `points`
    /// (N * P, 2) whose derivatives `dpoints` (N * P * 2 * F, `pose_gradient`'s result
    /// flattened) are given: (N, F), NaN where a pose is not finite.
    #[pyo3(signature = (points, dpoints, free, outputs=None))]
    fn dets_gradient<'py>(
        &self,
        py: Python<'py>,
        points: PyReadonlyArray2<'py, f64>,
        dpoints: PyReadonlyArray1<'py, f64>,
        free: Vec<(usize, usize)>,
        outputs: Option<Vec<String>>,
    ) -> PyResult<Arr2<'py, f64>> {
        let np = self.inner.point_names().len();
        let pts = points_of("points", &points)?;
        let nf = free.len();
        if np == 0 || pts.len() % np != 0 {
            return Err(array("points", format!("must hold whole poses of {np} points")));
        }
        let d = slice("dpoints", &dpoints)?;
        if d.len() != pts.len() * 2 * nf {
            return Err(array(
                "dpoints",
                format!("must hold {} values, the derivatives of points", pts.len() * 2 * nf),
            ));
        }
        let n = pts.len() / np;
        let mut out = zeros("conditioning gradients", n * nf)?;
        py.detach(|| self.inner.dets_gradient(outputs.as_deref(), &pts, d, &free, &mut out)).map_err(err)?;
        Ok(grid(py, n, nf, out))
    }

    /// Circuits at `theta`: (assemblies as in `assemblies`, counts, failed,
    /// [(assembly indices, turning points, net turn, (lo, hi), trace)]).
    #[pyo3(signature = (theta, seed, runs, step, max_points))]
    fn circuits<'py>(
        &self,
        py: Python<'py>,
        theta: f64,
        seed: u64,
        runs: i64,
        step: f64,
        max_points: i64,
    ) -> PyResult<(AssembliesOut<'py>, Vec<CircuitOut<'py>>)> {
        let hopts = HomotopyOptions::new(seed, runs).map_err(err)?;
        let topts = TraceOptions::new(step, max_points).map_err(err)?;
        let (a, cs) = Signals::detach(py, |signals| self.inner.circuits(theta, &hopts, &topts, signals))?;
        let np = self.inner.point_names().len();
        let circuits = cs
            .into_iter()
            .map(|c| Ok((c.assemblies, c.turning_points, c.net_turn, c.range, trace_out(py, c.trace, np)?)))
            .collect::<PyResult<_>>()?;
        Ok((assemblies_out(py, a)?, circuits))
    }

    /// Compiles the plan for `outputs` (None: every point and link).
    #[pyo3(signature = (outputs=None))]
    fn plan(&self, outputs: Option<Vec<String>>) -> PyResult<PyPlan> {
        Ok(PyPlan { inner: self.inner.plan(outputs.as_deref()).map_err(err)? })
    }
}

/// The scene as the core takes it (a linear input's kind by name).
#[allow(clippy::too_many_arguments)]
fn spec_of(
    points: Vec<(String, (f64, f64))>,
    links: Vec<(String, Vec<String>)>,
    ground: String,
    input: Named,
    output: Option<Named>,
    slots: Vec<(String, Joint)>,
    prismatic: Vec<(String, Joint)>,
    linear_input: Option<Named>,
) -> PyResult<SceneSpec> {
    let linear_input = match linear_input {
        None => None,
        Some((kind, name)) => Some((
            match kind.as_str() {
                "slot" => LinearKind::Slot,
                "prismatic" => LinearKind::Prismatic,
                other => {
                    return Err(err(Error::Scene {
                        entry: "input".into(),
                        message: format!("unknown linear input kind {other:?}"),
                    }))
                }
            },
            name,
        )),
    };
    Ok(SceneSpec {
        points: points.into_iter().map(|(n, (x, y))| (n, [x, y])).collect(),
        links,
        ground,
        input,
        output,
        slots: slots.into_iter().map(|(n, j)| (n, j.into())).collect(),
        prismatic: prismatic.into_iter().map(|(n, j)| (n, j.into())).collect(),
        linear_input,
    })
}

/// The exact points, in the order given, and how far each moved.
type SketchOut = (Vec<(f64, f64)>, Vec<f64>);

/// A sketch (the scene's arguments, its points roughly drawn) and its `lengths` ->
/// (exact points in the given order, how far each moved).
#[pyfunction]
#[pyo3(signature = (points, links, ground, input, output, slots, prismatic, linear_input, lengths))]
#[allow(clippy::too_many_arguments)]
fn sketch(
    py: Python<'_>,
    points: Vec<(String, (f64, f64))>,
    links: Vec<(String, Vec<String>)>,
    ground: String,
    input: Named,
    output: Option<Named>,
    slots: Vec<(String, Joint)>,
    prismatic: Vec<(String, Joint)>,
    linear_input: Option<Named>,
    lengths: Vec<(String, String, f64)>,
) -> PyResult<SketchOut> {
    let spec = spec_of(points, links, ground, input, output, slots, prismatic, linear_input)?;
    let s = Signals::detach(py, |signals| assemble_sketch(spec, &lengths, signals))?;
    Ok((s.points.into_iter().map(|[x, y]| (x, y)).collect(), s.moved))
}

/// A compiled plan.
#[pyclass(frozen, module = "planarkin._core", name = "Plan")]
pub(crate) struct PyPlan {
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
    #[allow(clippy::too_many_arguments)]
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
        let (npn, nln, nsn) = (grid_len(what, n, 2 * np)?, grid_len(what, n, nl)?, grid_len(what, n, ns)?);
        let mut points = zeros(what, npn)?;
        let mut angles = zeros(what, nln)?;
        let (mut status, mut nit, mut det, mut limit) =
            (zeros(what, n)?, zeros(what, n)?, zeros(what, n)?, zeros(what, n)?);
        let (mut step_status, mut step_det, mut point_status) =
            (zeros(what, nsn)?, zeros(what, nsn)?, zeros(what, npn / 2)?);
        let mut vel = omega.map(|_| Ok::<_, PyErr>((zeros(what, npn)?, zeros(what, nln)?))).transpose()?;
        let mut acc = omega.map(|_| Ok::<_, PyErr>((zeros(what, npn)?, zeros(what, nln)?))).transpose()?;
        Signals::detach(py, |signals| {
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
                acceleration: acc.as_mut().map(|(v, w)| (v.as_mut_slice(), w.as_mut_slice())),
            };
            plan.sweep(t, &opts, out, signals)
        })?;
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

type AssemblyOut<'py> = (Arr2<'py, f64>, String, f64, Vec<f64>);
type AssembliesOut<'py> = (Vec<AssemblyOut<'py>>, Vec<Vec<usize>>, Vec<Vec<usize>>, usize, usize);
type TraceOut<'py> = (Arr1<'py, f64>, Arr3<'py, f64>, Arr1<'py, f64>, Vec<f64>, bool);
type CircuitOut<'py> = (Vec<usize>, Vec<f64>, f64, (f64, f64), TraceOut<'py>);

/// The (x, y) pairs as one flat vector, allocated fallibly (a trace can be long).
fn flat(what: &str, pts: &[[f64; 2]]) -> PyResult<Vec<f64>> {
    let mut v = zeros(what, 2 * pts.len())?;
    for (d, p) in v.chunks_exact_mut(2).zip(pts) {
        d.copy_from_slice(p);
    }
    Ok(v)
}

fn assemblies_out(py: Python<'_>, a: Assemblies) -> PyResult<AssembliesOut<'_>> {
    let list = a
        .list
        .into_iter()
        .map(|x| Ok((grid(py, x.points.len(), 2, flat("assembly points", &x.points)?), x.label, x.det, x.step_det)))
        .collect::<PyResult<_>>()?;
    Ok((list, a.complex_counts, a.paths, a.failed_paths, a.continua))
}

fn trace_out(py: Python<'_>, t: Trace, np: usize) -> PyResult<TraceOut<'_>> {
    let m = t.theta.len();
    let pts = cube(py, (m, np, 2), flat("trace points", &t.points)?);
    Ok((t.theta.into_pyarray(py), pts, t.det.into_pyarray(py), t.turning_points, t.closed))
}

fn points_of(name: &str, a: &PyReadonlyArray2<'_, f64>) -> PyResult<Vec<[f64; 2]>> {
    let v = a.as_array();
    if v.ncols() != 2 {
        return Err(array(name, "must have shape (P, 2)"));
    }
    Ok(v.rows().into_iter().map(|r| [r[0], r[1]]).collect())
}

/// Adds the scene classes to the extension module.
pub(crate) fn register(m: &Bound<'_, PyModule>) -> PyResult<()> {
    m.add_class::<PyScene>()?;
    m.add_class::<PyPlan>()?;
    m.add_function(wrap_pyfunction!(sketch, m)?)?;
    Ok(())
}
