//! The page's JSON to the core's scene file format ([`planarkin_core::scene::format::Value`]):
//! conversion only (the core checks every entry and words every message, as for Python).

use planarkin_core::scene::format;
use serde_json::Value;

/// The page's JSON as the format's data (conversion only: the format checks it).
pub(super) fn value(v: &Value) -> format::Value {
    use format::Value as F;
    match v {
        Value::Null => F::Null,
        Value::Bool(b) => F::Bool(*b),
        Value::Number(n) => match (n.as_i64(), n.as_u64()) {
            (Some(i), _) => F::Int(i),
            (None, Some(u)) => F::BigInt { digits: u.to_string(), bits: u64::from(64 - u.leading_zeros()) },
            _ => F::Float(n.as_f64().unwrap_or(f64::NAN)),
        },
        Value::String(s) => F::Str(s.clone()),
        Value::Array(a) => F::List(a.iter().map(value).collect()),
        Value::Object(o) => F::Map(o.iter().map(|(k, v)| (F::Str(k.clone()), value(v))).collect()),
    }
}
