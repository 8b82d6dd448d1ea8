//! The four-bar linkage: r1 ground, r2 crank (input), r3 coupler, r4 rocker (output),
//! ground O2 = (0, 0) to O4 = (r1, 0), angles in radians counter-clockwise.
//!
//! Entry points: [`FourBar`] (validated lengths, one point by Newton or the closed form,
//! velocities, limit positions), [`sweep_into`] and [`sweep`] (a continuation sweep over
//! crank angles), [`sweep_batch`] and [`closed_form_batch`] (many linkages in parallel),
//! the pointwise kernels ([`closed_form_into`], [`velocity_into`], ...), and
//! [`classify`] (Grashof and Barker). Inside, entry files (`sweep`, `batch`, `pointwise`) call the
//! row dispatcher (`row`), which calls the kernels (`scalar`, `simd`), which call the
//! per-point rules (`point`) and the model (`model`, `closed_form`, `loop_system`,
//! `options`); never back.

mod batch;
mod closed_form;
mod grashof;
mod limits;
mod loop_system;
mod model;
mod options;
mod point;
mod pointwise;
mod row;
mod scalar;
mod simd;
mod sweep;

pub use batch::{closed_form_batch, sweep_batch, validate_links};
pub use closed_form::ClosedForm;
pub use grashof::{classify, Barker, Grashof, GrashofClass};
pub use limits::{Extreme, Limits};
pub use loop_system::Loop;
pub use model::{transmission_angle, FourBar, Mode, Point};
pub use options::{default_angles, BatchOut, Method, MotionOut, Predictor, SweepOptions, SweepOut};
pub use pointwise::{acceleration_into, closed_form_into, coupler_into, transmission_into, velocity_into};
pub use sweep::{sweep, sweep_into, Sweep};

#[cfg(test)]
mod tests;
