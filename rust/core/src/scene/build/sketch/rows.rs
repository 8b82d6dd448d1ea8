//! The conditions a sketch must meet: each moving link's shape from its lengths (sides
//! as sketched), slots and prismatic pairs by their distances from their lines. The rule
//! for sliders is [`assemble_sketch`](super::assemble_sketch)'s.

use super::given::{dist, Given, Owner, SAME};
use crate::error::Error;
use crate::scene::input::LinearKind;
use crate::scene::model::{Link, Scene};
use crate::scene::vec2::{cross, dot, sub, Xy};

/// A triangle whose squared height is within this fraction of its longest side squared
/// closes flat (its point lies on the line): lengths cannot fix a height better than the
/// square root of their rounding, so a height below 1e-6 of the link is taken as none.
pub(super) const FLAT: f64 = 1e-12;

/// One condition (two for `Affine`), with its target moving from `from` (as sketched) to
/// `to` (as given) along the continuation.
#[derive(Clone, Debug)]
pub(super) struct Row {
    pub(super) kind: Kind,
    pub(super) owner: Owner,
    pub(super) from: Xy,
    pub(super) to: Xy,
}

#[derive(Clone, Copy, Debug)]
pub(super) enum Kind {
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
    pub(super) fn points(self) -> [usize; 3] {
        match self {
            Kind::Dist { a, b } => [a, b, b],
            Kind::Affine { a, b, c } => [a, b, c],
            Kind::Off { l0, l1, p } | Kind::Along { l0, l1, p } => [l0, l1, p],
            Kind::Angle { pivot, tip, .. } => [pivot, tip, tip],
        }
    }

    pub(super) fn len(self) -> usize {
        if matches!(self, Kind::Affine { .. }) {
            2
        } else {
            1
        }
    }
}

/// The conditions of the sketch, in frame units, with their sketched and given targets.
pub(super) fn rows(sc: &Scene, fixed: &[bool], given: &Given) -> Result<Vec<Row>, Error> {
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

pub(super) fn unit(v: Xy) -> Xy {
    let n = dist(v);
    [v[0] / n, v[1] / n]
}

/// A link's shape from its listed distances: a base pair (a, b) at distance d and each
/// further point c as (c, alpha, beta) with c - a = alpha (b - a) + beta perp(b - a).
/// Each point is placed by its distances to two points already placed (the farthest
/// apart such pair), on the side it is sketched on. The error is the message.
pub(super) type Shape = (usize, usize, f64, Vec<(usize, f64, f64)>);

pub(super) fn shape(sc: &Scene, link: &Link, adj: &[(usize, usize, f64)], local: &[usize]) -> Result<Shape, String> {
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
