//! Any one-degree-of-freedom planar linkage of revolute joints, described as data: named
//! points drawn in one assembled pose and links as the lists of points they carry.
//! [`Scene::new`] validates it (names, geometry, mobility); [`Scene::plan`] compiles the
//! steps that the requested outputs need (dyads, rigid carries, Newton groups);
//! [`Plan::sweep`] solves them over input angles, [`Plan::assemblies`] finds every
//! assembly at one angle, and [`Tracer`] follows circuits through their dead points.
//! [`assemble_sketch`] turns `lengths` and a rough drawing into the exact pose.
//!
//! Inside, by layer: `sweep` (continuation, columns, stroke), `branches` (assemblies,
//! trace, circuits) and `gradient` are the entries; they call `build` (validation, plan,
//! sketch), which calls `ops` (one operation kind per file); `model` (the scene as data),
//! `input` (the input's kind) and `vec2` are the leaves they all share.

mod branches;
mod build;
mod gradient;
mod input;
mod model;
mod ops;
mod sweep;
mod vec2;

pub use branches::{Assemblies, Assembly, Circuit, Trace, TraceOptions, Tracer};
pub use build::{assemble_sketch, LengthSpec, Plan, Sketched, StepInfo, StepKind, MAX_SKETCH_POINTS};
pub use gradient::{Free, DET_STEP};
pub use input::{Linear, LinearKind, Pivoted};
pub use model::{Link, Prismatic, PrismaticSpec, Scene, SceneSpec, Slot, SlotSpec};
pub use sweep::{ScenePredictor, SceneSweepOptions, SceneSweepOut};
pub use vec2::Xy;

#[cfg(test)]
pub(crate) mod tests;
