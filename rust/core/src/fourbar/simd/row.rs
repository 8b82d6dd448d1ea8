//! The Newton continuation sweep of one linkage with the polynomial sin/cos of the SIMD
//! path: each Newton evaluation takes sin and cos of both unknowns in one AVX2 call
//! instead of two libm calls. The same continuation, predictor, convergence test and
//! statuses as the scalar `newton_sweep`; a point that leaves the common path (no previous
//! point, a crank pin on O4, a failed or slow solve, the other mode) is solved by the
//! scalar `sweep_point` from the same start.

use nalgebra::{Matrix2, Vector2};

use crate::error::Error;
use crate::fourbar::model::{FourBar, Point, FLAT_ULPS};
use crate::fourbar::options::{MotionOut, Predictor, SweepOptions, SweepOut};
use crate::fourbar::point::{fill_motion, predictor_rates, sweep_point};
use crate::interrupt::Poll;
use crate::simd::avx2_kernel;
use crate::simd::math::{sin_cos, SIN_COS_MAX};
use crate::{wrap_angle, Status};

/// Newton steps tried on the fast path before the scalar path takes the point over.
const FAST_STEPS: u32 = 8;

avx2_kernel! {
    pub(crate) fn newton_row(
        fb: &FourBar,
        theta2: &[f64],
        trig: &[(f64, f64)],
        guess: Option<[f64; 2]>,
        opts: &SweepOptions,
        out: SweepOut<'_>,
        motion: Option<MotionOut<'_>>,
        poll: &Poll<'_>,
    ) -> Result<(), Error> = row_body;
}

#[inline(always)]
fn row_body<const AVX: bool>(
    fb: &FourBar,
    theta2: &[f64],
    trig: &[(f64, f64)],
    guess: Option<[f64; 2]>,
    opts: &SweepOptions,
    mut out: SweepOut<'_>,
    mut motion: Option<MotionOut<'_>>,
    poll: &Poll<'_>,
) -> Result<(), Error> {
    let [r1, r2, r3, r4] = fb.unit_lengths();
    let r = [r1, r2, r3, r4];
    let scale = fb.longest();
    let cond_scale = r3.min(r4) / scale;
    let r3r4 = r3 * r4;
    let sign = opts.mode.sign();
    let (tol, singular, max_iter) = (opts.newton.tol, opts.newton.singular, opts.newton.max_iter);
    let cap = max_iter.min(FAST_STEPS);
    let fixed = Fixed { r, scale, r3r4, cond_scale, sign, tol, singular, max_iter, cap };
    // the last converged point: angles, and the predictor's rates
    let mut prev: Option<([f64; 2], [f64; 2], [f64; 2])> = None;
    for (i, &t2) in theta2.iter().enumerate() {
        poll.tick()?;
        let (s2, c2) = trig[i];
        let mut result: Option<(Point, [f64; 4])> = None;
        let mut start = None;
        if !t2.is_finite() {
            result = Some((Point::failed(Status::NonFinite, 0, f64::NAN), [f64::NAN; 4]));
        } else if let Some((x, v, a)) = prev {
            let h = wrap_angle(t2 - theta2[i - 1]);
            let x0 = match opts.predictor {
                Predictor::ClosedForm => unreachable!("the closed-form predictor sweeps on the scalar path"),
                Predictor::Previous => x,
                Predictor::Tangent => [x[0] + v[0] * h, x[1] + v[1] * h],
                Predictor::Quadratic => {
                    let hh = 0.5 * h * h;
                    [x[0] + v[0] * h + a[0] * hh, x[1] + v[1] * h + a[1] * hh]
                }
            };
            start = Some(x0);
            let ux = r1 - r2 * c2;
            let uy = -(r2 * s2);
            let d = (ux * ux + uy * uy).sqrt();
            let (q1, q2, q3) = (d + r3 - r4, d - r3 + r4, r3 + r4 - d);
            // within FLAT_ULPS ulp of closing (flat: the scalar path decides) is not "cannot close"
            let slack = FLAT_ULPS * f64::EPSILON * scale;
            let closes = (q1 >= 0.0) & (q2 >= 0.0) & (q3 >= 0.0);
            if d != 0.0 && !((q1 >= -slack) & (q2 >= -slack) & (q3 >= -slack)) {
                result = Some((Point::failed(Status::NotAssemblable, 0, f64::NAN), [f64::NAN; 4]));
            } else if d != 0.0 && closes {
                result = fast_newton::<AVX>(&fixed, s2, c2, x0);
            }
        }
        let (point, j) = match result {
            Some((p, [j00, j01, j10, j11])) => (p, Matrix2::new(j00, j01, j10, j11)),
            None => {
                let sys = fb.at_sin_cos(s2, c2);
                let first = if i == 0 { guess.map(Vector2::from) } else { start.map(Vector2::from) };
                sweep_point(fb, &sys, first, opts, poll)?
            }
        };
        out.set(i, &point);
        let converged = point.status == Status::Converged;
        if let Some(m) = motion.as_mut() {
            fill_motion(fb, t2, &point, converged, i, m, opts.newton.singular);
        }
        prev = if converged {
            let (v, a) = predictor_rates(fb, (s2, c2), &j, opts.predictor);
            Some(([point.theta3, point.theta4], [v[0], v[1]], [a[0], a[1]]))
        } else {
            None
        };
    }
    Ok(())
}

/// What [`fast_newton`] takes that is fixed for a whole row: the linkage's lengths and scales,
/// the mode's sign and the stopping criteria (`cap`: the steps tried on the fast path).
#[derive(Clone, Copy)]
struct Fixed {
    r: [f64; 4],
    scale: f64,
    r3r4: f64,
    cond_scale: f64,
    sign: f64,
    tol: f64,
    singular: f64,
    max_iter: u32,
    cap: u32,
}

/// Newton from `x0` as `newton::solve` does it (the scalar `Loop::eval` and `cramer`
/// in their operation order), with the mode check; `None` (the scalar path takes over)
/// unless it converges on the mode within `cap` steps.
#[inline(always)]
fn fast_newton<const AVX: bool>(fixed: &Fixed, s2: f64, c2: f64, x0: [f64; 2]) -> Option<(Point, [f64; 4])> {
    let Fixed { r, scale, r3r4, cond_scale, sign, tol, singular, max_iter, cap } = *fixed;
    let [r1, r2, r3, r4] = r;
    let mut x = x0;
    let mut nit = 0;
    let mut last_small = f64::INFINITY;
    loop {
        if !(x[0].abs() <= SIN_COS_MAX && x[1].abs() <= SIN_COS_MAX) {
            return None;
        }
        #[cfg(target_arch = "x86_64")]
        let [s3, c3, s4, c4] = if AVX {
            // SAFETY: AVX is true only inside the AVX2 trampoline, called after the run-time check.
            unsafe { super::avx2::sin_cos2(x[0], x[1]) }
        } else {
            let ((s3, c3), (s4, c4)) = (sin_cos(x[0]), sin_cos(x[1]));
            [s3, c3, s4, c4]
        };
        #[cfg(not(target_arch = "x86_64"))]
        let [s3, c3, s4, c4] = {
            let ((s3, c3), (s4, c4)) = (sin_cos(x[0]), sin_cos(x[1]));
            [s3, c3, s4, c4]
        };
        let f1 = r2 * c2 + r3 * c3 - r4 * c4 - r1;
        let f2 = r2 * s2 + r3 * s3 - r4 * s4;
        let (j00, j01, j10, j11) = (-r3 * s3, r4 * s4, r3 * c3, -r4 * c4);
        let residual = 0.0f64.max(f1.abs()).max(f2.abs()) / scale;
        let det = j00 * j11 - j01 * j10;
        let sin34 = -det / r3r4;
        if !(f1.is_finite() && f2.is_finite()) || sin34.abs() * cond_scale < singular || det == 0.0 {
            return None;
        }
        let dx0 = (-f1 * j11 - -f2 * j01) / det;
        let dx1 = (j00 * -f2 - j10 * -f1) / det;
        let step = dx0.abs().max(dx1.abs());
        if residual < tol {
            if step < tol {
                if sin34 * sign < 0.0 {
                    return None;
                }
                let (t3, t4) = (wrap_angle(x[0] + dx0), wrap_angle(x[1] + dx1));
                let p = Point { theta3: t3, theta4: t4, status: Status::Converged, nit, residual };
                return Some((p, [j00, j01, j10, j11]));
            }
            if step > 0.5 * last_small {
                return None;
            }
            last_small = step;
        }
        if nit >= max_iter || nit >= cap {
            return None;
        }
        x = [wrap_angle(x[0] + dx0), wrap_angle(x[1] + dx1)];
        nit += 1;
    }
}
