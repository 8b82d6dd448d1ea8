//! The one error type of the core: misuse (invalid input) only. Not converging is a
//! [`crate::Status`], never an error.

/// Invalid input, naming the offending parameter.
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
pub enum Error {
    /// A parameter has a value outside its domain.
    #[error("{name} {requirement}, got {value}")]
    InvalidParameter {
        /// Name of the parameter as the caller knows it (e.g. `r3`, `tol`, `links[4, 2]`).
        name: String,
        /// What the value must be, e.g. "must be finite and > 0".
        requirement: &'static str,
        /// The value received, formatted.
        value: String,
    },
    /// Arrays whose lengths must agree do not.
    #[error("{name} has length {got}, expected {expected}")]
    Shape {
        /// Name of the array.
        name: String,
        /// Its length.
        got: usize,
        /// The length it must have.
        expected: usize,
    },
    /// A scene (linkage drawn as data) is invalid: names the entry and says why.
    #[error("{entry}: {message}")]
    Scene {
        /// The entry as the scene file spells it, e.g. `links.crank` or `input.pivot`.
        entry: String,
        /// What is wrong with it.
        message: String,
    },
}

impl Error {
    pub(crate) fn scene(entry: impl Into<String>, message: impl Into<String>) -> Self {
        Error::Scene { entry: entry.into(), message: message.into() }
    }

    pub(crate) fn invalid(name: impl Into<String>, requirement: &'static str, value: impl std::fmt::Display) -> Self {
        Error::InvalidParameter { name: name.into(), requirement, value: value.to_string() }
    }
}

/// Checks that `value` is finite and > 0.
pub(crate) fn positive_finite(name: impl Into<String>, value: f64) -> Result<f64, Error> {
    if value.is_finite() && value > 0.0 {
        Ok(value)
    } else {
        Err(Error::invalid(name, "must be finite and > 0", value))
    }
}
