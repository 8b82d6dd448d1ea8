//! The atlas for the page's "draw a path" mode (the core's `atlas`, as `rust/python`'s
//! `atlas.rs` binds it): a shard of entries, a curve's descriptor, the placement of many
//! candidates onto a target, and an entry's pose. Convert and map errors; nothing numeric.

use planarkin_core::atlas::{
    build_shard, describe, match_many, pose, pose_names, Search, Topology, DESCRIPTOR, SAMPLES,
};
use planarkin_core::scene::Xy;
use planarkin_core::{Error, Never};
use serde_json::{json, Value};

use crate::json::{number, pair};

fn err(e: Error) -> String {
    e.to_string()
}

/// The topology named by the request's `topology` (default "four-bar").
fn topology(req: &Value) -> Result<Topology, String> {
    let name = match req.get("topology") {
        None => "four-bar",
        Some(v) => v.as_str().ok_or("topology must be a name")?,
    };
    Topology::from_name(name).map_err(err)
}

/// The non-negative integer `key` of a request.
fn count(req: &Value, key: &str) -> Result<u64, String> {
    req.get(key).and_then(Value::as_u64).ok_or_else(|| format!("{key} must be an integer >= 0"))
}

/// The flag `key` of a request.
fn flag(req: &Value, key: &str) -> Result<bool, String> {
    req.get(key).and_then(Value::as_bool).ok_or_else(|| format!("{key} must be true or false"))
}

/// The list of numbers `key` of a request.
fn numbers(req: &Value, key: &str) -> Result<Vec<f64>, String> {
    let bad = || format!("{key} must be a list of real numbers");
    req.get(key).and_then(Value::as_array).ok_or_else(bad)?.iter().map(|v| v.as_f64().ok_or_else(bad)).collect()
}

/// The points `key` of a request: a list of `[x, y]` pairs.
fn points(req: &Value, key: &str) -> Result<Vec<Xy>, String> {
    let bad = || format!("{key} must be a list of [x, y] pairs of real numbers");
    let list = req.get(key).and_then(Value::as_array).ok_or_else(bad)?;
    list.iter()
        .map(|p| match p.as_array().map(Vec::as_slice) {
            Some([x, y]) => Ok([x.as_f64().ok_or_else(bad)?, y.as_f64().ok_or_else(bad)?]),
            _ => Err(bad()),
        })
        .collect()
}

/// One candidate's parameters and signs, checked against its topology.
fn row(req: &Value, t: Topology) -> Result<(Vec<f64>, Vec<f64>), String> {
    let (p, s) = (numbers(req, "params")?, numbers(req, "signs")?);
    let shape = |name: &str, got, expected| err(Error::Shape { name: name.into(), got, expected });
    if p.len() != t.params() {
        return Err(shape("params", p.len(), t.params()));
    }
    if s.len() != t.signs() {
        return Err(shape("signs", s.len(), t.signs()));
    }
    Ok((p, s))
}

/// `{"topology", "seed", "start", "count"}`: entries start..start + count of the atlas.
/// Every column goes to `nums` as f64 (flags as 0 or 1, rows flat); the reply gives each
/// column's offset and columns per entry.
pub(crate) fn shard(req: &Value, nums: &mut Vec<f64>) -> Result<Value, String> {
    let t = topology(req)?;
    let (seed, start) = (count(req, "seed")?, count(req, "start")?);
    let n = usize::try_from(count(req, "count")?).map_err(|_| "count is too large")?;
    let s = build_shard(t, seed, start, n, &Never).map_err(err)?;
    let mut column = |values: &mut dyn Iterator<Item = f64>, cols: usize| {
        let offset = nums.len();
        nums.extend(values);
        json!({"offset": offset, "cols": cols})
    };
    Ok(json!({
        "topology": t.name(),
        "count": n,
        "params": column(&mut s.params.iter().copied(), t.params()),
        "signs": column(&mut s.signs.iter().map(|&v| f64::from(v)), t.signs()),
        "full_turn": column(&mut s.full_turn.iter().map(|&v| f64::from(u8::from(v))), 1),
        "conditioning": column(&mut s.conditioning.iter().copied(), 1),
        "descriptor": column(&mut s.descriptor.iter().map(|&v| f64::from(v)), DESCRIPTOR),
    }))
}

/// `{"points", "closed"}`: the curve's descriptor (null where it has no extent).
pub(crate) fn descriptor(req: &Value) -> Result<Value, String> {
    let pts = points(req, "points")?;
    let mut out = [0.0f32; DESCRIPTOR];
    let ok = describe(&pts, flag(req, "closed")?, &mut out);
    Ok(json!({ "descriptor": ok.then(|| out.iter().map(|&v| f64::from(v)).collect::<Vec<_>>()) }))
}

/// `{"topology", "params" (flat rows), "signs" (flat rows), "target", "closed", "offsets"}`:
/// each candidate placed onto the target, `{cost, a, b, fraction, reversed, theta}` (a and
/// b complex as [re, im], theta the entry's input at each target point), or null.
pub(crate) fn placements(req: &Value) -> Result<Value, String> {
    let t = topology(req)?;
    let (p, s) = (numbers(req, "params")?, numbers(req, "signs")?);
    if !p.len().is_multiple_of(t.params()) {
        return Err(format!("params must hold rows of {} numbers for {}, got {}", t.params(), t.name(), p.len()));
    }
    let target = points(req, "target")?;
    let offsets = usize::try_from(count(req, "offsets")?).map_err(|_| "offsets is too large")?;
    let found =
        match_many(t, &p, &s, SAMPLES, &target, flag(req, "closed")?, Search { offsets, ..Search::FINE }, &Never)
            .map_err(err)?;
    let list: Vec<Value> = found
        .into_iter()
        .map(|f| {
            f.map_or(Value::Null, |pl| {
                json!({
                    "cost": pl.cost,
                    "a": pair(pl.a),
                    "b": pair(pl.b),
                    "fraction": pl.fraction,
                    "reversed": pl.reversed,
                    "theta": pl.theta,
                })
            })
        })
        .collect();
    Ok(json!({ "placements": list }))
}

/// `{"topology", "params", "signs", "theta"}`: the entry's points at input `theta` (its
/// own frame), named; `points` null where it does not assemble.
pub(crate) fn entry_pose(req: &Value) -> Result<Value, String> {
    let t = topology(req)?;
    let (p, s) = row(req, t)?;
    let q = pose(t, &p, &s, number(req, "theta")?);
    Ok(json!({
        "names": pose_names(t),
        "points": q.map(|q| q.points[..q.count].iter().map(|&x| pair(x)).collect::<Vec<_>>()),
        "conditioning": q.map(|q| q.conditioning),
    }))
}
