//! Travel limits resolved on a scene: which coordinate each bounds (a slot's or prismatic
//! pair's displacement, or two links' relative angle at their shared joint) and its value
//! at any pose, measured from the drawn one as a linear input's displacement is.

use super::format::{Bounded, LimitSpec};
use super::model::Scene;
use super::vec2::{cross, dot, sub, Xy};
use crate::error::Error;
use crate::wrap_angle;

/// The coordinate a limit bounds, by point indices: `Slide` the displacement of `p` along
/// the line `a -> b`, `Turn` the turn of `c -> d` relative to `a -> b`.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum Coordinate {
    /// A slot's point or a prismatic pair's link point `p` along its guide's line a -> b.
    Slide { p: usize, a: usize, b: usize },
    /// The direction c -> d (the second link's) relative to a -> b (the first's).
    Turn { a: usize, b: usize, c: usize, d: usize },
}

/// A limit on a scene: its entry's name, coordinate, range, and the coordinate's raw value
/// as drawn (so that the drawn pose reads 0).
#[derive(Clone, Debug, PartialEq)]
pub struct Limit {
    /// The entry's key in `limits`.
    pub name: String,
    /// What it bounds.
    pub coordinate: Coordinate,
    /// The range [lo, hi] (lo <= 0 <= hi), scene units or radians.
    pub range: (f64, f64),
    pub(crate) drawn: f64,
}

impl Coordinate {
    /// The raw coordinate at solving-frame positions `pos` (a displacement in solving-frame
    /// units, or an angle).
    pub(crate) fn raw(&self, pos: &[Xy]) -> f64 {
        match *self {
            Coordinate::Slide { p, a, b } => {
                let u = sub(pos[b], pos[a]);
                dot(sub(pos[p], pos[a]), u) / dot(u, u).sqrt()
            }
            Coordinate::Turn { a, b, c, d } => {
                let (u, v) = (sub(pos[b], pos[a]), sub(pos[d], pos[c]));
                cross(u, v).atan2(dot(u, v))
            }
        }
    }

    /// The points it reads.
    pub(crate) fn points(&self) -> Vec<usize> {
        match *self {
            Coordinate::Slide { p, a, b } => vec![p, a, b],
            Coordinate::Turn { a, b, c, d } => vec![a, b, c, d],
        }
    }
}

impl Limit {
    /// The coordinate at solving-frame positions `pos`, from the drawn pose (scene units for
    /// a displacement: `scale` is the solving frame's).
    pub(crate) fn value(&self, pos: &[Xy], scale: f64) -> f64 {
        let raw = self.coordinate.raw(pos);
        match self.coordinate {
            Coordinate::Slide { .. } => (raw - self.drawn) * scale,
            Coordinate::Turn { .. } => wrap_angle(raw - self.drawn),
        }
    }
}

impl Scene {
    /// The scene with travel limits (the file format's `limits`, names checked): a
    /// revolute limit's two links must share a point. Replaces any limits it had.
    pub fn with_limits(mut self, specs: &[LimitSpec]) -> Result<Scene, Error> {
        let link = |n: &str| self.links.iter().position(|l| l.name == n);
        let mut out = Vec::with_capacity(specs.len());
        for s in specs {
            let e = format!("limits.{}", s.name);
            let coordinate = match &s.bounded {
                Bounded::Joint(j) => {
                    if let Some(sl) = self.slots.iter().find(|x| &x.name == j) {
                        Coordinate::Slide { p: sl.point, a: sl.line.0, b: sl.line.1 }
                    } else if let Some(pr) = self.prismatic.iter().find(|x| &x.name == j) {
                        let p = self.links[pr.link].points[0];
                        Coordinate::Slide { p, a: pr.line.0, b: pr.line.1 }
                    } else {
                        return Err(Error::scene(e, "names no slot or prismatic pair"));
                    }
                }
                Bounded::Angle(a, b) => {
                    let (Some(la), Some(lb)) = (link(a), link(b)) else {
                        return Err(Error::scene(format!("{e}.links"), "names a link the scene does not have"));
                    };
                    if !self.links[la].points.iter().any(|p| self.links[lb].points.contains(p)) {
                        return Err(Error::scene(
                            format!("{e}.links"),
                            format!("{a:?} and {b:?} share no joint (a revolute limit is between two links pinned together)"),
                        ));
                    }
                    let ((pa, pb), (pc, pd)) = (self.angle_points(la), self.angle_points(lb));
                    Coordinate::Turn { a: pa, b: pb, c: pc, d: pd }
                }
            };
            let drawn = coordinate.raw(&self.xy);
            out.push(Limit { name: s.name.clone(), coordinate, range: s.range, drawn });
        }
        self.limits = out;
        Ok(self)
    }

    /// The travel limits, in the order given.
    pub fn limits(&self) -> &[Limit] {
        &self.limits
    }
}
