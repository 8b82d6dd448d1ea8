//! What a four-bar sweep takes and writes: its validated options (mode, Newton
//! criteria, predictor, method), the caller-owned output slices of one sweep, of its
//! optional velocities and accelerations, and of a batch, and the default crank angles.

use super::model::{Mode, Point};
use crate::error::{quoted, Error};
use crate::solve::newton::NewtonOptions;

/// How the next point's first guess is made from the last converged one.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub enum Predictor {
    /// The previous solution itself (zeroth order; the seeds' continuation).
    Previous,
    /// First order: x + dtheta2 * dx/dtheta2, with dx/dtheta2 = -J^-1 dF/dtheta2.
    Tangent,
    /// Second order: adds dtheta2^2 / 2 * d2x/dtheta2^2 from the acceleration solve.
    Quadratic,
    /// No continuation: every point starts from the requested mode's closed form at its own
    /// crank angle and is verified (and polished) by Newton with the mode check. Points do
    /// not depend on each other.
    ClosedForm,
}

impl Predictor {
    /// Parses "previous" / "tangent" / "quadratic" / "closed-form".
    pub fn parse(s: &str) -> Result<Self, Error> {
        match s {
            "previous" => Ok(Predictor::Previous),
            "tangent" => Ok(Predictor::Tangent),
            "quadratic" => Ok(Predictor::Quadratic),
            "closed-form" => Ok(Predictor::ClosedForm),
            other => Err(Error::invalid(
                "predictor",
                "must be 'previous', 'tangent', 'quadratic' or 'closed-form'",
                quoted(other),
            )),
        }
    }
}

/// How each point of a sweep is solved.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub enum Method {
    /// Newton-Raphson with continuation: the general solver (multi-loop linkages have no
    /// closed form).
    Newton,
    /// The four-bar's closed form: no iterations, no residual computed (NaN), the same
    /// statuses; fastest where it exists.
    ClosedForm,
}

impl Method {
    /// Parses "newton" / "closed-form".
    pub fn parse(s: &str) -> Result<Self, Error> {
        match s {
            "newton" => Ok(Method::Newton),
            "closed-form" => Ok(Method::ClosedForm),
            other => Err(Error::invalid("method", "must be 'newton' or 'closed-form'", quoted(other))),
        }
    }
}

/// Everything a sweep needs besides the linkage and the angles.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct SweepOptions {
    /// Assembly mode to solve at every point.
    pub mode: Mode,
    /// Newton stopping criteria (also the singular threshold of the closed form).
    pub newton: NewtonOptions,
    /// First-guess predictor (Newton only).
    pub predictor: Predictor,
    /// Newton-Raphson or the closed form.
    pub method: Method,
}

impl SweepOptions {
    /// Validates every option as the caller spells it: `mode` ("open" / "crossed"),
    /// `tol` (finite, > 0), `max_iter` (1..=u32::MAX), `predictor` and `method`; the error
    /// names the parameter.
    pub fn new(mode: &str, tol: f64, max_iter: i64, predictor: &str, method: &str) -> Result<Self, Error> {
        Ok(Self {
            mode: Mode::parse(mode)?,
            newton: NewtonOptions::new(tol, max_iter)?,
            predictor: Predictor::parse(predictor)?,
            method: Method::parse(method)?,
        })
    }
}

/// Output slices of one sweep, all of the length of the crank-angle array.
pub struct SweepOut<'a> {
    pub theta3: &'a mut [f64],
    pub theta4: &'a mut [f64],
    pub status: &'a mut [i8],
    pub nit: &'a mut [u32],
    pub residual: &'a mut [f64],
}

impl SweepOut<'_> {
    /// Writes point `i`.
    #[inline(always)]
    pub(crate) fn set(&mut self, i: usize, p: &Point) {
        self.theta3[i] = p.theta3;
        self.theta4[i] = p.theta4;
        self.status[i] = p.status.code();
        self.nit[i] = p.nit;
        self.residual[i] = p.residual;
    }
}

/// Optional velocity (and acceleration) outputs, computed only when asked for.
pub struct MotionOut<'a> {
    /// Crank angular velocity.
    pub omega2: f64,
    pub omega3: &'a mut [f64],
    pub omega4: &'a mut [f64],
    /// Crank angular acceleration and the alpha3, alpha4 outputs.
    pub alpha: Option<(f64, &'a mut [f64], &'a mut [f64])>,
}

/// (M, N) row-major outputs of a batch sweep.
pub struct BatchOut<'a> {
    pub theta3: &'a mut [f64],
    pub theta4: &'a mut [f64],
    pub status: &'a mut [i8],
    pub nit: &'a mut [u32],
    pub residual: &'a mut [f64],
}

pub(crate) fn check_len(name: &str, got: usize, expected: usize) -> Result<(), Error> {
    if got == expected {
        Ok(())
    } else {
        Err(Error::Shape { name: name.to_string(), got, expected })
    }
}

impl SweepOut<'_> {
    pub(crate) fn check(&self, n: usize) -> Result<(), Error> {
        check_len("theta3", self.theta3.len(), n)?;
        check_len("theta4", self.theta4.len(), n)?;
        check_len("status", self.status.len(), n)?;
        check_len("nit", self.nit.len(), n)?;
        check_len("residual", self.residual.len(), n)
    }
}

/// Default sweep angles: 0..=2 pi in `n - 1` equal steps (361 points: 1 degree apart).
pub fn default_angles(n: usize) -> Vec<f64> {
    let step = std::f64::consts::TAU / (n.max(2) - 1) as f64;
    (0..n).map(|i| i as f64 * step).collect()
}
