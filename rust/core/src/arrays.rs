//! Pointwise kernels over arrays (no continuation): closed form, velocity, acceleration,
//! coupler points and transmission angles. Each writes into caller-owned slices of the
//! same length; the bindings broadcast and allocate, these only compute.

use crate::error::Error;
use crate::fourbar::{transmission_angle, Assembly, FourBar, Mode};
use crate::Status;

fn same_len(name: &str, got: usize, n: usize) -> Result<(), Error> {
    if got == n {
        Ok(())
    } else {
        Err(Error::Shape { name: name.into(), got, expected: n })
    }
}

/// Closed form of `mode` at each crank angle, with a status: Converged, NotAssemblable,
/// Singular (conditioning below `singular`, or indeterminate), NonFinite. Angles are NaN
/// only where no solution exists or it is indeterminate.
pub fn closed_form_into(
    fb: &FourBar,
    theta2: &[f64],
    mode: Mode,
    singular: f64,
    theta3: &mut [f64],
    theta4: &mut [f64],
    status: &mut [i8],
) {
    let trig = crate::sweep::sin_cos(theta2);
    closed_form_trig(fb, theta2, &trig, mode, singular, theta3, theta4, Some(status));
}

/// [`closed_form_into`] from precomputed (sin, cos) of the crank angles (shared across a
/// batch); the status is written only when a slice is given.
#[allow(clippy::too_many_arguments)]
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
        let spec = crate::simd::closed_form::RowSpec { mode, singular, nan_singular: false };
        return crate::simd::closed_form::closed_form_row(fb, theta2, trig, spec, theta3, theta4, status);
    }
    for (i, (&t2, &(s2, c2))) in theta2.iter().zip(trig).enumerate() {
        let (t3, t4, st) = if !t2.is_finite() {
            (f64::NAN, f64::NAN, Status::NonFinite)
        } else {
            match fb.closed_form_cs(c2, s2, mode) {
                Assembly::Closed { theta3, theta4, sin34 } => {
                    let st = if fb.conditioning(sin34) < singular { Status::Singular } else { Status::Converged };
                    (theta3, theta4, st)
                }
                Assembly::NotAssemblable => (f64::NAN, f64::NAN, Status::NotAssemblable),
                Assembly::Indeterminate => (f64::NAN, f64::NAN, Status::Singular),
            }
        };
        theta3[i] = t3;
        theta4[i] = t4;
        if let Some(s) = status.as_deref_mut() {
            s[i] = st.code();
        }
    }
}

/// Angular velocities at given positions. NaN and `Singular` at dead points.
#[allow(clippy::too_many_arguments)]
pub fn velocity_into(
    fb: &FourBar,
    theta2: &[f64],
    theta3: &[f64],
    theta4: &[f64],
    omega2: &[f64],
    singular: f64,
    omega3: &mut [f64],
    omega4: &mut [f64],
    status: &mut [i8],
) -> Result<(), Error> {
    let n = theta2.len();
    for (name, len) in [("theta3", theta3.len()), ("theta4", theta4.len()), ("omega2", omega2.len())] {
        same_len(name, len, n)?;
    }
    for i in 0..n {
        let (w, st) = fb.velocity(theta2[i], theta3[i], theta4[i], omega2[i], singular);
        omega3[i] = w[0];
        omega4[i] = w[1];
        status[i] = st.code();
    }
    Ok(())
}

/// Angular accelerations at given positions, for crank speed omega2 and acceleration
/// alpha2 (the coupler and rocker speeds are solved on the way).
#[allow(clippy::too_many_arguments)]
pub fn acceleration_into(
    fb: &FourBar,
    theta2: &[f64],
    theta3: &[f64],
    theta4: &[f64],
    omega2: &[f64],
    alpha2: &[f64],
    singular: f64,
    alpha3: &mut [f64],
    alpha4: &mut [f64],
    status: &mut [i8],
) -> Result<(), Error> {
    let n = theta2.len();
    for (name, len) in
        [("theta3", theta3.len()), ("theta4", theta4.len()), ("omega2", omega2.len()), ("alpha2", alpha2.len())]
    {
        same_len(name, len, n)?;
    }
    for i in 0..n {
        let (t2, t3, t4, w2) = (theta2[i], theta3[i], theta4[i], omega2[i]);
        let (w, st) = fb.velocity(t2, t3, t4, w2, singular);
        let (a, st) = if st == Status::Converged {
            fb.acceleration(t2, t3, t4, w2, w[0], w[1], alpha2[i], singular)
        } else {
            ([f64::NAN; 2], st)
        };
        alpha3[i] = a[0];
        alpha4[i] = a[1];
        status[i] = st.code();
    }
    Ok(())
}

/// Coupler-point positions for a point at distance `p` from the crank pin, at angle
/// `delta` from the coupler line.
pub fn coupler_into(
    fb: &FourBar,
    theta2: &[f64],
    theta3: &[f64],
    p: f64,
    delta: f64,
    x: &mut [f64],
    y: &mut [f64],
) -> Result<(), Error> {
    same_len("theta3", theta3.len(), theta2.len())?;
    for i in 0..theta2.len() {
        [x[i], y[i]] = fb.coupler_point(theta2[i], theta3[i], p, delta);
    }
    Ok(())
}

/// Transmission angles (acute, [0, pi/2]) and the branch indicator sin(theta4 - theta3).
pub fn transmission_into(theta3: &[f64], theta4: &[f64], mu: &mut [f64], sin34: &mut [f64]) -> Result<(), Error> {
    same_len("theta4", theta4.len(), theta3.len())?;
    for i in 0..theta3.len() {
        mu[i] = transmission_angle(theta3[i], theta4[i]);
        sin34[i] = (theta4[i] - theta3[i]).sin();
    }
    Ok(())
}
