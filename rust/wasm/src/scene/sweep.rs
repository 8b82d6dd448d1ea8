//! The kept scene's sweeps (the core's `scene/sweep`): one pose, the default path over
//! 361 input values, a linear input's stroke, and a declared linear output's coordinate
//! from the core; points in scene order, as JSON and flat numbers.

use planarkin_core::scene::{format, Plan, SceneSweepBuffers};
use planarkin_core::Never;
use serde_json::{json, Value};

use super::Kept;
use crate::json::{pair, status_name};

impl Kept {
    /// `Scene.stroke()`: the core's `Plan::stroke` on this plan.
    pub(super) fn find_stroke(&self, plan: &Plan) -> Result<(f64, f64), String> {
        plan.stroke(self.size, &self.opts, &Never).map_err(|e| e.to_string())
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
