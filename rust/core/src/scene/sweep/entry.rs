//! The sweep's entry, [`Plan::sweep`]: the output checked, the column path tried first
//! where the plan allows it, the continuation over the values (and back from the drawn
//! pose over what it left LIMIT), and LIMIT told from NOT_ASSEMBLABLE.

use super::columns;
use super::continuation::Solver;
use super::options::{ScenePredictor, SceneSweepOptions, SceneSweepOut};
use super::ways;
use crate::error::{quoted, try_zeros, Error};
use crate::interrupt::{Interrupt, Poll};
use crate::scene::build::Plan;
use crate::scene::ops::Op;
use crate::solve::homotopy::HomotopyOptions;
use crate::Status;

/// A column sweep whose every step keeps at least this conditioning (and whose angles are
/// at most `max_step` apart) has met no dead point or change point on its way.
const CERTIFIED: f64 = 0.05;
/// Largest group whose assemblies are counted (by the homotopy) to tell LIMIT from
/// NOT_ASSEMBLABLE at the angles a sweep does not reach.
const CLASSIFIED_GROUP: usize = 4;

impl Plan {
    /// Solves the plan at every input value of `theta` (radians, or a linear input's
    /// displacements; any order, any number of turns): each value's pose is the one
    /// reached from the drawn pose by moving the input straight to it, or where a dead
    /// point stops that, for an angle, the other way round (see `ways`); a value neither
    /// way reaches is LIMIT, and names the dead point met on the shorter way. The answer at
    /// a value does not depend on the other values in the array. What stays LIMIT is
    /// NOT_ASSEMBLABLE where the linkage has no assembly at all.
    /// [`ScenePredictor::ClosedForm`] solves every value on its own instead (plans with no
    /// group; an [`Error::InvalidParameter`] naming `predictor` otherwise).
    /// `interrupt` is asked every few thousand angles (Ctrl-C from Python).
    pub fn sweep(
        &self,
        theta: &[f64],
        opts: &SceneSweepOptions,
        mut out: SceneSweepOut<'_>,
        interrupt: &dyn Interrupt,
    ) -> Result<(), Error> {
        let poll = Poll::new(interrupt);
        let n = theta.len();
        let (np, nl, ns) = (self.points.len(), self.links.len(), self.steps.len());
        let check = |name: &str, got: usize, expected: usize| {
            if got == expected {
                Ok(())
            } else {
                Err(Error::Shape { name: name.into(), got, expected })
            }
        };
        check("points", out.points.len(), n * np * 2)?;
        check("angles", out.angles.len(), n * nl)?;
        check("status", out.status.len(), n)?;
        check("nit", out.nit.len(), n)?;
        check("det", out.det.len(), n)?;
        check("limit", out.limit.len(), n)?;
        check("step_status", out.step_status.len(), n * ns)?;
        check("step_det", out.step_det.len(), n * ns)?;
        check("point_status", out.point_status.len(), n * np)?;
        if let Some((v, w)) = out.velocity.as_ref() {
            check("velocity", v.len(), n * np * 2)?;
            check("angular velocity", w.len(), n * nl)?;
        }
        if let Some((v, w)) = out.acceleration.as_ref() {
            check("acceleration", v.len(), n * np * 2)?;
            check("angular acceleration", w.len(), n * nl)?;
        }
        if opts.predictor == ScenePredictor::ClosedForm {
            return self.closed_form_sweep(theta, opts, out, &poll);
        }
        let stops = self.stops(opts, &poll)?;
        // (no stops, no check; else a count with no early exit, which vectorizes)
        let within = || {
            stops == (f64::NEG_INFINITY, f64::INFINITY)
                || theta.iter().map(|&t| (t.is_finite() & !(stops.0 <= t && t <= stops.1)) as usize).sum::<usize>() == 0
        };
        if self.columns_ok() && within() {
            columns::sweep(self, theta, opts, &mut out, &poll)?;
            if self.certified(theta, opts, &out) {
                return Ok(());
            }
        }
        let limit = Status::Limit.code();
        // the links' directions, turned into angles at the end in one vectorized pass
        let mut dirs = try_zeros(|| "the links' directions".to_string(), 2 * n * nl)?;
        let nonfinite: Vec<usize> = (0..n).filter(|&k| !theta[k].is_finite()).collect();
        if !nonfinite.is_empty() {
            let mut s = Solver::new(self, *opts);
            s.eval(f64::NAN);
            for &k in &nonfinite {
                s.write(k, &mut out, &mut dirs);
            }
        }
        for run in ways::direct(theta, self.theta0) {
            self.continuation(&run, None, stops, opts, &mut out, &mut dirs, &poll)?;
        }
        // an angle stopped by a dead point one way may be reached the other way round
        if !self.linear {
            let stopped = (0..n).filter(|&k| out.status[k] == limit);
            for run in ways::other(theta, self.theta0, stopped) {
                self.continuation(&run, Some(theta), stops, opts, &mut out, &mut dirs, &poll)?;
            }
        }
        let (dx, dy) = dirs.split_at(n * nl);
        crate::simd::directions_into(dx, dy, out.angles);
        non_finite_rows(theta, &mut out);
        if !opts.classify {
            return Ok(());
        }
        self.classify_limits(theta, &mut out, interrupt)
    }

    /// [`ScenePredictor::ClosedForm`]: the column sweep as it is (every value on its own,
    /// each operation on its drawn side), with the values where the drawn sides do not
    /// close told apart: LIMIT where some other assembly exists, NOT_ASSEMBLABLE where none.
    fn closed_form_sweep(
        &self,
        theta: &[f64],
        opts: &SceneSweepOptions,
        mut out: SceneSweepOut<'_>,
        poll: &Poll<'_>,
    ) -> Result<(), Error> {
        if !self.columns_ok() {
            return Err(Error::invalid(
                "predictor",
                "must be 'continuation' for a plan with a group solved by Newton ('closed-form' \
                 solves dyads, sliders and carries)",
                quoted("closed-form"),
            ));
        }
        columns::sweep(self, theta, opts, &mut out, poll)?;
        non_finite_rows(theta, &mut out);
        // each value on its own, but not past a limit the motion from the drawn pose meets
        let stops = self.stops(opts, poll)?;
        for (k, &t) in theta.iter().enumerate() {
            if t.is_finite() && !(stops.0 <= t && t <= stops.1) {
                self.mark_stopped(k, if t > stops.1 { stops.1 } else { stops.0 }, &mut out);
            }
        }
        // a closed form that does not close says NOT_ASSEMBLABLE of its own step; whether
        // the linkage has no assembly at all is the classification's to say
        let (limit, none) = (Status::Limit.code(), Status::NotAssemblable.code());
        for codes in [&mut *out.status, &mut *out.step_status, &mut *out.point_status] {
            // a select per code, no branch: the loop vectorizes
            for code in codes.iter_mut() {
                *code = if *code == none { limit } else { *code };
            }
        }
        self.classify_limits(theta, &mut out, poll.source())
    }

    /// A column sweep (dyads and sliders on their drawn sides) is the drawn circuit's
    /// motion when no step came near a dead point: every input value solved, each step's
    /// conditioning at least [`CERTIFIED`] in size, and the ways from the drawn value to
    /// every value crossed in steps of at most `max_step` ([`ways::covered`]). Otherwise
    /// the plan is followed by continuation.
    fn certified(&self, theta: &[f64], opts: &SceneSweepOptions, out: &SceneSweepOut<'_>) -> bool {
        let ok = Status::Converged.code();
        // folds with no early exit: these loops vectorize
        out.status.iter().fold(true, |all, &s| all & (s == ok))
            && out.step_det.iter().fold(true, |all, d| all & (d.abs() >= CERTIFIED))
            && ways::covered(theta, self.theta0, opts.max_step, self.linear)
    }

    /// An angle that the drawn circuit does not reach is LIMIT when the linkage has some
    /// assembly there (another circuit or branch) and NOT_ASSEMBLABLE when it has none:
    /// every assembly is enumerated there (dyad sides; the homotopy for groups of at most
    /// [`CLASSIFIED_GROUP`] links). A plan with a larger group keeps LIMIT (its all-solution
    /// solve costs milliseconds per angle: [`Plan::assemblies`] answers it on request).
    fn classify_limits(
        &self,
        theta: &[f64],
        out: &mut SceneSweepOut<'_>,
        interrupt: &dyn Interrupt,
    ) -> Result<(), Error> {
        let (limit, none) = (Status::Limit.code(), Status::NotAssemblable.code());
        let (np, ns) = (self.points.len(), self.steps.len());
        let hopts = HomotopyOptions::default();
        if self.ops.iter().any(|o| matches!(o, Op::Group(g) if g.n() > CLASSIFIED_GROUP)) {
            return Ok(());
        }
        for (k, &t) in theta.iter().enumerate() {
            if out.status[k] != limit || !t.is_finite() {
                continue;
            }
            if !self.assemblies(t, &hopts, interrupt)?.list.is_empty() {
                continue;
            }
            // no assembly at all: no dead point to name
            out.status[k] = none;
            out.limit[k] = f64::NAN;
            for code in
                out.step_status[k * ns..(k + 1) * ns].iter_mut().chain(&mut out.point_status[k * np..(k + 1) * np])
            {
                if *code == limit {
                    *code = none;
                }
            }
        }
        Ok(())
    }

    /// Continuation from the drawn pose along `run` (one way, in order). The direct ways
    /// (`other` None) write every row; the other way round (`other`: the values asked for)
    /// writes only the rows the direct way left LIMIT, and where it is stopped too, names
    /// its dead point when it is the shorter way.
    fn continuation(
        &self,
        run: &ways::Run,
        other: Option<&[f64]>,
        stops: (f64, f64),
        opts: &SceneSweepOptions,
        out: &mut SceneSweepOut<'_>,
        dirs: &mut [f64],
        poll: &Poll<'_>,
    ) -> Result<(), Error> {
        if run.is_empty() {
            return Ok(());
        }
        let mut s = Solver::new(self, *opts);
        // tangents at the drawn pose
        s.eval(self.theta0);
        // rows past a limit's stop: a solver that solved nothing writes them
        let mut idle: Option<Solver<'_>> = None;
        for &(k, t) in run {
            poll.tick()?;
            if !(stops.0 <= t && t <= stops.1) {
                let stop = if t > stops.1 { stops.1 } else { stops.0 };
                match other {
                    // the other way is stopped too: name it where it is the shorter way
                    Some(asked) => {
                        if (t - self.theta0).abs() < (asked[k] - self.theta0).abs() {
                            out.limit[k] = stop;
                        }
                    }
                    None => {
                        let idle = idle.get_or_insert_with(|| {
                            let mut z = Solver::new(self, *opts);
                            z.eval(f64::NAN);
                            z
                        });
                        self.write_stopped(k, stop, idle, out, dirs);
                    }
                }
                continue;
            }
            s.nit = 0;
            s.advance(t, poll)?;
            if let Some(asked) = other {
                if s.status() == Status::Limit {
                    if (t - self.theta0).abs() < (asked[k] - self.theta0).abs() {
                        out.limit[k] = s.limit_angle();
                    }
                    continue;
                }
                // the same pose, solved at the angle asked for (not a turn away)
                let turns = asked[k] - t;
                s.shift(turns);
                s.eval(asked[k]);
                s.write(k, out, dirs);
                s.shift(-turns);
                continue;
            }
            s.write(k, out, dirs);
            out.limit[k] = s.limit_angle();
        }
        Ok(())
    }
}

/// A NaN or infinite input value is NON_FINITE wherever it leaves something unsolved (a
/// linear input's closed forms would call it NOT_ASSEMBLABLE).
fn non_finite_rows(theta: &[f64], out: &mut SceneSweepOut<'_>) {
    let (ok, bad) = (Status::Converged.code(), Status::NonFinite.code());
    let (np, ns) = (out.point_status.len() / theta.len().max(1), out.step_status.len() / theta.len().max(1));
    for k in (0..theta.len()).filter(|&k| !theta[k].is_finite()) {
        out.limit[k] = f64::NAN;
        for code in std::iter::once(&mut out.status[k])
            .chain(&mut out.step_status[k * ns..(k + 1) * ns])
            .chain(&mut out.point_status[k * np..(k + 1) * np])
        {
            if *code != ok {
                *code = bad;
            }
        }
    }
}
