//! A rigid group: links that no closed form reaches, solved together by the generic Newton
//! solver (a triad of a Stephenson six-bar: 4 unknowns; the double butterfly's six-link
//! group: 6), slots and prismatic pairs among them included.

use crate::scene::vec2::{sub, Xy};
use crate::{wrap_angle, Status};

/// Calls `$f::<N>(args)` for the runtime group size (even: two equations per closure).
macro_rules! dispatch {
    ($n:expr, $f:ident, $($arg:expr),*) => {
        match $n {
            2 => $f::<2>($($arg),*),
            4 => $f::<4>($($arg),*),
            6 => $f::<6>($($arg),*),
            8 => $f::<8>($($arg),*),
            10 => $f::<10>($($arg),*),
            12 => $f::<12>($($arg),*),
            n => unreachable!("group of {n} unknowns (build refuses odd sizes and more than MAX)"),
        }
    };
}

// Inside: `tree` builds a group; `solve` (Newton, placement) and `homotopy` (the
// all-solutions form) work on `equations` (the closures, their rates, the Newton system).
mod equations;
mod homotopy;
mod solve;
mod tree;

/// Most unknowns a group may have (the Newton system is sized at compile time).
pub(crate) const MAX: usize = 12;

/// How an edge turns with the linkage.
#[derive(Clone, Copy, Debug, PartialEq)]
pub(crate) enum Turn {
    /// With the unknown rotation in this column: M = (cos x_c, sin x_c).
    Col(usize),
    /// With a link whose rotation is known: M = anchor[b] - anchor[a] (group-anchor
    /// indices), the edge's vectors given as ratios to their drawn difference.
    Known(usize, usize),
}

/// The slide "column" of a linear input's own joint inside a group: its displacement is
/// the input, not an unknown (see [`Group::held`]).
pub(crate) const HELD: usize = usize::MAX;

/// An edge between two points of the group: `M (v + s d)`, s the displacement in column
/// `slide.0` (a sliding edge; [`HELD`]: the linear input's, given) or none.
#[derive(Clone, Copy, Debug, PartialEq)]
pub(crate) struct Term {
    pub turn: Turn,
    pub v: Xy,
    pub slide: Option<(usize, Xy)>,
}

impl Term {
    fn neg(self) -> Term {
        Term { v: [-self.v[0], -self.v[1]], slide: self.slide.map(|(k, d)| (k, [-d[0], -d[1]])), ..self }
    }

    /// v + s d (`held`: the linear input's displacement, for a [`HELD`] slide).
    #[inline]
    fn arm(&self, x: &[f64], held: f64) -> Xy {
        match self.slide {
            Some((HELD, d)) => [self.v[0] + held * d[0], self.v[1] + held * d[1]],
            Some((k, d)) => [self.v[0] + x[k] * d[0], self.v[1] + x[k] * d[1]],
            None => self.v,
        }
    }

    /// The rate of the slide's displacement: the unknowns' `dx`, or the input's `held`.
    #[inline]
    fn slide_rate(&self, dx: &[f64], held: f64) -> Option<(f64, Xy)> {
        match self.slide {
            Some((HELD, d)) => Some((held, d)),
            Some((k, d)) => Some((dx[k], d)),
            None => None,
        }
    }

    /// M from the columns' (cos, sin) and the anchors' values (positions, or their
    /// derivatives for a known turn's rate).
    #[inline]
    fn m(&self, cs: &[Xy], anchors: &[Xy]) -> Xy {
        match self.turn {
            Turn::Col(c) => cs[c],
            Turn::Known(a, b) => sub(anchors[b], anchors[a]),
        }
    }
}

/// A point the group solves: group point `base` (anchors first, then nodes) plus `term`.
#[derive(Clone, Debug, PartialEq)]
pub(crate) struct Node {
    pub point: usize,
    pub base: usize,
    pub term: Term,
}

/// One loop-closure pair of equations: F = a[plus] - a[minus] + sum of `terms`.
#[derive(Clone, Debug, PartialEq)]
pub(crate) struct Closure {
    pub plus: usize,
    pub minus: usize,
    pub terms: Vec<Term>,
}

/// How a column is read off positions: a rotation from two points of a link (their drawn
/// difference `drawn`), a displacement from the two ends of one of its sliding edges.
#[derive(Clone, Debug, PartialEq)]
pub(crate) enum Reader {
    Rotation { a: usize, b: usize, drawn: Xy },
    Slide { from: usize, to: usize, term: Term },
}

/// A compiled group.
#[derive(Clone, Debug, PartialEq)]
pub(crate) struct Group {
    /// Scene indices of its links (for the plan's steps).
    pub links: Vec<usize>,
    /// Rotation columns come first: columns `0..nrot` are angles, the rest displacements.
    pub nrot: usize,
    /// Scene indices of the known points it hangs from.
    pub anchors: Vec<usize>,
    /// Joints in tree order, then points carried by one group link only.
    pub nodes: Vec<Node>,
    /// How many of `nodes` are joints (the rest are carried).
    pub joints: usize,
    pub closures: Vec<Closure>,
    /// Per column, how to read it off positions.
    pub readers: Vec<Reader>,
    /// Per joint of two or more group links: (joint, a point of the first link, a point
    /// of the second). The sign of cross(a - joint, b - joint) is the joint's elbow: the
    /// assembly mode there, which changes only where the two links fall in line.
    pub elbows: Vec<(usize, usize, usize)>,
    /// Sign of the signed conditioning at the drawn pose: the branch to follow.
    pub sign: f64,
    /// The column of the input (a group of the whole linkage, as tracing builds it).
    pub input: Option<usize>,
    /// A linear input's own joint inside the group (a cylinder driving a coupler point):
    /// the (from, to) points of its edge and the edge. Its displacement is the input: the
    /// group's functions read it (and its rates) from one more anchor past its own, `[s, 0]`
    /// ([`Group::with_held`]).
    pub held: Option<(usize, usize, Term)>,
}

/// What one Newton solve of a group gives.
#[derive(Clone, Copy, Debug)]
pub(crate) struct GroupSolve {
    /// The unknowns: rotations (radians, wrapped) then displacements (solving frame).
    pub phi: [f64; MAX],
    /// d phi / d theta (NaN unless converged and anchor velocities were given).
    pub dphi: [f64; MAX],
    pub status: Status,
    pub nit: u32,
    /// Signed Hadamard ratio of the Jacobian at the solution.
    pub det: f64,
    /// (cos, sin) of the rotations in `phi` (when converged with anchor velocities given):
    /// computed once for the rates and the placement.
    pub cs: [Xy; MAX],
}

impl Group {
    /// Number of unknowns.
    #[inline]
    pub(crate) fn n(&self) -> usize {
        self.readers.len()
    }

    /// Whether column `k` is an angle (else a displacement).
    #[inline]
    pub(crate) fn is_angle(&self, k: usize) -> bool {
        k < self.nrot
    }

    /// `a - b` for column `k`: wrapped to (-pi, pi] for an angle.
    #[inline]
    pub(crate) fn gap(&self, k: usize, a: f64, b: f64) -> f64 {
        if self.is_angle(k) {
            wrap_angle(a - b)
        } else {
            a - b
        }
    }

    /// Whether the group has sliders or known turns (then it has no homotopy form).
    pub(crate) fn has_slides(&self) -> bool {
        self.n() > self.nrot
            || self.held.is_some()
            || self.closures.iter().any(|c| c.terms.iter().any(|t| matches!(t.turn, Turn::Known(..))))
    }

    /// The held displacement (or its rate) from anchors `k` that carry it past the group's
    /// own (0 for a group without one).
    #[inline]
    pub(crate) fn held_of(&self, k: &[Xy]) -> f64 {
        if self.held.is_some() {
            k[self.anchors.len()][0]
        } else {
            0.0
        }
    }

    /// The anchors' values `at` each anchor point, with the held displacement's `held`
    /// appended where the group has one.
    pub(crate) fn with_held(&self, at: impl Fn(usize) -> Xy, held: f64) -> Vec<Xy> {
        let mut out: Vec<Xy> = self.anchors.iter().map(|&p| at(p)).collect();
        if self.held.is_some() {
            out.push([held, 0.0]);
        }
        out
    }
}
