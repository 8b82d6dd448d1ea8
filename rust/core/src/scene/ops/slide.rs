//! Prismatic joints: slots (a point kept on a line of a guide link) and prismatic pairs (a
//! link translating along a line of its guide), and the closed forms the plan peels for
//! them, with their signed, scale-free conditioning:
//!
//! - [`Rrp`]: a point at a distance from a known point and on a known line (circle-line);
//!   conditioning the cosine of the angle between the line and the link reaching the point
//!   (0 where the circle touches the line: a dead point);
//! - [`LineLine`]: a point on two known lines; conditioning the sine between them;
//! - [`Rpr`]: a guide turning about a known point whose line passes through a known point;
//!   conditioning the signed distance along the line from the foot of the guide's pivot to
//!   the point (solving frame: a fraction of the scene's scale). It falls to 0 where the
//!   line touches the circle the point keeps about the pivot (a dead point) and, for a slot
//!   through the pivot, changes sign as the point passes through the pivot: the guide then
//!   turns on smoothly with the point behind the pivot, its side carried like a dyad's
//!   through a change point.
//!
//! A line is known when two points fix it: it passes through `base + m_off (b - a)` with
//! direction `m_dir (b - a)` (complex products), so it turns and moves with the link that
//! carries `a` and `b`. Every solve here also gives first and second derivatives by the
//! input, from those of the known points.

use crate::scene::vec2::{cdiv, cmul, cross, dot, perp, solve2, sub, unit, Xy};

/// A line fixed by known points: through `base + m_off (b - a)`, along `m_dir (b - a)`.
#[derive(Clone, Copy, Debug, PartialEq)]
pub(crate) struct Line {
    pub base: usize,
    pub a: usize,
    pub b: usize,
    pub m_off: Xy,
    pub m_dir: Xy,
}

/// A line's point and direction with their first and second derivatives.
#[derive(Clone, Copy, Debug)]
pub(crate) struct LineAt {
    pub p: [Xy; 3],
    pub d: [Xy; 3],
}

impl Line {
    /// The points it reads.
    pub(crate) fn inputs(&self) -> [usize; 3] {
        [self.base, self.a, self.b]
    }

    /// Its point and (unit-length as drawn) direction from the known points' positions,
    /// velocities and accelerations (`k[0]`, `k[1]`, `k[2]`, indexed by point).
    pub(crate) fn at(&self, k: [&[Xy]; 3]) -> LineAt {
        let mut p = [[0.0; 2]; 3];
        let mut d = [[0.0; 2]; 3];
        for o in 0..3 {
            (p[o], d[o]) = self.place(k[o][self.base], k[o][self.a], k[o][self.b]);
        }
        LineAt { p, d }
    }

    /// Its point and direction from the positions of `base`, `a` and `b` (linear in them:
    /// the same map gives their derivatives from the points' derivatives).
    #[inline]
    pub(crate) fn place(&self, base: Xy, a: Xy, b: Xy) -> (Xy, Xy) {
        let ab = sub(b, a);
        let off = cmul(self.m_off, ab);
        ([base[0] + off[0], base[1] + off[1]], cmul(self.m_dir, ab))
    }
}

/// The derivatives' equations of "x on line l": perp(d) . x' = cross(d, p') - cross(d', x - p)
/// and, one order up, perp(d) . x'' = cross(d, p'') - cross(d'', x - p) - 2 cross(d', x' - p').
#[inline]
fn on_line_rates(l: &LineAt, x: Xy, v: Xy) -> (Xy, f64, f64) {
    let e = perp(l.d[0]);
    let c1 = cross(l.d[0], l.p[1]) - cross(l.d[1], sub(x, l.p[0]));
    let c2 = cross(l.d[0], l.p[2]) - cross(l.d[2], sub(x, l.p[0])) - 2.0 * cross(l.d[1], sub(v, l.p[1]));
    (e, c1, c2)
}

/// A point solved with its first and second derivatives by the input, and the step's
/// signed conditioning.
#[derive(Clone, Copy, Debug)]
pub(crate) struct Solved {
    pub x: [Xy; 3],
    pub det: f64,
}

/// Circle-line: point `p` at distance `r` from known point `k` (through link `link`) and on
/// `line`, on `side` (+1: ahead of the foot of k along the line's direction).
#[derive(Clone, Debug, PartialEq)]
pub(crate) struct Rrp {
    pub p: usize,
    pub k: usize,
    pub r: f64,
    pub line: Line,
    pub side: f64,
    /// The slot or prismatic pair giving the line, and the link from `k`.
    pub links: [usize; 2],
}

impl Rrp {
    /// The two intersections' one on `side`, or `None` where the circle misses the line
    /// (beyond rounding).
    pub(crate) fn solve(&self, k: [Xy; 3], l: &LineAt, side: f64, rates: bool) -> Option<Solved> {
        let (x, det) = self.place(k[0], l.p[0], l.d[0], side)?;
        let mut out = Solved { x: [x, [f64::NAN; 2], [f64::NAN; 2]], det };
        if rates {
            let (e1, c1, a1) = on_line_rates(l, x, [0.0; 2]);
            let e2 = sub(x, k[0]);
            if let Some(v) = solve2(e1, e2, c1, dot(e2, k[1])) {
                let dv = sub(v, k[1]);
                // the line's second-order term needs x' itself
                let a1 = a1 - 2.0 * cross(l.d[1], v);
                let a2 = dot(e2, k[2]) - dot(dv, dv);
                out.x[1] = v;
                out.x[2] = solve2(e1, e2, a1, a2).unwrap_or([f64::NAN; 2]);
            }
        }
        Some(out)
    }

    /// The position alone (no rates) and its conditioning, from known point `k` and the
    /// line through `p` along `d`: what [`Rrp::solve`] places, bit for bit.
    #[inline]
    pub(crate) fn place(&self, k: Xy, p: Xy, d: Xy, side: f64) -> Option<(Xy, f64)> {
        self.place_along(k, p, unit(d), side)
    }

    /// [`Rrp::place`] with the line's unit direction `u` ([`unit`] of its direction) given.
    #[inline]
    pub(crate) fn place_along(&self, k: Xy, p: Xy, u: Xy, side: f64) -> Option<(Xy, f64)> {
        let (x, det, meets) = self.place_branch_free(k, p, u, side);
        meets.then_some((x, det))
    }

    /// [`Rrp::place_along`] without a branch (a loop over many values of `k` vectorizes):
    /// the position and conditioning, and whether the circle meets the line (where it
    /// does not, the foot of k on the line and 0).
    #[inline(always)]
    pub(crate) fn place_branch_free(&self, k: Xy, p: Xy, u: Xy, side: f64) -> (Xy, f64, bool) {
        let w = sub(k, p);
        let along = dot(w, u);
        let foot = [p[0] + along * u[0], p[1] + along * u[1]];
        let dist = cross(u, w);
        let r = self.r;
        let round = 4.0 * f64::EPSILON * (r + dist.abs());
        let h2 = (r - dist) * (r + dist);
        let h = side * h2.max(0.0).sqrt();
        ([foot[0] + h * u[0], foot[1] + h * u[1]], h / r, h2 >= -round * r)
    }

    /// Signed conditioning at positions: the cosine between the line and k -> p.
    pub(crate) fn det_at(&self, p: Xy, k: Xy, l: &LineAt) -> f64 {
        let n = dot(l.d[0], l.d[0]).sqrt();
        dot(sub(p, k), l.d[0]) / (n * self.r)
    }
}

/// Line-line: point `p` on two known lines.
#[derive(Clone, Debug, PartialEq)]
pub(crate) struct LineLine {
    pub p: usize,
    pub lines: [Line; 2],
    pub links: [usize; 2],
}

impl LineLine {
    pub(crate) fn solve(&self, l1: &LineAt, l2: &LineAt, rates: bool) -> Solved {
        let (x, det) = Self::place(l1.p[0], l1.d[0], l2.p[0], l2.d[0]);
        let mut out = Solved { x: [x, [f64::NAN; 2], [f64::NAN; 2]], det };
        if rates {
            let (e1, c1, a1) = on_line_rates(l1, x, [0.0; 2]);
            let (e2, c2, a2) = on_line_rates(l2, x, [0.0; 2]);
            if let Some(v) = solve2(e1, e2, c1, c2) {
                let a1 = a1 - 2.0 * cross(l1.d[1], v);
                let a2 = a2 - 2.0 * cross(l2.d[1], v);
                out.x[1] = v;
                out.x[2] = solve2(e1, e2, a1, a2).unwrap_or([f64::NAN; 2]);
            }
        }
        out
    }

    /// The intersection of the line through `p1` along `d1` with the one through `p2`
    /// along `d2`, and the sine between them: what [`LineLine::solve`] places.
    #[inline]
    pub(crate) fn place(p1: Xy, d1: Xy, p2: Xy, d2: Xy) -> (Xy, f64) {
        let (n1, n2) = (dot(d1, d1).sqrt(), dot(d2, d2).sqrt());
        let det = cross(d1, d2) / (n1 * n2);
        // p = p1 + t d1 with cross(d2, p - p2) = 0
        let t = cross(d2, sub(p2, p1)) / cross(d2, d1);
        ([p1[0] + t * d1[0], p1[1] + t * d1[1]], det)
    }
}

/// A slot's point this near its guide's pivot, the slot passing as near (solving frame):
/// the point is on the pivot.
const ON_PIVOT: f64 = 16.0 * f64::EPSILON;

/// The guide's turn behind an [`Rpr`] position: its line's direction `u`, the signed
/// distance `along` it from k to q, and the arm k -> t.
#[derive(Clone, Copy, Debug)]
pub(crate) struct RprTurn {
    pub u: Xy,
    pub along: f64,
    pub arm: Xy,
}

/// Guide turning about known point `k`: its slot line (through `l0` with unit direction
/// `d`, both as drawn) passes through known point `q` at the drawn `offset`. Solves the
/// guide's rotation and places its point `t`, on `side` (+1: q ahead of k along the line).
#[derive(Clone, Debug, PartialEq)]
pub(crate) struct Rpr {
    pub t: usize,
    pub k: usize,
    pub q: usize,
    /// Drawn (solving frame): k, the line's point, its unit direction, and t.
    pub k0: Xy,
    pub l0: Xy,
    pub d: Xy,
    pub t0: Xy,
    pub offset: f64,
    pub side: f64,
    /// The guide and the slot point's link.
    pub links: [usize; 2],
}

impl Rpr {
    /// cross(R d, q - k) = c, with c = offset + cross(d, l0 - k0).
    fn c(&self) -> f64 {
        self.offset + cross(self.d, sub(self.l0, self.k0))
    }

    pub(crate) fn solve(&self, k: [Xy; 3], q: [Xy; 3], side: f64, rates: bool) -> Option<Solved> {
        let c = self.c();
        let (x, det, RprTurn { u, along, arm }) = self.place(k[0], q[0], side)?;
        let mut out = Solved { x: [x, [f64::NAN; 2], [f64::NAN; 2]], det };
        if rates && along != 0.0 {
            let dw = sub(q[1], k[1]);
            let ddw = sub(q[2], k[2]);
            let psi1 = cross(u, dw) / along;
            let u1 = [-psi1 * u[1], psi1 * u[0]];
            let psi2 = (2.0 * cross(u1, dw) + cross(u, ddw) - psi1 * psi1 * c) / along;
            out.x[1] = [k[1][0] - psi1 * arm[1], k[1][1] + psi1 * arm[0]];
            out.x[2] = [k[2][0] - psi2 * arm[1] - psi1 * psi1 * arm[0], k[2][1] + psi2 * arm[0] - psi1 * psi1 * arm[1]];
        }
        Some(out)
    }

    /// The position of `t` alone (no rates) and its conditioning, from the known points
    /// `k` and `q`, with the guide's turn that the rates need: what [`Rpr::solve`] places.
    #[inline]
    pub(crate) fn place(&self, k: Xy, q: Xy, side: f64) -> Option<(Xy, f64, RprTurn)> {
        let w = sub(q, k);
        let rw = dot(w, w).sqrt();
        let c = self.c();
        if self.on_pivot_at(rw, c) {
            // the point on the pivot (the slot through it): any guide angle assembles, none
            // is chosen by the point (conditioning 0: SINGULAR); the drawn one is given
            let arm = sub(self.t0, self.k0);
            return Some(([k[0] + arm[0], k[1] + arm[1]], 0.0, RprTurn { u: self.d, along: 0.0, arm }));
        }
        let round = 4.0 * f64::EPSILON * (rw + c.abs());
        if !(c.abs() <= rw + round) {
            return None;
        }
        // u = R d: cross(u, w) = c and dot(u, w) = side sqrt(|w|^2 - c^2)
        let along = side * ((rw - c.abs()) * (rw + c.abs())).max(0.0).sqrt();
        let u = [(along * w[0] + c * w[1]) / (rw * rw), (along * w[1] - c * w[0]) / (rw * rw)];
        // the rotation taking d to u, applied to t0 - k0
        let rot = [u[0] * self.d[0] + u[1] * self.d[1], u[1] * self.d[0] - u[0] * self.d[1]];
        let arm = cmul(rot, sub(self.t0, self.k0));
        // (the guide's rate is the point's across the line over `along`: its conditioning,
        // continuous and changing sign where the point passes through the pivot)
        Some(([k[0] + arm[0], k[1] + arm[1]], along, RprTurn { u, along, arm }))
    }

    /// Signed conditioning at positions (guide placed so that t is at `t`): what
    /// [`Rpr::place`] gives there.
    pub(crate) fn det_at(&self, t: Xy, k: Xy, q: Xy) -> f64 {
        // the guide's rotation from t, then the distance along its line from k's foot to q
        let rot = cdiv(sub(t, k), sub(self.t0, self.k0));
        let n = dot(rot, rot).sqrt();
        let u = cmul([rot[0] / n, rot[1] / n], self.d);
        dot(u, sub(q, k))
    }

    /// The point is on the pivot, the slot through it (to rounding of the solving frame,
    /// whose lengths are about 1): every guide angle assembles (a continuum).
    pub(crate) fn on_pivot(&self, k: Xy, q: Xy) -> bool {
        let w = sub(q, k);
        self.on_pivot_at(dot(w, w).sqrt(), self.c())
    }

    #[inline]
    fn on_pivot_at(&self, rw: f64, c: f64) -> bool {
        rw <= ON_PIVOT && c.abs() <= ON_PIVOT
    }
}
