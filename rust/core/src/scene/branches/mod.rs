//! Branches of a scene: every assembly at one input value (`assemble`), circuits followed
//! through their dead points (`trace`), and the assemblies grouped by circuit.

mod assemble;
mod trace;

pub use assemble::{Assemblies, Assembly};
pub use trace::{Circuit, Trace, TraceOptions, Tracer};
