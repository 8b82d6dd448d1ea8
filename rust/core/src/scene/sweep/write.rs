//! One row of a continuation sweep's outputs from the solver's state: positions, the
//! links' directions, statuses, conditioning and the requested rates.

use super::continuation::Solver;
use super::options::SceneSweepOut;
use crate::scene::vec2::{angular_acceleration, cross, dot, sub};
use crate::Status;

impl Solver<'_> {
    /// The status of the last evaluation: the first operation's that did not converge.
    pub(super) fn status(&self) -> Status {
        if self.any_failure {
            self.op_status.iter().copied().find(|s| *s != Status::Converged).unwrap_or(Status::Converged)
        } else {
            Status::Converged
        }
    }

    /// Writes row `k` of the outputs; the links' directions go to `dirs` (row `k` of its x
    /// half and of its y half, NaN where a point is not solved), whose angles
    /// [`Plan::sweep`] takes at the end, all at once.
    pub(super) fn write(&self, k: usize, out: &mut SceneSweepOut<'_>, dirs: &mut [f64]) {
        let plan = self.plan;
        let (np, nl, ns) = (plan.points.len(), plan.links.len(), plan.steps.len());
        let (sc, org) = (plan.scale, plan.origin);
        let all_ok = !self.any_failure;
        let row = &mut out.points[2 * k * np..2 * (k + 1) * np];
        for (dst, &p) in row.chunks_exact_mut(2).zip(&plan.points) {
            let xy = self.pos[p];
            dst[0] = xy[0] * sc + org[0];
            dst[1] = xy[1] * sc + org[1];
        }
        let pst = &mut out.point_status[k * np..(k + 1) * np];
        if all_ok {
            pst.fill(0);
        } else {
            for ((code, dst), &p) in pst.iter_mut().zip(row.chunks_exact_mut(2)).zip(&plan.points) {
                *code = self.pst[p].code();
                if self.pst[p] != Status::Converged {
                    dst.fill(f64::NAN);
                }
            }
        }
        let ok = |p: usize| all_ok || self.pst[p] == Status::Converged;
        let (dx, dy) = dirs.split_at_mut(dirs.len() / 2);
        let row = dx[k * nl..(k + 1) * nl].iter_mut().zip(&mut dy[k * nl..(k + 1) * nl]);
        for ((x, y), &(a, b)) in row.zip(&plan.link_points) {
            [*x, *y] = if ok(a) && ok(b) { sub(self.pos[b], self.pos[a]) } else { [f64::NAN; 2] };
        }
        if let Some((v, w)) = out.velocity.as_mut() {
            // per unit of the sweep variable (a displacement's rates carry 1 / scale)
            let omega = self.opts.omega.unwrap_or(0.0) * self.rate();
            for (dst, &p) in v[2 * k * np..2 * (k + 1) * np].chunks_exact_mut(2).zip(&plan.points) {
                let (u, good) = (self.vel[p], ok(p));
                dst[0] = if good { u[0] * sc * omega } else { f64::NAN };
                dst[1] = if good { u[1] * sc * omega } else { f64::NAN };
            }
            for (dst, &(a, b)) in w[k * nl..(k + 1) * nl].iter_mut().zip(&plan.link_points) {
                let (d, dv) = (sub(self.pos[b], self.pos[a]), sub(self.vel[b], self.vel[a]));
                *dst = if ok(a) && ok(b) { cross(d, dv) / dot(d, d) * omega } else { f64::NAN };
            }
        }
        if let Some((acc, alpha)) = out.acceleration.as_mut() {
            let w2 = (self.opts.omega.unwrap_or(0.0) * self.rate()).powi(2);
            for (dst, &p) in acc[2 * k * np..2 * (k + 1) * np].chunks_exact_mut(2).zip(&plan.points) {
                let (u, good) = (self.acc[p], ok(p));
                dst[0] = if good { u[0] * sc * w2 } else { f64::NAN };
                dst[1] = if good { u[1] * sc * w2 } else { f64::NAN };
            }
            for (dst, &(a, b)) in alpha[k * nl..(k + 1) * nl].iter_mut().zip(&plan.link_points) {
                let (d, dv) = (sub(self.pos[b], self.pos[a]), sub(self.vel[b], self.vel[a]));
                let dw = sub(self.acc[b], self.acc[a]);
                *dst = if ok(a) && ok(b) { angular_acceleration(d, dv, dw) * w2 } else { f64::NAN };
            }
        }
        let status = self.status();
        let mut det = 1.0;
        let (sst, sdet) = (&mut out.step_status[k * ns..(k + 1) * ns], &mut out.step_det[k * ns..(k + 1) * ns]);
        for ((code, d), &i) in sst.iter_mut().zip(sdet.iter_mut()).zip(&plan.step_op) {
            *code = self.op_status[i].code();
            *d = self.op_det[i];
            det *= self.op_det[i];
        }
        out.status[k] = status.code();
        // a pose not solved has no conditioning (a dead point's is in `step_det`)
        out.det[k] = if status == Status::Converged { det } else { f64::NAN };
        out.limit[k] = f64::NAN;
        out.nit[k] = self.nit;
    }
}
