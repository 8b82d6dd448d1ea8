//! Any one-degree-of-freedom planar linkage described as data: [`Scene`] validates it,
//! [`Plan`] is what its outputs need, [`Plan::sweep`] solves it over the input, and
//! [`Plan::assemblies`], [`Tracer`] and [`assemble_sketch`] find its branches and poses.

// Layers, each calling only those below it: the entries `sweep` (continuation, columns,
// stroke; it asks `branches` for the assemblies where it stops), `branches` (assemblies,
// trace, circuits) and `gradient`; then `build` (validation, plan, sketch); then `ops`
// (one operation kind per file); beside them `format` (the file format and its defaults,
// which the bindings call); the leaves `model` (the scene as data), `input` (the
// input's kind) and `vec2`.
mod branches;
mod build;
pub mod format;
mod gradient;
mod input;
mod limits;
mod model;
mod ops;
mod sweep;
mod vec2;

pub use branches::{Assemblies, Assembly, Circuit, Trace, TraceOptions, Tracer};
pub use build::{assemble_sketch, LengthSpec, Plan, Sketched, StepInfo, StepKind, MAX_SKETCH_POINTS};
pub use gradient::{Free, DET_STEP};
pub use input::{Linear, LinearKind, Pivoted};
pub use limits::{Coordinate, Limit};
pub use model::{Link, Prismatic, PrismaticSpec, Scene, SceneSpec, Slot, SlotSpec};
pub use sweep::{Rates, ScenePredictor, SceneSweepBuffers, SceneSweepOptions, SceneSweepOut};
pub use vec2::Xy;

#[cfg(test)]
pub(crate) mod tests;
