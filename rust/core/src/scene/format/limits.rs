//! The format's `limits` key: travel limits of slots and prismatic pairs (their
//! displacement, in length units, measured as a linear input's is) and of revolute joints
//! (the relative angle of two links, radians, as drawn = 0), each as [lo, hi] around the
//! drawn pose. Names and ranges are checked here; which links share a joint, the scene's.

use super::value::{real, Value};
use crate::error::Error;

fn fail<T>(entry: impl Into<String>, message: impl Into<String>) -> Result<T, Error> {
    Err(Error::scene(entry, message))
}

/// What a limit bounds, by name.
#[derive(Clone, Debug, PartialEq, Eq)]
pub enum Bounded {
    /// The displacement along the slot or prismatic pair of this name.
    Joint(String),
    /// The relative angle of two links (the second's turn relative to the first).
    Angle(String, String),
}

/// One entry of `limits`: its name, what it bounds and the range [lo, hi] (lo <= 0 <= hi:
/// the drawn pose lies inside).
#[derive(Clone, Debug, PartialEq)]
pub struct LimitSpec {
    /// The entry's key.
    pub name: String,
    /// What it bounds.
    pub bounded: Bounded,
    /// The range, lo < hi.
    pub range: (f64, f64),
}

impl LimitSpec {
    /// The entry as the file writes it.
    pub fn to_value(&self) -> Value {
        let range = Value::List(vec![Value::Float(self.range.0), Value::Float(self.range.1)]);
        match &self.bounded {
            Bounded::Joint(_) => range,
            Bounded::Angle(a, b) => Value::Map(vec![
                (Value::Str("links".into()), Value::List(vec![Value::Str(a.clone()), Value::Str(b.clone())])),
                (Value::Str("range".into()), range),
            ]),
        }
    }
}

/// A range [lo, hi] with lo < hi, both finite, the drawn pose (0) inside.
fn range(entry: &str, v: &Value) -> Result<(f64, f64), Error> {
    let Some([lo, hi]) = v.as_list().and_then(|l| <&[Value; 2]>::try_from(l).ok()) else {
        return fail(entry, format!("must be a range [lo, hi], got {}", v.repr()));
    };
    let (lo, hi) = (real(&format!("{entry}[0]"), lo)?, real(&format!("{entry}[1]"), hi)?);
    if !(lo.is_finite() && hi.is_finite()) {
        return fail(entry, format!("must be finite, got [{lo}, {hi}]"));
    }
    if !(lo < hi) {
        return fail(entry, format!("must have lo < hi, got [{lo}, {hi}]"));
    }
    if !(lo <= 0.0 && 0.0 <= hi) {
        return fail(entry, format!("must hold the drawn pose (0: limits are measured from it), got [{lo}, {hi}]"));
    }
    Ok((lo, hi))
}

/// `limits`, if given: each key a slot or prismatic pair's name with its range, or any
/// name with `{"links": [a, b], "range": [lo, hi]}`. `joints` are the slots' and prismatic
/// pairs' names, `links` the links'.
pub(super) fn limits(v: Option<&Value>, joints: &[String], links: &[String]) -> Result<Vec<LimitSpec>, Error> {
    let Some(v) = v else { return Ok(Vec::new()) };
    let Some(table) = v.as_map() else {
        return fail("limits", format!("must be a table name -> [lo, hi] or {{links, range}}, got {}", v.repr()));
    };
    let mut out = Vec::with_capacity(table.len());
    for (k, v) in table {
        let name = k.str();
        let e = format!("limits.{name}");
        if let Some(t) = v.as_map() {
            let keys: Vec<String> = t.iter().map(|(k, _)| k.str()).collect();
            if keys.len() != 2 || !keys.iter().all(|k| k == "links" || k == "range") {
                return fail(e, format!("must have the keys 'links' and 'range', got {}", v.repr()));
            }
            let get = |key: &str| t.iter().find(|(k, _)| k.as_str() == Some(key)).map(|(_, v)| v);
            let pair = get("links").and_then(|l| l.as_list()).filter(|l| l.len() == 2);
            let names: Option<Vec<String>> =
                pair.map(|l| l.iter().filter_map(|x| x.as_str().map(str::to_owned)).collect());
            let Some([a, b]) = names.and_then(|n| <[String; 2]>::try_from(n).ok()) else {
                return fail(
                    format!("{e}.links"),
                    format!(
                        "must be a pair of link names, got {}",
                        get("links").map_or("nothing".into(), |x| x.repr())
                    ),
                );
            };
            for l in [&a, &b] {
                if !links.contains(l) {
                    return fail(format!("{e}.links"), format!("{l:?} is not a link"));
                }
            }
            if a == b {
                return fail(format!("{e}.links"), format!("must be two different links, got {a:?} twice"));
            }
            let r = range(&format!("{e}.range"), get("range").expect("keys checked"))?;
            out.push(LimitSpec { name, bounded: Bounded::Angle(a, b), range: r });
        } else {
            if !joints.contains(&name) {
                return fail(
                    e,
                    "names no slot or prismatic pair (a revolute joint's limit is {\"links\": [a, b], \"range\": [lo, hi]})",
                );
            }
            let r = range(&e, v)?;
            out.push(LimitSpec { name: name.clone(), bounded: Bounded::Joint(name), range: r });
        }
    }
    Ok(out)
}
