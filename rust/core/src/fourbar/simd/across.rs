//! `predictor = ClosedForm` on the SIMD path: every point from the requested mode's closed
//! form at its own crank angle (4 angles per call of the closed-form kernel), then one
//! Newton evaluation across 4 angles at once: a lane whose residual and correction are
//! both below the tolerance, whose conditioning clears the threshold and whose mode is the
//! one asked for is converged at once (the correction applied, as the scalar solve applies
//! it). Any other point (no closed form, a non-finite angle, a lane that needs more
//! Newton steps, the first point when a guess is given) is solved by the scalar
//! `sweep_point` from the closed form, so statuses are the scalar path's.

use super::closed_form::{closed_form_row, RowSpec};
use super::lane::{eval_lanes, lanes, wrap, Block, Check, Eval, M, V, W};
use crate::error::Error;
use crate::fourbar::model::{FourBar, Point};
use crate::fourbar::options::{MotionOut, SweepOptions, SweepOut};
use crate::fourbar::point::{fill_motion, sweep_point};
use crate::interrupt::Poll;
use crate::simd::avx2_kernel;
use crate::simd::math::SIN_COS_MAX;
use crate::Status;

const CONVERGED: i8 = Status::Converged as i8;

avx2_kernel! {
    pub(crate) fn closed_form_predicted(
        fb: &FourBar,
        theta2: &[f64],
        trig: &[(f64, f64)],
        guess: Option<[f64; 2]>,
        opts: &SweepOptions,
        out: SweepOut<'_>,
        motion: Option<MotionOut<'_>>,
        poll: &Poll<'_>,
    ) -> Result<(), Error> = body;
}

/// `AVX`: compiled inside the AVX2 trampoline (AVX2 and FMA present), where the evaluation
/// is written in AVX2 intrinsics (the same values as the lane loop, which LLVM vectorizes
/// only 2 wide).
#[inline(always)]
fn body<const AVX: bool>(
    fb: &FourBar,
    theta2: &[f64],
    trig: &[(f64, f64)],
    guess: Option<[f64; 2]>,
    opts: &SweepOptions,
    mut out: SweepOut<'_>,
    mut motion: Option<MotionOut<'_>>,
    poll: &Poll<'_>,
) -> Result<(), Error> {
    let n = theta2.len();
    // the vectorized pass costs nanoseconds a point: counted at once; the points it leaves
    // to the scalar path tick one by one below
    poll.tick_n(n)?;
    let spec = RowSpec { mode: opts.mode, singular: opts.newton.singular, nan_singular: false };
    closed_form_row(fb, theta2, trig, spec, out.theta3, out.theta4, Some(&mut *out.status));
    let check = check_of(fb, opts);
    // per point: solved here (true) or left to the scalar path
    let mut fast = vec![false; n];
    let mut i = 0;
    while i + W <= n {
        let cand: M = lanes!(|l| out.status[i + l] == CONVERGED && !(i + l == 0 && guess.is_some()));
        if cand.iter().any(|&c| c) {
            let block = Block {
                theta3: &mut out.theta3[i..i + W],
                theta4: &mut out.theta4[i..i + W],
                residual: &mut out.residual[i..i + W],
                trig: &trig[i..i + W],
            };
            let ok = if AVX { accept_avx2(&check, cand, block) } else { accept(&check, cand, block) };
            for l in (0..W).filter(|&l| ok[l]) {
                out.nit[i + l] = 0;
                fast[i + l] = true;
            }
        }
        i += W;
    }
    for (k, &t2) in theta2.iter().enumerate() {
        if fast[k] && motion.is_none() {
            continue; // written by the check above
        }
        poll.tick()?;
        let point = if fast[k] {
            Point {
                theta3: out.theta3[k],
                theta4: out.theta4[k],
                status: Status::Converged,
                nit: 0,
                residual: out.residual[k],
            }
        } else if t2.is_finite() {
            let (s2, c2) = trig[k];
            let sys = fb.at_sin_cos(s2, c2);
            let start = if k == 0 { guess.map(nalgebra::Vector2::from) } else { None };
            let p = sweep_point(fb, &sys, start, opts, poll)?.0;
            out.set(k, &p);
            p
        } else {
            let p = Point::failed(Status::NonFinite, 0, f64::NAN);
            out.set(k, &p);
            p
        };
        if let Some(m) = motion.as_mut() {
            fill_motion(fb, t2, &point, point.status == Status::Converged, k, m, opts.newton.singular);
        }
    }
    Ok(())
}

/// One Newton evaluation at the closed forms of a block's candidates: a lane is accepted
/// where its residual and correction are below the tolerance, its angles and residuals
/// finite, its conditioning clears the threshold and its mode is the one asked for; its
/// angles become the corrected ones (wrapped) and its residual is written. Returns the
/// accepted lanes.
#[inline(always)]
fn accept(c: &Check, cand: M, b: Block<'_>) -> M {
    let x: [V; 2] = [lanes!(|l| b.theta3[l]), lanes!(|l| b.theta4[l])];
    let (s2, c2): (V, V) = (lanes!(|l| b.trig[l].0), lanes!(|l| b.trig[l].1));
    let Eval { f1, f2, residual, det, sin34, dx: [dx0, dx1], step, .. } =
        eval_lanes(&c.r, &c.scale, &c.r3r4, &s2, &c2, &x);
    let ok: M = lanes!(|l| {
        let finite =
            f1[l].is_finite() & f2[l].is_finite() & (x[0][l].abs() <= SIN_COS_MAX) & (x[1][l].abs() <= SIN_COS_MAX);
        cand[l]
            & finite
            & (det[l] != 0.0)
            & (sin34[l].abs() * c.cond_scale >= c.singular)
            & (residual[l] < c.tol)
            & (step[l] < c.tol)
            & (sin34[l] * c.sign > 0.0)
    });
    let t3 = wrap(lanes!(|l| x[0][l] + dx0[l]));
    let t4 = wrap(lanes!(|l| x[1][l] + dx1[l]));
    for l in (0..W).filter(|&l| ok[l]) {
        b.theta3[l] = t3[l];
        b.theta4[l] = t4[l];
        b.residual[l] = residual[l];
    }
    ok
}

/// [`accept`] in AVX2 registers (the same decisions and values): called only from
/// `body::<true>`, inside the AVX2 trampoline.
#[inline(always)]
fn accept_avx2(c: &Check, cand: M, b: Block<'_>) -> M {
    #[cfg(target_arch = "x86_64")]
    {
        // SAFETY: reached only inside the AVX2 trampoline, whose caller checked AVX2 and FMA.
        unsafe { super::avx2::accept4(c, cand, b) }
    }
    #[cfg(not(target_arch = "x86_64"))]
    accept(c, cand, b)
}

/// The check's parameters for `fb` and `opts`.
fn check_of(fb: &FourBar, opts: &SweepOptions) -> Check {
    let r: [V; 4] = fb.unit_lengths().map(|v| [v; W]);
    let r3r4: V = lanes!(|l| r[2][l] * r[3][l]);
    Check {
        r,
        scale: [fb.longest(); W],
        r3r4,
        cond_scale: fb.cond_scale(),
        tol: opts.newton.tol,
        singular: opts.newton.singular,
        sign: opts.mode.sign(),
    }
}
