//! The predictors of the continuation: a dyad's side and signed conditioning carried
//! along the path, and a group's next solution from its last three and their tangents
//! (a quintic Hermite interpolant, or a cubic near a dead point).

use crate::scene::ops::{Group, MAX};
use crate::Status;

/// A converged group whose rotations moved more than this from the prediction (with a
/// prediction made over at most one `max_step`) has jumped to another solution.
pub(super) const JUMP: f64 = 0.25;
/// A group whose last conditioning is below this is near a dead point: a step that fails
/// there gets up to NEAR_DEAD_ITER Newton steps and a mirrored start.
pub(super) const NEAR_DEAD: f64 = 1e-2;

/// A jump lands a few times the distance to the estimated crossing past it (and at least
/// `max_step / JUMP_MIN` past, at most `max_step`): far enough from the crossing for Newton
/// to tell the two branches apart.
pub(super) const JUMP_REACH: f64 = 4.0;
pub(super) const JUMP_MIN: f64 = 64.0;
/// A bounded tangent: the last one at most this times the one before, while the
/// conditioning fell (at a fold it grows as one over the conditioning).
pub(super) const BOUNDED: f64 = 1.5;
/// The solution after the jump lies within this fraction of the jump's length (times the
/// tangent's size) of its prediction, with a tangent within this fraction of the carried
/// one: the crossing branch's differ by order one.
pub(super) const ON_PATH: f64 = 0.1;

/// Abscissae (in units of the step) this close give the quintic the same weights: within
/// rounding of the prediction, far below the Newton tolerance it only has to meet.
const RATIOS: f64 = 1e-12;

/// A step across a change point (see `jump`): the group (op `op`), its start and carried tangent there.
#[derive(Clone, Copy, Debug)]
pub(super) struct Jump {
    pub(super) op: usize,
    pub(super) from: f64,
    pub(super) guess: [f64; MAX],
    pub(super) tangent: [f64; MAX],
}

/// Continuation state of one dyad: the side it is on and its last signed conditioning.
#[derive(Clone, Copy, Debug)]
pub(super) struct DyadState {
    pub(super) side: f64,
    pub(super) theta: f64,
    pub(super) det: f64,
    /// d det / d theta at `theta` (NaN when unknown: no prediction).
    pub(super) ddet: f64,
    /// A fold met while continuing in direction `dir`: angles past it are LIMIT.
    pub(super) limit: Option<(f64, f64)>,
}

/// What [`DyadState::choose`] decided: the side, its conditioning and its solve, or a
/// status.
pub(super) type Choice<T> = Result<(f64, f64, T), (Status, f64)>;

impl DyadState {
    /// The side at `theta` of an operation whose conditioning on a side is `det_on(side)`
    /// (None: it cannot close): the side carried, flipped where the other side fits the
    /// prediction (over a step no longer than `fine`: a change point); LIMIT past a dead
    /// point met before; SINGULAR at a dead point (reached: the state moves there).
    /// `solve(side)` gives the conditioning and the solve on a side; the chosen one is
    /// returned, not solved again.
    pub(super) fn choose<T>(
        &mut self,
        theta: f64,
        max_step: f64,
        fine: bool,
        singular: f64,
        solve: impl Fn(f64) -> Option<(f64, T)>,
    ) -> Choice<T> {
        if let Some((at, dir)) = self.limit {
            if (theta - at) * dir > 0.0 {
                return Err((Status::Limit, f64::NAN));
            }
        }
        let mut side = self.side;
        let Some((mut det, mut out)) = solve(side) else { return Err((Status::NotAssemblable, f64::NAN)) };
        let pred = self.predict(theta, max_step);
        // the other side fits the prediction better: the links went through a line
        if (pred - det).abs() > (pred + det).abs() {
            if !fine {
                return Err((Status::BranchJump, det));
            }
            side = -side;
            let Some(other) = solve(side) else { return Err((Status::NotAssemblable, f64::NAN)) };
            (det, out) = other;
        }
        if !(det.abs() >= singular) {
            if det.is_nan() {
                return Err((Status::NonFinite, det));
            }
            // at a dead point: the path reached it (the slope carries over)
            *self = DyadState { side, theta, det, ..*self };
            return Err((Status::Singular, det));
        }
        Ok((side, det, out))
    }

    /// Commits a solve on `side`; `ddet` NaN: the slope from the last commit (secant).
    pub(super) fn commit(&mut self, theta: f64, side: f64, det: f64, ddet: f64) {
        let ddet = if ddet.is_finite() || self.theta == theta { ddet } else { (det - self.det) / (theta - self.theta) };
        *self = DyadState { side, theta, det, ddet, limit: None };
    }

    /// The predicted signed conditioning at `theta` (NaN: no prediction).
    pub(super) fn predict(&self, theta: f64, max_step: f64) -> f64 {
        let h = theta - self.theta;
        if h.abs() > 4.0 * max_step {
            return f64::NAN;
        }
        self.det + self.ddet * h
    }
}

#[derive(Clone, Copy, Debug)]
pub(super) struct Tangent {
    pub(super) theta: f64,
    pub(super) phi: [f64; MAX],
    pub(super) dphi: [f64; MAX],
    /// The conditioning there (its square falls linearly to a dead point: see
    /// [`Solver::split`]).
    pub(super) det: f64,
}

/// Continuation state of one group.
#[derive(Clone, Copy, Debug)]
pub(super) struct GroupState {
    /// The input value of the last solution (the drawn one before the first).
    pub(super) theta: f64,
    /// The last three solutions with their tangents, the newest at `head`: a ring, where
    /// a new solution takes the oldest one's place and nothing is moved.
    pub(super) tangents: [Option<Tangent>; 3],
    pub(super) head: usize,
    /// A dead point met while continuing in direction `dir` (+1 / -1): angles past it in
    /// that direction are LIMIT without a solve.
    pub(super) limit: Option<(f64, f64)>,
    /// Sign of the conditioning on the branch followed (as drawn; it changes at a change
    /// point).
    pub(super) sign: f64,
    /// The last two solutions' (input value, tangent) at least a given spacing apart (see
    /// [`GroupState::push`]; the older first): the curvature a step across a change point
    /// extrapolates with (see `jump`). Its last solutions are splits a hair apart there,
    /// where a tangent is off by about the solution's error over the conditioning, and two
    /// such tangents give no curvature.
    pub(super) spaced: [Option<(f64, [f64; MAX])>; 2],
    /// The quintic's weights for the last abscissae it was used with (as ratios to the
    /// step): a sweep at even steps computes them once.
    pub(super) weights: Option<([f64; 2], [f64; 5])>,
}

impl GroupState {
    /// The state at the drawn pose (`theta`), on the branch of conditioning sign `sign`.
    pub(super) fn new(theta: f64, sign: f64) -> Self {
        GroupState { theta, tangents: [None; 3], head: 0, limit: None, sign, spaced: [None; 2], weights: None }
    }

    /// The last solution's tangent.
    pub(super) fn tangent(&self) -> Option<&Tangent> {
        self.tangents[self.head].as_ref()
    }

    /// The last solution (the drawn pose, all zero, before the first).
    pub(super) fn phi(&self) -> [f64; MAX] {
        self.tangent().map_or([0.0; MAX], |t| t.phi)
    }

    /// The conditioning at the last solution (NaN before the first).
    pub(super) fn det(&self) -> f64 {
        self.tangent().map_or(f64::NAN, |t| t.det)
    }

    /// The one before it.
    pub(super) fn previous(&self) -> Option<&Tangent> {
        self.tangents[(self.head + 2) % 3].as_ref()
    }

    /// The one before that.
    pub(super) fn older(&self) -> Option<&Tangent> {
        self.tangents[(self.head + 1) % 3].as_ref()
    }

    /// Records a new solution: the last one becomes the previous one if it was taken at
    /// another input value (else the history restarts), and so on down the line; it joins
    /// the spaced ones where it lies at least `spacing` from the last of them.
    pub(super) fn push(&mut self, t: Tangent, spacing: f64) {
        match self.spaced[1] {
            Some((at, _)) if at == t.theta => self.spaced[1] = Some((t.theta, t.dphi)),
            Some((at, _)) if (t.theta - at).abs() < spacing => {}
            _ => self.spaced = [self.spaced[1], Some((t.theta, t.dphi))],
        }
        match self.tangent() {
            Some(t1) if t1.theta != t.theta => {
                let keep_previous = self.previous().is_some_and(|t0| t0.theta != t.theta);
                self.head = (self.head + 1) % 3;
                self.tangents[self.head] = Some(t);
                if !keep_previous {
                    self.tangents[(self.head + 1) % 3] = None;
                }
            }
            _ => {
                self.tangents = [None; 3];
                self.tangents[self.head] = Some(t);
            }
        }
    }

    /// From the last solution: fifth order from the last three tangents where the group is
    /// well away from a dead point and the three were taken at steps at least half as long
    /// as this one; else third order from the last two (the cubic Hermite), first order with one;
    /// the last solution itself after a gap or where the tangent is steep (a prediction
    /// over several steps, or across a dead point's square-root turn, is worse than none).
    ///
    /// The quintic's error over a step h is about h^6 |phi^(6)| / 20 (1.4e-12 |phi^(6)| at
    /// one degree), the cubic's h^4 |phi^(4)| / 6 (1.5e-8 |phi^(4)|): the quintic's start is
    /// often already within the Newton tolerance (99% of Stephenson III's angles, 58% of a
    /// double butterfly's at one-degree steps), and then one evaluation converges (its
    /// correction applied) where the cubic's took a step and a second evaluation.
    pub(super) fn predict(&mut self, theta: f64, g: &Group, max_step: f64) -> [f64; MAX] {
        let n = g.n();
        let h = theta - self.theta;
        let mut x = self.phi();
        if h.abs() > 4.0 * max_step {
            return x;
        }
        let Some(t1) = self.tangent() else { return x };
        let t0 = self.previous().filter(|t0| t0.theta != t1.theta);
        // the quintic: three solutions, each step at least half as long as this one
        let tm = match (t0, self.older()) {
            (Some(t0), Some(tm)) if self.det().abs() >= NEAR_DEAD => {
                let (s0, s1) = (t1.theta - t0.theta, t0.theta - tm.theta);
                (s0 * h > 0.0 && s1 * h > 0.0 && s0.abs() >= 0.5 * h.abs() && s1.abs() >= 0.5 * h.abs()).then_some(tm)
            }
            _ => None,
        };
        let quintic = t0.zip(tm).map(|(t0, tm)| {
            let ratios = [(t0.theta - t1.theta) / h, (tm.theta - t1.theta) / h];
            let w = match self.weights {
                Some((r, w)) if (r[0] - ratios[0]).abs() <= RATIOS && (r[1] - ratios[1]).abs() <= RATIOS => w,
                _ => Hermite5::weights(ratios),
            };
            (t0, tm, ratios, w)
        });
        for (k, xk) in x.iter_mut().enumerate().take(n) {
            let dx = match (t0, &quintic) {
                (_, Some((t0, tm, _, w))) => {
                    let (v0, vm) = (-g.gap(k, t1.phi[k], t0.phi[k]), -g.gap(k, t1.phi[k], tm.phi[k]));
                    (w[0] * t1.dphi[k] + w[2] * t0.dphi[k] + w[4] * tm.dphi[k]) * h + w[1] * v0 + w[3] * vm
                }
                // the cubic through both solutions with both tangents (Hermite), one step on
                (Some(t0), None) => {
                    let s = t1.theta - t0.theta;
                    let dp = g.gap(k, t1.phi[k], t0.phi[k]);
                    let (a, b) = (t0.dphi[k], t1.dphi[k]);
                    let c2 = (3.0 * dp / s - 2.0 * a - b) / s;
                    let c3 = (a + b - 2.0 * dp / s) / (s * s);
                    let x1 = s + h;
                    (a * x1 + c2 * x1 * x1 + c3 * x1 * x1 * x1) - dp
                }
                (None, None) => t1.dphi[k] * h,
            };
            // a steep tangent (near a dead point) predicts worse than none: start from the
            // last solution (the branch is then picked by the conditioning's sign)
            if !(dx.abs() <= 0.5 * JUMP) {
                return self.phi();
            }
            *xk += dx;
        }
        self.weights = quintic.map(|(_, _, r, w)| (r, w)).or(self.weights);
        x
    }
}

/// The quintic Hermite interpolant (Newton's divided differences on the doubled nodes) of
/// a function that is 0 with slope `d1` at abscissa 0 and has (value, slope) at two other
/// abscissae: prepared once for the abscissae (the reciprocals of the differences' spans),
/// then evaluated for each coordinate with no division.
pub(super) struct Hermite5 {
    pub(super) z: [f64; 6],
    /// `inv[j][i]` = 1 / (z[i] - z[i - j]) (unused where the span is 0: a slope there).
    pub(super) inv: [[f64; 6]; 6],
}

impl Hermite5 {
    /// The interpolant is linear in its data: its value one step `h` on is
    /// `(w0 d1 + w2 s0 + w4 sm) h + w1 v0 + w3 vm` for slope `d1` at 0 and (value, slope)
    /// `(v0, s0)`, `(vm, sm)` at the two other abscissae, `ratios` times `h` (in units of
    /// the step, where a slope is one times `h`).
    pub(super) fn weights(ratios: [f64; 2]) -> [f64; 5] {
        let q = Hermite5::new(ratios[0], ratios[1]);
        [
            q.eval(1.0, (0.0, 0.0), (0.0, 0.0), 1.0),
            q.eval(0.0, (1.0, 0.0), (0.0, 0.0), 1.0),
            q.eval(0.0, (0.0, 1.0), (0.0, 0.0), 1.0),
            q.eval(0.0, (0.0, 0.0), (1.0, 0.0), 1.0),
            q.eval(0.0, (0.0, 0.0), (0.0, 1.0), 1.0),
        ]
    }

    pub(super) fn new(a0: f64, am: f64) -> Self {
        let z = [0.0, 0.0, a0, a0, am, am];
        let mut inv = [[0.0; 6]; 6];
        for (j, row) in inv.iter_mut().enumerate().skip(1) {
            for i in j..6 {
                row[i] = 1.0 / (z[i] - z[i - j]);
            }
        }
        Hermite5 { z, inv }
    }

    /// The interpolant at `h`, for slope `d1` at 0 and (value, slope) `p0`, `pm` at the
    /// other two abscissae.
    pub(super) fn eval(&self, d1: f64, p0: (f64, f64), pm: (f64, f64), h: f64) -> f64 {
        let (z, inv) = (&self.z, &self.inv);
        // first differences: a slope at a doubled node, a secant between two nodes
        let mut q = [0.0, d1, p0.0 * inv[1][2], p0.1, (pm.0 - p0.0) * inv[1][4], pm.1];
        for (j, span) in inv.iter().enumerate().skip(2) {
            for i in (j..6).rev() {
                q[i] = (q[i] - q[i - 1]) * span[i];
            }
        }
        let mut p = q[5];
        for j in (0..5).rev() {
            p = p * (h - z[j]) + q[j];
        }
        p
    }
}

#[cfg(test)]
mod tests {
    use super::Hermite5;

    /// The quintic Hermite interpolant is exact on a polynomial of degree 5, at uneven
    /// abscissae, and its extrapolation of sin one step on has the error its remainder
    /// term gives (h^6 |f^(6)| / 20 for equal steps).
    #[test]
    pub(super) fn hermite5_is_exact_on_quintics_and_sixth_order_on_sin() {
        let f = |t: f64| 0.3 - 1.1 * t + 0.7 * t * t - 2.0 * t.powi(3) + 0.4 * t.powi(4) - 1.3 * t.powi(5);
        let df = |t: f64| -1.1 + 1.4 * t - 6.0 * t * t + 1.6 * t.powi(3) - 6.5 * t.powi(4);
        let (t1, t0, tm, t) = (0.2, -0.1, -0.35, 0.5);
        let older = |s: f64| (f(s) - f(t1), df(s));
        let p = Hermite5::new(t0 - t1, tm - t1).eval(df(t1), older(t0), older(tm), t - t1);
        assert!((p - (f(t) - f(t1))).abs() < 1e-13, "{p}");
        let h = 1f64.to_radians();
        for x1 in [0.3_f64, 1.0, 2.5] {
            let older = |s: f64| (s.sin() - x1.sin(), s.cos());
            let p = Hermite5::new(-h, -2.0 * h).eval(x1.cos(), older(x1 - h), older(x1 - 2.0 * h), h);
            let err = (p - ((x1 + h).sin() - x1.sin())).abs();
            // remainder: 36 h^6 / 720 |sin(xi)| <= h^6 / 20
            assert!(err <= h.powi(6) / 20.0 + 1e-16, "{err}");
            assert!(err > 0.0);
        }
    }

    /// Its weights give the interpolant's value at any step, the step's length scaled out.
    #[test]
    fn hermite5_weights_give_its_value_at_any_scale() {
        let (d1, p0, pm) = (0.7, (-0.2, 1.3), (-0.5, -0.4));
        for (a0, am, h) in [(-0.3, -0.55, 0.25), (-1.0, -2.0, 1e-3), (0.4, 0.9, -0.2)] {
            let want = Hermite5::new(a0, am).eval(d1, p0, pm, h);
            let w = Hermite5::weights([a0 / h, am / h]);
            let got = (w[0] * d1 + w[2] * p0.1 + w[4] * pm.1) * h + w[1] * p0.0 + w[3] * pm.0;
            assert!((got - want).abs() <= 1e-12 * want.abs().max(1.0), "{got} {want}");
        }
    }
}
