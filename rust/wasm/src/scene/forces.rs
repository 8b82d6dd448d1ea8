//! The kept scene's forces (the core's `forces/`): the statics input effort and every pin
//! reaction over the default input values, on a sweep with velocities (every point), as
//! `Scene.statics()` gives them; the arrays as flat numbers.

use planarkin_core::forces::{self, Model, Motion};
use planarkin_core::scene::{format, SceneSweepBuffers, SceneSweepOptions};
use planarkin_core::Never;
use serde_json::{json, Value};

use super::Kept;
use crate::json::status_name;

impl Kept {
    /// `{"loads": false}` without loads; else the input values (`theta`), their statuses,
    /// the effort's unit, the virtual-work check, and offsets into `nums` of the effort
    /// (N values, NaN where not solved) and of each pin's reaction (N x 2: the force the
    /// joint's first link exerts on `link` at `point`, both scene indices).
    pub(crate) fn forces(&self, nums: &mut Vec<f64>) -> Result<Value, String> {
        let Some(loads) = &self.loads else { return Ok(json!({ "loads": false })) };
        let err = |e: planarkin_core::Error| e.to_string();
        let sc = &self.scene;
        let parts = forces::parts(sc, &self.input, loads, self.output.as_ref(), self.factor).map_err(err)?;
        let model = Model::new(parts).map_err(err)?;
        let names = sc.point_names();
        // the kept plan reports every point and link (`outputs="all"` in Python)
        let plan = &self.plan;
        let theta = format::default_inputs(sc.input_angle(), self.stroke);
        let opts = SceneSweepOptions { omega: Some(1.0), ..self.opts };
        let mut b = SceneSweepBuffers::new(plan, theta.len(), true).map_err(err)?;
        plan.sweep(&theta, &opts, b.out(), &Never).map_err(err)?;
        let point_map: Vec<usize> = (0..names.len())
            .map(|p| plan.points().iter().position(|&q| q == p).ok_or("a point is not swept"))
            .collect::<Result<_, _>>()?;
        let ground = sc.ground();
        let link_map: Vec<usize> = (0..sc.links().len())
            .filter(|&l| l != ground)
            .map(|l| plan.links().iter().position(|&k| k == l).ok_or("a link is not swept"))
            .collect::<Result<_, _>>()?;
        let (velocity, angular) = b.velocity.as_ref().ok_or("no velocities")?;
        let motion = Motion {
            theta: &theta,
            status: &b.status,
            det: &b.det,
            coords: &b.points,
            velocity,
            acceleration: None,
            angular_velocity: angular,
            angular_acceleration: None,
            point_map: &point_map,
            link_map: &link_map,
            rate: 1.0,
        };
        let out = forces::solve(&model, &motion, None).map_err(err)?;
        let (n, k) = (theta.len(), model.columns());
        let effort = nums.len();
        nums.extend((0..n).map(|i| out.unknowns[i * k + k - 1]));
        let pins: Vec<Value> = forces::pins(sc)
            .into_iter()
            .map(|(point, link, column)| {
                let offset = nums.len();
                for i in 0..n {
                    nums.extend_from_slice(&out.unknowns[i * k + column..i * k + column + 2]);
                }
                json!({ "point": point, "link": link, "offset": offset })
            })
            .collect();
        let (length, force) = &self.unit_names;
        let angle = matches!(self.input, format::Drive::Angle { .. });
        let unit = if angle { format!("{force}*{}", length.as_deref().unwrap_or("length")) } else { force.clone() };
        Ok(json!({
            "loads": true,
            "n": n,
            "theta": theta,
            "status": out.status.iter().map(|&c| status_name(c)).collect::<Vec<_>>(),
            "effort": effort,
            "unit": unit,
            "force_unit": force,
            "pins": pins,
            "check": out.check_virtual_work,
        }))
    }
}
