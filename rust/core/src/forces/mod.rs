//! Forces on a scene along a sweep: statics (the input effort that holds every pose and
//! every joint reaction) and inverse dynamics (the same with the links' inertia), from a
//! plain-data description of the Newton-Euler system and its loads ([`model`]), solved
//! row by row ([`solve()`]). The Python layer builds the description itself; the browser
//! takes it from the core's scene ([`build`]).

pub mod build;
pub mod model;
pub mod solve;

#[cfg(test)]
mod tests;

pub use build::{inertia_factor, parts, pins};
pub use model::{Block, Direction, Element, Line, Loads, Mass, Model, Output, Parts, Table, UnitCouple, UnitForce};
pub use solve::{solve, Drive, Motion, Solution, DEAD_POINT};
