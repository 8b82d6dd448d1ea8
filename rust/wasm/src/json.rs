//! Conversions the subjects share: numbers from a request, status names as Python spells
//! them (`planarkin.Status`), points as `[x, y]` pairs (NaN becomes `null`).

use planarkin_core::Status;
use serde_json::Value;

/// The number `key` of a request.
pub(crate) fn number(req: &Value, key: &str) -> Result<f64, String> {
    req.get(key).and_then(Value::as_f64).ok_or_else(|| format!("{key} must be a real number"))
}

/// The core's name of a status code (`planarkin.Status(code).name` in Python).
pub(crate) fn status_name(code: i8) -> &'static str {
    Status::from_code(code).map_or("UNKNOWN", Status::name)
}

/// A point as `[x, y]` (`null` for a coordinate that is NaN).
pub(crate) fn pair(p: [f64; 2]) -> Value {
    Value::Array(vec![p[0].into(), p[1].into()])
}
