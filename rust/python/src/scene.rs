//! Bindings of the scene solver: `Scene` (validation, assemblies, trace, circuits) and
//! its compiled `Plan` (sweeps). Convert, release the GIL, map errors; nothing numeric.

use numpy::{IntoPyArray, PyReadonlyArray1, PyReadonlyArray2, PyReadonlyArray3};
use planarkin_core::scene::format::{self, Drive, Parsed};
use planarkin_core::scene::{
    Assemblies, Plan, Scene, ScenePredictor, SceneSweepBuffers, SceneSweepOptions, Trace, TraceOptions,
};
use planarkin_core::solve::homotopy::HomotopyOptions;
use planarkin_core::NewtonOptions;
use pyo3::prelude::*;

use crate::buffers::{cube, grid, grid_len, slice, zeros, Arr1, Arr2, Arr3, HugePages};
use crate::errors::{array, err, Signals};
use crate::format::value_of;

/// A validated scene (see `planarkin.Scene`, which wraps it); made by `load_scene`.
#[pyclass(frozen, module = "planarkin._core", name = "Scene")]
pub(crate) struct PyScene {
    inner: Scene,
    /// The output as the file declares it (a linear one is not in the core's scene).
    output: Option<Drive>,
}

/// A slot (point, guide, line) or a prismatic pair (link, guide, line).
type Joint = (String, String, (String, String));
/// An input or output as the entries of its table, in order.
type DriveOut = Vec<(String, String)>;
/// What `load_scene` reads besides the scene: (name, description, units), the points
/// (exact for a sketch), links, ground, input, output, outputs, slots, prismatic pairs,
/// lengths and how far a sketch's points moved.
type Loaded = (
    PyScene,
    (Option<String>, Option<String>, Option<String>),
    Vec<(String, (f64, f64))>,
    Vec<(String, Vec<String>)>,
    String,
    DriveOut,
    Option<DriveOut>,
    Option<Vec<String>>,
    Vec<(String, Joint)>,
    Vec<(String, Joint)>,
    Option<Vec<(String, String, f64)>>,
    Option<Vec<f64>>,
);

fn drive_out(d: &Drive) -> DriveOut {
    match d {
        Drive::Angle { link, pivot } => vec![("link".into(), link.clone()), ("pivot".into(), pivot.clone())],
        Drive::Linear { kind, name } => vec![(format::kind_name(*kind).into(), name.clone())],
    }
}

/// A scene from the file format's data (any mapping; the core checks every entry, in
/// Python's words), a sketch's `lengths` assembled into the exact pose.
#[pyfunction]
fn load_scene(py: Python<'_>, data: &Bound<'_, PyAny>) -> PyResult<Loaded> {
    let mut parsed = format::parse(&value_of(data, 1)?).map_err(err)?;
    let moved = match parsed.lengths {
        None => None,
        Some(_) => Signals::detach(py, |signals| parsed.assemble(signals))?,
    };
    let Parsed { spec, name, description, units, input, output, outputs, lengths } = parsed;
    let points = spec.points.iter().map(|(n, [x, y])| (n.clone(), (*x, *y))).collect();
    let links = spec.links.clone();
    let ground = spec.ground.clone();
    let joint = |(n, (a, g, l)): (&String, (&String, &String, &(String, String)))| {
        (n.clone(), (a.clone(), g.clone(), l.clone()))
    };
    let slots = spec.slots.iter().map(|(n, j)| joint((n, (&j.point, &j.guide, &j.line)))).collect();
    let prismatic = spec.prismatic.iter().map(|(n, j)| joint((n, (&j.link, &j.guide, &j.line)))).collect();
    let inner = Scene::new(spec).map_err(err)?;
    let (inp, out) = (drive_out(&input), output.as_ref().map(drive_out));
    let scene = PyScene { inner, output };
    Ok((scene, (name, description, units), points, links, ground, inp, out, outputs, slots, prismatic, lengths, moved))
}

#[pymethods]
impl PyScene {
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

    /// The drawing's extent: its bounding box's larger side (scene units).
    #[getter]
    fn size(&self) -> f64 {
        format::size(self.inner.drawn())
    }

    /// The default largest continuation step (3 degrees, or 3 degrees x size for a
    /// linear input).
    #[getter]
    fn max_step(&self) -> f64 {
        format::max_step(self.inner.linear_input().is_some(), format::size(self.inner.drawn()))
    }

    /// The default sweep's inputs: 361 angles from the drawn one through a full turn, or
    /// 361 displacements across a linear input's `stroke` (lo, hi).
    #[pyo3(signature = (stroke=None))]
    fn default_inputs<'py>(&self, py: Python<'py>, stroke: Option<(f64, f64)>) -> Arr1<'py, f64> {
        format::default_inputs(self.inner.input_angle(), stroke).into_pyarray(py)
    }

    /// A declared linear output's coordinate along a sweep whose `coords` (N, P, 2) hold
    /// the scene points `points`; None for an angle output, none, or points not reported.
    fn linear_output<'py>(
        &self,
        py: Python<'py>,
        points: Vec<usize>,
        coords: PyReadonlyArray3<'py, f64>,
    ) -> PyResult<Option<Arr1<'py, f64>>> {
        let Some(o) = &self.output else { return Ok(None) };
        let c = coords.as_slice().map_err(|_| array("coords", "must be a C-contiguous float64 array"))?;
        Ok(format::linear_output(&self.inner, o, &points, c).map(|v| v.into_pyarray(py)))
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
    m.add_function(wrap_pyfunction!(load_scene, m)?)?;
    Ok(())
}
