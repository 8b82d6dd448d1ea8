//! Forces on a scene along a sweep: statics (the input effort that holds every pose and
//! every joint reaction) and inverse dynamics (the same with the links' inertia), from a
//! plain-data description of the Newton-Euler system and its loads ([`model`]), solved
//! row by row ([`solve`]). The Python layer and the browser build the description.

pub mod model;
pub mod solve;

#[cfg(test)]
mod tests;

pub use model::{Block, Direction, Element, Line, Loads, Mass, Model, Output, Parts, Table, UnitCouple, UnitForce};
pub use solve::{solve, Drive, Motion, Solution, DEAD_POINT};
