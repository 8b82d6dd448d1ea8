//! The scalar row kernels of the four-bar: the Newton continuation sweep (bit-identical
//! to the NumPy reference), the closed-form sweep, and closed-form points with the
//! pointwise convention (angles kept at singular points).

use nalgebra::Vector2;

use super::closed_form::ClosedForm;
use super::model::{FourBar, Mode, Point};
use super::options::{MotionOut, Predictor, SweepOptions, SweepOut};
use super::point::{fill_motion, predictor_rates, sweep_point};
use crate::error::Error;
use crate::interrupt::Poll;
use crate::{wrap_angle, Status};

/// The last converged point, with what the predictors need.
struct Prev {
    theta2: f64,
    x: Vector2<f64>,
    v: Vector2<f64>,
    a: Vector2<f64>,
}

impl Prev {
    fn predict(&self, theta2: f64, predictor: Predictor) -> Vector2<f64> {
        let h = wrap_angle(theta2 - self.theta2);
        match predictor {
            Predictor::Previous => self.x,
            Predictor::Tangent => self.x + self.v * h,
            Predictor::Quadratic => self.x + self.v * h + self.a * (0.5 * h * h),
            Predictor::ClosedForm => unreachable!("the closed-form predictor keeps no previous point"),
        }
    }
}

/// The scalar Newton continuation sweep (bit-identical to the NumPy reference).
pub(crate) fn newton_sweep(
    fb: &FourBar,
    theta2: &[f64],
    trig: &[(f64, f64)],
    guess: Option<[f64; 2]>,
    opts: &SweepOptions,
    mut out: SweepOut<'_>,
    mut motion: Option<MotionOut<'_>>,
    poll: &Poll<'_>,
) -> Result<(), Error> {
    let mut prev: Option<Prev> = None;
    for (i, &t2) in theta2.iter().enumerate() {
        poll.tick()?;
        let start = match &prev {
            Some(p) => Some(p.predict(t2, opts.predictor)),
            None if i == 0 => guess.map(Vector2::from),
            None => None,
        };
        // (the closed-form predictor: every point from the mode's closed form)
        let (point, j) = if t2.is_finite() {
            let (s2, c2) = trig[i];
            let sys = fb.at_sin_cos(s2, c2);
            let (point, j) = sweep_point(fb, &sys, start, opts, poll)?;
            (point, Some((j, (sys.s2, sys.c2))))
        } else {
            (Point::failed(Status::NonFinite, 0, f64::NAN), None)
        };
        out.set(i, &point);
        let converged = point.status == Status::Converged;
        if let Some(m) = motion.as_mut() {
            fill_motion(fb, t2, &point, converged, i, m, opts.newton.singular);
        }
        prev = match (converged, j) {
            _ if opts.predictor == Predictor::ClosedForm => None,
            (true, Some((j, sc))) => {
                let (v, a) = predictor_rates(fb, sc, &j, opts.predictor);
                Some(Prev { theta2: t2, x: Vector2::new(point.theta3, point.theta4), v, a })
            }
            _ => None,
        };
    }
    Ok(())
}

/// A sweep by the closed form: each point on its own, NaN angles unless `Converged`
/// (`Singular` where the conditioning is below the threshold), `nit` 0, residual NaN.
pub(crate) fn closed_form_sweep(
    fb: &FourBar,
    theta2: &[f64],
    trig: &[(f64, f64)],
    opts: &SweepOptions,
    out: SweepOut<'_>,
    mut motion: Option<MotionOut<'_>>,
    poll: &Poll<'_>,
) -> Result<(), Error> {
    for (i, (&t2, &(s2, c2))) in theta2.iter().zip(trig).enumerate() {
        poll.tick()?;
        let status = if !t2.is_finite() {
            Status::NonFinite
        } else {
            match fb.closed_form_cs(c2, s2, opts.mode) {
                ClosedForm::Solved { theta3, theta4, sin34 } if fb.conditioning(sin34) >= opts.newton.singular => {
                    out.theta3[i] = theta3;
                    out.theta4[i] = theta4;
                    Status::Converged
                }
                ClosedForm::NotAssemblable => Status::NotAssemblable,
                _ => Status::Singular,
            }
        };
        if status != Status::Converged {
            out.theta3[i] = f64::NAN;
            out.theta4[i] = f64::NAN;
        }
        out.status[i] = status.code();
        out.nit[i] = 0;
        out.residual[i] = f64::NAN;
        if let Some(m) = motion.as_mut() {
            let p = Point { theta3: out.theta3[i], theta4: out.theta4[i], status, nit: 0, residual: f64::NAN };
            fill_motion(fb, t2, &p, status == Status::Converged, i, m, opts.newton.singular);
        }
    }
    Ok(())
}

/// One closed-form point from the crank angle and its sin and cos.
#[inline]
pub(crate) fn closed_point(fb: &FourBar, t2: f64, s2: f64, c2: f64, mode: Mode, singular: f64) -> (f64, f64, Status) {
    if !t2.is_finite() {
        return (f64::NAN, f64::NAN, Status::NonFinite);
    }
    match fb.closed_form_cs(c2, s2, mode) {
        ClosedForm::Solved { theta3, theta4, sin34 } => {
            let st = if fb.conditioning(sin34) < singular { Status::Singular } else { Status::Converged };
            (theta3, theta4, st)
        }
        ClosedForm::NotAssemblable => (f64::NAN, f64::NAN, Status::NotAssemblable),
        ClosedForm::Indeterminate => (f64::NAN, f64::NAN, Status::Singular),
    }
}
