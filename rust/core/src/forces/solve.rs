//! Statics and inverse dynamics along a sweep, row by row: the loads (and d'Alembert's
//! inertia forces) gathered per link, the Newton-Euler equations solved block after block
//! for every reaction and the input effort, the same effort by virtual work through the
//! sweep's velocity map, the energies and the checks' residuals. The kernel of the subject.

use super::model::{Direction, Model, Output};
use crate::error::Error;
use crate::status::Status;

/// A point is taken to be at a dead point when the sweep's scale-free conditioning is
/// below this (as the Python layer's `DEAD_POINT`): an effort there is amplified by more
/// than 1e5 over the loads' scale.
pub const DEAD_POINT: f64 = 1e-5;

/// A sweep's rows as the kernel reads them: arrays in the sweep's own point and link
/// order, with the maps from the model's points and moving links into it.
#[derive(Clone, Copy, Debug)]
pub struct Motion<'a> {
    /// (N,) input values.
    pub theta: &'a [f64],
    /// (N,) the sweep's statuses.
    pub status: &'a [i8],
    /// (N,) the sweep's scale-free conditioning.
    pub det: &'a [f64],
    /// (N, SP, 2) positions, velocities (at `rate`) and accelerations (at `rate`, constant).
    pub coords: &'a [f64],
    /// Velocities.
    pub velocity: &'a [f64],
    /// Accelerations (needed for dynamics).
    pub acceleration: Option<&'a [f64]>,
    /// (N, SL) links' angular velocities and accelerations.
    pub angular_velocity: &'a [f64],
    /// Angular accelerations (needed for dynamics).
    pub angular_acceleration: Option<&'a [f64]>,
    /// The sweep column of each model point.
    pub point_map: &'a [usize],
    /// The sweep column of each moving link.
    pub link_map: &'a [usize],
    /// The input rate the sweep's velocities were computed at (nonzero).
    pub rate: f64,
}

/// The input's rate and its rate of change at every row (dynamics).
#[derive(Clone, Copy, Debug)]
pub struct Drive<'a> {
    /// (N,) input rate.
    pub omega: &'a [f64],
    /// (N,) its rate of change.
    pub alpha: &'a [f64],
}

/// What [`solve`] writes, row by row.
#[derive(Clone, Debug, Default)]
pub struct Solution {
    /// (N, columns) every unknown (NaN where not solved).
    pub unknowns: Vec<f64>,
    /// (N,) the sweep's status, SINGULAR at a dead point or a singular block.
    pub status: Vec<i8>,
    /// (N,) the input effort by virtual work.
    pub virtual_work: Vec<f64>,
    /// (N, 3) the force and moment (divided by the size) the links exert on the ground.
    pub ground: Vec<f64>,
    /// (N,) kinetic and potential energy.
    pub kinetic: Vec<f64>,
    /// Potential energy.
    pub potential: Vec<f64>,
    /// (N,) input power.
    pub input_power: Vec<f64>,
    /// (N,) mechanical advantage (empty without an output).
    pub advantage: Vec<f64>,
    /// Largest relative residual: virtual work against Newton-Euler.
    pub check_virtual_work: f64,
    /// The energy balance's (dynamics only).
    pub check_energy: Option<f64>,
}

#[inline]
fn cross(r: [f64; 2], f: [f64; 2]) -> f64 {
    r[0] * f[1] - r[1] * f[0]
}

#[inline]
fn dot(a: [f64; 2], b: [f64; 2]) -> f64 {
    a[0] * b[0] + a[1] * b[1]
}

#[inline]
fn sub(a: [f64; 2], b: [f64; 2]) -> [f64; 2] {
    [a[0] - b[0], a[1] - b[1]]
}

/// Per-row sums of the loads: force and moment on each link, virtual power at unit rate
/// (and its magnitude), power at the actual rate (and its magnitude), the energies.
#[derive(Default)]
struct Tally {
    f: Vec<[f64; 2]>,
    m: Vec<f64>,
    gen: f64,
    gabs: f64,
    power: f64,
    pabs: f64,
    pot: f64,
    dpot: f64,
    dpabs: f64,
    kin: f64,
    dkin: f64,
    dkabs: f64,
}

impl Tally {
    fn reset(&mut self) {
        self.f.iter_mut().for_each(|v| *v = [0.0; 2]);
        self.m.iter_mut().for_each(|v| *v = 0.0);
        for s in [
            &mut self.gen,
            &mut self.gabs,
            &mut self.power,
            &mut self.pabs,
            &mut self.pot,
            &mut self.dpot,
            &mut self.dpabs,
            &mut self.kin,
            &mut self.dkin,
            &mut self.dkabs,
        ] {
            *s = 0.0;
        }
    }

    fn force(&mut self, link: usize, arm: [f64; 2], f: [f64; 2], v1: [f64; 2], v: [f64; 2], work: bool) {
        self.f[link][0] += f[0];
        self.f[link][1] += f[1];
        self.m[link] += cross(arm, f);
        let g = dot(f, v1);
        self.gen += g;
        self.gabs += g.abs();
        if work {
            let p = dot(f, v);
            self.power += p;
            self.pabs += p.abs();
        }
    }
}

/// One row's kinematics in the model's order, at unit rate (`v1`, `w1`) and actual rate.
struct Row {
    p: Vec<[f64; 2]>,
    v1: Vec<[f64; 2]>,
    acc: Vec<[f64; 2]>,
    w1: Vec<f64>,
    wa: Vec<f64>,
    u: Vec<[f64; 2]>,
    n: Vec<[f64; 2]>,
}

/// Statics (`drive` None) or inverse dynamics along `motion`.
pub fn solve(model: &Model, motion: &Motion<'_>, drive: Option<Drive<'_>>) -> Result<Solution, Error> {
    let n = motion.theta.len();
    let sp = motion.coords.len().checked_div(2 * n).unwrap_or(0);
    let sl = motion.angular_velocity.len().checked_div(n).unwrap_or(0);
    let need = |name: &str, a: &[f64], len: usize| {
        if a.len() == len {
            Ok(())
        } else {
            Err(Error::Shape { name: name.into(), got: a.len(), expected: len })
        }
    };
    need("coords", motion.coords, n * sp * 2)?;
    need("velocity", motion.velocity, n * sp * 2)?;
    need("det", motion.det, n)?;
    need("angular_velocity", motion.angular_velocity, n * sl)?;
    if motion.status.len() != n {
        return Err(Error::Shape { name: "status".into(), got: motion.status.len(), expected: n });
    }
    if motion.point_map.len() != model.points || motion.point_map.iter().any(|&c| c >= sp) {
        return Err(Error::array("point_map", "must give a sweep column for every point"));
    }
    if motion.link_map.len() != model.moving || motion.link_map.iter().any(|&c| c >= sl) {
        return Err(Error::array("link_map", "must give a sweep column for every moving link"));
    }
    if !(motion.rate.is_finite() && motion.rate != 0.0) {
        return Err(Error::invalid("rate", "must be finite and nonzero", motion.rate));
    }
    let accel = match drive {
        Some(d) => {
            need("omega", d.omega, n)?;
            need("alpha", d.alpha, n)?;
            let (Some(a), Some(aa)) = (motion.acceleration, motion.angular_acceleration) else {
                return Err(Error::array("acceleration", "is needed for dynamics"));
            };
            need("acceleration", a, n * sp * 2)?;
            need("angular_acceleration", aa, n * sl)?;
            Some((a, aa))
        }
        None => None,
    };
    let dynamic = drive.is_some();
    let nl = model.moving + 1;
    let k = model.columns;
    let rows = 3 * nl;
    let mut out = Solution {
        unknowns: vec![f64::NAN; n * k],
        status: motion.status.to_vec(),
        virtual_work: vec![f64::NAN; n],
        ground: vec![f64::NAN; n * 3],
        kinetic: vec![0.0; n],
        potential: vec![0.0; n],
        input_power: vec![0.0; n],
        advantage: if model.output.is_some() { vec![f64::NAN; n] } else { Vec::new() },
        check_virtual_work: 0.0,
        check_energy: None,
    };
    let mut a = vec![0.0; rows * k];
    let mut t = Tally { f: vec![[0.0; 2]; nl], m: vec![0.0; nl], ..Tally::default() };
    let np = model.points;
    let nlines = model.lines.len();
    let mut row = Row {
        p: vec![[0.0; 2]; np],
        v1: vec![[0.0; 2]; np],
        acc: vec![[0.0; 2]; np],
        w1: vec![0.0; nl],
        wa: vec![0.0; nl],
        u: vec![[0.0; 2]; nlines],
        n: vec![[0.0; 2]; nlines],
    };
    let wide = model.widest;
    let mut lu = vec![0.0; wide * wide];
    let mut rhs = vec![0.0; rows];
    let mut b = vec![0.0; wide];
    let (mut vw_res, mut vw_scale) = (0.0f64, 0.0f64);
    let (mut e_res, mut e_scale) = (0.0f64, 0.0f64);
    let converged = Status::Converged.code();
    let per_rate = 1.0 / motion.rate;
    let inv_size = 1.0 / model.size;
    for i in 0..n {
        let theta = motion.theta[i];
        let (w, al) = drive.map_or((0.0, 0.0), |d| (d.omega[i], d.alpha[i]));
        // kinematics in the model's order, scaled to a unit input rate
        for (q, &c) in motion.point_map.iter().enumerate() {
            let o = (i * sp + c) * 2;
            row.p[q] = [motion.coords[o], motion.coords[o + 1]];
            row.v1[q] = [motion.velocity[o] * per_rate, motion.velocity[o + 1] * per_rate];
        }
        for (l, &c) in motion.link_map.iter().enumerate() {
            row.w1[l] = motion.angular_velocity[i * sl + c] * per_rate;
        }
        if let Some((acc, aacc)) = accel {
            // the accelerations at a constant unit rate, scaled to this rate and its change
            let ww = w * w * per_rate * per_rate;
            for (q, &c) in motion.point_map.iter().enumerate() {
                let o = (i * sp + c) * 2;
                let v1 = row.v1[q];
                row.acc[q] = [ww * acc[o] + al * v1[0], ww * acc[o + 1] + al * v1[1]];
            }
            for (l, &c) in motion.link_map.iter().enumerate() {
                row.wa[l] = ww * aacc[i * sl + c] + al * row.w1[l];
            }
        }
        for (j, line) in model.lines.iter().enumerate() {
            let d = sub(row.p[line.b], row.p[line.a]);
            let len = (d[0] * d[0] + d[1] * d[1]).sqrt();
            let u = [d[0] / len, d[1] / len];
            row.u[j] = u;
            row.n[j] = [-u[1], u[0]];
        }
        t.reset();
        loads(model, &row, &mut t, theta, w, dynamic);
        out.kinetic[i] = t.kin;
        out.potential[i] = t.pot;

        let mut st = motion.status[i];
        if st == converged && !(motion.det[i].abs() >= DEAD_POINT) {
            st = Status::Singular.code();
        }
        let x = &mut out.unknowns[i * k..(i + 1) * k];
        if st == converged {
            matrix(model, &row, &mut a);
            for l in 0..model.moving {
                rhs[3 * l] = -t.f[l][0];
                rhs[3 * l + 1] = -t.f[l][1];
                rhs[3 * l + 2] = -t.m[l] * inv_size;
            }
            if !blocks(model, &a, &rhs, x, &mut lu, &mut b) {
                st = Status::Singular.code();
                x.iter_mut().for_each(|v| *v = f64::NAN);
            }
        }
        out.status[i] = st;
        if st != converged {
            out.kinetic[i] = f64::NAN;
            out.potential[i] = f64::NAN;
            out.input_power[i] = f64::NAN;
            continue;
        }
        let g = &mut out.ground[i * 3..i * 3 + 3];
        for (r, gr) in g.iter_mut().enumerate() {
            let ar = &a[(3 * model.moving + r) * k..(3 * model.moving + r + 1) * k];
            *gr = ar.iter().zip(x.iter()).map(|(p, q)| p * q).sum();
        }
        let q_ne = x[k - 1];
        let q_vw = -t.gen;
        out.virtual_work[i] = q_vw;
        vw_res = vw_res.max((q_vw - q_ne).abs());
        vw_scale = vw_scale.max(t.gabs + q_ne.abs());
        let p_in = q_ne * w;
        out.input_power[i] = p_in;
        if dynamic {
            e_res = e_res.max((p_in + t.power - t.dpot - t.dkin).abs());
            e_scale = e_scale.max(p_in.abs() + t.pabs + t.dpabs + t.dkabs);
        }
        match model.output {
            Some(Output::Link(l)) => out.advantage[i] = 1.0 / row.w1[l],
            Some(Output::Line(j, q)) => out.advantage[i] = 1.0 / along(model, &row, j, q),
            None => {}
        }
    }
    out.check_virtual_work = if vw_scale > 0.0 { vw_res / vw_scale } else { 0.0 };
    if dynamic {
        out.check_energy = Some(if e_scale > 0.0 { e_res / e_scale } else { 0.0 });
    }
    Ok(out)
}

/// The rate of the displacement of point `q` along line `j` relative to its guide, at a
/// unit input rate.
fn along(model: &Model, row: &Row, j: usize, q: usize) -> f64 {
    let line = model.lines[j];
    let r = sub(row.p[q], row.p[line.a]);
    let wg = row.w1[line.guide];
    let rel = [row.v1[q][0] - row.v1[line.a][0] + wg * r[1], row.v1[q][1] - row.v1[line.a][1] - wg * r[0]];
    dot(row.u[j], rel)
}

/// Every load of one row into the tally (`w` the input rate; inertia when `dynamic`).
fn loads(model: &Model, row: &Row, t: &mut Tally, theta: f64, w: f64, dynamic: bool) {
    let l = &model.loads;
    let refp = |k: usize| row.p[model.refs[k]];
    let scaled = |v: [f64; 2]| [w * v[0], w * v[1]];
    for (link, q, tab) in &l.point_forces {
        let f = tab.at2(theta);
        let (p, v1) = (row.p[*q], row.v1[*q]);
        t.force(*link, sub(p, refp(*link)), f, v1, scaled(v1), true);
    }
    for (j, q, holder, tab) in &l.line_forces {
        let mag = tab.at(theta, 0);
        let u = row.u[*j];
        let fu = [mag * u[0], mag * u[1]];
        let s1 = along(model, row, *j, *q);
        let p = row.p[*q];
        let g = model.lines[*j].guide;
        t.f[*holder][0] += fu[0];
        t.f[*holder][1] += fu[1];
        t.m[*holder] += cross(sub(p, refp(*holder)), fu);
        t.f[g][0] -= fu[0];
        t.f[g][1] -= fu[1];
        t.m[g] -= cross(sub(p, refp(g)), fu);
        t.gen += mag * s1;
        t.gabs += (mag * s1).abs();
        t.power += mag * w * s1;
        t.pabs += (mag * w * s1).abs();
    }
    for (k, tab) in &l.torques {
        let tq = tab.at(theta, 0);
        t.m[*k] += tq;
        let g = tq * row.w1[*k];
        t.gen += g;
        t.gabs += g.abs();
        let p = tq * w * row.w1[*k];
        t.power += p;
        t.pabs += p.abs();
    }
    for (e, spring) in l.springs.iter().map(|e| (e, true)).chain(l.dampers.iter().map(|e| (e, false))) {
        let (pa, pb) = (row.p[e.a], row.p[e.b]);
        let d = sub(pb, pa);
        let length = (d[0] * d[0] + d[1] * d[1]).sqrt();
        let ev = [d[0] / length, d[1] / length];
        let (va, vb) = (scaled(row.v1[e.a]), scaled(row.v1[e.b]));
        let rate_d = dot(ev, sub(vb, va));
        let tension = if spring {
            let stretch = length - e.free_length;
            t.pot += e.preload * stretch + 0.5 * e.rate * stretch * stretch;
            e.preload + e.rate * stretch
        } else {
            e.rate * rate_d
        };
        let f = [tension * ev[0], tension * ev[1]];
        // a spring's power is its potential energy's rate, tallied apart
        t.force(e.link_a, sub(pa, refp(e.link_a)), f, row.v1[e.a], va, !spring);
        t.force(e.link_b, sub(pb, refp(e.link_b)), [-f[0], -f[1]], row.v1[e.b], vb, !spring);
        if spring {
            t.dpot += tension * rate_d;
            t.dpabs += (tension * rate_d).abs();
        }
    }
    for m in &l.masses {
        let k = m.link;
        // the centre's arm from point a as drawn, turned with the link
        let d = sub(row.p[m.b], row.p[m.a]);
        let inv = 1.0 / (d[0] * d[0] + d[1] * d[1]).sqrt();
        let d = [d[0] * inv, d[1] * inv];
        let cs = dot(d, m.drawn);
        let sn = cross(m.drawn, d);
        let r = [cs * m.arm[0] - sn * m.arm[1], sn * m.arm[0] + cs * m.arm[1]];
        let rp = [-r[1], r[0]];
        let g_at = [row.p[m.a][0] + r[0], row.p[m.a][1] + r[1]];
        let w1 = row.w1[k];
        let v1g = [row.v1[m.a][0] + w1 * rp[0], row.v1[m.a][1] + w1 * rp[1]];
        let vg = scaled(v1g);
        let mut f = [0.0; 2];
        if let Some(gv) = l.gravity {
            let wg = [m.mass * gv[0], m.mass * gv[1]];
            f = wg;
            let pw = dot(vg, wg);
            t.pot -= dot(g_at, wg);
            t.dpot -= pw;
            t.dpabs += pw.abs();
        }
        let mut tq = 0.0;
        if dynamic {
            let (wa, wl) = (row.wa[k], w * w1);
            let ag = [row.acc[m.a][0] + wa * rp[0] - wl * wl * r[0], row.acc[m.a][1] + wa * rp[1] - wl * wl * r[1]];
            // d'Alembert: the inertia force and couple as loads (no power: they are the
            // kinetic energy's rate of change, tallied apart)
            f[0] -= m.mass * ag[0];
            f[1] -= m.mass * ag[1];
            tq = -m.inertia * wa;
            t.kin += 0.5 * (m.mass * dot(vg, vg) + m.inertia * wl * wl);
            let dk_t = m.mass * dot(ag, vg);
            let dk_r = m.inertia * wa * wl;
            t.dkin += dk_t + dk_r;
            t.dkabs += dk_t.abs() + dk_r.abs();
        }
        t.f[k][0] += f[0];
        t.f[k][1] += f[1];
        t.m[k] += cross(sub(g_at, refp(k)), f) + tq;
        let gf = dot(f, v1g);
        let gt = tq * w1;
        t.gen += gf + gt;
        t.gabs += gf.abs() + gt.abs();
    }
}

/// The Newton-Euler matrix at one pose: each link's force (x, y) and moment about its
/// reference point (divided by the size) from unit unknowns, ground's rows last.
fn matrix(model: &Model, row: &Row, a: &mut [f64]) {
    let k = model.columns;
    // moments are divided by the size: multiplied by its reciprocal (a division per entry
    // costs more than the rest of the entry)
    let inv = 1.0 / model.size;
    for f in &model.forces {
        let r = sub(row.p[f.point], row.p[model.refs[f.link]]);
        let base = 3 * f.link * k + f.column;
        let w = f.sign * inv;
        // an axis force leaves the other axis' entry alone (another column may own it)
        match f.dir {
            Direction::X => {
                a[base] = f.sign;
                a[base + 2 * k] = -r[1] * w;
            }
            Direction::Y => {
                a[base + k] = f.sign;
                a[base + 2 * k] = r[0] * w;
            }
            Direction::Normal(j) | Direction::Along(j) => {
                let d = if matches!(f.dir, Direction::Normal(_)) { row.n[j] } else { row.u[j] };
                a[base] = f.sign * d[0];
                a[base + k] = f.sign * d[1];
                a[base + 2 * k] = cross(r, d) * w;
            }
        }
    }
    for c in &model.couples {
        a[(3 * c.link + 2) * k + c.column] = c.sign * inv;
    }
}

/// Solves the moving links' equations block by block into `x`; false where a block is
/// singular (an exactly zero pivot) or its solution is not finite.
fn blocks(model: &Model, a: &[f64], rhs: &[f64], x: &mut [f64], lu: &mut [f64], b: &mut [f64]) -> bool {
    for (blk, plan) in model.blocks.iter().zip(&model.plans) {
        let m = blk.rows.len();
        for (i, &r) in blk.rows.iter().enumerate() {
            b[i] = rhs[r];
        }
        for &(i, e, c) in &plan.prior {
            b[i] -= a[e] * x[c];
        }
        if m == 1 {
            x[blk.columns[0]] = b[0] / a[plan.entries[0]];
            continue;
        }
        let lu = &mut lu[..m * m];
        for (v, &e) in lu.iter_mut().zip(&plan.entries) {
            *v = a[e];
        }
        // the exact pivots first: their rows stay as they are, the others lose the column
        for &(i, j) in &plan.statics {
            let p = 1.0 / lu[i * m + j];
            for &q in &plan.rest_rows {
                let e = lu[q * m + j];
                if e != 0.0 {
                    let f = e * p;
                    for &l in &plan.rest_cols {
                        lu[q * m + l] -= f * lu[i * m + l];
                    }
                    lu[q * m + j] = 0.0;
                    b[q] -= f * b[i];
                }
            }
        }
        let t = plan.rest_rows.len();
        let mut small = [0.0; 36];
        let mut v = [0.0; 6];
        let solved = if t <= 6 {
            for (i, &q) in plan.rest_rows.iter().enumerate() {
                for (j, &l) in plan.rest_cols.iter().enumerate() {
                    small[i * t + j] = lu[q * m + l];
                }
                v[i] = b[q];
            }
            match t {
                0 => true,
                1 => {
                    v[0] /= small[0];
                    true
                }
                2 => fixed::<2>(&small, &mut v),
                3 => fixed::<3>(&small, &mut v),
                4 => fixed::<4>(&small, &mut v),
                _ => dense_solve(&mut small[..t * t], &mut v[..t], t),
            }
        } else {
            let mut big: Vec<f64> = Vec::with_capacity(t * t);
            for &q in &plan.rest_rows {
                big.extend(plan.rest_cols.iter().map(|&l| lu[q * m + l]));
            }
            let mut w: Vec<f64> = plan.rest_rows.iter().map(|&q| b[q]).collect();
            let ok = dense_solve(&mut big, &mut w, t);
            for (j, &l) in plan.rest_cols.iter().enumerate() {
                x[blk.columns[l]] = w[j];
            }
            ok
        };
        if !solved {
            return false;
        }
        if t <= 6 {
            for (j, &l) in plan.rest_cols.iter().enumerate() {
                x[blk.columns[l]] = v[j];
            }
        }
        for &(i, j) in &plan.statics {
            let s: f64 = plan.rest_cols.iter().map(|&l| lu[i * m + l] * x[blk.columns[l]]).sum();
            x[blk.columns[j]] = (b[i] - s) * (1.0 / lu[i * m + j]);
        }
    }
    x.iter().all(|v| v.is_finite())
}

/// [`dense_solve`] of a system of a size known at compile time (`a` row-major, N x N),
/// on the stack: `b` becomes the solution. False on an exactly zero pivot.
#[inline]
fn fixed<const N: usize>(a: &[f64], b: &mut [f64]) -> bool {
    let mut m = [[0.0; N]; N];
    let mut v = [0.0; N];
    let mut inv = [0.0; N];
    for i in 0..N {
        m[i].copy_from_slice(&a[i * N..(i + 1) * N]);
        v[i] = b[i];
    }
    for col in 0..N {
        let mut piv = col;
        let mut best = m[col][col].abs();
        for (r, row) in m.iter().enumerate().skip(col + 1) {
            if row[col].abs() > best {
                best = row[col].abs();
                piv = r;
            }
        }
        if best == 0.0 {
            return false;
        }
        if piv != col {
            m.swap(col, piv);
            v.swap(col, piv);
        }
        // as LAPACK's getf2: the column scaled by the pivot's reciprocal
        let d = 1.0 / m[col][col];
        inv[col] = d;
        let pivot_row = m[col];
        let vc = v[col];
        for r in col + 1..N {
            if m[r][col] != 0.0 {
                let f = m[r][col] * d;
                for j in col + 1..N {
                    m[r][j] -= f * pivot_row[j];
                }
                v[r] -= f * vc;
            }
        }
    }
    for col in (0..N).rev() {
        let mut s = v[col];
        for j in col + 1..N {
            s -= m[col][j] * v[j];
        }
        v[col] = s * inv[col];
    }
    b[..N].copy_from_slice(&v);
    true
}

/// Gaussian elimination with partial pivoting, in place: `b` becomes the solution of
/// `a x = b`. False on an exactly zero pivot.
fn dense_solve(a: &mut [f64], b: &mut [f64], m: usize) -> bool {
    for col in 0..m {
        let mut piv = col;
        let mut best = a[col * m + col].abs();
        for r in col + 1..m {
            let v = a[r * m + col].abs();
            if v > best {
                best = v;
                piv = r;
            }
        }
        if best == 0.0 {
            return false;
        }
        if piv != col {
            for j in 0..m {
                a.swap(col * m + j, piv * m + j);
            }
            b.swap(col, piv);
        }
        let d = 1.0 / a[col * m + col];
        for r in col + 1..m {
            let f = a[r * m + col] * d;
            if f != 0.0 {
                for j in col + 1..m {
                    a[r * m + j] -= f * a[col * m + j];
                }
                b[r] -= f * b[col];
            }
        }
    }
    for col in (0..m).rev() {
        let mut s = b[col];
        for j in col + 1..m {
            s -= a[col * m + j] * b[j];
        }
        b[col] = s / a[col * m + col];
    }
    true
}
