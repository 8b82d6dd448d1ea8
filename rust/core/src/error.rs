//! The one error type of the core: misuse (invalid input), an output too large to
//! allocate, or an interruption the caller asked for. Not converging is a
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
    /// An array argument whose shape or memory layout a kernel cannot take (a binding's
    /// check on what it was handed, e.g. `links must be a C-contiguous float64 array`).
    #[error("{name} {requirement}")]
    Array {
        /// Name of the array as the caller knows it.
        name: String,
        /// What it must be, with what it is where that helps.
        requirement: String,
    },
    /// A scene (linkage drawn as data) is invalid: names the entry and says why.
    #[error("{entry}: {message}")]
    Scene {
        /// The entry as the scene file spells it, e.g. `links.crank` or `input.pivot`.
        entry: String,
        /// What is wrong with it.
        message: String,
    },
    /// An output too large to allocate: raised before any work, naming the sizes.
    #[error("{what}: cannot allocate {bytes} bytes")]
    Allocation {
        /// What was being allocated, with its dimensions (e.g. "5 arrays of 1000 x 100000000").
        what: String,
        /// Bytes asked for (saturating).
        bytes: u128,
    },
    /// The caller's [`crate::interrupt::Interrupt`] asked the computation to stop.
    #[error("interrupted")]
    Interrupted,
}

impl Error {
    pub(crate) fn scene(entry: impl Into<String>, message: impl Into<String>) -> Self {
        Error::Scene { entry: entry.into(), message: message.into() }
    }

    /// An [`Error::Array`] naming the array `name` and what it must be.
    pub fn array(name: impl Into<String>, requirement: impl Into<String>) -> Self {
        Error::Array { name: name.into(), requirement: requirement.into() }
    }

    pub(crate) fn invalid(name: impl Into<String>, requirement: &'static str, value: impl std::fmt::Display) -> Self {
        Error::InvalidParameter { name: name.into(), requirement, value: value.to_string() }
    }
}

/// Numbers whose all-zero bits are their zero: a buffer of them can come zeroed from the
/// allocator (`calloc`), which does not write pages fresh from the system a second time.
///
/// # Safety
/// The all-zero bit pattern must be a valid value of the type.
pub unsafe trait Zeroed: Copy {}

// SAFETY: all zero bits are 0 (or 0.0) for each of these, and for a pair of them.
unsafe impl Zeroed for f64 {}
unsafe impl Zeroed for i8 {}
unsafe impl Zeroed for f32 {}
unsafe impl Zeroed for u32 {}
unsafe impl Zeroed for (f64, f64) {}

/// A vector of `len` zeros, allocated fallibly: an [`Error::Allocation`] naming `what`
/// instead of an abort when the memory is not there.
pub fn try_zeros<T: Zeroed>(what: impl FnOnce() -> String, len: usize) -> Result<Vec<T>, Error> {
    try_zeros_advised(what, len, |_| {})
}

/// [`try_zeros`] that hands the buffer to `advise` before anything writes to it (a caller
/// that knows the operating system may ask for its memory policy there, as the Python
/// bindings ask for huge pages).
pub fn try_zeros_advised<T: Zeroed>(
    what: impl FnOnce() -> String,
    len: usize,
    advise: impl FnOnce(&mut Vec<T>),
) -> Result<Vec<T>, Error> {
    let size = std::mem::size_of::<T>();
    if len == 0 || size == 0 {
        return Ok(Vec::new());
    }
    let fail = || Error::Allocation { what: what(), bytes: len as u128 * size as u128 };
    let Ok(layout) = std::alloc::Layout::array::<T>(len) else { return Err(fail()) };
    // SAFETY: the layout's size is not zero (len > 0, T not zero-sized).
    let ptr = unsafe { std::alloc::alloc_zeroed(layout) }.cast::<T>();
    if ptr.is_null() {
        return Err(fail());
    }
    // SAFETY: `ptr` comes from the global allocator with the layout of `len` values of T,
    // all of whose bits are zero, a valid T (`Zeroed`); the vector owns it from here.
    let mut v = unsafe { Vec::from_raw_parts(ptr, len, len) };
    advise(&mut v);
    Ok(v)
}

/// Makes room for `additional` more values in `v`, fallibly: an [`Error::Allocation`]
/// naming `what` (and the bytes the grown vector needs) instead of an abort.
pub(crate) fn try_grow<T>(v: &mut Vec<T>, additional: usize, what: impl FnOnce() -> String) -> Result<(), Error> {
    v.try_reserve(additional).map_err(|_| Error::Allocation {
        what: what(),
        bytes: (v.len() as u128 + additional as u128) * std::mem::size_of::<T>() as u128,
    })
}

/// Checks that `value` is finite and > 0.
pub(crate) fn positive_finite(name: impl Into<String>, value: f64) -> Result<f64, Error> {
    if value.is_finite() && value > 0.0 {
        Ok(value)
    } else {
        Err(Error::invalid(name, "must be finite and > 0", Real(value)))
    }
}

/// Checks that `value` is finite.
pub(crate) fn finite(name: impl Into<String>, value: f64) -> Result<f64, Error> {
    if value.is_finite() {
        Ok(value)
    } else {
        Err(Error::invalid(name, "must be finite", Real(value)))
    }
}

/// A real number in a message, written as Python writes it (`repr`): the shortest digits
/// that round-trip, an exponent of two digits or more with its sign (`1e-09`, `1e+16`),
/// `nan`, `inf`. The core's messages then read the same as the Python layer's and the
/// NumPy reference's.
#[derive(Clone, Copy, Debug)]
pub struct Real(pub f64);

impl std::fmt::Display for Real {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        let x = self.0;
        if x.is_nan() {
            return f.write_str("nan");
        }
        if x.is_infinite() {
            return f.write_str(if x > 0.0 { "inf" } else { "-inf" });
        }
        // Debug is the shortest round-trip form, exponential outside [1e-4, 1e16) as in Python
        let s = format!("{x:?}");
        match s.split_once('e') {
            Some((mantissa, exp)) => {
                let (sign, digits) = exp.strip_prefix('-').map_or(("+", exp), |d| ("-", d));
                write!(f, "{mantissa}e{sign}{digits:0>2}")
            }
            None => f.write_str(&s),
        }
    }
}

/// A string in a message, quoted as Python's `repr` quotes a plain string.
pub(crate) fn quoted(s: &str) -> String {
    format!("'{s}'")
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn reals_read_as_python_writes_them() {
        // the strings Python's repr() gives for the same doubles
        for (x, py) in [
            (1.0, "1.0"),
            (-1e-9, "-1e-09"),
            (1e16, "1e+16"),
            (1.5e-300, "1.5e-300"),
            (0.0001, "0.0001"),
            (123456.0, "123456.0"),
            (f64::NAN, "nan"),
            (f64::NEG_INFINITY, "-inf"),
            (5e-324, "5e-324"),
        ] {
            assert_eq!(Real(x).to_string(), py);
        }
        assert_eq!(positive_finite("tol", -1e-9).unwrap_err().to_string(), "tol must be finite and > 0, got -1e-09");
    }

    #[test]
    fn advice_sees_the_zeroed_buffer_before_the_caller_writes_it() {
        let mut seen = None;
        let v: Vec<f64> = try_zeros_advised(
            || "x".into(),
            1000,
            |v: &mut Vec<f64>| seen = Some((v.len(), v.capacity(), v.iter().all(|x| x.to_bits() == 0))),
        )
        .unwrap();
        assert_eq!(seen, Some((1000, 1000, true)));
        assert!(v.len() == 1000 && v.iter().all(|x| *x == 0.0));
        let pairs: Vec<(f64, f64)> = try_zeros(|| "pairs".into(), 3).unwrap();
        assert_eq!(pairs, vec![(0.0, 0.0); 3]);
        assert!(try_zeros::<i8>(|| "none".into(), 0).unwrap().is_empty());
        let e = try_zeros_advised::<f64>(|| "huge".into(), usize::MAX / 4, |_| panic!("not reserved")).unwrap_err();
        assert!(matches!(e, Error::Allocation { .. }), "{e}");
    }
}
