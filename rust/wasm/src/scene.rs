//! Scenes: the file format (JSON) to the core's `SceneSpec` with the checks that Python's
//! `planarkin.Scene` makes before the core's (the same entries, the same words), then
//! the core's validation, sweeps, assemblies and circuits, as JSON and flat numbers.
//!
//! Python's defaults are used throughout (`tol=1e-9`, `max_iter=100`, `max_step=3 deg`,
//! the homotopy's seed and runs, the trace's step and length), so the page shows what
//! `pk.Scene` computes.

use std::f64::consts::TAU;

use planarkin_core::scene::{Plan, Scene, SceneSpec, SceneSweepOptions, SceneSweepOut, Trace, TraceOptions};
use planarkin_core::solve::homotopy::HomotopyOptions;
use planarkin_core::{Never, NewtonOptions};
use serde_json::{json, Map, Value};

use crate::json::{pair, status_name};

/// The keys a scene may have (Python's `planarkin.scene._model.KEYS`), and the required.
const KEYS: [&str; 9] = ["name", "description", "units", "points", "links", "ground", "input", "output", "outputs"];
const REQUIRED: [&str; 4] = ["points", "links", "ground", "input"];
/// Python's `SEED` (the homotopy's random gammas) and default `runs`.
const SEED: u64 = 0x5EED_2026;
const RUNS: i64 = 2;
/// Python's default sweep: 361 input angles from the drawn one through one full turn.
const PATH_ANGLES: usize = 361;

/// A validated scene and the plan that solves every point, kept between requests.
pub(crate) struct Kept {
    scene: Scene,
    plan: Plan,
    opts: SceneSweepOptions,
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

fn pivoted(d: &Map<String, Value>, key: &str) -> Result<(String, String), String> {
    let v = &d[key];
    let table = v.as_object().filter(|t| t.len() == 2 && t.contains_key("link") && t.contains_key("pivot"));
    let t =
        table.ok_or_else(|| entry(key, format!("must be a table with keys 'link' and 'pivot', got {}", repr(v))))?;
    let link = t["link"]
        .as_str()
        .ok_or_else(|| entry(&format!("{key}.link"), format!("must be a link name, got {}", repr(&t["link"]))))?;
    let pivot = t["pivot"]
        .as_str()
        .ok_or_else(|| entry(&format!("{key}.pivot"), format!("must be a point name, got {}", repr(&t["pivot"]))))?;
    Ok((link.to_owned(), pivot.to_owned()))
}

/// The scene file's data as the core's spec (and the `outputs` names), checked as
/// Python's `Scene.__init__` checks it before calling the core.
fn spec(data: &Value) -> Result<(SceneSpec, Option<Vec<String>>), String> {
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
    Ok((SceneSpec { points, links: lk, ground, input, output, ..Default::default() }, outputs))
}

impl Kept {
    /// Validates a scene (the file format's data) as `pk.Scene(data)` does.
    pub(crate) fn new(data: &Value) -> Result<Kept, String> {
        let (spec, outputs) = spec(data)?;
        let scene = Scene::new(spec).map_err(|e| e.to_string())?;
        if let Some(o) = outputs {
            scene.plan(Some(&o)).map_err(|e| e.to_string())?; // names checked, as Python does
        }
        let plan = scene.plan(None).map_err(|e| e.to_string())?;
        let newton = NewtonOptions::new(1e-9, 100).map_err(|e| e.to_string())?;
        let opts = SceneSweepOptions::new(newton, 3f64.to_radians(), None).map_err(|e| e.to_string())?;
        Ok(Kept { scene, plan, opts })
    }

    /// Names, links (as point indices), ground, input, output, the drawn input angle, the
    /// plan's steps, and which points are joints (on two or more links).
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
        json!({
            "ok": true,
            "names": names,
            "drawn": sc.drawn().iter().map(|&p| pair(p)).collect::<Vec<_>>(),
            "links": sc.links().iter().map(|l| json!({"name": l.name, "points": l.points})).collect::<Vec<_>>(),
            "ground": sc.ground(),
            "input": sc.input().map(pivoted),
            "output": sc.output().map(pivoted),
            "input_angle": sc.input_angle(),
            "links_per_point": on,
            "steps": self.plan.steps().iter().map(|s| s.kind.name()).collect::<Vec<_>>(),
        })
    }

    /// Solves `theta` and writes the points in scene order (NaN where unsolved).
    fn sweep(&self, theta: &[f64]) -> Result<Solved, String> {
        let (n, np, nl, ns) = (theta.len(), self.plan.points().len(), self.plan.links().len(), self.plan.steps().len());
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
        self.plan.sweep(theta, &self.opts, out, &Never).map_err(|e| e.to_string())?;
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

    /// The pose at input angle `theta`, reached from the drawn pose as `Scene.sweep` does.
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
    /// turn. The points (361 x P x 2, scene order) go to `nums` from `offset`.
    pub(crate) fn path(&self, nums: &mut Vec<f64>) -> Result<Value, String> {
        let t0 = self.scene.input_angle();
        let theta: Vec<f64> = (0..PATH_ANGLES).map(|k| t0 + k as f64 * (TAU / 360.0)).collect();
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

/// A sweep's arrays, in scene order.
struct Solved {
    points: Vec<f64>,
    status: Vec<i8>,
    det: Vec<f64>,
    limit: Vec<f64>,
    point_status: Vec<i8>,
}
