//! Solving a group by Newton and placing its points (with their velocities and
//! accelerations), and reading its unknowns back off positions.

use nalgebra::SVector;

use super::equations::{cs_of, At};
use super::{Group, GroupSolve, Node, Reader, MAX};
use crate::scene::vec2::{cdiv, cmul, dot, sub, Xy};
use crate::solve::newton::{self, hadamard_ratio, NewtonOptions};
use crate::{wrap_angle, Status};

impl Group {
    /// Newton from `guess` with the anchors at `anchors`; the tangent dx/dtheta from the
    /// anchors' velocities `anchor_vel` when given. `stall`: give up where Newton's residual
    /// stalls ([`newton::solve_or_stall`]), as near a dead point, where a step past it has
    /// no root.
    pub(crate) fn solve(
        &self,
        anchors: &[Xy],
        anchor_vel: Option<&[Xy]>,
        guess: &[f64],
        opts: &NewtonOptions,
        stall: bool,
    ) -> GroupSolve {
        dispatch!(self.n(), solve_n, self, anchors, anchor_vel, guess, opts, stall)
    }

    /// Newton's first evaluation from a prediction, kept only where it converges there
    /// (its correction applied, as [`newton::solve`] does: the same solution, status and
    /// conditioning), with the tangent dx/dtheta from the same elimination. That Jacobian
    /// is the prediction's, one correction (below `tol`) from the solution's, so the tangent
    /// is within about `tol` / conditioning of the solution's: enough to predict the next
    /// angle, not for rates reported as outputs (those take [`Group::solve`]). `None`: it did
    /// not converge there, and the full solve decides.
    pub(crate) fn solve_predicted(
        &self,
        anchors: &[Xy],
        anchor_vel: &[Xy],
        guess: &[f64],
        opts: &NewtonOptions,
    ) -> Option<GroupSolve> {
        dispatch!(self.n(), predicted_n, self, anchors, anchor_vel, guess, opts)
    }

    /// Visits each node with its term's multiplier and arm.
    pub(super) fn each_node(&self, x: &[f64], anchors: &[Xy], mut visit: impl FnMut(usize, &Node, Xy, Xy)) {
        let cs: Vec<Xy> = x[..self.nrot].iter().map(|a| cs_of(*a)).collect();
        for (i, nd) in self.nodes.iter().enumerate() {
            visit(i, nd, nd.term.m(&cs, anchors), nd.term.arm(x, self.held_of(anchors)));
        }
    }

    /// Positions of the nodes from the anchors' positions and the unknowns.
    pub(crate) fn place(&self, x: &[f64], anchors: &[Xy], mut put: impl FnMut(usize, Xy)) {
        // (the anchors' own: a held displacement past them is no point)
        let mut pos: Vec<Xy> = anchors[..self.anchors.len()].to_vec();
        self.each_node(x, anchors, |_, nd, m, arm| {
            let r = cmul(m, arm);
            let b = pos[nd.base];
            let p = [b[0] + r[0], b[1] + r[1]];
            pos.push(p);
            put(nd.point, p);
        });
    }

    /// Positions (as [`Group::place`] gives them, bit for bit) and velocities (per unit
    /// input rate, from the anchors' velocities and the unknowns' rates `dx`) of the nodes
    /// in one pass, from the rotations' (cos, sin) `cs` (those of [`GroupSolve::cs`]), with
    /// no allocation for a group of up to 32 points (a sweep's every solved angle); the
    /// velocities only where `rates` (zero otherwise).
    pub(crate) fn place_moving(
        &self,
        x: &[f64],
        dx: &[f64],
        cs: &[Xy],
        anchors: &[Xy],
        anchor_vel: &[Xy],
        rates: bool,
        mut put: impl FnMut(usize, Xy, Xy),
    ) {
        const SMALL: usize = 32;
        let na = self.anchors.len();
        let total = na + self.nodes.len();
        let (mut pbuf, mut vbuf) = ([[0.0; 2]; SMALL], [[0.0; 2]; SMALL]);
        let mut heap: (Vec<Xy>, Vec<Xy>);
        let (pos, vel): (&mut [Xy], &mut [Xy]) = if total <= SMALL {
            (&mut pbuf[..total], &mut vbuf[..total])
        } else {
            heap = (vec![[0.0; 2]; total], vec![[0.0; 2]; total]);
            (&mut heap.0, &mut heap.1)
        };
        pos[..na].copy_from_slice(&anchors[..na]);
        vel[..na].copy_from_slice(&anchor_vel[..na]);
        for (k, nd) in (na..).zip(&self.nodes) {
            let (m, arm) = (nd.term.m(&cs[..self.nrot], anchors), nd.term.arm(x, self.held_of(anchors)));
            let r = cmul(m, arm);
            let b = pos[nd.base];
            pos[k] = [b[0] + r[0], b[1] + r[1]];
            if rates {
                let (vb, w) = (vel[nd.base], self.term_rate(&nd.term, m, arm, dx, anchor_vel));
                vel[k] = [vb[0] + w[0], vb[1] + w[1]];
            }
            put(nd.point, pos[k], vel[k]);
        }
    }

    /// Accelerations of the nodes (per unit input rate squared), from the anchors'
    /// positions, velocities and accelerations `k` and the unknowns' first and second rates.
    pub(crate) fn place_acceleration(
        &self,
        x: &[f64],
        dx: &[f64],
        ddx: &[f64],
        k: [&[Xy]; 3],
        mut put: impl FnMut(usize, Xy),
    ) {
        let cs: Vec<Xy> = x[..self.nrot].iter().map(|a| cs_of(*a)).collect();
        let mut acc: Vec<Xy> = k[2][..self.anchors.len()].to_vec();
        let still = vec![[0.0; 2]; k[0].len()];
        for nd in &self.nodes {
            let t = &nd.term;
            let m = t.m(&cs, k[0]);
            // the x'' part: w' perp(M arm) + M s'' d
            let lin = self.term_rate(t, m, t.arm(x, self.held_of(k[0])), ddx, &still);
            let rest = self.term_curvature(t, &cs, dx, x, k);
            let ab = acc[nd.base];
            let a = [ab[0] + lin[0] + rest[0], ab[1] + lin[1] + rest[1]];
            acc.push(a);
            put(nd.point, a);
        }
    }

    /// The unknowns read off positions: rotations from their drawn pose, then
    /// displacements.
    pub(crate) fn unknowns_from(&self, pos: impl Fn(usize) -> Xy) -> Vec<f64> {
        let anchors: Vec<Xy> = self.anchors.iter().map(|&p| pos(p)).collect();
        let mut x = vec![0.0; self.n()];
        for (k, r) in self.readers.iter().enumerate() {
            if let Reader::Rotation { a, b, drawn } = r {
                let d = sub(pos(*b), pos(*a));
                x[k] = wrap_angle((d[1] + 0.0).atan2(d[0]) - (drawn[1] + 0.0).atan2(drawn[0]));
            }
        }
        let cs: Vec<Xy> = x[..self.nrot].iter().map(|a| cs_of(*a)).collect();
        for (k, r) in self.readers.iter().enumerate() {
            if let Reader::Slide { from, to, term } = r {
                let (_, d) = term.slide.expect("a slide reader's edge slides");
                let q = sub(cdiv(sub(pos(*to), pos(*from)), term.m(&cs, &anchors)), term.v);
                x[k] = dot(q, d) / dot(d, d);
            }
        }
        x
    }

    /// The held displacement (solving frame) at positions `pos` of every point, read off
    /// its edge as a slide column is; 0 for a group without one.
    pub(crate) fn held_at(&self, pos: impl Fn(usize) -> Xy) -> f64 {
        let Some((from, to, term)) = self.held else { return 0.0 };
        let anchors: Vec<Xy> = self.anchors.iter().map(|&p| pos(p)).collect();
        let x = self.unknowns_from(&pos);
        let cs: Vec<Xy> = x[..self.nrot].iter().map(|a| cs_of(*a)).collect();
        let (_, d) = term.slide.expect("the held edge slides");
        let q = sub(cdiv(sub(pos(to), pos(from)), term.m(&cs, &anchors)), term.v);
        dot(q, d) / dot(d, d)
    }

    /// The elbow signs of the group's joints at positions `pos`: "+" / "-" per joint.
    pub(crate) fn elbow_label(&self, pos: impl Fn(usize) -> Xy) -> String {
        self.elbows
            .iter()
            .map(|&(p, a, b)| {
                let (u, v) = (sub(pos(a), pos(p)), sub(pos(b), pos(p)));
                if u[0] * v[1] - u[1] * v[0] < 0.0 {
                    '-'
                } else {
                    '+'
                }
            })
            .collect()
    }
}

pub(super) fn solve_n<const N: usize>(
    g: &Group,
    anchors: &[Xy],
    anchor_vel: Option<&[Xy]>,
    guess: &[f64],
    opts: &NewtonOptions,
    stall: bool,
) -> GroupSolve {
    let sys = At { g, anchors };
    let x0 = SVector::<f64, N>::from_fn(|k, _| guess[k]);
    let out = if stall { newton::solve_or_stall(&sys, x0, opts) } else { newton::solve(&sys, x0, opts, None) };
    let mut phi = [f64::NAN; MAX];
    let mut dphi = [f64::NAN; MAX];
    let mut cs = [[f64::NAN; 2]; MAX];
    // (the signed Hadamard ratio of the last Jacobian, from the last step's elimination)
    let det = if out.conditioning.is_nan() { hadamard_ratio(&out.jacobian) } else { out.conditioning };
    if out.status == Status::Converged {
        for (k, (p, x)) in phi.iter_mut().zip(out.x.iter()).enumerate() {
            *p = if g.is_angle(k) { wrap_angle(*x) } else { *x };
        }
        if let Some(vel) = anchor_vel {
            // J dx = -dF/dtheta at fixed unknowns, with J at the solution: Newton's last
            // Jacobian is one correction away from it, and where the start was predicted so
            // well that it converged at once (nit 0) that correction is about the tolerance,
            // and the rates would be off by as much. The rotations' sines and cosines are
            // kept for the placement.
            g.turns(&phi[..N], &mut cs);
            let mut m = [[0.0; N]; N];
            g.closure_terms_with(&phi[..N], &cs[..g.nrot], anchors, |_, _| {}, |r, c, v| m[r][c] += v);
            let d = g.rate_terms(&phi[..N], &cs[..g.nrot], anchors, vel);
            let mut rhs: [[f64; 1]; N] = std::array::from_fn(|r| [-d[r / 2][r % 2]]);
            if newton::eliminate_rows(&mut m, &mut rhs, &mut 1.0) {
                for (t, r) in dphi.iter_mut().zip(rhs) {
                    *t = r[0];
                }
            }
        }
    }
    GroupSolve { phi, dphi, status: out.status, nit: out.nit, det, cs }
}

fn predicted_n<const N: usize>(
    g: &Group,
    anchors: &[Xy],
    anchor_vel: &[Xy],
    guess: &[f64],
    opts: &NewtonOptions,
) -> Option<GroupSolve> {
    let x = &guess[..N];
    let mut cs = [[f64::NAN; 2]; MAX];
    g.turns(x, &mut cs);
    // [J | -F | -dF/dtheta] at the prediction, J row-major: the two right-hand sides are
    // eliminated together
    let mut m = [[0.0; N]; N];
    let mut rhs = [[0.0; 2]; N];
    g.closure_terms_with(x, &cs[..g.nrot], anchors, |r, v| rhs[r][0] = -v, |r, c, v| m[r][c] += v);
    let residual = rhs.iter().fold(0.0_f64, |a, r| a.max(r[0].abs()));
    if !rhs.iter().zip(x).all(|(r, v)| r[0].is_finite() && v.is_finite()) || !(residual < opts.tol) {
        return None;
    }
    let d = g.rate_terms(x, &cs[..g.nrot], anchors, anchor_vel);
    for (r, row) in rhs.iter_mut().enumerate() {
        row[1] = -d[r / 2][r % 2];
    }
    // the signed Hadamard ratio, as [`newton::hadamard_step`] gives it
    let norms: f64 = (0..N).map(|c| m.iter().fold(0.0, |a, row| a + row[c] * row[c]).sqrt()).product();
    let mut det = 1.0;
    if !newton::eliminate_rows(&mut m, &mut rhs, &mut det) {
        return None;
    }
    let conditioning = if norms == 0.0 { 0.0 } else { det / norms };
    if !(conditioning.abs() >= opts.singular) || !rhs.iter().all(|r| r[0].abs() < opts.tol) {
        return None;
    }
    let mut out = GroupSolve {
        phi: [f64::NAN; MAX],
        dphi: [f64::NAN; MAX],
        status: Status::Converged,
        nit: 0,
        det: conditioning,
        cs: [[f64::NAN; 2]; MAX],
    };
    for (k, (v, r)) in x.iter().zip(rhs).enumerate() {
        let [step, rate] = r;
        out.dphi[k] = rate;
        if g.is_angle(k) {
            out.phi[k] = wrap_angle(v + step);
            // (cos, sin) turned on by the step: cos and sin of a step below `tol` are
            // 1 - step^2 / 2 and step to within rounding
            let ([c, s], h) = (cs[k], 1.0 - 0.5 * step * step);
            out.cs[k] = [c * h - s * step, s * h + c * step];
        } else {
            out.phi[k] = v + step;
        }
    }
    Some(out)
}
