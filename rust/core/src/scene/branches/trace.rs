//! Tracing a circuit through its dead points: pseudo-arclength continuation in
//! (configuration, input angle) space.
//!
//! The whole linkage is one [`Group`] over the ground points with the input link among its
//! links: n rotations (the input's is theta - theta0), n - 1 loop-closure equations F = 0.
//! Its solution set is a curve; each step predicts along the unit tangent (the null vector
//! of dF) and corrects by Newton on [F; t . (x - x_pred)] = 0, so dead points, where
//! theta turns back, are passed like any other point. Turning points are where the plan's
//! signed conditioning (the product of its steps') changes sign and the input reverses,
//! refined by bisection along the step.

use nalgebra::{DMatrix, DVector};

use crate::error::{positive_finite, try_grow, Error};
use crate::interrupt::{Interrupt, Poll};
use crate::scene::build::Plan;
use crate::scene::model::Scene;
use crate::scene::ops::Group;
use crate::scene::vec2::Xy;
use crate::wrap_angle;

/// Tracing options.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct TraceOptions {
    /// Largest arclength step (radians of rotation, all links together).
    pub step: f64,
    /// At most this many points on a trace.
    pub max_points: usize,
}

/// The default largest arclength step of a trace (radians of rotation, all links).
pub(crate) const DEFAULT_STEP: f64 = 0.05;
/// The default largest number of points of a trace.
pub(crate) const DEFAULT_MAX_POINTS: usize = 50_000;

impl Default for TraceOptions {
    fn default() -> Self {
        Self { step: DEFAULT_STEP, max_points: DEFAULT_MAX_POINTS }
    }
}

impl TraceOptions {
    /// Validates `step` (finite, > 0) and `max_points` (an integer >= 2).
    pub fn new(step: f64, max_points: i64) -> Result<Self, Error> {
        positive_finite("step", step)?;
        let max_points = usize::try_from(max_points)
            .ok()
            .filter(|&m| m >= 2)
            .ok_or_else(|| Error::invalid("max_points", "must be an integer >= 2", max_points))?;
        Ok(Self { step, max_points })
    }
}

/// A traced path.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct Trace {
    /// Input angle at each point, continuous along the path (not wrapped).
    pub theta: Vec<f64>,
    /// Every point of the scene at each path point, scene coordinates: (M, P) row-major.
    pub points: Vec<Xy>,
    /// The plan's signed conditioning at each path point.
    pub det: Vec<f64>,
    /// Input angles (continuous, as `theta`) of the dead points passed, in path order.
    pub turning_points: Vec<f64>,
    /// The path came back to its start (the last point is the start again).
    pub closed: bool,
    /// Input values (continuous, as `theta`) where the path stops at a travel limit (the
    /// scene's `limits`), in path order: its two ends, or none.
    pub limits: Vec<f64>,
}

/// The whole linkage as one curve.
pub struct Tracer<'s> {
    chain: Group,
    /// Unknown index of the input link.
    input: usize,
    pub(super) plan: Plan,
    scene: &'s Scene,
}

impl<'s> Tracer<'s> {
    /// The chain of every non-ground link over the ground points.
    pub fn new(scene: &'s Scene) -> Result<Self, Error> {
        let links: Vec<usize> = (0..scene.links.len()).filter(|&l| l != scene.ground).collect();
        let mut known = vec![false; scene.names.len()];
        for &p in &scene.links[scene.ground].points {
            known[p] = true;
        }
        let chain = Group::tree(scene, &links, &known, true)
            .ok_or_else(|| Error::scene("trace", "the links do not form one connected linkage over the ground"))?;
        let input = chain.input.expect("a chain has an input column");
        Ok(Tracer { chain, input, plan: scene.plan(None)?, scene })
    }

    fn n(&self) -> usize {
        self.chain.n()
    }

    fn anchors(&self) -> Vec<Xy> {
        self.chain.anchors.iter().map(|&p| self.scene.xy[p]).collect()
    }

    /// F and dF at rotations x.
    fn eval(&self, x: &[f64], delta: &[Xy]) -> (DVector<f64>, DMatrix<f64>) {
        let m = 2 * self.chain.closures.len();
        let mut f = DVector::zeros(m);
        let mut j = DMatrix::zeros(m, self.n());
        self.chain.closure_terms(x, delta, |r, v| f[r] = v, |r, c, v| j[(r, c)] += v);
        (f, j)
    }

    /// Unit tangent at x (the null vector of dF, from [dF; c^T] t = e_n with c the previous
    /// tangent, or a coordinate axis at the start), oriented along `prev` (or with the
    /// input angle increasing).
    fn tangent(&self, x: &[f64], delta: &[Xy], prev: Option<&DVector<f64>>) -> Option<DVector<f64>> {
        let (_, j) = self.eval(x, delta);
        let n = self.n();
        let axis = |k: usize| {
            let mut e = DVector::zeros(n);
            e[k] = 1.0;
            e
        };
        let cands: Vec<DVector<f64>> = match prev {
            Some(p) => vec![p.clone()],
            None => std::iter::once(self.input).chain((0..n).filter(|&k| k != self.input)).map(axis).collect(),
        };
        let mut best: Option<DVector<f64>> = None;
        for c in cands {
            let mut a = DMatrix::zeros(n, n);
            a.view_mut((0, 0), (n - 1, n)).copy_from(&j);
            a.row_mut(n - 1).copy_from(&c.transpose());
            if let Some(t) = a.lu().solve(&axis(n - 1)) {
                let norm = t.norm();
                if norm.is_finite() && norm > 0.0 {
                    let t = t / norm;
                    let align = t.dot(&c).abs();
                    // prefer the candidate best aligned with the tangent (least ill-posed)
                    if best.as_ref().is_none_or(|b: &DVector<f64>| align > b.dot(&c).abs()) {
                        best = Some(t);
                    }
                    if align > 0.1 {
                        break;
                    }
                }
            }
        }
        let mut t = best?;
        let flip = match prev {
            Some(p) => t.dot(p) < 0.0,
            None => t[self.input] < 0.0,
        };
        if flip {
            t = -t;
        }
        Some(t)
    }

    /// Newton on [F(y); t . (y - xp)] = 0 from xp.
    fn correct(&self, xp: &DVector<f64>, t: &DVector<f64>, delta: &[Xy]) -> Option<(DVector<f64>, u32)> {
        let n = self.n();
        let mut y = xp.clone();
        for it in 0..12u32 {
            let (f, j) = self.eval(y.as_slice(), delta);
            let mut a = DMatrix::zeros(n, n);
            a.view_mut((0, 0), (n - 1, n)).copy_from(&j);
            a.row_mut(n - 1).copy_from(&t.transpose());
            let mut r = DVector::zeros(n);
            r.rows_mut(0, n - 1).copy_from(&(-&f));
            r[n - 1] = -t.dot(&(&y - xp));
            let dx = a.lu().solve(&r)?;
            y += &dx;
            let step = dx.amax();
            if !step.is_finite() {
                return None;
            }
            if step < 1e-13 && f.amax() < 1e-12 {
                return Some((y, it + 1));
            }
        }
        let (f, _) = self.eval(y.as_slice(), delta);
        (f.amax() < 1e-11).then_some((y, 12))
    }

    /// Positions of every point (solving frame) at rotations x.
    fn positions(&self, x: &[f64]) -> Vec<Xy> {
        let mut pos = vec![[f64::NAN; 2]; self.scene.names.len()];
        for &(p, xy) in &self.plan.fixed {
            pos[p] = xy;
        }
        let anchors = self.anchors();
        self.chain.place(x, &anchors, |p, xy| pos[p] = xy);
        pos
    }

    fn det(&self, x: &[f64]) -> f64 {
        self.plan.dets_at(&self.positions(x)).0
    }

    /// The input at unknowns x: an angle, or a linear input's displacement (scene units).
    fn theta(&self, x: &[f64]) -> f64 {
        if self.chain.is_angle(self.input) {
            self.scene.theta0 + x[self.input]
        } else {
            x[self.input] * self.plan.scale
        }
    }

    /// `theta - target`, wrapped to (-pi, pi] for an angle input.
    fn offset(&self, theta: f64, target: f64) -> f64 {
        if self.chain.is_angle(self.input) {
            wrap_angle(theta - target)
        } else {
            theta - target
        }
    }

    /// Rotations of an assembly given by its positions (solving frame), polished by Newton
    /// at its input angle.
    fn start(&self, pos: &[Xy], delta: &[Xy]) -> Option<DVector<f64>> {
        let x = DVector::from_vec(self.chain.unknowns_from(|p| pos[p]));
        let mut e = DVector::zeros(self.n());
        e[self.input] = 1.0;
        self.correct(&x, &e, delta).map(|(y, _)| y)
    }

    /// Traces the circuit through the assembly `pos` (solving frame, every point), in the
    /// direction of increasing input angle (or along its tangent at a dead point).
    /// `interrupt` is asked every few thousand steps (Ctrl-C from Python).
    pub fn trace_from(&self, pos: &[Xy], opts: &TraceOptions, interrupt: &dyn Interrupt) -> Result<Trace, Error> {
        Ok(self.trace_watching(pos, opts, None, &Poll::new(interrupt))?.0)
    }

    /// [`Tracer::trace_from`], also returning the poses (solving frame) where the path
    /// crosses the input angle `watch` (modulo 2 pi), the start excluded.
    pub(super) fn trace_watching(
        &self,
        pos: &[Xy],
        opts: &TraceOptions,
        watch: Option<f64>,
        poll: &Poll<'_>,
    ) -> Result<(Trace, Vec<Vec<Xy>>), Error> {
        let mut crossings = Vec::new();
        let delta = self.anchors();
        let x0 = self
            .start(pos, &delta)
            .ok_or_else(|| Error::scene("trace", "the given pose is not an assembly of the scene"))?;
        let mut t = self
            .tangent(x0.as_slice(), &delta, None)
            .ok_or_else(|| Error::scene("trace", "no tangent at the start"))?;
        let mut out = Trace::default();
        self.record(&mut out, x0.as_slice(), self.det(x0.as_slice()))?;
        // travel limits bind only a path that starts inside them
        let limited = !self.plan.limits.is_empty() && self.inside(x0.as_slice());
        let stopped = self.walk(&x0, &t, opts, watch, limited, poll, &mut out, &mut crossings)?;
        if stopped {
            // the other way from the start, to the other limit: the path is the arc between
            let mut back = Trace::default();
            self.record(&mut back, x0.as_slice(), self.det(x0.as_slice()))?;
            t = -t;
            self.walk(&x0, &t, opts, watch, true, poll, &mut back, &mut crossings)?;
            out = join(back, out, self.plan.npoints);
        }
        Ok((out, crossings))
    }

    /// Every travel limit holds at unknowns x.
    fn inside(&self, x: &[f64]) -> bool {
        let pos = self.positions(x);
        self.plan.limits.iter().all(|l| {
            let v = l.value(&pos, self.plan.scale);
            let slack = 16.0 * f64::EPSILON * (l.range.0.abs() + l.range.1.abs());
            v >= l.range.0 - slack && v <= l.range.1 + slack
        })
    }

    /// Follows the path from x0 along t0 into `out` (which holds x0) until it closes,
    /// `opts.max_points` is reached or (`limited`) a travel limit binds, the last recorded
    /// then; true when it stopped at a limit.
    #[allow(clippy::too_many_arguments)]
    fn walk(
        &self,
        x0: &DVector<f64>,
        t0: &DVector<f64>,
        opts: &TraceOptions,
        watch: Option<f64>,
        limited: bool,
        poll: &Poll<'_>,
        out: &mut Trace,
        crossings: &mut Vec<Vec<Xy>>,
    ) -> Result<bool, Error> {
        let delta = self.anchors();
        let (mut x, mut t) = (x0.clone(), t0.clone());
        let mut d = self.det(x.as_slice());
        let mut h = opts.step;
        let hmin = opts.step * 1e-7;
        let mut travelled = 0.0;
        while out.theta.len() < opts.max_points {
            poll.tick()?;
            let xp = &x + &t * h;
            let Some((y, it)) = self.correct(&xp, &t, &delta) else {
                h *= 0.5;
                if h < hmin {
                    break;
                }
                continue;
            };
            let Some(tn) = self.tangent(y.as_slice(), &delta, Some(&t)) else { break };
            // a step that turns the tangent by more than ~30 degrees may have jumped branch
            if tn.dot(&t) < 0.85 && h > hmin {
                h *= 0.5;
                continue;
            }
            travelled += h;
            // back at the start (all rotations equal modulo 2 pi)? The last step then ends
            // at the start itself, along the chord from x (a dead point between them, met
            // when the drawing lies near one, is still found on it)
            let mut closing = None;
            if travelled > 4.0 * opts.step && self.wrapped_gap(&y, x0) < h {
                let unwrapped = self.unwrap_like(x0, &y);
                if let Some((z, _)) = self.correct(&unwrapped, &t, &delta) {
                    if self.wrapped_gap(&z, x0) < 1e-9 {
                        closing = Some(z);
                    }
                }
            }
            let (end, dir, len) = match &closing {
                Some(z) => {
                    let chord = z - &x;
                    let len = chord.norm();
                    (z.clone(), if len > 0.0 { chord / len } else { t.clone() }, len)
                }
                None => (y.clone(), t.clone(), h),
            };
            if limited && !self.inside(end.as_slice()) {
                // a travel limit binds within this step: the path stops there
                let (at, z) = self.limit_point(&x, &dir, len, &delta);
                if let Some(z) = z {
                    self.record(out, z.as_slice(), self.det(z.as_slice()))?;
                }
                out.limits.push(at);
                return Ok(true);
            }
            let dn = self.det(end.as_slice());
            // the step in pieces over which the input is monotone: split at a dead point
            let mut pieces = vec![(0.0, self.theta(x.as_slice()))];
            let mut dead = None;
            // the conditioning changes sign at a dead point, where the input reverses, and at
            // a change point, where it does not (links falling in line and on through it, a
            // slot's point passing through its guide's pivot)
            let reverses = d * dn < 0.0 && {
                let te =
                    if closing.is_some() { self.tangent(end.as_slice(), &delta, Some(&t)) } else { Some(tn.clone()) };
                te.is_none_or(|te| t[self.input] * te[self.input] < 0.0)
            };
            if reverses {
                let (tp, at, z) = self.turning_point(&x, &dir, len, d, &delta);
                out.turning_points.push(tp);
                pieces.push((at, tp));
                dead = z;
            }
            pieces.push((len, self.theta(end.as_slice())));
            if let Some(w) = watch {
                for k in 1..pieces.len() {
                    let ((lo, ta), (hi, tb)) = (pieces[k - 1], pieces[k]);
                    let (wa, wb) = (self.offset(ta, w), self.offset(tb, w));
                    // (an angle's wrap from pi to -pi is no crossing; the start is none)
                    let wrapped = self.chain.is_angle(self.input) && (wa - wb).abs() >= std::f64::consts::PI;
                    let start = closing.is_some() && k + 1 == pieces.len() && wb == 0.0;
                    if wa != 0.0 && wa * wb <= 0.0 && !wrapped && !start {
                        if let Some(p) = self.crossing(&x, &dir, (lo, hi), w, &delta) {
                            crossings.push(p);
                        }
                    }
                }
            }
            // the path passes through its dead point (the input's extreme there, as refined)
            if let Some(z) = dead {
                self.record(out, z.as_slice(), self.det(z.as_slice()))?;
            }
            if closing.is_some() {
                self.record(out, end.as_slice(), dn)?;
                out.closed = true;
                break;
            }
            self.record(out, y.as_slice(), dn)?;
            x = y;
            t = tn;
            d = dn;
            h = if it <= 3 {
                (h * 1.5).min(opts.step)
            } else if it >= 6 {
                h * 0.5
            } else {
                h
            };
        }
        Ok(false)
    }

    /// Bisection on the travel limits along the step from x (inside them) in the unit
    /// direction t, of length h: the input where the first binds, and the pose there.
    fn limit_point(&self, x: &DVector<f64>, t: &DVector<f64>, h: f64, delta: &[Xy]) -> (f64, Option<DVector<f64>>) {
        let (mut lo, mut hi) = (0.0, h);
        let mut best = (self.theta(x.as_slice()), Some(x.clone()));
        for _ in 0..60 {
            let mid = 0.5 * (lo + hi);
            let Some((y, _)) = self.correct(&(x + t * mid), t, delta) else { break };
            if self.inside(y.as_slice()) {
                lo = mid;
                best = (self.theta(y.as_slice()), Some(y));
            } else {
                hi = mid;
            }
            if hi - lo < 1e-14 {
                break;
            }
        }
        best
    }

    fn record(&self, out: &mut Trace, x: &[f64], det: f64) -> Result<(), Error> {
        self.record_pose(out, &self.positions(x), self.theta(x), det)
    }

    /// Appends one path point, growing the trace fallibly (a long trace is the user's to
    /// ask for: `max_points`).
    pub(super) fn record_pose(&self, out: &mut Trace, pos: &[Xy], theta: f64, det: f64) -> Result<(), Error> {
        let plan = &self.plan;
        let (m, np) = (out.theta.len() + 1, pos.len());
        let what = || format!("trace: {m} points of {np} scene points each");
        try_grow(&mut out.points, pos.len(), what)?;
        try_grow(&mut out.theta, 1, what)?;
        try_grow(&mut out.det, 1, what)?;
        out.theta.push(theta);
        out.det.push(det);
        out.points.extend(pos.iter().map(|p| [p[0] * plan.scale + plan.origin[0], p[1] * plan.scale + plan.origin[1]]));
        Ok(())
    }

    /// Bisection on the conditioning's sign along the step from x (where it is `d0`) in the
    /// unit direction t, of length h: the input there, the step's parameter and the
    /// unknowns (None where no bisection point converged).
    fn turning_point(
        &self,
        x: &DVector<f64>,
        t: &DVector<f64>,
        h: f64,
        d0: f64,
        delta: &[Xy],
    ) -> (f64, f64, Option<DVector<f64>>) {
        let (mut lo, mut hi) = (0.0, h);
        let mut best = (self.theta(x.as_slice()), 0.0, None);
        for _ in 0..60 {
            let mid = 0.5 * (lo + hi);
            let Some((y, _)) = self.correct(&(x + t * mid), t, delta) else { break };
            best = (self.theta(y.as_slice()), mid, None);
            if self.det(y.as_slice()) * d0 > 0.0 {
                lo = mid;
            } else {
                hi = mid;
            }
            best.2 = Some(y);
            if hi - lo < 1e-13 {
                break;
            }
        }
        best
    }

    /// The point of the step from x along t, between the parameters `span` (over which the
    /// input is monotone), where the input angle is `target` modulo 2 pi, by bisection;
    /// positions in the solving frame.
    fn crossing(
        &self,
        x: &DVector<f64>,
        t: &DVector<f64>,
        span: (f64, f64),
        target: f64,
        delta: &[Xy],
    ) -> Option<Vec<Xy>> {
        let g = |y: &DVector<f64>| self.offset(self.theta(y.as_slice()), target);
        let (mut lo, mut hi) = span;
        let mut y = if lo > 0.0 { self.correct(&(x + t * lo), t, delta)?.0 } else { x.clone() };
        let g0 = g(&y);
        for _ in 0..80 {
            let mid = 0.5 * (lo + hi);
            y = self.correct(&(x + t * mid), t, delta)?.0;
            let gm = g(&y);
            if gm == 0.0 {
                break;
            }
            if gm * g0 > 0.0 {
                lo = mid;
            } else {
                hi = mid;
            }
            if hi - lo < 1e-14 {
                break;
            }
        }
        // land exactly on the target angle
        let mut e = DVector::zeros(self.n());
        e[self.input] = 1.0;
        let mut z = y.clone();
        let unit = if self.chain.is_angle(self.input) { 1.0 } else { self.plan.scale };
        z[self.input] -= g(&y) / unit;
        let (z, _) = self.correct(&z, &e, delta)?;
        Some(self.positions(z.as_slice()))
    }

    /// Largest |a_k - b_k|, angles wrapped.
    fn wrapped_gap(&self, a: &DVector<f64>, b: &DVector<f64>) -> f64 {
        (0..a.len()).map(|k| self.chain.gap(k, a[k], b[k]).abs()).fold(0.0, f64::max)
    }

    /// `a` with its angles shifted by whole turns to lie next to `b`.
    fn unwrap_like(&self, a: &DVector<f64>, b: &DVector<f64>) -> DVector<f64> {
        DVector::from_iterator(a.len(), (0..a.len()).map(|k| b[k] + self.chain.gap(k, a[k], b[k])))
    }
}

impl Scene {
    /// Traces the circuit through `start` (every point, scene coordinates; default the
    /// drawn pose) through its dead points until it closes or `opts.max_points` is reached.
    /// `interrupt` is asked every few thousand steps.
    pub fn trace(&self, start: Option<&[Xy]>, opts: &TraceOptions, interrupt: &dyn Interrupt) -> Result<Trace, Error> {
        let pos = match start {
            None => self.xy.clone(),
            Some(p) => {
                if p.len() != self.names.len() {
                    return Err(Error::Shape { name: "start".into(), got: p.len(), expected: self.names.len() });
                }
                p.iter().map(|&q| self.to_frame(q)).collect()
            }
        };
        Tracer::new(self)?.trace_from(&pos, opts, interrupt)
    }
}

/// The path `back` (from the start, the other way) reversed, then `ahead` (from the start):
/// one arc between the two limits, the start once; `np` points per path point.
fn join(back: Trace, ahead: Trace, np: usize) -> Trace {
    let m = back.theta.len();
    let mut out = Trace::default();
    for k in (1..m).rev() {
        out.theta.push(back.theta[k]);
        out.det.push(back.det[k]);
        out.points.extend_from_slice(&back.points[k * np..(k + 1) * np]);
    }
    out.theta.extend(ahead.theta);
    out.det.extend(ahead.det);
    out.points.extend(ahead.points);
    out.turning_points = back.turning_points.into_iter().rev().chain(ahead.turning_points).collect();
    out.limits = back.limits.into_iter().chain(ahead.limits).collect();
    out
}
