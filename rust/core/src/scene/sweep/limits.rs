//! Travel limits in a sweep: where along each way from the drawn pose a limit first binds
//! (the stops), found by following the motion out from the drawn pose and bisecting the
//! step that crosses a limit; a value past its way's stop is LIMIT and names the stop.

use super::continuation::Solver;
use super::options::{SceneSweepOptions, SceneSweepOut};
use crate::error::Error;
use crate::interrupt::Poll;
use crate::scene::build::Plan;
use crate::Status;
use std::f64::consts::TAU;

/// How far the stops are looked for along a linear input, in solving-frame units (the
/// drawing's size is about 1 there).
const LINEAR_REACH: f64 = 8.0;
/// Bisections of the step that crosses a limit (its length halves each time).
const BISECTIONS: u32 = 60;

impl Solver<'_> {
    /// Every limit holds at the last evaluation, to rounding (a linear input's own limit is
    /// met exactly at its bound, whose coordinate reads a few ulp either side).
    pub(super) fn inside_limits(&self) -> bool {
        let plan = self.plan;
        plan.limits.iter().all(|l| {
            let v = l.value(&self.pos, plan.scale);
            let slack = 16.0 * f64::EPSILON * (l.range.0.abs() + l.range.1.abs());
            v >= l.range.0 - slack && v <= l.range.1 + slack
        })
    }
}

impl Plan {
    /// The input values `(lo, hi)` around the drawn one where the motion from the drawn
    /// pose first meets a limit going down and up (infinite where it meets none: within a
    /// turn for an angle, or before a dead point).
    pub(super) fn stops(&self, opts: &SceneSweepOptions, poll: &Poll<'_>) -> Result<(f64, f64), Error> {
        if self.limits.is_empty() {
            return Ok((f64::NEG_INFINITY, f64::INFINITY));
        }
        let span = if self.linear { LINEAR_REACH * self.scale } else { TAU };
        let mut ends = [f64::NEG_INFINITY, f64::INFINITY];
        for (end, dir) in ends.iter_mut().zip([-1.0, 1.0]) {
            let mut s = Solver::new(self, *opts);
            s.eval(self.theta0);
            let m = (span / opts.max_step).ceil().max(1.0) as usize;
            let mut inside = self.theta0;
            for k in 1..=m {
                poll.tick()?;
                let t = self.theta0 + dir * span * (k as f64 / m as f64);
                let before = s.clone();
                s.advance(t, poll)?;
                if s.status() != Status::Converged {
                    break; // a dead point first: the continuation stops there
                }
                if s.inside_limits() {
                    inside = t;
                    continue;
                }
                // bisect (inside, t]: the last value inside
                let mut out = t;
                for _ in 0..BISECTIONS {
                    let mid = 0.5 * (inside + out);
                    if mid == inside || mid == out {
                        break;
                    }
                    let mut probe = before.clone();
                    probe.advance(mid, poll)?;
                    if probe.status() == Status::Converged && probe.inside_limits() {
                        inside = mid;
                    } else {
                        out = mid;
                    }
                }
                *end = inside;
                break;
            }
        }
        Ok((ends[0], ends[1]))
    }

    /// Row `k` past a stop: nothing moves there (the input cannot reach it): LIMIT, naming
    /// the stop; only the ground's points are placed.
    pub(super) fn write_stopped(
        &self,
        k: usize,
        stop: f64,
        idle: &Solver<'_>,
        out: &mut SceneSweepOut<'_>,
        dirs: &mut [f64],
    ) {
        idle.write(k, out, dirs);
        let (np, ns) = (self.points.len(), self.steps.len());
        let (ok, limit) = (Status::Converged.code(), Status::Limit.code());
        out.status[k] = limit;
        for code in out.step_status[k * ns..(k + 1) * ns].iter_mut().chain(&mut out.point_status[k * np..(k + 1) * np])
        {
            if *code != ok {
                *code = limit;
            }
        }
        out.limit[k] = stop;
    }

    /// Row `k` of a sweep written already, marked past a stop: LIMIT, naming the stop;
    /// only the ground's points keep their place.
    pub(super) fn mark_stopped(&self, k: usize, stop: f64, out: &mut SceneSweepOut<'_>) {
        let (np, nl, ns) = (self.points.len(), self.links.len(), self.steps.len());
        let fixed = |p: usize| self.fixed.iter().any(|f| f.0 == p);
        let limit = Status::Limit.code();
        out.status[k] = limit;
        out.det[k] = f64::NAN;
        out.limit[k] = stop;
        out.step_status[k * ns..(k + 1) * ns].fill(limit);
        out.step_det[k * ns..(k + 1) * ns].fill(f64::NAN);
        for (j, &p) in self.points.iter().enumerate() {
            if !fixed(p) {
                out.point_status[k * np + j] = limit;
                out.points[2 * (k * np + j)..2 * (k * np + j) + 2].fill(f64::NAN);
            }
        }
        for (j, &(a, b)) in self.link_points.iter().enumerate() {
            if !(fixed(a) && fixed(b)) {
                out.angles[k * nl + j] = f64::NAN;
            }
        }
        for rates in [out.velocity.as_mut(), out.acceleration.as_mut()].into_iter().flatten() {
            rates.0[2 * k * np..2 * (k + 1) * np].fill(f64::NAN);
            rates.1[k * nl..(k + 1) * nl].fill(f64::NAN);
        }
    }
}
