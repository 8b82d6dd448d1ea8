//! Conversions the subjects share: numbers from a request, status names as Python spells
//! them (`planarkin.Status`), points as `[x, y]` pairs (NaN becomes `null`).

use planarkin_core::Status;
use serde_json::Value;

/// The number `key` of a request.
pub(crate) fn number(req: &Value, key: &str) -> Result<f64, String> {
    req.get(key).and_then(Value::as_f64).ok_or_else(|| format!("{key} must be a real number"))
}

/// Python's name of a status code (`planarkin.Status(code).name`).
pub(crate) fn status_name(code: i8) -> &'static str {
    match Status::ALL.into_iter().find(|s| s.code() == code) {
        Some(Status::Converged) => "CONVERGED",
        Some(Status::MaxIterations) => "MAX_ITERATIONS",
        Some(Status::NonFinite) => "NON_FINITE",
        Some(Status::Singular) => "SINGULAR",
        Some(Status::NotAssemblable) => "NOT_ASSEMBLABLE",
        Some(Status::BranchJump) => "BRANCH_JUMP",
        Some(Status::PrecisionLoss) => "PRECISION_LOSS",
        Some(Status::Limit) => "LIMIT",
        None => "UNKNOWN",
    }
}

/// A point as `[x, y]` (`null` for a coordinate that is NaN).
pub(crate) fn pair(p: [f64; 2]) -> Value {
    Value::Array(vec![p[0].into(), p[1].into()])
}
