//! Any one-degree-of-freedom planar linkage of revolute joints, described as data: named
//! points drawn in one assembled pose and links as the lists of points they carry.
//! [`Scene::new`] validates it (names, geometry, mobility); [`Scene::plan`] compiles the
//! steps that the requested outputs need (dyads, rigid carries, Newton groups);
//! [`Plan::sweep`] solves them over input angles, [`Plan::assemblies`] finds every
//! assembly at one angle, and [`Tracer`] follows circuits through their dead points.
//! [`assemble_sketch`] turns `lengths` and a rough drawing into the exact pose.
//!
//! Inside: `validate` and `plan` build (`sketch` assembles a sketch before); `sweep` (continuation) and `columns` (dyad-only
//! plans, blocks of angles) solve, on `dyad` and `group`; `assemble` and `trace` branch
//! and follow; `options` and `vec2` are the leaves they share.

mod assemble;
mod buffers;
mod columns;
mod dyad;
mod eval;
pub mod format;
mod gradient;
mod group;
mod options;
mod plan;
mod sketch;
mod slide;
mod stroke;
mod sweep;
mod trace;
mod validate;
mod vec2;

use std::collections::HashMap;

pub use assemble::{Assemblies, Assembly};
pub use buffers::{Advise, NoAdvice, Rates, SceneSweepBuffers};
pub use gradient::{Free, DET_STEP};
pub use options::{ScenePredictor, SceneSweepOptions, SceneSweepOut};
pub use plan::{Plan, StepInfo, StepKind};
pub use sketch::{assemble_sketch, LengthSpec, Sketched, MAX_SKETCH_POINTS};
pub use slide::{Prismatic, Slot};
pub use trace::{Circuit, Trace, TraceOptions, Tracer};
pub use vec2::Xy;

use crate::error::Error;
use crate::interrupt::Interrupt;
use crate::solve::homotopy::HomotopyOptions;

/// A link: a rigid body carrying the listed points (indices into the scene's points).
#[derive(Clone, Debug, PartialEq)]
pub struct Link {
    /// Its name in the scene.
    pub name: String,
    /// The points it carries, in the order listed.
    pub points: Vec<usize>,
}

/// A ground-pivoted link whose angle is an input or output: the direction from `pivot`
/// to `tip`, its first listed point other than the pivot.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct Pivoted {
    /// Index of the link.
    pub link: usize,
    /// Index of the ground pivot.
    pub pivot: usize,
    /// Index of the point whose direction from the pivot is the link's angle.
    pub tip: usize,
}

/// A slot as given: a point kept on the line through two points of a guide link.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct SlotSpec {
    /// The point (of one or more moving links).
    pub point: String,
    /// The link carrying the line.
    pub guide: String,
    /// Two points of the guide: the line, directed from the first to the second.
    pub line: (String, String),
}

/// A prismatic pair as given: a link translating along a line of its guide.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct PrismaticSpec {
    /// The translating link.
    pub link: String,
    /// The link it slides in.
    pub guide: String,
    /// Two points of the guide: the direction of travel.
    pub line: (String, String),
}

impl From<(String, String, (String, String))> for SlotSpec {
    /// (point, guide, line).
    fn from((point, guide, line): (String, String, (String, String))) -> Self {
        Self { point, guide, line }
    }
}

impl From<(String, String, (String, String))> for PrismaticSpec {
    /// (link, guide, line).
    fn from((link, guide, line): (String, String, (String, String))) -> Self {
        Self { link, guide, line }
    }
}

/// Which kind of prismatic joint drives a linear input.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum LinearKind {
    /// A slot: the displacement of its point along the line.
    Slot,
    /// A prismatic pair: the displacement of its link along the line.
    Prismatic,
}

/// A linear input, validated: the joint and its direction of travel as drawn.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Linear {
    /// Slot or prismatic pair.
    pub kind: LinearKind,
    /// Its index among the scene's slots or prismatic pairs.
    pub index: usize,
    /// The guide link.
    pub guide: usize,
    /// Unit direction of travel as drawn (line.0 -> line.1).
    pub dir: Xy,
}

/// The scene as given, before validation: names and drawn coordinates.
#[derive(Clone, Debug, Default)]
pub struct SceneSpec {
    /// Point name and drawn (x, y), any length unit.
    pub points: Vec<(String, Xy)>,
    /// Link name and the names of the points it carries.
    pub links: Vec<(String, Vec<String>)>,
    /// The fixed link.
    pub ground: String,
    /// The driven link and its ground pivot (an angle input; ignored when `linear_input`
    /// names a joint).
    pub input: (String, String),
    /// Optional output link and its ground pivot.
    pub output: Option<(String, String)>,
    /// Slots by name.
    pub slots: Vec<(String, SlotSpec)>,
    /// Prismatic pairs by name.
    pub prismatic: Vec<(String, PrismaticSpec)>,
    /// A linear input instead of the angle one: a slot or prismatic pair by name.
    pub linear_input: Option<(LinearKind, String)>,
}

/// A validated scene. Coordinates are kept as drawn and, for solving, shifted to the input
/// pivot and divided by a power of two near the scene's size (exact: any power-of-two
/// scaling of a drawing gives bit-identical angles and statuses).
#[derive(Clone, Debug)]
pub struct Scene {
    names: Vec<String>,
    drawn: Vec<Xy>,
    /// (drawn - origin) / scale.
    xy: Vec<Xy>,
    origin: Xy,
    scale: f64,
    links: Vec<Link>,
    /// Links carrying each point.
    point_links: Vec<Vec<usize>>,
    ground: usize,
    /// The angle input (None for a linear one).
    input: Option<Pivoted>,
    output: Option<Pivoted>,
    slots: Vec<Slot>,
    prismatic: Vec<Prismatic>,
    linear: Option<Linear>,
    /// The drawn input: its angle, or 0 for a linear input (displacements are measured
    /// from the drawn pose).
    theta0: f64,
}

impl Scene {
    /// Validates a scene: every name, coordinate and link, the ground, input and output
    /// links, and mobility (Gruebler count and a rank check at the drawn pose). The error
    /// names the entry and says why.
    pub fn new(spec: SceneSpec) -> Result<Scene, Error> {
        validate::scene(spec)
    }

    /// Point names, in the order given.
    pub fn point_names(&self) -> &[String] {
        &self.names
    }

    /// Drawn coordinates, in the order of [`Scene::point_names`].
    pub fn drawn(&self) -> &[Xy] {
        &self.drawn
    }

    /// The links, in the order given.
    pub fn links(&self) -> &[Link] {
        &self.links
    }

    /// Index of the ground link.
    pub fn ground(&self) -> usize {
        self.ground
    }

    /// The input link, its pivot and the point that sets its angle (None: a linear input).
    pub fn input(&self) -> Option<Pivoted> {
        self.input
    }

    /// The linear input, if the scene is driven by a slot or prismatic pair.
    pub fn linear_input(&self) -> Option<Linear> {
        self.linear
    }

    /// The slots, in the order given.
    pub fn slots(&self) -> &[Slot] {
        &self.slots
    }

    /// The prismatic pairs, in the order given.
    pub fn prismatic(&self) -> &[Prismatic] {
        &self.prismatic
    }

    /// The output link, if any.
    pub fn output(&self) -> Option<Pivoted> {
        self.output
    }

    /// The input angle as drawn (radians, atan2 of pivot -> tip); 0 for a linear input.
    pub fn input_angle(&self) -> f64 {
        self.theta0
    }

    /// The power of two that coordinates are divided by for solving (about the largest
    /// distance between two points of one link).
    pub fn scale(&self) -> f64 {
        self.scale
    }

    /// Gruebler's count M = 3 (links - 1) - 2 joints - slots - 2 prismatic pairs, where a
    /// point on m links is m - 1 joints. A valid scene has M = 1.
    pub fn gruebler(&self) -> i64 {
        validate::gruebler(self.links.len(), &self.point_links)
            - self.slots.len() as i64
            - 2 * self.prismatic.len() as i64
    }

    /// Number of joints (a point on m >= 2 links counts m - 1).
    pub fn joint_count(&self) -> usize {
        self.point_links.iter().map(|l| l.len().saturating_sub(1)).sum()
    }

    /// Index of a point by name.
    pub fn point_index(&self, name: &str) -> Option<usize> {
        self.names.iter().position(|n| n == name)
    }

    /// The points that define a link's angle: (pivot, tip) for the input and output links,
    /// else its first two listed points.
    pub fn angle_points(&self, link: usize) -> (usize, usize) {
        for p in [self.input, self.output].into_iter().flatten() {
            if p.link == link {
                return (p.pivot, p.tip);
            }
        }
        let pts = &self.links[link].points;
        (pts[0], pts[1])
    }

    /// Compiles the steps that solve `outputs` (point or link names; `None`: every point
    /// and link). Errors name an unknown output.
    pub fn plan(&self, outputs: Option<&[String]>) -> Result<Plan, Error> {
        let (points, links) = match outputs {
            None => ((0..self.names.len()).collect(), (0..self.links.len()).collect()),
            Some(names) => self.resolve(names)?,
        };
        plan::compile(self, &points, &links)
    }

    /// Every real assembly at input angle `theta` (every point solved). `interrupt` is
    /// asked every few thousand homotopy steps (Ctrl-C from Python).
    pub fn assemblies(
        &self,
        theta: f64,
        opts: &HomotopyOptions,
        interrupt: &dyn Interrupt,
    ) -> Result<Assemblies, Error> {
        self.plan(None)?.assemblies(theta, opts, interrupt)
    }

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

    /// The assemblies at `theta` grouped by circuit.
    pub fn circuits(
        &self,
        theta: f64,
        hopts: &HomotopyOptions,
        topts: &TraceOptions,
        interrupt: &dyn Interrupt,
    ) -> Result<(Assemblies, Vec<Circuit>), Error> {
        Tracer::new(self)?.circuits(theta, hopts, topts, interrupt)
    }

    /// Solving-frame coordinates of a point in scene coordinates.
    pub(crate) fn to_frame(&self, p: Xy) -> Xy {
        [(p[0] - self.origin[0]) / self.scale, (p[1] - self.origin[1]) / self.scale]
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

#[cfg(test)]
pub(crate) mod tests;
