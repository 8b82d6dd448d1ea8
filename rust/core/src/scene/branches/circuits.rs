//! Circuits as the classes of assemblies that tracing connects: each assembly at an input
//! value traced once, the assemblies its trace meets belonging to its circuit.

use super::assemble::{Assemblies, Assembly};
use super::trace::{Trace, TraceOptions, Tracer};
use crate::error::Error;
use crate::interrupt::{Interrupt, Poll};
use crate::scene::model::Scene;
use crate::scene::vec2::Xy;
use crate::solve::homotopy::HomotopyOptions;
use crate::wrap_angle;

/// One circuit at an input angle.
#[derive(Clone, Debug, PartialEq)]
pub struct Circuit {
    /// Indices into the assemblies at that angle, in the order the trace meets them.
    pub assemblies: Vec<usize>,
    /// Turning points, wrapped to (-pi, pi], in path order.
    pub turning_points: Vec<f64>,
    /// Net change of the input angle once round the circuit (a multiple of 2 pi when
    /// closed: nonzero means the input turns fully round on it).
    pub net_turn: f64,
    /// Smallest and largest input angle on the path (continuous): where the input reverses,
    /// the refined turning points.
    pub range: (f64, f64),
    /// The path.
    pub trace: Trace,
}

impl Tracer<'_> {
    /// Circuits through the assemblies at `theta`: each traced once; the assemblies a
    /// trace meets at `theta` (modulo 2 pi) belong to its circuit.
    pub fn circuits(
        &self,
        theta: f64,
        hopts: &HomotopyOptions,
        opts: &TraceOptions,
        interrupt: &dyn Interrupt,
    ) -> Result<(Assemblies, Vec<Circuit>), Error> {
        let mut found = self.plan.assemblies(theta, hopts, interrupt)?;
        let poll = Poll::new(interrupt);
        let plan = &self.plan;
        let to_frame = |p: &Xy| [(p[0] - plan.origin[0]) / plan.scale, (p[1] - plan.origin[1]) / plan.scale];
        let mut frames: Vec<Vec<Xy>> = found.list.iter().map(|a| a.points.iter().map(to_frame).collect()).collect();
        let mut owner: Vec<Option<usize>> = vec![None; frames.len()];
        let mut circuits = Vec::new();
        let mut k = 0;
        while k < frames.len() {
            if owner[k].is_some() {
                k += 1;
                continue;
            }
            let id = circuits.len();
            let (tr, crossings) = match self.trace_watching(&frames[k], opts, Some(theta), &poll) {
                Ok(r) => r,
                Err(e @ (Error::Interrupted | Error::Allocation { .. })) => return Err(e),
                Err(_) => {
                    // a singular assembly Newton cannot start from: a circuit of its own
                    let mut tr = Trace::default();
                    self.record_pose(&mut tr, &frames[k], theta, plan.dets_at(&frames[k]).0)?;
                    (tr, Vec::new())
                }
            };
            owner[k] = Some(id);
            let mut members = vec![k];
            for pos in crossings {
                let j = match frames.iter().position(|f| max_gap(f, &pos) < 1e-7) {
                    Some(j) => j,
                    None => {
                        // met by tracing but missed by the homotopy: keep it, marked
                        let (det, step_det) = plan.dets_at(&pos);
                        let points = pos
                            .iter()
                            .map(|p| [p[0] * plan.scale + plan.origin[0], p[1] * plan.scale + plan.origin[1]])
                            .collect();
                        found.list.push(Assembly { points, step_det, det, label: "traced".into() });
                        frames.push(pos);
                        owner.push(None);
                        frames.len() - 1
                    }
                };
                if owner[j].is_none() {
                    owner[j] = Some(id);
                    members.push(j);
                }
            }
            // the range's ends are the refined turning points where the input reverses
            let lo = tr.theta.iter().chain(&tr.turning_points).copied().fold(f64::INFINITY, f64::min);
            let hi = tr.theta.iter().chain(&tr.turning_points).copied().fold(f64::NEG_INFINITY, f64::max);
            let net = if tr.closed { tr.theta[tr.theta.len() - 1] - tr.theta[0] } else { f64::NAN };
            circuits.push(Circuit {
                assemblies: members,
                turning_points: tr
                    .turning_points
                    .iter()
                    .map(|&a| if self.plan.linear { a } else { wrap_angle(a) })
                    .collect(),
                net_turn: net,
                range: (lo, hi),
                trace: tr,
            });
            k += 1;
        }
        Ok((found, circuits))
    }
}

/// Largest distance between corresponding points (NaN-free points only).
fn max_gap(a: &[Xy], b: &[Xy]) -> f64 {
    a.iter()
        .zip(b)
        .filter(|(p, q)| p[0].is_finite() && q[0].is_finite())
        .map(|(p, q)| (p[0] - q[0]).abs().max((p[1] - q[1]).abs()))
        .fold(0.0, f64::max)
}

impl Scene {
    /// The assemblies at `theta` grouped by circuit.
    pub fn circuits(
        &self,
        theta: f64,
        hopts: &HomotopyOptions,
        topts: &TraceOptions,
        interrupt: &dyn Interrupt,
    ) -> Result<(Assemblies, Vec<Circuit>), Error> {
        Tracer::new(self)?.circuits(theta, hopts, topts, interrupt)
    }
}
