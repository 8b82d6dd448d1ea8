//! Bindings of the core's `scene/gradient`: exact derivatives of solved poses and of their
//! conditioning by the free drawn coordinates (what synthesis asks for).

use numpy::{PyReadonlyArray1, PyReadonlyArray2};
use planarkin_core::scene::Scene;
use pyo3::prelude::*;

use crate::buffers::{grid, points_of, slice, zeros, Arr2};
use crate::errors::{array, err};

/// `Scene.pose_gradient`: (N * P, 2 * F), NaN for a pose that is not finite or singular.
pub(super) fn poses<'py>(
    py: Python<'py>,
    scene: &Scene,
    points: PyReadonlyArray2<'py, f64>,
    free: Vec<(usize, usize)>,
    relative: bool,
) -> PyResult<Arr2<'py, f64>> {
    let np = scene.point_names().len();
    let pts = points_of("points", &points)?;
    if np > 0 && pts.len() % np != 0 {
        return Err(array("points", format!("must hold whole poses of {np} points")));
    }
    let nf = free.len();
    if nf == 0 || np == 0 {
        return Ok(grid(py, pts.len(), 2 * nf, Vec::new()));
    }
    let mut out = zeros("pose gradients", pts.len() * 2 * nf)?;
    py.detach(|| scene.poses_gradient(&pts, &free, relative, &mut out)).map_err(err)?;
    Ok(grid(py, pts.len(), 2 * nf, out))
}

/// `Scene.dets_gradient`: (N, F), NaN where a pose is not finite.
pub(super) fn dets<'py>(
    py: Python<'py>,
    scene: &Scene,
    points: PyReadonlyArray2<'py, f64>,
    dpoints: PyReadonlyArray1<'py, f64>,
    free: Vec<(usize, usize)>,
    outputs: Option<Vec<String>>,
) -> PyResult<Arr2<'py, f64>> {
    let np = scene.point_names().len();
    let pts = points_of("points", &points)?;
    let nf = free.len();
    if np == 0 || pts.len() % np != 0 {
        return Err(array("points", format!("must hold whole poses of {np} points")));
    }
    let d = slice("dpoints", &dpoints)?;
    if d.len() != pts.len() * 2 * nf {
        return Err(array("dpoints", format!("must hold {} values, the derivatives of points", pts.len() * 2 * nf)));
    }
    let n = pts.len() / np;
    let mut out = zeros("conditioning gradients", n * nf)?;
    py.detach(|| scene.dets_gradient(outputs.as_deref(), &pts, d, &free, &mut out)).map_err(err)?;
    Ok(grid(py, n, nf, out))
}
