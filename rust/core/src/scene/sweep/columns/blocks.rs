//! One operation over a block of input values, on columns: the input, rigid carries,
//! RRR dyads and the sliders' closed forms (with their rates where asked for). Every
//! operation is solved on its drawn side with the closed forms the continuation calls.

// the column loops index several arrays (and an offset into each) by the same angle
#![allow(clippy::needless_range_loop)]

use super::frame::{inputs_status, solved_status, two_columns, two_in_one_out, Columns, Scratch, B, OK};
use crate::scene::ops::{closed_form, Dyad, Known, Op, Rrp, APART, COINCIDE, SOLVED};
use crate::scene::vec2::Xy;
use crate::Status;

/// The input link's point `q` = pivot + lam u + mu perp(u), u = (cos, sin) of the block's
/// values (`trig`: their (sin, cos)), with its first and second derivatives where `vel`.
#[inline(always)]
pub(super) fn input_block(
    pivot: Xy,
    (q, lam, mu): (usize, f64, f64),
    c: &mut Columns<'_>,
    trig: &[(f64, f64)],
    block: &[f64],
    vel: bool,
) {
    let m = block.len();
    let (px, py) = (pivot[0], pivot[1]);
    let o = q * B;
    let nonfinite = Status::NonFinite.code();
    let (xs, ys, sts) = (&mut c.x[o..o + m], &mut c.y[o..o + m], &mut c.st[o..o + m]);
    for (((x, y), st), (&(u1, u0), &t)) in xs.iter_mut().zip(ys).zip(sts).zip(trig.iter().zip(block)) {
        *x = px + lam * u0 - mu * u1;
        *y = py + lam * u1 + mu * u0;
        *st = if t.is_finite() { OK } else { nonfinite };
    }
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

/// A rigid carry at the block's values: q = a + m (b - a) (complex `ratio`), its status the
/// first failure of a and b, with its rates where `vel`.
#[inline(always)]
pub(super) fn carry_block((q, a, bb): (usize, usize, usize), ratio: Xy, c: &mut Columns<'_>, m: usize, vel: bool) {
    let (oq, oa, ob) = (q * B, a * B, bb * B);
    let (m0, m1) = (ratio[0], ratio[1]);
    // disjoint columns: the loops vectorize
    let (xa, xb, xq) = two_in_one_out(c.x, a, bb, q, m);
    let (ya, yb, yq) = two_in_one_out(c.y, a, bb, q, m);
    for j in 0..m {
        let (ax, ay) = (xa[j], ya[j]);
        let (dx, dy) = (xb[j] - ax, yb[j] - ay);
        xq[j] = ax + (m0 * dx - m1 * dy);
        yq[j] = ay + (m1 * dx + m0 * dy);
    }
    let (sa, sb, sq) = two_in_one_out(c.st, a, bb, q, m);
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
}

/// [`slider_block`] for a circle-line whose line is fixed (through `p` along unit `u` at
/// every value): only its known point moves. Branch-free over the block's values.
#[inline(always)]
pub(super) fn rrp_fixed_line_block(
    r: &Rrp,
    p: Xy,
    u: Xy,
    c: &mut Columns<'_>,
    m: usize,
    singular: f64,
    det: &mut [f64],
    sst: &mut [i8],
) {
    let (kx, qx) = two_columns(c.x, r.k, r.p, m);
    let (ky, qy) = two_columns(c.y, r.k, r.p, m);
    let (kst, qst) = two_columns(c.st, r.k, r.p, m);
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

/// A slider's closed form or a fused guide's operation (one output point) at the block's
/// input values `sv` (solving frame), positions only, on the drawn side.
#[inline(always)]
pub(super) fn slider_block(
    op: &Op,
    ins: &[usize],
    c: &mut Columns<'_>,
    sv: &[f64],
    singular: f64,
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
pub(super) fn slider_rates_block(
    op: &Op,
    ins: &[usize],
    c: &mut Columns<'_>,
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
pub(super) fn dyad_block(
    d: &Dyad,
    c: &mut Columns<'_>,
    m: usize,
    singular: f64,
    vel: bool,
    det: &mut [f64],
    sst: &mut [i8],
) {
    let sst = &mut sst[..m];
    {
        // `Dyad::solve`'s closed form over the block's values (it has no branch, so this
        // vectorizes), its cases kept as numbers; the statuses after
        let (x1, x2, xq) = two_in_one_out(c.x, d.k1, d.k2, d.p, m);
        let (y1, y2, yq) = two_in_one_out(c.y, d.k1, d.k2, d.p, m);
        let det = &mut det[..m];
        let (na, nonfinite, sing) = (Status::NotAssemblable.code(), Status::NonFinite.code(), Status::Singular.code());
        let mut case = [0.0; B];
        for j in 0..m {
            // (a point that did not solve is masked where it is written out)
            let (p, dt, cs) = closed_form([x1[j], y1[j]], [x2[j], y2[j]], d.side, d.r1, d.r2);
            (xq[j], yq[j], det[j], case[j]) = (p[0], p[1], dt, cs);
        }
        let (s1, s2, sq) = two_in_one_out(c.st, d.k1, d.k2, d.p, m);
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
