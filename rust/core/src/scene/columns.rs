//! The sweep of a plan with no group (dyads and rigid carries only): nothing carries over
//! from one angle to the next, so each operation runs over a block of angles at a time,
//! on columns of coordinates (tight loops, no per-angle dispatch), and the rows of the
//! outputs are written once per block. Same numbers as the per-angle path of `sweep`.

// the column loops index several arrays (and an offset into each) by the same angle
#![allow(clippy::needless_range_loop)]

use super::dyad::{Dyad, DyadOut};
use super::options::{SceneSweepOptions, SceneSweepOut};
use super::plan::{Op, Plan};
use super::vec2::angular_acceleration;
use crate::error::Error;
use crate::interrupt::Poll;
use crate::Status;

/// Angles per block: the columns of a block stay in cache.
const B: usize = 128;

const OK: i8 = 0;

/// Columns of one block: point p's values for the block's angles are `[p * B .. p * B + m]`.
struct Columns {
    x: Vec<f64>,
    y: Vec<f64>,
    vx: Vec<f64>,
    vy: Vec<f64>,
    /// Second derivatives by the input angle (empty unless accelerations are asked for).
    ax: Vec<f64>,
    ay: Vec<f64>,
    st: Vec<i8>,
}

pub(super) fn sweep(
    plan: &Plan,
    theta: &[f64],
    opts: &SceneSweepOptions,
    out: &mut SceneSweepOut<'_>,
    poll: &Poll<'_>,
) -> Result<(), Error> {
    let np = plan.npoints;
    // velocities and accelerations go together: both come with `omega`
    let vel = opts.omega.is_some();
    let nv = if vel { np * B } else { 0 };
    let mut c = Columns {
        x: vec![0.0; np * B],
        y: vec![0.0; np * B],
        vx: vec![0.0; nv],
        vy: vec![0.0; nv],
        ax: vec![0.0; nv],
        ay: vec![0.0; nv],
        st: vec![OK; np * B],
    };
    for &(p, xy) in &plan.fixed {
        c.x[p * B..(p + 1) * B].fill(xy[0]);
        c.y[p * B..(p + 1) * B].fill(xy[1]);
    }
    let ns = plan.steps.len();
    let mut step_of = vec![usize::MAX; plan.ops.len()];
    for (s, &i) in plan.step_op.iter().enumerate() {
        step_of[i] = s;
    }
    let mut sdet = vec![1.0; ns * B];
    let mut sst = vec![OK; ns * B];
    let mut first_bad = [OK; B];
    let (mut cs, mut sn) = ([0.0; B], [0.0; B]);
    for (b, block) in theta.chunks(B).enumerate() {
        for _ in block {
            poll.tick()?;
        }
        let m = block.len();
        let k0 = b * B;
        first_bad[..m].fill(OK);
        for j in 0..m {
            let (s, co) = block[j].sin_cos();
            sn[j] = s;
            cs[j] = co;
        }
        for (i, op) in plan.ops.iter().enumerate() {
            match op {
                Op::Input { q, lam, mu } => {
                    let (px, py) = (plan.pivot[0], plan.pivot[1]);
                    let o = q * B;
                    for j in 0..m {
                        let (u0, u1) = (cs[j], sn[j]);
                        c.x[o + j] = px + lam * u0 - mu * u1;
                        c.y[o + j] = py + lam * u1 + mu * u0;
                        let st = if block[j].is_finite() { OK } else { Status::NonFinite.code() };
                        c.st[o + j] = st;
                        if st != OK && first_bad[j] == OK {
                            first_bad[j] = st;
                        }
                    }
                    if vel {
                        for j in 0..m {
                            let (u0, u1) = (cs[j], sn[j]);
                            c.vx[o + j] = -lam * u1 - mu * u0;
                            c.vy[o + j] = lam * u0 - mu * u1;
                            c.ax[o + j] = -(lam * u0 - mu * u1);
                            c.ay[o + j] = -(lam * u1 + mu * u0);
                        }
                    }
                }
                Op::Carry { q, a, b: bb, m: ratio } => {
                    let (oq, oa, ob) = (q * B, a * B, bb * B);
                    let (m0, m1) = (ratio[0], ratio[1]);
                    for j in 0..m {
                        let (ax, ay) = (c.x[oa + j], c.y[oa + j]);
                        let (dx, dy) = (c.x[ob + j] - ax, c.y[ob + j] - ay);
                        c.x[oq + j] = ax + (m0 * dx - m1 * dy);
                        c.y[oq + j] = ay + (m1 * dx + m0 * dy);
                        let sa = c.st[oa + j];
                        c.st[oq + j] = if sa != OK { sa } else { c.st[ob + j] };
                    }
                    if vel {
                        for j in 0..m {
                            let (ax, ay) = (c.vx[oa + j], c.vy[oa + j]);
                            let (dx, dy) = (c.vx[ob + j] - ax, c.vy[ob + j] - ay);
                            c.vx[oq + j] = ax + (m0 * dx - m1 * dy);
                            c.vy[oq + j] = ay + (m1 * dx + m0 * dy);
                        }
                        for j in 0..m {
                            let (ax, ay) = (c.ax[oa + j], c.ay[oa + j]);
                            let (dx, dy) = (c.ax[ob + j] - ax, c.ay[ob + j] - ay);
                            c.ax[oq + j] = ax + (m0 * dx - m1 * dy);
                            c.ay[oq + j] = ay + (m1 * dx + m0 * dy);
                        }
                    }
                    for j in 0..m {
                        let st = c.st[oq + j];
                        if st != OK && first_bad[j] == OK {
                            first_bad[j] = st;
                        }
                    }
                }
                Op::Dyad(d) => {
                    let s = step_of[i];
                    dyad_block(d, &mut c, m, opts.newton.singular, vel, &mut sdet[s * B..], &mut sst[s * B..]);
                    for j in 0..m {
                        let st = sst[s * B + j];
                        if st != OK && first_bad[j] == OK {
                            first_bad[j] = st;
                        }
                    }
                }
                _ => unreachable!("the column sweep runs plans of dyads, carries and the input angle"),
            }
        }
        write_block(plan, &c, &sdet, &sst, &first_bad, k0, m, opts, out);
    }
    Ok(())
}

fn dyad_block(d: &Dyad, c: &mut Columns, m: usize, singular: f64, vel: bool, det: &mut [f64], sst: &mut [i8]) {
    let (op, o1, o2) = (d.p * B, d.k1 * B, d.k2 * B);
    for j in 0..m {
        let (s1, s2) = (c.st[o1 + j], c.st[o2 + j]);
        if s1 != OK || s2 != OK {
            let st = if s1 != OK { s1 } else { s2 };
            c.st[op + j] = st;
            sst[j] = st;
            det[j] = f64::NAN;
            continue;
        }
        let (a, b) = ([c.x[o1 + j], c.y[o1 + j]], [c.x[o2 + j], c.y[o2 + j]]);
        let (st, dt) = match d.solve(a, b) {
            DyadOut::Solved(p, dt) => {
                if dt.abs() >= singular {
                    c.x[op + j] = p[0];
                    c.y[op + j] = p[1];
                    (OK, dt)
                } else if dt.is_nan() {
                    (Status::NonFinite.code(), dt)
                } else {
                    (Status::Singular.code(), dt)
                }
            }
            DyadOut::NotAssemblable => (Status::NotAssemblable.code(), f64::NAN),
            DyadOut::Indeterminate => (Status::Singular.code(), 0.0),
        };
        c.st[op + j] = st;
        sst[j] = st;
        det[j] = dt;
    }
    if vel {
        for j in 0..m {
            if c.st[op + j] != OK {
                continue;
            }
            let p = [c.x[op + j], c.y[op + j]];
            let (a, b) = ([c.x[o1 + j], c.y[o1 + j]], [c.x[o2 + j], c.y[o2 + j]]);
            let (va, vb) = ([c.vx[o1 + j], c.vy[o1 + j]], [c.vx[o2 + j], c.vy[o2 + j]]);
            let (wa, wb) = ([c.ax[o1 + j], c.ay[o1 + j]], [c.ax[o2 + j], c.ay[o2 + j]]);
            let solved = Dyad::velocity(p, a, b, va, vb)
                .and_then(|v| Dyad::acceleration(p, a, b, v, va, vb, wa, wb).map(|w| (v, w)));
            match solved {
                Some((v, w)) => {
                    c.vx[op + j] = v[0];
                    c.vy[op + j] = v[1];
                    c.ax[op + j] = w[0];
                    c.ay[op + j] = w[1];
                }
                None => {
                    let st = Status::Singular.code();
                    c.st[op + j] = st;
                    sst[j] = st;
                }
            }
        }
    }
}

#[allow(clippy::too_many_arguments)]
fn write_block(
    plan: &Plan,
    c: &Columns,
    sdet: &[f64],
    sst: &[i8],
    first_bad: &[i8],
    k0: usize,
    m: usize,
    opts: &SceneSweepOptions,
    out: &mut SceneSweepOut<'_>,
) {
    let (np, nl, ns) = (plan.points.len(), plan.links.len(), plan.steps.len());
    let (sc, org) = (plan.scale, plan.origin);
    let omega = opts.omega.unwrap_or(0.0);
    for j in 0..m {
        let k = k0 + j;
        let all_ok = first_bad[j] == OK;
        let row = &mut out.points[2 * k * np..2 * (k + 1) * np];
        let pst = &mut out.point_status[k * np..(k + 1) * np];
        for ((dst, code), &p) in row.chunks_exact_mut(2).zip(pst.iter_mut()).zip(&plan.points) {
            let o = p * B + j;
            let st = c.st[o];
            *code = st;
            if all_ok || st == OK {
                dst[0] = c.x[o] * sc + org[0];
                dst[1] = c.y[o] * sc + org[1];
            } else {
                dst[0] = f64::NAN;
                dst[1] = f64::NAN;
            }
        }
        let ok = |p: usize| all_ok || c.st[p * B + j] == OK;
        for (dst, &(a, b)) in out.angles[k * nl..(k + 1) * nl].iter_mut().zip(&plan.link_points) {
            let (oa, ob) = (a * B + j, b * B + j);
            let (dx, dy) = (c.x[ob] - c.x[oa], c.y[ob] - c.y[oa]);
            *dst = if ok(a) && ok(b) { (dy + 0.0).atan2(dx) } else { f64::NAN };
        }
        if let Some((v, w)) = out.velocity.as_mut() {
            for (dst, &p) in v[2 * k * np..2 * (k + 1) * np].chunks_exact_mut(2).zip(&plan.points) {
                let o = p * B + j;
                let good = ok(p);
                dst[0] = if good { c.vx[o] * sc * omega } else { f64::NAN };
                dst[1] = if good { c.vy[o] * sc * omega } else { f64::NAN };
            }
            for (dst, &(a, b)) in w[k * nl..(k + 1) * nl].iter_mut().zip(&plan.link_points) {
                let (oa, ob) = (a * B + j, b * B + j);
                let (dx, dy) = (c.x[ob] - c.x[oa], c.y[ob] - c.y[oa]);
                let (dvx, dvy) = (c.vx[ob] - c.vx[oa], c.vy[ob] - c.vy[oa]);
                *dst = if ok(a) && ok(b) { (dx * dvy - dy * dvx) / (dx * dx + dy * dy) * omega } else { f64::NAN };
            }
        }
        if let Some((acc, alpha)) = out.acceleration.as_mut() {
            let w2 = omega * omega;
            for (dst, &p) in acc[2 * k * np..2 * (k + 1) * np].chunks_exact_mut(2).zip(&plan.points) {
                let o = p * B + j;
                let good = ok(p);
                dst[0] = if good { c.ax[o] * sc * w2 } else { f64::NAN };
                dst[1] = if good { c.ay[o] * sc * w2 } else { f64::NAN };
            }
            for (dst, &(a, b)) in alpha[k * nl..(k + 1) * nl].iter_mut().zip(&plan.link_points) {
                let (oa, ob) = (a * B + j, b * B + j);
                let d = [c.x[ob] - c.x[oa], c.y[ob] - c.y[oa]];
                let dv = [c.vx[ob] - c.vx[oa], c.vy[ob] - c.vy[oa]];
                let dw = [c.ax[ob] - c.ax[oa], c.ay[ob] - c.ay[oa]];
                *dst = if ok(a) && ok(b) { angular_acceleration(d, dv, dw) * w2 } else { f64::NAN };
            }
        }
        let mut det = 1.0;
        for s in 0..ns {
            let (code, d) = (sst[s * B + j], sdet[s * B + j]);
            out.step_status[k * ns + s] = code;
            out.step_det[k * ns + s] = d;
            det *= d;
        }
        out.status[k] = first_bad[j];
        out.det[k] = det;
        out.limit[k] = f64::NAN;
        out.nit[k] = 0;
    }
}
