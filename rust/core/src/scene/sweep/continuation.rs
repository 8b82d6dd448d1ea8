//! A scene sweep: the plan solved at each input angle, following the drawn assembly.
//!
//! Continuation from the drawn pose: to the first angle along the shortest way round, then
//! along the angles in order, in steps of at most `max_step`. A dyad is a closed form on
//! the side it is on, and that side is carried along the path: each step predicts the
//! dyad's signed conditioning from the last one and its derivative, and where the other
//! side matches the prediction (the two links fell in line and went through: a change
//! point, as a parallelogram's) the step is halved until it is below `max_step / 2^14`
//! and the side then flips, so the motion goes on with its smooth tangent. A group is
//! predicted from its last three solutions and their tangents (dphi/dtheta = -J^-1
//! dF/dtheta, J at the solution): a quintic, or a cubic from two near a dead point.
//! A step where a dyad cannot close (a fold: the motion's dead point) or a group's Newton
//! solve fails, jumps, or lands on another branch (the sign of its conditioning changed)
//! is split, down to `2^-16` of its length (at most `max_step / 2^16`): halved, or just
//! short of the dead point a failing group's conditioning extrapolates to; what still
//! fails there has met a dead point, and angles past it are LIMIT. Points that do not depend on a failure are solved all the
//! same.

use super::options::SceneSweepOptions;
use super::predict::{DyadState, GroupState, Jump, Tangent, BOUNDED, JUMP, JUMP_MIN, NEAR_DEAD, ON_PATH};
use crate::scene::build::Plan;
use crate::scene::ops::Known;
use crate::scene::ops::Op;
use crate::scene::ops::{Dyad, DyadOut};
use crate::scene::ops::{GroupSolve, MAX};
use crate::scene::vec2::{cmul, cross, perp, sub, Xy};
use crate::solve::newton::NewtonOptions;
use crate::Status;

/// Newton steps per continuation step before it is halved (at most the user's max_iter).
const STEP_ITER: u32 = 5;
/// Newton steps near a dead point, where it converges linearly: enough to halve an error
/// of 1e-2 down to a tolerance of 1e-9 (at most the user's max_iter).
const NEAR_DEAD_ITER: u32 = 25;
/// A dyad changes side only over a step shorter than `max_step / 2^FLIP_HALVINGS`: there a
/// prediction that crosses zero is a change point, not a near miss.
const FLIP_HALVINGS: i32 = 14;
/// A group through a change point lands this close to its prediction (a jump to the other
/// branch near a fold lands about the square root of the step away).
const FLIP_JUMP: f64 = 1e-5;

#[derive(Clone)]
pub(super) struct Solver<'p> {
    pub(super) plan: &'p Plan,
    pub(super) opts: SceneSweepOptions,
    pub(super) step_newton: NewtonOptions,
    /// Velocities are needed for group tangents and for the `omega` outputs.
    pub(super) need_vel: bool,
    pub(super) pos: Vec<Xy>,
    pub(super) vel: Vec<Xy>,
    /// Second derivatives of positions by the input (accelerations when `omega` is given).
    pub(super) acc: Vec<Xy>,
    pub(super) need_acc: bool,
    pub(super) pst: Vec<Status>,
    pub(super) op_status: Vec<Status>,
    pub(super) op_det: Vec<f64>,
    /// The op (a group) failed by itself at the last evaluation, not through its inputs.
    pub(super) own_failure: Vec<bool>,
    /// Some op failed at the last evaluation (else every status is CONVERGED: fast paths).
    pub(super) any_failure: bool,
    /// Group state per op (None for other ops).
    pub(super) groups: Vec<Option<GroupState>>,
    /// Dyad state per op (None for other ops).
    pub(super) dyads: Vec<Option<DyadState>>,
    pub(super) nit: u32,
    pub(super) last_eval: f64,
    /// Length of the continuation step being taken (infinite outside `reach`).
    pub(super) step: f64,
    /// The anchors' positions and rates of the group being solved (buffers kept).
    pub(super) anchor_pos: Vec<Xy>,
    pub(super) anchor_vel: Vec<Xy>,
    /// Aimed splits left to the failing step being split (see [`Solver::split`]).
    pub(super) aimed_left: u32,
    /// The solution (its input value) the last aimed split was predicted from.
    pub(super) aimed_from: f64,
    /// A step across a group's change point being taken (see [`Solver::jump`]).
    pub(super) jump: Option<Jump>,
}

impl<'p> Solver<'p> {
    pub(super) fn new(plan: &'p Plan, opts: SceneSweepOptions) -> Self {
        let n = plan.npoints;
        let mut s = Solver {
            plan,
            opts,
            step_newton: NewtonOptions { max_iter: opts.newton.max_iter.min(STEP_ITER), ..opts.newton },
            // velocities give the groups' tangents and the dyads' predictions
            need_vel: true,
            pos: vec![[f64::NAN; 2]; n],
            vel: vec![[0.0; 2]; n],
            acc: vec![[0.0; 2]; n],
            need_acc: opts.omega.is_some(),
            pst: vec![Status::Converged; n],
            op_status: vec![Status::Converged; plan.ops.len()],
            op_det: vec![1.0; plan.ops.len()],
            own_failure: vec![false; plan.ops.len()],
            any_failure: false,
            groups: plan
                .ops
                .iter()
                .map(|o| match o {
                    Op::Group(g) => Some(GroupState::new(plan.theta0, g.sign)),
                    _ => None,
                })
                .collect(),
            dyads: plan
                .ops
                .iter()
                .map(|o| {
                    o.sided().then_some(DyadState {
                        side: o.drawn_side(),
                        theta: plan.theta0,
                        det: f64::NAN,
                        ddet: f64::NAN,
                        limit: None,
                    })
                })
                .collect(),
            nit: 0,
            last_eval: f64::NAN,
            step: f64::INFINITY,
            anchor_pos: Vec::new(),
            anchor_vel: Vec::new(),
            aimed_left: 0,
            aimed_from: f64::NAN,
            jump: None,
        };
        for &(p, xy) in &plan.fixed {
            s.pos[p] = xy;
        }
        s
    }

    /// Solves every op at `theta`, each group from its own prediction; commits the groups
    /// that converge on their branch. Returns true when some group failed by itself (not
    /// because something it depends on failed).
    pub(super) fn eval(&mut self, theta: f64) -> bool {
        self.last_eval = theta;
        let plan = self.plan;
        let (s, c) = crate::simd::sin_cos(theta);
        let u = [c, s];
        let pu = perp(u);
        let mut failed = false;
        // until an op fails, every input is CONVERGED: skip the lookups
        let mut seen = false;
        for (i, op) in plan.ops.iter().enumerate() {
            let bad = |pst: &[Status], ins: &[usize]| {
                if seen {
                    ins.iter().map(|&p| pst[p]).find(|s| *s != Status::Converged)
                } else {
                    None
                }
            };
            let (status, det) = match op {
                Op::Input { q, lam, mu } => {
                    let st = if theta.is_finite() { Status::Converged } else { Status::NonFinite };
                    let p = plan.pivot;
                    self.pos[*q] = [p[0] + lam * u[0] + mu * pu[0], p[1] + lam * u[1] + mu * pu[1]];
                    self.vel[*q] = [lam * pu[0] - mu * u[0], lam * pu[1] - mu * u[1]];
                    // a point turning about the pivot: q'' = -(q - pivot)
                    self.acc[*q] = [-(lam * u[0] + mu * pu[0]), -(lam * u[1] + mu * pu[1])];
                    self.pst[*q] = st;
                    (st, 1.0)
                }
                Op::Dyad(d) => {
                    let (r, own) = match bad(&self.pst, &[d.k1, d.k2]) {
                        Some(st) => ((st, f64::NAN), false),
                        None => {
                            let r = self.dyad(i, d, theta);
                            (r, matches!(r.0, Status::NotAssemblable | Status::BranchJump))
                        }
                    };
                    self.own_failure[i] = own;
                    failed |= own;
                    self.pst[d.p] = r.0;
                    r
                }
                Op::Carry { q, a, b, m } => {
                    let st = bad(&self.pst, &[*a, *b]).unwrap_or(Status::Converged);
                    let (pa, pb) = (self.pos[*a], self.pos[*b]);
                    let r = cmul(*m, sub(pb, pa));
                    self.pos[*q] = [pa[0] + r[0], pa[1] + r[1]];
                    if self.need_vel {
                        let (va, vb) = (self.vel[*a], self.vel[*b]);
                        let rv = cmul(*m, sub(vb, va));
                        self.vel[*q] = [va[0] + rv[0], va[1] + rv[1]];
                    }
                    if self.need_acc {
                        let (wa, wb) = (self.acc[*a], self.acc[*b]);
                        let rw = cmul(*m, sub(wb, wa));
                        self.acc[*q] = [wa[0] + rw[0], wa[1] + rw[1]];
                    }
                    self.pst[*q] = st;
                    (st, 1.0)
                }
                op @ (Op::StrokeCarry { .. }
                | Op::StrokeDyad(..)
                | Op::Rrp(_)
                | Op::Pp(_)
                | Op::Rpr(_)
                | Op::Offset { .. }) => {
                    let (r, own) = match bad(&self.pst, &op.inputs()) {
                        Some(st) => ((st, f64::NAN), false),
                        None => {
                            let r = self.slider(i, op, theta);
                            (r, matches!(r.0, Status::NotAssemblable | Status::BranchJump))
                        }
                    };
                    self.own_failure[i] = own;
                    failed |= own;
                    for p in op.outputs() {
                        self.pst[p] = r.0;
                    }
                    r
                }
                Op::Group(g) => {
                    let r = match bad(&self.pst, &g.anchors) {
                        Some(st) => (st, f64::NAN),
                        None => self.group(i, theta),
                    };
                    let own = r.0 != Status::Converged && r.0 != Status::Limit && bad(&self.pst, &g.anchors).is_none();
                    self.own_failure[i] = own;
                    failed |= own;
                    if r.0 != Status::Converged {
                        for nd in &g.nodes {
                            self.pst[nd.point] = r.0;
                        }
                    }
                    r
                }
            };
            seen |= status != Status::Converged;
            self.op_status[i] = status;
            self.op_det[i] = det;
        }
        self.any_failure = seen;
        failed
    }

    /// The dyad of op `i` at `theta` on the side it is on; the side flips at a change point
    /// (see the module's notes). A fold is NOT_ASSEMBLABLE here (the caller halves the step
    /// and, at the smallest, records the dead point).
    pub(super) fn dyad(&mut self, i: usize, d: &Dyad, theta: f64) -> (Status, f64) {
        let (a, b) = (self.pos[d.k1], self.pos[d.k2]);
        if d.solve(a, b) == DyadOut::Indeterminate {
            return (Status::Singular, 0.0);
        }
        let mut state = self.dyads[i].expect("a dyad has a state");
        let chosen = state.choose(theta, self.opts.max_step, self.fine(), self.opts.closed_form_singular(), |side| {
            match d.solve_side(a, b, side) {
                DyadOut::Solved(p, det) => Some((det, p)),
                _ => None,
            }
        });
        self.dyads[i] = Some(state);
        let (side, det, p) = match chosen {
            Ok(c) => c,
            Err(r) => return r,
        };
        self.pos[d.p] = p;
        let (va, vb) = (self.vel[d.k1], self.vel[d.k2]);
        let Some(v) = Dyad::velocity(p, a, b, va, vb) else { return (Status::Singular, det) };
        self.vel[d.p] = v;
        if self.need_acc {
            let (wa, wb) = (self.acc[d.k1], self.acc[d.k2]);
            match Dyad::acceleration(p, a, b, v, va, vb, wa, wb) {
                Some(w) => self.acc[d.p] = w,
                None => return (Status::Singular, det),
            }
        }
        // d det / d theta of cross(a - p, b - p) / (r1 r2) (rates are by the solving frame's
        // input: a linear input's displacement is divided by the scale there)
        let ddet = (cross(sub(va, v), sub(b, p)) + cross(sub(a, p), sub(vb, v))) / (d.r1 * d.r2) * self.rate();
        state.commit(theta, side, det, ddet);
        self.dyads[i] = Some(state);
        (Status::Converged, det)
    }

    /// d (solving-frame input) / d (sweep variable): 1 for an angle, 1 / scale for a
    /// displacement.
    pub(super) fn rate(&self) -> f64 {
        if self.plan.linear {
            1.0 / self.plan.scale
        } else {
            1.0
        }
    }

    /// A continuation step is short enough for a change point to be told from a near miss.
    pub(super) fn fine(&self) -> bool {
        self.step <= self.opts.max_step * 2f64.powi(-FLIP_HALVINGS)
    }

    /// A slider's closed form or a fused linear input's operation at input value `theta`
    /// (a displacement for a linear input): sided ones carry their side as dyads do.
    pub(super) fn slider(&mut self, i: usize, op: &Op, theta: f64) -> (Status, f64) {
        let singular = self.opts.closed_form_singular();
        // the fused guide reads the displacement in the solving frame
        let s = if self.plan.linear { theta / self.plan.scale } else { theta };
        let k: Known<'_> = [&self.pos, &self.vel, &self.acc];
        // one solve per side tried, with its rates: the chosen one is kept
        let (side, out, mut state) = if op.sided() {
            let mut state = self.dyads[i].expect("a sided operation has a state");
            let chosen = state.choose(theta, self.opts.max_step, self.fine(), singular, |side| {
                op.solve_slider(s, k, side, true).map(|x| (x.det, x))
            });
            self.dyads[i] = Some(state);
            match chosen {
                Ok((side, _, out)) => (side, out, Some(state)),
                Err(r) => return r,
            }
        } else {
            let Some(out) = op.solve_slider(s, k, 1.0, true) else {
                return (Status::NotAssemblable, f64::NAN);
            };
            (1.0, out, None)
        };
        if !(out.det.abs() >= singular) {
            return (if out.det.is_nan() { Status::NonFinite } else { Status::Singular }, out.det);
        }
        if !out.x[1][0].is_finite() || !out.x[1][1].is_finite() {
            return (Status::Singular, out.det);
        }
        for p in op.outputs() {
            self.pos[p] = out.x[0];
            self.vel[p] = out.x[1];
            self.acc[p] = out.x[2];
        }
        if let Some(st) = state.as_mut() {
            st.commit(theta, side, out.det, f64::NAN);
            self.dyads[i] = state;
        }
        (Status::Converged, out.det)
    }

    pub(super) fn group(&mut self, i: usize, theta: f64) -> (Status, f64) {
        // the anchors' positions and rates, in buffers kept from angle to angle
        let (mut anchors, mut anchor_vel) =
            (std::mem::take(&mut self.anchor_pos), std::mem::take(&mut self.anchor_vel));
        let r = self.group_with(i, theta, &mut anchors, &mut anchor_vel);
        (self.anchor_pos, self.anchor_vel) = (anchors, anchor_vel);
        r
    }

    pub(super) fn group_with(
        &mut self,
        i: usize,
        theta: f64,
        anchors: &mut Vec<Xy>,
        anchor_vel: &mut Vec<Xy>,
    ) -> (Status, f64) {
        let Op::Group(g) = &self.plan.ops[i] else { unreachable!("op {i} is a group") };
        let n = g.n();
        // (borrowed, not copied: the state holds three tangents)
        let (across, max_step) = (self.jump.filter(|j| j.op == i), self.opts.max_step);
        let state = self.groups[i].as_mut().expect("a group has a state");
        if let Some((at, dir)) = state.limit {
            if (theta - at) * dir > 0.0 {
                return (Status::Limit, f64::NAN);
            }
        }
        let guess = across.map_or_else(|| state.predict(theta, g, max_step), |j| j.guess);
        let state = &*state;
        let (det0, sign0) = (state.det(), state.sign);
        anchors.clear();
        anchors.extend(g.anchors.iter().map(|&a| self.pos[a]));
        anchor_vel.clear();
        anchor_vel.extend(g.anchors.iter().map(|&a| self.vel[a]));
        if g.held.is_some() {
            // the input's own joint in the group: its displacement (solving frame), moving
            // at a unit rate by the solving frame's input
            anchors.push([theta * self.rate(), 0.0]);
            anchor_vel.push([1.0, 0.0]);
        }
        let (anchors, anchor_vel) = (&anchors[..], &anchor_vel[..]);
        let near_dead = !(det0.abs() >= NEAR_DEAD);
        let near_newton = NewtonOptions { max_iter: self.opts.newton.max_iter.min(NEAR_DEAD_ITER), ..self.opts.newton };
        // Newton converges only linearly near a dead point (the error halves per step): give
        // it enough steps for that there; and a step past the dead point has no root, so it
        // gives up where its residual stalls
        let longer = near_dead && near_newton.max_iter > self.step_newton.max_iter;
        let solve = |guess: &[f64], opts: &NewtonOptions| g.solve(anchors, Some(anchor_vel), guess, opts, longer);
        let jump =
            |out: &GroupSolve, guess: &[f64]| (0..n).map(|k| g.gap(k, out.phi[k], guess[k]).abs()).fold(0.0, f64::max);
        let newton = if longer { &near_newton } else { &self.step_newton };
        if let Some(j) = across {
            // across a change point: kept only on the carried path (see `jump`)
            let out = solve(&guess[..n], &self.opts.newton);
            self.nit += out.nit;
            let h = (theta - j.from).abs();
            let size = (0..n).map(|k| j.tangent[k].abs()).fold(1.0, f64::max);
            let on_path = out.status == Status::Converged
                && out.det * sign0 < 0.0
                && (0..n).all(|k| g.gap(k, out.phi[k], guess[k]).abs() <= ON_PATH * h * size)
                && (0..n).all(|k| (out.dphi[k] * self.rate() - j.tangent[k]).abs() <= ON_PATH * size);
            if !on_path {
                return (Status::BranchJump, out.det);
            }
            return self.commit_group(i, theta, &out, -sign0, anchors, anchor_vel);
        }
        // an angle predicted to within the tolerance (most of them, away from dead points)
        // converges at Newton's first evaluation: that evaluation's elimination gives the
        // tangent too, where the rates are not outputs (they then take the solution's)
        let first = (!near_dead && self.opts.omega.is_none())
            .then(|| g.solve_predicted(anchors, anchor_vel, &guess[..n], newton))
            .flatten();
        let mut out: GroupSolve = first.unwrap_or_else(|| solve(&guess[..n], newton));
        self.nit += out.nit;
        let mut sign = sign0;
        if near_dead && out.status == Status::Converged && out.det * sign < 0.0 {
            // near a dead point both branches are close: the prediction reflected through
            // the solution found starts Newton on the other one
            let mirror: Vec<f64> = (0..n).map(|k| guess[k] - g.gap(k, out.phi[k], guess[k])).collect();
            let again = solve(&mirror, &near_newton);
            self.nit += again.nit;
            if again.status == Status::Converged && again.det * sign > 0.0 && jump(&again, &guess[..n]) <= JUMP {
                out = again;
            } else if self.step <= self.opts.max_step * 2f64.powi(-FLIP_HALVINGS)
                && jump(&out, &guess[..n]) <= FLIP_JUMP
                && self.groups[i].as_ref().and_then(|st| st.tangent()).is_some_and(|t| {
                    // the branch that crosses there has another tangent
                    let size = (0..n).map(|k| t.dphi[k].abs()).fold(1.0, f64::max);
                    (0..n).all(|k| (out.dphi[k] * self.rate() - t.dphi[k]).abs() <= ON_PATH * size)
                })
            {
                // on the predicted path over a tiny step, through a change point
                sign = -sign;
            }
        }
        let mut status = out.status;
        if status == Status::Converged && (out.det * sign < 0.0 || jump(&out, &guess[..n]) > JUMP) {
            status = Status::BranchJump;
        }
        if status == Status::Converged && near_dead && !self.carried(i, theta, &out) {
            // near a change point the branch that crosses ours is close, with the same sign
            status = Status::BranchJump;
        }
        if status != Status::Converged {
            return (status, out.det);
        }
        self.commit_group(i, theta, &out, sign, anchors, anchor_vel)
    }

    /// A solution approaching a dead or change point (the conditioning falling) keeps the
    /// tangent carried along the path, where that tangent is bounded (a change point: at a
    /// fold it grows as one over the conditioning and says nothing): within [`ON_PATH`] of
    /// its size of the tangent extrapolated from the last two solutions.
    fn carried(&self, i: usize, theta: f64, out: &GroupSolve) -> bool {
        let Some(st) = self.groups[i].as_ref() else { return true };
        let (Some(t1), Some(t0)) = (st.tangent(), st.previous()) else { return true };
        let Op::Group(g) = &self.plan.ops[i] else { return true };
        let n = g.n();
        let s = t1.theta - t0.theta;
        let norm = |v: &[f64; MAX]| v[..n].iter().map(|x| x * x).sum::<f64>().sqrt();
        if s == 0.0 || !(t1.det.abs() < t0.det.abs()) || !(norm(&t1.dphi) <= BOUNDED * norm(&t0.dphi)) {
            return true;
        }
        let size = (0..n).map(|k| t1.dphi[k].abs()).fold(1.0, f64::max);
        (0..n).all(|k| {
            let want = t1.dphi[k] + (t1.dphi[k] - t0.dphi[k]) / s * (theta - t1.theta);
            (out.dphi[k] * self.rate() - want).abs() <= ON_PATH * size
        })
    }

    /// Places a group's converged solution `out` at `theta` (positions, rates) and records
    /// it on the branch of sign `sign`.
    fn commit_group(
        &mut self,
        i: usize,
        theta: f64,
        out: &GroupSolve,
        sign: f64,
        anchors: &[Xy],
        anchor_vel: &[Xy],
    ) -> (Status, f64) {
        let Op::Group(g) = &self.plan.ops[i] else { unreachable!("op {i} is a group") };
        let n = g.n();
        // the nodes' velocities where something reads them: the rates asked for, or a later
        // operation (a carry, dyad or group on these points); else only the tangents are kept
        let rates = self.need_acc || i + 1 < self.plan.ops.len();
        let (pos, vel) = (&mut self.pos, &mut self.vel);
        g.place_moving(&out.phi[..n], &out.dphi[..n], &out.cs[..g.nrot], anchors, anchor_vel, rates, |p, xy, v| {
            pos[p] = xy;
            if rates {
                vel[p] = v;
            }
        });
        if self.need_acc {
            let anchor_acc = g.with_held(|a| self.acc[a], 0.0);
            let k = [anchors, anchor_vel, &anchor_acc[..]];
            let ddphi = g.second(&out.phi[..n], &out.dphi[..n], k).unwrap_or([f64::NAN; MAX]);
            let acc = &mut self.acc;
            g.place_acceleration(&out.phi[..n], &out.dphi[..n], &ddphi[..n], k, |p, w| acc[p] = w);
        }
        for nd in &g.nodes {
            self.pst[nd.point] = Status::Converged;
        }
        let mut dphi = out.dphi;
        for w in &mut dphi {
            *w *= self.rate();
        }
        let t = Tangent { theta, phi: out.phi, dphi, det: out.det };
        let st = self.groups[i].as_mut().expect("a group has a state");
        st.push(t, self.opts.max_step / JUMP_MIN);
        st.theta = theta;
        st.sign = sign;
        st.limit = None;
        (Status::Converged, out.det)
    }
}
