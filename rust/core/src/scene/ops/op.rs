//! [`Op`], one operation of a compiled plan, and the points each kind reads and solves:
//! the one dispatch over the operation kinds of this folder.

use super::dyad::Dyad;
use super::group::Group;
use super::slide::{LineLine, Rpr, Rrp};
use crate::scene::vec2::Xy;

/// One operation of the compiled plan.
#[derive(Clone, Debug, PartialEq)]
pub(crate) enum Op {
    /// A point of the input link: pivot + lam u + mu perp(u), u = (cos theta, sin theta).
    Input {
        q: usize,
        lam: f64,
        mu: f64,
    },
    Dyad(Dyad),
    /// q = a + m (b - a), m the complex ratio (q - a) / (b - a) as drawn: a rigid link
    /// with two known points carries its others.
    Carry {
        q: usize,
        a: usize,
        b: usize,
        m: Xy,
    },
    Group(Box<Group>),
    /// q = a + m(s) (b - a) on a linear input's guide fused with what slides in it, m(s) =
    /// (num0 + s num1) / (den0 + s den1) (complex): the body shape changes with the input s.
    StrokeCarry {
        q: usize,
        a: usize,
        b: usize,
        num: [Xy; 2],
        den: [Xy; 2],
    },
    /// An RRR dyad on the fused guide: arm i has length |arm_i.0 + s arm_i.1|.
    StrokeDyad(Dyad, [[Xy; 2]; 2]),
    Rrp(Rrp),
    Pp(LineLine),
    Rpr(Rpr),
    /// q = base + m (b - a): a link whose rotation is known (that of the link carrying a
    /// and b, its prismatic partner) and one of whose points is known.
    Offset {
        q: usize,
        base: usize,
        a: usize,
        b: usize,
        m: Xy,
    },
}

impl Op {
    pub(crate) fn inputs(&self) -> Vec<usize> {
        match self {
            Op::Input { .. } => Vec::new(),
            Op::Dyad(d) => vec![d.k1, d.k2],
            Op::Carry { a, b, .. } | Op::StrokeCarry { a, b, .. } => vec![*a, *b],
            Op::Group(g) => g.anchors.clone(),
            Op::StrokeDyad(d, _) => vec![d.k1, d.k2],
            Op::Rrp(r) => [vec![r.k], r.line.inputs().to_vec()].concat(),
            Op::Pp(l) => [l.lines[0].inputs(), l.lines[1].inputs()].concat(),
            Op::Rpr(r) => vec![r.k, r.q],
            Op::Offset { base, a, b, .. } => vec![*base, *a, *b],
        }
    }

    pub(crate) fn outputs(&self) -> Vec<usize> {
        match self {
            Op::Input { q, .. } | Op::Carry { q, .. } | Op::StrokeCarry { q, .. } | Op::Offset { q, .. } => vec![*q],
            Op::Dyad(d) | Op::StrokeDyad(d, _) => vec![d.p],
            Op::Rrp(r) => vec![r.p],
            Op::Pp(l) => vec![l.p],
            Op::Rpr(r) => vec![r.t],
            Op::Group(g) => g.nodes.iter().map(|n| n.point).collect(),
        }
    }
}
