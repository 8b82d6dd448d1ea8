//! Bindings of the scene solver, mirroring the core's `scene/`: here the `Scene` class
//! (validation, the format's defaults) and `load_scene`; `sweep` (the compiled `Plan`),
//! `branches` (assemblies, trace, circuits), `gradient` and `format` (Python data to the
//! file format). Convert, release the GIL, map errors; nothing numeric.

use numpy::{IntoPyArray, PyReadonlyArray1, PyReadonlyArray2, PyReadonlyArray3};
use planarkin_core::scene::format::{self as core_format, Drive, Parsed, Value};
use planarkin_core::scene::Scene;
use pyo3::prelude::*;
use pyo3::types::{PyDict, PyString, PyTuple};

// As in the core: this entry (the `Scene` class) calls `sweep` (the `Plan` class),
// `branches` and `gradient`; `format` converts Python data for the file format.
mod branches;
mod format;
mod gradient;
mod sweep;

use crate::buffers::{Arr1, Arr2};
use crate::errors::{array, err, Signals};

use branches::{AssembliesOut, CircuitOut, TraceOut};
use format::value_of;
use sweep::PyPlan;

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
/// (a dict name -> (x, y), exact for a sketch), links (a dict name -> tuple of point names,
/// the same str objects), ground, input, output, outputs, slots, prismatic pairs,
/// lengths, how far a sketch's points moved, and the `units` table, `loads` and `limits` (plain
/// data, normalised by the core; None where not given).
type Loaded<'py> = (
    PyScene,
    (Option<String>, Option<String>, Option<String>),
    Bound<'py, PyDict>,
    Bound<'py, PyDict>,
    String,
    DriveOut,
    Option<DriveOut>,
    Option<Vec<String>>,
    Vec<(String, Joint)>,
    Vec<(String, Joint)>,
    Option<Vec<(String, String, f64)>>,
    (Option<Vec<f64>>, Bound<'py, PyAny>, Bound<'py, PyAny>, Bound<'py, PyAny>),
);

fn drive_out(d: &Drive) -> DriveOut {
    match d {
        Drive::Angle { link, pivot } => vec![("link".into(), link.clone()), ("pivot".into(), pivot.clone())],
        Drive::Linear { kind, name } => vec![(core_format::kind_name(*kind).into(), name.clone())],
    }
}

/// A scene from the file format's data (any mapping; the core checks every entry, in
/// Python's words), a sketch's `lengths` assembled into the exact pose.
#[pyfunction]
fn load_scene<'py>(py: Python<'py>, data: &Bound<'_, PyAny>) -> PyResult<Loaded<'py>> {
    loaded(py, &value_of(data, 1)?)
}

/// `load_scene` of a JSON file's text, read in the core (`name` defaulting to `stem`, as
/// `Scene.load` names a scene); None where the text is not plain JSON the core's reader
/// takes (Python's `json` then reads it and words the error).
#[pyfunction]
fn load_scene_json<'py>(py: Python<'py>, text: &str, stem: &str) -> PyResult<Option<Loaded<'py>>> {
    let Some(mut data) = core_format::read_json(text) else { return Ok(None) };
    if let Value::Map(m) = &mut data {
        let name = Value::Str(stem.to_owned());
        match m.iter_mut().find(|(k, _)| k.as_str() == Some("name")) {
            Some((_, v)) if matches!(v, Value::Null) => *v = name,
            Some(_) => {}
            None => m.push((Value::Str("name".into()), name)),
        }
    }
    loaded(py, &data).map(Some)
}

fn loaded<'py>(py: Python<'py>, data: &Value) -> PyResult<Loaded<'py>> {
    let mut parsed = core_format::parse(data).map_err(err)?;
    let moved = match parsed.lengths {
        None => None,
        Some(_) => Signals::detach(py, |signals| parsed.assemble(signals))?,
    };
    let Parsed { spec, name, description, units, unit_table, input, output, outputs, lengths, loads, limits } = parsed;
    let none = || py.None().into_bound(py);
    let (table, loads) = (
        unit_table.map_or_else(|| Ok(none()), |u| format::to_py(py, &u.to_value()))?,
        loads.map_or_else(|| Ok(none()), |l| format::to_py(py, &l.to_value()))?,
    );
    let ground = spec.ground.clone();
    let joint = |(n, (a, g, l)): (&String, (&String, &String, &(String, String)))| {
        (n.clone(), (a.clone(), g.clone(), l.clone()))
    };
    let slots = spec.slots.iter().map(|(n, j)| joint((n, (&j.point, &j.guide, &j.line)))).collect();
    let prismatic = spec.prismatic.iter().map(|(n, j)| joint((n, (&j.link, &j.guide, &j.line)))).collect();
    let inner = Scene::new(spec).and_then(|s| s.with_limits(&limits)).map_err(err)?;
    let (points, links) = drawing(py, &inner)?;
    let limits = if limits.is_empty() {
        none()
    } else {
        let table = limits.iter().map(|l| (Value::Str(l.name.clone()), l.to_value())).collect();
        format::to_py(py, &Value::Map(table))?
    };
    let (inp, out) = (drive_out(&input), output.as_ref().map(drive_out));
    let scene = PyScene { inner, output };
    Ok((
        scene,
        (name, description, units),
        points,
        links,
        ground,
        inp,
        out,
        outputs,
        slots,
        prismatic,
        lengths,
        (moved, table, loads, limits),
    ))
}

/// The scene's points (name -> (x, y)) and links (name -> tuple of point names) as Python
/// dicts, each point's name one str object wherever it appears.
fn drawing<'py>(py: Python<'py>, sc: &Scene) -> PyResult<(Bound<'py, PyDict>, Bound<'py, PyDict>)> {
    let names: Vec<Bound<'py, PyString>> = sc.point_names().iter().map(|n| PyString::new(py, n)).collect();
    let points = PyDict::new(py);
    for (n, [x, y]) in names.iter().zip(sc.drawn()) {
        points.set_item(n, (*x, *y))?;
    }
    let links = PyDict::new(py);
    for l in sc.links() {
        links.set_item(&l.name, PyTuple::new(py, l.points.iter().map(|&p| &names[p]))?)?;
    }
    Ok((points, links))
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
        core_format::size(self.inner.drawn())
    }

    /// The default largest continuation step (3 degrees, or 3 degrees x size for a
    /// linear input).
    #[getter]
    fn max_step(&self) -> f64 {
        core_format::max_step(self.inner.linear_input().is_some(), core_format::size(self.inner.drawn()))
    }

    /// The default sweep's inputs: 361 angles from the drawn one through a full turn, or
    /// 361 displacements across a linear input's `stroke` (lo, hi).
    #[pyo3(signature = (stroke=None))]
    fn default_inputs<'py>(&self, py: Python<'py>, stroke: Option<(f64, f64)>) -> Arr1<'py, f64> {
        core_format::default_inputs(self.inner.input_angle(), stroke).into_pyarray(py)
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
        Ok(core_format::linear_output(&self.inner, o, &points, c).map(|v| v.into_pyarray(py)))
    }

    /// Every real assembly at `theta`: ([(points (P,2), label, det, step_det)],
    /// complex counts per group step, failed homotopy paths).
    #[pyo3(signature = (theta, seed, runs))]
    fn assemblies<'py>(&self, py: Python<'py>, theta: f64, seed: u64, runs: i64) -> PyResult<AssembliesOut<'py>> {
        branches::assemblies(py, &self.inner, theta, seed, runs)
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
        branches::trace(py, &self.inner, start, step, max_points)
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
        gradient::poses(py, &self.inner, points, free, relative)
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
        gradient::dets(py, &self.inner, points, dpoints, free, outputs)
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
        branches::circuits(py, &self.inner, theta, seed, runs, step, max_points)
    }

    /// Compiles the plan for `outputs` (None: every point and link).
    #[pyo3(signature = (outputs=None))]
    fn plan(&self, outputs: Option<Vec<String>>) -> PyResult<PyPlan> {
        sweep::plan(&self.inner, outputs)
    }
}

/// Adds the scene format's keys and defaults and the scene classes to the extension module.
pub(crate) fn register(m: &Bound<'_, PyModule>) -> PyResult<()> {
    format::register(m)?;
    m.add_class::<PyScene>()?;
    m.add_class::<PyPlan>()?;
    m.add_function(wrap_pyfunction!(load_scene, m)?)?;
    m.add_function(wrap_pyfunction!(load_scene_json, m)?)?;
    Ok(())
}
