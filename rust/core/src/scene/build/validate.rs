//! Scene validation: names, coordinates, links, ground/input/output, and mobility (the
//! Gruebler count, then the rank of the constraint Jacobian at the drawn pose, so that a
//! special geometry that moves although the count says it cannot is reported).

use std::collections::HashMap;

use nalgebra::DMatrix;

use super::compile::compile;
use crate::error::Error;
use crate::scene::input::{Linear, LinearKind, Pivoted};
use crate::scene::model::{Link, Prismatic, Scene, SceneSpec, Slot};
use crate::scene::vec2::{cross, dot, perp, sub, Xy};

/// Two points of one link closer than this, relative to the scene's size, coincide.
const COINCIDENT: f64 = 1e-12;
/// The constraint Jacobian at the drawn pose is rank deficient when its smallest singular
/// value is below this fraction of its largest.
const RANK_TOL: f64 = 1e-9;
/// Largest Jacobian (unknowns) whose singular values are computed when the plan cannot
/// prove full rank (cubic time: about 0.1 s at this size).
const DENSE_COLUMNS: usize = 600;
/// Most points (and most links) a scene may have: loading stays near linear in its size,
/// so this bounds a file's memory and time (a million points load in seconds).
const MAX_ENTRIES: usize = 1_000_000;

pub(crate) fn scene(spec: SceneSpec) -> Result<Scene, Error> {
    let sc = structure(spec)?;
    rank_check(&sc)?;
    Ok(sc)
}

/// Everything [`scene`] checks but the rank at the drawn pose: names, coordinates, links,
/// joints, inputs and the Gruebler count. A sketch (whose pose is not yet an assembly) is
/// checked by this before it is assembled.
pub(crate) fn structure(spec: SceneSpec) -> Result<Scene, Error> {
    let SceneSpec { points, links, ground, input, output, slots, prismatic, linear_input } = spec;
    if points.is_empty() {
        return Err(Error::scene("points", "the scene has no points"));
    }
    for (what, n) in [("points", points.len()), ("links", links.len())] {
        if n > MAX_ENTRIES {
            return Err(Error::scene(what, format!("{n} entries; a scene may have at most {MAX_ENTRIES}")));
        }
    }
    let mut index: HashMap<&str, usize> = HashMap::new();
    for (i, (name, xy)) in points.iter().enumerate() {
        if index.insert(name.as_str(), i).is_some() {
            return Err(Error::scene(format!("points.{name}"), "is given twice"));
        }
        if !xy.iter().all(|v| v.is_finite()) {
            return Err(Error::scene(format!("points.{name}"), format!("coordinates must be finite, got {xy:?}")));
        }
    }
    let drawn: Vec<Xy> = points.iter().map(|p| p.1).collect();
    let names: Vec<String> = points.iter().map(|p| p.0.clone()).collect();

    if links.is_empty() {
        return Err(Error::scene("links", "the scene has no links"));
    }
    let mut link_index: HashMap<&str, usize> = HashMap::new();
    let mut parsed = Vec::with_capacity(links.len());
    // the link (plus one) that last listed each point: a repeat within a link in O(1)
    let mut listed_by = vec![0usize; points.len()];
    for (k, (name, pts)) in links.iter().enumerate() {
        let entry = format!("links.{name}");
        if link_index.insert(name.as_str(), k).is_some() {
            return Err(Error::scene(entry, "is given twice"));
        }
        if pts.len() < 2 {
            return Err(Error::scene(entry, format!("a link needs at least 2 points, got {}", pts.len())));
        }
        let mut idx = Vec::with_capacity(pts.len());
        for p in pts {
            let &i = index.get(p.as_str()).ok_or_else(|| Error::scene(&entry, format!("unknown point {p:?}")))?;
            if listed_by[i] == k + 1 {
                return Err(Error::scene(&entry, format!("lists point {p:?} twice")));
            }
            listed_by[i] = k + 1;
            idx.push(i);
        }
        parsed.push(Link { name: name.clone(), points: idx });
    }

    // Size of the scene: the largest diagonal of a link's bounding box, measured after an
    // exact power-of-two scaling by its largest side (no square overflows or underflows,
    // from 1e-300 to 1e300).
    let mut side = 0.0_f64;
    let boxes: Vec<(Xy, Xy)> = parsed.iter().map(|l| bounding_box(l.points.iter().map(|&p| drawn[p]))).collect();
    for (lo, hi) in &boxes {
        side = side.max(hi[0] - lo[0]).max(hi[1] - lo[1]);
    }
    if !side.is_finite() {
        return Err(Error::scene("points", "coordinates are too large to measure (a distance overflows)"));
    }
    let pre = power_of_two_below(side);
    let size = boxes.iter().map(|(lo, hi)| ((hi[0] - lo[0]) / pre).hypot((hi[1] - lo[1]) / pre)).fold(0.0, f64::max);
    for l in &parsed {
        if let Some((a, b, d)) = coincident(&l.points, &drawn, pre, COINCIDENT * size) {
            return Err(Error::scene(
                format!("links.{}", l.name),
                format!("points {:?} and {:?} coincide (distance {:e})", names[a], names[b], d * pre),
            ));
        }
    }

    let mut point_links = vec![Vec::new(); names.len()];
    for (k, l) in parsed.iter().enumerate() {
        for &p in &l.points {
            point_links[p].push(k);
        }
    }
    if let Some(p) = point_links.iter().position(|l| l.is_empty()) {
        return Err(Error::scene(format!("points.{}", names[p]), "is on no link"));
    }

    let link_of = |entry: &str, name: &str| {
        link_index.get(name).copied().ok_or_else(|| Error::scene(entry, format!("{name:?} is not a link")))
    };
    let ground = link_of("ground", &ground)?;
    let pivoted = |what: &str, (link, pivot): &(String, String)| -> Result<Pivoted, Error> {
        let l = link_of(&format!("{what}.link"), link)?;
        if l == ground {
            return Err(Error::scene(format!("{what}.link"), format!("{link:?} is the ground link")));
        }
        let entry = format!("{what}.pivot");
        let &p = index.get(pivot.as_str()).ok_or_else(|| Error::scene(&entry, format!("unknown point {pivot:?}")))?;
        if !parsed[l].points.contains(&p) {
            return Err(Error::scene(entry, format!("{pivot:?} is not a point of link {link:?}")));
        }
        if !parsed[ground].points.contains(&p) {
            return Err(Error::scene(
                entry,
                format!(
                    "{pivot:?} is not on the ground link {:?}: the {what} must be pinned to ground",
                    parsed[ground].name
                ),
            ));
        }
        let tip = *parsed[l].points.iter().find(|&&q| q != p).expect("a link has >= 2 distinct points");
        Ok(Pivoted { link: l, pivot: p, tip })
    };
    let output = output.as_ref().map(|o| pivoted("output", o)).transpose()?;

    // slots and prismatic pairs: names, their links and line points (scaled positions for
    // the offsets come once the frame is fixed, below)
    let point_of = |entry: &str, name: &str| {
        index.get(name).copied().ok_or_else(|| Error::scene(entry, format!("unknown point {name:?}")))
    };
    let line_of = |entry: &str, guide: usize, line: &(String, String)| -> Result<(usize, usize), Error> {
        let (a, b) = (point_of(&format!("{entry}.line"), &line.0)?, point_of(&format!("{entry}.line"), &line.1)?);
        for (n, p) in [(&line.0, a), (&line.1, b)] {
            if !parsed[guide].points.contains(&p) {
                return Err(Error::scene(
                    format!("{entry}.line"),
                    format!("{n:?} is not a point of the guide {:?}", parsed[guide].name),
                ));
            }
        }
        let d = sub(drawn[b], drawn[a]);
        if !((d[0] / pre).hypot(d[1] / pre) > COINCIDENT * size) {
            return Err(Error::scene(
                format!("{entry}.line"),
                format!("points {:?} and {:?} coincide", line.0, line.1),
            ));
        }
        Ok((a, b))
    };
    let mut joint_names: HashMap<&str, &str> = HashMap::new();
    let mut slot_list = Vec::with_capacity(slots.len());
    for (name, sp) in &slots {
        let entry = format!("slots.{name}");
        if joint_names.insert(name.as_str(), "slot").is_some() {
            return Err(Error::scene(entry, "is given twice"));
        }
        let point = point_of(&format!("{entry}.point"), &sp.point)?;
        let guide = link_of(&format!("{entry}.guide"), &sp.guide)?;
        if parsed[guide].points.contains(&point) {
            return Err(Error::scene(
                format!("{entry}.point"),
                format!("{:?} is a point of its guide {:?}: it could not move along the line", sp.point, sp.guide),
            ));
        }
        if point_links[point].iter().all(|&l| l == ground) {
            return Err(Error::scene(format!("{entry}.point"), format!("{:?} is on no moving link", sp.point)));
        }
        let line = line_of(&entry, guide, &sp.line)?;
        slot_list.push(Slot { name: name.clone(), point, guide, line, offset: 0.0 });
    }
    let mut prism_list = Vec::with_capacity(prismatic.len());
    for (name, sp) in &prismatic {
        let entry = format!("prismatic.{name}");
        if joint_names.insert(name.as_str(), "prismatic").is_some() {
            return Err(Error::scene(entry, "is given twice (names of slots and prismatic pairs are one namespace)"));
        }
        let link = link_of(&format!("{entry}.link"), &sp.link)?;
        let guide = link_of(&format!("{entry}.guide"), &sp.guide)?;
        if link == guide {
            return Err(Error::scene(format!("{entry}.guide"), format!("{:?} cannot guide itself", sp.link)));
        }
        if let Some(&p) = parsed[link].points.iter().find(|p| parsed[guide].points.contains(p)) {
            return Err(Error::scene(
                format!("{entry}.link"),
                format!("{:?} and its guide {:?} share point {:?}: they could not slide", sp.link, sp.guide, names[p]),
            ));
        }
        let line = line_of(&entry, guide, &sp.line)?;
        prism_list.push(Prismatic { name: name.clone(), link, guide, line });
    }
    let linear = match &linear_input {
        None => None,
        Some((kind, name)) => {
            let (key, found) = match kind {
                LinearKind::Slot => ("slot", slot_list.iter().position(|s| &s.name == name)),
                LinearKind::Prismatic => ("prismatic", prism_list.iter().position(|s| &s.name == name)),
            };
            let index =
                found.ok_or_else(|| Error::scene(format!("input.{key}"), format!("{name:?} is not a {key}")))?;
            let (guide, line) = match kind {
                LinearKind::Slot => (slot_list[index].guide, slot_list[index].line),
                LinearKind::Prismatic => (prism_list[index].guide, prism_list[index].line),
            };
            Some(Linear { kind: *kind, index, guide, dir: sub(drawn[line.1], drawn[line.0]) })
        }
    };
    let input = match linear {
        None => Some(pivoted("input", &input)?),
        Some(_) => None,
    };

    let m = gruebler(parsed.len(), &point_links) - slot_list.len() as i64 - 2 * prism_list.len() as i64;
    if m != 1 {
        let joints: usize = point_links.iter().map(|l| l.len().saturating_sub(1)).sum();
        let extra = if slot_list.is_empty() && prism_list.is_empty() {
            String::new()
        } else {
            format!(" - {} slots - 2 x {} prismatic pairs", slot_list.len(), prism_list.len())
        };
        return Err(Error::scene(
            "mobility",
            format!(
                "Gruebler's count gives M = {m} (3 x ({} links - 1) - 2 x {joints} joints{extra}), expected 1 \
                 (a one-degree-of-freedom linkage)",
                parsed.len()
            ),
        ));
    }

    let scale = power_of_two_below(size * pre);
    let origin = match (input, linear) {
        (Some(i), _) => drawn[i.pivot],
        (None, Some(l)) => match l.kind {
            LinearKind::Slot => drawn[slot_list[l.index].line.0],
            LinearKind::Prismatic => drawn[prism_list[l.index].line.0],
        },
        (None, None) => unreachable!("a scene has an angle or a linear input"),
    };
    let xy: Vec<Xy> = drawn.iter().map(|&p| [(p[0] - origin[0]) / scale, (p[1] - origin[1]) / scale]).collect();
    let theta0 = match input {
        Some(i) => {
            let d = sub(xy[i.tip], xy[i.pivot]);
            (d[1] + 0.0).atan2(d[0])
        }
        None => 0.0,
    };
    let unit = |a: usize, b: usize| {
        let d = sub(xy[b], xy[a]);
        let n = d[0].hypot(d[1]);
        [d[0] / n, d[1] / n]
    };
    for sl in &mut slot_list {
        sl.offset = cross(unit(sl.line.0, sl.line.1), sub(xy[sl.point], xy[sl.line.0]));
    }
    let linear = linear.map(|l| {
        let line = match l.kind {
            LinearKind::Slot => slot_list[l.index].line,
            LinearKind::Prismatic => prism_list[l.index].line,
        };
        Linear { dir: unit(line.0, line.1), ..l }
    });

    Ok(Scene {
        names,
        drawn,
        xy,
        origin,
        scale,
        links: parsed,
        point_links,
        ground,
        input,
        output,
        slots: slot_list,
        prismatic: prism_list,
        linear,
        theta0,
    })
}

/// The largest power of two at most `x` (> 0, finite; subnormal sizes included).
fn power_of_two_below(x: f64) -> f64 {
    if !(x > 0.0) {
        return 1.0;
    }
    // exact for normal and subnormal x: powi would over- or underflow past 2^1023 / 2^-1022
    let e = x.log2().floor() as i32;
    let p = 2f64.powi(e.clamp(-1022, 1023));
    let p = if e < -1022 { p * 2f64.powi(e + 1022) } else { p };
    if p > x {
        p / 2.0
    } else {
        p
    }
}

fn bounding_box(points: impl Iterator<Item = Xy>) -> (Xy, Xy) {
    points.fold(([f64::INFINITY; 2], [f64::NEG_INFINITY; 2]), |(lo, hi), p| {
        ([lo[0].min(p[0]), lo[1].min(p[1])], [hi[0].max(p[0]), hi[1].max(p[1])])
    })
}

/// Two of `points` closer than `tol` (in units of `pre`): the first such pair and its
/// distance. Sorted by x, each point is compared with those within `tol` of it in x: near
/// linear for the points of one link, however many.
fn coincident(points: &[usize], drawn: &[Xy], pre: f64, tol: f64) -> Option<(usize, usize, f64)> {
    // (x, y, position in the link's list)
    let mut order: Vec<(f64, f64, usize)> =
        points.iter().enumerate().map(|(k, &p)| (drawn[p][0] / pre, drawn[p][1] / pre, k)).collect();
    order.sort_by(|a, b| a.0.total_cmp(&b.0));
    // the pair first in the link's listed order, as a reader scans it
    let mut found: Option<(usize, usize, f64)> = None;
    for (i, a) in order.iter().enumerate() {
        for b in order[i + 1..].iter().take_while(|b| b.0 - a.0 <= tol) {
            let d = (b.0 - a.0).hypot(b.1 - a.1);
            let pair = (a.2.min(b.2), a.2.max(b.2));
            if !(d > tol) && found.is_none_or(|f| pair < (f.0, f.1)) {
                found = Some((pair.0, pair.1, d));
            }
        }
    }
    found.map(|(i, j, d)| (points[i], points[j], d))
}

/// M = 3 (links - 1) - 2 joints.
pub(crate) fn gruebler(links: usize, point_links: &[Vec<usize>]) -> i64 {
    let joints: usize = point_links.iter().map(|l| l.len().saturating_sub(1)).sum();
    3 * (links as i64 - 1) - 2 * joints as i64
}

/// The constraint Jacobian at the drawn pose, with the input angle held, must be square and
/// of full rank: otherwise the drawn pose is a dead point, or the linkage has more freedom
/// there than its count says (e.g. a structure that moves because of special geometry).
///
/// The plan is the cheap proof: it solves the constraints in order, so where each of its
/// steps is regular at the drawn pose the Jacobian is block triangular with regular blocks
/// (time linear in the scene's size). Otherwise, up to [`DENSE_COLUMNS`] unknowns, the
/// singular values decide (and say why); a larger scene gets the plan's own answer.
fn rank_check(sc: &Scene) -> Result<(), Error> {
    let points: Vec<usize> = (0..sc.names.len()).collect();
    let links: Vec<usize> = (0..sc.links.len()).collect();
    let planned = compile(sc, &points, &links);
    if let Ok(p) = &planned {
        let (_, dets) = p.dets_at(&sc.xy);
        match dets.iter().position(|d| !(d.abs() > RANK_TOL)) {
            None => return Ok(()),
            Some(k) if 3 * (sc.links.len() - 1) > DENSE_COLUMNS => {
                let step = &p.steps()[k];
                let at: Vec<&str> = step.points.iter().map(|&q| sc.names[q].as_str()).collect();
                return Err(Error::scene(
                    "mobility",
                    format!(
                        "the drawn pose is a dead point: the {} solving {at:?} has conditioning {:.1e}",
                        step.kind.name(),
                        dets[k]
                    ),
                ));
            }
            Some(_) => {}
        }
    }
    if 3 * (sc.links.len() - 1) > DENSE_COLUMNS {
        return planned.map(|_| ());
    }
    dense_rank_check(sc)
}

/// [`rank_check`] by the singular values of the whole Jacobian.
fn dense_rank_check(sc: &Scene) -> Result<(), Error> {
    // unknowns: (tx, ty, phi) of every non-ground link; a link's points are
    // t + R(phi) (p - p_first)
    let col: Vec<Option<usize>> = {
        let mut next = 0;
        (0..sc.links.len())
            .map(|k| {
                (k != sc.ground).then(|| {
                    next += 3;
                    next - 3
                })
            })
            .collect()
    };
    let ncol = 3 * (sc.links.len() - 1);
    let mut rows: Vec<Vec<f64>> = Vec::new();
    // d position of point p via link k
    let grad = |k: usize, p: usize, row: &mut [f64], comp: usize, sign: f64| {
        if let Some(c) = col[k] {
            let first = sc.links[k].points[0];
            let r = perp(sub(sc.xy[p], sc.xy[first]));
            row[c + comp] += sign;
            row[c + 2] += sign * r[comp];
        }
    };
    for (p, ls) in sc.point_links.iter().enumerate() {
        for &k in &ls[1..] {
            for comp in 0..2 {
                let mut row = vec![0.0; ncol];
                grad(k, p, &mut row, comp, 1.0);
                grad(ls[0], p, &mut row, comp, -1.0);
                rows.push(row);
            }
        }
    }
    // a point's position derivative row: d p / d (tx, ty, phi) of link k, component comp
    let dpos = |k: usize, p: usize, row: &mut [f64], w: Xy| {
        if let Some(c) = col[k] {
            let first = sc.links[k].points[0];
            let r = perp(sub(sc.xy[p], sc.xy[first]));
            row[c] += w[0];
            row[c + 1] += w[1];
            row[c + 2] += dot(w, r);
        }
    };
    let link_of = |p: usize| sc.point_links[p][0];
    // a slot: cross(u, p - l0) with u the guide's unit direction; d = cross(du, p - l0) +
    // cross(u, dp - dl0), du = dphi_guide perp(u)
    let on_line = |guide: usize, line: (usize, usize), p: usize, pl: usize, row: &mut [f64]| {
        let u = {
            let d = sub(sc.xy[line.1], sc.xy[line.0]);
            let n = dot(d, d).sqrt();
            [d[0] / n, d[1] / n]
        };
        let n = perp(u); // cross(u, v) = n . v
        dpos(pl, p, row, n);
        dpos(guide, line.0, row, [-n[0], -n[1]]);
        if let Some(c) = col[guide] {
            // cross(perp(u), p - l0) = -u . (p - l0)
            row[c + 2] -= dot(u, sub(sc.xy[p], sc.xy[line.0]));
        }
    };
    let linear = sc.linear.map(|l| (l.kind, l.index));
    for (i, sl) in sc.slots.iter().enumerate() {
        let mut row = vec![0.0; ncol];
        on_line(sl.guide, sl.line, sl.point, link_of(sl.point), &mut row);
        rows.push(row);
        if linear == Some((LinearKind::Slot, i)) {
            // the input holds the point's place along the line
            let mut row = vec![0.0; ncol];
            let u = sub(sc.xy[sl.line.1], sc.xy[sl.line.0]);
            dpos(link_of(sl.point), sl.point, &mut row, u);
            dpos(sl.guide, sl.line.0, &mut row, [-u[0], -u[1]]);
            if let Some(c) = col[sl.guide] {
                row[c + 2] += cross(u, sub(sc.xy[sl.point], sc.xy[sl.line.0]));
            }
            rows.push(row);
        }
    }
    for (i, pr) in sc.prismatic.iter().enumerate() {
        let q = sc.links[pr.link].points[0];
        let mut row = vec![0.0; ncol];
        on_line(pr.guide, pr.line, q, pr.link, &mut row);
        rows.push(row);
        let mut row = vec![0.0; ncol];
        if let Some(c) = col[pr.link] {
            row[c + 2] += 1.0;
        }
        if let Some(c) = col[pr.guide] {
            row[c + 2] -= 1.0;
        }
        rows.push(row);
        if linear == Some((LinearKind::Prismatic, i)) {
            let mut row = vec![0.0; ncol];
            let u = sub(sc.xy[pr.line.1], sc.xy[pr.line.0]);
            dpos(pr.link, q, &mut row, u);
            dpos(pr.guide, pr.line.0, &mut row, [-u[0], -u[1]]);
            if let Some(c) = col[pr.guide] {
                row[c + 2] += cross(u, sub(sc.xy[q], sc.xy[pr.line.0]));
            }
            rows.push(row);
        }
    }
    if let Some(input) = sc.input {
        let mut row = vec![0.0; ncol];
        row[col[input.link].expect("input is not ground") + 2] = 1.0;
        rows.push(row);
    }
    debug_assert_eq!(rows.len(), ncol, "Gruebler M = 1 makes the system square");
    let j = DMatrix::from_fn(rows.len(), ncol, |r, c| rows[r][c]);
    let sv = j.singular_values();
    let (lo, hi) = (sv.min(), sv.max());
    if !(lo > RANK_TOL * hi) {
        return Err(Error::scene(
            "mobility",
            format!(
                "the constraint Jacobian at the drawn pose is rank deficient (smallest / largest singular value \
                 {:.1e}): the drawn pose is a dead point, or the linkage moves with more than one degree of \
                 freedom there although Gruebler's count is 1",
                lo / hi
            ),
        ));
    }
    Ok(())
}

impl Scene {
    /// Validates a scene: every name, coordinate and link, the ground, input and output
    /// links, and mobility (Gruebler count and a rank check at the drawn pose). The error
    /// names the entry and says why.
    pub fn new(spec: SceneSpec) -> Result<Scene, Error> {
        scene(spec)
    }
}
