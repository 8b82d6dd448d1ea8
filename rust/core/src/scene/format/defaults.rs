//! The defaults a scene is solved with where the caller gives none, and the values they
//! are computed from (the drawing's size, the default inputs), for every binding alike.

use std::f64::consts::{PI, TAU};

use crate::error::Error;
use crate::scene::branches::{DEFAULT_MAX_POINTS, DEFAULT_STEP};
use crate::scene::{SceneSweepOptions, TraceOptions, Xy};
use crate::solve::homotopy::{HomotopyOptions, DEFAULT_RUNS, DEFAULT_SEED};
use crate::solve::newton::{NewtonOptions, DEFAULT_MAX_ITER, DEFAULT_TOL};

// the solvers' own defaults (their `Default` options), as the bindings take them
/// Newton's tolerance.
pub const TOL: f64 = DEFAULT_TOL;
/// Newton's steps at most.
pub const MAX_ITER: i64 = DEFAULT_MAX_ITER as i64;
/// Largest continuation step of an angle input (3 degrees, as `math.radians(3.0)`); a
/// linear input's is this times the drawing's size.
pub const MAX_STEP: f64 = 3.0 * (PI / 180.0);
/// Seed of the homotopy's random gammas (results are reproducible).
pub const SEED: u64 = DEFAULT_SEED;
/// Homotopy runs merged.
pub const RUNS: i64 = DEFAULT_RUNS as i64;
/// Largest arclength step of a trace (radians of rotation, all links together).
pub const TRACE_STEP: f64 = DEFAULT_STEP;
/// Points of a trace at most.
pub const TRACE_MAX_POINTS: i64 = DEFAULT_MAX_POINTS as i64;
/// Input values of the default sweep.
pub const SWEEP_LEN: usize = 361;

/// The drawing's extent: its bounding box's larger side (0 for no points).
pub fn size(points: &[Xy]) -> f64 {
    let (mut lo, mut hi) = ([f64::INFINITY; 2], [f64::NEG_INFINITY; 2]);
    for p in points {
        for k in 0..2 {
            lo[k] = lo[k].min(p[k]);
            hi[k] = hi[k].max(p[k]);
        }
    }
    if points.is_empty() {
        return 0.0;
    }
    (hi[0] - lo[0]).max(hi[1] - lo[1])
}

/// The default largest continuation step: [`MAX_STEP`], times `size` for a linear input.
pub fn max_step(linear: bool, size: f64) -> f64 {
    if linear {
        MAX_STEP * size
    } else {
        MAX_STEP
    }
}

/// A sweep's default options ([`TOL`], [`MAX_ITER`], [`max_step`], no rates).
pub fn sweep_options(linear: bool, size: f64) -> Result<SceneSweepOptions, Error> {
    SceneSweepOptions::new(NewtonOptions::new(TOL, MAX_ITER)?, max_step(linear, size), None)
}

/// The homotopy's default options ([`SEED`], [`RUNS`]).
pub fn homotopy_options() -> Result<HomotopyOptions, Error> {
    HomotopyOptions::new(SEED, RUNS)
}

/// A trace's default options ([`TRACE_STEP`], [`TRACE_MAX_POINTS`]).
pub fn trace_options() -> Result<TraceOptions, Error> {
    TraceOptions::new(TRACE_STEP, TRACE_MAX_POINTS)
}

/// `numpy.linspace(lo, hi, n)`, bit for bit: `i * step + lo`, the last value `hi`.
pub fn linspace(lo: f64, hi: f64, n: usize) -> Vec<f64> {
    match n {
        0 => Vec::new(),
        1 => vec![lo],
        _ => {
            let div = (n - 1) as f64;
            let delta = hi - lo;
            let step = delta / div;
            let mut v: Vec<f64> = if step == 0.0 {
                // NumPy's way when the step underflows: scale after dividing
                (0..n).map(|i| i as f64 / div * delta + lo).collect()
            } else {
                (0..n).map(|i| i as f64 * step + lo).collect()
            };
            v[n - 1] = hi;
            v
        }
    }
}

/// The default sweep's inputs: [`SWEEP_LEN`] angles from the drawn `input_angle` through
/// one full turn, or, for a linear input, [`SWEEP_LEN`] displacements across its `stroke`.
pub fn default_inputs(input_angle: f64, stroke: Option<(f64, f64)>) -> Vec<f64> {
    match stroke {
        Some((lo, hi)) => linspace(lo, hi, SWEEP_LEN),
        None => (0..SWEEP_LEN).map(|k| input_angle + k as f64 * (TAU / 360.0)).collect(),
    }
}
