//! Bindings of the core's `forces/`: the `ForceModel` class (the plain-data Newton-Euler
//! system of a scene with its loads, checked once) and its `run` along a sweep. Convert,
//! release the GIL, map errors; nothing numeric.

use numpy::{IntoPyArray, PyReadonlyArray1, PyReadonlyArrayDyn};
use planarkin_core::forces::{
    self as core_forces, Block, Direction, Drive, Element, Line, Loads, Mass, Model, Motion, Output, Parts, Table,
    UnitCouple, UnitForce,
};
use pyo3::prelude::*;

use crate::buffers::{grid, slice, Arr1, Arr2};
use crate::errors::{array, err};

/// A table: (input values, empty for a constant; values, row after row).
type TableIn = (Vec<f64>, Vec<f64>);
/// A unit force: (link, column, sign, point, kind 0 x / 1 y / 2 normal / 3 along, line).
type ForceIn = (usize, usize, f64, usize, u8, usize);
/// A spring or damper: (a, b, link of a, link of b, rate, free length, preload).
type ElementIn = (usize, usize, usize, usize, f64, f64, f64);
/// A mass: (link, a, b, arm as drawn, unit a -> b as drawn, mass, inertia).
type MassIn = (usize, usize, usize, (f64, f64), (f64, f64), f64, f64);
/// What `run` returns: unknowns (N, columns), status, virtual-work effort, ground (N, 3),
/// kinetic and potential energy, input power, mechanical advantage (None without an
/// output), the virtual-work check and the energy check (dynamics).
type RunOut<'py> = (
    Arr2<'py, f64>,
    Arr1<'py, i8>,
    Arr1<'py, f64>,
    Arr2<'py, f64>,
    Arr1<'py, f64>,
    Arr1<'py, f64>,
    Arr1<'py, f64>,
    Option<Arr1<'py, f64>>,
    f64,
    Option<f64>,
);

fn table(name: &str, t: &TableIn, width: usize, period: Option<f64>) -> PyResult<Table> {
    Table::new(name, &t.0, &t.1, width, period).map_err(err)
}

fn dyn_slice<'a>(name: &str, a: &'a PyReadonlyArrayDyn<'_, f64>) -> PyResult<&'a [f64]> {
    a.as_slice().map_err(|_| array(name, "must be a C-contiguous float64 array"))
}

/// A scene's Newton-Euler system and loads (see `planarkin.forces`, which builds it).
#[pyclass(frozen, module = "planarkin._core", name = "ForceModel")]
pub(crate) struct PyForceModel {
    inner: Model,
}

#[pymethods]
impl PyForceModel {
    #[new]
    #[pyo3(signature = (points, moving, size, refs, forces, couples, lines, blocks, point_forces,
        line_forces, torques, springs, dampers, gravity, masses, period, output))]
    #[allow(clippy::too_many_arguments)]
    fn new(
        points: usize,
        moving: usize,
        size: f64,
        refs: Vec<usize>,
        forces: Vec<ForceIn>,
        couples: Vec<(usize, usize, f64)>,
        lines: Vec<(usize, usize, usize)>,
        blocks: Vec<(Vec<usize>, Vec<usize>, Vec<usize>)>,
        point_forces: Vec<(usize, usize, TableIn)>,
        line_forces: Vec<(usize, usize, usize, TableIn)>,
        torques: Vec<(usize, TableIn)>,
        springs: Vec<ElementIn>,
        dampers: Vec<ElementIn>,
        gravity: Option<(f64, f64)>,
        masses: Vec<MassIn>,
        period: Option<f64>,
        output: Option<(bool, usize, usize)>,
    ) -> PyResult<Self> {
        let mut unit = Vec::with_capacity(forces.len());
        for (link, column, sign, point, kind, line) in forces {
            let dir = match kind {
                0 => Direction::X,
                1 => Direction::Y,
                2 => Direction::Normal(line),
                3 => Direction::Along(line),
                _ => return Err(array("forces", "kinds must be 0 (x), 1 (y), 2 (normal) or 3 (along)")),
            };
            unit.push(UnitForce { link, column, sign, point, dir });
        }
        let element = |e: ElementIn| Element {
            a: e.0,
            b: e.1,
            link_a: e.2,
            link_b: e.3,
            rate: e.4,
            free_length: e.5,
            preload: e.6,
        };
        let loads = Loads {
            point_forces: point_forces
                .iter()
                .map(|(k, q, t)| Ok((*k, *q, table("forces", t, 2, period)?)))
                .collect::<PyResult<_>>()?,
            line_forces: line_forces
                .iter()
                .map(|(j, q, k, t)| Ok((*j, *q, *k, table("forces", t, 1, period)?)))
                .collect::<PyResult<_>>()?,
            torques: torques.iter().map(|(k, t)| Ok((*k, table("torques", t, 1, period)?))).collect::<PyResult<_>>()?,
            springs: springs.into_iter().map(element).collect(),
            dampers: dampers.into_iter().map(element).collect(),
            gravity: gravity.map(|g| [g.0, g.1]),
            masses: masses
                .into_iter()
                .map(|m| Mass {
                    link: m.0,
                    a: m.1,
                    b: m.2,
                    arm: [m.3 .0, m.3 .1],
                    drawn: [m.4 .0, m.4 .1],
                    mass: m.5,
                    inertia: m.6,
                })
                .collect(),
        };
        let parts = Parts {
            points,
            moving,
            columns: 3 * moving,
            size,
            refs,
            forces: unit,
            couples: couples.into_iter().map(|(link, column, sign)| UnitCouple { link, column, sign }).collect(),
            lines: lines.into_iter().map(|(guide, a, b)| Line { guide, a, b }).collect(),
            blocks: blocks.into_iter().map(|(rows, columns, prior)| Block { rows, columns, prior }).collect(),
            loads,
            output: output.map(|(link, i, q)| if link { Output::Link(i) } else { Output::Line(i, q) }),
        };
        Ok(PyForceModel { inner: Model::new(parts).map_err(err)? })
    }

    /// Statics (`omega` None) or inverse dynamics along a sweep's arrays.
    #[pyo3(signature = (theta, status, det, coords, velocity, acceleration, angular_velocity,
        angular_acceleration, point_map, link_map, rate, omega=None, alpha=None))]
    #[allow(clippy::too_many_arguments)]
    fn run<'py>(
        &self,
        py: Python<'py>,
        theta: PyReadonlyArray1<'py, f64>,
        status: PyReadonlyArray1<'py, i8>,
        det: PyReadonlyArray1<'py, f64>,
        coords: PyReadonlyArrayDyn<'py, f64>,
        velocity: PyReadonlyArrayDyn<'py, f64>,
        acceleration: Option<PyReadonlyArrayDyn<'py, f64>>,
        angular_velocity: PyReadonlyArrayDyn<'py, f64>,
        angular_acceleration: Option<PyReadonlyArrayDyn<'py, f64>>,
        point_map: Vec<usize>,
        link_map: Vec<usize>,
        rate: f64,
        omega: Option<PyReadonlyArray1<'py, f64>>,
        alpha: Option<PyReadonlyArray1<'py, f64>>,
    ) -> PyResult<RunOut<'py>> {
        let motion = Motion {
            theta: slice("theta", &theta)?,
            status: status.as_slice().map_err(|_| array("status", "must be a contiguous int8 array"))?,
            det: slice("det", &det)?,
            coords: dyn_slice("coords", &coords)?,
            velocity: dyn_slice("velocity", &velocity)?,
            acceleration: acceleration.as_ref().map(|a| dyn_slice("acceleration", a)).transpose()?,
            angular_velocity: dyn_slice("angular_velocity", &angular_velocity)?,
            angular_acceleration: angular_acceleration
                .as_ref()
                .map(|a| dyn_slice("angular_acceleration", a))
                .transpose()?,
            point_map: &point_map,
            link_map: &link_map,
            rate,
        };
        let drive = match (&omega, &alpha) {
            (Some(w), Some(a)) => Some(Drive { omega: slice("omega", w)?, alpha: slice("alpha", a)? }),
            (None, None) => None,
            _ => return Err(array("alpha", "must be given with omega (dynamics), or neither (statics)")),
        };
        let model = &self.inner;
        let out = py.detach(|| core_forces::solve(model, &motion, drive)).map_err(err)?;
        let n = motion.theta.len();
        let ma = model.has_output().then(|| out.advantage.into_pyarray(py));
        Ok((
            grid(py, n, model.columns(), out.unknowns),
            out.status.into_pyarray(py),
            out.virtual_work.into_pyarray(py),
            grid(py, n, 3, out.ground),
            out.kinetic.into_pyarray(py),
            out.potential.into_pyarray(py),
            out.input_power.into_pyarray(py),
            ma,
            out.check_virtual_work,
            out.check_energy,
        ))
    }
}

pub(crate) fn register(m: &Bound<'_, PyModule>) -> PyResult<()> {
    m.add_class::<PyForceModel>()?;
    Ok(())
}
