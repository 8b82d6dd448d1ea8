//! The solvers the subjects share: Newton-Raphson written once, generic over the number
//! of unknowns ([`newton`]), and every complex solution of a group's loop equations by
//! homotopy continuation ([`homotopy`]).

pub mod homotopy;
pub mod newton;
