//! Pointwise kernels over arrays (no continuation): closed form, velocity, acceleration,
//! coupler points and transmission angles. Each writes into caller-owned slices of the
//! same length; the bindings broadcast and allocate, these only compute. Each asks its
//! `interrupt` every [`crate::interrupt::CHECK_EVERY`] points ([`Error::Interrupted`]).

use super::model::{transmission_angle, FourBar, Mode};
use super::options::check_len;
use super::row::{closed_form_trig, sin_cos_fill};
use crate::error::{finite, Error};
use crate::interrupt::{Interrupt, Poll};
use crate::Status;

/// Crank rates must be finite: a NaN rate would give NaN rates at solved points.
fn all_finite(name: &str, rates: &[f64]) -> Result<(), Error> {
    match rates.iter().find(|v| !v.is_finite()) {
        Some(&v) => finite(name, v).map(|_| ()),
        None => Ok(()),
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
    interrupt: &dyn Interrupt,
) -> Result<(), Error> {
    // blocks of angles: the (sin, cos) table of each (4 at a time with SIMD) stays small,
    // and the interrupt is asked between blocks
    const BLOCK: usize = 4096;
    let n = theta2.len();
    for (name, len) in [("theta3", theta3.len()), ("theta4", theta4.len()), ("status", status.len())] {
        check_len(name, len, n)?;
    }
    let poll = Poll::new(interrupt);
    let mut trig = vec![(0.0, 0.0); BLOCK.min(theta2.len())];
    for (k, t) in theta2.chunks(BLOCK).enumerate() {
        for _ in t {
            poll.tick()?;
        }
        let (o, e) = (k * BLOCK, k * BLOCK + t.len());
        let tr = &mut trig[..t.len()];
        sin_cos_fill(t, tr);
        closed_form_trig(fb, t, tr, mode, singular, &mut theta3[o..e], &mut theta4[o..e], Some(&mut status[o..e]));
    }
    Ok(())
}

/// Angular velocities at given positions. NaN and `Singular` at dead points; a crank speed
/// that is not finite is an error naming `omega2`.
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
    interrupt: &dyn Interrupt,
) -> Result<(), Error> {
    let n = theta2.len();
    for (name, len) in [("theta3", theta3.len()), ("theta4", theta4.len()), ("omega2", omega2.len())] {
        check_len(name, len, n)?;
    }
    all_finite("omega2", omega2)?;
    let poll = Poll::new(interrupt);
    for i in 0..n {
        poll.tick()?;
        let (w, st) = fb.velocity(theta2[i], theta3[i], theta4[i], omega2[i], singular);
        omega3[i] = w[0];
        omega4[i] = w[1];
        status[i] = st.code();
    }
    Ok(())
}

/// Angular accelerations at given positions, for crank speed omega2 and acceleration
/// alpha2 (the coupler and rocker speeds are solved on the way).
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
    interrupt: &dyn Interrupt,
) -> Result<(), Error> {
    let n = theta2.len();
    for (name, len) in
        [("theta3", theta3.len()), ("theta4", theta4.len()), ("omega2", omega2.len()), ("alpha2", alpha2.len())]
    {
        check_len(name, len, n)?;
    }
    all_finite("omega2", omega2)?;
    all_finite("alpha2", alpha2)?;
    let poll = Poll::new(interrupt);
    for i in 0..n {
        poll.tick()?;
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
    interrupt: &dyn Interrupt,
) -> Result<(), Error> {
    check_len("theta3", theta3.len(), theta2.len())?;
    let poll = Poll::new(interrupt);
    for i in 0..theta2.len() {
        poll.tick()?;
        [x[i], y[i]] = fb.coupler_point(theta2[i], theta3[i], p, delta);
    }
    Ok(())
}

/// Transmission angles (acute, [0, pi/2]) and the branch indicator sin(theta4 - theta3).
pub fn transmission_into(
    theta3: &[f64],
    theta4: &[f64],
    mu: &mut [f64],
    sin34: &mut [f64],
    interrupt: &dyn Interrupt,
) -> Result<(), Error> {
    check_len("theta4", theta4.len(), theta3.len())?;
    let poll = Poll::new(interrupt);
    for i in 0..theta3.len() {
        poll.tick()?;
        mu[i] = transmission_angle(theta3[i], theta4[i]);
        sin34[i] = (theta4[i] - theta3[i]).sin();
    }
    Ok(())
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::Never;

    #[test]
    fn pointwise_kernels_stop_when_interrupted() {
        let fb = FourBar::new(6.0, 2.0, 5.0, 5.0).unwrap();
        let n = 3 * crate::interrupt::CHECK_EVERY as usize;
        let t = vec![0.5; n];
        let (mut a, mut b, mut st) = (vec![0.0; n], vec![0.0; n], vec![0i8; n]);
        let yes = || true;
        let r = closed_form_into(&fb, &t, Mode::Open, 1e-6, &mut a, &mut b, &mut st, &yes);
        assert_eq!(r, Err(Error::Interrupted));
        closed_form_into(&fb, &t, Mode::Open, 1e-6, &mut a, &mut b, &mut st, &Never).unwrap();
        assert!(st.iter().all(|&s| s == 0));
        let (mut c, mut d) = (vec![0.0; n], vec![0.0; n]);
        let w = vec![1.0; n];
        assert_eq!(velocity_into(&fb, &t, &a, &b, &w, 1e-6, &mut c, &mut d, &mut st, &yes), Err(Error::Interrupted));
        assert_eq!(coupler_into(&fb, &t, &a, 1.0, 0.0, &mut c, &mut d, &yes), Err(Error::Interrupted));
        assert_eq!(transmission_into(&a, &b, &mut c, &mut d, &yes), Err(Error::Interrupted));
    }
}
