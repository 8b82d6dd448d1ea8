//! The lengths as given, parsed: each link's listed distances and each point's distance
//! from a slot's or prismatic pair's line, checked against each other, and what each
//! condition belongs to (for the messages).

use std::collections::HashMap;

use crate::error::Error;
use crate::scene::model::Scene;
use crate::scene::vec2::{sub, Xy};

/// A length as given: two names and a distance in the scene's unit. The names are two
/// points of one link (a distance > 0), or a point and a slot or prismatic pair (the
/// point's distance from that joint's line, >= 0).
pub type LengthSpec = (String, String, f64);

/// Lengths that agree to this (relative) are the same length.
pub(super) const SAME: f64 = 1e-9;

/// What a row of conditions belongs to, for error messages.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub(super) enum Owner {
    Link(usize),
    Slot(usize),
    Prismatic(usize),
    Input,
}

impl Owner {
    pub(super) fn entry(self, sc: &Scene) -> String {
        match self {
            Owner::Link(l) => format!("links.{}", sc.links[l].name),
            Owner::Slot(s) => format!("slots.{}", sc.slots[s].name),
            Owner::Prismatic(p) => format!("prismatic.{}", sc.prismatic[p].name),
            Owner::Input => "input".into(),
        }
    }
}

/// The parsed `lengths` (frame units).
pub(super) struct Given {
    /// Distances between two points (lower index first): (distance, entry).
    pub(super) pairs: HashMap<(usize, usize), (f64, usize)>,
    /// Per slot: its pin's distance from the line, if given.
    pub(super) slot_offset: Vec<Option<(f64, usize)>>,
    /// Per prismatic pair: its sliding link's points held at distances from the line.
    pub(super) held: Vec<Vec<(usize, f64, usize)>>,
}

/// A name in a `lengths` entry.
#[derive(Clone, Copy)]
pub(super) enum Name {
    Point(usize),
    Slot(usize),
    Prismatic(usize),
}

impl Given {
    pub(super) fn parse(sc: &Scene, fixed: &[bool], lengths: &[LengthSpec]) -> Result<Given, Error> {
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
    pub(super) fn pair(
        &mut self,
        sc: &Scene,
        fixed: &[bool],
        (p, q): (usize, usize),
        v: f64,
        k: usize,
    ) -> Result<(), Error> {
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
    pub(super) fn line(
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

pub(super) fn same(a: f64, b: f64) -> bool {
    (a - b).abs() <= SAME * a.abs().max(b.abs())
}

pub(super) fn dist(v: Xy) -> f64 {
    v[0].hypot(v[1])
}
