//! A rigid group: links that no closed form reaches, solved together by the generic Newton
//! solver (a triad of a Stephenson six-bar: 4 unknowns; the double butterfly's six-link
//! group: 6), slots and prismatic pairs among them included.
//!
//! Unknowns (columns) are the rotations of the group's links from their drawn pose (links
//! joined by a prismatic pair turn together: one rotation) and the displacements of its
//! slots and prismatic pairs from the drawn pose. Joints are reached from the known points
//! (anchors) through a spanning tree; each edge outside the tree closes a loop. An edge
//! from point x to point y is a [`Term`], `y - x = M (v + s d)`: M the rotation of the link
//! (or, for a link whose rotation is known, the complex ratio of two known points' current
//! difference to their drawn one), v the drawn vector, and for a sliding edge s its
//! displacement along the unit direction d. So every loop-closure equation has the form
//!
//! ```text
//! F_c = (a_plus - a_minus) + sum_terms M_t (v_t + s_t d_t) = 0,
//! ```
//!
//! linear in each link's (cos phi, sin phi) and in the displacements; without sliders it is
//! linear in (cos phi_j, sin phi_j), and the same coefficients feed the all-solutions
//! homotopy. dF/dphi_r = perp(M (v + s d)) for the terms turning with r, dF/ds = M d, and
//! at fixed unknowns dF/dtheta comes from the anchors' velocities (and those of the known
//! points a known rotation is read from).

use nalgebra::{SMatrix, SVector};

use crate::scene::input::LinearKind;
use crate::scene::model::Scene;
use crate::scene::vec2::{cdiv, cmul};
use crate::scene::vec2::{dot, perp, sub, Xy};
use crate::solve::homotopy::Quadric;
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
            n => unreachable!("group of {n} unknowns (build refuses odd sizes and more than MAX)"),
        }
    };
}

/// Most unknowns a group may have (the Newton system is sized at compile time).
pub(crate) const MAX: usize = 12;

/// How an edge turns with the linkage.
#[derive(Clone, Copy, Debug, PartialEq)]
pub(crate) enum Turn {
    /// With the unknown rotation in this column: M = (cos x_c, sin x_c).
    Col(usize),
    /// With a link whose rotation is known: M = anchor[b] - anchor[a] (group-anchor
    /// indices), the edge's vectors given as ratios to their drawn difference.
    Known(usize, usize),
}

/// An edge between two points of the group: `M (v + s d)`, s the displacement in column
/// `slide.0` (a sliding edge) or none.
#[derive(Clone, Copy, Debug, PartialEq)]
pub(crate) struct Term {
    pub turn: Turn,
    pub v: Xy,
    pub slide: Option<(usize, Xy)>,
}

impl Term {
    fn neg(self) -> Term {
        Term { v: [-self.v[0], -self.v[1]], slide: self.slide.map(|(k, d)| (k, [-d[0], -d[1]])), ..self }
    }

    /// v + s d.
    #[inline]
    fn arm(&self, x: &[f64]) -> Xy {
        match self.slide {
            Some((k, d)) => [self.v[0] + x[k] * d[0], self.v[1] + x[k] * d[1]],
            None => self.v,
        }
    }

    /// M from the columns' (cos, sin) and the anchors' values (positions, or their
    /// derivatives for a known turn's rate).
    #[inline]
    fn m(&self, cs: &[Xy], anchors: &[Xy]) -> Xy {
        match self.turn {
            Turn::Col(c) => cs[c],
            Turn::Known(a, b) => sub(anchors[b], anchors[a]),
        }
    }
}

/// A point the group solves: group point `base` (anchors first, then nodes) plus `term`.
#[derive(Clone, Debug, PartialEq)]
pub(crate) struct Node {
    pub point: usize,
    pub base: usize,
    pub term: Term,
}

/// One loop-closure pair of equations: F = a[plus] - a[minus] + sum of `terms`.
#[derive(Clone, Debug, PartialEq)]
pub(crate) struct Closure {
    pub plus: usize,
    pub minus: usize,
    pub terms: Vec<Term>,
}

/// How a column is read off positions: a rotation from two points of a link (their drawn
/// difference `drawn`), a displacement from the two ends of one of its sliding edges.
#[derive(Clone, Debug, PartialEq)]
pub(crate) enum Reader {
    Rotation { a: usize, b: usize, drawn: Xy },
    Slide { from: usize, to: usize, term: Term },
}

/// A compiled group.
#[derive(Clone, Debug, PartialEq)]
pub(crate) struct Group {
    /// Scene indices of its links (for the plan's steps).
    pub links: Vec<usize>,
    /// Rotation columns come first: columns `0..nrot` are angles, the rest displacements.
    pub nrot: usize,
    /// Scene indices of the known points it hangs from.
    pub anchors: Vec<usize>,
    /// Joints in tree order, then points carried by one group link only.
    pub nodes: Vec<Node>,
    /// How many of `nodes` are joints (the rest are carried).
    pub joints: usize,
    pub closures: Vec<Closure>,
    /// Per column, how to read it off positions.
    pub readers: Vec<Reader>,
    /// Per joint of two or more group links: (joint, a point of the first link, a point
    /// of the second). The sign of cross(a - joint, b - joint) is the joint's elbow: the
    /// assembly mode there, which changes only where the two links fall in line.
    pub elbows: Vec<(usize, usize, usize)>,
    /// Sign of the signed conditioning at the drawn pose: the branch to follow.
    pub sign: f64,
    /// The column of the input (a group of the whole linkage, as tracing builds it).
    pub input: Option<usize>,
}

/// What one Newton solve of a group gives.
#[derive(Clone, Copy, Debug)]
pub(crate) struct GroupSolve {
    /// The unknowns: rotations (radians, wrapped) then displacements (solving frame).
    pub phi: [f64; MAX],
    /// d phi / d theta (NaN unless converged and anchor velocities were given).
    pub dphi: [f64; MAX],
    pub status: Status,
    pub nit: u32,
    /// Signed Hadamard ratio of the Jacobian at the solution.
    pub det: f64,
    /// (cos, sin) of the rotations in `phi` (when converged with anchor velocities given):
    /// computed once for the rates and the placement.
    pub cs: [Xy; MAX],
}

/// Union-find root.
fn root(parent: &mut [usize], mut l: usize) -> usize {
    while parent[l] != l {
        parent[l] = parent[parent[l]];
        l = parent[l];
    }
    l
}

impl Group {
    /// The group of `links` over the known points, rigid (no unknown left free), with its
    /// slots and prismatic pairs; `None` when they are not one connected rigid group over
    /// the known points, when it has more than [`MAX`] unknowns, or when it is singular as
    /// drawn. A linear input's joint is not part of it (its displacement is the input).
    pub(crate) fn build(sc: &Scene, links: &[usize], known: &[bool]) -> Option<Group> {
        let mut g = Self::tree(sc, links, known, false)?;
        let n = g.n();
        if n == 0 || n > MAX || n % 2 == 1 {
            return None;
        }
        let anchors: Vec<Xy> = g.anchors.iter().map(|&p| sc.xy[p]).collect();
        let det = g.conditioning_with(&[0.0; MAX][..n], &anchors);
        if !(det.abs() >= newton::SINGULAR_THRESHOLD) {
            return None;
        }
        g.sign = det.signum();
        Some(g)
    }

    /// The joints of a set of links: the slots and prismatic pairs that act on it (and the
    /// linear input's joint only for a whole-linkage `chain`).
    fn joints_of(sc: &Scene, inset: &[bool], known: &[bool], chain: bool) -> (Vec<usize>, Vec<usize>) {
        let all_known = |l: usize| sc.links[l].points.iter().all(|&p| known[p]);
        let is_input = |k: LinearKind, i: usize| sc.linear.is_some_and(|l| l.kind == k && l.index == i);
        let slots = (0..sc.slots.len())
            .filter(|&i| {
                let s = &sc.slots[i];
                let p_ok = known[s.point] || sc.point_links[s.point].iter().any(|&l| inset[l]);
                let g_ok = inset[s.guide] || all_known(s.guide);
                p_ok && g_ok && (inset[s.guide] || !known[s.point]) && (chain || !is_input(LinearKind::Slot, i))
            })
            .collect();
        let prismatic = (0..sc.prismatic.len())
            .filter(|&i| {
                let p = &sc.prismatic[i];
                let ok = |l: usize| inset[l] || all_known(l);
                ok(p.link)
                    && ok(p.guide)
                    && (inset[p.link] || inset[p.guide])
                    && (chain || !is_input(LinearKind::Prismatic, i))
            })
            .collect();
        (slots, prismatic)
    }

    /// Constraints minus freedoms of a set of links over the known points (Gruebler's count
    /// with its slots and prismatic pairs): 0 for a rigid group.
    pub(crate) fn freedom(sc: &Scene, links: &[usize], known: &[bool]) -> i64 {
        let mut inset = vec![false; sc.links.len()];
        for &l in links {
            inset[l] = true;
        }
        let mut m = std::collections::HashMap::<usize, i64>::new();
        for &l in links {
            for &p in &sc.links[l].points {
                *m.entry(p).or_default() += 1;
            }
        }
        let c: i64 = m.iter().map(|(&p, &k)| if known[p] { 2 * k } else { 2 * (k - 1) }).sum();
        let (slots, prismatic) = Self::joints_of(sc, &inset, known, false);
        3 * links.len() as i64 - c - slots.len() as i64 - 2 * prismatic.len() as i64
    }

    /// The spanning tree and closures of `links` over the known points, with the slots and
    /// prismatic pairs acting on them. A `chain` (the whole linkage over the ground, as
    /// tracing uses it) leaves one unknown free, the input (its link's rotation, or the
    /// linear input's displacement); otherwise the group must be rigid. Any size: the caller
    /// checks what it needs.
    pub(crate) fn tree(sc: &Scene, links: &[usize], known: &[bool], chain: bool) -> Option<Group> {
        let xy = &sc.xy;
        let nl = sc.links.len();
        let mut inset = vec![false; nl];
        for &l in links {
            inset[l] = true;
        }
        let all_known = |l: usize| sc.links[l].points.iter().all(|&p| known[p]);
        let (slots, prismatic) = Self::joints_of(sc, &inset, known, chain);

        // rotation classes: links joined by a prismatic pair turn together
        let mut parent: Vec<usize> = (0..nl).collect();
        for &i in &prismatic {
            let (a, b) = (root(&mut parent, sc.prismatic[i].link), root(&mut parent, sc.prismatic[i].guide));
            parent[a] = b;
        }
        // a class is known when one of its links is (its two farthest points carry it)
        let mut carrier: Vec<Option<(usize, usize)>> = vec![None; nl];
        for l in (0..nl).filter(|&l| all_known(l) && sc.links[l].points.len() >= 2) {
            let r = root(&mut parent, l);
            if carrier[r].is_none() {
                let pts = &sc.links[l].points;
                let mut best = (pts[0], pts[1], -1.0);
                for (i, &a) in pts.iter().enumerate() {
                    for &b in &pts[i + 1..] {
                        let d = sub(xy[b], xy[a]);
                        if dot(d, d) > best.2 {
                            best = (a, b, dot(d, d));
                        }
                    }
                }
                carrier[r] = Some((best.0, best.1));
            }
        }
        // columns: unknown rotation classes in the order their links come, then slides
        let mut col_of_class: Vec<Option<usize>> = vec![None; nl];
        let mut readers = Vec::new();
        for &l in links {
            let r = root(&mut parent, l);
            if carrier[r].is_none() && col_of_class[r].is_none() {
                col_of_class[r] = Some(readers.len());
                let pts = &sc.links[l].points;
                let (a, b) = (pts[0], *pts.get(1)?);
                readers.push(Reader::Rotation { a, b, drawn: sub(xy[b], xy[a]) });
            }
        }
        let nrot = readers.len();

        // anchors: the known points the edges start from or read rotations off
        let mut anchors: Vec<usize> = Vec::new();
        for &l in links {
            for &p in &sc.links[l].points {
                if known[p] {
                    anchor_index(&mut anchors, p);
                }
            }
        }
        // the turn of a link's class, and the factor that gives a drawn vector for it
        let turn_of = |l: usize, parent: &mut [usize], anchors: &mut Vec<usize>| -> (Turn, Xy) {
            let r = root(parent, l);
            match (col_of_class[r], carrier[r]) {
                (Some(c), _) => (Turn::Col(c), [1.0, 0.0]),
                (None, Some((a, b))) => {
                    let h = sub(xy[b], xy[a]);
                    (Turn::Known(anchor_index(anchors, a), anchor_index(anchors, b)), cdiv([1.0, 0.0], h))
                }
                (None, None) => unreachable!("every class has a column or a carrier"),
            }
        };

        // incidences: links in the set, then sliding edges
        let mut count = vec![0usize; sc.names.len()];
        for &l in links {
            for &p in &sc.links[l].points {
                count[p] += 1;
            }
        }
        let slot_points: Vec<usize> = slots.iter().map(|&i| sc.slots[i].point).collect();
        // a link's star centre: its first joint
        let centres: Vec<usize> = (0..nl)
            .map(|l| {
                let pts = &sc.links[l].points;
                pts.iter().copied().find(|&p| known[p] || count[p] >= 2 || slot_points.contains(&p)).unwrap_or(pts[0])
            })
            .collect();
        let mut edges: Vec<(usize, usize, Term)> = Vec::new();
        let mut slide_cols = Vec::new();
        let mut input = None;
        for &i in &slots {
            let s = &sc.slots[i];
            let (a, b) = s.line;
            let (turn, unit) = turn_of(s.guide, &mut parent, &mut anchors);
            let d = unit_dir(xy, a, b);
            let k = nrot + slide_cols.len();
            slide_cols.push(k);
            let term = Term { turn, v: cmul(unit, sub(xy[s.point], xy[a])), slide: Some((k, cmul(unit, d))) };
            if sc.linear.is_some_and(|l| l.kind == LinearKind::Slot && l.index == i) {
                input = Some(k);
            }
            if known[a] {
                anchor_index(&mut anchors, a);
            }
            readers.push(Reader::Slide { from: a, to: s.point, term });
            edges.push((a, s.point, term));
        }
        for &i in &prismatic {
            let pr = &sc.prismatic[i];
            let (a, b) = pr.line;
            let (turn, unit) = turn_of(pr.guide, &mut parent, &mut anchors);
            let d = unit_dir(xy, a, b);
            let c = centres[pr.link];
            let k = nrot + slide_cols.len();
            slide_cols.push(k);
            let term = Term { turn, v: cmul(unit, sub(xy[c], xy[a])), slide: Some((k, cmul(unit, d))) };
            if sc.linear.is_some_and(|l| l.kind == LinearKind::Prismatic && l.index == i) {
                input = Some(k);
            }
            for p in [a, c] {
                if known[p] {
                    anchor_index(&mut anchors, p);
                }
            }
            readers.push(Reader::Slide { from: a, to: c, term });
            edges.push((a, c, term));
        }
        for &(a, c, _) in &edges {
            count[a] += 1;
            count[c] += 1;
        }
        let is_joint = |p: usize| known[p] || count[p] >= 2;
        let mut leaves: Vec<(usize, usize, Term)> = Vec::new();
        for &l in links {
            let c = centres[l];
            let (turn, unit) = turn_of(l, &mut parent, &mut anchors);
            for &y in sc.links[l].points.iter().filter(|&&y| y != c) {
                let e = (c, y, Term { turn, v: cmul(unit, sub(xy[y], xy[c])), slide: None });
                if is_joint(y) {
                    edges.push(e);
                } else {
                    leaves.push(e);
                }
            }
        }
        if chain && input.is_none() {
            let pv = sc.input?;
            input = match turn_of(pv.link, &mut parent, &mut anchors).0 {
                Turn::Col(c) => Some(c),
                Turn::Known(..) => return None,
            };
        }

        // breadth-first from the anchors; paths hold the terms from a point's anchor
        let na = anchors.len();
        let mut gp = std::collections::HashMap::<usize, usize>::new();
        for (i, &a) in anchors.iter().enumerate() {
            gp.insert(a, i);
        }
        let mut rootp: Vec<usize> = (0..na).collect();
        let mut path: Vec<Vec<Term>> = vec![Vec::new(); na];
        let mut nodes = Vec::new();
        let mut used = vec![false; edges.len()];
        let mut closures = Vec::new();
        let mut queue: std::collections::VecDeque<usize> = anchors.iter().copied().collect();
        while let Some(x) = queue.pop_front() {
            let gx = gp[&x];
            for (e, &(from, to, term)) in edges.iter().enumerate() {
                if used[e] || (from != x && to != x) {
                    continue;
                }
                used[e] = true;
                let (y, t) = if from == x { (to, term) } else { (from, term.neg()) };
                match gp.get(&y) {
                    Some(&gy) => {
                        // closure: anchor(x) + path(x) + t - anchor(y) - path(y) = 0
                        let mut terms = path[gx].clone();
                        terms.push(t);
                        terms.extend(path[gy].iter().map(|t| t.neg()));
                        closures.push(Closure { plus: rootp[gx], minus: rootp[gy], terms: merged(terms) });
                    }
                    None => {
                        let gy = na + nodes.len();
                        gp.insert(y, gy);
                        nodes.push(Node { point: y, base: gx, term: t });
                        rootp.push(rootp[gx]);
                        let mut p = path[gx].clone();
                        p.push(t);
                        path.push(p);
                        queue.push_back(y);
                    }
                }
            }
        }
        if used.contains(&false) {
            return None; // a part not connected to the known points
        }
        let joints = nodes.len();
        for (c, y, t) in leaves {
            let &gc = gp.get(&c)?;
            nodes.push(Node { point: y, base: gc, term: t });
        }
        let ncols = nrot + slide_cols.len();
        if 2 * closures.len() + usize::from(chain) != ncols {
            return None;
        }
        let mut elbows = Vec::new();
        for nd in &nodes[..joints] {
            let on: Vec<usize> =
                links.iter().copied().filter(|&l| sc.links[l].points.contains(&nd.point)).take(2).collect();
            if let [l1, l2] = on[..] {
                let other = |l: usize| sc.links[l].points.iter().copied().find(|&q| q != nd.point);
                if let (Some(a), Some(b)) = (other(l1), other(l2)) {
                    elbows.push((nd.point, a, b));
                }
            }
        }
        // the readers of displacements use anchor indices for known turns: keep them valid
        Some(Group {
            links: links.to_vec(),
            nrot,
            anchors,
            nodes,
            joints,
            closures,
            readers,
            elbows,
            sign: 0.0,
            input: if chain { input } else { None },
        })
    }

    /// Whether column `k` is an angle (else a displacement).
    #[inline]
    pub(crate) fn is_angle(&self, k: usize) -> bool {
        k < self.nrot
    }

    /// `a - b` for column `k`: wrapped to (-pi, pi] for an angle.
    #[inline]
    pub(crate) fn gap(&self, k: usize, a: f64, b: f64) -> f64 {
        if self.is_angle(k) {
            wrap_angle(a - b)
        } else {
            a - b
        }
    }

    /// Whether the group has sliders or known turns (then it has no homotopy form).
    pub(crate) fn has_slides(&self) -> bool {
        self.n() > self.nrot || self.closures.iter().any(|c| c.terms.iter().any(|t| matches!(t.turn, Turn::Known(..))))
    }

    /// (cos, sin) of the rotation columns, all at once (4 at a time where the SIMD kernels
    /// are on: see [`cs_of`]).
    #[inline]
    fn turns(&self, x: &[f64], buf: &mut [Xy; MAX]) -> usize {
        let n = self.nrot.min(MAX);
        let mut sc = [(0.0, 0.0); MAX];
        crate::simd::sin_cos_block(&x[..n], &mut sc[..n]);
        for (b, (s, c)) in buf.iter_mut().zip(&sc[..n]) {
            *b = [*c, *s];
        }
        n
    }

    /// Residuals and Jacobian of the closures at unknowns `x` with the anchors at
    /// `anchors`: `f(row, value)` sets a residual, `j(row, column, value)` adds to an entry.
    pub(crate) fn closure_terms(
        &self,
        x: &[f64],
        anchors: &[Xy],
        f: impl FnMut(usize, f64),
        j: impl FnMut(usize, usize, f64),
    ) {
        let mut buf = [[0.0; 2]; MAX];
        let heap: Vec<Xy>;
        let cs: &[Xy] = if self.nrot <= buf.len() {
            let n = self.turns(x, &mut buf);
            &buf[..n]
        } else {
            heap = x[..self.nrot].iter().map(|a| cs_of(*a)).collect();
            &heap
        };
        self.closure_terms_with(x, cs, anchors, f, j);
    }

    /// [`Group::closure_terms`] with the rotations' (cos, sin) `cs` given.
    fn closure_terms_with(
        &self,
        x: &[f64],
        cs: &[Xy],
        anchors: &[Xy],
        mut f: impl FnMut(usize, f64),
        mut j: impl FnMut(usize, usize, f64),
    ) {
        for (c, cl) in self.closures.iter().enumerate() {
            let d = sub(anchors[cl.plus], anchors[cl.minus]);
            let (mut fx, mut fy) = (d[0], d[1]);
            for t in &cl.terms {
                let m = t.m(cs, anchors);
                let r = cmul(m, t.arm(x));
                fx += r[0];
                fy += r[1];
                if let Turn::Col(k) = t.turn {
                    j(2 * c, k, -r[1]);
                    j(2 * c + 1, k, r[0]);
                }
                if let Some((k, dv)) = t.slide {
                    let md = cmul(m, dv);
                    j(2 * c, k, md[0]);
                    j(2 * c + 1, k, md[1]);
                }
            }
            f(2 * c, fx);
            f(2 * c + 1, fy);
        }
    }

    /// dF/dtheta at fixed unknowns, per closure: the anchors' rates `anchor_d` (and those of
    /// the known turns read from them).
    fn rate_terms(&self, x: &[f64], anchor_d: &[Xy]) -> [Xy; MAX] {
        let mut out = [[0.0; 2]; MAX];
        for (c, cl) in self.closures.iter().enumerate().take(MAX) {
            let mut r = sub(anchor_d[cl.plus], anchor_d[cl.minus]);
            for t in &cl.terms {
                if let Turn::Known(a, b) = t.turn {
                    let w = cmul(sub(anchor_d[b], anchor_d[a]), t.arm(x));
                    r = [r[0] + w[0], r[1] + w[1]];
                }
            }
            out[c] = r;
        }
        out
    }

    /// The closures as `A z = b`, z = (cos phi_1..cos phi_N, sin phi_1..sin phi_N):
    /// M v = (c v_x - s v_y, s v_x + c v_y), b = -(a_plus - a_minus); `None` for a group
    /// with slides or known turns (no such form).
    pub(crate) fn linear_form(&self, anchors: &[Xy]) -> Option<(nalgebra::DMatrix<f64>, nalgebra::DVector<f64>)> {
        if self.has_slides() {
            return None;
        }
        let (m, n) = (2 * self.closures.len(), self.n());
        let mut a = nalgebra::DMatrix::zeros(m, 2 * n);
        let mut b = nalgebra::DVector::zeros(m);
        for (c, cl) in self.closures.iter().enumerate() {
            for t in &cl.terms {
                let Turn::Col(k) = t.turn else { return None };
                let u = t.v;
                a[(2 * c, k)] += u[0];
                a[(2 * c, n + k)] -= u[1];
                a[(2 * c + 1, k)] += u[1];
                a[(2 * c + 1, n + k)] += u[0];
            }
            let d = sub(anchors[cl.plus], anchors[cl.minus]);
            b[2 * c] = -d[0];
            b[2 * c + 1] = -d[1];
        }
        Some((a, b))
    }

    /// The closures of a group with sliders as `A z = b` with quadrics, for the homotopy:
    /// z holds each rotation column's (cos, sin) (cosines first, as in
    /// [`Group::linear_form`]), then per displacement column either (s cos, s sin) of its
    /// guide's unknown rotation, parallel to that (cos, sin) (a bilinear quadric), or s
    /// itself where its guide's rotation is known.
    pub(crate) fn homotopy_form(
        &self,
        anchors: &[Xy],
    ) -> (nalgebra::DMatrix<f64>, nalgebra::DVector<f64>, Vec<Quadric>) {
        let (nr, n) = (self.nrot, self.n());
        // where each slide column's variables start, and its guide's rotation column
        let mut at = vec![0usize; n];
        let mut next = 2 * nr;
        let mut quads: Vec<Quadric> = (0..nr).map(|r| Quadric::Circle { c: r, s: nr + r }).collect();
        for (k, r) in self.readers.iter().enumerate().skip(nr) {
            let Reader::Slide { term, .. } = r else { unreachable!("columns after the rotations slide") };
            at[k] = next;
            match term.turn {
                Turn::Col(g) => {
                    // (e, f) = s (c, s_g): e s_g = f c
                    quads.push(Quadric::Bilinear { a: next, b: nr + g, c: next + 1, d: g });
                    next += 2;
                }
                Turn::Known(..) => next += 1,
            }
        }
        let m = 2 * self.closures.len();
        let mut a = nalgebra::DMatrix::zeros(m, next);
        let mut b = nalgebra::DVector::zeros(m);
        for (c, cl) in self.closures.iter().enumerate() {
            let mut rhs = sub(anchors[cl.plus], anchors[cl.minus]);
            let (rx, ry) = (2 * c, 2 * c + 1);
            for t in &cl.terms {
                match t.turn {
                    Turn::Col(g) => {
                        let v = t.v;
                        a[(rx, g)] += v[0];
                        a[(rx, nr + g)] -= v[1];
                        a[(ry, g)] += v[1];
                        a[(ry, nr + g)] += v[0];
                        if let Some((k, d)) = t.slide {
                            let (e, f) = (at[k], at[k] + 1);
                            a[(rx, e)] += d[0];
                            a[(rx, f)] -= d[1];
                            a[(ry, e)] += d[1];
                            a[(ry, f)] += d[0];
                        }
                    }
                    Turn::Known(ia, ib) => {
                        let mm = sub(anchors[ib], anchors[ia]);
                        let w = cmul(mm, t.v);
                        rhs = [rhs[0] + w[0], rhs[1] + w[1]];
                        if let Some((k, d)) = t.slide {
                            let md = cmul(mm, d);
                            a[(rx, at[k])] += md[0];
                            a[(ry, at[k])] += md[1];
                        }
                    }
                }
            }
            b[rx] = -rhs[0];
            b[ry] = -rhs[1];
        }
        (a, b, quads)
    }

    /// The unknowns (real parts) from a root `z` of [`Group::homotopy_form`].
    pub(crate) fn unknowns_of_root(&self, z: &[nalgebra::Complex<f64>]) -> Vec<f64> {
        let nr = self.nrot;
        let mut x: Vec<f64> = (0..nr).map(|r| z[nr + r].re.atan2(z[r].re)).collect();
        let mut next = 2 * nr;
        for r in self.readers.iter().skip(nr) {
            let Reader::Slide { term, .. } = r else { unreachable!("columns after the rotations slide") };
            match term.turn {
                Turn::Col(g) => {
                    // s = (s cos, s sin) . (cos, sin)
                    let (sin, cos) = x[g].sin_cos();
                    x.push(z[next].re * cos + z[next + 1].re * sin);
                    next += 2;
                }
                Turn::Known(..) => {
                    x.push(z[next].re);
                    next += 1;
                }
            }
        }
        x
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

    /// Signed Hadamard ratio of the group's Jacobian at unknowns `x`.
    pub(crate) fn conditioning_with(&self, x: &[f64], anchors: &[Xy]) -> f64 {
        dispatch!(self.n(), cond_n, self, anchors, x)
    }

    /// Number of unknowns.
    #[inline]
    pub(crate) fn n(&self) -> usize {
        self.readers.len()
    }

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

    /// Visits each node with its term's multiplier and arm.
    fn each_node(&self, x: &[f64], anchors: &[Xy], mut visit: impl FnMut(usize, &Node, Xy, Xy)) {
        let cs: Vec<Xy> = x[..self.nrot].iter().map(|a| cs_of(*a)).collect();
        for (i, nd) in self.nodes.iter().enumerate() {
            visit(i, nd, nd.term.m(&cs, anchors), nd.term.arm(x));
        }
    }

    /// Positions of the nodes from the anchors' positions and the unknowns.
    pub(crate) fn place(&self, x: &[f64], anchors: &[Xy], mut put: impl FnMut(usize, Xy)) {
        let mut pos: Vec<Xy> = anchors.to_vec();
        self.each_node(x, anchors, |_, nd, m, arm| {
            let r = cmul(m, arm);
            let b = pos[nd.base];
            let p = [b[0] + r[0], b[1] + r[1]];
            pos.push(p);
            put(nd.point, p);
        });
    }

    /// d2x / dtheta2 at unknowns `x` with rates `dx`, from the anchors' positions, velocities
    /// and accelerations: differentiating each closure twice,
    /// J x'' = -(a_plus'' - a_minus'') - sum over terms of the rest of (M (v + s d))''.
    /// `None` where J is singular.
    pub(crate) fn second(&self, x: &[f64], dx: &[f64], k: [&[Xy]; 3]) -> Option<[f64; MAX]> {
        dispatch!(self.n(), second_n, self, x, dx, k)
    }

    /// The second derivative of a term without its x'' part: for a rotation column c
    /// (rate w) -w^2 M arm + 2 w s' perp(M d); for a known turn M'' arm + 2 M' s' d.
    #[inline]
    fn term_curvature(t: &Term, cs: &[Xy], dx: &[f64], x: &[f64], k: [&[Xy]; 3]) -> Xy {
        let arm = t.arm(x);
        let sd = t.slide.map_or([0.0; 2], |(s, d)| [dx[s] * d[0], dx[s] * d[1]]);
        match t.turn {
            Turn::Col(c) => {
                let w = dx[c];
                let r = cmul(cs[c], arm);
                let q = perp(cmul(cs[c], sd));
                [-w * w * r[0] + 2.0 * w * q[0], -w * w * r[1] + 2.0 * w * q[1]]
            }
            Turn::Known(a, b) => {
                let (mv, ma) = (sub(k[1][b], k[1][a]), sub(k[2][b], k[2][a]));
                let (u, v) = (cmul(ma, arm), cmul(mv, sd));
                [u[0] + 2.0 * v[0], u[1] + 2.0 * v[1]]
            }
        }
    }

    /// The rate of a term with the unknowns' rates `dx`: perp(M arm) w + M s' d for a
    /// rotation column, M' arm + M s' d for a known turn.
    #[inline]
    fn term_rate(t: &Term, m: Xy, arm: Xy, dx: &[f64], anchor_vel: &[Xy]) -> Xy {
        let sd = t.slide.map_or([0.0; 2], |(s, d)| cmul(m, [dx[s] * d[0], dx[s] * d[1]]));
        let turn = match t.turn {
            Turn::Col(c) => {
                let r = perp(cmul(m, arm));
                [dx[c] * r[0], dx[c] * r[1]]
            }
            Turn::Known(a, b) => cmul(sub(anchor_vel[b], anchor_vel[a]), arm),
        };
        [turn[0] + sd[0], turn[1] + sd[1]]
    }

    /// Positions (as [`Group::place`] gives them, bit for bit) and velocities (per unit
    /// input rate, from the anchors' velocities and the unknowns' rates `dx`) of the nodes
    /// in one pass, from the rotations' (cos, sin) `cs` (those of [`GroupSolve::cs`]), with
    /// no allocation for a group of up to 32 points (a sweep's every solved angle).
    pub(crate) fn place_moving(
        &self,
        x: &[f64],
        dx: &[f64],
        cs: &[Xy],
        anchors: &[Xy],
        anchor_vel: &[Xy],
        mut put: impl FnMut(usize, Xy, Xy),
    ) {
        const SMALL: usize = 32;
        let total = anchors.len() + self.nodes.len();
        let (mut pbuf, mut vbuf) = ([[0.0; 2]; SMALL], [[0.0; 2]; SMALL]);
        let mut heap: (Vec<Xy>, Vec<Xy>);
        let (pos, vel): (&mut [Xy], &mut [Xy]) = if total <= SMALL {
            (&mut pbuf[..total], &mut vbuf[..total])
        } else {
            heap = (vec![[0.0; 2]; total], vec![[0.0; 2]; total]);
            (&mut heap.0, &mut heap.1)
        };
        pos[..anchors.len()].copy_from_slice(anchors);
        vel[..anchors.len()].copy_from_slice(anchor_vel);
        for (k, nd) in (anchors.len()..).zip(&self.nodes) {
            let (m, arm) = (nd.term.m(&cs[..self.nrot], anchors), nd.term.arm(x));
            let r = cmul(m, arm);
            let (b, vb) = (pos[nd.base], vel[nd.base]);
            pos[k] = [b[0] + r[0], b[1] + r[1]];
            let w = Self::term_rate(&nd.term, m, arm, dx, anchor_vel);
            vel[k] = [vb[0] + w[0], vb[1] + w[1]];
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
        let mut acc: Vec<Xy> = k[2].to_vec();
        let still = vec![[0.0; 2]; k[0].len()];
        for nd in &self.nodes {
            let t = &nd.term;
            let m = t.m(&cs, k[0]);
            // the x'' part: w' perp(M arm) + M s'' d
            let lin = Self::term_rate(t, m, t.arm(x), ddx, &still);
            let rest = Self::term_curvature(t, &cs, dx, x, k);
            let ab = acc[nd.base];
            let a = [ab[0] + lin[0] + rest[0], ab[1] + lin[1] + rest[1]];
            acc.push(a);
            put(nd.point, a);
        }
    }
}

/// Index of scene point `p` among the anchors, adding it if new.
fn anchor_index(anchors: &mut Vec<usize>, p: usize) -> usize {
    match anchors.iter().position(|&q| q == p) {
        Some(i) => i,
        None => {
            anchors.push(p);
            anchors.len() - 1
        }
    }
}

/// The unit vector along b - a (solving frame).
fn unit_dir(xy: &[Xy], a: usize, b: usize) -> Xy {
    let d = sub(xy[b], xy[a]);
    let n = dot(d, d).sqrt();
    [d[0] / n, d[1] / n]
}

/// Terms turning with one rotation column and not sliding are summed into one (the loop
/// equations' coefficient of that link): fewer terms per evaluation.
fn merged(terms: Vec<Term>) -> Vec<Term> {
    let mut out: Vec<Term> = Vec::with_capacity(terms.len());
    for t in terms {
        if t.slide.is_none() {
            if let Some(o) = out.iter_mut().find(|o| o.slide.is_none() && o.turn == t.turn) {
                o.v = [o.v[0] + t.v[0], o.v[1] + t.v[1]];
                continue;
            }
        }
        out.push(t);
    }
    out.retain(|t| t.slide.is_some() || t.v != [0.0; 2]);
    out
}

/// (cos, sin) of a rotation: the polynomial within 2 ulp of libm where the SIMD kernels
/// are on ([`crate::simd::sin_cos`]; about a third of libm's cost, and a group's
/// evaluations take a dozen a step), libm otherwise.
#[inline]
fn cs_of(a: f64) -> Xy {
    let (s, c) = crate::simd::sin_cos(a);
    [c, s]
}

/// The group's loop equations at fixed anchors, as a Newton system.
struct At<'a> {
    g: &'a Group,
    anchors: &'a [Xy],
}

impl<const N: usize> System<N> for At<'_> {
    fn eval(&self, x: &SVector<f64, N>) -> (SVector<f64, N>, SMatrix<f64, N, N>) {
        let mut f = SVector::<f64, N>::zeros();
        let mut j = SMatrix::<f64, N, N>::zeros();
        self.g.closure_terms(x.as_slice(), self.anchors, |r, v| f[r] = v, |r, c, v| j[(r, c)] += v);
        (f, j)
    }

    /// Coordinates are divided by the scene's scale: lengths are already dimensionless.
    fn scale(&self) -> f64 {
        1.0
    }

    fn conditioned_step(&self, j: &SMatrix<f64, N, N>, f: &SVector<f64, N>) -> (f64, Option<SVector<f64, N>>) {
        newton::hadamard_step(j, f)
    }

    fn normalize(&self, x: &mut SVector<f64, N>) {
        for v in x.iter_mut().take(self.g.nrot) {
            *v = wrap_angle(*v);
        }
    }
}

fn cond_n<const N: usize>(g: &Group, anchors: &[Xy], x: &[f64]) -> f64 {
    let x = SVector::<f64, N>::from_fn(|k, _| x[k]);
    let (_, j) = System::<N>::eval(&At { g, anchors }, &x);
    hadamard_ratio(&j)
}

fn second_n<const N: usize>(g: &Group, x: &[f64], dx: &[f64], k: [&[Xy]; 3]) -> Option<[f64; MAX]> {
    let xs = SVector::<f64, N>::from_fn(|i, _| x[i]);
    let (_, j) = System::<N>::eval(&At { g, anchors: k[0] }, &xs);
    let cs: Vec<Xy> = x[..g.nrot].iter().map(|a| cs_of(*a)).collect();
    let mut rhs = SVector::<f64, N>::zeros();
    for (c, cl) in g.closures.iter().enumerate() {
        let mut r = sub(k[2][cl.plus], k[2][cl.minus]);
        for t in &cl.terms {
            let q = Group::term_curvature(t, &cs, dx, x, k);
            r = [r[0] + q[0], r[1] + q[1]];
        }
        rhs[2 * c] = -r[0];
        rhs[2 * c + 1] = -r[1];
    }
    let x = newton::eliminate(j, rhs, &mut 1.0)?;
    let mut out = [f64::NAN; MAX];
    out[..N].copy_from_slice(x.as_slice());
    Some(out)
}

fn solve_n<const N: usize>(
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
            let mut jacobian = SMatrix::<f64, N, N>::zeros();
            g.closure_terms_with(&phi[..N], &cs[..g.nrot], anchors, |_, _| {}, |r, c, v| jacobian[(r, c)] += v);
            let d = g.rate_terms(&phi[..N], vel);
            let rhs = SVector::<f64, N>::from_fn(|r, _| -d[r / 2][r % 2]);
            if let Some(t) = newton::eliminate(jacobian, rhs, &mut 1.0) {
                dphi[..N].copy_from_slice(t.as_slice());
            }
        }
    }
    GroupSolve { phi, dphi, status: out.status, nit: out.nit, det, cs }
}
