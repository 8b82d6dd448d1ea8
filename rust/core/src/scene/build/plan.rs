//! The compiled plan as data: its operations, the steps shown to a user, and what a sweep
//! reports; [`Scene::plan`](crate::scene::Scene::plan) compiles one (in `compile`).

use crate::scene::ops::Op;
use crate::scene::vec2::Xy;

/// Kind of a plan step.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum StepKind {
    /// A point reached by two links from two known points (circle intersection).
    Dyad,
    /// A point reached by a link from a known point and kept on a known line
    /// (circle-line: a slider's block, a prismatic pair's point).
    Rrp,
    /// A guide turning about a known point whose line passes through a known point.
    Rpr,
    /// A point on two known lines.
    Pp,
    /// Links solved together by Newton-Raphson (no dyad reaches them).
    Group,
}

impl StepKind {
    /// "dyad", "rrp", "rpr", "pp" or "group".
    pub fn name(self) -> &'static str {
        match self {
            StepKind::Dyad => "dyad",
            StepKind::Rrp => "rrp",
            StepKind::Rpr => "rpr",
            StepKind::Pp => "pp",
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

/// A compiled plan: self-contained (it copies what it needs from the scene).
#[derive(Clone, Debug)]
pub struct Plan {
    pub(crate) ops: Vec<Op>,
    pub(crate) steps: Vec<StepInfo>,
    /// The op that opens each step (its dyad or group).
    pub(crate) step_op: Vec<usize>,
    /// Points reported, scene order.
    pub(crate) points: Vec<usize>,
    /// Links whose angles are reported, and their angle points.
    pub(crate) links: Vec<usize>,
    pub(crate) link_points: Vec<(usize, usize)>,
    /// Ground points, solving frame.
    pub(crate) fixed: Vec<(usize, Xy)>,
    pub(crate) npoints: usize,
    pub(crate) pivot: Xy,
    pub(crate) theta0: f64,
    pub(crate) scale: f64,
    pub(crate) origin: Xy,
    /// The input is a displacement (no turn repeats it: never wrapped).
    pub(crate) linear: bool,
    /// Travel limits: the motion stops where one binds.
    pub(crate) limits: Vec<crate::scene::Limit>,
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
    /// positions of every point (solving frame; a linear input at its drawn value).
    pub(crate) fn dets_at(&self, pos: &[Xy]) -> (f64, Vec<f64>) {
        let dets: Vec<f64> = self
            .step_op
            .iter()
            .map(|&i| match &self.ops[i] {
                Op::Dyad(d) => d.det_at(pos[d.p], pos[d.k1], pos[d.k2]),
                Op::Group(g) => {
                    let x = g.unknowns_from(|p| pos[p]);
                    let anchors = g.with_held(|p| pos[p], g.held_at(|p| pos[p]));
                    g.conditioning_with(&x, &anchors)
                }
                op => op.slider_det_at(0.0, pos),
            })
            .collect();
        (dets.iter().product(), dets)
    }

    /// True when some step is a group (solved by Newton with continuation).
    pub fn has_group(&self) -> bool {
        self.ops.iter().any(|o| matches!(o, Op::Group(_)))
    }

    /// True when every operation runs on the column path: closed forms (RRR dyads and the
    /// sliders' circle-line, line-line and guide-through-a-point, a linear input's fused
    /// guide), carries and the input; no group.
    pub(crate) fn columns_ok(&self) -> bool {
        self.ops.iter().all(|o| match o {
            Op::Input { .. } | Op::Dyad(_) | Op::Carry { .. } | Op::Offset { .. } => true,
            Op::StrokeCarry { .. } | Op::StrokeDyad(..) | Op::Rrp(_) | Op::Pp(_) | Op::Rpr(_) => true,
            Op::Group(_) => false,
        })
    }
}
