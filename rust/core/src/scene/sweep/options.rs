//! What a scene sweep takes and writes: its validated options and the caller-owned
//! output slices (row-major over input angles).

use crate::error::{finite, positive_finite, quoted, Error};
use crate::solve::newton::NewtonOptions;

/// Options of a scene sweep, validated once.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct SceneSweepOptions {
    /// Newton stopping criteria for groups; its singular threshold applies to closed forms
    /// too, raised to `CLOSED_FORM_FLOOR` (1e-5).
    pub newton: NewtonOptions,
    /// Largest continuation step of a group (radians of input angle).
    pub max_step: f64,
    /// Input angular velocity (constant): point and link velocities and accelerations are
    /// computed when given.
    pub omega: Option<f64>,
    /// How each input value's pose is found ([`ScenePredictor::Continuation`] unless set).
    pub predictor: ScenePredictor,
    /// Tell NOT_ASSEMBLABLE from LIMIT where the motion from the drawn pose does not reach
    /// (counting every assembly there: the homotopy for a group). True unless set; an
    /// atlas, which needs only what the drawn circuit reaches, turns it off.
    pub classify: bool,
}

/// A closed-form step (a dyad, a slider's circle-line, line-line or guide through a point)
/// whose conditioning is below this is SINGULAR: rounding in its inputs (a few eps of the
/// drawing's size) moves its point by about c eps / conditioning, c measured up to 27 by
/// the fuzzing of issue 32 (6e-15 / conditioning), so above it every CONVERGED point is
/// within 1e-9 of the size. Groups keep the Newton threshold on their Hadamard ratio.
pub(crate) const CLOSED_FORM_FLOOR: f64 = 1e-5;

impl SceneSweepOptions {
    /// The conditioning below which a closed-form step is SINGULAR: the Newton threshold,
    /// raised to `CLOSED_FORM_FLOOR` (1e-5).
    pub fn closed_form_singular(&self) -> f64 {
        self.newton.singular.max(CLOSED_FORM_FLOOR)
    }
}

/// How a scene sweep finds each input value's pose.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Hash)]
pub enum ScenePredictor {
    /// Follows the drawn circuit from the drawn pose: groups by continuation, LIMIT past a
    /// dead point. A plan with no group is solved by its closed forms across values at once
    /// where that is certified to be the same motion (no step near a dead point, values no
    /// more than `max_step` apart), and followed by continuation otherwise.
    #[default]
    Continuation,
    /// No continuation: every value on its own, each dyad and slider on its drawn side by
    /// its closed form (plans with no group only). Values where the drawn sides do not
    /// close are LIMIT when some other assembly exists there, NOT_ASSEMBLABLE when none.
    ClosedForm,
}

impl ScenePredictor {
    /// Parses "continuation" / "closed-form".
    pub fn parse(s: &str) -> Result<Self, Error> {
        match s {
            "continuation" => Ok(ScenePredictor::Continuation),
            "closed-form" => Ok(ScenePredictor::ClosedForm),
            other => Err(Error::invalid("predictor", "must be 'continuation' or 'closed-form'", quoted(other))),
        }
    }
}

impl SceneSweepOptions {
    /// Validates `max_step` (finite, > 0) and `omega` (finite).
    pub fn new(newton: NewtonOptions, max_step: f64, omega: Option<f64>) -> Result<Self, Error> {
        positive_finite("max_step", max_step)?;
        if let Some(w) = omega {
            finite("omega", w)?;
        }
        Ok(Self { newton, max_step, omega, predictor: ScenePredictor::Continuation, classify: true })
    }

    /// The same options, telling NOT_ASSEMBLABLE from LIMIT or not (see `classify`).
    pub fn with_classify(self, classify: bool) -> Self {
        Self { classify, ..self }
    }

    /// The same options with `predictor`.
    pub fn with_predictor(self, predictor: ScenePredictor) -> Self {
        Self { predictor, ..self }
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
