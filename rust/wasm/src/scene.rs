//! Scenes: the file format (JSON) to the core's `SceneSpec` with the checks that Python's
//! `planarkin.Scene` makes before the core's (the same entries, the same words), then
//! the core's validation, sweeps, assemblies and circuits, as JSON and flat numbers.
//!
//! Python's defaults are used throughout (`tol=1e-9`, `max_iter=100`, `max_step=3 deg`, or
//! `3 deg x size` for a linear input, the homotopy's seed and runs, the trace's step and
//! length, a linear input's stroke), so the page shows what `pk.Scene` computes.

use std::f64::consts::TAU;

use planarkin_core::scene::{
    assemble_sketch, LengthSpec, LinearKind, Plan, Scene, SceneSpec, SceneSweepOptions, SceneSweepOut, Trace,
    TraceOptions,
};
use planarkin_core::solve::homotopy::HomotopyOptions;
use planarkin_core::{Never, NewtonOptions};
use serde_json::{json, Map, Value};

use crate::json::{pair, status_name};

/// The keys a scene may have (Python's `planarkin.scene._model.KEYS`), and the required.
const KEYS: [&str; 12] = [
    "name",
    "description",
    "units",
    "points",
    "links",
    "ground",
    "input",
    "output",
    "outputs",
    "slots",
    "prismatic",
    "lengths",
];
const REQUIRED: [&str; 4] = ["points", "links", "ground", "input"];
/// Python's `SEED` (the homotopy's random gammas) and default `runs`.
const SEED: u64 = 0x5EED_2026;
const RUNS: i64 = 2;
/// Python's default sweep: 361 input angles from the drawn one through one full turn (or
/// 361 displacements across a linear input's stroke).
const PATH_ANGLES: usize = 361;

/// A validated scene and the plan that solves every point, kept between requests.
pub(crate) struct Kept {
    scene: Scene,
    plan: Plan,
    opts: SceneSweepOptions,
    /// A linear output as the file names it (the core is given angle outputs only).
    linear_output: Option<(LinearKind, String)>,
    /// The drawing's extent: its bounding box's larger side (Python's `Scene._size()`).
    size: f64,
    /// A linear input's reachable interval (`Scene.stroke()`); None for an angle input.
    stroke: Option<(f64, f64)>,
}

/// An input or output as the file gives it: a link's angle about its pivot, or the
/// displacement along a slot or prismatic pair.
enum Drive {
    Angle(String, String),
    Linear(LinearKind, String),
}

/// A slot (point, guide, line) or a prismatic pair (link, guide, line), by name.
type Joints = Vec<(String, (String, String, (String, String)))>;

fn kind_name(k: LinearKind) -> &'static str {
    match k {
        LinearKind::Slot => "slot",
        LinearKind::Prismatic => "prismatic",
    }
}

fn entry(e: &str, message: impl std::fmt::Display) -> String {
    format!("{e}: {message}")
}

/// A value as Python's `repr` writes what `json.loads` made of it (for messages).
fn repr(v: &Value) -> String {
    match v {
        Value::Null => "None".into(),
        Value::Bool(b) => if *b { "True" } else { "False" }.into(),
        Value::Number(n) if n.is_f64() => {
            let s = n.to_string();
            if s.contains(['.', 'e', 'E']) {
                s
            } else {
                format!("{s}.0")
            }
        }
        Value::Number(n) => n.to_string(),
        Value::String(s) => format!("'{s}'"),
        Value::Array(a) => format!("[{}]", a.iter().map(repr).collect::<Vec<_>>().join(", ")),
        Value::Object(o) => {
            format!("{{{}}}", o.iter().map(|(k, v)| format!("'{k}': {}", repr(v))).collect::<Vec<_>>().join(", "))
        }
    }
}

/// Python's type name of a JSON value.
fn type_name(v: &Value) -> &'static str {
    match v {
        Value::Null => "NoneType",
        Value::Bool(_) => "bool",
        Value::Number(n) if n.is_f64() => "float",
        Value::Number(_) => "int",
        Value::String(_) => "str",
        Value::Array(_) => "list",
        Value::Object(_) => "dict",
    }
}

fn coordinate(name: &str, v: &Value) -> Result<f64, String> {
    v.as_f64().ok_or_else(|| format!("{name} must be a real number, got {}", repr(v)))
}

/// An input or output (Python's `_pivoted`).
fn pivoted(d: &Map<String, Value>, key: &str) -> Result<Drive, String> {
    let v = &d[key];
    if let Some(t) = v.as_object().filter(|t| t.len() == 1) {
        let (k, name) = t.iter().next().expect("one entry");
        let kind = match k.as_str() {
            "slot" => Some(LinearKind::Slot),
            "prismatic" => Some(LinearKind::Prismatic),
            _ => None,
        };
        if let Some(kind) = kind {
            let name = name
                .as_str()
                .ok_or_else(|| entry(&format!("{key}.{k}"), format!("must be a {k} name, got {}", repr(name))))?;
            return Ok(Drive::Linear(kind, name.to_owned()));
        }
    }
    let table = v.as_object().filter(|t| t.len() == 2 && t.contains_key("link") && t.contains_key("pivot"));
    let t = table.ok_or_else(|| {
        entry(
            key,
            format!(
                "must be a table with keys 'link' and 'pivot' (an angle), or with one key 'slot' or \
                 'prismatic' (a displacement), got {}",
                repr(v)
            ),
        )
    })?;
    let link = t["link"]
        .as_str()
        .ok_or_else(|| entry(&format!("{key}.link"), format!("must be a link name, got {}", repr(&t["link"]))))?;
    let pivot = t["pivot"]
        .as_str()
        .ok_or_else(|| entry(&format!("{key}.pivot"), format!("must be a point name, got {}", repr(&t["pivot"]))))?;
    Ok(Drive::Angle(link.to_owned(), pivot.to_owned()))
}

/// Slots (`first` = "point") or prismatic pairs (`first` = "link") (Python's `_joints`).
fn joints(d: &Map<String, Value>, key: &str, first: &str) -> Result<Joints, String> {
    let table = match d.get(key) {
        None | Some(Value::Null) => return Ok(Vec::new()),
        Some(t) => {
            t.as_object().ok_or_else(|| entry(key, format!("must be a table name -> {{{first}, guide, line}}")))?
        }
    };
    let mut out = Vec::with_capacity(table.len());
    for (n, v) in table {
        let e = format!("{key}.{n}");
        let t = v
            .as_object()
            .filter(|t| t.len() == 3 && t.contains_key(first) && t.contains_key("guide") && t.contains_key("line"));
        let t = t.ok_or_else(|| {
            entry(&e, format!("must be a table with keys '{first}', 'guide' and 'line', got {}", repr(v)))
        })?;
        let name = |k: &str| {
            t[k].as_str()
                .map(str::to_owned)
                .ok_or_else(|| entry(&format!("{e}.{k}"), format!("must be a name, got {}", repr(&t[k]))))
        };
        let (moving, guide) = (name(first)?, name("guide")?);
        let line = t["line"].as_array().filter(|a| a.len() == 2).and_then(|a| Some((a[0].as_str()?, a[1].as_str()?)));
        let (a, b) = line.ok_or_else(|| {
            entry(&format!("{e}.line"), format!("must be a pair of point names, got {}", repr(&t["line"])))
        })?;
        out.push((n.clone(), (moving, guide, (a.to_owned(), b.to_owned()))));
    }
    Ok(out)
}

/// What the file gives beyond the core's spec: the `outputs` names, a linear output, and a
/// sketch's `lengths`.
type Extra = (Option<Vec<String>>, Option<(LinearKind, String)>, Option<Vec<LengthSpec>>);

/// A sketch's `lengths` as (name, name, distance) (Python's `_lengths`); their meaning is the
/// core's to check.
fn lengths(d: &Map<String, Value>) -> Result<Option<Vec<LengthSpec>>, String> {
    let v = match d.get("lengths") {
        None | Some(Value::Null) => return Ok(None),
        Some(v) => v,
    };
    let list = v
        .as_array()
        .ok_or_else(|| entry("lengths", format!("must be a list of [name, name, length], got {}", repr(v))))?;
    let mut out = Vec::with_capacity(list.len());
    for (k, e) in list.iter().enumerate() {
        let t = e.as_array().filter(|t| t.len() == 3 && t[0].is_string() && t[1].is_string());
        let t =
            t.ok_or_else(|| entry(&format!("lengths[{k}]"), format!("must be [name, name, length], got {}", repr(e))))?;
        let length = coordinate("length", &t[2]).map_err(|m| format!("lengths[{k}]: the {m}"))?;
        let name = |i: usize| t[i].as_str().expect("checked above").to_owned();
        out.push((name(0), name(1), length));
    }
    Ok(Some(out))
}

/// The scene file's data as the core's spec (and what it does not take), checked as
/// Python's `Scene.__init__` checks it before calling the core.
fn spec(data: &Value) -> Result<(SceneSpec, Extra), String> {
    let d = data.as_object().ok_or_else(|| entry("scene", format!("must be a mapping, got {}", type_name(data))))?;
    let unknown: Vec<String> = d.keys().filter(|k| !KEYS.contains(&k.as_str())).map(|k| format!("'{k}'")).collect();
    if !unknown.is_empty() {
        return Err(entry("scene", format!("unknown keys [{}]; known keys: {}", unknown.join(", "), KEYS.join(", "))));
    }
    for k in REQUIRED {
        if !d.contains_key(k) {
            return Err(entry(k, "is required"));
        }
    }
    let pts = d["points"].as_object().ok_or_else(|| entry("points", "must be a table name -> [x, y]"))?;
    let links = d["links"].as_object().ok_or_else(|| entry("links", "must be a table name -> [point names]"))?;
    let mut points = Vec::with_capacity(pts.len());
    for (name, v) in pts {
        let xy = v.as_array().filter(|a| a.len() == 2);
        let xy =
            xy.ok_or_else(|| entry(&format!("points.{name}"), format!("must be a pair [x, y], got {}", repr(v))))?;
        let x = coordinate(&format!("points.{name}[0]"), &xy[0])?;
        let y = coordinate(&format!("points.{name}[1]"), &xy[1])?;
        points.push((name.clone(), [x, y]));
    }
    let mut lk = Vec::with_capacity(links.len());
    for (name, v) in links {
        let names: Option<Vec<String>> =
            v.as_array().and_then(|a| a.iter().map(|p| p.as_str().map(str::to_owned)).collect());
        let names = names.ok_or_else(|| {
            entry(&format!("links.{name}"), format!("must be a list of point names, got {}", repr(v)))
        })?;
        lk.push((name.clone(), names));
    }
    let ground = d["ground"].as_str().ok_or_else(|| entry("ground", "must be a link name"))?.to_owned();
    let input = pivoted(d, "input")?;
    let output = match d.get("output") {
        None | Some(Value::Null) => None,
        Some(_) => Some(pivoted(d, "output")?),
    };
    let (slots, prismatic) = (joints(d, "slots", "point")?, joints(d, "prismatic", "link")?);
    if let Some(Drive::Linear(kind, name)) = &output {
        let known = match kind {
            LinearKind::Slot => slots.iter().any(|(n, _)| n == name),
            LinearKind::Prismatic => prismatic.iter().any(|(n, _)| n == name),
        };
        if !known {
            let k = kind_name(*kind);
            return Err(entry(&format!("output.{k}"), format!("'{name}' is not a {k}")));
        }
    }
    let outputs =
        match d.get("outputs") {
            None | Some(Value::Null) => None,
            Some(v) => {
                let names: Option<Vec<String>> =
                    v.as_array().and_then(|a| a.iter().map(|p| p.as_str().map(str::to_owned)).collect());
                Some(names.ok_or_else(|| {
                    entry("outputs", format!("must be a list of point or link names, got {}", repr(v)))
                })?)
            }
        };
    for k in ["name", "description", "units"] {
        match d.get(k) {
            None | Some(Value::Null) | Some(Value::String(_)) => {}
            Some(v) => return Err(entry(k, format!("must be a string, got {}", repr(v)))),
        }
    }
    let (input, linear_input) = match input {
        Drive::Angle(link, pivot) => ((link, pivot), None),
        Drive::Linear(kind, name) => ((String::new(), String::new()), Some((kind, name))),
    };
    let (output, linear_output) = match output {
        None => (None, None),
        Some(Drive::Angle(link, pivot)) => (Some((link, pivot)), None),
        Some(Drive::Linear(kind, name)) => (None, Some((kind, name))),
    };
    let spec = SceneSpec {
        points,
        links: lk,
        ground,
        input,
        output,
        slots: slots.into_iter().map(|(n, j)| (n, j.into())).collect(),
        prismatic: prismatic.into_iter().map(|(n, j)| (n, j.into())).collect(),
        linear_input,
    };
    Ok((spec, (outputs, linear_output, lengths(d)?)))
}

/// `np.linspace(lo, hi, n)`, bit for bit: `lo + i * step`, the last value `hi`.
fn linspace(lo: f64, hi: f64, n: usize) -> Vec<f64> {
    let step = (hi - lo) / (n - 1) as f64;
    let mut v: Vec<f64> = (0..n).map(|i| i as f64 * step + lo).collect();
    v[n - 1] = hi;
    v
}

impl Kept {
    /// Validates a scene (the file format's data) as `pk.Scene(data)` does.
    pub(crate) fn new(data: &Value) -> Result<Kept, String> {
        let (mut spec, (outputs, linear_output, lengths)) = spec(data)?;
        if let Some(l) = lengths {
            // a sketch: the core assembles the exact pose, which is what is drawn and saved
            let exact = assemble_sketch(spec.clone(), &l, &Never).map_err(|e| e.to_string())?;
            for (p, xy) in spec.points.iter_mut().zip(exact.points) {
                p.1 = xy;
            }
        }
        let scene = Scene::new(spec).map_err(|e| e.to_string())?;
        // names checked, as Python does; the stroke is found on this plan, as Python's is
        let outputs_plan = match outputs {
            Some(o) => Some(scene.plan(Some(&o)).map_err(|e| e.to_string())?),
            None => None,
        };
        let plan = scene.plan(None).map_err(|e| e.to_string())?;
        let (mut lo, mut hi) = ([f64::INFINITY; 2], [f64::NEG_INFINITY; 2]);
        for p in scene.drawn() {
            for k in 0..2 {
                lo[k] = lo[k].min(p[k]);
                hi[k] = hi[k].max(p[k]);
            }
        }
        let size = (hi[0] - lo[0]).max(hi[1] - lo[1]);
        let newton = NewtonOptions::new(1e-9, 100).map_err(|e| e.to_string())?;
        let linear = scene.linear_input().is_some();
        let max_step = if linear { 3f64.to_radians() * size } else { 3f64.to_radians() };
        let opts = SceneSweepOptions::new(newton, max_step, None).map_err(|e| e.to_string())?;
        let mut kept = Kept { scene, plan, opts, linear_output, size, stroke: None };
        if linear {
            kept.stroke = Some(kept.find_stroke(outputs_plan.as_ref().unwrap_or(&kept.plan))?);
        }
        Ok(kept)
    }

    /// `Scene.stroke()`: the core's `Plan::stroke` on this plan.
    fn find_stroke(&self, plan: &Plan) -> Result<(f64, f64), String> {
        plan.stroke(self.size, &self.opts, &Never).map_err(|e| e.to_string())
    }

    /// Names, links (as point indices), ground, input (an angle's link and pivot, or a linear
    /// input's slot or pair: `input_kind`), output, the drawn input angle (0 for a linear
    /// input), a linear input's stroke, slots and prismatic pairs (point and link indices),
    /// the plan's steps, and which points are joints (on two or more links).
    pub(crate) fn describe(&self) -> Value {
        let sc = &self.scene;
        let names = sc.point_names();
        let mut on = vec![0usize; names.len()];
        for l in sc.links() {
            for &p in &l.points {
                on[p] += 1;
            }
        }
        let pivoted = |p: planarkin_core::scene::Pivoted| json!({"link": p.link, "pivot": p.pivot, "tip": p.tip});
        let linear = sc.linear_input().map(|l| {
            let name = match l.kind {
                LinearKind::Slot => &sc.slots()[l.index].name,
                LinearKind::Prismatic => &sc.prismatic()[l.index].name,
            };
            json!({"kind": kind_name(l.kind), "name": name, "index": l.index, "guide": l.guide})
        });
        let slots: Vec<Value> = sc
            .slots()
            .iter()
            .map(|s| json!({"name": s.name, "point": s.point, "guide": s.guide, "line": [s.line.0, s.line.1]}))
            .collect();
        let prismatic: Vec<Value> = sc
            .prismatic()
            .iter()
            .map(|p| json!({"name": p.name, "link": p.link, "guide": p.guide, "line": [p.line.0, p.line.1]}))
            .collect();
        json!({
            "ok": true,
            "names": names,
            "drawn": sc.drawn().iter().map(|&p| pair(p)).collect::<Vec<_>>(),
            "links": sc.links().iter().map(|l| json!({"name": l.name, "points": l.points})).collect::<Vec<_>>(),
            "ground": sc.ground(),
            "input": sc.input().map(pivoted),
            "input_kind": if linear.is_some() { "displacement" } else { "angle" },
            "linear_input": linear,
            "output": sc.output().map(pivoted),
            "linear_output": self.linear_output.as_ref().map(|(k, n)| json!({"kind": kind_name(*k), "name": n})),
            "input_angle": sc.input_angle(),
            "stroke": self.stroke.map(|(lo, hi)| [lo, hi]),
            "size": self.size,
            "slots": slots,
            "prismatic": prismatic,
            "links_per_point": on,
            "steps": self.plan.steps().iter().map(|s| s.kind.name()).collect::<Vec<_>>(),
        })
    }

    /// Solves `theta` and writes the points in scene order (NaN where unsolved).
    fn sweep(&self, theta: &[f64]) -> Result<Solved, String> {
        let mut s = raw_sweep(&self.plan, theta, &self.opts)?;
        let (n, np) = (theta.len(), self.plan.points().len());
        // in scene order: the plan reports its points in its own order
        let total = self.scene.point_names().len();
        let mut points = vec![f64::NAN; n * total * 2];
        let mut point_status = vec![0i8; n * total];
        for i in 0..n {
            for (j, &p) in self.plan.points().iter().enumerate() {
                points[2 * (i * total + p)..2 * (i * total + p) + 2]
                    .copy_from_slice(&s.points[2 * (i * np + j)..2 * (i * np + j) + 2]);
                point_status[i * total + p] = s.point_status[i * np + j];
            }
        }
        s.points = points;
        s.point_status = point_status;
        Ok(s)
    }

    /// The pose at input `theta` (an angle, or a linear input's displacement), reached from
    /// the drawn pose as `Scene.sweep` does.
    pub(crate) fn pose(&self, theta: f64) -> Result<Value, String> {
        let s = self.sweep(&[theta])?;
        let points: Vec<Value> = s.points.chunks_exact(2).map(|c| pair([c[0], c[1]])).collect();
        Ok(json!({
            "theta": theta,
            "status": status_name(s.status[0]),
            "det": s.det[0],
            "limit": s.limit[0],
            "points": points,
            "point_status": s.point_status.iter().map(|&c| status_name(c)).collect::<Vec<_>>(),
        }))
    }

    /// `Scene.sweep()`'s default: 361 input angles from the drawn one through one full
    /// turn, or 361 displacements across a linear input's stroke. The points (361 x P x 2,
    /// scene order) go to `nums` from `offset`.
    pub(crate) fn path(&self, nums: &mut Vec<f64>) -> Result<Value, String> {
        let theta: Vec<f64> = match self.stroke {
            Some((lo, hi)) => linspace(lo, hi, PATH_ANGLES),
            None => {
                let t0 = self.scene.input_angle();
                (0..PATH_ANGLES).map(|k| t0 + k as f64 * (TAU / 360.0)).collect()
            }
        };
        let s = self.sweep(&theta)?;
        let offset = nums.len();
        nums.extend_from_slice(&s.points);
        Ok(json!({
            "offset": offset,
            "n": PATH_ANGLES,
            "theta": theta,
            "status": s.status,
            "limit": s.limit,
        }))
    }

    fn assembly_list(&self, a: &planarkin_core::scene::Assemblies) -> Vec<Value> {
        a.list
            .iter()
            .map(|x| {
                json!({
                    "points": x.points.iter().map(|&p| pair(p)).collect::<Vec<_>>(),
                    "label": x.label,
                    "det": x.det,
                })
            })
            .collect()
    }

    /// Every real assembly at `theta` (`Scene.assemblies(theta)`).
    pub(crate) fn assemblies(&self, theta: f64) -> Result<Value, String> {
        let opts = HomotopyOptions::new(SEED, RUNS).map_err(|e| e.to_string())?;
        let a = self.scene.assemblies(theta, &opts, &Never).map_err(|e| e.to_string())?;
        Ok(json!({
            "theta": theta,
            "assemblies": self.assembly_list(&a),
            "complex_counts": a.complex_counts,
            "paths": a.paths,
            "failed_paths": a.failed_paths,
            "continua": a.continua,
        }))
    }

    /// The circuits at `theta` (`Scene.circuits(theta)`); each circuit's trace (M x P x 2)
    /// goes to `nums` from its `offset`.
    pub(crate) fn circuits(&self, theta: f64, nums: &mut Vec<f64>) -> Result<Value, String> {
        let hopts = HomotopyOptions::new(SEED, RUNS).map_err(|e| e.to_string())?;
        let topts = TraceOptions::default();
        let (a, cs) = self.scene.circuits(theta, &hopts, &topts, &Never).map_err(|e| e.to_string())?;
        let circuits: Vec<Value> = cs
            .iter()
            .map(|c| {
                json!({
                    "assemblies": c.assemblies,
                    "turning_points": c.turning_points,
                    "net_turn": c.net_turn,
                    "full_turn": c.net_turn.is_finite() && c.net_turn.abs() > std::f64::consts::PI,
                    "range": [c.range.0, c.range.1],
                    "trace": trace(&c.trace, nums),
                })
            })
            .collect();
        Ok(json!({ "theta": theta, "assemblies": self.assembly_list(&a), "circuits": circuits }))
    }
}

/// A trace's points to `nums`; the reply says where.
fn trace(t: &Trace, nums: &mut Vec<f64>) -> Value {
    let offset = nums.len();
    nums.extend(t.points.iter().flat_map(|p| [p[0], p[1]]));
    json!({ "offset": offset, "m": t.theta.len(), "theta": t.theta, "turning_points": t.turning_points, "closed": t.closed })
}

/// A plan's sweep over `theta` (its points in the plan's order).
fn raw_sweep(plan: &Plan, theta: &[f64], opts: &SceneSweepOptions) -> Result<Solved, String> {
    let (n, np, nl, ns) = (theta.len(), plan.points().len(), plan.links().len(), plan.steps().len());
    let mut s = Solved {
        points: vec![0.0; n * np * 2],
        status: vec![0; n],
        det: vec![0.0; n],
        limit: vec![0.0; n],
        point_status: vec![0; n * np],
    };
    let (mut angles, mut nit) = (vec![0.0; n * nl], vec![0u32; n]);
    let (mut step_status, mut step_det) = (vec![0i8; n * ns], vec![0.0; n * ns]);
    let out = SceneSweepOut {
        points: &mut s.points,
        angles: &mut angles,
        status: &mut s.status,
        nit: &mut nit,
        det: &mut s.det,
        limit: &mut s.limit,
        step_status: &mut step_status,
        step_det: &mut step_det,
        point_status: &mut s.point_status,
        velocity: None,
        acceleration: None,
    };
    plan.sweep(theta, opts, out, &Never).map_err(|e| e.to_string())?;
    Ok(s)
}

/// A sweep's arrays, in scene order.
struct Solved {
    points: Vec<f64>,
    status: Vec<i8>,
    det: Vec<f64>,
    limit: Vec<f64>,
    point_status: Vec<i8>,
}
