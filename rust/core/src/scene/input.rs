//! The input's kind: an angle (a ground-pivoted link, [`Pivoted`]) or a displacement (a
//! slot or prismatic pair, [`Linear`]); the output link is a [`Pivoted`] too.

use super::vec2::Xy;

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
