//! Scenes: the page's JSON to the core's file format (`planarkin_core::scene::format`,
//! the one place its keys, checks, messages and defaults live, as for Python), then the
//! core's validation, sweeps, assemblies and circuits, as JSON and flat numbers.
//!
//! The core's defaults are used throughout (tol, max_iter, max step, the homotopy's seed
//! and runs, the trace's step and length, the default inputs, a linear input's stroke), so
//! the page shows what `pk.Scene` computes.

use planarkin_core::scene::format::{self, Drive, Parsed};
use planarkin_core::scene::{LinearKind, Plan, Scene, SceneSweepBuffers, SceneSweepOptions, Trace};
use planarkin_core::Never;
use serde_json::{json, Value};

use crate::json::{pair, status_name};

/// A validated scene and the plan that solves every point, kept between requests.
pub(crate) struct Kept {
    scene: Scene,
    plan: Plan,
    opts: SceneSweepOptions,
    /// The output as the file declares it (a linear one is not in the core's scene).
    output: Option<Drive>,
    /// The drawing's extent (`format::size`).
    size: f64,
    /// A linear input's reachable interval (`Scene.stroke()`); None for an angle input.
    stroke: Option<(f64, f64)>,
}

/// The page's JSON as the format's data (conversion only: the format checks it).
fn value(v: &Value) -> format::Value {
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

impl Kept {
    /// Validates a scene (the file format's data) as `pk.Scene(data)` does.
    pub(crate) fn new(data: &Value) -> Result<Kept, String> {
        let mut parsed = format::parse(&value(data)).map_err(|e| e.to_string())?;
        // a sketch: the core assembles the exact pose, which is what is drawn and saved
        parsed.assemble(&Never).map_err(|e| e.to_string())?;
        let Parsed { spec, output, outputs, .. } = parsed;
        let scene = Scene::new(spec).map_err(|e| e.to_string())?;
        // names checked, as Python does; the stroke is found on this plan, as Python's is
        let outputs_plan = match outputs {
            Some(o) => Some(scene.plan(Some(&o)).map_err(|e| e.to_string())?),
            None => None,
        };
        let plan = scene.plan(None).map_err(|e| e.to_string())?;
        let size = format::size(scene.drawn());
        let linear = scene.linear_input().is_some();
        let opts = format::sweep_options(linear, size).map_err(|e| e.to_string())?;
        let mut kept = Kept { scene, plan, opts, output, size, stroke: None };
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
            json!({"kind": format::kind_name(l.kind), "name": name, "index": l.index, "guide": l.guide})
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
            "linear_output": self.linear_output().map(|(k, n)| json!({"kind": format::kind_name(k), "name": n})),
            "input_angle": sc.input_angle(),
            "stroke": self.stroke.map(|(lo, hi)| [lo, hi]),
            "size": self.size,
            "slots": slots,
            "prismatic": prismatic,
            "links_per_point": on,
            "steps": self.plan.steps().iter().map(|s| s.kind.name()).collect::<Vec<_>>(),
        })
    }

    /// The output as the file declares it when it is a displacement (kind, name).
    fn linear_output(&self) -> Option<(LinearKind, &str)> {
        match &self.output {
            Some(Drive::Linear { kind, name }) => Some((*kind, name.as_str())),
            _ => None,
        }
    }

    /// Solves `theta` and writes the points in scene order (NaN where unsolved).
    fn sweep(&self, theta: &[f64]) -> Result<Solved, String> {
        let mut b = SceneSweepBuffers::new(&self.plan, theta.len(), false).map_err(|e| e.to_string())?;
        self.plan.sweep(theta, &self.opts, b.out(), &Never).map_err(|e| e.to_string())?;
        let (n, np) = (theta.len(), self.plan.points().len());
        // in scene order: the plan reports its points in its own order
        let total = self.scene.point_names().len();
        let mut points = vec![f64::NAN; n * total * 2];
        let mut point_status = vec![0i8; n * total];
        for i in 0..n {
            for (j, &p) in self.plan.points().iter().enumerate() {
                points[2 * (i * total + p)..2 * (i * total + p) + 2]
                    .copy_from_slice(&b.points[2 * (i * np + j)..2 * (i * np + j) + 2]);
                point_status[i * total + p] = b.point_status[i * np + j];
            }
        }
        // a declared linear output's coordinate, from the core as Python gets it
        let output = self.output.as_ref().and_then(|o| {
            let every: Vec<usize> = (0..total).collect();
            format::linear_output(&self.scene, o, &every, &points)
        });
        Ok(Solved { points, status: b.status, det: b.det, limit: b.limit, point_status, output })
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
            "output": s.output.map(|o| o[0]),
        }))
    }

    /// `Scene.sweep()`'s default: 361 input angles from the drawn one through one full
    /// turn, or 361 displacements across a linear input's stroke (`format::default_inputs`).
    /// The points (361 x P x 2, scene order) go to `nums` from `offset`.
    pub(crate) fn path(&self, nums: &mut Vec<f64>) -> Result<Value, String> {
        let theta = format::default_inputs(self.scene.input_angle(), self.stroke);
        let s = self.sweep(&theta)?;
        let offset = nums.len();
        nums.extend_from_slice(&s.points);
        Ok(json!({
            "offset": offset,
            "n": theta.len(),
            "theta": theta,
            "status": s.status,
            "limit": s.limit,
            "output": s.output,
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
        let opts = format::homotopy_options().map_err(|e| e.to_string())?;
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
        let hopts = format::homotopy_options().map_err(|e| e.to_string())?;
        let topts = format::trace_options().map_err(|e| e.to_string())?;
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
    /// A declared linear output's coordinate (None for an angle output or none).
    output: Option<Vec<f64>>,
}
