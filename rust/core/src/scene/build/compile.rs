//! Compiling the plan: the steps that solve what was asked for, compiled once per scene and set of
//! requested outputs. From ground and the input link it peels RRR dyads (closed form) and
//! rigid bodies (a link with two known points is known); where no dyad remains it finds
//! the smallest group of links that is rigid over the known points and solves it by
//! Newton. Then it keeps only the operations the requested points and link angles need:
//! this is where "model only what a scene requires" lives.

use super::plan::{Plan, StepInfo, StepKind};
use std::collections::HashMap;

use crate::error::Error;
use crate::scene::input::LinearKind;
use crate::scene::model::Scene;
use crate::scene::ops::Dyad;
use crate::scene::ops::Op;
use crate::scene::ops::{Group, MAX};
use crate::scene::ops::{Line, LineLine, Rpr, Rrp};
use crate::scene::vec2::{cdiv, cmul, cross, dot, sub, unit, Xy};

impl Scene {
    /// Compiles the steps that solve `outputs` (point or link names; `None`: every point
    /// and link). Errors name an unknown output.
    pub fn plan(&self, outputs: Option<&[String]>) -> Result<Plan, Error> {
        let (points, links): (Vec<usize>, Vec<usize>) = match outputs {
            None => ((0..self.names.len()).collect(), (0..self.links.len()).collect()),
            Some(names) => self.resolve(names)?,
        };
        if self.limits.is_empty() {
            return compile(self, &points, &links);
        }
        // a limit stops the motion wherever it binds: its points are solved too, and
        // reported only as they would be without it
        let reported = compile(self, &points, &links)?.points;
        let mut with = points.clone();
        for p in self.limits.iter().flat_map(|l| l.coordinate.points()) {
            if !with.contains(&p) {
                with.push(p);
            }
        }
        let mut plan = compile(self, &with, &links)?;
        plan.points = reported;
        plan.limits = self.limits.clone();
        Ok(plan)
    }

    fn resolve(&self, names: &[String]) -> Result<(Vec<usize>, Vec<usize>), Error> {
        let pts: HashMap<&str, usize> = self.names.iter().enumerate().map(|(i, n)| (n.as_str(), i)).collect();
        let lks: HashMap<&str, usize> = self.links.iter().enumerate().map(|(i, l)| (l.name.as_str(), i)).collect();
        let (mut points, mut links) = (Vec::new(), Vec::new());
        for (k, name) in names.iter().enumerate() {
            match (pts.get(name.as_str()), lks.get(name.as_str())) {
                (Some(_), Some(_)) => {
                    return Err(Error::scene(
                        format!("outputs[{k}]"),
                        format!("{name:?} names both a point and a link; rename one"),
                    ))
                }
                (Some(&p), None) => points.push(p),
                (None, Some(&l)) => links.push(l),
                (None, None) => {
                    return Err(Error::scene(format!("outputs[{k}]"), format!("{name:?} is not a point or link")))
                }
            }
        }
        Ok((points, links))
    }
}

/// Most subsets of links examined when searching for the smallest rigid group.
const GROUP_SEARCH_BUDGET: usize = 200_000;

/// A linear input's guide and what slides in it (its link's points, or its slot's point),
/// seen as one body whose shape changes with the input s: a sliding point sits at its
/// drawn place plus s `dir` in the guide's frame.
struct Fused {
    points: Vec<usize>,
    sliding: Vec<bool>,
    dir: Xy,
    /// The guide link (named for steps that go through the fused body).
    guide: usize,
    /// The joint it replaces: its kind and index (not a constraint of its own any more).
    joint: (LinearKind, usize),
}

impl Fused {
    fn of(sc: &Scene) -> Option<Fused> {
        let l = sc.linear?;
        let mut sliding = vec![false; sc.names.len()];
        let mut points = sc.links[l.guide].points.clone();
        let moving: Vec<usize> = match l.kind {
            LinearKind::Slot => vec![sc.slots[l.index].point],
            LinearKind::Prismatic => sc.links[sc.prismatic[l.index].link].points.clone(),
        };
        for p in moving {
            sliding[p] = true;
            points.push(p);
        }
        Some(Fused { points, sliding, dir: l.dir, guide: l.guide, joint: (l.kind, l.index) })
    }

    /// The stroke term of `q - a` in the body frame: (sliding q - sliding a) dir.
    fn stroke(&self, q: usize, a: usize) -> Xy {
        let c = f64::from(u8::from(self.sliding[q])) - f64::from(u8::from(self.sliding[a]));
        [c * self.dir[0], c * self.dir[1]]
    }
}

pub(crate) fn compile(sc: &Scene, want_points: &[usize], want_links: &[usize]) -> Result<Plan, Error> {
    let np = sc.names.len();
    let xy = &sc.xy;
    let mut known = vec![false; np];
    for &p in &sc.links[sc.ground].points {
        known[p] = true;
    }
    let mut ops: Vec<Op> = Vec::new();
    if let Some(input) = sc.input {
        let (piv, tip) = (xy[input.pivot], xy[input.tip]);
        let u0 = sub(tip, piv);
        let u0 = {
            let n = dot(u0, u0).sqrt();
            [u0[0] / n, u0[1] / n]
        };
        for &q in &sc.links[input.link].points {
            if !known[q] {
                let d = sub(xy[q], piv);
                ops.push(Op::Input { q, lam: dot(d, u0), mu: cross(u0, d) });
                known[q] = true;
            }
        }
    }
    let fused = Fused::of(sc);
    loop {
        carry_all(sc, fused.as_ref(), &mut known, &mut ops);
        if known.iter().all(|&k| k) {
            break;
        }
        if let Some(op) = find_dyad(sc, fused.as_ref(), &known) {
            for p in op.outputs() {
                known[p] = true;
            }
            ops.push(op);
            continue;
        }
        if let Some(op) = find_slider(sc, fused.as_ref(), &known) {
            for p in op.outputs() {
                known[p] = true;
            }
            ops.push(op);
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

/// Two known points fixing the rotation of `link`: its own, or those of a prismatic
/// partner (a prismatic pair keeps the two links' relative rotation).
fn rotation_carrier(sc: &Scene, known: &[bool], link: usize) -> Option<(usize, usize)> {
    let two = |l: usize| {
        let mut k = sc.links[l].points.iter().copied().filter(|&p| known[p]);
        Some((k.next()?, k.next()?))
    };
    two(link).or_else(|| {
        sc.prismatic.iter().find_map(|pr| {
            if pr.link == link {
                two(pr.guide)
            } else if pr.guide == link {
                two(pr.link)
            } else {
                None
            }
        })
    })
}

/// The known lines an unknown point `p` must stay on, with the link giving each: its slots
/// on known guides, the paths of a prismatic link over a known guide, and the lines a
/// known slot point draws on a guide whose rotation is known.
fn lines_of(sc: &Scene, fused: Option<&Fused>, known: &[bool], p: usize) -> Vec<(Line, usize)> {
    let xy = &sc.xy;
    let is_input = |k: LinearKind, i: usize| fused.is_some_and(|f| f.joint == (k, i));
    let mut out = Vec::new();
    for (i, sl) in sc.slots.iter().enumerate() {
        if is_input(LinearKind::Slot, i) {
            continue;
        }
        let (a, b) = sl.line;
        if sl.point == p && known[a] && known[b] {
            let len = dot(sub(xy[b], xy[a]), sub(xy[b], xy[a])).sqrt();
            out.push((Line { base: a, a, b, m_off: [0.0, sl.offset / len], m_dir: [1.0 / len, 0.0] }, sl.guide));
        }
        // the slot point is known and p is on a guide whose rotation is known
        if sl.point != p && known[sl.point] && sc.links[sl.guide].points.contains(&p) {
            if let Some((ha, hb)) = rotation_carrier(sc, known, sl.guide) {
                let d0 = unit(sub(xy[b], xy[a]));
                let shift = sub(xy[p], xy[a]);
                let off = [shift[0] + sl.offset * d0[1], shift[1] - sl.offset * d0[0]];
                let h = sub(xy[hb], xy[ha]);
                out.push((Line { base: sl.point, a: ha, b: hb, m_off: cdiv(off, h), m_dir: cdiv(d0, h) }, sl.guide));
            }
        }
    }
    for (i, pr) in sc.prismatic.iter().enumerate() {
        if is_input(LinearKind::Prismatic, i) {
            continue;
        }
        let (a, b) = pr.line;
        if sc.links[pr.link].points.contains(&p) && known[a] && known[b] {
            let h = sub(xy[b], xy[a]);
            let len = dot(h, h).sqrt();
            out.push((Line { base: a, a, b, m_off: cdiv(sub(xy[p], xy[a]), h), m_dir: [1.0 / len, 0.0] }, pr.link));
        }
    }
    out
}

/// The first closed form for a slider: a point on two known lines (PP), a point on a known
/// line reached by a link from a known point (RRP), or a guide with one known point whose
/// line passes through a known slot point (RPR).
fn find_slider(sc: &Scene, fused: Option<&Fused>, known: &[bool]) -> Option<Op> {
    let xy = &sc.xy;
    for p in (0..sc.names.len()).filter(|&p| !known[p]) {
        let lines = lines_of(sc, fused, known, p);
        if let [(l1, k1), rest @ ..] = &lines[..] {
            if let Some((l2, k2)) = rest.iter().find(|(l, _)| {
                let (d1, d2) = (cmul(l1.m_dir, sub(xy[l1.b], xy[l1.a])), cmul(l.m_dir, sub(xy[l.b], xy[l.a])));
                cross(d1, d2).abs() > 1e-9 * dot(d1, d1).sqrt() * dot(d2, d2).sqrt()
            }) {
                return Some(Op::Pp(LineLine { p, lines: [*l1, *l2], links: [*k1, *k2] }));
            }
            for &l in &sc.point_links[p] {
                if l == *k1 {
                    continue;
                }
                if let Some(&k) = sc.links[l].points.iter().find(|&&q| known[q]) {
                    let e = sub(xy[p], xy[k]);
                    let d = cmul(l1.m_dir, sub(xy[l1.b], xy[l1.a]));
                    let side = if dot(e, d) < 0.0 { -1.0 } else { 1.0 };
                    return Some(Op::Rrp(Rrp { p, k, r: dot(e, e).sqrt(), line: *l1, side, links: [*k1, l] }));
                }
            }
        }
    }
    // a guide with one known point, its slot's point known: it turns to pass through it
    for (i, sl) in sc.slots.iter().enumerate() {
        if fused.is_some_and(|f| f.joint == (LinearKind::Slot, i)) || !known[sl.point] {
            continue;
        }
        let pts = &sc.links[sl.guide].points;
        let mut k = pts.iter().copied().filter(|&q| known[q]);
        let (Some(k), None) = (k.next(), k.next()) else { continue };
        if rotation_carrier(sc, known, sl.guide).is_some() {
            continue;
        }
        let Some(&t) = pts.iter().find(|&&q| !known[q]) else { continue };
        let d = unit(sub(xy[sl.line.1], xy[sl.line.0]));
        let side = if dot(d, sub(xy[sl.point], xy[k])) < 0.0 { -1.0 } else { 1.0 };
        let on = *sc.point_links[sl.point].first().expect("a slot point is on a moving link");
        return Some(Op::Rpr(Rpr {
            t,
            k,
            q: sl.point,
            k0: xy[k],
            l0: xy[sl.line.0],
            d,
            t0: xy[t],
            offset: sl.offset,
            side,
            links: [sl.guide, on],
        }));
    }
    None
}

/// Every link with two known points carries the rest (from the two farthest apart); so does
/// a linear input's fused guide (with the input's stroke); a link whose rotation is known
/// from its prismatic partner carries the rest from one known point.
fn carry_all(sc: &Scene, fused: Option<&Fused>, known: &mut [bool], ops: &mut Vec<Op>) {
    let xy = &sc.xy;
    let bodies = sc.links.len() + usize::from(fused.is_some());
    loop {
        let mut changed = false;
        for body in 0..bodies {
            let pts: &[usize] = match sc.links.get(body) {
                Some(l) => &l.points,
                None => &fused.expect("the extra body is the fused input").points,
            };
            let k: Vec<usize> = pts.iter().copied().filter(|&p| known[p]).collect();
            if k.len() == pts.len() || k.is_empty() {
                continue;
            }
            if k.len() < 2 {
                // one known point and a known rotation: translate the drawn shape
                let (Some(_), [base]) = (sc.links.get(body), &k[..]) else { continue };
                let Some((a, b)) = rotation_carrier(sc, known, body) else { continue };
                let h = sub(xy[b], xy[a]);
                let unknown: Vec<usize> = pts.iter().copied().filter(|&q| !known[q]).collect();
                for q in unknown {
                    ops.push(Op::Offset { q, base: *base, a, b, m: cdiv(sub(xy[q], xy[*base]), h) });
                    known[q] = true;
                }
                changed = true;
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
            let unknown: Vec<usize> = pts.iter().copied().filter(|&q| !known[q]).collect();
            for q in unknown {
                let aq = sub(xy[q], xy[a]);
                let stroke = match (body >= sc.links.len(), fused) {
                    (true, Some(f)) => Some((f.stroke(q, a), f.stroke(b, a))),
                    _ => None,
                };
                match stroke {
                    Some((sq, sb)) if sq != [0.0; 2] || sb != [0.0; 2] => {
                        ops.push(Op::StrokeCarry { q, a, b, num: [aq, sq], den: [ab, sb] });
                    }
                    _ => {
                        let m = [dot(aq, ab) / d2, cross(ab, aq) / d2];
                        ops.push(Op::Carry { q, a, b, m });
                    }
                }
                known[q] = true;
            }
            changed = true;
        }
        if !changed {
            return;
        }
    }
}

/// The first unknown point reached by two links (or a link and the fused input body) from
/// two distinct known points.
fn find_dyad(sc: &Scene, fused: Option<&Fused>, known: &[bool]) -> Option<Op> {
    let xy = &sc.xy;
    let fused_id = sc.links.len();
    for p in (0..sc.names.len()).filter(|&p| !known[p]) {
        let mut reach: Vec<(usize, usize)> = Vec::new(); // (link, its known point)
        for &l in &sc.point_links[p] {
            if let Some(&k) = sc.links[l].points.iter().find(|&&q| known[q]) {
                reach.push((l, k));
            }
        }
        if let Some(f) = fused.filter(|f| f.points.contains(&p)) {
            if let Some(&k) = f.points.iter().find(|&&q| known[q] && f.stroke(p, q) != [0.0; 2]) {
                reach.push((fused_id, k));
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
                let d = Dyad {
                    p,
                    k1,
                    k2,
                    r1: dot(e1, e1).sqrt(),
                    r2: dot(e2, e2).sqrt(),
                    side: if side < 0.0 { -1.0 } else { 1.0 },
                    links: [l1, l2],
                };
                let arm = |l: usize, k: usize, e: Xy| match fused {
                    Some(f) if l == fused_id => [e, f.stroke(p, k)],
                    _ => [e, [0.0; 2]],
                };
                if let Some(f) = fused.filter(|_| l1 == fused_id || l2 == fused_id) {
                    let named = |l: usize| if l == fused_id { f.guide } else { l };
                    let links = [named(l1), named(l2)];
                    return Some(Op::StrokeDyad(Dyad { links, ..d }, [arm(l1, k1, e1), arm(l2, k2, e2)]));
                }
                return Some(Op::Dyad(d));
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
    let mut examined = 0usize;
    // revolute groups have an even number of links; with sliders any number can be rigid
    let sliders = !sc.slots.is_empty() || !sc.prismatic.is_empty();
    let (first, by) = if sliders { (1, 1) } else { (2, 2) };
    for size in (first..=cand.len().min(MAX)).step_by(by) {
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
            if Group::freedom(sc, &set, known) == 0 {
                if let Some(g) = Group::build(sc, &set, known) {
                    return Ok(g);
                }
            }
            // a linear input's joint among them, held at the input (a cylinder pushing a
            // point of a group's link)
            if sc.linear.is_some() && Group::freedom_held(sc, &set, known) == 0 {
                if let Some(g) = Group::build_held(sc, &set, known) {
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
        if let Some(input) = sc.input {
            need[input.pivot] = true; // the input link's points hang from it
        }
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
    // a link with two points known before a step (the ground, the input link, a slot's
    // guide) has a known angle: not one of the step's unknowns
    let mut known = vec![false; np];
    for &p in &sc.links[sc.ground].points {
        known[p] = true;
    }
    for (i, op) in kept.iter().enumerate() {
        let opens = match op {
            Op::Input { .. } => None,
            Op::Carry { .. } | Op::StrokeCarry { .. } | Op::Offset { .. } => None,
            Op::Dyad(d) | Op::StrokeDyad(d, _) => Some((StepKind::Dyad, d.links.to_vec())),
            Op::Group(g) => Some((StepKind::Group, g.links.clone())),
            Op::Rrp(r) => Some((StepKind::Rrp, r.links.to_vec())),
            Op::Pp(l) => Some((StepKind::Pp, l.links.to_vec())),
            Op::Rpr(r) => Some((StepKind::Rpr, r.links.to_vec())),
        };
        let s = match opens {
            Some((kind, mut unknowns)) => {
                unknowns
                    .retain(|&l| l >= sc.links.len() || sc.links[l].points.iter().filter(|&&p| known[p]).count() < 2);
                steps.push(StepInfo { kind, points: vec![], unknowns });
                step_op.push(i);
                Some(steps.len() - 1)
            }
            // a carry joins the step that made its latest input
            None => op.inputs().iter().map(|&p| producer[p]).max().flatten(),
        };
        for p in op.outputs() {
            known[p] = true;
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
        pivot: sc.input.map_or([0.0; 2], |i| sc.xy[i.pivot]),
        theta0: sc.theta0,
        scale: sc.scale,
        origin: sc.origin,
        linear: sc.linear.is_some(),
        limits: Vec::new(),
    })
}
