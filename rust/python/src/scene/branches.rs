//! Bindings of the core's `scene/branches`: every assembly at one input value, the trace
//! of one branch and the circuits, as NumPy arrays and tuples.

use numpy::{IntoPyArray, PyReadonlyArray2};
use planarkin_core::scene::{Assemblies, Scene, Trace, TraceOptions};
use planarkin_core::solve::homotopy::HomotopyOptions;
use pyo3::prelude::*;

use crate::buffers::{cube, grid, points_of, zeros, Arr1, Arr2, Arr3};
use crate::errors::{err, Signals};

type AssemblyOut<'py> = (Arr2<'py, f64>, String, f64, Vec<f64>);
pub(super) type AssembliesOut<'py> = (Vec<AssemblyOut<'py>>, Vec<Vec<usize>>, Vec<Vec<usize>>, usize, usize);
pub(super) type TraceOut<'py> = (Arr1<'py, f64>, Arr3<'py, f64>, Arr1<'py, f64>, Vec<f64>, bool, Vec<f64>);
pub(super) type CircuitOut<'py> = (Vec<usize>, Vec<f64>, f64, (f64, f64), TraceOut<'py>);

/// `Scene.assemblies`: every real assembly at `theta`.
pub(super) fn assemblies<'py>(
    py: Python<'py>,
    scene: &Scene,
    theta: f64,
    seed: u64,
    runs: i64,
) -> PyResult<AssembliesOut<'py>> {
    let opts = HomotopyOptions::new(seed, runs).map_err(err)?;
    let a = Signals::detach(py, |signals| scene.assemblies(theta, &opts, signals))?;
    assemblies_out(py, a)
}

/// `Scene.trace`: one branch traced from `start` (None: the drawn pose).
pub(super) fn trace<'py>(
    py: Python<'py>,
    scene: &Scene,
    start: Option<PyReadonlyArray2<'py, f64>>,
    step: f64,
    max_points: i64,
) -> PyResult<TraceOut<'py>> {
    let opts = TraceOptions::new(step, max_points).map_err(err)?;
    let start = start.map(|a| points_of("start", &a)).transpose()?;
    let t = Signals::detach(py, |signals| scene.trace(start.as_deref(), &opts, signals))?;
    trace_out(py, t, scene.point_names().len())
}

/// `Scene.circuits`: the assemblies at `theta` and the circuits joining them.
pub(super) fn circuits<'py>(
    py: Python<'py>,
    scene: &Scene,
    theta: f64,
    seed: u64,
    runs: i64,
    step: f64,
    max_points: i64,
) -> PyResult<(AssembliesOut<'py>, Vec<CircuitOut<'py>>)> {
    let hopts = HomotopyOptions::new(seed, runs).map_err(err)?;
    let topts = TraceOptions::new(step, max_points).map_err(err)?;
    let (a, cs) = Signals::detach(py, |signals| scene.circuits(theta, &hopts, &topts, signals))?;
    let np = scene.point_names().len();
    let circuits = cs
        .into_iter()
        .map(|c| Ok((c.assemblies, c.turning_points, c.net_turn, c.range, trace_out(py, c.trace, np)?)))
        .collect::<PyResult<_>>()?;
    Ok((assemblies_out(py, a)?, circuits))
}

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
    Ok((t.theta.into_pyarray(py), pts, t.det.into_pyarray(py), t.turning_points, t.closed, t.limits))
}
