//! The kept scene's branches (the core's `scene/branches`): every assembly at one input
//! value and the circuits joining them, each circuit's trace as flat numbers.

use planarkin_core::scene::{format, Assemblies, Trace};
use planarkin_core::Never;
use serde_json::{json, Value};

use super::Kept;
use crate::json::pair;

impl Kept {
    fn assembly_list(&self, a: &Assemblies) -> Vec<Value> {
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
