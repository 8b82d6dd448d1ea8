//! What the atlas's kernels hand each other: a solved pose and a coupler curve.

use crate::scene::Xy;

/// Most points of any topology's pose.
pub const MAX_POINTS: usize = 8;

/// A solved pose: the points (in the order [`super::pose_names`] gives), the tracer's index
/// among them, and the worst transmission sine of its dyads.
#[derive(Clone, Copy, Debug)]
pub struct Pose {
    /// The points; only the first `count` are set.
    pub points: [Xy; MAX_POINTS],
    /// How many points.
    pub count: usize,
    /// The smallest sine of a dyad's transmission angle (0 at a dead point).
    pub conditioning: f64,
}

impl Pose {
    /// The tracer point (the last one).
    pub fn tracer(&self) -> Xy {
        self.points[self.count - 1]
    }
}

/// A coupler curve: `points` at the input angles `theta` (increasing); `closed` where the
/// input turns fully (the last point then joins the first).
#[derive(Clone, Debug)]
pub struct Curve {
    /// The tracer's positions.
    pub points: Vec<Xy>,
    /// The input angles (radians, increasing, within one turn of the first).
    pub theta: Vec<f64>,
    /// The input turns fully.
    pub closed: bool,
    /// The smallest transmission sine over the points.
    pub conditioning: f64,
}
