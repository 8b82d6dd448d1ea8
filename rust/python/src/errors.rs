//! The one place core errors become Python exceptions, and the interrupt that lets a
//! kernel call answer Ctrl-C.

use std::sync::Mutex;

use planarkin_core::interrupt::Interrupt;
use planarkin_core::Error;
use pyo3::exceptions::{PyKeyboardInterrupt, PyMemoryError, PyValueError};
use pyo3::prelude::*;

/// Invalid input is ValueError, an output too large MemoryError, an interruption
/// KeyboardInterrupt (use [`Signals::err`] to re-raise what the signal handler raised).
pub(crate) fn err(e: Error) -> PyErr {
    match e {
        Error::Allocation { .. } => PyMemoryError::new_err(e.to_string()),
        Error::Interrupted => PyKeyboardInterrupt::new_err("interrupted"),
        _ => PyValueError::new_err(e.to_string()),
    }
}

/// [`err`] of an [`Error::Array`]: the binding's own checks of an array argument (shape,
/// layout, writability) go through the same map as the kernels' errors.
pub(crate) fn array(name: &str, requirement: impl Into<String>) -> PyErr {
    err(Error::array(name, requirement))
}

/// The kernels' [`Interrupt`]: re-attaches to Python and runs its signal handlers
/// (`py.check_signals()`); the exception a handler raised (KeyboardInterrupt for Ctrl-C)
/// is kept and raised once the kernel has stopped.
#[derive(Default)]
pub(crate) struct Signals {
    raised: Mutex<Option<PyErr>>,
}

impl Interrupt for Signals {
    fn interrupted(&self) -> bool {
        match Python::attach(|py| py.check_signals()) {
            Ok(()) => false,
            Err(e) => {
                *self.raised.lock().unwrap_or_else(|p| p.into_inner()) = Some(e);
                true
            }
        }
    }
}

impl Signals {
    /// Runs `work` with the GIL released and this interrupt polled by the kernel; maps its
    /// error, re-raising the signal handler's own exception after an interruption.
    pub(crate) fn detach<T: Send>(
        py: Python<'_>,
        work: impl FnOnce(&Signals) -> Result<T, Error> + Send,
    ) -> PyResult<T> {
        let signals = Signals::default();
        py.detach(|| work(&signals)).map_err(|e| signals.err(e))
    }

    fn err(&self, e: Error) -> PyErr {
        match e {
            Error::Interrupted => {
                self.raised.lock().unwrap_or_else(|p| p.into_inner()).take().unwrap_or_else(|| err(e))
            }
            e => err(e),
        }
    }
}
