//! The Newton continuation sweep of one linkage with the polynomial sin/cos of the SIMD
//! path: each Newton evaluation takes sin and cos of both unknowns in one AVX2 call
//! instead of two libm calls. The same continuation, predictor, convergence test and
//! statuses as `sweep::sweep_unchecked`; a point that leaves the common path (no previous
//! point, a crank pin on O4, a failed or slow solve, the other mode) is solved by the
//! scalar `sweep_point` from the same start.

use nalgebra::Vector2;

use super::newton::{eval_lanes, rates, wrap, Eval, W};
use crate::fourbar::{FourBar, Point};
use crate::sweep::{fill_motion, sweep_point, MotionOut, Predictor, SweepOptions, SweepOut};
use crate::{wrap_angle, Status};

/// Newton steps tried on the fast path before the scalar path takes the point over.
const FAST_STEPS: u32 = 8;

#[allow(clippy::too_many_arguments)]
pub(crate) fn newton_row(
    fb: &FourBar,
    theta2: &[f64],
    trig: &[(f64, f64)],
    guess: Option<[f64; 2]>,
    opts: &SweepOptions,
    out: SweepOut<'_>,
    motion: Option<MotionOut<'_>>,
) {
    #[cfg(target_arch = "x86_64")]
    if super::available() {
        // SAFETY: AVX2 and FMA checked at run time.
        return unsafe { row_avx2(fb, theta2, trig, guess, opts, out, motion) };
    }
    row_body::<false>(fb, theta2, trig, guess, opts, out, motion)
}

#[cfg(target_arch = "x86_64")]
#[target_feature(enable = "avx2,fma")]
#[allow(clippy::too_many_arguments)]
unsafe fn row_avx2(
    fb: &FourBar,
    theta2: &[f64],
    trig: &[(f64, f64)],
    guess: Option<[f64; 2]>,
    opts: &SweepOptions,
    out: SweepOut<'_>,
    motion: Option<MotionOut<'_>>,
) {
    row_body::<true>(fb, theta2, trig, guess, opts, out, motion)
}

#[inline(always)]
#[allow(clippy::too_many_arguments)]
fn row_body<const AVX: bool>(
    fb: &FourBar,
    theta2: &[f64],
    trig: &[(f64, f64)],
    guess: Option<[f64; 2]>,
    opts: &SweepOptions,
    out: SweepOut<'_>,
    mut motion: Option<MotionOut<'_>>,
) {
    let [r1, r2, r3, r4] = fb.lengths();
    // lanes 0 and 1 carry the two unknowns' sines and cosines (x3 in lane 0 of the first
    // vector, x4 in lane 0 of the second): one linkage in every lane
    let r = [[r1; W], [r2; W], [r3; W], [r4; W]];
    let scale = [fb.longest(); W];
    let cond_scale = r3.min(r4) / fb.longest();
    let r3r4 = [r3 * r4; W];
    let sign = opts.mode.sign();
    let (tol, singular, max_iter) = (opts.newton.tol, opts.newton.singular, opts.newton.max_iter);
    let cap = max_iter.min(FAST_STEPS);
    // the last converged point: angles, and the predictor's rates
    let mut prev: Option<([f64; 2], [f64; 2], [f64; 2])> = None;
    for (i, &t2) in theta2.iter().enumerate() {
        let (s2, c2) = trig[i];
        let mut result: Option<(Point, [f64; 4])> = None;
        let mut start = None;
        if !t2.is_finite() {
            result = Some((Point::failed(Status::NonFinite, 0, f64::NAN), [f64::NAN; 4]));
        } else if let Some((x, v, a)) = prev {
            let h = wrap_angle(t2 - theta2[i - 1]);
            let x0 = match opts.predictor {
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
            if d != 0.0 && !((q1 >= 0.0) & (q2 >= 0.0) & (q3 >= 0.0)) {
                result = Some((Point::failed(Status::NotAssemblable, 0, f64::NAN), [f64::NAN; 4]));
            } else if d != 0.0 {
                result =
                    fast_newton::<AVX>(&r, &scale, &r3r4, cond_scale, s2, c2, x0, sign, tol, singular, max_iter, cap);
            }
        }
        let (point, j) = match result {
            Some(pj) => pj,
            None => {
                let sys = fb.at_sin_cos(s2, c2);
                let first = if i == 0 { guess.map(Vector2::from) } else { start.map(Vector2::from) };
                let (p, j) = sweep_point(fb, &sys, first, opts);
                (p, [j[(0, 0)], j[(0, 1)], j[(1, 0)], j[(1, 1)]])
            }
        };
        out.theta3[i] = point.theta3;
        out.theta4[i] = point.theta4;
        out.status[i] = point.status.code();
        out.nit[i] = point.nit;
        out.residual[i] = point.residual;
        let converged = point.status == Status::Converged;
        if let Some(m) = motion.as_mut() {
            fill_motion(fb, t2, &point, converged, i, m, opts.newton.singular);
        }
        prev = if converged {
            let jac = [[j[0]; W], [j[1]; W], [j[2]; W], [j[3]; W]];
            let (v, a) = rates(&r[1], s2, c2, &jac, opts.predictor);
            Some(([point.theta3, point.theta4], [v[0][0], v[1][0]], [a[0][0], a[1][0]]))
        } else {
            None
        };
    }
}

/// Newton from `x0` as `newton::solve` does it, with the mode check; `None` (the scalar
/// path takes over) unless it converges on the mode within `cap` steps.
#[inline(always)]
#[allow(clippy::too_many_arguments)]
fn fast_newton<const AVX: bool>(
    r: &[[f64; W]; 4],
    scale: &[f64; W],
    r3r4: &[f64; W],
    cond_scale: f64,
    s2: f64,
    c2: f64,
    x0: [f64; 2],
    sign: f64,
    tol: f64,
    singular: f64,
    max_iter: u32,
    cap: u32,
) -> Option<(Point, [f64; 4])> {
    let mut x = x0;
    let mut nit = 0;
    let mut last_small = f64::INFINITY;
    loop {
        let xs = [[x[0]; W], [x[1]; W]];
        #[cfg(target_arch = "x86_64")]
        let e = if AVX {
            // SAFETY: AVX is true only inside row_avx2, called after the run-time check.
            unsafe { super::avx2::eval4(r, scale, r3r4, s2, c2, &xs) }
        } else {
            eval_lanes(r, scale, r3r4, s2, c2, &xs)
        };
        #[cfg(not(target_arch = "x86_64"))]
        let e = eval_lanes(r, scale, r3r4, s2, c2, &xs);
        let Eval { f1, f2, j, residual, det, sin34, dx, step } = e;
        let finite = f1[0].is_finite()
            && f2[0].is_finite()
            && x[0].abs() <= super::math::SIN_COS_MAX
            && x[1].abs() <= super::math::SIN_COS_MAX;
        if !finite || sin34[0].abs() * cond_scale < singular || det[0] == 0.0 {
            return None;
        }
        let (res, step) = (residual[0], step[0]);
        if res < tol {
            if step < tol {
                if sin34[0] * sign < 0.0 {
                    return None;
                }
                let (t3, t4) = (wrap_angle(x[0] + dx[0][0]), wrap_angle(x[1] + dx[1][0]));
                let p = Point { theta3: t3, theta4: t4, status: Status::Converged, nit, residual: res };
                return Some((p, [j[0][0], j[1][0], j[2][0], j[3][0]]));
            }
            if step > 0.5 * last_small {
                return None;
            }
            last_small = step;
        }
        if nit >= max_iter || nit >= cap {
            return None;
        }
        let w = wrap([x[0] + dx[0][0], x[1] + dx[1][0], 0.0, 0.0]);
        x = [w[0], w[1]];
        nit += 1;
    }
}
