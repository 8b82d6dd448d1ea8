//! Bindings of the atlas: a shard of entries, a curve's descriptor, an entry's curve and
//! pose, and the placement of many candidates onto a target. Convert, release the GIL,
//! map errors; nothing numeric.

use numpy::{IntoPyArray, PyReadonlyArray1, PyReadonlyArray2, PyUntypedArrayMethods};
use planarkin_core::atlas::{
    build_shard, coupler_curve, describe, match_curves, match_many, pose, pose_names, Curve, Placement, Search,
    Topology, DESCRIPTOR, HARMONICS, SAMPLES,
};
use planarkin_core::Error;
use pyo3::prelude::*;

use crate::buffers::{grid, points_of, Arr1, Arr2};
use crate::errors::{err, Signals};

fn topology(name: &str) -> PyResult<Topology> {
    Topology::from_name(name).map_err(err)
}

/// A candidate's topology, parameters and signs, checked against each other: copied (a
/// dozen numbers), so any layout will do, a strided view or a buffer Dask unpickled unaligned.
fn row(
    name: &str,
    p: &PyReadonlyArray1<'_, f64>,
    s: &PyReadonlyArray1<'_, f64>,
) -> PyResult<(Topology, Vec<f64>, Vec<f64>)> {
    let t = topology(name)?;
    let (p, s) = (p.as_array().to_vec(), s.as_array().to_vec());
    let bad = |name: &str, got, expected| err(Error::Shape { name: name.into(), got, expected });
    if p.len() != t.params() {
        return Err(bad("params", p.len(), t.params()));
    }
    if s.len() != t.signs() {
        return Err(bad("signs", s.len(), t.signs()));
    }
    Ok((t, p, s))
}

/// `offsets` starts and a target resampled to `resolution` points, searched finely near
/// the best from [`Search::FINE`]'s resolution on.
fn search(offsets: usize, resolution: usize) -> Search {
    Search { offsets, resolution, local: resolution >= Search::FINE.resolution }
}

type ShardOut<'py> = (Arr2<'py, f64>, Arr2<'py, i8>, Arr1<'py, bool>, Arr1<'py, f64>, Arr2<'py, f32>);

/// Entries start..start + count of the atlas of `topology` drawn from `seed`:
/// (params, signs, full_turn, conditioning, descriptor).
#[pyfunction]
fn atlas_shard<'py>(
    py: Python<'py>,
    topology_name: &str,
    seed: u64,
    start: u64,
    count: usize,
) -> PyResult<ShardOut<'py>> {
    let t = topology(topology_name)?;
    let s = Signals::detach(py, |signals| build_shard(t, seed, start, count, signals))?;
    Ok((
        grid(py, count, t.params(), s.params),
        grid(py, count, t.signs(), s.signs),
        s.full_turn.into_pyarray(py),
        s.conditioning.into_pyarray(py),
        grid(py, count, DESCRIPTOR, s.descriptor),
    ))
}

/// The descriptor of the curve through `points` (n, 2); None where it has no extent.
#[pyfunction]
fn atlas_describe<'py>(
    py: Python<'py>,
    points: PyReadonlyArray2<'py, f64>,
    closed: bool,
) -> PyResult<Option<Arr1<'py, f32>>> {
    let pts = points_of("points", &points)?;
    let mut out = [0.0f32; DESCRIPTOR];
    Ok(describe(&pts, closed, &mut out).then(|| out.to_vec().into_pyarray(py)))
}

type CurveOut<'py> = (Arr2<'py, f64>, Arr1<'py, f64>, bool, f64);

/// The coupler curve of one entry at `samples` input angles: (points, theta, closed,
/// conditioning); None where it assembles nowhere.
#[pyfunction]
fn atlas_curve<'py>(
    py: Python<'py>,
    topology_name: &str,
    params: PyReadonlyArray1<'py, f64>,
    signs: PyReadonlyArray1<'py, f64>,
    samples: usize,
) -> PyResult<Option<CurveOut<'py>>> {
    let (t, p, s) = row(topology_name, &params, &signs)?;
    if samples < 2 {
        return Err(err(Error::InvalidParameter {
            name: "samples".into(),
            requirement: "must be >= 2",
            value: samples.to_string(),
        }));
    }
    Ok(coupler_curve(t, &p, &s, samples).map(|c| {
        let n = c.points.len();
        let flat: Vec<f64> = c.points.iter().flatten().copied().collect();
        (grid(py, n, 2, flat), c.theta.into_pyarray(py), c.closed, c.conditioning)
    }))
}

type PoseOut<'py> = (Vec<&'static str>, Arr2<'py, f64>, f64);

/// The pose of one entry at input angle `theta`: (names, points (k, 2), conditioning);
/// None where it does not assemble.
#[pyfunction]
fn atlas_pose<'py>(
    py: Python<'py>,
    topology_name: &str,
    params: PyReadonlyArray1<'py, f64>,
    signs: PyReadonlyArray1<'py, f64>,
    theta: f64,
) -> PyResult<Option<PoseOut<'py>>> {
    let (t, p, s) = row(topology_name, &params, &signs)?;
    Ok(pose(t, &p, &s, theta).map(|q| {
        let flat: Vec<f64> = q.points[..q.count].iter().flatten().copied().collect();
        (pose_names(t).to_vec(), grid(py, q.count, 2, flat), q.conditioning)
    }))
}

type MatchOut<'py> = (Arr1<'py, f64>, Arr2<'py, f64>, Arr2<'py, f64>, Arr1<'py, f64>, Arr1<'py, bool>, Arr2<'py, f64>);

/// Places N candidates (params (N, P), signs (N, S)) onto the target (n, 2), `offsets`
/// starts per direction and the target resampled to `resolution` points: per
/// candidate (cost, a, b, fraction, reversed, theta (n,)); cost NaN where none fits.
#[pyfunction]
fn atlas_match<'py>(
    py: Python<'py>,
    topology_name: &str,
    params: PyReadonlyArray2<'py, f64>,
    signs: PyReadonlyArray2<'py, f64>,
    target: PyReadonlyArray2<'py, f64>,
    closed: bool,
    offsets: usize,
    resolution: usize,
) -> PyResult<MatchOut<'py>> {
    let t = topology(topology_name)?;
    let pts = points_of("target", &target)?;
    let (p, s) = (
        params.as_slice().map_err(|_| err(Error::array("params", "must be C-contiguous float64")))?,
        signs.as_slice().map_err(|_| err(Error::array("signs", "must be C-contiguous float64")))?,
    );
    if params.shape()[1] != t.params() {
        return Err(err(Error::array("params", format!("must have {} columns for {}", t.params(), t.name()))));
    }
    let n = params.shape()[0];
    let m = pts.len();
    let found = Signals::detach(py, |signals| {
        match_many(t, p, s, SAMPLES, &pts, closed, search(offsets, resolution), signals)
    })?;
    Ok(placements(py, found, n, m))
}

/// The placements as columns (NaN and false where a candidate has none).
fn placements(py: Python<'_>, found: Vec<Option<Placement>>, n: usize, m: usize) -> MatchOut<'_> {
    let (mut cost, mut a, mut b) = (vec![f64::NAN; n], vec![f64::NAN; 2 * n], vec![f64::NAN; 2 * n]);
    let (mut frac, mut rev, mut theta) = (vec![f64::NAN; n], vec![false; n], vec![f64::NAN; n * m]);
    for (i, f) in found.into_iter().enumerate() {
        if let Some(pl) = f {
            cost[i] = pl.cost;
            a[2 * i..2 * i + 2].copy_from_slice(&pl.a);
            b[2 * i..2 * i + 2].copy_from_slice(&pl.b);
            frac[i] = pl.fraction;
            rev[i] = pl.reversed;
            theta[i * m..(i + 1) * m].copy_from_slice(&pl.theta);
        }
    }
    (
        cost.into_pyarray(py),
        grid(py, n, 2, a),
        grid(py, n, 2, b),
        frac.into_pyarray(py),
        rev.into_pyarray(py),
        grid(py, n, m, theta),
    )
}

/// Places curves already made onto the target: `points` (N, M, 2) flattened to (N * M, 2),
/// `theta` (N, M) their input angles (NaN past a curve's end), `closed` (N,) whether each
/// turns fully. Columns as `atlas_match`.
#[pyfunction]
fn atlas_match_curves<'py>(
    py: Python<'py>,
    points: PyReadonlyArray2<'py, f64>,
    theta: PyReadonlyArray2<'py, f64>,
    closed: Vec<bool>,
    target: PyReadonlyArray2<'py, f64>,
    target_closed: bool,
    offsets: usize,
    resolution: usize,
) -> PyResult<MatchOut<'py>> {
    let pts = points_of("points", &points)?;
    let tgt = points_of("target", &target)?;
    let th = theta.as_array();
    let (n, m) = (th.nrows(), th.ncols());
    // (each length named on its own: one message for both would read "expected 6, got 6")
    if pts.len() != n * m {
        return Err(err(Error::Shape { name: "points".into(), got: pts.len(), expected: n * m }));
    }
    if closed.len() != n {
        return Err(err(Error::Shape { name: "closed".into(), got: closed.len(), expected: n }));
    }
    let curves: Vec<Curve> = (0..n)
        .map(|i| {
            let (points, theta) = (0..m)
                .map(|j| (pts[i * m + j], th[[i, j]]))
                .filter(|(p, t)| t.is_finite() && p[0].is_finite() && p[1].is_finite())
                .unzip();
            Curve { points, theta, closed: closed[i], conditioning: f64::NAN }
        })
        .collect();
    let found = Signals::detach(py, |signals| {
        match_curves(&curves, &tgt, target_closed, search(offsets, resolution), signals)
    })?;
    Ok(placements(py, found, n, tgt.len()))
}

pub(crate) fn register(m: &Bound<'_, PyModule>) -> PyResult<()> {
    m.add_function(wrap_pyfunction!(atlas_shard, m)?)?;
    m.add_function(wrap_pyfunction!(atlas_describe, m)?)?;
    m.add_function(wrap_pyfunction!(atlas_curve, m)?)?;
    m.add_function(wrap_pyfunction!(atlas_pose, m)?)?;
    m.add_function(wrap_pyfunction!(atlas_match, m)?)?;
    m.add_function(wrap_pyfunction!(atlas_match_curves, m)?)?;
    m.add("ATLAS_DESCRIPTOR", DESCRIPTOR)?;
    m.add("ATLAS_HARMONICS", HARMONICS)?;
    m.add("ATLAS_SAMPLES", SAMPLES)?;
    let tops: Vec<(&str, usize, usize)> = Topology::ALL.iter().map(|t| (t.name(), t.params(), t.signs())).collect();
    m.add("ATLAS_TOPOLOGIES", tops)?;
    Ok(())
}
