//! One crank angle solved: Newton-Raphson from a guess or the closed form with the mode
//! check, the continuation rule for one point of a sweep (continuation first, the closed
//! form of the mode when that fails), the predictor's rates, and the point's motion.

use nalgebra::{Matrix2, Vector2};

use super::closed_form::Geometry;
use super::loop_system::Loop;
use super::model::{cramer, FourBar, Mode, Point};
use super::options::{MotionOut, Predictor, SweepOptions};
use crate::error::Error;
use crate::interrupt::{Never, Poll};
use crate::solve::newton::{self, NewtonOptions};
use crate::{wrap_angle, Status};

impl FourBar {
    /// Solves one crank angle by Newton-Raphson from `guess` (default: the closed form of
    /// `mode`). Not-assemblable angles are reported before any iteration; a converged
    /// point on the other mode is reported [`Status::BranchJump`].
    pub fn solve(
        &self,
        theta2: f64,
        mode: Mode,
        guess: Option<[f64; 2]>,
        opts: &NewtonOptions,
        history: Option<&mut Vec<f64>>,
    ) -> Point {
        let never = Poll::new(&Never);
        // Never does not interrupt: the error branch is unreachable, and harmless
        self.solve_polled(theta2, mode, guess, opts, history, &never)
            .unwrap_or_else(|_| Point::failed(Status::MaxIterations, 0, f64::NAN))
    }

    /// [`FourBar::solve`] that counts its Newton steps on `poll` and returns
    /// [`Error::Interrupted`] when the poll's interrupt asks to stop.
    pub fn solve_polled(
        &self,
        theta2: f64,
        mode: Mode,
        guess: Option<[f64; 2]>,
        opts: &NewtonOptions,
        history: Option<&mut Vec<f64>>,
        poll: &Poll<'_>,
    ) -> Result<Point, Error> {
        if !theta2.is_finite() {
            return Ok(Point::unsolved(Status::NonFinite).0);
        }
        Ok(self.solve_on(&self.at(theta2), mode, guess, opts, history, poll)?.0)
    }

    /// Solves on a loop already set up at a finite crank angle; also hands back the
    /// Jacobian at the solution.
    pub(crate) fn solve_on(
        &self,
        sys: &Loop<'_>,
        mode: Mode,
        guess: Option<[f64; 2]>,
        opts: &NewtonOptions,
        history: Option<&mut Vec<f64>>,
        poll: &Poll<'_>,
    ) -> Result<(Point, Matrix2<f64>), Error> {
        let start = match (self.geometry(sys.c2, sys.s2), guess) {
            (Geometry::NotAssemblable, _) => return Ok(Point::unsolved(Status::NotAssemblable)),
            (_, Some(g)) => Vector2::from(g),
            (Geometry::Triangle(t), None) => t.angles(mode).0,
            (Geometry::Indeterminate, None) => return Ok(Point::unsolved(Status::Singular)),
        };
        self.solve_from(sys, start, mode, opts, history, poll)
    }

    /// Newton from `start` on the loop `sys`, then the mode check.
    pub(crate) fn solve_from(
        &self,
        sys: &Loop<'_>,
        start: Vector2<f64>,
        mode: Mode,
        opts: &NewtonOptions,
        history: Option<&mut Vec<f64>>,
        poll: &Poll<'_>,
    ) -> Result<(Point, Matrix2<f64>), Error> {
        let out = newton::solve_polled(sys, start, opts, history, poll)?;
        let mut status = out.status;
        if status == Status::Converged && sys.sin34(&out.jacobian) * mode.sign() < 0.0 {
            status = Status::BranchJump;
        }
        let point = if status == Status::Converged {
            Point {
                theta3: wrap_angle(out.x[0]),
                theta4: wrap_angle(out.x[1]),
                status,
                nit: out.nit,
                residual: out.residual,
            }
        } else {
            Point::failed(status, out.nit, out.residual)
        };
        Ok((point, out.jacobian))
    }
}

/// Solves one sweep point: continuation from `start` first, then, if that fails in any
/// way, the closed form of the mode as the starting guess. `nit` counts both attempts.
/// Always inlined: the scalar sweep's cost per point is unchanged by its SIMD callers.
#[inline(always)]
pub(crate) fn sweep_point(
    fb: &FourBar,
    sys: &Loop<'_>,
    start: Option<Vector2<f64>>,
    opts: &SweepOptions,
    poll: &Poll<'_>,
) -> Result<(Point, Matrix2<f64>), Error> {
    let Some(x0) = start else {
        return fb.solve_on(sys, opts.mode, None, &opts.newton, None, poll);
    };
    let tri = match fb.geometry(sys.c2, sys.s2) {
        Geometry::NotAssemblable => return Ok(Point::unsolved(Status::NotAssemblable)),
        Geometry::Indeterminate => None,
        Geometry::Triangle(t) => Some(t),
    };
    let (first, j) = fb.solve_from(sys, x0, opts.mode, &opts.newton, None, poll)?;
    if first.status == Status::Converged {
        return Ok((first, j));
    }
    // the closed form of the mode is computed only now, when continuation failed
    let (mut second, j) = match tri {
        Some(t) => fb.solve_from(sys, t.angles(opts.mode).0, opts.mode, &opts.newton, None, poll)?,
        None => Point::unsolved(Status::Singular),
    };
    second.nit += first.nit;
    Ok((second, j))
}

/// dx/dtheta2 and d2x/dtheta2^2 at unit crank speed, as far as the predictor needs them.
/// Both reuse the Jacobian at the solution (r3 c3 = J10, r3 s3 = -J00, r4 c4 = -J11,
/// r4 s4 = J01), so a prediction costs no trigonometry.
pub(crate) fn predictor_rates(
    fb: &FourBar,
    (s2, c2): (f64, f64),
    j: &Matrix2<f64>,
    p: Predictor,
) -> (Vector2<f64>, Vector2<f64>) {
    let zero = Vector2::zeros();
    if p == Predictor::Previous {
        return (zero, zero);
    }
    let r2 = fb.unit_lengths()[1];
    let Some(v) = cramer(j, &Vector2::new(r2 * s2, -(r2 * c2))) else { return (zero, zero) };
    if p == Predictor::Tangent {
        return (v, zero);
    }
    let (w3s, w4s) = (v[0] * v[0], v[1] * v[1]);
    let b = Vector2::new(r2 * c2 + j[(1, 0)] * w3s + j[(1, 1)] * w4s, r2 * s2 - j[(0, 0)] * w3s - j[(0, 1)] * w4s);
    (v, cramer(j, &b).unwrap_or(zero))
}

/// Writes the velocities (and accelerations) of point `i` into `m`: NaN unless converged.
pub(crate) fn fill_motion(
    fb: &FourBar,
    t2: f64,
    p: &Point,
    converged: bool,
    i: usize,
    m: &mut MotionOut<'_>,
    singular: f64,
) {
    let (w, a) = if converged {
        let (w, _) = fb.velocity(t2, p.theta3, p.theta4, m.omega2, singular);
        let a = m
            .alpha
            .as_ref()
            .map(|(alpha2, _, _)| fb.acceleration(t2, p.theta3, p.theta4, m.omega2, w[0], w[1], *alpha2, singular).0);
        (w, a)
    } else {
        ([f64::NAN; 2], Some([f64::NAN; 2]))
    };
    m.omega3[i] = w[0];
    m.omega4[i] = w[1];
    if let (Some((_, a3, a4)), Some(a)) = (m.alpha.as_mut(), a) {
        a3[i] = a[0];
        a4[i] = a[1];
    }
}
