//! Python data to the core's scene file format ([`planarkin_core::scene::format::Value`]):
//! conversion only, one pass, no checks (the core checks every entry and words every
//! message). What has no plain counterpart (NumPy scalars and arrays, other mappings, any
//! object) is kept as a foreign value whose `repr` is asked only if a message quotes it.

use numpy::{PyUntypedArray, PyUntypedArrayMethods};
use planarkin_core::scene::format::{self, Describe, Like, Value, MAX_DEPTH};
use pyo3::prelude::*;
use pyo3::types::{PyBool, PyBytes, PyComplex, PyDict, PyFloat, PyInt, PyList, PyMapping, PyString, PyTuple};

/// A Python object the format quotes by its own `repr`, `str` and type name.
struct Foreign(Py<PyAny>);

impl Describe for Foreign {
    fn repr(&self) -> String {
        Python::attach(|py| self.0.bind(py).repr().map(|s| s.to_string()).unwrap_or_else(|_| "<?>".into()))
    }
    fn type_name(&self) -> String {
        Python::attach(|py| self.0.bind(py).get_type().name().map(|s| s.to_string()).unwrap_or_else(|_| "?".into()))
    }
    fn str(&self) -> String {
        Python::attach(|py| self.0.bind(py).str().map(|s| s.to_string()).unwrap_or_else(|_| "<?>".into()))
    }
}

fn foreign(v: &Bound<'_, PyAny>, like: Like) -> Value {
    Value::foreign(Foreign(v.clone().unbind()), like)
}

/// The items of a list, tuple or any iterable, converted one level deeper.
fn items<'py>(it: impl Iterator<Item = Bound<'py, PyAny>>, depth: usize) -> PyResult<Vec<Value>> {
    it.map(|x| value_of(&x, depth + 1)).collect()
}

fn entries<'py>(
    it: impl Iterator<Item = (Bound<'py, PyAny>, Bound<'py, PyAny>)>,
    depth: usize,
) -> PyResult<Vec<(Value, Value)>> {
    it.map(|(k, v)| Ok((value_of(&k, depth + 1)?, value_of(&v, depth + 1)?))).collect()
}

/// A real number as `float()` reads it for the format: not a string, bytes, bool or a
/// complex number (NumPy's `bool` and complex scalars included); None otherwise.
fn real(v: &Bound<'_, PyAny>) -> Option<f64> {
    if v.is_instance_of::<PyBytes>() || v.is_instance_of::<PyComplex>() {
        return None;
    }
    if let Ok(dtype) = v.getattr("dtype") {
        let kind: Option<String> = dtype.getattr("kind").and_then(|k| k.extract()).ok();
        if matches!(kind.as_deref(), Some("b" | "c")) {
            return None;
        }
    }
    let f = v.py().get_type::<PyFloat>().call1((v,)).ok()?;
    f.extract::<f64>().ok()
}

/// `v` (at nesting `depth`, the scene itself 1) as the format's data. Lists and mappings
/// deeper than one level past [`MAX_DEPTH`] are left empty: the core refuses them by
/// their depth before it reads anything in them.
pub(super) fn value_of(v: &Bound<'_, PyAny>, depth: usize) -> PyResult<Value> {
    let deep = depth > MAX_DEPTH;
    if v.is_exact_instance_of::<PyFloat>() {
        return Ok(Value::Float(v.extract()?));
    }
    if let Ok(f) = v.cast::<PyFloat>() {
        // a float subclass (NumPy's float64): its value, its own repr
        return Ok(foreign(v, Like::Real(f.value())));
    }
    if let Ok(s) = v.cast::<PyString>() {
        return Ok(Value::Str(s.to_str()?.to_owned()));
    }
    if v.is_none() {
        return Ok(Value::Null);
    }
    if v.is_exact_instance_of::<PyBool>() {
        return Ok(Value::Bool(v.extract()?));
    }
    if v.is_exact_instance_of::<PyInt>() {
        return Ok(match v.extract::<i64>() {
            Ok(i) => Value::Int(i),
            Err(_) => Value::BigInt { digits: v.repr()?.to_string(), bits: v.call_method0("bit_length")?.extract()? },
        });
    }
    if let Ok(l) = v.cast::<PyList>() {
        return Ok(Value::List(if deep { Vec::new() } else { items(l.iter(), depth)? }));
    }
    if let Ok(t) = v.cast::<PyTuple>() {
        return Ok(Value::Tuple(if deep { Vec::new() } else { items(t.iter(), depth)? }));
    }
    if let Ok(d) = v.cast_exact::<PyDict>() {
        return Ok(Value::Map(if deep { Vec::new() } else { entries(d.iter(), depth)? }));
    }
    if let Ok(a) = v.cast::<PyUntypedArray>() {
        // an array may give a point's coordinates; 0-d: a number
        if a.ndim() == 0 {
            return Ok(foreign(v, real(v).map_or(Like::Nothing, Like::Real)));
        }
        let list =
            if deep { Vec::new() } else { items(v.try_iter()?.collect::<PyResult<Vec<_>>>()?.into_iter(), depth)? };
        return Ok(foreign(v, Like::Array(list)));
    }
    if let Ok(m) = v.cast::<PyMapping>() {
        let pairs = if deep {
            Vec::new()
        } else {
            let list = m.items()?;
            let pairs: Vec<(Bound<'_, PyAny>, Bound<'_, PyAny>)> =
                list.iter().map(|kv| kv.extract()).collect::<PyResult<_>>()?;
            entries(pairs.into_iter(), depth)?
        };
        return Ok(foreign(v, Like::Map(pairs)));
    }
    Ok(foreign(v, real(v).map_or(Like::Nothing, Like::Real)))
}

/// Plain data the core wrote (the normalised `loads` and `units` tables) as Python's
/// dicts, lists, floats and strings.
pub(super) fn to_py<'py>(py: Python<'py>, v: &Value) -> PyResult<Bound<'py, PyAny>> {
    Ok(match v {
        Value::Null => py.None().into_bound(py),
        Value::Bool(b) => PyBool::new(py, *b).to_owned().into_any(),
        Value::Int(i) => i.into_pyobject(py)?.into_any(),
        Value::Float(x) => PyFloat::new(py, *x).into_any(),
        Value::Str(t) => PyString::new(py, t).into_any(),
        Value::List(l) | Value::Tuple(l) => {
            PyList::new(py, l.iter().map(|x| to_py(py, x)).collect::<PyResult<Vec<_>>>()?)?.into_any()
        }
        Value::Map(m) => {
            let d = PyDict::new(py);
            for (k, x) in m {
                d.set_item(to_py(py, k)?, to_py(py, x)?)?;
            }
            d.into_any()
        }
        Value::BigInt { digits, .. } => PyString::new(py, digits).into_any(),
        Value::Foreign(_) => py.None().into_bound(py),
    })
}

/// Adds the scene format's keys and defaults (written once, in the core) to the module.
pub(super) fn register(m: &Bound<'_, PyModule>) -> PyResult<()> {
    m.add("SCENE_KEYS", format::KEYS.to_vec())?;
    m.add("SCENE_REQUIRED", format::REQUIRED.to_vec())?;
    m.add("SCENE_MAX_DEPTH", format::MAX_DEPTH)?;
    m.add("TOL", format::TOL)?;
    m.add("MAX_ITER", format::MAX_ITER)?;
    m.add("MAX_STEP", format::MAX_STEP)?;
    m.add("SEED", format::SEED)?;
    m.add("RUNS", format::RUNS)?;
    m.add("TRACE_STEP", format::TRACE_STEP)?;
    m.add("TRACE_MAX_POINTS", format::TRACE_MAX_POINTS)?;
    m.add("SWEEP_LEN", format::SWEEP_LEN)?;
    Ok(())
}
