//! A linear input's stroke: the interval of displacements the drawn pose reaches, both ends
//! dead points. The motion is followed out from the drawn pose both ways over displacements
//! of up to [`REACH`] sizes of the drawing, and each end is the dead point where it stops
//! (`limit` of the values not reached on that side, refined by the sweep's step halving),
//! else the farthest value reached.

use super::options::{SceneSweepOptions, SceneSweepOut};
use super::plan::Plan;
use crate::error::{try_zeros, Error};
use crate::interrupt::Interrupt;

/// How far the probe looks each way, in sizes of the drawing.
const REACH: f64 = 4.0;
/// Values in the probe sweep.
const PROBE: usize = 801;

impl Plan {
    /// The stroke `(lo, hi)` (lo <= 0 <= hi) of a plan with a linear input, for a drawing of
    /// extent `size` (scene units). Errors where the input is an angle.
    pub fn stroke(&self, size: f64, opts: &SceneSweepOptions, interrupt: &dyn Interrupt) -> Result<(f64, f64), Error> {
        if !self.linear {
            return Err(Error::scene("input", "a stroke is a linear input's (this input is an angle)"));
        }
        let reach = REACH * size;
        let s: Vec<f64> = (0..PROBE).map(|k| -reach + 2.0 * reach * k as f64 / (PROBE - 1) as f64).collect();
        let (np, nl, ns) = (self.points.len(), self.links.len(), self.steps.len());
        let what = || "stroke probe".to_string();
        let (mut points, mut angles) = (try_zeros(what, PROBE * np * 2)?, try_zeros(what, PROBE * nl)?);
        let (mut det, mut limit) = (try_zeros(what, PROBE)?, try_zeros(what, PROBE)?);
        let (mut step_det, mut nit) = (try_zeros(what, PROBE * ns)?, try_zeros(what, PROBE)?);
        let (mut status, mut step_status) = (try_zeros(what, PROBE)?, try_zeros(what, PROBE * ns)?);
        let mut point_status = try_zeros(what, PROBE * np)?;
        let out = SceneSweepOut {
            points: &mut points,
            angles: &mut angles,
            status: &mut status,
            nit: &mut nit,
            det: &mut det,
            limit: &mut limit,
            step_status: &mut step_status,
            step_det: &mut step_det,
            point_status: &mut point_status,
            velocity: None,
            acceleration: None,
        };
        self.sweep(&s, opts, out, interrupt)?;
        let end = |below: bool| {
            let side = |k: usize| if below { s[k] < 0.0 } else { s[k] > 0.0 };
            let pick = |a: f64, b: f64| if below { a.min(b) } else { a.max(b) };
            let lim = (0..PROBE).filter(|&k| side(k) && status[k] != 0 && limit[k].is_finite()).map(|k| limit[k]);
            let solved = (0..PROBE).filter(|&k| side(k) && status[k] == 0).map(|k| s[k]);
            lim.reduce(pick).or_else(|| solved.reduce(pick)).unwrap_or(0.0)
        };
        Ok((end(true), end(false)))
    }
}
