//! The declared output's coordinate along a sweep when it is a displacement (along a slot
//! or prismatic pair): the bindings read it here, from the points a sweep reports.

use super::Drive;
use crate::scene::{LinearKind, Scene};

/// The displacement of `output` (a [`Drive::Linear`] of `scene`) along its line at each of
/// a sweep's N poses, measured from the drawn pose: `coords` holds N poses of the points
/// `reported` (scene indices), (N, P, 2) row-major. None when the output is an angle, names
/// no joint of the scene, or its points are not among those reported.
pub fn linear_output(scene: &Scene, output: &Drive, reported: &[usize], coords: &[f64]) -> Option<Vec<f64>> {
    let Drive::Linear { kind, name } = output else { return None };
    let (q, (a, b)) = match kind {
        LinearKind::Slot => {
            let s = scene.slots().iter().find(|s| &s.name == name)?;
            (s.point, s.line)
        }
        LinearKind::Prismatic => {
            let p = scene.prismatic().iter().find(|p| &p.name == name)?;
            (scene.links()[p.link].points[0], p.line)
        }
    };
    let col = |i: usize| reported.iter().position(|&r| r == i);
    let (cq, ca, cb) = (col(q)?, col(a)?, col(b)?);
    let np = reported.len();
    let drawn = scene.drawn();
    let (dq, da, db) = (drawn[q], drawn[a], drawn[b]);
    let u0 = [db[0] - da[0], db[1] - da[1]];
    let h0 = u0[0].hypot(u0[1]);
    let s0 = (dq[0] - da[0]) * (u0[0] / h0) + (dq[1] - da[1]) * (u0[1] / h0);
    let n = if np == 0 { 0 } else { coords.len() / (2 * np) };
    let at = |i: usize, c: usize| [coords[2 * (i * np + c)], coords[2 * (i * np + c) + 1]];
    Some(
        (0..n)
            .map(|i| {
                let (pq, pa, pb) = (at(i, cq), at(i, ca), at(i, cb));
                let u = [pb[0] - pa[0], pb[1] - pa[1]];
                let h = u[0].hypot(u[1]);
                // unit first: no square overflows
                (pq[0] - pa[0]) * (u[0] / h) + (pq[1] - pa[1]) * (u[1] / h) - s0
            })
            .collect(),
    )
}
