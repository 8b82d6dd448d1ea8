//! A rigid group: links that no dyad reaches, solved together by the generic Newton solver
//! (a triad of a Stephenson six-bar: 4 unknowns; the double butterfly's six-link group: 6).
//!
//! Unknowns are the rotations phi_j of the group's links from their drawn pose. Joints are
//! reached from the known points (anchors) through a spanning tree of links; each link
//! outside the tree closes a loop. A point reached through links j_1 .. j_m from anchor a
//! sits at a + sum R(phi_j) v_j, so every loop-closure equation has the form
//!
//! ```text
//! F_c = (a_plus - a_minus) + sum_j R(phi_j) u_cj = 0,
//! ```
//!
//! linear in (cos phi_j, sin phi_j): the same coefficients feed Newton here and the
//! all-solutions homotopy. dF_c/dphi_j = perp(R(phi_j) u_cj); at fixed phi,
//! dF_c/dtheta = v_plus - v_minus (anchor velocities).

use nalgebra::{SMatrix, SVector};

use super::vec2::{perp, sub, turn, Xy};
use crate::solve::newton::{self, hadamard_ratio, NewtonOptions, System};
use crate::{wrap_angle, Status};

/// Calls `$f::<N>(args)` for the runtime group size (even: two equations per closure).
macro_rules! dispatch {
    ($n:expr, $f:ident, $($arg:expr),*) => {
        match $n {
            2 => $f::<2>($($arg),*),
            4 => $f::<4>($($arg),*),
            6 => $f::<6>($($arg),*),
            8 => $f::<8>($($arg),*),
            10 => $f::<10>($($arg),*),
            12 => $f::<12>($($arg),*),
            n => unreachable!("group of {n} links (build refuses odd sizes and more than MAX)"),
        }
    };
}

/// Most links a group may have (the Newton system is sized at compile time).
pub(crate) const MAX: usize = 12;

/// A point the group solves: `base` (a group-point index: anchors first, then nodes)
/// plus R(phi_link) v.
#[derive(Clone, Debug, PartialEq)]
pub(super) struct Node {
    pub point: usize,
    pub base: usize,
    pub link: usize,
    pub v: Xy,
}

/// One loop-closure pair of equations.
#[derive(Clone, Debug, PartialEq)]
pub(super) struct Closure {
    /// Anchor indices: F = a[plus] - a[minus] + sum_j R_j u[j].
    pub plus: usize,
    pub minus: usize,
    pub u: Vec<Xy>,
}

/// A compiled group.
#[derive(Clone, Debug, PartialEq)]
pub(super) struct Group {
    /// Scene indices of its links (unknown j is links[j]).
    pub links: Vec<usize>,
    /// Scene indices of the known points it hangs from.
    pub anchors: Vec<usize>,
    /// Joints in tree order, then points carried by one group link only.
    pub nodes: Vec<Node>,
    /// How many of `nodes` are joints (the rest are carried).
    pub joints: usize,
    pub closures: Vec<Closure>,
    /// Per link: two of its points (base, other) and their drawn difference, to read the
    /// link's rotation off positions.
    pub arms: Vec<(usize, usize, Xy)>,
    /// Per joint of two or more group links: (joint, a point of the first link, a point
    /// of the second). The sign of cross(a - joint, b - joint) is the joint's elbow: the
    /// assembly mode there, which changes only where the two links fall in line.
    pub elbows: Vec<(usize, usize, usize)>,
    /// Sign of the signed conditioning at the drawn pose: the branch to follow.
    pub sign: f64,
}

/// What one Newton solve of a group gives.
#[derive(Clone, Copy, Debug)]
pub(super) struct GroupSolve {
    pub phi: [f64; MAX],
    /// dphi / dtheta (NaN unless converged and anchor velocities were given).
    pub dphi: [f64; MAX],
    pub status: Status,
    pub nit: u32,
    /// Signed Hadamard ratio of the Jacobian at the solution.
    pub det: f64,
}

impl Group {
    /// Builds the spanning tree and closures for `links` hanging from the known points;
    /// `None` when the links are not one connected rigid group over them (some link or
    /// joint unreached, or a count that does not close), or when it is singular as drawn.
    pub(super) fn build(links: &[usize], link_points: &[&[usize]], known: &[bool], xy: &[Xy]) -> Option<Group> {
        let n = links.len();
        if n == 0 || n > MAX || n % 2 == 1 {
            return None;
        }
        let mut g = Self::tree(links, link_points, known, xy, 0)?;
        let delta = g.deltas(|p| xy[p]);
        let det = g.conditioning_with(&[0.0; MAX][..n], &delta[..g.closures.len()]);
        if !(det.abs() >= newton::SINGULAR_THRESHOLD) {
            return None;
        }
        g.sign = det.signum();
        Some(g)
    }

    /// The spanning tree and closures of `links` over the known points, leaving `dof`
    /// unknowns free (0 for a rigid group; 1 for a whole linkage with its input among the
    /// links, as tracing uses it). Any size: the caller checks what it needs.
    pub(super) fn tree(
        links: &[usize],
        link_points: &[&[usize]],
        known: &[bool],
        xy: &[Xy],
        dof: usize,
    ) -> Option<Group> {
        let n = links.len();
        let mut count = std::collections::HashMap::<usize, usize>::new();
        for pts in link_points {
            for &p in *pts {
                *count.entry(p).or_default() += 1;
            }
        }
        let mut anchors: Vec<usize> = count.keys().copied().filter(|&p| known[p]).collect();
        anchors.sort_unstable();
        let na = anchors.len();
        // group-point index of each scene point reached so far
        let mut gp = std::collections::HashMap::<usize, usize>::new();
        for (i, &a) in anchors.iter().enumerate() {
            gp.insert(a, i);
        }
        // per group point: its anchor and its path terms (link, vector)
        let mut root: Vec<usize> = (0..na).collect();
        let mut path: Vec<Vec<(usize, Xy)>> = vec![Vec::new(); na];
        let mut nodes = Vec::new();
        let mut base = vec![usize::MAX; n];
        let mut arms = vec![(0, 0, [0.0; 2]); n];
        let mut closures_at: Vec<(usize, usize)> = Vec::new(); // (group point, link)
        let mut queue: std::collections::VecDeque<usize> = anchors.iter().copied().collect();
        let is_joint = |p: usize| known[p] || count[&p] >= 2;
        while let Some(x) = queue.pop_front() {
            let gx = gp[&x];
            for (j, pts) in link_points.iter().enumerate() {
                if base[j] != usize::MAX || !pts.contains(&x) {
                    continue;
                }
                base[j] = gx;
                if let Some(&y) = pts.iter().find(|&&y| y != x) {
                    arms[j] = (x, y, sub(xy[y], xy[x]));
                }
                for &y in pts.iter().filter(|&&y| y != x && is_joint(y)) {
                    match gp.get(&y) {
                        Some(&gy) => closures_at.push((gy, j)),
                        None => {
                            let gy = na + nodes.len();
                            gp.insert(y, gy);
                            nodes.push(Node { point: y, base: gx, link: j, v: sub(xy[y], xy[x]) });
                            root.push(root[gx]);
                            let mut p = path[gx].clone();
                            p.push((j, sub(xy[y], xy[x])));
                            path.push(p);
                            queue.push_back(y);
                        }
                    }
                }
            }
        }
        if base.contains(&usize::MAX) || count.keys().any(|p| is_joint(*p) && !gp.contains_key(p)) {
            return None;
        }
        if 2 * closures_at.len() + dof != n {
            return None;
        }
        let closures = closures_at
            .iter()
            .map(|&(gq, j)| {
                let gb = base[j];
                let bp = if gb < na { anchors[gb] } else { nodes[gb - na].point };
                let q = if gq < na { anchors[gq] } else { nodes[gq - na].point };
                let mut u = vec![[0.0; 2]; n];
                for &(k, v) in &path[gb] {
                    u[k] = [u[k][0] + v[0], u[k][1] + v[1]];
                }
                let w = sub(xy[q], xy[bp]);
                u[j] = [u[j][0] + w[0], u[j][1] + w[1]];
                for &(k, v) in &path[gq] {
                    u[k] = [u[k][0] - v[0], u[k][1] - v[1]];
                }
                Closure { plus: root[gb], minus: root[gq], u }
            })
            .collect();
        let joints = nodes.len();
        let mut elbows = Vec::new();
        for nd in &nodes[..joints] {
            let on: Vec<&&[usize]> = link_points.iter().filter(|pts| pts.contains(&nd.point)).take(2).collect();
            if let [l1, l2] = on[..] {
                let other = |pts: &[usize]| pts.iter().copied().find(|&q| q != nd.point);
                if let (Some(a), Some(b)) = (other(l1), other(l2)) {
                    elbows.push((nd.point, a, b));
                }
            }
        }
        for (j, pts) in link_points.iter().enumerate() {
            for &y in pts.iter().filter(|&&y| !is_joint(y)) {
                let gb = base[j];
                let bp = if gb < na { anchors[gb] } else { nodes[gb - na].point };
                nodes.push(Node { point: y, base: gb, link: j, v: sub(xy[y], xy[bp]) });
            }
        }
        Some(Group { links: links.to_vec(), anchors, nodes, joints, closures, arms, elbows, sign: 0.0 })
    }

    /// Residuals and Jacobian of the closures at rotations `phi` (any number of them):
    /// `f(row, value)` and `j(row, column, value)` receive the nonzero entries.
    pub(super) fn closure_terms(
        &self,
        phi: &[f64],
        delta: &[Xy],
        mut f: impl FnMut(usize, f64),
        mut j: impl FnMut(usize, usize, f64),
    ) {
        // on the stack for every group (and chains up to 32 links): this runs per Newton step
        let mut buf = [[0.0; 2]; 32];
        let heap: Vec<Xy>;
        let cs: &[Xy] = if phi.len() <= buf.len() {
            for (b, a) in buf.iter_mut().zip(phi) {
                *b = cs_of(*a);
            }
            &buf[..phi.len()]
        } else {
            heap = phi.iter().map(|a| cs_of(*a)).collect();
            &heap
        };
        for (c, cl) in self.closures.iter().enumerate() {
            let (mut fx, mut fy) = (delta[c][0], delta[c][1]);
            for (k, u) in cl.u.iter().enumerate() {
                if u[0] == 0.0 && u[1] == 0.0 {
                    continue;
                }
                let r = turn(cs[k], *u);
                fx += r[0];
                fy += r[1];
                j(2 * c, k, -r[1]);
                j(2 * c + 1, k, r[0]);
            }
            f(2 * c, fx);
            f(2 * c + 1, fy);
        }
    }

    /// The closures as `A z = b`, z = (cos phi_1..cos phi_N, sin phi_1..sin phi_N):
    /// R(phi) u = (c u_x - s u_y, s u_x + c u_y), b = -delta.
    pub(super) fn linear_form(&self, delta: &[Xy]) -> (nalgebra::DMatrix<f64>, nalgebra::DVector<f64>) {
        let (m, n) = (2 * self.closures.len(), self.n());
        let mut a = nalgebra::DMatrix::zeros(m, 2 * n);
        let mut b = nalgebra::DVector::zeros(m);
        for (c, cl) in self.closures.iter().enumerate() {
            for (k, u) in cl.u.iter().enumerate() {
                a[(2 * c, k)] = u[0];
                a[(2 * c, n + k)] = -u[1];
                a[(2 * c + 1, k)] = u[1];
                a[(2 * c + 1, n + k)] = u[0];
            }
            b[2 * c] = -delta[c][0];
            b[2 * c + 1] = -delta[c][1];
        }
        (a, b)
    }

    /// The elbow signs of the group's joints at positions `pos`: "+" / "-" per joint.
    pub(super) fn elbow_label(&self, pos: impl Fn(usize) -> Xy) -> String {
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

    /// Rotations of the group's links from their drawn pose, read off positions.
    pub(super) fn rotations_from(&self, pos: impl Fn(usize) -> Xy) -> Vec<f64> {
        self.arms
            .iter()
            .map(|&(a, b, e)| {
                let d = sub(pos(b), pos(a));
                wrap_angle((d[1] + 0.0).atan2(d[0]) - (e[1] + 0.0).atan2(e[0]))
            })
            .collect()
    }

    /// Signed Hadamard ratio of the group's Jacobian at rotations `phi`.
    pub(super) fn conditioning_with(&self, phi: &[f64], delta: &[Xy]) -> f64 {
        dispatch!(self.n(), cond_n, self, delta, phi)
    }

    /// Number of unknowns.
    #[inline]
    pub(super) fn n(&self) -> usize {
        self.links.len()
    }

    /// Anchor differences a_plus - a_minus per closure, from the anchors' positions.
    pub(super) fn deltas(&self, anchor: impl Fn(usize) -> Xy) -> [Xy; MAX / 2] {
        let mut d = [[0.0; 2]; MAX / 2];
        for (c, cl) in self.closures.iter().enumerate() {
            d[c] = sub(anchor(self.anchors[cl.plus]), anchor(self.anchors[cl.minus]));
        }
        d
    }

    /// Newton from `guess` with the anchors' `delta`; the tangent dphi/dtheta from the
    /// anchors' velocity differences `ddelta` when given.
    pub(super) fn solve(&self, delta: &[Xy], ddelta: Option<&[Xy]>, guess: &[f64], opts: &NewtonOptions) -> GroupSolve {
        dispatch!(self.n(), solve_n, self, delta, ddelta, guess, opts)
    }

    /// Positions of the nodes from the anchors' positions and the rotations.
    pub(super) fn place(&self, phi: &[f64], anchors: &[Xy], mut put: impl FnMut(usize, Xy)) {
        let cs: Vec<Xy> = phi.iter().map(|a| cs_of(*a)).collect();
        let na = self.anchors.len();
        let mut pos: Vec<Xy> = anchors.to_vec();
        for nd in &self.nodes {
            let r = turn(cs[nd.link], nd.v);
            let b = pos[nd.base];
            let p = [b[0] + r[0], b[1] + r[1]];
            pos.push(p);
            put(nd.point, p);
        }
        debug_assert_eq!(pos.len(), na + self.nodes.len());
    }

    /// d2phi / dtheta2 at rotations `phi` with rates `dphi`, from the anchors' second
    /// derivatives `dd2` (a_plus'' - a_minus'' per closure): differentiating each closure
    /// twice, J phi'' = -dd2 + sum_j R(phi_j) u_cj phi_j'^2. `None` where J is singular.
    pub(super) fn second(&self, phi: &[f64], dphi: &[f64], dd2: &[Xy]) -> Option<[f64; MAX]> {
        dispatch!(self.n(), second_n, self, phi, dphi, dd2)
    }

    /// Accelerations of the nodes (per unit input rate squared): a node at base + R(phi) v
    /// has base'' + phi'' perp(R v) - phi'^2 R v.
    pub(super) fn place_acceleration(
        &self,
        dphi: &[f64],
        ddphi: &[f64],
        pos: impl Fn(usize) -> Xy,
        anchor_acc: &[Xy],
        mut put: impl FnMut(usize, Xy),
    ) {
        let mut acc: Vec<Xy> = anchor_acc.to_vec();
        let na = self.anchors.len();
        let point_of = |g: usize| if g < na { self.anchors[g] } else { self.nodes[g - na].point };
        for nd in &self.nodes {
            let r = sub(pos(nd.point), pos(point_of(nd.base)));
            let (w, dw) = (dphi[nd.link], ddphi[nd.link]);
            let ab = acc[nd.base];
            let a = [ab[0] - dw * r[1] - w * w * r[0], ab[1] + dw * r[0] - w * w * r[1]];
            acc.push(a);
            put(nd.point, a);
        }
    }

    /// Velocities of the nodes (per unit input rate) from the anchors' velocities and dphi.
    pub(super) fn place_velocity(
        &self,
        dphi: &[f64],
        pos: impl Fn(usize) -> Xy,
        anchor_vel: &[Xy],
        mut put: impl FnMut(usize, Xy),
    ) {
        let mut vel: Vec<Xy> = anchor_vel.to_vec();
        let na = self.anchors.len();
        let point_of = |g: usize| if g < na { self.anchors[g] } else { self.nodes[g - na].point };
        for nd in &self.nodes {
            let r = perp(sub(pos(nd.point), pos(point_of(nd.base))));
            let vb = vel[nd.base];
            let w = dphi[nd.link];
            let v = [vb[0] + w * r[0], vb[1] + w * r[1]];
            vel.push(v);
            put(nd.point, v);
        }
    }
}

#[inline]
fn cs_of(a: f64) -> Xy {
    let (s, c) = a.sin_cos();
    [c, s]
}

/// The group's loop equations at fixed anchors, as a Newton system.
struct At<'a> {
    g: &'a Group,
    delta: &'a [Xy],
}

impl<const N: usize> System<N> for At<'_> {
    fn eval(&self, x: &SVector<f64, N>) -> (SVector<f64, N>, SMatrix<f64, N, N>) {
        let mut f = SVector::<f64, N>::zeros();
        let mut j = SMatrix::<f64, N, N>::zeros();
        self.g.closure_terms(x.as_slice(), self.delta, |r, v| f[r] = v, |r, c, v| j[(r, c)] = v);
        (f, j)
    }

    /// Coordinates are divided by the scene's scale: lengths are already dimensionless.
    fn scale(&self) -> f64 {
        1.0
    }

    fn normalize(&self, x: &mut SVector<f64, N>) {
        for v in x.iter_mut() {
            *v = wrap_angle(*v);
        }
    }
}

fn cond_n<const N: usize>(g: &Group, delta: &[Xy], phi: &[f64]) -> f64 {
    let x = SVector::<f64, N>::from_fn(|k, _| phi[k]);
    let (_, j) = System::<N>::eval(&At { g, delta }, &x);
    hadamard_ratio(&j)
}

fn second_n<const N: usize>(g: &Group, phi: &[f64], dphi: &[f64], dd2: &[Xy]) -> Option<[f64; MAX]> {
    let mut j = SMatrix::<f64, N, N>::zeros();
    let mut rhs = SVector::<f64, N>::zeros();
    for (c, cl) in g.closures.iter().enumerate() {
        let (mut rx, mut ry) = (-dd2[c][0], -dd2[c][1]);
        for (k, u) in cl.u.iter().enumerate() {
            if u[0] == 0.0 && u[1] == 0.0 {
                continue;
            }
            let r = turn(cs_of(phi[k]), *u);
            let w2 = dphi[k] * dphi[k];
            rx += r[0] * w2;
            ry += r[1] * w2;
            j[(2 * c, k)] = -r[1];
            j[(2 * c + 1, k)] = r[0];
        }
        rhs[2 * c] = rx;
        rhs[2 * c + 1] = ry;
    }
    let x = newton::eliminate(j, rhs, &mut 1.0)?;
    let mut out = [f64::NAN; MAX];
    out[..N].copy_from_slice(x.as_slice());
    Some(out)
}

fn solve_n<const N: usize>(
    g: &Group,
    delta: &[Xy],
    ddelta: Option<&[Xy]>,
    guess: &[f64],
    opts: &NewtonOptions,
) -> GroupSolve {
    let sys = At { g, delta };
    let x0 = SVector::<f64, N>::from_fn(|k, _| guess[k]);
    let out = newton::solve(&sys, x0, opts, None);
    let mut phi = [f64::NAN; MAX];
    let mut dphi = [f64::NAN; MAX];
    let det = hadamard_ratio(&out.jacobian);
    if out.status == Status::Converged {
        for (p, x) in phi.iter_mut().zip(out.x.iter()) {
            *p = wrap_angle(*x);
        }
        if let Some(dd) = ddelta {
            // J dphi = -dF/dtheta, with dF/dtheta = v_plus - v_minus
            let rhs = SVector::<f64, N>::from_fn(|r, _| -dd[r / 2][r % 2]);
            if let Some(t) = newton::eliminate(out.jacobian, rhs, &mut 1.0) {
                dphi[..N].copy_from_slice(t.as_slice());
            }
        }
    }
    GroupSolve { phi, dphi, status: out.status, nit: out.nit, det }
}
