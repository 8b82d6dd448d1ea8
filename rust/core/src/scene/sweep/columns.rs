//! The sweep of a plan with no group (dyads, sliders' closed forms, rigid carries and the
//! input): nothing carries over from one input value to the next, so each operation runs
//! over a block of values at a time, on columns of coordinates (tight loops, no per-value
//! dispatch), and the rows of the outputs are written once per block. Every operation is
//! solved on its drawn side with the closed forms the continuation of `sweep` calls, so a
//! certified column sweep gives that path's numbers (the input's sin and cos excepted:
//! the polynomial ones, within 2 ulp, where the SIMD kernels are on).

// the column loops index several arrays (and an offset into each) by the same angle
#![allow(clippy::needless_range_loop)]

use super::options::{SceneSweepOptions, SceneSweepOut};
use crate::error::Error;
use crate::interrupt::Poll;
use crate::scene::build::Plan;
use crate::scene::ops::Known;
use crate::scene::ops::Op;
use crate::scene::ops::Rrp;
use crate::scene::ops::{closed_form, Dyad, APART, COINCIDE, SOLVED};
use crate::scene::vec2::unit;
use crate::scene::vec2::{angular_acceleration, Xy};
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

/// One input value's known points, indexed by point, for the slider solves with rates
/// (only the operation's inputs are filled in).
struct Scratch {
    pos: Vec<Xy>,
    vel: Vec<Xy>,
    acc: Vec<Xy>,
}

/// The column sweep of `plan` over `theta` into `out`, compiled for AVX2 where the SIMD
/// kernels are on (the same operations on 4 lanes, without fused multiply-adds: the same
/// numbers as the baseline build).
pub(crate) fn sweep(
    plan: &Plan,
    theta: &[f64],
    opts: &SceneSweepOptions,
    out: &mut SceneSweepOut<'_>,
    poll: &Poll<'_>,
) -> Result<(), Error> {
    #[cfg(target_arch = "x86_64")]
    if crate::simd::enabled() {
        // SAFETY: the SIMD kernels are on only where the CPU has AVX2 (and FMA).
        return unsafe { sweep_avx2(plan, theta, opts, out, poll) };
    }
    sweep_body(plan, theta, opts, out, poll)
}

#[cfg(target_arch = "x86_64")]
#[target_feature(enable = "avx2,fma")]
unsafe fn sweep_avx2(
    plan: &Plan,
    theta: &[f64],
    opts: &SceneSweepOptions,
    out: &mut SceneSweepOut<'_>,
    poll: &Poll<'_>,
) -> Result<(), Error> {
    sweep_body(plan, theta, opts, out, poll)
}

#[inline(always)]
fn sweep_body(
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
    let mut fixed = vec![false; np];
    for &(p, _) in &plan.fixed {
        fixed[p] = true;
    }
    let inputs: Vec<Vec<usize>> = plan.ops.iter().map(Op::inputs).collect();
    let angle = plan.ops.iter().any(|o| matches!(o, Op::Input { .. }));
    let mut scratch =
        vel.then(|| Scratch { pos: vec![[0.0; 2]; np], vel: vec![[0.0; 2]; np], acc: vec![[0.0; 2]; np] });
    let mut sdet = vec![1.0; ns * B];
    let mut sst = vec![OK; ns * B];
    // the conditioning and status of an operation that opens no step (a carry)
    let (mut cdet, mut cst) = ([1.0; B], [OK; B]);
    let mut first_bad = [OK; B];
    let mut trig = [(0.0, 1.0); B];
    let mut sv = [0.0; B];
    for (b, block) in theta.chunks(B).enumerate() {
        poll.tick_n(block.len())?;
        let m = block.len();
        let k0 = b * B;
        first_bad[..m].fill(OK);
        if angle {
            crate::simd::sin_cos_block(block, &mut trig[..m]);
        }
        if plan.linear {
            // the fused guide reads the displacement in the solving frame
            for j in 0..m {
                sv[j] = block[j] / plan.scale;
            }
        }
        for (i, op) in plan.ops.iter().enumerate() {
            match op {
                Op::Input { q, lam, mu } => {
                    let (px, py) = (plan.pivot[0], plan.pivot[1]);
                    let o = q * B;
                    let nonfinite = Status::NonFinite.code();
                    let (xs, ys, sts) = (&mut c.x[o..o + m], &mut c.y[o..o + m], &mut c.st[o..o + m]);
                    for (((x, y), st), (&(u1, u0), &t)) in xs.iter_mut().zip(ys).zip(sts).zip(trig.iter().zip(block)) {
                        *x = px + lam * u0 - mu * u1;
                        *y = py + lam * u1 + mu * u0;
                        *st = if t.is_finite() { OK } else { nonfinite };
                    }
                    note(&mut first_bad[..m], &c.st[o..o + m]);
                    if vel {
                        for j in 0..m {
                            let (u1, u0) = trig[j];
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
                    // disjoint columns: the loops vectorize
                    let (xa, xb, xq) = two_in_one_out(&mut c.x, *a, *bb, *q, m);
                    let (ya, yb, yq) = two_in_one_out(&mut c.y, *a, *bb, *q, m);
                    for j in 0..m {
                        let (ax, ay) = (xa[j], ya[j]);
                        let (dx, dy) = (xb[j] - ax, yb[j] - ay);
                        xq[j] = ax + (m0 * dx - m1 * dy);
                        yq[j] = ay + (m1 * dx + m0 * dy);
                    }
                    let (sa, sb, sq) = two_in_one_out(&mut c.st, *a, *bb, *q, m);
                    for ((q, &a), &b) in sq.iter_mut().zip(sa).zip(sb) {
                        *q = if a != OK { a } else { b };
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
                    note(&mut first_bad[..m], &c.st[oq..oq + m]);
                }
                Op::Dyad(d) => {
                    let s = step_of[i];
                    dyad_block(d, &mut c, m, opts.newton.singular, vel, &mut sdet[s * B..], &mut sst[s * B..]);
                    note(&mut first_bad[..m], &sst[s * B..s * B + m]);
                }
                Op::Group(_) => unreachable!("the column sweep runs plans with no group"),
                op => {
                    let (det, st) = match step_of[i] {
                        usize::MAX => (&mut cdet[..], &mut cst[..]),
                        s => (&mut sdet[s * B..], &mut sst[s * B..]),
                    };
                    let sv = if plan.linear { &sv[..m] } else { &block[..m] };
                    let ins = &inputs[i];
                    let singular = opts.newton.singular;
                    match (scratch.as_mut(), op) {
                        // a slot on a line fixed in ground (a slider-crank's): the line once
                        (None, Op::Rrp(r)) if r.line.inputs().iter().all(|&p| fixed[p]) => {
                            let l = &r.line;
                            let (p, d) = l.place(c.point(l.base, 0), c.point(l.a, 0), c.point(l.b, 0));
                            rrp_fixed_line_block(r, p, unit(d), &mut c, m, singular, det, st);
                        }
                        (None, _) => slider_block(op, ins, &mut c, sv, singular, det, st),
                        (Some(k), _) => slider_rates_block(op, ins, &mut c, sv, singular, k, det, st),
                    }
                    note(&mut first_bad[..m], &st[..m]);
                }
            }
        }
        write_block(plan, &c, &sdet, &sst, &first_bad, k0, m, opts, out);
    }
    Ok(())
}

/// Keeps each value's first failure: `st` where nothing failed before.
#[inline(always)]
fn note(first_bad: &mut [i8], st: &[i8]) {
    for (f, &s) in first_bad.iter_mut().zip(st) {
        *f = if *f == OK { s } else { *f };
    }
}

impl Columns {
    /// Point p's position at the block's value j.
    #[inline(always)]
    fn point(&self, p: usize, j: usize) -> Xy {
        [self.x[p * B + j], self.y[p * B + j]]
    }
}

/// [`slider_block`] for a circle-line whose line is fixed (through `p` along unit `u` at
/// every value): only its known point moves. Branch-free over the block's values.
#[allow(clippy::too_many_arguments)]
#[inline(always)]
fn rrp_fixed_line_block(
    r: &Rrp,
    p: Xy,
    u: Xy,
    c: &mut Columns,
    m: usize,
    singular: f64,
    det: &mut [f64],
    sst: &mut [i8],
) {
    let (kx, qx) = two_columns(&mut c.x, r.k, r.p, m);
    let (ky, qy) = two_columns(&mut c.y, r.k, r.p, m);
    let (kst, qst) = two_columns(&mut c.st, r.k, r.p, m);
    let (na, nonfinite, sing) = (Status::NotAssemblable.code(), Status::NonFinite.code(), Status::Singular.code());
    for j in 0..m {
        let (x, dt, meets) = r.place_branch_free([kx[j], ky[j]], p, u, r.side);
        let bad = kst[j];
        let finite = x[0].is_finite() & x[1].is_finite();
        let solved = if dt.abs() >= singular && finite {
            OK
        } else if dt.is_nan() || !finite {
            nonfinite
        } else {
            sing
        };
        let st = if bad != OK {
            bad
        } else if meets {
            solved
        } else {
            na
        };
        qx[j] = x[0];
        qy[j] = x[1];
        qst[j] = st;
        sst[j] = st;
        det[j] = if bad == OK && meets { dt } else { f64::NAN };
    }
}

/// Point a's column (read) and point b's (written) for the block's `m` values (a != b).
fn two_columns<T>(v: &mut [T], a: usize, b: usize, m: usize) -> (&[T], &mut [T]) {
    let (x, _, q) = two_in_one_out(v, a, a, b, m);
    (x, q)
}

/// Columns `a` and `b` (read; they may be one) and column `q` (written; another) for the
/// block's `m` values.
fn two_in_one_out<T>(v: &mut [T], a: usize, b: usize, q: usize, m: usize) -> (&[T], &[T], &mut [T]) {
    let (lo, hi) = v.split_at_mut(q * B);
    let (out, rest) = hi.split_at_mut(B);
    let (lo, rest) = (&*lo, &*rest);
    let col = |p: usize| if p < q { &lo[p * B..p * B + m] } else { &rest[(p - q - 1) * B..(p - q - 1) * B + m] };
    (col(a), col(b), &mut out[..m])
}

/// The first failure among an operation's inputs at the block's value `j`.
#[inline(always)]
fn inputs_status(c: &Columns, ins: &[usize], j: usize) -> i8 {
    ins.iter().map(|&p| c.st[p * B + j]).find(|&s| s != OK).unwrap_or(OK)
}

/// The status of a solve with conditioning `det` at a finite or not position `x`.
#[inline(always)]
fn solved_status(x: Xy, det: f64, singular: f64) -> i8 {
    if det.abs() >= singular && x[0].is_finite() && x[1].is_finite() {
        OK
    } else if det.is_nan() || !(x[0].is_finite() && x[1].is_finite()) {
        Status::NonFinite.code()
    } else {
        Status::Singular.code()
    }
}

/// A slider's closed form or a fused guide's operation (one output point) at the block's
/// input values `sv` (solving frame), positions only, on the drawn side.
#[inline(always)]
fn slider_block(op: &Op, ins: &[usize], c: &mut Columns, sv: &[f64], singular: f64, det: &mut [f64], sst: &mut [i8]) {
    let q = op.outputs()[0] * B;
    let side = op.drawn_side();
    for j in 0..sv.len() {
        let bad = inputs_status(c, ins, j);
        let (st, dt) = if bad != OK {
            (bad, f64::NAN)
        } else {
            let (x, y) = (&c.x, &c.y);
            match op.place_slider(sv[j], |p| [x[p * B + j], y[p * B + j]], side) {
                Some((p, dt)) => {
                    let st = solved_status(p, dt, singular);
                    if st == OK {
                        c.x[q + j] = p[0];
                        c.y[q + j] = p[1];
                    }
                    (st, dt)
                }
                None => (Status::NotAssemblable.code(), f64::NAN),
            }
        };
        c.st[q + j] = st;
        sst[j] = st;
        det[j] = dt;
    }
}

/// [`slider_block`] with first and second derivatives by the input: each value's solve is
/// the continuation's own ([`Op::solve_slider`] on the drawn side).
#[allow(clippy::too_many_arguments)]
fn slider_rates_block(
    op: &Op,
    ins: &[usize],
    c: &mut Columns,
    sv: &[f64],
    singular: f64,
    k: &mut Scratch,
    det: &mut [f64],
    sst: &mut [i8],
) {
    let q = op.outputs()[0] * B;
    let side = op.drawn_side();
    for j in 0..sv.len() {
        let bad = inputs_status(c, ins, j);
        let (st, dt) = if bad != OK {
            (bad, f64::NAN)
        } else {
            for &p in ins {
                let o = p * B + j;
                k.pos[p] = [c.x[o], c.y[o]];
                k.vel[p] = [c.vx[o], c.vy[o]];
                k.acc[p] = [c.ax[o], c.ay[o]];
            }
            let known: Known<'_> = [&k.pos, &k.vel, &k.acc];
            match op.solve_slider(sv[j], known, side, true) {
                Some(out) => {
                    let mut st = solved_status(out.x[0], out.det, singular);
                    if st == OK && !(out.x[1][0].is_finite() && out.x[1][1].is_finite()) {
                        st = Status::Singular.code();
                    }
                    if st == OK {
                        let [p, v, w] = out.x;
                        (c.x[q + j], c.y[q + j]) = (p[0], p[1]);
                        (c.vx[q + j], c.vy[q + j]) = (v[0], v[1]);
                        (c.ax[q + j], c.ay[q + j]) = (w[0], w[1]);
                    }
                    (st, out.det)
                }
                None => (Status::NotAssemblable.code(), f64::NAN),
            }
        };
        c.st[q + j] = st;
        sst[j] = st;
        det[j] = dt;
    }
}

#[inline(always)]
fn dyad_block(d: &Dyad, c: &mut Columns, m: usize, singular: f64, vel: bool, det: &mut [f64], sst: &mut [i8]) {
    let sst = &mut sst[..m];
    {
        // `Dyad::solve`'s closed form over the block's values (it has no branch, so this
        // vectorizes), its cases kept as numbers; the statuses after
        let (x1, x2, xq) = two_in_one_out(&mut c.x, d.k1, d.k2, d.p, m);
        let (y1, y2, yq) = two_in_one_out(&mut c.y, d.k1, d.k2, d.p, m);
        let det = &mut det[..m];
        let (na, nonfinite, sing) = (Status::NotAssemblable.code(), Status::NonFinite.code(), Status::Singular.code());
        let mut case = [0.0; B];
        for j in 0..m {
            // (a point that did not solve is masked where it is written out)
            let (p, dt, cs) = closed_form([x1[j], y1[j]], [x2[j], y2[j]], d.side, d.r1, d.r2);
            (xq[j], yq[j], det[j], case[j]) = (p[0], p[1], dt, cs);
        }
        let (s1, s2, sq) = two_in_one_out(&mut c.st, d.k1, d.k2, d.p, m);
        // the common block: both known points solved and the dyad closes, away from its
        // dead points, at every value (folds, not searches: they vectorize)
        let known = s1.iter().zip(s2).fold(OK, |a, (&x, &y)| a | x | y) == OK;
        let closes = det.iter().zip(&case[..m]).fold(true, |a, (&dt, &cs)| a & (cs == SOLVED) & (dt.abs() >= singular));
        if known && closes {
            sq.fill(OK);
            sst.fill(OK);
        } else {
            for j in 0..m {
                let dt = det[j];
                let st = if s1[j] != OK {
                    s1[j]
                } else if s2[j] != OK {
                    s2[j]
                } else if case[j] == COINCIDE {
                    // a continuum with equal links (conditioning 0), no assembly otherwise
                    if dt == 0.0 {
                        sing
                    } else {
                        na
                    }
                } else if case[j] == APART {
                    na
                } else if dt.abs() >= singular {
                    OK
                } else if dt.is_nan() {
                    nonfinite
                } else {
                    sing
                };
                if (s1[j] != OK) | (s2[j] != OK) {
                    det[j] = f64::NAN;
                }
                sq[j] = st;
                sst[j] = st;
            }
        }
    }
    let (op, o1, o2) = (d.p * B, d.k1 * B, d.k2 * B);
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

/// The block's rows of the outputs, written point by point (and link by link, step by
/// step) down the block's values: a point failing at a value is NaN there unless every
/// step solved (then its status is CONVERGED too).
#[allow(clippy::too_many_arguments)]
#[inline(always)]
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
    // per unit of the sweep variable (a displacement's rates carry 1 / scale)
    let omega = opts.omega.unwrap_or(0.0) * if plan.linear { 1.0 / sc } else { 1.0 };
    let w2 = omega * omega;
    let rows = k0..k0 + m;
    let first_bad = &first_bad[..m];
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
        for (i, &(a, b)) in plan.link_points.iter().enumerate() {
            let both = good(a).zip(good(b));
            for (j, (row, (oa, ob))) in angles.chunks_exact_mut(nl).zip(both).enumerate() {
                let (pa, pb) = (a * B + j, b * B + j);
                let d = [c.x[pb] - c.x[pa], c.y[pb] - c.y[pa]];
                row[i] = if oa && ob { crate::simd::direction(d, fast) } else { f64::NAN };
            }
        }
    }
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

#[cfg(test)]
mod tests {
    //! The column path against the continuation on the slider built-ins (their drawings
    //! copied from `python/planarkin/scene/builtin`): the same statuses, and positions,
    //! angles, conditioning, velocities and accelerations to 1e-12 of the drawing's size.

    use super::*;
    use crate::interrupt::{Never, Poll};
    use crate::scene::{LinearKind, PrismaticSpec, Scene, SceneSpec, SlotSpec};
    use crate::solve::newton::NewtonOptions;

    type Joint<'a> = (&'a str, &'a str, &'a str, (&'a str, &'a str));

    struct Spec<'a> {
        points: &'a [(&'a str, Xy)],
        links: &'a [(&'a str, &'a [&'a str])],
        input: (&'a str, &'a str),
        slots: &'a [Joint<'a>],
        prismatic: &'a [Joint<'a>],
        linear: Option<(LinearKind, &'a str)>,
    }

    fn scene(s: &Spec<'_>) -> Scene {
        let o = |x: &str| x.to_string();
        let joint = |&(n, a, g, (l0, l1)): &Joint<'_>| (o(n), (o(a), o(g), (o(l0), o(l1))));
        let spec = SceneSpec {
            points: s.points.iter().map(|&(n, p)| (o(n), p)).collect(),
            links: s.links.iter().map(|&(n, ps)| (o(n), ps.iter().map(|p| o(p)).collect())).collect(),
            ground: o("ground"),
            input: (o(s.input.0), o(s.input.1)),
            output: None,
            slots: s.slots.iter().map(joint).map(|(n, j)| (n, SlotSpec::from(j))).collect(),
            prismatic: s.prismatic.iter().map(joint).map(|(n, j)| (n, PrismaticSpec::from(j))).collect(),
            linear_input: s.linear.map(|(k, n)| (k, o(n))),
        };
        Scene::new(spec).expect("a built-in is valid")
    }

    const NO: &[Joint<'static>] = &[];

    fn builtins() -> Vec<(&'static str, Scene)> {
        let slider_crank = |b: Xy, a: Xy, x: Xy| {
            scene(&Spec {
                points: &[("O2", [0.0, 0.0]), ("X", x), ("A", a), ("B", b)],
                links: &[("ground", &["O2", "X"]), ("crank", &["O2", "A"]), ("rod", &["A", "B"])],
                input: ("crank", "O2"),
                slots: &[("piston", "B", "ground", ("O2", "X"))],
                prismatic: NO,
                linear: None,
            })
        };
        let whitworth = scene(&Spec {
            points: &[
                ("O2", [0.0, 0.0]),
                ("O4", [0.0, 30.0]),
                ("X", [-1.0, 30.0]),
                ("A", [51.96152422706632, 29.999999999999996]),
                ("C", [-50.0, 30.000000000000004]),
                ("D", [-200.0, 30.0]),
            ],
            links: &[
                ("ground", &["O2", "O4", "X"]),
                ("crank", &["O2", "A"]),
                ("lever", &["O4", "C"]),
                ("rod", &["C", "D"]),
            ],
            input: ("crank", "O2"),
            slots: &[("block", "A", "lever", ("O4", "C")), ("ram", "D", "ground", ("O4", "X"))],
            prismatic: NO,
            linear: None,
        });
        let yoke = scene(&Spec {
            points: &[
                ("O2", [0.0, 0.0]),
                ("G", [1.0, 0.0]),
                ("A", [45.31538935183249, 21.130913087034973]),
                ("Y1", [45.31538935183249, -60.0]),
                ("Y2", [45.31538935183249, 60.0]),
                ("R", [165.3153893518325, 0.0]),
            ],
            links: &[("ground", &["O2", "G"]), ("crank", &["O2", "A"]), ("yoke", &["Y1", "Y2", "R"])],
            input: ("crank", "O2"),
            slots: &[("pin", "A", "yoke", ("Y1", "Y2"))],
            prismatic: &[("guide", "yoke", "ground", ("O2", "G"))],
            linear: None,
        });
        let inverted = scene(&Spec {
            points: &[
                ("O2", [0.0, 0.0]),
                ("O4", [100.0, 0.0]),
                ("A", [30.64177772475912, 25.71150438746157]),
                ("C", [-40.64693667150496, 52.1386536546704]),
            ],
            links: &[("ground", &["O2", "O4"]), ("crank", &["O2", "A"]), ("cylinder", &["O4", "C"])],
            input: ("crank", "O2"),
            slots: &[("block", "A", "cylinder", ("O4", "C"))],
            prismatic: NO,
            linear: None,
        });
        let trammel = scene(&Spec {
            points: &[
                ("O", [0.0, 0.0]),
                ("X", [1.0, 0.0]),
                ("Y", [0.0, 1.0]),
                ("A", [60.0, 0.0]),
                ("B", [0.0, 80.0]),
                ("P", [36.0, 32.0]),
            ],
            links: &[("ground", &["O", "X", "Y"]), ("bar", &["A", "B", "P"])],
            input: ("", ""),
            slots: &[("a", "A", "ground", ("O", "X")), ("b", "B", "ground", ("O", "Y"))],
            prismatic: NO,
            linear: Some((LinearKind::Slot, "a")),
        });
        let boom = scene(&Spec {
            points: &[
                ("O", [0.0, 0.0]),
                ("C1", [600.0, -400.0]),
                ("E", [692.820323027551, 399.99999999999994]),
                ("T", [1732.0508075688774, 999.9999999999999]),
                ("C2", [634.5756721218627, -101.9991226567924]),
                ("R", [646.7194268650675, 2.665496875723136]),
            ],
            links: &[
                ("ground", &["O", "C1"]),
                ("boom", &["O", "E", "T"]),
                ("barrel", &["C1", "C2"]),
                ("rod", &["R", "E"]),
            ],
            input: ("", ""),
            slots: NO,
            prismatic: &[("cylinder", "rod", "barrel", ("C1", "C2"))],
            linear: Some((LinearKind::Prismatic, "cylinder")),
        });
        vec![
            (
                "slider-crank",
                slider_crank([193.386094815253, 0.0], [34.64101615137755, 19.999999999999996], [1.0, 0.0]),
            ),
            ("whitworth", whitworth),
            ("scotch-yoke", yoke),
            ("inverted-slider-crank", inverted),
            ("elliptic-trammel", trammel),
            ("hydraulic-boom", boom),
        ]
    }

    struct Bufs {
        f: Vec<Vec<f64>>,
        i: Vec<Vec<i8>>,
        nit: Vec<u32>,
    }

    impl Bufs {
        /// With `rates`, velocities and accelerations too.
        fn new(plan: &Plan, n: usize, rates: bool) -> Self {
            let (np, nl, ns) = (plan.points.len(), plan.links.len(), plan.steps.len());
            let k = usize::from(rates);
            let f = [2 * n * np, n * nl, n, n, n * ns, 2 * n * np * k, n * nl * k, 2 * n * np * k, n * nl * k];
            let i = vec![vec![0; n], vec![0; n * ns], vec![0; n * np]];
            Bufs { f: f.iter().map(|&m| vec![0.0; m]).collect(), i, nit: vec![0; n] }
        }

        fn out(&mut self) -> SceneSweepOut<'_> {
            let [pts, ang, det, lim, sdet, v, w, a, al] = &mut self.f[..] else { unreachable!() };
            let [st, sst, pst] = &mut self.i[..] else { unreachable!() };
            let rates = !v.is_empty();
            SceneSweepOut {
                points: pts,
                angles: ang,
                status: st,
                nit: &mut self.nit,
                det,
                limit: lim,
                step_status: sst,
                step_det: sdet,
                point_status: pst,
                velocity: rates.then_some((&mut v[..], &mut w[..])),
                acceleration: rates.then_some((&mut a[..], &mut al[..])),
            }
        }
    }

    #[test]
    fn sliders_on_columns_match_the_continuation() {
        for ((name, sc), omega) in builtins().into_iter().flat_map(|b| [(b.clone(), None), (b, Some(2.5))]) {
            let plan = sc.plan(None).expect("the plan compiles");
            assert!(plan.columns_ok(), "{name}");
            let size = sc.scale();
            // 1-degree steps through a turn; a linear input from its drawn pose 0.4 sizes on
            let theta: Vec<f64> = if plan.linear {
                (0..100).map(|k| k as f64 * 0.004 * size).collect()
            } else {
                (0..361).map(|k| sc.input_angle() + (k as f64).to_radians()).collect()
            };
            let h = (theta[1] - theta[0]).abs();
            let n = theta.len();
            let opts = |max_step: f64| SceneSweepOptions::new(NewtonOptions::default(), max_step, omega).unwrap();
            let mut cols = Bufs::new(&plan, n, omega.is_some());
            sweep(&plan, &theta, &opts(2.0 * h), &mut cols.out(), &Poll::new(&Never)).unwrap();
            // the certificate holds here: the plain sweep takes the columns as they are
            assert!(cols.i[0].iter().all(|&s| s == OK), "{name}: {:?}", cols.i[0]);
            assert!(cols.f[4].iter().all(|d| d.abs() >= 0.05), "{name}");
            let mut plain = Bufs::new(&plan, n, omega.is_some());
            plan.sweep(&theta, &opts(2.0 * h), plain.out(), &Never).unwrap();
            let bits =
                |b: &Bufs| b.f.iter().map(|v| v.iter().map(|x| x.to_bits()).collect::<Vec<_>>()).collect::<Vec<_>>();
            assert!(bits(&plain) == bits(&cols), "{name}: the plain sweep is not the column one");
            // steps longer than max_step: the continuation
            let mut cont = Bufs::new(&plan, n, omega.is_some());
            plan.sweep(&theta, &opts(0.5 * h), cont.out(), &Never).unwrap();
            assert!(cont.i == cols.i && cont.nit == cols.nit, "{name}: statuses differ");
            for (k, (a, b)) in cols.f.iter().zip(&cont.f).enumerate() {
                // positions, angles, dets and rates: 1e-12 of their largest size
                let big = a.iter().map(|x| x.abs()).filter(|x| x.is_finite()).fold(1.0, f64::max);
                for (x, y) in a.iter().zip(b) {
                    let same = (x.is_nan() && y.is_nan()) || (x - y).abs() <= 1e-12 * big;
                    assert!(same, "{name} (omega {omega:?}): output {k}: {x} vs {y}");
                }
            }
        }
    }

    /// The dyad over a block is `Dyad::solve` value for value, bit for bit (both run
    /// `closed_form`; what this checks is the block's statuses, conditioning and masking
    /// against the scalar solve's cases, which its own tests hold to circle
    /// intersections): random known points, and the cases at the edges (coincident points
    /// with equal and unequal links, out of reach, exactly in line, a non-finite input, a
    /// failed input).
    #[test]
    fn the_dyad_block_is_dyad_solve_bit_for_bit() {
        let mut seed = 0x2545_f491_4f6c_dd1d_u64;
        let mut next = move || {
            seed ^= seed << 13;
            seed ^= seed >> 7;
            seed ^= seed << 17;
            (seed >> 11) as f64 / (1u64 << 53) as f64 * 12.0 - 6.0
        };
        let links = [0, 0];
        for d in [
            Dyad { p: 2, k1: 0, k2: 1, r1: 5.0, r2: 5.0, side: 1.0, links },
            Dyad { p: 0, k1: 2, k2: 1, r1: 2.5, r2: 4.0, side: -1.0, links },
        ] {
            let mut c = Columns {
                x: vec![0.0; 3 * B],
                y: vec![0.0; 3 * B],
                vx: vec![],
                vy: vec![],
                ax: vec![],
                ay: vec![],
                st: vec![OK; 3 * B],
            };
            let (o1, o2) = (d.k1 * B, d.k2 * B);
            for j in 0..B {
                (c.x[o1 + j], c.y[o1 + j], c.x[o2 + j], c.y[o2 + j]) = (next(), next(), next(), next());
            }
            // coincident; in line at full reach; out of reach; non-finite; a failed input
            (c.x[o2], c.y[o2]) = (c.x[o1], c.y[o1]);
            (c.x[o2 + 1], c.y[o2 + 1]) = (c.x[o1 + 1] + d.r1 + d.r2, c.y[o1 + 1]);
            (c.x[o2 + 2], c.y[o2 + 2]) = (c.x[o1 + 2] + 2.0 * (d.r1 + d.r2), c.y[o1 + 2]);
            c.x[o1 + 3] = f64::NAN;
            c.st[o2 + 4] = Status::Limit.code();
            let (mut det, mut sst) = (vec![0.0; B], vec![OK; B]);
            dyad_block(&d, &mut c, B, 1e-6, false, &mut det, &mut sst);
            let mut seen = std::collections::BTreeSet::new();
            for j in 0..B {
                let (a, b) = ([c.x[o1 + j], c.y[o1 + j]], [c.x[o2 + j], c.y[o2 + j]]);
                let bad = [c.st[o1 + j], c.st[o2 + j]].into_iter().find(|&s| s != OK);
                let (st, dt, p) = match (bad, d.solve(a, b)) {
                    (Some(s), _) => (s, f64::NAN, None),
                    (None, crate::scene::ops::DyadOut::Solved(p, dt)) if dt.abs() >= 1e-6 => (OK, dt, Some(p)),
                    (None, crate::scene::ops::DyadOut::Solved(_, dt)) => {
                        (if dt.is_nan() { Status::NonFinite.code() } else { Status::Singular.code() }, dt, None)
                    }
                    (None, crate::scene::ops::DyadOut::NotAssemblable) => {
                        (Status::NotAssemblable.code(), f64::NAN, None)
                    }
                    (None, crate::scene::ops::DyadOut::Indeterminate) => (Status::Singular.code(), 0.0, None),
                };
                seen.insert(st);
                assert_eq!((sst[j], c.st[d.p * B + j]), (st, st), "value {j}");
                assert_eq!(det[j].to_bits(), dt.to_bits(), "value {j}: {} vs {dt}", det[j]);
                if let Some(p) = p {
                    let q = [c.x[d.p * B + j], c.y[d.p * B + j]];
                    assert_eq!(q.map(f64::to_bits), p.map(f64::to_bits), "value {j}");
                }
            }
            // every case met: solved, singular (in line or coincident), not assemblable,
            // and the failed input's status carried
            assert!(seen.len() >= 4, "{seen:?}");
        }
    }
}
