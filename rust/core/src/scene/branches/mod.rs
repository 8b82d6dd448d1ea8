//! Branches of a scene: every assembly at one input value (`assemble`), circuits followed
//! through their dead points (`trace`), and the assemblies grouped by circuit.

mod assemble;
mod circuits;
mod trace;

pub use assemble::{Assemblies, Assembly};
pub use circuits::Circuit;
pub use trace::{Trace, TraceOptions, Tracer};
pub(crate) use trace::{DEFAULT_MAX_POINTS, DEFAULT_STEP};
