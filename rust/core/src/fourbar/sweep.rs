//! The four-bar sweep over crank angles: continuation (each point starts from the
//! previous solution or a prediction from it; a point whose continuation fails falls back
//! to the closed form of the requested mode, so the sweep never follows the other
//! branch), or the closed form point by point.

use super::model::FourBar;
use super::options::{check_len, MotionOut, SweepOptions, SweepOut};
use super::row::{sin_cos_table, sweep_row};
use crate::error::{finite, Error};
use crate::interrupt::{Interrupt, Never, Poll};

/// Sweeps `theta2` in order into `out` (and `motion` when given). `guess` seeds the
/// first point instead of the closed form. `interrupt` is asked every
/// [`crate::interrupt::CHECK_EVERY`] points and Newton steps; when it says stop, the sweep
/// returns [`Error::Interrupted`] (the outputs are then partly written).
pub fn sweep_into(
    fb: &FourBar,
    theta2: &[f64],
    guess: Option<[f64; 2]>,
    opts: &SweepOptions,
    out: SweepOut<'_>,
    motion: Option<MotionOut<'_>>,
    interrupt: &dyn Interrupt,
) -> Result<(), Error> {
    let n = theta2.len();
    out.check(n)?;
    if let Some(m) = &motion {
        finite("omega2", m.omega2)?;
        if let Some((alpha2, _, _)) = &m.alpha {
            finite("alpha2", *alpha2)?;
        }
        check_len("omega3", m.omega3.len(), n)?;
        check_len("omega4", m.omega4.len(), n)?;
        if let Some((_, a3, a4)) = &m.alpha {
            check_len("alpha3", a3.len(), n)?;
            check_len("alpha4", a4.len(), n)?;
        }
    }
    sweep_row(fb, theta2, &sin_cos_table(theta2)?, guess, opts, out, motion, &Poll::new(interrupt))
}

/// Owned results of one sweep, for Rust callers (the bindings fill their own buffers).
#[derive(Clone, Debug, Default, PartialEq)]
pub struct Sweep {
    pub theta3: Vec<f64>,
    pub theta4: Vec<f64>,
    pub status: Vec<i8>,
    pub nit: Vec<u32>,
    pub residual: Vec<f64>,
}

/// Sweeps `theta2` into a freshly allocated [`Sweep`].
pub fn sweep(fb: &FourBar, theta2: &[f64], guess: Option<[f64; 2]>, opts: &SweepOptions) -> Sweep {
    let n = theta2.len();
    let mut s = Sweep {
        theta3: vec![0.0; n],
        theta4: vec![0.0; n],
        status: vec![0; n],
        nit: vec![0; n],
        residual: vec![0.0; n],
    };
    let out = SweepOut {
        theta3: &mut s.theta3,
        theta4: &mut s.theta4,
        status: &mut s.status,
        nit: &mut s.nit,
        residual: &mut s.residual,
    };
    let trig: Vec<(f64, f64)> = theta2.iter().map(|t| t.sin_cos()).collect();
    // Never interrupts: the sweep always completes
    let _ = sweep_row(fb, theta2, &trig, guess, opts, out, None, &Poll::new(&Never));
    s
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::fourbar::{default_angles, ClosedForm, Method, Mode, Predictor};
    use crate::solve::newton::NewtonOptions;
    use crate::{wrap_angle, Status};

    fn run(fb: &FourBar, t2: &[f64], opts: &SweepOptions) -> Sweep {
        sweep(fb, t2, None, opts)
    }

    fn opts(mode: Mode, predictor: Predictor) -> SweepOptions {
        SweepOptions { mode, newton: NewtonOptions::default(), predictor, method: Method::Newton }
    }

    #[test]
    fn seed_sweep_matches_the_closed_form_within_the_residual_bound() {
        // tol bounds the residual; the angle error is bounded by
        // sqrt(2) * residual * L / (r_other * |sin(theta4 - theta3)|) to first order.
        let fb = FourBar::new(6.0, 2.0, 5.0, 5.0).unwrap();
        let t2 = default_angles(361);
        for mode in [Mode::Open, Mode::Crossed] {
            for p in [Predictor::Previous, Predictor::Tangent, Predictor::Quadratic] {
                let Sweep { theta3: a, theta4: b, status: s, residual: r, .. } = run(&fb, &t2, &opts(mode, p));
                assert!(s.iter().all(|&c| c == 0));
                for i in 0..t2.len() {
                    let ClosedForm::Solved { theta3, theta4, sin34 } = fb.closed_form(t2[i], mode) else { panic!() };
                    let bound = 1.01 * 2f64.sqrt() * r[i] * 6.0 / (5.0 * sin34.abs()) + 1e-14;
                    assert!(wrap_angle(a[i] - theta3).abs() <= bound, "{mode:?} {p:?} {i}");
                    assert!(wrap_angle(b[i] - theta4).abs() <= bound, "{mode:?} {p:?} {i}");
                    if p == Predictor::Quadratic {
                        assert!(wrap_angle(a[i] - theta3).abs() < 1e-9);
                    }
                }
            }
        }
    }

    #[test]
    fn closed_form_method_gives_the_closed_form_with_statuses() {
        let fb = FourBar::new(2.0, 5.0, 2.5, 2.0).unwrap(); // triple rocker: unreachable spans
        let t2 = default_angles(361);
        let o = SweepOptions { method: Method::ClosedForm, ..opts(Mode::Crossed, Predictor::Quadratic) };
        let s = sweep(&fb, &t2, None, &o);
        for (i, &t) in t2.iter().enumerate() {
            match fb.closed_form(t, Mode::Crossed) {
                ClosedForm::Solved { theta3, .. } => {
                    assert_eq!(s.status[i], 0);
                    // bit for bit on the scalar path; the SIMD path's crank trigonometry and
                    // atan2 differ from libm's by ulps
                    assert!((s.theta3[i] - theta3).abs() <= 1e-12);
                }
                _ => assert_eq!(s.status[i], Status::NotAssemblable.code()),
            }
            assert!(s.nit[i] == 0 && s.residual[i].is_nan());
        }
        assert!(Method::parse("bogus").unwrap_err().to_string().starts_with("method "));
    }

    #[test]
    fn tangent_predictor_needs_fewer_iterations() {
        let fb = FourBar::new(6.0, 2.0, 5.0, 5.0).unwrap();
        let t2 = default_angles(361);
        let total = |p| run(&fb, &t2, &opts(Mode::Open, p)).nit.iter().sum::<u32>();
        let (prev, tan) = (total(Predictor::Previous), total(Predictor::Tangent));
        assert!(tan < prev, "tangent {tan} vs previous {prev}");
    }

    #[test]
    fn non_grashof_sweep_flags_unreachable_angles_and_carries_on() {
        let fb = FourBar::new(2.0, 5.0, 2.5, 2.0).unwrap(); // crank cannot turn fully
        let t2 = default_angles(361);
        let Sweep { status: s, nit: k, .. } = run(&fb, &t2, &opts(Mode::Open, Predictor::Tangent));
        let na = Status::NotAssemblable.code();
        assert!(s.contains(&na) && s.contains(&0));
        for i in 0..t2.len() {
            let cf = fb.closed_form(t2[i], Mode::Open);
            assert_eq!(cf == ClosedForm::NotAssemblable, s[i] == na);
            if s[i] == na {
                assert_eq!(k[i], 0);
            }
        }
    }
}
