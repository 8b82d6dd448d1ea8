//! Continuation sweep over crank angles: each point starts from the previous solution
//! (or a tangent prediction from it); a point whose continuation fails falls back to the
//! closed form of the requested mode, so the sweep never follows the other branch.

use nalgebra::{Matrix2, Vector2};

use crate::error::{try_zeros, Error};
use crate::fourbar::{cramer, Assembly, FourBar, Geometry, Loop, Mode, Point};
use crate::interrupt::{Interrupt, Never, Poll};
use crate::newton::NewtonOptions;
use crate::{wrap_angle, Status};

/// How the next point's first guess is made from the last converged one.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub enum Predictor {
    /// The previous solution itself (zeroth order; the seeds' continuation).
    Previous,
    /// First order: x + dtheta2 * dx/dtheta2, with dx/dtheta2 = -J^-1 dF/dtheta2.
    Tangent,
    /// Second order: adds dtheta2^2 / 2 * d2x/dtheta2^2 from the acceleration solve.
    Quadratic,
}

impl Predictor {
    /// Parses "previous" / "tangent" / "quadratic".
    pub fn parse(s: &str) -> Result<Self, Error> {
        match s {
            "previous" => Ok(Predictor::Previous),
            "tangent" => Ok(Predictor::Tangent),
            "quadratic" => Ok(Predictor::Quadratic),
            other => {
                Err(Error::invalid("predictor", "must be 'previous', 'tangent' or 'quadratic'", format!("{other:?}")))
            }
        }
    }
}

/// How each point of a sweep is solved.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub enum Method {
    /// Newton-Raphson with continuation: the general solver (multi-loop linkages have no
    /// closed form).
    Newton,
    /// The four-bar's closed form: no iterations, no residual computed (NaN), the same
    /// statuses; fastest where it exists.
    ClosedForm,
}

impl Method {
    /// Parses "newton" / "closed-form".
    pub fn parse(s: &str) -> Result<Self, Error> {
        match s {
            "newton" => Ok(Method::Newton),
            "closed-form" => Ok(Method::ClosedForm),
            other => Err(Error::invalid("method", "must be 'newton' or 'closed-form'", format!("{other:?}"))),
        }
    }
}

/// Everything a sweep needs besides the linkage and the angles.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct SweepOptions {
    /// Assembly mode to solve at every point.
    pub mode: Mode,
    /// Newton stopping criteria (also the singular threshold of the closed form).
    pub newton: NewtonOptions,
    /// First-guess predictor (Newton only).
    pub predictor: Predictor,
    /// Newton-Raphson or the closed form.
    pub method: Method,
}

/// Output slices of one sweep, all of the length of the crank-angle array.
pub struct SweepOut<'a> {
    pub theta3: &'a mut [f64],
    pub theta4: &'a mut [f64],
    pub status: &'a mut [i8],
    pub nit: &'a mut [u32],
    pub residual: &'a mut [f64],
}

/// Optional velocity (and acceleration) outputs, computed only when asked for.
pub struct MotionOut<'a> {
    /// Crank angular velocity.
    pub omega2: f64,
    pub omega3: &'a mut [f64],
    pub omega4: &'a mut [f64],
    /// Crank angular acceleration and the alpha3, alpha4 outputs.
    pub alpha: Option<(f64, &'a mut [f64], &'a mut [f64])>,
}

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
        }
    }
}

fn check_len(name: &str, got: usize, expected: usize) -> Result<(), Error> {
    if got == expected {
        Ok(())
    } else {
        Err(Error::Shape { name: name.to_string(), got, expected })
    }
}

impl SweepOut<'_> {
    fn check(&self, n: usize) -> Result<(), Error> {
        check_len("theta3", self.theta3.len(), n)?;
        check_len("theta4", self.theta4.len(), n)?;
        check_len("status", self.status.len(), n)?;
        check_len("nit", self.nit.len(), n)?;
        check_len("residual", self.residual.len(), n)
    }
}

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
        check_len("omega3", m.omega3.len(), n)?;
        check_len("omega4", m.omega4.len(), n)?;
        if let Some((_, a3, a4)) = &m.alpha {
            check_len("alpha3", a3.len(), n)?;
            check_len("alpha4", a4.len(), n)?;
        }
    }
    sweep_unchecked(fb, theta2, &sin_cos(theta2)?, guess, opts, out, motion, &Poll::new(interrupt))
}

/// (sin, cos) of every crank angle: computed once, shared by every linkage of a batch
/// (4 at a time by polynomials when [`crate::simd::enabled`], libm otherwise). Allocated
/// fallibly ([`Error::Allocation`]).
pub fn sin_cos(theta2: &[f64]) -> Result<Vec<(f64, f64)>, Error> {
    let mut v = try_zeros::<(f64, f64)>(|| format!("sin and cos of {} crank angles", theta2.len()), theta2.len())?;
    if crate::simd::enabled() {
        crate::simd::sin_cos_into(theta2, &mut v);
        return Ok(v);
    }
    for (o, t) in v.iter_mut().zip(theta2) {
        *o = t.sin_cos();
    }
    Ok(v)
}

/// [`sweep_into`] for slices known to have the right lengths (the batch kernel).
#[allow(clippy::too_many_arguments)]
pub(crate) fn sweep_unchecked(
    fb: &FourBar,
    theta2: &[f64],
    trig: &[(f64, f64)],
    guess: Option<[f64; 2]>,
    opts: &SweepOptions,
    out: SweepOut<'_>,
    motion: Option<MotionOut<'_>>,
    poll: &Poll<'_>,
) -> Result<(), Error> {
    if opts.method == Method::ClosedForm {
        return closed_form_sweep(fb, theta2, trig, opts, out, motion, poll);
    }
    if crate::simd::enabled() {
        return crate::simd::sweep::newton_row(fb, theta2, trig, guess, opts, out, motion, poll);
    }
    newton_sweep(fb, theta2, trig, guess, opts, out, motion, poll)
}

/// The scalar Newton continuation sweep (bit-identical to the NumPy reference).
#[allow(clippy::too_many_arguments)]
pub(crate) fn newton_sweep(
    fb: &FourBar,
    theta2: &[f64],
    trig: &[(f64, f64)],
    guess: Option<[f64; 2]>,
    opts: &SweepOptions,
    out: SweepOut<'_>,
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
        let (point, j) = if t2.is_finite() {
            let (s2, c2) = trig[i];
            let sys = fb.at_sin_cos(s2, c2);
            let (point, j) = sweep_point(fb, &sys, start, opts, poll)?;
            (point, Some((j, (sys.s2, sys.c2))))
        } else {
            (Point::failed(Status::NonFinite, 0, f64::NAN), None)
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
        prev = match (converged, j) {
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
fn closed_form_sweep(
    fb: &FourBar,
    theta2: &[f64],
    trig: &[(f64, f64)],
    opts: &SweepOptions,
    out: SweepOut<'_>,
    mut motion: Option<MotionOut<'_>>,
    poll: &Poll<'_>,
) -> Result<(), Error> {
    if crate::simd::enabled() {
        return crate::simd::closed_form::sweep(fb, theta2, trig, opts, out, motion, poll);
    }
    for (i, (&t2, &(s2, c2))) in theta2.iter().zip(trig).enumerate() {
        poll.tick()?;
        let status = if !t2.is_finite() {
            Status::NonFinite
        } else {
            match fb.closed_form_cs(c2, s2, opts.mode) {
                Assembly::Closed { theta3, theta4, sin34 } if fb.conditioning(sin34) >= opts.newton.singular => {
                    out.theta3[i] = theta3;
                    out.theta4[i] = theta4;
                    Status::Converged
                }
                Assembly::NotAssemblable => Status::NotAssemblable,
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
    let _ = sweep_unchecked(fb, theta2, &trig, guess, opts, out, None, &Poll::new(&Never));
    s
}

/// Default sweep angles: 0..=2 pi in `n - 1` equal steps (361 points: 1 degree apart).
pub fn default_angles(n: usize) -> Vec<f64> {
    let step = std::f64::consts::TAU / (n.max(2) - 1) as f64;
    (0..n).map(|i| i as f64 * step).collect()
}

#[cfg(test)]
mod tests {
    use super::*;

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
                    let Assembly::Closed { theta3, theta4, sin34 } = fb.closed_form(t2[i], mode) else { panic!() };
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
                Assembly::Closed { theta3, .. } => {
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
            assert_eq!(cf == Assembly::NotAssemblable, s[i] == na);
            if s[i] == na {
                assert_eq!(k[i], 0);
            }
        }
    }
}
