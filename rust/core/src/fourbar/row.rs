//! One row of a four-bar computation, dispatched to its kernel: a sweep (Newton or
//! closed form, SIMD or scalar) and the closed form at many angles, from one table of
//! crank-angle sines and cosines shared by every linkage of a batch.

use super::model::{FourBar, Mode};
use super::options::{Method, MotionOut, Predictor, SweepOptions, SweepOut};
use super::{scalar, simd};
use crate::error::{try_zeros, Error};
use crate::interrupt::Poll;

/// (sin, cos) of every crank angle: computed once, shared by every linkage of a batch
/// (4 at a time by polynomials when [`crate::simd::enabled`], libm otherwise). Allocated
/// fallibly ([`Error::Allocation`]).
pub(crate) fn sin_cos_table(theta2: &[f64]) -> Result<Vec<(f64, f64)>, Error> {
    let mut v = try_zeros::<(f64, f64)>(|| format!("sin and cos of {} crank angles", theta2.len()), theta2.len())?;
    sin_cos_fill(theta2, &mut v);
    Ok(v)
}

/// [`sin_cos_table`] into a buffer of the same length.
pub(crate) fn sin_cos_fill(theta2: &[f64], out: &mut [(f64, f64)]) {
    if crate::simd::enabled() {
        crate::simd::sin_cos_into(theta2, out);
        return;
    }
    for (o, t) in out.iter_mut().zip(theta2) {
        *o = t.sin_cos();
    }
}

/// One sweep row, for slices known to have the right lengths: the closed-form or the
/// Newton kernel, SIMD when [`crate::simd::enabled`], else scalar.
pub(crate) fn sweep_row(
    fb: &FourBar,
    theta2: &[f64],
    trig: &[(f64, f64)],
    guess: Option<[f64; 2]>,
    opts: &SweepOptions,
    out: SweepOut<'_>,
    motion: Option<MotionOut<'_>>,
    poll: &Poll<'_>,
) -> Result<(), Error> {
    let vectorized = crate::simd::enabled();
    match opts.method {
        Method::ClosedForm if vectorized => simd::closed_form::sweep(fb, theta2, trig, opts, out, motion, poll),
        Method::ClosedForm => scalar::closed_form_sweep(fb, theta2, trig, opts, out, motion, poll),
        Method::Newton if vectorized && opts.predictor == Predictor::ClosedForm => {
            simd::across::closed_form_predicted(fb, theta2, trig, guess, opts, out, motion, poll)
        }
        Method::Newton if vectorized => simd::row::newton_row(fb, theta2, trig, guess, opts, out, motion, poll),
        Method::Newton => scalar::newton_sweep(fb, theta2, trig, guess, opts, out, motion, poll),
    }
}

/// [`closed_form_into`] from precomputed (sin, cos) of the crank angles (shared across a
/// batch); the status is written only when a slice is given.
pub(crate) fn closed_form_trig(
    fb: &FourBar,
    theta2: &[f64],
    trig: &[(f64, f64)],
    mode: Mode,
    singular: f64,
    theta3: &mut [f64],
    theta4: &mut [f64],
    mut status: Option<&mut [i8]>,
) {
    if crate::simd::enabled() {
        let spec = simd::closed_form::RowSpec { mode, singular, nan_singular: false };
        return simd::closed_form::closed_form_row(fb, theta2, trig, spec, theta3, theta4, status);
    }
    for (i, (&t2, &(s2, c2))) in theta2.iter().zip(trig).enumerate() {
        let (t3, t4, st) = scalar::closed_point(fb, t2, s2, c2, mode, singular);
        theta3[i] = t3;
        theta4[i] = t4;
        if let Some(s) = status.as_deref_mut() {
            s[i] = st.code();
        }
    }
}
