//! The plan: the steps that solve what was asked for, compiled once per scene and set of
//! requested outputs. From ground and the input link it peels RRR dyads (closed form) and
//! rigid bodies (a link with two known points is known); where no dyad remains it finds
//! the smallest group of links that is rigid over the known points and solves it by
//! Newton. Then it keeps only the operations the requested points and link angles need:
//! this is where "model only what a scene requires" lives.

use super::dyad::Dyad;
use super::group::{Group, MAX};
use super::vec2::{cross, dot, sub, Xy};
use super::Scene;
use crate::error::Error;

/// Kind of a plan step.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum StepKind {
    /// A point reached by two links from two known points (circle intersection).
    Dyad,
    /// Links solved together by Newton-Raphson (no dyad reaches them).
    Group,
}

impl StepKind {
    /// "dyad" or "group".
    pub fn name(self) -> &'static str {
        match self {
            StepKind::Dyad => "dyad",
            StepKind::Group => "group",
        }
    }
}

/// One step as shown to a user.
#[derive(Clone, Debug, PartialEq)]
pub struct StepInfo {
    /// Dyad or group.
    pub kind: StepKind,
    /// Points it solves (scene indices), the primary ones first, then those carried by
    /// the links it makes known.
    pub points: Vec<usize>,
    /// Links whose angles are its unknowns (a dyad's two links; a group's links).
    pub unknowns: Vec<usize>,
}

/// One operation of the compiled plan.
#[derive(Clone, Debug, PartialEq)]
pub(super) enum Op {
    /// A point of the input link: pivot + lam u + mu perp(u), u = (cos theta, sin theta).
    Input {
        q: usize,
        lam: f64,
        mu: f64,
    },
    Dyad(Dyad),
    /// q = a + m (b - a), m the complex ratio (q - a) / (b - a) as drawn: a rigid link
    /// with two known points carries its others.
    Carry {
        q: usize,
        a: usize,
        b: usize,
        m: Xy,
    },
    Group(Box<Group>),
}

impl Op {
    fn inputs(&self) -> Vec<usize> {
        match self {
            Op::Input { .. } => Vec::new(),
            Op::Dyad(d) => vec![d.k1, d.k2],
            Op::Carry { a, b, .. } => vec![*a, *b],
            Op::Group(g) => g.anchors.clone(),
        }
    }

    fn outputs(&self) -> Vec<usize> {
        match self {
            Op::Input { q, .. } | Op::Carry { q, .. } => vec![*q],
            Op::Dyad(d) => vec![d.p],
            Op::Group(g) => g.nodes.iter().map(|n| n.point).collect(),
        }
    }
}

/// A compiled plan: self-contained (it copies what it needs from the scene).
#[derive(Clone, Debug)]
pub struct Plan {
    pub(super) ops: Vec<Op>,
    pub(super) steps: Vec<StepInfo>,
    /// The op that opens each step (its dyad or group).
    pub(super) step_op: Vec<usize>,
    /// Points reported, scene order.
    pub(super) points: Vec<usize>,
    /// Links whose angles are reported, and their angle points.
    pub(super) links: Vec<usize>,
    pub(super) link_points: Vec<(usize, usize)>,
    /// Ground points, solving frame.
    pub(super) fixed: Vec<(usize, Xy)>,
    pub(super) npoints: usize,
    pub(super) pivot: Xy,
    pub(super) theta0: f64,
    pub(super) scale: f64,
    pub(super) origin: Xy,
}

impl Plan {
    /// The steps, in solving order.
    pub fn steps(&self) -> &[StepInfo] {
        &self.steps
    }

    /// Scene indices of the points a sweep reports (every point the plan reads or solves).
    pub fn points(&self) -> &[usize] {
        &self.points
    }

    /// Scene indices of the links whose angles a sweep reports.
    pub fn links(&self) -> &[usize] {
        &self.links
    }

    /// The drawn input angle the sweep starts from.
    pub fn input_angle(&self) -> f64 {
        self.theta0
    }

    /// The signed conditioning of the whole solve and of each step at a pose given by the
    /// positions of every point (solving frame).
    pub(super) fn dets_at(&self, pos: &[Xy]) -> (f64, Vec<f64>) {
        let dets: Vec<f64> = self
            .step_op
            .iter()
            .map(|&i| match &self.ops[i] {
                Op::Dyad(d) => d.det_at(pos[d.p], pos[d.k1], pos[d.k2]),
                Op::Group(g) => {
                    let phi = g.rotations_from(|p| pos[p]);
                    let delta = g.deltas(|p| pos[p]);
                    g.conditioning_with(&phi, &delta[..g.closures.len()])
                }
                _ => unreachable!("steps open with a dyad or a group"),
            })
            .collect();
        (dets.iter().product(), dets)
    }

    /// True when some step is a group (solved by Newton with continuation).
    pub fn has_group(&self) -> bool {
        self.ops.iter().any(|o| matches!(o, Op::Group(_)))
    }
}

/// Most subsets of links examined when searching for the smallest rigid group.
const GROUP_SEARCH_BUDGET: usize = 200_000;

pub(super) fn compile(sc: &Scene, want_points: &[usize], want_links: &[usize]) -> Result<Plan, Error> {
    let np = sc.names.len();
    let xy = &sc.xy;
    let mut known = vec![false; np];
    for &p in &sc.links[sc.ground].points {
        known[p] = true;
    }
    let mut ops: Vec<Op> = Vec::new();
    let (piv, tip) = (xy[sc.input.pivot], xy[sc.input.tip]);
    let u0 = sub(tip, piv);
    let u0 = {
        let n = dot(u0, u0).sqrt();
        [u0[0] / n, u0[1] / n]
    };
    for &q in &sc.links[sc.input.link].points {
        if !known[q] {
            let d = sub(xy[q], piv);
            ops.push(Op::Input { q, lam: dot(d, u0), mu: cross(u0, d) });
            known[q] = true;
        }
    }
    loop {
        carry_all(sc, &mut known, &mut ops);
        if known.iter().all(|&k| k) {
            break;
        }
        if let Some(d) = find_dyad(sc, &known) {
            known[d.p] = true;
            ops.push(Op::Dyad(d));
            continue;
        }
        let g = find_group(sc, &known)?;
        for nd in &g.nodes {
            known[nd.point] = true;
        }
        ops.push(Op::Group(Box::new(g)));
    }
    prune(sc, ops, want_points, want_links)
}

/// Every link with two known points carries the rest (from the two farthest apart).
fn carry_all(sc: &Scene, known: &mut [bool], ops: &mut Vec<Op>) {
    let xy = &sc.xy;
    loop {
        let mut changed = false;
        for l in &sc.links {
            let k: Vec<usize> = l.points.iter().copied().filter(|&p| known[p]).collect();
            if k.len() < 2 || k.len() == l.points.len() {
                continue;
            }
            let mut best = (k[0], k[1], -1.0);
            for (i, &a) in k.iter().enumerate() {
                for &b in &k[i + 1..] {
                    let d = sub(xy[b], xy[a]);
                    let d2 = dot(d, d);
                    if d2 > best.2 {
                        best = (a, b, d2);
                    }
                }
            }
            let (a, b, d2) = best;
            let ab = sub(xy[b], xy[a]);
            let unknown: Vec<usize> = l.points.iter().copied().filter(|&q| !known[q]).collect();
            for q in unknown {
                let aq = sub(xy[q], xy[a]);
                let m = [dot(aq, ab) / d2, cross(ab, aq) / d2];
                ops.push(Op::Carry { q, a, b, m });
                known[q] = true;
            }
            changed = true;
        }
        if !changed {
            return;
        }
    }
}

/// The first unknown point reached by two links from two distinct known points.
fn find_dyad(sc: &Scene, known: &[bool]) -> Option<Dyad> {
    let xy = &sc.xy;
    for p in (0..sc.names.len()).filter(|&p| !known[p]) {
        let mut reach: Vec<(usize, usize)> = Vec::new(); // (link, its known point)
        for &l in &sc.point_links[p] {
            if let Some(&k) = sc.links[l].points.iter().find(|&&q| known[q]) {
                reach.push((l, k));
            }
        }
        for (i, &(l1, k1)) in reach.iter().enumerate() {
            for &(l2, k2) in &reach[i + 1..] {
                let u = sub(xy[k2], xy[k1]);
                if k1 == k2 || dot(u, u) == 0.0 {
                    continue;
                }
                let (e1, e2) = (sub(xy[p], xy[k1]), sub(xy[p], xy[k2]));
                let side = cross(u, e1);
                return Some(Dyad {
                    p,
                    k1,
                    k2,
                    r1: dot(e1, e1).sqrt(),
                    r2: dot(e2, e2).sqrt(),
                    side: if side < 0.0 { -1.0 } else { 1.0 },
                    links: [l1, l2],
                });
            }
        }
    }
    None
}

/// The smallest set of partly known links that is rigid over the known points: by
/// increasing size, connected subsets whose degrees of freedom count to zero and whose
/// loop equations are regular at the drawn pose.
fn find_group(sc: &Scene, known: &[bool]) -> Result<Group, Error> {
    let cand: Vec<usize> = (0..sc.links.len()).filter(|&l| sc.links[l].points.iter().any(|&p| !known[p])).collect();
    let unknown: Vec<&str> = (0..sc.names.len()).filter(|&p| !known[p]).map(|p| sc.names[p].as_str()).collect();
    let dof = |set: &[usize]| -> i64 {
        let mut m = std::collections::HashMap::<usize, i64>::new();
        for &l in set {
            for &p in &sc.links[l].points {
                *m.entry(p).or_default() += 1;
            }
        }
        let c: i64 = m.iter().map(|(&p, &k)| if known[p] { 2 * k } else { 2 * (k - 1) }).sum();
        3 * set.len() as i64 - c
    };
    let mut examined = 0usize;
    for size in (2..=cand.len().min(MAX)).step_by(2) {
        let mut idx: Vec<usize> = (0..size).collect();
        loop {
            examined += 1;
            if examined > GROUP_SEARCH_BUDGET {
                return Err(Error::scene(
                    "plan",
                    format!("no rigid group found for points {unknown:?} within the search budget"),
                ));
            }
            let set: Vec<usize> = idx.iter().map(|&i| cand[i]).collect();
            if dof(&set) == 0 {
                let pts: Vec<&[usize]> = set.iter().map(|&l| sc.links[l].points.as_slice()).collect();
                if let Some(g) = Group::build(&set, &pts, known, &sc.xy) {
                    return Ok(g);
                }
            }
            // next combination of `size` out of cand.len()
            let n = cand.len();
            let mut i = size;
            while i > 0 && idx[i - 1] == n - size + i - 1 {
                i -= 1;
            }
            if i == 0 {
                break;
            }
            idx[i - 1] += 1;
            for k in i..size {
                idx[k] = idx[k - 1] + 1;
            }
        }
    }
    Err(Error::scene(
        "plan",
        format!("points {unknown:?} are not reached by dyads and no rigid group of at most {MAX} links solves them"),
    ))
}

/// Keeps the operations that the wanted points and link angles need, and groups them into
/// steps.
fn prune(sc: &Scene, ops: Vec<Op>, want_points: &[usize], want_links: &[usize]) -> Result<Plan, Error> {
    let np = sc.names.len();
    let mut need = vec![false; np];
    for &p in want_points {
        need[p] = true;
    }
    let link_points: Vec<(usize, usize)> = want_links.iter().map(|&l| sc.angle_points(l)).collect();
    for &(a, b) in &link_points {
        need[a] = true;
        need[b] = true;
    }
    let mut keep = vec![false; ops.len()];
    for (i, op) in ops.iter().enumerate().rev() {
        if op.outputs().iter().any(|&p| need[p]) {
            keep[i] = true;
            for p in op.inputs() {
                need[p] = true;
            }
        }
    }
    if ops.iter().zip(&keep).any(|(o, &k)| k && matches!(o, Op::Input { .. })) {
        need[sc.input.pivot] = true; // the input link's points hang from it
    }
    let mut kept = Vec::new();
    for (op, k) in ops.into_iter().zip(keep) {
        if !k {
            continue;
        }
        kept.push(match op {
            Op::Group(mut g) => {
                let joints = g.joints;
                let mut i = 0;
                g.nodes.retain(|n| {
                    i += 1;
                    i <= joints || need[n.point]
                });
                Op::Group(g)
            }
            other => other,
        });
    }
    // steps: each dyad or group opens one; a carry joins the step that made its later input
    let mut producer: Vec<Option<usize>> = vec![None; np];
    let mut steps: Vec<StepInfo> = Vec::new();
    let mut step_op = Vec::new();
    for (i, op) in kept.iter().enumerate() {
        let s = match op {
            Op::Input { .. } => None,
            Op::Dyad(d) => {
                steps.push(StepInfo { kind: StepKind::Dyad, points: vec![], unknowns: d.links.to_vec() });
                step_op.push(i);
                Some(steps.len() - 1)
            }
            Op::Group(g) => {
                steps.push(StepInfo { kind: StepKind::Group, points: vec![], unknowns: g.links.clone() });
                step_op.push(i);
                Some(steps.len() - 1)
            }
            Op::Carry { a, b, .. } => producer[*a].max(producer[*b]),
        };
        for p in op.outputs() {
            producer[p] = s;
            if let Some(s) = s {
                steps[s].points.push(p);
            }
        }
    }
    let fixed: Vec<(usize, Xy)> = sc.links[sc.ground].points.iter().map(|&p| (p, sc.xy[p])).collect();
    let points: Vec<usize> = (0..np).filter(|&p| need[p]).collect();
    Ok(Plan {
        ops: kept,
        steps,
        step_op,
        points,
        links: want_links.to_vec(),
        link_points,
        fixed,
        npoints: np,
        pivot: sc.xy[sc.input.pivot],
        theta0: sc.theta0,
        scale: sc.scale,
        origin: sc.origin,
    })
}
