//! Scenes for the page, mirroring the core's `scene/`: here the kept scene (its validation
//! through the core's file format, and its description); `sweep` (a pose, the default
//! path), `branches` (assemblies, circuits, their traces) and `format` (the page's JSON to
//! the format's data). Convert to JSON and flat numbers; nothing numeric.
//!
//! The core's defaults are used throughout (tol, max_iter, max step, the homotopy's seed
//! and runs, the trace's step and length, the default inputs, a linear input's stroke), so
//! the page shows what `pk.Scene` computes.

use planarkin_core::scene::format::{self as core_format, Drive, Parsed};
use planarkin_core::scene::{LinearKind, Plan, Scene, SceneSweepOptions};
use planarkin_core::Never;
use serde_json::{json, Value};

use crate::json::pair;

// As in the core: this entry (the kept scene) calls `sweep` for its stroke; `sweep`,
// `branches` and `forces` answer the requests on it; `format` converts the page's JSON for
// the format.
mod branches;
mod forces;
mod format;
mod sweep;

/// A validated scene and the plan that solves every point, kept between requests.
pub(crate) struct Kept {
    scene: Scene,
    plan: Plan,
    opts: SceneSweepOptions,
    /// The output as the file declares it (a linear one is not in the core's scene).
    output: Option<Drive>,
    /// The drawing's extent (the core's `format::size`).
    size: f64,
    /// A linear input's reachable interval (`Scene.stroke()`); None for an angle input.
    stroke: Option<(f64, f64)>,
    /// The input as the file declares it, the loads (None without) and the units' inertia
    /// factor and names (length, force), for the forces.
    input: Drive,
    loads: Option<core_format::Loads>,
    factor: f64,
    unit_names: (Option<String>, String),
}

impl Kept {
    /// Validates a scene (the file format's data) as `pk.Scene(data)` does.
    pub(crate) fn new(data: &Value) -> Result<Kept, String> {
        let mut parsed = core_format::parse(&format::value(data)).map_err(|e| e.to_string())?;
        // a sketch: the core assembles the exact pose, which is what is drawn and saved
        parsed.assemble(&Never).map_err(|e| e.to_string())?;
        let Parsed { spec, output, outputs, input, loads, units, unit_table, limits, .. } = parsed;
        let factor = planarkin_core::forces::inertia_factor(units.as_deref(), unit_table.as_ref());
        let unit_names = (
            unit_table.as_ref().and_then(|t| t.length.clone()).or(units),
            unit_table.and_then(|t| t.force).unwrap_or_else(|| "N".into()),
        );
        let scene = Scene::new(spec).and_then(|s| s.with_limits(&limits)).map_err(|e| e.to_string())?;
        // names checked, as Python does; the stroke is found on this plan, as Python's is
        let outputs_plan = match outputs {
            Some(o) => Some(scene.plan(Some(&o)).map_err(|e| e.to_string())?),
            None => None,
        };
        let plan = scene.plan(None).map_err(|e| e.to_string())?;
        let size = core_format::size(scene.drawn());
        let linear = scene.linear_input().is_some();
        let opts = core_format::sweep_options(linear, size).map_err(|e| e.to_string())?;
        let mut kept = Kept { scene, plan, opts, output, size, stroke: None, input, loads, factor, unit_names };
        if linear {
            kept.stroke = Some(kept.find_stroke(outputs_plan.as_ref().unwrap_or(&kept.plan))?);
        }
        Ok(kept)
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
            json!({"kind": core_format::kind_name(l.kind), "name": name, "index": l.index, "guide": l.guide})
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
            "linear_output": self.linear_output().map(|(k, n)| json!({"kind": core_format::kind_name(k), "name": n})),
            "input_angle": sc.input_angle(),
            "stroke": self.stroke.map(|(lo, hi)| [lo, hi]),
            "size": self.size,
            "slots": slots,
            "prismatic": prismatic,
            "links_per_point": on,
            "steps": self.plan.steps().iter().map(|s| s.kind.name()).collect::<Vec<_>>(),
            "loads": self.loads.is_some(),
        })
    }

    /// The output as the file declares it when it is a displacement (kind, name).
    fn linear_output(&self) -> Option<(LinearKind, &str)> {
        match &self.output {
            Some(Drive::Linear { kind, name }) => Some((*kind, name.as_str())),
            _ => None,
        }
    }
}
