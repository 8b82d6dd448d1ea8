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

use super::columns;
use super::options::{ScenePredictor, SceneSweepOptions, SceneSweepOut};
use crate::error::{quoted, try_zeros, Error};
use crate::interrupt::{Interrupt, Poll};
use crate::scene::build::Plan;
use crate::scene::ops::Known;
use crate::scene::ops::Op;
use crate::scene::ops::{Dyad, DyadOut};
use crate::scene::ops::{Group, GroupSolve, MAX};
use crate::scene::vec2::{angular_acceleration, cross, dot, perp, sub, Xy};
use crate::solve::homotopy::HomotopyOptions;
use crate::solve::newton::NewtonOptions;
use crate::{wrap_angle, Status};

/// A column sweep whose every step keeps at least this conditioning (and whose angles are
/// at most `max_step` apart) has met no dead point or change point on its way.
const CERTIFIED: f64 = 0.05;
/// Largest group whose assemblies are counted (by the homotopy) to tell LIMIT from
/// NOT_ASSEMBLABLE at the angles a sweep does not reach.
const CLASSIFIED_GROUP: usize = 4;
/// A failing continuation step is split until it is `2^-MAX_HALVINGS` of its length (by
/// halving, or sooner where a group nearing a dead point predicts it).
const MAX_HALVINGS: u32 = 16;
/// At most this many splits of one failing step are aimed at a predicted dead point; the
/// rest halve.
const AIMED_SPLITS: u32 = 12;
/// An aimed split stops this fraction of the predicted distance short of the dead point.
const AIM_SHORT: f64 = 0.05;
/// Newton steps per continuation step before it is halved (at most the user's max_iter).
const STEP_ITER: u32 = 5;
/// A converged group whose rotations moved more than this from the prediction (with a
/// prediction made over at most one `max_step`) has jumped to another solution.
const JUMP: f64 = 0.25;
/// A group whose last conditioning is below this is near a dead point: a step that fails
/// there gets up to NEAR_DEAD_ITER Newton steps and a mirrored start.
const NEAR_DEAD: f64 = 1e-2;
/// Newton steps near a dead point, where it converges linearly: enough to halve an error
/// of 1e-2 down to a tolerance of 1e-9 (at most the user's max_iter).
const NEAR_DEAD_ITER: u32 = 25;
/// A dyad changes side only over a step shorter than `max_step / 2^FLIP_HALVINGS`: there a
/// prediction that crosses zero is a change point, not a near miss.
const FLIP_HALVINGS: i32 = 14;
/// A group through a change point lands this close to its prediction (a jump to the other
/// branch near a fold lands about the square root of the step away).
const FLIP_JUMP: f64 = 1e-5;

/// Continuation state of one dyad: the side it is on and its last signed conditioning.
#[derive(Clone, Copy, Debug)]
struct DyadState {
    side: f64,
    theta: f64,
    det: f64,
    /// d det / d theta at `theta` (NaN when unknown: no prediction).
    ddet: f64,
    /// A fold met while continuing in direction `dir`: angles past it are LIMIT.
    limit: Option<(f64, f64)>,
}

/// What [`DyadState::choose`] decided: the side, its conditioning and its solve, or a
/// status.
type Choice<T> = Result<(f64, f64, T), (Status, f64)>;

impl DyadState {
    /// The side at `theta` of an operation whose conditioning on a side is `det_on(side)`
    /// (None: it cannot close): the side carried, flipped where the other side fits the
    /// prediction (over a step no longer than `fine`: a change point); LIMIT past a dead
    /// point met before; SINGULAR at a dead point (reached: the state moves there).
    /// `solve(side)` gives the conditioning and the solve on a side; the chosen one is
    /// returned, not solved again.
    fn choose<T>(
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
    fn commit(&mut self, theta: f64, side: f64, det: f64, ddet: f64) {
        let ddet = if ddet.is_finite() || self.theta == theta { ddet } else { (det - self.det) / (theta - self.theta) };
        *self = DyadState { side, theta, det, ddet, limit: None };
    }

    /// The predicted signed conditioning at `theta` (NaN: no prediction).
    fn predict(&self, theta: f64, max_step: f64) -> f64 {
        let h = theta - self.theta;
        if h.abs() > 4.0 * max_step {
            return f64::NAN;
        }
        self.det + self.ddet * h
    }
}

#[derive(Clone, Copy, Debug)]
struct Tangent {
    theta: f64,
    phi: [f64; MAX],
    dphi: [f64; MAX],
    /// The conditioning there (its square falls linearly to a dead point: see
    /// [`Solver::split`]).
    det: f64,
}

/// Continuation state of one group.
#[derive(Clone, Copy, Debug)]
struct GroupState {
    /// The input value of the last solution (the drawn one before the first).
    theta: f64,
    /// The last three solutions with their tangents, the newest at `head`: a ring, where
    /// a new solution takes the oldest one's place and nothing is moved.
    tangents: [Option<Tangent>; 3],
    head: usize,
    /// A dead point met while continuing in direction `dir` (+1 / -1): angles past it in
    /// that direction are LIMIT without a solve.
    limit: Option<(f64, f64)>,
    /// Sign of the conditioning on the branch followed (as drawn; it changes at a change
    /// point).
    sign: f64,
}

impl GroupState {
    /// The last solution's tangent.
    fn tangent(&self) -> Option<&Tangent> {
        self.tangents[self.head].as_ref()
    }

    /// The last solution (the drawn pose, all zero, before the first).
    fn phi(&self) -> [f64; MAX] {
        self.tangent().map_or([0.0; MAX], |t| t.phi)
    }

    /// The conditioning at the last solution (NaN before the first).
    fn det(&self) -> f64 {
        self.tangent().map_or(f64::NAN, |t| t.det)
    }

    /// The one before it.
    fn previous(&self) -> Option<&Tangent> {
        self.tangents[(self.head + 2) % 3].as_ref()
    }

    /// The one before that.
    fn older(&self) -> Option<&Tangent> {
        self.tangents[(self.head + 1) % 3].as_ref()
    }

    /// Records a new solution: the last one becomes the previous one if it was taken at
    /// another input value (else the history restarts), and so on down the line.
    fn push(&mut self, t: Tangent) {
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
    fn predict(&self, theta: f64, g: &Group, max_step: f64) -> [f64; MAX] {
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
        let quintic = t0.zip(tm).map(|(t0, tm)| (t0, tm, Hermite5::new(t0.theta - t1.theta, tm.theta - t1.theta)));
        for (k, xk) in x.iter_mut().enumerate().take(n) {
            let dx = match (t0, &quintic) {
                (_, Some((t0, tm, q))) => {
                    let older = |t: &Tangent| (-g.gap(k, t1.phi[k], t.phi[k]), t.dphi[k]);
                    q.eval(t1.dphi[k], older(t0), older(tm), h)
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
        x
    }
}

/// The quintic Hermite interpolant (Newton's divided differences on the doubled nodes) of
/// a function that is 0 with slope `d1` at abscissa 0 and has (value, slope) at two other
/// abscissae: prepared once for the abscissae (the reciprocals of the differences' spans),
/// then evaluated for each coordinate with no division.
struct Hermite5 {
    z: [f64; 6],
    /// `inv[j][i]` = 1 / (z[i] - z[i - j]) (unused where the span is 0: a slope there).
    inv: [[f64; 6]; 6],
}

impl Hermite5 {
    fn new(a0: f64, am: f64) -> Self {
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
    fn eval(&self, d1: f64, p0: (f64, f64), pm: (f64, f64), h: f64) -> f64 {
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

struct Solver<'p> {
    plan: &'p Plan,
    opts: SceneSweepOptions,
    step_newton: NewtonOptions,
    /// Velocities are needed for group tangents and for the `omega` outputs.
    need_vel: bool,
    pos: Vec<Xy>,
    vel: Vec<Xy>,
    /// Second derivatives of positions by the input (accelerations when `omega` is given).
    acc: Vec<Xy>,
    need_acc: bool,
    pst: Vec<Status>,
    op_status: Vec<Status>,
    op_det: Vec<f64>,
    /// The op (a group) failed by itself at the last evaluation, not through its inputs.
    own_failure: Vec<bool>,
    /// Some op failed at the last evaluation (else every status is CONVERGED: fast paths).
    any_failure: bool,
    /// Group state per op (None for other ops).
    groups: Vec<Option<GroupState>>,
    /// Dyad state per op (None for other ops).
    dyads: Vec<Option<DyadState>>,
    nit: u32,
    last_eval: f64,
    /// Length of the continuation step being taken (infinite outside `reach`).
    step: f64,
    /// The anchors' positions and rates of the group being solved (buffers kept).
    anchor_pos: Vec<Xy>,
    anchor_vel: Vec<Xy>,
    /// Aimed splits left to the failing step being split (see [`Solver::split`]).
    aimed_left: u32,
    /// The solution (its input value) the last aimed split was predicted from.
    aimed_from: f64,
}

impl<'p> Solver<'p> {
    fn new(plan: &'p Plan, opts: SceneSweepOptions) -> Self {
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
                    Op::Group(g) => {
                        Some(GroupState { theta: plan.theta0, tangents: [None; 3], head: 0, limit: None, sign: g.sign })
                    }
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
        };
        for &(p, xy) in &plan.fixed {
            s.pos[p] = xy;
        }
        s
    }

    /// Solves every op at `theta`, each group from its own prediction; commits the groups
    /// that converge on their branch. Returns true when some group failed by itself (not
    /// because something it depends on failed).
    fn eval(&mut self, theta: f64) -> bool {
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
                    let r = rot_m(*m, sub(pb, pa));
                    self.pos[*q] = [pa[0] + r[0], pa[1] + r[1]];
                    if self.need_vel {
                        let (va, vb) = (self.vel[*a], self.vel[*b]);
                        let rv = rot_m(*m, sub(vb, va));
                        self.vel[*q] = [va[0] + rv[0], va[1] + rv[1]];
                    }
                    if self.need_acc {
                        let (wa, wb) = (self.acc[*a], self.acc[*b]);
                        let rw = rot_m(*m, sub(wb, wa));
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
    fn dyad(&mut self, i: usize, d: &Dyad, theta: f64) -> (Status, f64) {
        let (a, b) = (self.pos[d.k1], self.pos[d.k2]);
        if d.solve(a, b) == DyadOut::Indeterminate {
            return (Status::Singular, 0.0);
        }
        let mut state = self.dyads[i].expect("a dyad has a state");
        let chosen = state.choose(theta, self.opts.max_step, self.fine(), self.opts.newton.singular, |side| {
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
    fn rate(&self) -> f64 {
        if self.plan.linear {
            1.0 / self.plan.scale
        } else {
            1.0
        }
    }

    /// A continuation step is short enough for a change point to be told from a near miss.
    fn fine(&self) -> bool {
        self.step <= self.opts.max_step * 2f64.powi(-FLIP_HALVINGS)
    }

    /// A slider's closed form or a fused linear input's operation at input value `theta`
    /// (a displacement for a linear input): sided ones carry their side as dyads do.
    fn slider(&mut self, i: usize, op: &Op, theta: f64) -> (Status, f64) {
        let singular = self.opts.newton.singular;
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

    fn group(&mut self, i: usize, theta: f64) -> (Status, f64) {
        // the anchors' positions and rates, in buffers kept from angle to angle
        let (mut anchors, mut anchor_vel) =
            (std::mem::take(&mut self.anchor_pos), std::mem::take(&mut self.anchor_vel));
        let r = self.group_with(i, theta, &mut anchors, &mut anchor_vel);
        (self.anchor_pos, self.anchor_vel) = (anchors, anchor_vel);
        r
    }

    fn group_with(&mut self, i: usize, theta: f64, anchors: &mut Vec<Xy>, anchor_vel: &mut Vec<Xy>) -> (Status, f64) {
        let Op::Group(g) = &self.plan.ops[i] else { unreachable!("op {i} is a group") };
        let n = g.n();
        // (borrowed, not copied: the state holds three tangents)
        let state = self.groups[i].as_ref().expect("a group has a state");
        if let Some((at, dir)) = state.limit {
            if (theta - at) * dir > 0.0 {
                return (Status::Limit, f64::NAN);
            }
        }
        let guess = state.predict(theta, g, self.opts.max_step);
        let (det0, sign0) = (state.det(), state.sign);
        anchors.clear();
        anchors.extend(g.anchors.iter().map(|&a| self.pos[a]));
        anchor_vel.clear();
        anchor_vel.extend(g.anchors.iter().map(|&a| self.vel[a]));
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
        let mut out: GroupSolve = solve(&guess[..n], newton);
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
            {
                // on the predicted path over a tiny step, through a change point
                sign = -sign;
            }
        }
        let mut status = out.status;
        if status == Status::Converged && (out.det * sign < 0.0 || jump(&out, &guess[..n]) > JUMP) {
            status = Status::BranchJump;
        }
        if status != Status::Converged {
            return (status, out.det);
        }
        let (pos, vel) = (&mut self.pos, &mut self.vel);
        g.place_moving(&out.phi[..n], &out.dphi[..n], &out.cs[..g.nrot], anchors, anchor_vel, |p, xy, v| {
            pos[p] = xy;
            vel[p] = v;
        });
        if self.need_acc {
            let anchor_acc: Vec<Xy> = g.anchors.iter().map(|&a| self.acc[a]).collect();
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
        st.push(t);
        st.theta = theta;
        st.sign = sign;
        st.limit = None;
        (Status::Converged, out.det)
    }

    /// Continuation to `to` from where the groups and dyads are (the one farthest away sets
    /// the start; one stopped at a dead point that `to` lies beyond does not): uniform steps
    /// of at most `max_step`, each split while some group fails ([`Solver::reach`]); a group
    /// that still fails at the smallest step has met a dead point there, and angles past it
    /// are LIMIT. Ends with an evaluation at `to`. Every step is counted on `poll`
    /// (a small `max_step` makes many).
    fn advance(&mut self, to: f64, poll: &Poll<'_>) -> Result<(), Error> {
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
    fn reach(&mut self, a: f64, b: f64) -> bool {
        self.aimed_left = AIMED_SPLITS;
        self.aimed_from = f64::NAN;
        self.reach_within(a, b, 0, (b - a).abs() * 2f64.powi(-(MAX_HALVINGS as i32)))
    }

    fn reach_within(&mut self, a: f64, b: f64, depth: u32, floor: f64) -> bool {
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
    fn split(&mut self, a: f64, b: f64, floor: f64) -> f64 {
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
    fn aimed(&mut self, a: f64, b: f64, floor: f64, failing: bool) -> Option<f64> {
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

    /// The dead point (input angle) that stops the first group at LIMIT, if any.
    fn limit_angle(&self) -> f64 {
        for (i, (g, d)) in self.groups.iter().zip(&self.dyads).enumerate() {
            if self.op_status[i] != Status::Limit {
                continue;
            }
            let limit = g.and_then(|g| g.limit).or_else(|| d.and_then(|d| d.limit));
            if let Some((at, _)) = limit {
                return at;
            }
        }
        f64::NAN
    }

    /// Writes row `k` of the outputs; the links' directions go to `dirs` (row `k` of its x
    /// half and of its y half, NaN where a point is not solved), whose angles
    /// [`Plan::sweep`] takes at the end, all at once.
    fn write(&self, k: usize, out: &mut SceneSweepOut<'_>, dirs: &mut [f64]) {
        let plan = self.plan;
        let (np, nl, ns) = (plan.points.len(), plan.links.len(), plan.steps.len());
        let (sc, org) = (plan.scale, plan.origin);
        let all_ok = !self.any_failure;
        let row = &mut out.points[2 * k * np..2 * (k + 1) * np];
        for (dst, &p) in row.chunks_exact_mut(2).zip(&plan.points) {
            let xy = self.pos[p];
            dst[0] = xy[0] * sc + org[0];
            dst[1] = xy[1] * sc + org[1];
        }
        let pst = &mut out.point_status[k * np..(k + 1) * np];
        if all_ok {
            pst.fill(0);
        } else {
            for ((code, dst), &p) in pst.iter_mut().zip(row.chunks_exact_mut(2)).zip(&plan.points) {
                *code = self.pst[p].code();
                if self.pst[p] != Status::Converged {
                    dst.fill(f64::NAN);
                }
            }
        }
        let ok = |p: usize| all_ok || self.pst[p] == Status::Converged;
        let (dx, dy) = dirs.split_at_mut(dirs.len() / 2);
        let row = dx[k * nl..(k + 1) * nl].iter_mut().zip(&mut dy[k * nl..(k + 1) * nl]);
        for ((x, y), &(a, b)) in row.zip(&plan.link_points) {
            [*x, *y] = if ok(a) && ok(b) { sub(self.pos[b], self.pos[a]) } else { [f64::NAN; 2] };
        }
        if let Some((v, w)) = out.velocity.as_mut() {
            // per unit of the sweep variable (a displacement's rates carry 1 / scale)
            let omega = self.opts.omega.unwrap_or(0.0) * self.rate();
            for (dst, &p) in v[2 * k * np..2 * (k + 1) * np].chunks_exact_mut(2).zip(&plan.points) {
                let (u, good) = (self.vel[p], ok(p));
                dst[0] = if good { u[0] * sc * omega } else { f64::NAN };
                dst[1] = if good { u[1] * sc * omega } else { f64::NAN };
            }
            for (dst, &(a, b)) in w[k * nl..(k + 1) * nl].iter_mut().zip(&plan.link_points) {
                let (d, dv) = (sub(self.pos[b], self.pos[a]), sub(self.vel[b], self.vel[a]));
                *dst = if ok(a) && ok(b) { cross(d, dv) / dot(d, d) * omega } else { f64::NAN };
            }
        }
        if let Some((acc, alpha)) = out.acceleration.as_mut() {
            let w2 = (self.opts.omega.unwrap_or(0.0) * self.rate()).powi(2);
            for (dst, &p) in acc[2 * k * np..2 * (k + 1) * np].chunks_exact_mut(2).zip(&plan.points) {
                let (u, good) = (self.acc[p], ok(p));
                dst[0] = if good { u[0] * sc * w2 } else { f64::NAN };
                dst[1] = if good { u[1] * sc * w2 } else { f64::NAN };
            }
            for (dst, &(a, b)) in alpha[k * nl..(k + 1) * nl].iter_mut().zip(&plan.link_points) {
                let (d, dv) = (sub(self.pos[b], self.pos[a]), sub(self.vel[b], self.vel[a]));
                let dw = sub(self.acc[b], self.acc[a]);
                *dst = if ok(a) && ok(b) { angular_acceleration(d, dv, dw) * w2 } else { f64::NAN };
            }
        }
        let status = if all_ok {
            Status::Converged
        } else {
            self.op_status.iter().copied().find(|s| *s != Status::Converged).unwrap_or(Status::Converged)
        };
        let mut det = 1.0;
        let (sst, sdet) = (&mut out.step_status[k * ns..(k + 1) * ns], &mut out.step_det[k * ns..(k + 1) * ns]);
        for ((code, d), &i) in sst.iter_mut().zip(sdet.iter_mut()).zip(&plan.step_op) {
            *code = self.op_status[i].code();
            *d = self.op_det[i];
            det *= self.op_det[i];
        }
        out.status[k] = status.code();
        out.det[k] = det;
        out.limit[k] = f64::NAN;
        out.nit[k] = self.nit;
    }
}

/// q - a = m (b - a) in complex arithmetic.
#[inline]
fn rot_m(m: Xy, d: Xy) -> Xy {
    [m[0] * d[0] - m[1] * d[1], m[1] * d[0] + m[0] * d[1]]
}

impl Plan {
    /// Solves the plan at every input value of `theta` (radians, or a linear input's
    /// displacements; any order): from the drawn pose to `theta[0]` (an angle the shortest
    /// way round), then along `theta` in order. Values past a dead point are LIMIT; those
    /// that the drawn circuit reaches the other way are then solved by continuing from the
    /// drawn pose backwards over `theta`, from the last LIMIT value to the first. What
    /// stays LIMIT is NOT_ASSEMBLABLE where the linkage has no assembly at all.
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
        if self.columns_ok() {
            columns::sweep(self, theta, opts, &mut out, &poll)?;
            if self.certified(theta, opts, &out) {
                return Ok(());
            }
        }
        let limit = Status::Limit.code();
        // the links' directions, turned into angles at the end in one vectorized pass
        let mut dirs = try_zeros(|| "the links' directions".to_string(), 2 * n * nl)?;
        self.continuation(theta, 0..n, opts, &mut out, &mut dirs, false, &poll)?;
        // the rest of the drawn circuit, backwards from the drawn pose: the angles left
        // LIMIT, from the last of them back to the first (what the other way round reaches)
        if let (Some(first), Some(last)) =
            (out.status.iter().position(|&s| s == limit), out.status.iter().rposition(|&s| s == limit))
        {
            self.continuation(theta, (first..=last).rev(), opts, &mut out, &mut dirs, true, &poll)?;
        }
        let (dx, dy) = dirs.split_at(n * nl);
        crate::simd::directions_into(dx, dy, out.angles);
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
    /// conditioning at least [`CERTIFIED`] in size, and the values in sweep order (from the
    /// drawn one; an angle the shortest way round) no more than `max_step` apart.
    /// Otherwise the plan is followed by continuation.
    fn certified(&self, theta: &[f64], opts: &SceneSweepOptions, out: &SceneSweepOut<'_>) -> bool {
        let Some(&t0) = theta.first() else { return true };
        let h0 = if self.linear { t0 - self.theta0 } else { wrap_angle(t0 - self.theta0) };
        // folds with no early exit: these loops vectorize
        let close =
            theta.windows(2).fold(h0.abs() <= opts.max_step, |ok, t| ok & ((t[1] - t[0]).abs() <= opts.max_step));
        let ok = Status::Converged.code();
        close
            && out.status.iter().fold(true, |all, &s| all & (s == ok))
            && out.step_det.iter().fold(true, |all, d| all & (d.abs() >= CERTIFIED))
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
            // the dead point that stopped the motion stays in `limit`
            out.status[k] = none;
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

    /// Continuation from the drawn pose over the indices `order`; `backward` writes only the
    /// angles the forward pass left LIMIT (and leaves non-finite angles as they are).
    #[allow(clippy::too_many_arguments)]
    fn continuation(
        &self,
        theta: &[f64],
        order: impl Iterator<Item = usize>,
        opts: &SceneSweepOptions,
        out: &mut SceneSweepOut<'_>,
        dirs: &mut [f64],
        backward: bool,
        poll: &Poll<'_>,
    ) -> Result<(), Error> {
        let mut s = Solver::new(self, *opts);
        s.eval(self.theta0); // tangents at the drawn pose
        let mut started = false;
        for k in order {
            poll.tick()?;
            let t = theta[k];
            s.nit = 0;
            if !t.is_finite() {
                s.eval(t);
            } else {
                if !started {
                    // the input repeats every turn: reach theta[k] the shortest way, then
                    // relabel the states to it
                    let start = if self.linear { t } else { self.theta0 + wrap_angle(t - self.theta0) };
                    s.advance(start, poll)?;
                    for g in s.groups.iter_mut().flatten() {
                        let shift = t - start;
                        g.theta += shift;
                        for tg in g.tangents.iter_mut().flatten() {
                            tg.theta += shift;
                        }
                        if let Some(l) = g.limit.as_mut() {
                            l.0 += shift;
                        }
                    }
                    for d in s.dyads.iter_mut().flatten() {
                        d.theta += t - start;
                        if let Some(l) = d.limit.as_mut() {
                            l.0 += t - start;
                        }
                    }
                    if start == t {
                        s.last_eval = t;
                    } else {
                        // the same pose, solved at the angle asked for (not a turn away)
                        s.eval(t);
                    }
                    started = true;
                } else {
                    s.advance(t, poll)?;
                }
            }
            // going back, only what the forward pass left LIMIT is written
            if backward && (!t.is_finite() || out.status[k] != Status::Limit.code()) {
                continue;
            }
            s.write(k, out, dirs);
            out.limit[k] = s.limit_angle();
        }
        Ok(())
    }
}

#[cfg(test)]
mod tests {
    use super::Hermite5;

    /// The quintic Hermite interpolant is exact on a polynomial of degree 5, at uneven
    /// abscissae, and its extrapolation of sin one step on has the error its remainder
    /// term gives (h^6 |f^(6)| / 20 for equal steps).
    #[test]
    fn hermite5_is_exact_on_quintics_and_sixth_order_on_sin() {
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
}
