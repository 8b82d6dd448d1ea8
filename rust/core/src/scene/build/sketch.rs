//! Scenes from a sketch: `lengths` and roughly drawn points become the exact assembly
//! nearest the sketch. [`assemble_sketch`] builds each moving link's shape from its listed
//! distances (sides as sketched), places slots and prismatic pairs by their listed
//! distances from their lines, holds ground and the sketched input, and follows the sketch,
//! an exact assembly of its own lengths, while those lengths move to the given ones (Newton
//! on the moving points' coordinates). Passing a dead point on the way would change the
//! assembly mode, so it is refused instead, naming the link that cannot close.
//!
//! The rule for sliders, which distances alone cannot say: a slot's pin lies on its line
//! unless `lengths` gives its distance from it (`[pin, slot, e]`, on the side it is
//! sketched); a prismatic pair holds two points of its sliding link at given distances from
//! its guide's line (`[point, pair, d]`, exactly two such entries), or, with none given,
//! the sliding link's first two listed points on the line (a rod in its barrel).

use std::collections::HashMap;

use nalgebra::{DMatrix, DVector};

use super::validate::structure;
use crate::error::Error;
use crate::interrupt::Interrupt;
use crate::scene::input::LinearKind;
use crate::scene::model::{Scene, SceneSpec};
use crate::scene::vec2::{cross, dot, perp, sub, Xy};

/// A length as given: two names and a distance in the scene's unit. The names are two
/// points of one link (a distance > 0), or a point and a slot or prismatic pair (the
/// point's distance from that joint's line, >= 0).
pub type LengthSpec = (String, String, f64);

/// A sketch assembled: the exact pose and how far each point moved to reach it.
#[derive(Clone, Debug, PartialEq)]
pub struct Sketched {
    /// Exact coordinates, in the order of the spec's points (scene units).
    pub points: Vec<Xy>,
    /// Distance from each sketched point to its exact place (scene units; 0 for ground).
    pub moved: Vec<f64>,
}

/// Most moving points a sketch may have: it is assembled with dense matrices (cubic time;
/// about a tenth of a second per factorisation at this size).
pub const MAX_SKETCH_POINTS: usize = 500;

/// A triangle whose squared height is within this fraction of its longest side squared
/// closes flat (its point lies on the line): lengths cannot fix a height better than the
/// square root of their rounding, so a height below 1e-6 of the link is taken as none.
const FLAT: f64 = 1e-12;
/// Lengths that agree to this (relative) are the same length.
const SAME: f64 = 1e-9;
/// Newton corrections below this converge a continuation step (frame units: coordinates
/// divided by the power of two at or below the largest link); the last solve goes on to
/// rounding.
const STEP_TOL: f64 = 1e-10;
/// The final pose must meet every condition to this (frame units).
const CLOSE_TOL: f64 = 1e-12;
/// The first correction of a continuation step may be at most this (frame units), and
/// each next one at most half the one before: a step that converges otherwise may have
/// jumped to another assembly, so it is halved.
const FIRST_MAX: f64 = 0.25;
/// Smallest continuation step (a fraction of the way from the sketched lengths).
const H_MIN: f64 = 1.0 / (1u64 << 20) as f64;
/// Most continuation steps tried, and Newton iterations per step and for the last solve.
const MAX_STEPS: usize = 200;
const STEP_ITERS: usize = 8;
const FINAL_ITERS: usize = 40;
/// Below this ratio of the smallest to the largest LU pivot the Jacobian is taken as
/// singular (then its singular values decide and say where).
const PIVOT_RATIO: f64 = 1e-13;
/// The sketch is at a dead point when the smallest singular value of its Jacobian is below
/// this fraction of the largest.
const DEAD: f64 = 1e-10;

/// Assembles the sketch `spec` with `lengths` (see the module docs for the rule). Errors
/// name the entry: `lengths[k]` for an entry that is malformed or contradicts another,
/// `links.X` for a link whose lengths leave it non-rigid or cannot close, `slots.X` or
/// `prismatic.X` for a joint the lengths do not place; the spec itself is checked as
/// [`Scene::new`] checks it, except the rank at the (sketched) pose. `interrupt` is asked
/// once per continuation step (Ctrl-C from Python).
pub fn assemble_sketch(spec: SceneSpec, lengths: &[LengthSpec], interrupt: &dyn Interrupt) -> Result<Sketched, Error> {
    let sc = structure(spec)?;
    let fixed: Vec<bool> = sc.point_links.iter().map(|l| l.contains(&sc.ground)).collect();
    let moving = fixed.iter().filter(|f| !**f).count();
    if moving > MAX_SKETCH_POINTS {
        return Err(Error::scene(
            "lengths",
            format!("the sketch has {moving} moving points; a sketch may have at most {MAX_SKETCH_POINTS}"),
        ));
    }
    let given = Given::parse(&sc, &fixed, lengths)?;
    let rows = rows(&sc, &fixed, &given)?;
    let sys = System::new(&sc, &fixed, rows);
    if sys.rows_len != sys.n {
        // Gruebler's count is 1 (checked), so this is a link welded to ground or the like
        return Err(Error::scene(
            "mobility",
            format!(
                "the sketch has {} unknown coordinates but {} conditions; a one-degree-of-freedom scene with \
                 its input held has as many",
                sys.n, sys.rows_len
            ),
        ));
    }
    let x = sys.solve(&sc, interrupt)?;
    let mut points = sc.drawn.clone();
    let mut moved = vec![0.0; points.len()];
    for (p, c) in sys.col.iter().enumerate() {
        if let Some(c) = *c {
            let d = [x[c] - sc.xy[p][0], x[c + 1] - sc.xy[p][1]];
            points[p] = [sc.drawn[p][0] + sc.scale * d[0], sc.drawn[p][1] + sc.scale * d[1]];
            moved[p] = sc.scale * d[0].hypot(d[1]);
        }
    }
    Ok(Sketched { points, moved })
}

/// What a row of conditions belongs to, for error messages.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
enum Owner {
    Link(usize),
    Slot(usize),
    Prismatic(usize),
    Input,
}

impl Owner {
    fn entry(self, sc: &Scene) -> String {
        match self {
            Owner::Link(l) => format!("links.{}", sc.links[l].name),
            Owner::Slot(s) => format!("slots.{}", sc.slots[s].name),
            Owner::Prismatic(p) => format!("prismatic.{}", sc.prismatic[p].name),
            Owner::Input => "input".into(),
        }
    }
}

/// The parsed `lengths` (frame units).
struct Given {
    /// Distances between two points (lower index first): (distance, entry).
    pairs: HashMap<(usize, usize), (f64, usize)>,
    /// Per slot: its pin's distance from the line, if given.
    slot_offset: Vec<Option<(f64, usize)>>,
    /// Per prismatic pair: its sliding link's points held at distances from the line.
    held: Vec<Vec<(usize, f64, usize)>>,
}

/// A name in a `lengths` entry.
#[derive(Clone, Copy)]
enum Name {
    Point(usize),
    Slot(usize),
    Prismatic(usize),
}

impl Given {
    fn parse(sc: &Scene, fixed: &[bool], lengths: &[LengthSpec]) -> Result<Given, Error> {
        let points: HashMap<&str, usize> = sc.names.iter().enumerate().map(|(i, n)| (n.as_str(), i)).collect();
        let slots: HashMap<&str, usize> = sc.slots.iter().enumerate().map(|(i, s)| (s.name.as_str(), i)).collect();
        let prism: HashMap<&str, usize> = sc.prismatic.iter().enumerate().map(|(i, s)| (s.name.as_str(), i)).collect();
        let mut g = Given {
            pairs: HashMap::new(),
            slot_offset: vec![None; sc.slots.len()],
            held: vec![Vec::new(); sc.prismatic.len()],
        };
        // distances from joints' lines by (joint, point), to find duplicates
        let mut lines: HashMap<(bool, usize, usize), (f64, usize)> = HashMap::new();
        for (k, (a, b, v)) in lengths.iter().enumerate() {
            let entry = format!("lengths[{k}]");
            let name = |n: &str| -> Result<Name, Error> {
                let joint = slots.get(n).map(|&s| Name::Slot(s)).or_else(|| prism.get(n).map(|&p| Name::Prismatic(p)));
                match (points.get(n), joint) {
                    (Some(_), Some(_)) => Err(Error::scene(
                        &entry,
                        format!("{n:?} names both a point and a slot or prismatic pair; rename one"),
                    )),
                    (Some(&p), None) => Ok(Name::Point(p)),
                    (None, Some(j)) => Ok(j),
                    (None, None) => Err(Error::scene(&entry, format!("unknown point {n:?}"))),
                }
            };
            if a == b {
                return Err(Error::scene(entry, format!("names {a:?} twice: a length is between two names")));
            }
            let (na, nb) = (name(a)?, name(b)?);
            if !v.is_finite() {
                return Err(Error::scene(entry, format!("the length must be finite, got {v}")));
            }
            match (na, nb) {
                (Name::Point(p), Name::Point(q)) => g.pair(sc, fixed, (p, q), *v, k)?,
                (Name::Point(p), j) => g.line(sc, &mut lines, p, (j, b), *v, k)?,
                (j, Name::Point(p)) => g.line(sc, &mut lines, p, (j, a), *v, k)?,
                _ => {
                    return Err(Error::scene(
                        entry,
                        format!(
                            "names two joints ({a:?}, {b:?}); a length is between two points, or a point and a \
                             joint's line"
                        ),
                    ))
                }
            }
        }
        for (i, held) in g.held.iter_mut().enumerate() {
            let pr = &sc.prismatic[i];
            match held.len() {
                0 => {
                    let pts = &sc.links[pr.link].points;
                    held.extend([(pts[0], 0.0, usize::MAX), (pts[1], 0.0, usize::MAX)]);
                }
                2 => {}
                n => {
                    let named: Vec<&str> = held.iter().map(|h| sc.names[h.0].as_str()).collect();
                    return Err(Error::scene(
                        format!("prismatic.{}", pr.name),
                        format!(
                            "a sketch holds two points of its sliding link {:?} at distances from its line; lengths \
                             gives {n} ({named:?}): give two (or none: its first two points on the line)",
                            sc.links[pr.link].name
                        ),
                    ));
                }
            }
        }
        Ok(g)
    }

    /// Entry `k`: the distance `v` between points `p` and `q`.
    fn pair(&mut self, sc: &Scene, fixed: &[bool], (p, q): (usize, usize), v: f64, k: usize) -> Result<(), Error> {
        let (a, b) = (&sc.names[p], &sc.names[q]);
        let entry = || format!("lengths[{k}]");
        if !(v > 0.0) {
            return Err(Error::scene(entry(), format!("the distance between {a:?} and {b:?} must be > 0, got {v}")));
        }
        if !sc.point_links[p].iter().any(|l| sc.point_links[q].contains(l)) {
            return Err(Error::scene(entry(), format!("{a:?} and {b:?} are on no common link")));
        }
        if fixed[p] && fixed[q] {
            let drawn = dist(sub(sc.drawn[q], sc.drawn[p]));
            if !((drawn - v).abs() <= SAME * drawn.max(v)) {
                return Err(Error::scene(
                    entry(),
                    format!(
                        "{a:?} and {b:?} are ground points, which stay as drawn ({drawn} apart), but the length is {v}"
                    ),
                ));
            }
        }
        let d = v / sc.scale;
        match self.pairs.get(&(p.min(q), p.max(q))) {
            Some(&(d0, k0)) if !same(d0, d) => {
                Err(Error::scene(entry(), format!("gives |{a} {b}| = {v}, but lengths[{k0}] gave {}", d0 * sc.scale)))
            }
            Some(_) => Ok(()),
            None => {
                self.pairs.insert((p.min(q), p.max(q)), (d, k));
                Ok(())
            }
        }
    }

    /// Entry `k`: the distance `v` of point `p` from the line of joint `j` (named `jname`).
    fn line(
        &mut self,
        sc: &Scene,
        seen: &mut HashMap<(bool, usize, usize), (f64, usize)>,
        p: usize,
        (j, jname): (Name, &str),
        v: f64,
        k: usize,
    ) -> Result<(), Error> {
        let pname = &sc.names[p];
        let entry = || format!("lengths[{k}]");
        if !(v >= 0.0) {
            return Err(Error::scene(
                entry(),
                format!("the distance of {pname:?} from the line of {jname:?} must be >= 0, got {v}"),
            ));
        }
        let key = match j {
            Name::Slot(s) if sc.slots[s].point != p => {
                let pin = &sc.names[sc.slots[s].point];
                return Err(Error::scene(
                    entry(),
                    format!("{pname:?} is not the pin of slot {jname:?} (its pin is {pin:?})"),
                ));
            }
            Name::Slot(s) => (true, s, p),
            Name::Prismatic(i) => {
                let link = &sc.links[sc.prismatic[i].link];
                if !link.points.contains(&p) {
                    return Err(Error::scene(
                        entry(),
                        format!(
                            "{pname:?} is not a point of {:?}, the link that prismatic pair {jname:?} slides",
                            link.name
                        ),
                    ));
                }
                (false, i, p)
            }
            Name::Point(_) => unreachable!("a joint's name"),
        };
        let d = v / sc.scale;
        match seen.get(&key) {
            Some(&(d0, k0)) if !same(d0, d) => Err(Error::scene(
                entry(),
                format!(
                    "gives the distance of {pname:?} from the line of {jname:?} as {v}, but lengths[{k0}] gave {}",
                    d0 * sc.scale
                ),
            )),
            Some(_) => Ok(()),
            None => {
                seen.insert(key, (d, k));
                match key {
                    (true, s, _) => self.slot_offset[s] = Some((d, k)),
                    (false, i, _) => self.held[i].push((p, d, k)),
                }
                Ok(())
            }
        }
    }
}

fn same(a: f64, b: f64) -> bool {
    (a - b).abs() <= SAME * a.abs().max(b.abs())
}

fn dist(v: Xy) -> f64 {
    v[0].hypot(v[1])
}

/// One condition (two for `Affine`), with its target moving from `from` (as sketched) to
/// `to` (as given) along the continuation.
#[derive(Clone, Debug)]
struct Row {
    kind: Kind,
    owner: Owner,
    from: Xy,
    to: Xy,
}

#[derive(Clone, Copy, Debug)]
enum Kind {
    /// |b - a| = target.
    Dist { a: usize, b: usize },
    /// c - a = alpha (b - a) + beta perp(b - a), target (alpha, beta): a rigid link's
    /// further point, linear in the coordinates (no flat triangle is ill-conditioned).
    Affine { a: usize, b: usize, c: usize },
    /// cross(unit(l1 - l0), p - l0) = target: a signed distance from a line.
    Off { l0: usize, l1: usize, p: usize },
    /// dot(unit(l1 - l0), p - l0) = target: a place along a line (a linear input).
    Along { l0: usize, l1: usize, p: usize },
    /// cross(u, tip - pivot) = 0: the input's direction.
    Angle { pivot: usize, tip: usize, u: Xy },
}

impl Kind {
    /// The points it reads.
    fn points(self) -> [usize; 3] {
        match self {
            Kind::Dist { a, b } => [a, b, b],
            Kind::Affine { a, b, c } => [a, b, c],
            Kind::Off { l0, l1, p } | Kind::Along { l0, l1, p } => [l0, l1, p],
            Kind::Angle { pivot, tip, .. } => [pivot, tip, tip],
        }
    }

    fn len(self) -> usize {
        if matches!(self, Kind::Affine { .. }) {
            2
        } else {
            1
        }
    }
}

/// The conditions of the sketch, in frame units, with their sketched and given targets.
fn rows(sc: &Scene, fixed: &[bool], given: &Given) -> Result<Vec<Row>, Error> {
    let xy = &sc.xy;
    let mut rows = Vec::new();
    // links: each moving link's shape from its lengths
    let mut local = vec![usize::MAX; sc.names.len()];
    let mut adj: Vec<Vec<(usize, usize, f64)>> = vec![Vec::new(); sc.links.len()];
    for (&(p, q), &(d, _)) in &given.pairs {
        for &l in &sc.point_links[p] {
            if l != sc.ground && sc.point_links[q].contains(&l) {
                adj[l].push((p, q, d));
            }
        }
    }
    for (l, link) in sc.links.iter().enumerate() {
        if l == sc.ground {
            continue;
        }
        let entry = format!("links.{}", link.name);
        let on_ground: Vec<&str> = link.points.iter().filter(|&&p| fixed[p]).map(|&p| sc.names[p].as_str()).collect();
        if on_ground.len() >= 2 {
            return Err(Error::scene(
                entry,
                format!(
                    "carries the ground points {on_ground:?}, so it cannot move: put its points on the ground link"
                ),
            ));
        }
        for (i, &p) in link.points.iter().enumerate() {
            local[p] = i;
        }
        adj[l].sort_by(|x, y| (local[x.0], local[x.1]).cmp(&(local[y.0], local[y.1])));
        let shape = shape(sc, link, &adj[l], &local).map_err(|m| Error::scene(&entry, m));
        for &p in &link.points {
            local[p] = usize::MAX;
        }
        let (a, b, d, others) = shape?;
        let owner = Owner::Link(l);
        rows.push(Row { kind: Kind::Dist { a, b }, owner, from: [dist(sub(xy[b], xy[a])), 0.0], to: [d, 0.0] });
        for (c, alpha, beta) in others {
            let e = sub(xy[b], xy[a]);
            let w = sub(xy[c], xy[a]);
            let n2 = dot(e, e);
            rows.push(Row {
                kind: Kind::Affine { a, b, c },
                owner,
                from: [dot(w, e) / n2, cross(e, w) / n2],
                to: [alpha, beta],
            });
        }
    }
    // slots and prismatic pairs: distances from their lines, sides as sketched
    let side = |entry: &str, l0: usize, l1: usize, p: usize, d: f64, k: usize| -> Result<Row, Error> {
        let u = unit(sub(xy[l1], xy[l0]));
        let now = cross(u, sub(xy[p], xy[l0]));
        if d > 0.0 && now == 0.0 {
            let which = if k == usize::MAX { String::new() } else { format!(" lengths[{k}] puts it") };
            return Err(Error::scene(
                entry,
                format!(
                    "{:?} is sketched on the line, so the sketch does not say on which side{which} (at {}); \
                     draw it on its side",
                    sc.names[p],
                    d * sc.scale
                ),
            ));
        }
        Ok(Row { kind: Kind::Off { l0, l1, p }, owner: Owner::Input, from: [now, 0.0], to: [d.copysign(now), 0.0] })
    };
    for (s, sl) in sc.slots.iter().enumerate() {
        let (d, k) = given.slot_offset[s].unwrap_or((0.0, usize::MAX));
        let row = side(&format!("slots.{}", sl.name), sl.line.0, sl.line.1, sl.point, d, k)?;
        rows.push(Row { owner: Owner::Slot(s), ..row });
    }
    for (i, pr) in sc.prismatic.iter().enumerate() {
        for &(p, d, k) in &given.held[i] {
            let row = side(&format!("prismatic.{}", pr.name), pr.line.0, pr.line.1, p, d, k)?;
            rows.push(Row { owner: Owner::Prismatic(i), ..row });
        }
    }
    // the input, held as sketched
    let input = match (sc.input, sc.linear) {
        (Some(i), _) => Kind::Angle { pivot: i.pivot, tip: i.tip, u: unit(sub(xy[i.tip], xy[i.pivot])) },
        (None, Some(lin)) => {
            let (line, p) = match lin.kind {
                LinearKind::Slot => (sc.slots[lin.index].line, sc.slots[lin.index].point),
                LinearKind::Prismatic => {
                    let pr = &sc.prismatic[lin.index];
                    (pr.line, sc.links[pr.link].points[0])
                }
            };
            Kind::Along { l0: line.0, l1: line.1, p }
        }
        (None, None) => unreachable!("a validated scene has an input"),
    };
    let now = match input {
        Kind::Along { l0, l1, p } => dot(unit(sub(xy[l1], xy[l0])), sub(xy[p], xy[l0])),
        _ => 0.0,
    };
    rows.push(Row { kind: input, owner: Owner::Input, from: [now, 0.0], to: [now, 0.0] });
    Ok(rows)
}

fn unit(v: Xy) -> Xy {
    let n = dist(v);
    [v[0] / n, v[1] / n]
}

/// A link's shape from its listed distances: a base pair (a, b) at distance d and each
/// further point c as (c, alpha, beta) with c - a = alpha (b - a) + beta perp(b - a).
/// Each point is placed by its distances to two points already placed (the farthest
/// apart such pair), on the side it is sketched on. The error is the message.
type Shape = (usize, usize, f64, Vec<(usize, f64, f64)>);

fn shape(
    sc: &Scene,
    link: &crate::scene::model::Link,
    adj: &[(usize, usize, f64)],
    local: &[usize],
) -> Result<Shape, String> {
    let pts = &link.points;
    let k = pts.len();
    let name = |p: usize| sc.names[p].as_str();
    let need = "a sketch fixes a link by its lengths: a binary link its length, a ternary its three sides, and \
                each further point its distances to two points already fixed";
    // the longest listed distance is the base
    let Some(&(a, b, d)) = adj.iter().fold(None, |best: Option<&(usize, usize, f64)>, e| match best {
        Some(x) if x.2 >= e.2 => Some(x),
        _ => Some(e),
    }) else {
        return Err(format!("has no lengths: {need}"));
    };
    let mut at: Vec<Option<Xy>> = vec![None; k];
    at[local[a]] = Some([0.0, 0.0]);
    at[local[b]] = Some([d, 0.0]);
    // each point's listed distances to the link's other points
    let mut nbr: Vec<Vec<(usize, f64)>> = vec![Vec::new(); k];
    for &(p, q, r) in adj {
        nbr[local[p]].push((q, r));
        nbr[local[q]].push((p, r));
    }
    let mut others = Vec::with_capacity(k.saturating_sub(2));
    for _ in 2..k {
        // the unplaced point with two placed neighbours farthest apart
        let mut best: Option<(f64, usize, usize, usize, f64, f64)> = None;
        for &c in pts.iter().filter(|&&c| at[local[c]].is_none()) {
            let nb: Vec<(usize, f64)> =
                nbr[local[c]].iter().copied().filter(|&(u, _)| at[local[u]].is_some()).collect();
            for (i, &(u, du)) in nb.iter().enumerate() {
                for &(v, dv) in &nb[i + 1..] {
                    let span = dist(sub(at[local[v]].expect("placed"), at[local[u]].expect("placed")));
                    if best.is_none_or(|b| span > b.0) && span > 0.0 {
                        best = Some((span, c, u, v, du, dv));
                    }
                }
            }
        }
        let Some((n, c, u, v, du, dv)) = best else {
            let left: Vec<&str> = pts.iter().filter(|&&p| at[local[p]].is_none()).map(|&p| name(p)).collect();
            return Err(format!("its lengths leave it non-rigid: {left:?} not fixed ({need})"));
        };
        let (pu, pv) = (at[local[u]].expect("placed"), at[local[v]].expect("placed"));
        let e = [(pv[0] - pu[0]) / n, (pv[1] - pu[1]) / n];
        let x = (du * du - dv * dv + n * n) / (2.0 * n);
        let h2 = du * du - x * x;
        let m = du.max(dv).max(n);
        if h2 < -FLAT * m * m {
            return Err(format!(
                "its lengths cannot close: |{0} {2}| = {3}, |{1} {2}| = {4} and |{0} {1}| = {5} make no triangle",
                name(u),
                name(v),
                name(c),
                du * sc.scale,
                dv * sc.scale,
                n * sc.scale
            ));
        }
        let h = if h2 <= FLAT * m * m { 0.0 } else { h2.sqrt() };
        let s = cross(sub(sc.xy[v], sc.xy[u]), sub(sc.xy[c], sc.xy[u]));
        if h > 0.0 && s == 0.0 {
            return Err(format!(
                "{:?} is sketched on the line through {:?} and {:?}, so the sketch does not say on which side its \
                 lengths put it; draw it on its side",
                name(c),
                name(u),
                name(v)
            ));
        }
        let h = h.copysign(s);
        let pc = [pu[0] + x * e[0] - h * e[1], pu[1] + x * e[1] + h * e[0]];
        at[local[c]] = Some(pc);
        others.push((c, pc[0] / d, pc[1] / d));
    }
    // every listed distance must agree with the shape
    for &(p, q, r) in adj {
        let got = dist(sub(at[local[q]].expect("placed"), at[local[p]].expect("placed")));
        if !((got - r).abs() <= SAME * d) {
            return Err(format!(
                "its lengths disagree: |{} {}| is listed as {} but its other lengths make it {}",
                name(p),
                name(q),
                r * sc.scale,
                got * sc.scale
            ));
        }
    }
    Ok((a, b, d, others))
}

/// The square system: unknowns are the frame coordinates of the moving points.
struct System {
    rows: Vec<Row>,
    /// Column of each point's x (its y is the next), None for a fixed point.
    col: Vec<Option<usize>>,
    /// First residual of each row.
    start: Vec<usize>,
    n: usize,
    rows_len: usize,
    fixed_xy: Vec<Xy>,
}

/// An LU factorisation with its determinant's sign and pivot ratio.
struct Lu {
    lu: nalgebra::LU<f64, nalgebra::Dyn, nalgebra::Dyn>,
    sign: f64,
    ratio: f64,
}

impl Lu {
    fn new(j: DMatrix<f64>) -> Lu {
        let lu = j.lu();
        let diag = lu.u().diagonal();
        let (mut lo, mut hi) = (f64::INFINITY, 0.0_f64);
        let mut sign = lu.p().determinant::<f64>();
        for &u in diag.iter() {
            lo = lo.min(u.abs());
            hi = hi.max(u.abs());
            if u < 0.0 {
                sign = -sign;
            }
        }
        let ratio = if hi > 0.0 && lo.is_finite() { lo / hi } else { 0.0 };
        Lu { lu, sign, ratio: if ratio.is_nan() { 0.0 } else { ratio } }
    }

    fn regular(&self) -> bool {
        self.ratio > PIVOT_RATIO
    }

    /// -J^-1 b.
    fn step(&self, b: &DVector<f64>) -> Option<DVector<f64>> {
        self.lu.solve(b).map(|x| -x).filter(|x| x.iter().all(|v| v.is_finite()))
    }
}

fn norm(v: &DVector<f64>) -> f64 {
    v.iter().fold(0.0_f64, |m, x| if x.abs() > m || x.is_nan() { x.abs() } else { m })
}

impl System {
    fn new(sc: &Scene, fixed: &[bool], rows: Vec<Row>) -> System {
        let mut col = vec![None; fixed.len()];
        let mut n = 0;
        for (p, &f) in fixed.iter().enumerate() {
            if !f {
                col[p] = Some(n);
                n += 2;
            }
        }
        let mut start = Vec::with_capacity(rows.len());
        let mut m = 0;
        for r in &rows {
            start.push(m);
            m += r.kind.len();
        }
        System { rows, col, start, n, rows_len: m, fixed_xy: sc.xy.clone() }
    }

    fn pos(&self, x: &DVector<f64>, p: usize) -> Xy {
        match self.col[p] {
            Some(c) => [x[c], x[c + 1]],
            None => self.fixed_xy[p],
        }
    }

    /// Residuals at (x, lam) into `f`; with `jac`, the Jacobian too.
    fn eval(&self, x: &DVector<f64>, lam: f64, f: &mut DVector<f64>, mut jac: Option<&mut DMatrix<f64>>) {
        if let Some(j) = jac.as_deref_mut() {
            j.fill(0.0);
        }
        let col = &self.col;
        let put = |j: &mut Option<&mut DMatrix<f64>>, r: usize, p: usize, g: Xy| {
            if let (Some(j), Some(c)) = (j.as_deref_mut(), col[p]) {
                j[(r, c)] += g[0];
                j[(r, c + 1)] += g[1];
            }
        };
        for (row, &r) in self.rows.iter().zip(&self.start) {
            let t = [row.from[0] + lam * (row.to[0] - row.from[0]), row.from[1] + lam * (row.to[1] - row.from[1])];
            match row.kind {
                Kind::Dist { a, b } => {
                    let e = sub(self.pos(x, b), self.pos(x, a));
                    let n = dist(e);
                    f[r] = n - t[0];
                    let g = [e[0] / n, e[1] / n];
                    put(&mut jac, r, b, g);
                    put(&mut jac, r, a, [-g[0], -g[1]]);
                }
                Kind::Affine { a, b, c } => {
                    let (pa, pb, pc) = (self.pos(x, a), self.pos(x, b), self.pos(x, c));
                    let e = sub(pb, pa);
                    let q = perp(e);
                    let (al, be) = (t[0], t[1]);
                    f[r] = pc[0] - pa[0] - al * e[0] - be * q[0];
                    f[r + 1] = pc[1] - pa[1] - al * e[1] - be * q[1];
                    put(&mut jac, r, c, [1.0, 0.0]);
                    put(&mut jac, r + 1, c, [0.0, 1.0]);
                    put(&mut jac, r, a, [al - 1.0, -be]);
                    put(&mut jac, r + 1, a, [be, al - 1.0]);
                    put(&mut jac, r, b, [-al, be]);
                    put(&mut jac, r + 1, b, [-be, -al]);
                }
                Kind::Off { l0, l1, p } | Kind::Along { l0, l1, p } => {
                    let d = sub(self.pos(x, l1), self.pos(x, l0));
                    let w = sub(self.pos(x, p), self.pos(x, l0));
                    let n = dist(d);
                    let (gp, gd) = if let Kind::Off { .. } = row.kind {
                        let c = cross(d, w);
                        f[r] = c / n - t[0];
                        let gp = [-d[1] / n, d[0] / n];
                        let pw = perp(w);
                        (gp, [-pw[0] / n - c * d[0] / (n * n * n), -pw[1] / n - c * d[1] / (n * n * n)])
                    } else {
                        let s = dot(d, w);
                        f[r] = s / n - t[0];
                        ([d[0] / n, d[1] / n], [w[0] / n - s * d[0] / (n * n * n), w[1] / n - s * d[1] / (n * n * n)])
                    };
                    put(&mut jac, r, p, gp);
                    put(&mut jac, r, l1, gd);
                    put(&mut jac, r, l0, [-gp[0] - gd[0], -gp[1] - gd[1]]);
                }
                Kind::Angle { pivot, tip, u } => {
                    f[r] = cross(u, sub(self.pos(x, tip), self.pos(x, pivot)));
                    let g = perp(u);
                    put(&mut jac, r, tip, g);
                    put(&mut jac, r, pivot, [-g[0], -g[1]]);
                }
            }
        }
    }

    /// d residuals / d lam at x.
    fn dlam(&self, x: &DVector<f64>) -> DVector<f64> {
        let mut v = DVector::zeros(self.rows_len);
        for (row, &r) in self.rows.iter().zip(&self.start) {
            let dt = [row.to[0] - row.from[0], row.to[1] - row.from[1]];
            match row.kind {
                Kind::Affine { a, b, .. } => {
                    let e = sub(self.pos(x, b), self.pos(x, a));
                    let q = perp(e);
                    v[r] = -(dt[0] * e[0] + dt[1] * q[0]);
                    v[r + 1] = -(dt[0] * e[1] + dt[1] * q[1]);
                }
                _ => v[r] = -dt[0],
            }
        }
        v
    }

    fn jacobian(&self, x: &DVector<f64>, lam: f64) -> (DVector<f64>, DMatrix<f64>) {
        let mut f = DVector::zeros(self.rows_len);
        let mut j = DMatrix::zeros(self.rows_len, self.n);
        self.eval(x, lam, &mut f, Some(&mut j));
        (f, j)
    }

    /// Newton at `lam` from `x`: the converged point and its factorisation, or None when it
    /// does not converge the way a nearby solution would (see [`FIRST_MAX`]).
    fn correct(&self, mut x: DVector<f64>, lam: f64) -> Option<(DVector<f64>, Lu)> {
        let mut last = f64::INFINITY;
        for it in 0..STEP_ITERS {
            let (f, j) = self.jacobian(&x, lam);
            let lu = Lu::new(j);
            if !lu.regular() {
                return None;
            }
            let dx = lu.step(&f)?;
            let size = norm(&dx);
            if (it == 0 && !(size <= FIRST_MAX)) || (it > 0 && !(size <= 0.5 * last)) {
                return None;
            }
            x += dx;
            if size <= STEP_TOL {
                let (_, j) = self.jacobian(&x, lam);
                return Some((x, Lu::new(j)));
            }
            last = size;
        }
        None
    }

    /// From the sketch (lam = 0, where every condition holds as sketched) to the given
    /// lengths (lam = 1), keeping the sign of the Jacobian's determinant (the assembly
    /// mode); then Newton to rounding.
    fn solve(&self, sc: &Scene, interrupt: &dyn Interrupt) -> Result<DVector<f64>, Error> {
        let mut x = DVector::zeros(self.n);
        for (p, c) in self.col.iter().enumerate() {
            if let Some(c) = *c {
                x[c] = sc.xy[p][0];
                x[c + 1] = sc.xy[p][1];
            }
        }
        if self.n == 0 {
            return Ok(x);
        }
        let (f1, _) = self.jacobian(&x, 1.0);
        // a sketch that is already exact (a saved scene read back) needs no continuation:
        // the rank check that follows judges its pose
        if !(norm(&f1) <= CLOSE_TOL) {
            let (_, j0) = self.jacobian(&x, 0.0);
            let mut lu = Lu::new(j0.clone());
            if !lu.regular() {
                self.dead_start(sc, &j0)?;
            }
            let sign = lu.sign;
            let (mut lam, mut h, mut steps) = (0.0, 1.0_f64, 0);
            while lam < 1.0 {
                steps += 1;
                if interrupt.interrupted() {
                    return Err(Error::Interrupted);
                }
                if steps > MAX_STEPS || h < H_MIN {
                    return Err(self.cannot_close(sc, &x, lam));
                }
                let h1 = h.min(1.0 - lam);
                let next = if h1 == 1.0 - lam { 1.0 } else { lam + h1 };
                let tried = lu.step(&self.dlam(&x)).and_then(|t| self.correct(&x + t * h1, next));
                match tried {
                    Some((xn, lun)) if lun.regular() && lun.sign == sign => {
                        (x, lu, lam) = (xn, lun, next);
                        h = (2.0 * h1).min(1.0);
                    }
                    _ => h = h1 / 2.0,
                }
            }
        }
        // Newton to rounding at the given lengths
        let mut last = f64::INFINITY;
        for _ in 0..FINAL_ITERS {
            let (f, j) = self.jacobian(&x, 1.0);
            let lu = Lu::new(j);
            let Some(dx) = lu.step(&f) else { break };
            let size = norm(&dx);
            if size <= 4.0 * f64::EPSILON || (size >= last && last <= 1e3 * CLOSE_TOL) {
                break;
            }
            x += dx;
            last = size;
        }
        let (f, _) = self.jacobian(&x, 1.0);
        if !(norm(&f) <= CLOSE_TOL) {
            return Err(self.cannot_close(sc, &x, f64::NAN));
        }
        Ok(x)
    }

    /// The owner a failure is blamed on, and the point that moves most at it. At a dead
    /// point the Jacobian's smallest singular direction says which points move (right
    /// vector) and which conditions cannot hold together (left vector): of the owners with
    /// a moving point, the one those conditions weigh most, a link where one weighs at
    /// least a quarter of the heaviest.
    fn blame(&self, j: &DMatrix<f64>) -> (Owner, Option<usize>) {
        let svd = j.clone().svd(true, true);
        let sv = &svd.singular_values;
        let k = (0..sv.len()).fold(0, |b, i| if sv[i] < sv[b] { i } else { b });
        let (Some(u), Some(vt)) = (&svd.u, &svd.v_t) else { return (Owner::Input, None) };
        let motion: Vec<f64> = self.col.iter().map(|c| c.map_or(0.0, |c| vt[(k, c)].hypot(vt[(k, c + 1)]))).collect();
        let top_motion = motion.iter().fold(0.0_f64, |m, &x| m.max(x));
        let point = (0..motion.len()).fold(None, |b: Option<usize>, p| match b {
            Some(q) if motion[q] >= motion[p] => Some(q),
            _ if self.col[p].is_some() => Some(p),
            _ => b,
        });
        let mut weight: Vec<(Owner, f64, bool)> = Vec::new();
        for (row, &r) in self.rows.iter().zip(&self.start) {
            let w: f64 = (0..row.kind.len()).map(|i| u[(r + i, k)].powi(2)).sum();
            let moves = row.kind.points().iter().any(|&p| motion[p] >= 0.1 * top_motion && motion[p] > 0.0);
            match weight.iter_mut().find(|(o, ..)| *o == row.owner) {
                Some(x) => {
                    x.1 += w;
                    x.2 |= moves;
                }
                None => weight.push((row.owner, w, moves)),
            }
        }
        let heaviest = |links_only: bool| {
            weight.iter().filter(|w| w.2 && (!links_only || matches!(w.0, Owner::Link(_)))).fold(
                None,
                |b: Option<(Owner, f64)>, w| match b {
                    Some(x) if x.1 >= w.1 => Some(x),
                    _ => Some((w.0, w.1)),
                },
            )
        };
        let owner = match (heaviest(true), heaviest(false)) {
            (Some(l), Some(t)) if l.1 >= 0.25 * t.1 => l.0,
            (_, Some(t)) => t.0,
            _ => Owner::Input,
        };
        (owner, point)
    }

    /// The error when the lengths do not close: the continuation stopped at `lam` (NaN: the
    /// last Newton solve at the given lengths did not converge).
    fn cannot_close(&self, sc: &Scene, x: &DVector<f64>, lam: f64) -> Error {
        let (_, j) = self.jacobian(x, if lam.is_nan() { 1.0 } else { lam });
        let (owner, _) = self.blame(&j);
        let why = if lam.is_nan() {
            "Newton's method does not close them".to_string()
        } else {
            format!(
                "changing the sketch's own lengths into the given ones, the pose meets a dead point {:.0}% of the way",
                100.0 * lam
            )
        };
        Error::scene(
            owner.entry(sc),
            format!(
                "no assembly near the sketch: its lengths cannot close at the sketched input in the sketched \
                 assembly mode ({why})"
            ),
        )
    }

    /// Err when the sketch itself is at a dead point (it then names no assembly mode).
    fn dead_start(&self, sc: &Scene, j: &DMatrix<f64>) -> Result<(), Error> {
        let sv = j.singular_values();
        let (lo, hi) = (sv.min(), sv.max());
        if lo > DEAD * hi {
            return Ok(());
        }
        let (owner, point) = self.blame(j);
        let point = point.map_or(String::new(), |p| format!(": draw {:?} off it", sc.names[p]));
        Err(Error::scene(
            owner.entry(sc),
            format!(
                "the sketch is drawn at a dead point (its points can move to first order with every condition held), \
                 so it does not say which assembly it means{point}"
            ),
        ))
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::scene::tests::fourbar;
    use crate::{ClosedForm, FourBar, Mode, Never};

    fn lengths(v: &[(&str, &str, f64)]) -> Vec<LengthSpec> {
        v.iter().map(|(a, b, d)| (a.to_string(), b.to_string(), *d)).collect()
    }

    fn sketch(spec: SceneSpec, l: &[LengthSpec]) -> Result<Sketched, Error> {
        assemble_sketch(spec, l, &Never)
    }

    fn fourbar_lengths() -> Vec<LengthSpec> {
        lengths(&[("O2", "A", 2.0), ("A", "B", 5.0), ("O4", "B", 5.0)])
    }

    /// The entry and message of a scene error.
    fn scene_err(r: Result<Sketched, Error>) -> (String, String) {
        match r {
            Err(Error::Scene { entry, message }) => (entry, message),
            other => panic!("expected a scene error, got {other:?}"),
        }
    }

    #[test]
    fn a_fourbar_sketch_assembles_to_the_closed_form_in_its_sketched_mode() {
        let fb = FourBar::new(6.0, 2.0, 5.0, 5.0).unwrap();
        for (sign, mode) in [(1.0, Mode::Open), (-1.0, Mode::Crossed)] {
            for deg in [0.0_f64, 35.0, 100.0, 200.0, 300.0] {
                let t = deg.to_radians();
                let ClosedForm::Solved { theta3, .. } = fb.closed_form(t, mode) else { panic!("{deg}") };
                let a = [2.0 * t.cos(), 2.0 * t.sin()];
                let b = [a[0] + 5.0 * theta3.cos(), a[1] + 5.0 * theta3.sin()];
                let mut spec = fourbar(sign);
                // A sketched 15% long on its exact direction, B off by (0.3, -0.25)
                spec.points[2].1 = [2.3 * t.cos(), 2.3 * t.sin()];
                spec.points[3].1 = [b[0] + 0.3, b[1] - 0.25];
                let s = sketch(spec, &fourbar_lengths()).unwrap();
                for (p, q) in [(2, a), (3, b)] {
                    let e = (s.points[p][0] - q[0]).hypot(s.points[p][1] - q[1]);
                    assert!(e < 1e-12 * 6.0, "{deg} {p} {e:e}");
                }
                assert_eq!(&s.points[..2], &[[0.0, 0.0], [6.0, 0.0]]);
                assert_eq!(&s.moved[..2], &[0.0, 0.0]);
                assert!((s.moved[2] - 0.3).abs() < 1e-12, "{}", s.moved[2]);
                assert!((s.moved[3] - 0.3f64.hypot(0.25)).abs() < 1e-12, "{}", s.moved[3]);
            }
        }
    }

    #[test]
    fn an_exact_drawing_is_kept_bit_for_bit() {
        for sign in [1.0, -1.0] {
            let spec = fourbar(sign);
            let drawn: Vec<Xy> = spec.points.iter().map(|p| p.1).collect();
            let s = sketch(spec, &lengths(&[("O2", "A", 2.0), ("A", "B", 5.0), ("O4", "B", 5.0)])).unwrap();
            assert_eq!(s.points, drawn);
            assert!(s.moved.iter().all(|&m| m == 0.0));
        }
    }

    #[test]
    fn a_power_of_two_scaling_scales_the_result_exactly() {
        let mut spec = fourbar(1.0);
        spec.points[3].1 = [4.4, 4.1];
        let base = sketch(spec.clone(), &fourbar_lengths()).unwrap();
        for f in [2f64.powi(-60), 2f64.powi(70)] {
            let mut s = spec.clone();
            for p in &mut s.points {
                p.1 = [p.1[0] * f, p.1[1] * f];
            }
            let l: Vec<LengthSpec> = fourbar_lengths().into_iter().map(|(a, b, d)| (a, b, d * f)).collect();
            let out = sketch(s, &l).unwrap();
            for (p, q) in out.points.iter().zip(&base.points) {
                assert_eq!(*p, [q[0] * f, q[1] * f]);
            }
        }
    }

    #[test]
    fn lengths_that_cannot_close_name_a_link_of_the_loop() {
        let (entry, message) =
            scene_err(sketch(fourbar(1.0), &lengths(&[("O2", "A", 2.0), ("A", "B", 1.5), ("O4", "B", 1.5)])));
        assert!(entry == "links.coupler" || entry == "links.rocker", "{entry}");
        assert!(message.starts_with("no assembly near the sketch"), "{message}");
    }

    #[test]
    fn a_link_without_its_length_is_named() {
        let (entry, message) = scene_err(sketch(fourbar(1.0), &lengths(&[("O2", "A", 2.0), ("A", "B", 5.0)])));
        assert_eq!(entry, "links.rocker");
        assert!(message.starts_with("has no lengths"), "{message}");
    }

    #[test]
    fn bad_entries_are_named() {
        type Case = (&'static [(&'static str, &'static str, f64)], &'static str);
        let cases: [Case; 7] = [
            (&[("A", "Q", 1.0)], "unknown point \"Q\""),
            (&[("A", "A", 1.0)], "names \"A\" twice"),
            (&[("O2", "B", 1.0)], "are on no common link"),
            (&[("A", "B", 0.0)], "must be > 0"),
            (&[("A", "B", f64::NAN)], "must be finite"),
            (&[("B", "A", 4.0)], "but lengths[1] gave 5"),
            (&[("O2", "O4", 5.0)], "ground points, which stay as drawn"),
        ];
        for (extra, want) in cases {
            let mut l = fourbar_lengths();
            l.extend(lengths(extra));
            let (entry, message) = scene_err(sketch(fourbar(1.0), &l));
            assert_eq!(entry, "lengths[3]", "{message}");
            assert!(message.contains(want), "{message}");
        }
    }

    #[test]
    fn a_dead_point_sketch_is_refused() {
        let mut spec = fourbar(1.0);
        spec.points[3].1 = [4.0, 0.0]; // A, B and O4 in line
        let (entry, message) = scene_err(sketch(spec, &fourbar_lengths()));
        assert!(entry == "links.coupler" || entry == "links.rocker", "{entry}");
        assert!(message.contains("drawn at a dead point") && message.contains("\"B\""), "{message}");
    }
}
