//! Building a scene: validation ([`Scene::new`](crate::scene::Scene::new)), the plan its
//! outputs need (`plan`, `compile`), and the sketch that turns lengths and a rough drawing
//! into an exact pose (`sketch`).

mod compile;
mod plan;
mod sketch;
mod validate;

pub use plan::{Plan, StepInfo, StepKind};
pub use sketch::{assemble_sketch, LengthSpec, Sketched, MAX_SKETCH_POINTS};
