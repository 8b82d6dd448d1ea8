//! The format's `loads` and `units` keys: what acts on a scene (forces, torques, springs,
//! dampers, gravity, masses) and the unit system it is stated in, checked against the
//! scene's names with one-line messages naming the entry. The numbers are the forces
//! subject's to use; the core only checks and hands them on, normalised ([`Loads::to_value`]).

use super::value::{real, Value};
use crate::error::Error;

fn fail<T>(entry: impl Into<String>, message: impl Into<String>) -> Result<T, Error> {
    Err(Error::scene(entry, message))
}

/// The keys `loads` may have, in the order messages list them.
pub const LOAD_KEYS: [&str; 6] = ["forces", "torques", "springs", "dampers", "gravity", "masses"];

/// `units` given as a table: each unit's name, if given.
#[derive(Clone, Debug, Default, PartialEq, Eq)]
pub struct Units {
    /// The length unit (`units` as a string means this one).
    pub length: Option<String>,
    /// The force unit.
    pub force: Option<String>,
    /// The mass unit.
    pub mass: Option<String>,
}

/// A value that is constant, or a table over the input coordinate (linear in between).
#[derive(Clone, Debug, PartialEq)]
pub struct Profile {
    /// Input values, strictly increasing (None: constant).
    pub input: Option<Vec<f64>>,
    /// The value (`width` numbers), or one per input value, row after row.
    pub values: Vec<f64>,
    /// 2 for a vector, 1 for a scalar.
    pub width: usize,
}

/// Where a force acts.
#[derive(Clone, Debug, PartialEq, Eq)]
pub enum Target {
    /// At a point (a vector force).
    Point(String),
    /// Along a slot, on its point (a scalar force along the line's direction).
    Slot(String),
    /// Along a prismatic pair, on its link.
    Prismatic(String),
}

/// A spring or damper between two points.
#[derive(Clone, Debug, PartialEq)]
pub struct Element {
    /// Its two points.
    pub between: (String, String),
    /// Stiffness (force per length) or damping (force per speed).
    pub rate: f64,
    /// A spring's free length (None for a damper).
    pub free_length: Option<f64>,
    /// A spring's tension at its free length (0 unless given).
    pub preload: f64,
}

/// Where a link's centre of mass is.
#[derive(Clone, Debug, PartialEq)]
pub enum Center {
    /// At one of its points.
    Point(String),
    /// At these coordinates of the drawing (moving with the link).
    At([f64; 2]),
}

/// A link's mass properties.
#[derive(Clone, Debug, PartialEq)]
pub struct Mass {
    /// Mass (>= 0).
    pub mass: f64,
    /// Centre of mass.
    pub center: Center,
    /// Moment of inertia about the centre of mass (>= 0).
    pub inertia: f64,
}

/// The loads of a scene, checked.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct Loads {
    /// External forces.
    pub forces: Vec<(Target, Profile)>,
    /// External torques on links.
    pub torques: Vec<(String, Profile)>,
    /// Linear springs.
    pub springs: Vec<Element>,
    /// Viscous dampers.
    pub dampers: Vec<Element>,
    /// The gravitational acceleration (length units per second squared).
    pub gravity: Option<[f64; 2]>,
    /// Mass properties by link.
    pub masses: Vec<(String, Mass)>,
}

/// The names a scene has, which loads may name.
pub(crate) struct Names<'a> {
    pub points: &'a [(String, [f64; 2])],
    pub links: &'a [(String, Vec<String>)],
    pub slots: &'a [String],
    pub prismatic: &'a [String],
}

/// `units`: a string (the length unit) or a table with keys among length, force, mass.
pub(crate) fn units(v: Option<&Value>) -> Result<(Option<String>, Option<Units>), Error> {
    let Some(v) = v else { return Ok((None, None)) };
    if let Value::Str(s) = v {
        return Ok((Some(s.clone()), None));
    }
    let Some(m) = v.as_map() else { return fail("units", format!("must be a string, got {}", v.repr())) };
    let mut u = Units::default();
    for (k, x) in m {
        let slot = match k.as_str() {
            Some("length") => &mut u.length,
            Some("force") => &mut u.force,
            Some("mass") => &mut u.mass,
            _ => {
                return fail("units", format!("unknown key {}; known keys: length, force, mass", k.repr()));
            }
        };
        match x {
            Value::Str(s) => *slot = Some(s.clone()),
            _ => return fail(format!("units.{}", k.str()), format!("must be a string, got {}", x.repr())),
        }
    }
    Ok((u.length.clone(), Some(u)))
}

/// A mapping's entries with exactly `required` and some of `optional`, or the message.
fn table<'a>(e: &str, v: &'a Value, required: &[&str], optional: &[&str]) -> Result<&'a [(Value, Value)], Error> {
    let want = || {
        let quoted = |ks: &[&str]| ks.iter().map(|k| format!("'{k}'")).collect::<Vec<_>>().join(", ");
        match (required.is_empty(), optional.is_empty()) {
            (_, true) => quoted(required),
            (true, false) => format!("(optional {})", quoted(optional)),
            (false, false) => format!("{} (optional {})", quoted(required), quoted(optional)),
        }
    };
    let Some(m) = v.as_map() else { return fail(e, format!("must be a table with keys {}, got {}", want(), v.repr())) };
    for (k, _) in m {
        if !k.as_str().is_some_and(|k| required.contains(&k) || optional.contains(&k)) {
            return fail(e, format!("unknown key {}; keys: {}", k.repr(), want()));
        }
    }
    for r in required {
        if v.get(r).is_none() {
            return fail(e, format!("must have key '{r}', got {}", v.repr()));
        }
    }
    Ok(m)
}

fn number(e: &str, v: &Value) -> Result<f64, Error> {
    let x = real(e, v)?;
    if !x.is_finite() {
        return fail(e, format!("must be finite, got {}", v.repr()));
    }
    Ok(x)
}

fn nonneg(e: &str, v: &Value) -> Result<f64, Error> {
    let x = number(e, v)?;
    if x < 0.0 {
        return fail(e, format!("must be >= 0, got {}", v.repr()));
    }
    Ok(x)
}

fn pair(e: &str, v: &Value) -> Result<[f64; 2], Error> {
    let Some([x, y]) = v.as_list() else { return fail(e, format!("must be a pair [x, y], got {}", v.repr())) };
    Ok([number(&format!("{e}[0]"), x)?, number(&format!("{e}[1]"), y)?])
}

/// A value of `width` (1: a number, 2: a pair), or with `input` a list of them.
fn profile(e: &str, t: &Value, key: &str, width: usize) -> Result<Profile, Error> {
    let v = t.get(key).expect("a key checked present");
    let one = |e: &str, v: &Value| -> Result<Vec<f64>, Error> {
        if width == 2 {
            Ok(pair(e, v)?.to_vec())
        } else {
            Ok(vec![number(e, v)?])
        }
    };
    let Some(inp) = t.get("input") else {
        return Ok(Profile { input: None, values: one(&format!("{e}.{key}"), v)?, width });
    };
    let Some(xs) = inp.as_list().filter(|l| l.len() >= 2) else {
        return fail(format!("{e}.input"), format!("must be a list of at least 2 input values, got {}", inp.repr()));
    };
    let xs: Vec<f64> =
        xs.iter().enumerate().map(|(i, x)| number(&format!("{e}.input[{i}]"), x)).collect::<Result<_, _>>()?;
    if xs.windows(2).any(|w| w[1] <= w[0]) {
        return fail(format!("{e}.input"), "must be strictly increasing");
    }
    let Some(vs) = v.as_list().filter(|l| l.len() == xs.len()) else {
        return fail(
            format!("{e}.{key}"),
            format!("must be a list of {} values (one per input value), got {}", xs.len(), v.repr()),
        );
    };
    let mut values = Vec::with_capacity(xs.len() * width);
    for (i, x) in vs.iter().enumerate() {
        values.extend(one(&format!("{e}.{key}[{i}]"), x)?);
    }
    Ok(Profile { input: Some(xs), values, width })
}

impl Names<'_> {
    fn point(&self, e: &str, v: &Value) -> Result<String, Error> {
        match v.as_str() {
            Some(s) if self.points.iter().any(|(n, _)| n == s) => Ok(s.to_owned()),
            Some(s) => fail(e, format!("{} is not a point of the scene", super::value::str_repr(s))),
            None => fail(e, format!("must be a point name, got {}", v.repr())),
        }
    }
    fn link(&self, e: &str, v: &Value) -> Result<String, Error> {
        match v.as_str() {
            Some(s) if self.links.iter().any(|(n, _)| n == s) => Ok(s.to_owned()),
            Some(s) => fail(e, format!("{} is not a link of the scene", super::value::str_repr(s))),
            None => fail(e, format!("must be a link name, got {}", v.repr())),
        }
    }
    fn between(&self, e: &str, v: &Value) -> Result<(String, String), Error> {
        let Some([a, b]) = v.as_list() else {
            return fail(e, format!("must be a pair of point names, got {}", v.repr()));
        };
        let (a, b) = (self.point(&format!("{e}[0]"), a)?, self.point(&format!("{e}[1]"), b)?);
        if a == b {
            return fail(e, format!("must name two different points, got {}", v.repr()));
        }
        Ok((a, b))
    }
}

fn list<'a>(e: &str, v: &'a Value) -> Result<&'a [Value], Error> {
    v.as_list().map_or_else(|| fail(e, format!("must be a list of tables, got {}", v.repr())), Ok)
}

/// `loads`, checked against the scene's `names`.
pub(crate) fn loads(v: Option<&Value>, names: &Names<'_>) -> Result<Option<Loads>, Error> {
    let Some(v) = v else { return Ok(None) };
    let m = table("loads", v, &[], &LOAD_KEYS)?;
    let mut out = Loads::default();
    let got =
        |k: &str| m.iter().find(|(x, _)| x.as_str() == Some(k)).map(|(_, v)| v).filter(|v| !matches!(v, Value::Null));
    if let Some(fs) = got("forces") {
        for (i, f) in list("loads.forces", fs)?.iter().enumerate() {
            let e = format!("loads.forces[{i}]");
            let kind = ["point", "slot", "prismatic"].into_iter().find(|k| f.get(k).is_some());
            let Some(kind) = kind else {
                return fail(e, format!("must have a key 'point', 'slot' or 'prismatic', got {}", f.repr()));
            };
            table(&e, f, &[kind, "force"], &["input"])?;
            let name = f.get(kind).expect("present");
            let (target, width) = match kind {
                "point" => (Target::Point(names.point(&format!("{e}.point"), name)?), 2),
                _ => {
                    let s = name.as_str();
                    let slot = s.filter(|s| names.slots.iter().any(|n| n == s));
                    let prism = s.filter(|s| names.prismatic.iter().any(|n| n == s));
                    match (slot, prism, kind) {
                        (Some(s), _, "slot") => (Target::Slot(s.to_owned()), 1),
                        (_, Some(s), _) => (Target::Prismatic(s.to_owned()), 1),
                        (Some(s), _, _) => (Target::Slot(s.to_owned()), 1),
                        _ => {
                            return fail(
                                format!("{e}.{kind}"),
                                format!("must name a slot or prismatic pair of the scene, got {}", name.repr()),
                            )
                        }
                    }
                }
            };
            out.forces.push((target, profile(&e, f, "force", width)?));
        }
    }
    if let Some(ts) = got("torques") {
        for (i, t) in list("loads.torques", ts)?.iter().enumerate() {
            let e = format!("loads.torques[{i}]");
            table(&e, t, &["link", "torque"], &["input"])?;
            let link = names.link(&format!("{e}.link"), t.get("link").expect("present"))?;
            out.torques.push((link, profile(&e, t, "torque", 1)?));
        }
    }
    if let Some(ss) = got("springs") {
        for (i, s) in list("loads.springs", ss)?.iter().enumerate() {
            let e = format!("loads.springs[{i}]");
            table(&e, s, &["between", "k", "free_length"], &["preload"])?;
            let between = names.between(&format!("{e}.between"), s.get("between").expect("present"))?;
            let rate = nonneg(&format!("{e}.k"), s.get("k").expect("present"))?;
            let free = nonneg(&format!("{e}.free_length"), s.get("free_length").expect("present"))?;
            let preload = s.get("preload").map(|p| number(&format!("{e}.preload"), p)).transpose()?.unwrap_or(0.0);
            out.springs.push(Element { between, rate, free_length: Some(free), preload });
        }
    }
    if let Some(ds) = got("dampers") {
        for (i, d) in list("loads.dampers", ds)?.iter().enumerate() {
            let e = format!("loads.dampers[{i}]");
            table(&e, d, &["between", "c"], &[])?;
            let between = names.between(&format!("{e}.between"), d.get("between").expect("present"))?;
            let rate = nonneg(&format!("{e}.c"), d.get("c").expect("present"))?;
            out.dampers.push(Element { between, rate, free_length: None, preload: 0.0 });
        }
    }
    if let Some(g) = got("gravity") {
        out.gravity = Some(pair("loads.gravity", g)?);
    }
    if let Some(ms) = got("masses") {
        let Some(ms) = ms.as_map() else {
            return fail(
                "loads.masses",
                format!("must be a table link -> {{mass, center, inertia}}, got {}", ms.repr()),
            );
        };
        for (k, t) in ms {
            let e = format!("loads.masses.{}", k.str());
            let link = names.link(&e, k)?;
            table(&e, t, &["mass", "center"], &["inertia"])?;
            let mass = nonneg(&format!("{e}.mass"), t.get("mass").expect("present"))?;
            let inertia = t.get("inertia").map(|x| nonneg(&format!("{e}.inertia"), x)).transpose()?.unwrap_or(0.0);
            let c = t.get("center").expect("present");
            let center = match c.as_str() {
                Some(p) => {
                    let on =
                        names.links.iter().find(|(n, _)| *n == link).is_some_and(|(_, ps)| ps.iter().any(|q| q == p));
                    if !on {
                        return fail(
                            format!("{e}.center"),
                            format!(
                                "{} is not a point of link {}",
                                super::value::str_repr(p),
                                super::value::str_repr(&link)
                            ),
                        );
                    }
                    Center::Point(p.to_owned())
                }
                None => Center::At(pair(&format!("{e}.center"), c)?),
            };
            if out.masses.iter().any(|(n, _)| *n == link) {
                return fail(e, "is given twice");
            }
            out.masses.push((link, Mass { mass, center, inertia }));
        }
    }
    Ok(Some(out))
}

fn s(x: &str) -> Value {
    Value::Str(x.to_owned())
}

fn map(v: Vec<(&str, Value)>) -> Value {
    Value::Map(v.into_iter().map(|(k, v)| (s(k), v)).collect())
}

fn floats(v: &[f64]) -> Value {
    Value::List(v.iter().map(|x| Value::Float(*x)).collect())
}

impl Profile {
    /// The entries `key` (and `input`, for a table) as the file spells them.
    fn entries(&self, key: &'static str) -> Vec<(&'static str, Value)> {
        let one = |v: &[f64]| if self.width == 2 { floats(v) } else { Value::Float(v[0]) };
        match &self.input {
            None => vec![(key, one(&self.values))],
            Some(xs) => {
                vec![(key, Value::List(self.values.chunks(self.width).map(one).collect())), ("input", floats(xs))]
            }
        }
    }
}

impl Units {
    /// The table as the file spells it (keys given only).
    pub fn to_value(&self) -> Value {
        let mut v = Vec::new();
        for (k, x) in [("length", &self.length), ("force", &self.force), ("mass", &self.mass)] {
            if let Some(x) = x {
                v.push((k, s(x)));
            }
        }
        map(v)
    }
}

impl Loads {
    /// The loads as the file spells them, normalised: every key present, springs with
    /// their preload, masses with their inertia, tables with their `input`.
    pub fn to_value(&self) -> Value {
        let forces = self
            .forces
            .iter()
            .map(|(t, p)| {
                let (k, n) = match t {
                    Target::Point(n) => ("point", n),
                    Target::Slot(n) => ("slot", n),
                    Target::Prismatic(n) => ("prismatic", n),
                };
                let mut e = vec![(k, s(n))];
                e.extend(p.entries("force"));
                map(e)
            })
            .collect();
        let torques = self
            .torques
            .iter()
            .map(|(l, p)| {
                let mut e = vec![("link", s(l))];
                e.extend(p.entries("torque"));
                map(e)
            })
            .collect();
        let between = |e: &Element| Value::List(vec![s(&e.between.0), s(&e.between.1)]);
        let springs = self
            .springs
            .iter()
            .map(|e| {
                map(vec![
                    ("between", between(e)),
                    ("k", Value::Float(e.rate)),
                    ("free_length", Value::Float(e.free_length.unwrap_or(0.0))),
                    ("preload", Value::Float(e.preload)),
                ])
            })
            .collect();
        let dampers =
            self.dampers.iter().map(|e| map(vec![("between", between(e)), ("c", Value::Float(e.rate))])).collect();
        let masses = self
            .masses
            .iter()
            .map(|(l, m)| {
                let center = match &m.center {
                    Center::Point(p) => s(p),
                    Center::At(xy) => floats(xy),
                };
                (
                    s(l),
                    map(vec![("mass", Value::Float(m.mass)), ("center", center), ("inertia", Value::Float(m.inertia))]),
                )
            })
            .collect();
        map(vec![
            ("forces", Value::List(forces)),
            ("torques", Value::List(torques)),
            ("springs", Value::List(springs)),
            ("dampers", Value::List(dampers)),
            ("gravity", self.gravity.map_or(Value::Null, |g| floats(&g))),
            ("masses", Value::Map(masses)),
        ])
    }
}
