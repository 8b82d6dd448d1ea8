//! What a scene sweep takes and writes: its validated options and the caller-owned
//! output slices (row-major over input angles).

use crate::error::{finite, positive_finite, Error};
use crate::solve::newton::NewtonOptions;

/// Options of a scene sweep, validated once.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct SceneSweepOptions {
    /// Newton stopping criteria for groups; its singular threshold applies to dyads too.
    pub newton: NewtonOptions,
    /// Largest continuation step of a group (radians of input angle).
    pub max_step: f64,
    /// Input angular velocity (constant): point and link velocities and accelerations are
    /// computed when given.
    pub omega: Option<f64>,
}

impl SceneSweepOptions {
    /// Validates `max_step` (finite, > 0) and `omega` (finite).
    pub fn new(newton: NewtonOptions, max_step: f64, omega: Option<f64>) -> Result<Self, Error> {
        positive_finite("max_step", max_step)?;
        if let Some(w) = omega {
            finite("omega", w)?;
        }
        Ok(Self { newton, max_step, omega })
    }
}

/// Output slices of a sweep over N input angles with P reported points, L reported link
/// angles and S steps (row-major).
pub struct SceneSweepOut<'a> {
    /// (N, P, 2) positions in scene units; NaN where the point is not solved.
    pub points: &'a mut [f64],
    /// (N, L) link angles in (-pi, pi].
    pub angles: &'a mut [f64],
    /// (N,) the first failing step's status, or CONVERGED.
    pub status: &'a mut [i8],
    /// (N,) Newton steps spent reaching each angle (groups only; dyads take none).
    pub nit: &'a mut [u32],
    /// (N,) product of the steps' signed conditioning.
    pub det: &'a mut [f64],
    /// (N,) for LIMIT angles (and NOT_ASSEMBLABLE ones the motion reached through a dead
    /// point), the input of the dead point that stops the motion (where continuation last
    /// converged, within about max_step / 2^16 of it); else NaN.
    pub limit: &'a mut [f64],
    /// (N, S) each step's status.
    pub step_status: &'a mut [i8],
    /// (N, S) each step's signed conditioning.
    pub step_det: &'a mut [f64],
    /// (N, P) each reported point's status.
    pub point_status: &'a mut [i8],
    /// (N, P, 2) and (N, L): velocities and angular velocities, when `omega` is given.
    pub velocity: Option<(&'a mut [f64], &'a mut [f64])>,
    /// (N, P, 2) and (N, L): accelerations and angular accelerations at constant `omega`,
    /// when given.
    pub acceleration: Option<(&'a mut [f64], &'a mut [f64])>,
}
