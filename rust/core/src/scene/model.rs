//! The scene as data: what a caller gives ([`SceneSpec`]) and the validated [`Scene`] with
//! its drawn and solving-frame coordinates; the leaf every other part of the scene reads.

use super::input::{Linear, LinearKind, Pivoted};
use super::vec2::Xy;

/// A link: a rigid body carrying the listed points (indices into the scene's points).
#[derive(Clone, Debug, PartialEq)]
pub struct Link {
    /// Its name in the scene.
    pub name: String,
    /// The points it carries, in the order listed.
    pub points: Vec<usize>,
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

/// A pin in a slot: `point` stays on the line through `line`'s two points (points of link
/// `guide`) at its drawn perpendicular `offset` (solving-frame units).
#[derive(Clone, Debug, PartialEq)]
pub struct Slot {
    /// Its name in the scene.
    pub name: String,
    /// The point kept on the line.
    pub point: usize,
    /// The link carrying the line.
    pub guide: usize,
    /// Two points of the guide fixing the line; its direction is line.0 -> line.1.
    pub line: (usize, usize),
    /// cross(unit direction, point - line.0) as drawn (solving frame).
    pub offset: f64,
}

/// A prismatic pair: `link` translates along `line` (two points of `guide`) and keeps its
/// drawn rotation relative to the guide.
#[derive(Clone, Debug, PartialEq)]
pub struct Prismatic {
    /// Its name in the scene.
    pub name: String,
    /// The translating link.
    pub link: usize,
    /// The link it slides in.
    pub guide: usize,
    /// Two points of the guide fixing the direction of travel (line.0 -> line.1).
    pub line: (usize, usize),
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
    pub(crate) names: Vec<String>,
    pub(crate) drawn: Vec<Xy>,
    /// (drawn - origin) / scale.
    pub(crate) xy: Vec<Xy>,
    pub(crate) origin: Xy,
    pub(crate) scale: f64,
    pub(crate) links: Vec<Link>,
    /// Links carrying each point.
    pub(crate) point_links: Vec<Vec<usize>>,
    pub(crate) ground: usize,
    /// The angle input (None for a linear one).
    pub(crate) input: Option<Pivoted>,
    pub(crate) output: Option<Pivoted>,
    pub(crate) slots: Vec<Slot>,
    pub(crate) prismatic: Vec<Prismatic>,
    pub(crate) linear: Option<Linear>,
    /// The drawn input: its angle, or 0 for a linear input (displacements are measured
    /// from the drawn pose).
    pub(crate) theta0: f64,
    /// Travel limits ([`Scene::with_limits`]; none unless given).
    pub(crate) limits: Vec<crate::scene::Limit>,
}

impl Scene {
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
        gruebler(self.links.len(), &self.point_links) - self.slots.len() as i64 - 2 * self.prismatic.len() as i64
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

    /// Solving-frame coordinates of a point in scene coordinates.
    pub(crate) fn to_frame(&self, p: Xy) -> Xy {
        [(p[0] - self.origin[0]) / self.scale, (p[1] - self.origin[1]) / self.scale]
    }
}

/// M = 3 (links - 1) - 2 joints.
pub(crate) fn gruebler(links: usize, point_links: &[Vec<usize>]) -> i64 {
    let joints: usize = point_links.iter().map(|l| l.len().saturating_sub(1)).sum();
    3 * (links as i64 - 1) - 2 * joints as i64
}
