//! The scene file format's rules: which keys, which are required, what each entry holds,
//! and the message naming the entry when it does not (Python's `repr` of what it got).

use super::value::{real, Like, Value};
use super::{Drive, Parsed, KEYS, MAX_DEPTH, REQUIRED};
use crate::error::Error;
use crate::scene::{LengthSpec, LinearKind, PrismaticSpec, SceneSpec, SlotSpec};

fn fail<T>(entry: impl Into<String>, message: impl Into<String>) -> Result<T, Error> {
    Err(Error::scene(entry, message))
}

/// The table at `entry` must be a mapping; ordered entries.
type Entries<'a> = &'a [(Value, Value)];

/// Keys exactly `want` (as strings), in any order.
fn keys_are(m: Entries<'_>, want: &[&str]) -> bool {
    m.len() == want.len() && want.iter().all(|w| m.iter().any(|(k, _)| k.as_str() == Some(w)))
}

fn at<'a>(m: Entries<'a>, key: &str) -> &'a Value {
    m.iter().find(|(k, _)| k.as_str() == Some(key)).map(|(_, v)| v).expect("a key checked present")
}

/// `Some` unless absent or null.
fn given<'a>(d: Entries<'a>, key: &str) -> Option<&'a Value> {
    d.iter().find(|(k, _)| k.as_str() == Some(key)).map(|(_, v)| v).filter(|v| !matches!(v, Value::Null))
}

/// All strings: a list of names.
fn names(v: &Value) -> Option<Vec<String>> {
    v.as_list()?.iter().map(|p| p.as_str().map(str::to_owned)).collect()
}

/// The name of a linear kind as the file spells it.
pub fn kind_name(k: LinearKind) -> &'static str {
    match k {
        LinearKind::Slot => "slot",
        LinearKind::Prismatic => "prismatic",
    }
}

/// An input or output: a link's angle about its pivot, or a displacement along a slot or
/// prismatic pair.
fn pivoted(v: &Value, key: &str) -> Result<Drive, Error> {
    if let Some([(k, name)]) = v.as_map() {
        let kind = match k.as_str() {
            Some("slot") => Some(LinearKind::Slot),
            Some("prismatic") => Some(LinearKind::Prismatic),
            _ => None,
        };
        if let Some(kind) = kind {
            let k = kind_name(kind);
            let Some(name) = name.as_str() else {
                return fail(format!("{key}.{k}"), format!("must be a {k} name, got {}", name.repr()));
            };
            return Ok(Drive::Linear { kind, name: name.to_owned() });
        }
    }
    let Some(t) = v.as_map().filter(|t| keys_are(t, &["link", "pivot"])) else {
        return fail(
            key,
            format!(
                "must be a table with keys 'link' and 'pivot' (an angle), or with one key 'slot' or \
                 'prismatic' (a displacement), got {}",
                v.repr()
            ),
        );
    };
    let (link, pivot) = (at(t, "link"), at(t, "pivot"));
    let Some(link) = link.as_str() else {
        return fail(format!("{key}.link"), format!("must be a link name, got {}", link.repr()));
    };
    let Some(pivot) = pivot.as_str() else {
        return fail(format!("{key}.pivot"), format!("must be a point name, got {}", pivot.repr()));
    };
    Ok(Drive::Angle { link: link.to_owned(), pivot: pivot.to_owned() })
}

/// A slot (point, guide, line) or prismatic pair (link, guide, line), by name.
type Joint = (String, (String, String, (String, String)));

/// Slots (`first` = "point") or prismatic pairs (`first` = "link").
fn joints(d: Entries<'_>, key: &str, first: &str) -> Result<Vec<Joint>, Error> {
    let Some(table) = given(d, key) else { return Ok(Vec::new()) };
    let Some(table) = table.as_map() else {
        return fail(key, format!("must be a table name -> {{{first}, guide, line}}"));
    };
    let mut out = Vec::with_capacity(table.len());
    for (n, v) in table {
        let e = format!("{key}.{}", n.str());
        let Some(t) = v.as_map().filter(|t| keys_are(t, &[first, "guide", "line"])) else {
            return fail(e, format!("must be a table with keys '{first}', 'guide' and 'line', got {}", v.repr()));
        };
        let name = |k: &str| match at(t, k).as_str() {
            Some(s) => Ok(s.to_owned()),
            None => fail(format!("{e}.{k}"), format!("must be a name, got {}", at(t, k).repr())),
        };
        let (moving, guide) = (name(first)?, name("guide")?);
        let line = at(t, "line");
        let pair = names(line).and_then(|v| <[String; 2]>::try_from(v).ok());
        let Some([a, b]) = pair else {
            return fail(format!("{e}.line"), format!("must be a pair of point names, got {}", line.repr()));
        };
        out.push((n.str(), (moving, guide, (a, b))));
    }
    Ok(out)
}

/// A sketch's `lengths` as (name, name, distance); their meaning is the core's to check.
fn lengths(d: Entries<'_>) -> Result<Option<Vec<LengthSpec>>, Error> {
    let Some(v) = given(d, "lengths") else { return Ok(None) };
    let Some(list) = v.as_list() else {
        return fail("lengths", format!("must be a list of [name, name, length], got {}", v.repr()));
    };
    let mut out = Vec::with_capacity(list.len());
    for (k, e) in list.iter().enumerate() {
        let t = e.as_list().filter(|t| t.len() == 3);
        let Some((a, b, x)) = t.and_then(|t| Some((t[0].as_str()?, t[1].as_str()?, &t[2]))) else {
            return fail(format!("lengths[{k}]"), format!("must be [name, name, length], got {}", e.repr()));
        };
        let length = real("length", x).map_err(|m| Error::scene(format!("lengths[{k}]"), format!("the {m}")))?;
        out.push((a.to_owned(), b.to_owned(), length));
    }
    Ok(Some(out))
}

/// How a value is reached from the list or mapping holding it.
#[derive(Clone, Copy)]
enum Step<'a> {
    Key(&'a Value),
    Index(usize),
}

/// The first list or mapping nested deeper than [`MAX_DEPTH`] (parents first, in order, as
/// Python's walk finds it), as `child` names it from `root` down; no recursion. Named with
/// `()` it is only a check, which costs nothing per value: a file of many points is walked
/// once that way, and again with names only where it is refused ([`dotted`]).
fn too_deep<'a, T>(data: &'a Value, root: T, child: impl Fn(&T, Step<'a>) -> T) -> Option<T> {
    let mut todo = vec![(root, data, 1usize)];
    while let Some((t, v, depth)) = todo.pop() {
        if let Some(m) = v.as_map() {
            if depth > MAX_DEPTH {
                return Some(t);
            }
            todo.extend(m.iter().rev().map(|(k, x)| (child(&t, Step::Key(k)), x, depth + 1)));
        } else if let Some(l) = v.as_list() {
            if depth > MAX_DEPTH {
                return Some(t);
            }
            todo.extend(l.iter().enumerate().rev().map(|(i, x)| (child(&t, Step::Index(i)), x, depth + 1)));
        }
    }
    None
}

/// A value's dotted name from its parent's `name` (the data's own is empty).
fn dotted(name: &str, step: Step<'_>) -> String {
    match step {
        Step::Key(k) if name.is_empty() => k.str(),
        Step::Key(k) => format!("{name}.{}", k.str()),
        Step::Index(i) => format!("{name}[{i}]"),
    }
}

/// A point's coordinate: a double as it is (most are), anything else by [`real`], which
/// names the entry.
fn coordinate(v: &Value, name: &str, k: usize) -> Result<f64, Error> {
    match v {
        Value::Float(x) => Ok(*x),
        Value::Int(i) => Ok(*i as f64),
        _ => real(&format!("points.{name}[{k}]"), v),
    }
}

/// The scene's data (the file format's keys) as the core's spec and what the spec does not
/// hold; every error names the entry, in the words Python's `planarkin.Scene` has always used.
pub fn parse(data: &Value) -> Result<Parsed, Error> {
    let Some(d) = data.as_map() else {
        return fail("scene", format!("must be a mapping, got {}", data.type_name()));
    };
    if too_deep(data, (), |_, _| ()).is_some() {
        let name = too_deep(data, String::new(), |n, s| dotted(n, s)).unwrap_or_default();
        return fail("scene", format!("{name} nests deeper than {MAX_DEPTH} levels (a scene has at most 4)"));
    }
    let unknown: Vec<String> =
        d.iter().filter(|(k, _)| !k.as_str().is_some_and(|k| KEYS.contains(&k))).map(|(k, _)| k.repr()).collect();
    if !unknown.is_empty() {
        return fail("scene", format!("unknown keys [{}]; known keys: {}", unknown.join(", "), KEYS.join(", ")));
    }
    for k in REQUIRED {
        if !d.iter().any(|(key, _)| key.as_str() == Some(k)) {
            return fail(k, "is required");
        }
    }
    let Some(pts) = at(d, "points").as_map() else { return fail("points", "must be a table name -> [x, y]") };
    let Some(links) = at(d, "links").as_map() else {
        return fail("links", "must be a table name -> [point names]");
    };
    let mut points = Vec::with_capacity(pts.len());
    for (n, v) in pts {
        let name = n.str();
        let xy = match v {
            Value::Foreign(f) => match &f.like {
                Like::Array(a) => Some(&a[..]),
                _ => None,
            },
            _ => v.as_list(),
        };
        let Some([x, y]) = xy else {
            return fail(format!("points.{name}"), format!("must be a pair [x, y], got {}", v.repr()));
        };
        let (x, y) = (coordinate(x, &name, 0)?, coordinate(y, &name, 1)?);
        points.push((name, [x, y]));
    }
    let mut lk = Vec::with_capacity(links.len());
    for (n, v) in links {
        let Some(list) = names(v) else {
            return fail(format!("links.{}", n.str()), format!("must be a list of point names, got {}", v.repr()));
        };
        lk.push((n.str(), list));
    }
    let Some(ground) = at(d, "ground").as_str() else { return fail("ground", "must be a link name") };
    let input = pivoted(at(d, "input"), "input")?;
    let output = given(d, "output").map(|v| pivoted(v, "output")).transpose()?;
    let (slots, prismatic) = (joints(d, "slots", "point")?, joints(d, "prismatic", "link")?);
    if let Some(Drive::Linear { kind, name }) = &output {
        let table = if *kind == LinearKind::Slot { &slots } else { &prismatic };
        if !table.iter().any(|(n, _)| n == name) {
            let k = kind_name(*kind);
            return fail(format!("output.{k}"), format!("{} is not a {k}", super::value::str_repr(name)));
        }
    }
    let outputs = match given(d, "outputs") {
        None => None,
        Some(v) => match names(v) {
            Some(o) => Some(o),
            None => return fail("outputs", format!("must be a list of point or link names, got {}", v.repr())),
        },
    };
    let mut text = [None, None];
    for (k, t) in ["name", "description"].into_iter().zip(&mut text) {
        match given(d, k) {
            None => {}
            Some(Value::Str(s)) => *t = Some(s.clone()),
            Some(v) => return fail(k, format!("must be a string, got {}", v.repr())),
        }
    }
    let lengths = lengths(d)?;
    let (units, unit_table) = super::loads::units(given(d, "units"))?;
    let (slot_names, prism_names): (Vec<String>, Vec<String>) =
        (slots.iter().map(|s| s.0.clone()).collect(), prismatic.iter().map(|p| p.0.clone()).collect());
    let names = super::loads::Names { points: &points, links: &lk, slots: &slot_names, prismatic: &prism_names };
    let loads = super::loads::loads(given(d, "loads"), &names)?;
    let joint_names: Vec<String> = slot_names.iter().chain(&prism_names).cloned().collect();
    let link_names: Vec<String> = lk.iter().map(|l| l.0.clone()).collect();
    let limits = super::limits::limits(given(d, "limits"), &joint_names, &link_names)?;
    let (spec_input, linear_input) = match &input {
        Drive::Angle { link, pivot } => ((link.clone(), pivot.clone()), None),
        Drive::Linear { kind, name } => ((String::new(), String::new()), Some((*kind, name.clone()))),
    };
    let spec_output = match &output {
        Some(Drive::Angle { link, pivot }) => Some((link.clone(), pivot.clone())),
        _ => None,
    };
    let spec = SceneSpec {
        points,
        links: lk,
        ground: ground.to_owned(),
        input: spec_input,
        output: spec_output,
        slots: slots.into_iter().map(|(n, j)| (n, SlotSpec::from(j))).collect(),
        prismatic: prismatic.into_iter().map(|(n, j)| (n, PrismaticSpec::from(j))).collect(),
        linear_input,
    };
    let [name, description] = text;
    Ok(Parsed { spec, name, description, units, unit_table, input, output, outputs, lengths, loads, limits })
}
