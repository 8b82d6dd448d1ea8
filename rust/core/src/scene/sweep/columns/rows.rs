//! The block's rows of the outputs: positions and the links' angles, their rates, and the
//! steps' conditioning and statuses, written once per block.

// the column loops index several arrays (and an offset into each) by the same angle
#![allow(clippy::needless_range_loop)]

use std::ops::Range;

use super::frame::{Columns, B, OK};
use crate::scene::build::Plan;
use crate::scene::sweep::options::{SceneSweepOptions, SceneSweepOut};
use crate::scene::vec2::angular_acceleration;

/// The block's rows of the outputs, written point by point (and link by link, step by
/// step) down the block's values: a point failing at a value is NaN there unless every
/// step solved (then its status is CONVERGED too).
#[inline(always)]
pub(super) fn write_block(
    plan: &Plan,
    c: &Columns<'_>,
    sdet: &[f64],
    sst: &[i8],
    first_bad: &[i8],
    k0: usize,
    m: usize,
    opts: &SceneSweepOptions,
    out: &mut SceneSweepOut<'_>,
) {
    let (sc, first_bad) = (plan.scale, &first_bad[..m]);
    // per unit of the sweep variable (a displacement's rates carry 1 / scale)
    let omega = opts.omega.unwrap_or(0.0) * if plan.linear { 1.0 / sc } else { 1.0 };
    let rows = k0..k0 + m;
    write_poses(plan, c, first_bad, rows.clone(), out);
    write_rates(plan, c, first_bad, rows.clone(), omega, out);
    write_steps(plan, sdet, sst, first_bad, rows, out);
}

/// The positions (scene coordinates) and the links' angles.
#[inline(always)]
fn write_poses(plan: &Plan, c: &Columns<'_>, first_bad: &[i8], rows: Range<usize>, out: &mut SceneSweepOut<'_>) {
    let (np, nl, m) = (plan.points.len(), plan.links.len(), first_bad.len());
    let (sc, org) = (plan.scale, plan.origin);
    let col = |p: usize| p * B..p * B + m;
    // a point's column: solved where it or every step is
    let good = |p: usize| c.st[col(p)].iter().zip(first_bad).map(|(&st, &fb)| fb == OK || st == OK);
    if np > 0 {
        let pts = &mut out.points[2 * rows.start * np..2 * rows.end * np];
        let pst = &mut out.point_status[rows.start * np..rows.end * np];
        let all_ok = first_bad.iter().fold(OK, |a, &s| a | s) == OK;
        if all_ok {
            // every step solved: every point is, with status CONVERGED
            for (i, &p) in plan.points.iter().enumerate() {
                let (xs, ys) = (&c.x[col(p)], &c.y[col(p)]);
                for ((row, &x), &y) in pts.chunks_exact_mut(2 * np).zip(xs).zip(ys) {
                    let dst = &mut row[2 * i..2 * i + 2];
                    dst[0] = x * sc + org[0];
                    dst[1] = y * sc + org[1];
                }
            }
            pst.fill(OK);
        } else {
            for (i, &p) in plan.points.iter().enumerate() {
                let (xs, ys) = (&c.x[col(p)], &c.y[col(p)]);
                let dst = pts.chunks_exact_mut(2 * np).zip(pst.chunks_exact_mut(np));
                for ((((row, code), &x), &y), (ok, &st)) in dst.zip(xs).zip(ys).zip(good(p).zip(&c.st[col(p)])) {
                    code[i] = st;
                    row[2 * i] = if ok { x * sc + org[0] } else { f64::NAN };
                    row[2 * i + 1] = if ok { y * sc + org[1] } else { f64::NAN };
                }
            }
        }
    }
    if nl > 0 {
        let angles = &mut out.angles[rows.start * nl..rows.end * nl];
        let fast = crate::simd::enabled();
        // each link's directions down the block's column first (a branch-free loop that
        // vectorizes), then into its place in the rows
        let (mut dx, mut dy, mut dir) = ([0.0; B], [0.0; B], [0.0; B]);
        for (i, &(a, b)) in plan.link_points.iter().enumerate() {
            let (dx, dy, dir) = (&mut dx[..m], &mut dy[..m], &mut dir[..m]);
            for (((dx, dy), (xa, ya)), (xb, yb)) in dx
                .iter_mut()
                .zip(dy.iter_mut())
                .zip(c.x[col(a)].iter().zip(&c.y[col(a)]))
                .zip(c.x[col(b)].iter().zip(&c.y[col(b)]))
            {
                *dx = xb - xa;
                *dy = yb - ya;
            }
            if fast {
                crate::simd::directions_body(dx, dy, dir, true);
            } else {
                crate::simd::directions_body(dx, dy, dir, false);
            }
            let both = good(a).zip(good(b));
            for ((row, (oa, ob)), &d) in angles.chunks_exact_mut(nl).zip(both).zip(&*dir) {
                row[i] = if oa && ob { d } else { f64::NAN };
            }
        }
    }
}

/// The velocities and accelerations of the points and links, where asked for (`omega`:
/// the input's rate, per unit of the sweep variable).
#[inline(always)]
fn write_rates(
    plan: &Plan,
    c: &Columns<'_>,
    first_bad: &[i8],
    rows: Range<usize>,
    omega: f64,
    out: &mut SceneSweepOut<'_>,
) {
    let (np, nl, m) = (plan.points.len(), plan.links.len(), first_bad.len());
    let sc = plan.scale;
    let w2 = omega * omega;
    let col = |p: usize| p * B..p * B + m;
    // a point's column: solved where it or every step is
    let good = |p: usize| c.st[col(p)].iter().zip(first_bad).map(|(&st, &fb)| fb == OK || st == OK);
    if let Some((v, w)) = out.velocity.as_mut() {
        for (i, &p) in plan.points.iter().enumerate() {
            let dst = v[2 * rows.start * np..2 * rows.end * np].chunks_exact_mut(2 * np);
            for (j, (row, ok)) in dst.zip(good(p)).enumerate() {
                let o = p * B + j;
                row[2 * i] = if ok { c.vx[o] * sc * omega } else { f64::NAN };
                row[2 * i + 1] = if ok { c.vy[o] * sc * omega } else { f64::NAN };
            }
        }
        for (i, &(a, b)) in plan.link_points.iter().enumerate() {
            let dst = w[rows.start * nl..rows.end * nl].chunks_exact_mut(nl);
            for (j, (row, (oa, ob))) in dst.zip(good(a).zip(good(b))).enumerate() {
                let (pa, pb) = (a * B + j, b * B + j);
                let (dx, dy) = (c.x[pb] - c.x[pa], c.y[pb] - c.y[pa]);
                let (dvx, dvy) = (c.vx[pb] - c.vx[pa], c.vy[pb] - c.vy[pa]);
                row[i] = if oa && ob { (dx * dvy - dy * dvx) / (dx * dx + dy * dy) * omega } else { f64::NAN };
            }
        }
    }
    if let Some((acc, alpha)) = out.acceleration.as_mut() {
        for (i, &p) in plan.points.iter().enumerate() {
            let dst = acc[2 * rows.start * np..2 * rows.end * np].chunks_exact_mut(2 * np);
            for (j, (row, ok)) in dst.zip(good(p)).enumerate() {
                let o = p * B + j;
                row[2 * i] = if ok { c.ax[o] * sc * w2 } else { f64::NAN };
                row[2 * i + 1] = if ok { c.ay[o] * sc * w2 } else { f64::NAN };
            }
        }
        for (i, &(a, b)) in plan.link_points.iter().enumerate() {
            let dst = alpha[rows.start * nl..rows.end * nl].chunks_exact_mut(nl);
            for (j, (row, (oa, ob))) in dst.zip(good(a).zip(good(b))).enumerate() {
                let (pa, pb) = (a * B + j, b * B + j);
                let d = [c.x[pb] - c.x[pa], c.y[pb] - c.y[pa]];
                let dv = [c.vx[pb] - c.vx[pa], c.vy[pb] - c.vy[pa]];
                let dw = [c.ax[pb] - c.ax[pa], c.ay[pb] - c.ay[pa]];
                row[i] = if oa && ob { angular_acceleration(d, dv, dw) * w2 } else { f64::NAN };
            }
        }
    }
}

/// The product of the steps' conditioning, each step's status and conditioning, and the
/// values' statuses.
#[inline(always)]
fn write_steps(
    plan: &Plan,
    sdet: &[f64],
    sst: &[i8],
    first_bad: &[i8],
    rows: Range<usize>,
    out: &mut SceneSweepOut<'_>,
) {
    let (ns, m) = (plan.steps.len(), first_bad.len());
    // the product of the steps' conditioning, step by step down the block's columns
    let det = &mut out.det[rows.clone()];
    det.fill(1.0);
    for dt in sdet.chunks_exact(B).take(ns) {
        for (total, &dt) in det.iter_mut().zip(dt) {
            *total *= dt;
        }
    }
    if ns > 0 {
        let (codes, dets) =
            (&mut out.step_status[rows.start * ns..rows.end * ns], &mut out.step_det[rows.start * ns..rows.end * ns]);
        for s in 0..ns {
            let (st, dt) = (&sst[s * B..s * B + m], &sdet[s * B..s * B + m]);
            for (((code, d), &st), &dt) in codes.chunks_exact_mut(ns).zip(dets.chunks_exact_mut(ns)).zip(st).zip(dt) {
                code[s] = st;
                d[s] = dt;
            }
        }
    }
    out.status[rows.clone()].copy_from_slice(first_bad);
    out.limit[rows.clone()].fill(f64::NAN);
    out.nit[rows].fill(0);
}
