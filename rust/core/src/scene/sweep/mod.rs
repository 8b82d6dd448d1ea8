//! Sweeping a plan over input values: the entry ([`Plan::sweep`](crate::scene::Plan::sweep)),
//! the continuation solver with its predictors and step control, the column path for
//! closed-form plans (`columns`), a linear input's stroke, and the options and output.

mod buffers;
mod columns;
mod continuation;
mod entry;
mod jump;
mod limits;
mod options;
mod predict;
mod step;
mod stroke;
mod ways;
mod write;

pub use buffers::{Rates, SceneSweepBuffers};
pub use options::{ScenePredictor, SceneSweepOptions, SceneSweepOut};
