//! The operations a plan is made of, one kind per file: RRR dyads (`dyad`), the sliders'
//! closed forms (`slide`), rigid groups solved together (`group`), and what every kind
//! computes at an input value (`eval`); [`Op`] (in `op`) is the one dispatch over them.

mod dyad;
mod eval;
mod group;
mod op;
mod slide;

pub(crate) use dyad::{closed_form, Dyad, DyadOut, APART, COINCIDE, SOLVED};
pub(crate) use eval::Known;
pub(crate) use group::{Group, GroupSolve, MAX};
pub(crate) use op::Op;
pub(crate) use slide::{Line, LineLine, Rpr, Rrp};
