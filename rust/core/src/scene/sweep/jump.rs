//! Through a change point inside a group: where a group's conditioning falls linearly to
//! zero while its tangent stays bounded, two branches cross there (an exact parallelogram
//! or kite among its loops), not a fold; the drawn branch goes on with its tangent (DESIGN,
//! "Scenes"). The step is taken over the crossing from a prediction on that tangent, and
//! the solution kept only where its conditioning changed sign, it lies on the prediction,
//! and its tangent is the one carried: the branch that crosses would differ in both.

use super::continuation::Solver;
use super::predict::{Jump, BOUNDED, JUMP_MIN, JUMP_REACH};
use crate::scene::ops::{Op, MAX};

impl Solver<'_> {
    /// At a failing step from `a` (solved) towards `b`: when the group that failed there
    /// is at a change point (see the module's notes), the input value past it where the
    /// motion was found again with the carried tangent; `None` otherwise (a dead point).
    pub(super) fn jump(&mut self, a: f64, b: f64) -> Option<f64> {
        let i = (0..self.plan.ops.len()).find(|&i| self.own_failure[i] && self.groups[i].is_some())?;
        let Op::Group(g) = &self.plan.ops[i] else { return None };
        let st = self.groups[i].as_ref()?;
        let (t1, t0) = (*st.tangent()?, *st.previous()?);
        let dir = (b - a).signum();
        let s = t1.theta - t0.theta;
        if t1.theta != a || s * dir <= 0.0 || !(t1.det.abs() < t0.det.abs()) {
            return None;
        }
        let n = g.n();
        let norm = |v: &[f64; MAX]| v[..n].iter().map(|x| x * x).sum::<f64>().sqrt();
        if !(norm(&t1.dphi) <= BOUNDED * norm(&t0.dphi)) {
            return None; // the tangent grows: a fold
        }
        // the crossing, where the conditioning's line through the last two reaches zero
        let at = t1.theta - t1.det * s / (t1.det - t0.det);
        let max_step = self.opts.max_step;
        let h = (JUMP_REACH * (at - a).abs()).clamp(max_step / JUMP_MIN, max_step);
        let to = at + dir * h;
        let d = to - a;
        // the tangent's change from two solutions far enough apart to tell it (the last
        // two, where there are no others)
        let (f0, f1) = match st.spaced {
            [Some(f0), Some(f1)] => (f0, f1),
            _ => ((t0.theta, t0.dphi), (t1.theta, t1.dphi)),
        };
        let mut guess = [0.0; MAX];
        let mut tangent = [0.0; MAX];
        for k in 0..n {
            // Taylor to second order
            let curv = (f1.1[k] - f0.1[k]) / (f1.0 - f0.0);
            guess[k] = t1.phi[k] + t1.dphi[k] * d + 0.5 * curv * d * d;
            tangent[k] = t1.dphi[k] + curv * d;
        }
        self.jump = Some(Jump { op: i, from: a, guess, tangent });
        let failed = self.eval(to);
        self.jump = None;
        (!failed && !self.any_failure).then_some(to)
    }
}
