//! The scene file format, once for every binding: its keys, the data's checks and their
//! messages (Python's words, quoting Python's `repr` of what was given), and the defaults
//! a scene is solved with. Bindings convert their data to a [`Value`] (a JSON file's text:
//! [`read_json`]) and call [`parse`].
//!
//! Inside: `value` (the data and its `repr`) is the leaf; `json` reads a file's text into
//! it; `parse` reads it into a [`SceneSpec`]; `defaults` and `output` serve what a binding
//! computes with a scene once it is built.

mod defaults;
mod json;
mod limits;
mod loads;
mod output;
mod parse;
mod value;

#[cfg(test)]
mod tests;

pub use defaults::{
    default_inputs, homotopy_options, linspace, max_step, size, sweep_options, trace_options, MAX_ITER, MAX_STEP, RUNS,
    SEED, SWEEP_LEN, TOL, TRACE_MAX_POINTS, TRACE_STEP,
};
pub use json::read_json;
pub use limits::{Bounded, LimitSpec};
pub use loads::{Center, Element, Loads, Mass, Profile, Target, Units, LOAD_KEYS};
pub use output::linear_output;
pub use parse::{kind_name, parse};
pub use value::{float_repr, str_repr, Describe, Described, Foreign, Like, Value};

use crate::error::Error;
use crate::interrupt::Interrupt;
use crate::scene::{assemble_sketch, LengthSpec, LinearKind, SceneSpec};

/// The keys a scene may have, in the order messages list them.
pub const KEYS: [&str; 14] = [
    "name",
    "description",
    "units",
    "points",
    "links",
    "ground",
    "input",
    "output",
    "outputs",
    "slots",
    "prismatic",
    "lengths",
    "loads",
    "limits",
];
/// The keys a scene must have.
pub const REQUIRED: [&str; 4] = ["points", "links", "ground", "input"];
/// Deepest nesting of lists and mappings a scene's data may have. A scene's own is 4 (the
/// scene, "slots", one slot, its "line"); the bound keeps every walk of the data shallow,
/// and a binding need convert no deeper than one level past it.
pub const MAX_DEPTH: usize = 16;

/// An input or output as the file gives it.
#[derive(Clone, Debug, PartialEq, Eq)]
pub enum Drive {
    /// A link's angle about its ground pivot.
    Angle {
        /// The link.
        link: String,
        /// Its ground pivot.
        pivot: String,
    },
    /// The displacement along a slot or prismatic pair.
    Linear {
        /// Slot or prismatic pair.
        kind: LinearKind,
        /// Its name.
        name: String,
    },
}

/// A scene's data read: the core's spec and what the spec does not hold.
#[derive(Clone, Debug)]
pub struct Parsed {
    /// What [`Scene::new`](crate::scene::Scene::new) (or a sketch's assembly) takes; an
    /// output along a slot or prismatic pair is not in it.
    pub spec: SceneSpec,
    /// `name`, if given.
    pub name: Option<String>,
    /// `description`, if given.
    pub description: Option<String>,
    /// `units`, if given: the length unit (the string, or the table's `length`).
    pub units: Option<String>,
    /// `units` when given as a table (length, force, mass).
    pub unit_table: Option<Units>,
    /// `loads`, if given, checked against the scene's names.
    pub loads: Option<Loads>,
    /// `limits` (empty if not given), names checked; [`Scene::with_limits`](crate::scene::Scene::with_limits)
    /// resolves them.
    pub limits: Vec<LimitSpec>,
    /// The input as the file gives it.
    pub input: Drive,
    /// The output as the file gives it, if any.
    pub output: Option<Drive>,
    /// The names requested by default (`outputs`), unchecked (a plan checks them).
    pub outputs: Option<Vec<String>>,
    /// A sketch's lengths (name, name, distance), unchecked (the sketch checks them).
    pub lengths: Option<Vec<LengthSpec>>,
}

impl Parsed {
    /// A sketch's exact pose: with `lengths`, every point moves to the nearest exact
    /// assembly ([`assemble_sketch`]) and the spec holds that pose; returns how far each
    /// point moved (None for data without `lengths`, which is left as it is). Every
    /// binding loads a scene as parse, this, then [`Scene::new`](crate::scene::Scene::new).
    pub fn assemble(&mut self, interrupt: &dyn Interrupt) -> Result<Option<Vec<f64>>, Error> {
        let Some(lengths) = &self.lengths else { return Ok(None) };
        let exact = assemble_sketch(self.spec.clone(), lengths, interrupt)?;
        for (p, xy) in self.spec.points.iter_mut().zip(exact.points) {
            p.1 = xy;
        }
        Ok(Some(exact.moved))
    }
}
