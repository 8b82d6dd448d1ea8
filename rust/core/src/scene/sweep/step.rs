//! Step control of the continuation: uniform steps of at most `max_step`, a failing step
//! split (halved, or aimed just short of a predicted dead point) until what still fails
//! has met a dead point, and the input value it met it at.

use super::continuation::Solver;
use crate::error::Error;
use crate::interrupt::Poll;
use crate::Status;

/// A failing continuation step is split until it is `2^-MAX_HALVINGS` of its length (by
/// halving, or sooner where a group nearing a dead point predicts it).
const MAX_HALVINGS: u32 = 16;
/// At most this many splits of one failing step are aimed at a predicted dead point; the
/// rest halve.
const AIMED_SPLITS: u32 = 12;
/// An aimed split stops this fraction of the predicted distance short of the dead point.
const AIM_SHORT: f64 = 0.05;

impl Solver<'_> {
    /// Continuation to `to` from where the groups and dyads are (the one farthest away sets
    /// the start; one stopped at a dead point that `to` lies beyond does not): uniform steps
    /// of at most `max_step`, each split while some group fails ([`Solver::reach`]); a group
    /// that still fails at the smallest step has met a dead point there, and angles past it
    /// are LIMIT. Ends with an evaluation at `to`. Every step is counted on `poll`
    /// (a small `max_step` makes many).
    pub(super) fn advance(&mut self, to: f64, poll: &Poll<'_>) -> Result<(), Error> {
        // a state stopped at a dead point that `to` lies beyond stays there: it sets no start
        let moves = |limit: Option<(f64, f64)>| limit.is_none_or(|(at, dir)| (to - at) * dir <= 0.0);
        let from = self
            .groups
            .iter()
            .flatten()
            .filter(|g| moves(g.limit))
            .map(|g| g.theta)
            .chain(self.dyads.iter().flatten().filter(|d| moves(d.limit)).map(|d| d.theta))
            .max_by(|a, b| (a - to).abs().total_cmp(&(b - to).abs()))
            .unwrap_or(to);
        let h = to - from;
        let m = (h.abs() / self.opts.max_step).ceil().clamp(1.0, 1e7) as u64;
        let mut a = from;
        for k in 1..=m {
            let b = if k == m { to } else { from + h * (k as f64 / m as f64) };
            // a small max_step makes many steps: each is counted (the splits of one step
            // are bounded: depth 4 MAX_HALVINGS at most)
            poll.tick()?;
            if !self.reach(a, b) {
                break;
            }
            a = b;
        }
        if self.last_eval != to {
            self.eval(to);
        }
        Ok(())
    }

    /// One continuation step from `a` (solved) to `b`; a failing step is split until it is
    /// `2^-MAX_HALVINGS` of its length, and what still fails then is at a dead point.
    pub(super) fn reach(&mut self, a: f64, b: f64) -> bool {
        self.aimed_left = AIMED_SPLITS;
        self.aimed_from = f64::NAN;
        self.reach_within(a, b, 0, (b - a).abs() * 2f64.powi(-(MAX_HALVINGS as i32)))
    }

    pub(super) fn reach_within(&mut self, a: f64, b: f64, depth: u32, floor: f64) -> bool {
        // inside a failing step's splits, from a new solution: where a group predicts its
        // dead point well short of `b`, the whole step would fail (a Newton solve run to its
        // cap for nothing): aim first
        if let Some(mid) = (depth > 0).then(|| self.aimed(a, b, floor, false)).flatten() {
            return self.reach_within(a, mid, depth + 1, floor) && self.reach_within(mid, b, depth + 1, floor);
        }
        self.step = (b - a).abs();
        let failed = self.eval(b);
        self.step = f64::INFINITY;
        if !failed {
            return true;
        }
        // (halving alone reaches `floor` at depth MAX_HALVINGS; aimed splits add levels)
        if (b - a).abs() <= floor * (1.0 + 1e-9) || depth >= 4 * MAX_HALVINGS || !b.is_finite() {
            // a group at a change point goes on across it, with its tangent
            if let Some(past) = b.is_finite().then(|| self.jump(a, b)).flatten() {
                return (past - b) * (b - a) >= 0.0 || self.reach_within(past, b, depth + 1, floor);
            }
            // what still fails this close to its last solution is at a dead point
            for (i, st) in self.groups.iter_mut().enumerate() {
                if let Some(g) = st.as_mut() {
                    let s = self.op_status[i];
                    if self.own_failure[i] && s != Status::Limit {
                        g.limit = Some((g.theta, (b - g.theta).signum()));
                    }
                }
            }
            for (i, st) in self.dyads.iter_mut().enumerate() {
                if let Some(d) = st.as_mut() {
                    if self.own_failure[i] && self.op_status[i] != Status::Limit {
                        d.limit = Some((d.theta, (b - d.theta).signum()));
                    }
                }
            }
            return false;
        }
        let mid = self.split(a, b, floor);
        self.reach_within(a, mid, depth + 1, floor) && self.reach_within(mid, b, depth + 1, floor)
    }

    /// Where to split the failing step from `a` (solved) to `b`: halfway, or just short of
    /// the dead point a failing group predicts. Near a dead point the square of a group's
    /// conditioning falls linearly in the input (the two assemblies meet as a square
    /// root), so its last two solutions extrapolate to the dead point; a split a little
    /// short of it ([`Solver::aimed`]) succeeds, and the next prediction, from nearer, is
    /// better; one success within `floor` of the prediction is followed by a probe `floor`
    /// beyond, whose failure ends the search. From a new solution inside a failing step,
    /// [`Solver::reach_within`] aims before it tries the rest of the step where the
    /// prediction falls short of its end (that try would run Newton to its cap and fail).
    /// Halving takes 2 Newton solves per halving of the interval near the dead point (32
    /// for `MAX_HALVINGS`); the prediction, superlinear, a handful (double-butterfly-1's two
    /// dead points: 5-6 solves, 26-29 Newton steps each, against 10-25 and 49-113 with
    /// aims just a quarter of `floor` short and the rest of the step tried first). A
    /// prediction is used once per new solution and `AIMED_SPLITS` times per step at most;
    /// the bracket is what makes the answer, so a poor prediction costs solves, never the
    /// result.
    pub(super) fn split(&mut self, a: f64, b: f64, floor: f64) -> f64 {
        self.aimed(a, b, floor, true).unwrap_or(0.5 * (a + b))
    }

    /// The split aimed at the nearest dead point that a group predicts from its last two
    /// solutions, when that lies short of `b` (by `floor` more where the step has not been
    /// tried: `failing` false); `None` where none does, or the prediction from `a` was used
    /// already, or the step's aims are spent. `failing`: only the groups that failed by
    /// themselves at the last evaluation. The split stops [`AIM_SHORT`] of the predicted
    /// distance short (the extrapolation's error shrinks with it, so the next aim, from
    /// nearer, is better) or a quarter of `floor`, whichever is more; within `floor` of
    /// the prediction, a probe past it.
    pub(super) fn aimed(&mut self, a: f64, b: f64, floor: f64, failing: bool) -> Option<f64> {
        if self.aimed_left == 0 || !(floor > 0.0) || a == self.aimed_from {
            return None;
        }
        let (dir, len) = ((b - a).signum(), (b - a).abs());
        let mut ahead = f64::INFINITY;
        for (i, st) in self.groups.iter().enumerate() {
            let Some(g) = st else { continue };
            let (Some(t1), Some(t0)) = (g.tangent(), g.previous()) else { continue };
            if (failing && !self.own_failure[i]) || t1.theta != a {
                continue;
            }
            let (s0, s1) = (t0.det * t0.det, t1.det * t1.det);
            let h = t1.theta - t0.theta;
            if !(s1 < s0) || h * dir <= 0.0 {
                continue;
            }
            let d = s1 * h.abs() / (s0 - s1);
            if d.is_finite() {
                ahead = ahead.min(d);
            }
        }
        let room = if failing { len } else { len - floor };
        if !(ahead < room) {
            return None;
        }
        self.aimed_left -= 1;
        self.aimed_from = a;
        let d = if ahead <= floor { 0.75 * floor } else { ahead - (AIM_SHORT * ahead).max(0.25 * floor) };
        Some(a + dir * d.clamp(0.5 * floor, len - 0.5 * floor))
    }

    /// Relabels every state `by` (whole turns): the same poses at input values `by` away.
    pub(super) fn shift(&mut self, by: f64) {
        for g in self.groups.iter_mut().flatten() {
            g.theta += by;
            for tg in g.tangents.iter_mut().flatten() {
                tg.theta += by;
            }
            for (at, _) in g.spaced.iter_mut().flatten() {
                *at += by;
            }
            if let Some(l) = g.limit.as_mut() {
                l.0 += by;
            }
        }
        for d in self.dyads.iter_mut().flatten() {
            d.theta += by;
            if let Some(l) = d.limit.as_mut() {
                l.0 += by;
            }
        }
        self.last_eval += by;
    }

    /// The dead point (input angle) that stops the first operation at LIMIT, if any: past
    /// the last solution, where its conditioning's square (linear in the input near a fold)
    /// reaches zero, from the last two solutions (a group) or the conditioning's slope (a
    /// dyad or slider), within the smallest split beyond it (the bracket): about 1e-12 rad
    /// off where the bracket is 1e-6 wide, where the bracket's end is 5e-7 off.
    pub(super) fn limit_angle(&self) -> f64 {
        let bracket = self.opts.max_step * 2f64.powi(-(MAX_HALVINGS as i32));
        for (i, (g, d)) in self.groups.iter().zip(&self.dyads).enumerate() {
            if self.op_status[i] != Status::Limit {
                continue;
            }
            let (at, dir, ahead) = if let Some((at, dir)) = g.and_then(|g| g.limit) {
                let ahead = g.as_ref().and_then(|g| Some((g.tangent()?, g.previous()?))).map(|(t1, t0)| {
                    let (s1, s0) = (t1.det * t1.det, t0.det * t0.det);
                    s1 * (t1.theta - t0.theta).abs() / (s0 - s1)
                });
                (at, dir, ahead)
            } else if let Some((at, dir)) = d.and_then(|d| d.limit) {
                // det^2 falls at 2 det ddet: zero det / (2 |ddet|) ahead
                let ahead = d.map(|d| (d.det / (2.0 * d.ddet)).abs());
                (at, dir, ahead)
            } else {
                continue;
            };
            let ahead = ahead.filter(|x| x.is_finite() && *x >= 0.0).map_or(0.0, |x| x.min(bracket));
            return at + dir * ahead;
        }
        f64::NAN
    }
}
