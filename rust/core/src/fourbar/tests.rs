//! Tests of the four-bar model against independent truths: the design note's and
//! Norton's printed angles, the closed form, finite differences, and scaling.

use std::f64::consts::PI;

use super::model::times_pow2;
use super::*;
use crate::error::Error;
use crate::interrupt::Poll;
use crate::solve::newton::NewtonOptions;
use crate::Status;

const DEG: f64 = PI / 180.0;

fn seed() -> FourBar {
    FourBar::new(6.0, 2.0, 5.0, 5.0).unwrap()
}

#[test]
fn design_note_open_mode_at_zero() {
    // DESIGN.md: r = (6, 2, 5, 5), theta2 = 0, open: theta3 = 66.42 deg, theta4 = 113.58 deg
    let ClosedForm::Solved { theta3, theta4, sin34 } = seed().closed_form(0.0, Mode::Open) else { panic!() };
    assert!((theta3 / DEG - 66.42).abs() < 5e-3);
    assert!((theta4 / DEG - 113.58).abs() < 5e-3);
    assert!(sin34 > 0.0);
}

#[test]
fn norton_example_4_1() {
    // Norton, Design of Machinery, Example 4-1: a=40, b=120, c=80, d=100, theta2=40 deg
    let fb = FourBar::new(100.0, 40.0, 120.0, 80.0).unwrap();
    for (mode, t3, t4) in [(Mode::Open, 20.30, 57.32), (Mode::Crossed, -60.98, -98.00)] {
        let ClosedForm::Solved { theta3, theta4, .. } = fb.closed_form(40.0 * DEG, mode) else { panic!() };
        assert!((theta3 / DEG - t3).abs() < 5e-3, "{mode:?} theta3 {}", theta3 / DEG);
        assert!((theta4 / DEG - t4).abs() < 5e-3, "{mode:?} theta4 {}", theta4 / DEG);
    }
}

#[test]
fn newton_matches_closed_form_from_a_cold_guess() {
    let fb = seed();
    let opts = NewtonOptions::default();
    let p = fb.solve(45.0 * DEG, Mode::Open, Some([80.0 * DEG, 100.0 * DEG]), &opts, None);
    assert_eq!(p.status, Status::Converged);
    let ClosedForm::Solved { theta3, theta4, .. } = fb.closed_form(45.0 * DEG, Mode::Open) else { panic!() };
    assert!((p.theta3 - theta3).abs() < 1e-9 && (p.theta4 - theta4).abs() < 1e-9);
    assert!(p.residual < 1e-9);
}

#[test]
fn crossed_guess_for_open_request_is_a_branch_jump() {
    let fb = seed();
    let ClosedForm::Solved { theta3, theta4, .. } = fb.closed_form(0.3, Mode::Crossed) else { panic!() };
    let p = fb.solve(0.3, Mode::Open, Some([theta3, theta4]), &NewtonOptions::default(), None);
    assert_eq!(p.status, Status::BranchJump);
    assert!(p.theta3.is_nan());
}

#[test]
fn not_assemblable_before_any_iteration() {
    // triple rocker: r2 too long to turn fully
    let fb = FourBar::new(2.0, 5.0, 2.5, 2.0).unwrap();
    let p = fb.solve(PI, Mode::Open, None, &NewtonOptions::default(), None);
    assert_eq!((p.status, p.nit), (Status::NotAssemblable, 0));
}

#[test]
fn invalid_lengths_name_the_parameter() {
    for (i, name) in ["r1", "r2", "r3", "r4"].iter().enumerate() {
        for bad in [0.0, -1.0, f64::NAN, f64::INFINITY] {
            let mut r = [6.0, 2.0, 5.0, 5.0];
            r[i] = bad;
            let e = FourBar::new(r[0], r[1], r[2], r[3]).unwrap_err().to_string();
            assert!(e.starts_with(name), "{e}");
        }
    }
}

#[test]
fn any_scale_gives_the_seed_results() {
    // the problem is scale-free: power-of-two scales are bit-identical, others agree
    // to rounding, down to the smallest and up to the largest lengths a double holds
    let t2: Vec<f64> = crate::fourbar::default_angles(361);
    let opts = crate::fourbar::SweepOptions {
        mode: Mode::Open,
        newton: NewtonOptions::default(),
        predictor: crate::fourbar::Predictor::Quadratic,
        method: crate::fourbar::Method::Newton,
    };
    let base = crate::fourbar::sweep(&seed(), &t2, None, &opts);
    let lim = seed().limits(Mode::Open);
    for k in [-1070, -1000, -340, -200, 0, 200, 340, 1020] {
        let s = times_pow2(1.0, k);
        let fb = FourBar::new(6.0 * s, 2.0 * s, 5.0 * s, 5.0 * s).unwrap();
        let sw = crate::fourbar::sweep(&fb, &t2, None, &opts);
        assert_eq!(sw.status, base.status, "2^{k}");
        assert!(sw.theta3.iter().zip(&base.theta3).all(|(a, b)| a.to_bits() == b.to_bits()), "2^{k}");
        assert_eq!(fb.limits(Mode::Open), lim, "2^{k}");
    }
    for s in [1e-300, 1e-100, 1e-9, 3.0, 1e100, 1e160, 1e300] {
        let fb = FourBar::new(6.0 * s, 2.0 * s, 5.0 * s, 5.0 * s).unwrap();
        let sw = crate::fourbar::sweep(&fb, &t2, None, &opts);
        assert_eq!(sw.status, base.status, "{s}");
        assert!(sw.theta4.iter().zip(&base.theta4).all(|(a, b)| (a - b).abs() < 1e-12), "{s}");
        let l = fb.limits(Mode::Open);
        assert!(l.full_rotation && l.dead_points.is_empty(), "{s}");
    }
}

#[test]
fn lengths_the_unit_problem_cannot_hold_are_rejected() {
    let e = FourBar::new(1e300, 1e-300, 1e300, 1e300).unwrap_err().to_string();
    assert!(e.starts_with("r2 is too short"), "{e}");
    assert!(FourBar::new(5e-324, 1.0, 1.0, 1.0).is_ok());
    assert!(FourBar::new(1.0, 1e-300, 1.0, 1.0).is_ok());
    assert!(FourBar::new(5e-324, 5e-324, 5e-324, 5e-324).is_ok());
}

#[test]
fn an_interrupt_stops_a_long_solve() {
    let opts = NewtonOptions::new(1e-300, 4_294_967_295).unwrap();
    let yes = || true;
    let p = seed().solve_polled(0.5, Mode::Open, Some([1.0, 2.0]), &opts, None, &Poll::new(&yes));
    assert_eq!(p, Err(Error::Interrupted));
}

#[test]
fn velocity_matches_finite_difference_of_closed_form() {
    let fb = seed();
    let (t2, h) = (0.7, 1e-6);
    let cf = |t: f64| match fb.closed_form(t, Mode::Open) {
        ClosedForm::Solved { theta3, theta4, .. } => [theta3, theta4],
        _ => panic!(),
    };
    let [t3, t4] = cf(t2);
    let (w, st) = fb.velocity(t2, t3, t4, 1.0, 1e-7);
    assert_eq!(st, Status::Converged);
    let (p, m) = (cf(t2 + h), cf(t2 - h));
    assert!((w[0] - (p[0] - m[0]) / (2.0 * h)).abs() < 1e-7);
    assert!((w[1] - (p[1] - m[1]) / (2.0 * h)).abs() < 1e-7);
    let (wp, _) = fb.velocity(t2 + h, p[0], p[1], 1.0, 1e-7);
    let (wm, _) = fb.velocity(t2 - h, m[0], m[1], 1.0, 1e-7);
    let (a, _) = fb.acceleration(t2, t3, t4, 1.0, w[0], w[1], 0.0, 1e-7);
    assert!((a[0] - (wp[0] - wm[0]) / (2.0 * h)).abs() < 1e-6);
    assert!((a[1] - (wp[1] - wm[1]) / (2.0 * h)).abs() < 1e-6);
}
