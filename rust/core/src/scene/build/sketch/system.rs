//! The sketch's square system and its dense Newton continuation from the sketched lengths
//! to the given ones (an LU per step, its pivots telling a dead point), and the messages
//! that name what cannot close.

use nalgebra::{DMatrix, DVector};

use super::given::{dist, Owner};
use super::rows::{Kind, Row};
use crate::error::Error;
use crate::interrupt::Interrupt;
use crate::scene::model::Scene;
use crate::scene::vec2::{cross, dot, perp, sub, Xy};

/// Newton corrections below this converge a continuation step (frame units: coordinates
/// divided by the power of two at or below the largest link); the last solve goes on to
/// rounding.
pub(super) const STEP_TOL: f64 = 1e-10;
/// The final pose must meet every condition to this (frame units).
pub(super) const CLOSE_TOL: f64 = 1e-12;
/// The first correction of a continuation step may be at most this (frame units), and
/// each next one at most half the one before: a step that converges otherwise may have
/// jumped to another assembly, so it is halved.
pub(super) const FIRST_MAX: f64 = 0.25;
/// Smallest continuation step (a fraction of the way from the sketched lengths).
pub(super) const H_MIN: f64 = 1.0 / (1u64 << 20) as f64;
/// Most continuation steps tried, and Newton iterations per step and for the last solve.
pub(super) const MAX_STEPS: usize = 200;
pub(super) const STEP_ITERS: usize = 8;
pub(super) const FINAL_ITERS: usize = 40;
/// Below this ratio of the smallest to the largest LU pivot the Jacobian is taken as
/// singular (then its singular values decide and say where).
pub(super) const PIVOT_RATIO: f64 = 1e-13;
/// The sketch is at a dead point when the smallest singular value of its Jacobian is below
/// this fraction of the largest.
pub(super) const DEAD: f64 = 1e-10;

/// The square system: unknowns are the frame coordinates of the moving points.
pub(super) struct System {
    pub(super) rows: Vec<Row>,
    /// Column of each point's x (its y is the next), None for a fixed point.
    pub(super) col: Vec<Option<usize>>,
    /// First residual of each row.
    pub(super) start: Vec<usize>,
    pub(super) n: usize,
    pub(super) rows_len: usize,
    pub(super) fixed_xy: Vec<Xy>,
}

/// An LU factorisation with its determinant's sign and pivot ratio.
pub(super) struct Lu {
    pub(super) lu: nalgebra::LU<f64, nalgebra::Dyn, nalgebra::Dyn>,
    pub(super) sign: f64,
    pub(super) ratio: f64,
}

impl Lu {
    pub(super) fn new(j: DMatrix<f64>) -> Lu {
        let lu = j.lu();
        let diag = lu.u().diagonal();
        let (mut lo, mut hi) = (f64::INFINITY, 0.0_f64);
        let mut sign = lu.p().determinant::<f64>();
        for &u in diag.iter() {
            lo = lo.min(u.abs());
            hi = hi.max(u.abs());
            if u < 0.0 {
                sign = -sign;
            }
        }
        let ratio = if hi > 0.0 && lo.is_finite() { lo / hi } else { 0.0 };
        Lu { lu, sign, ratio: if ratio.is_nan() { 0.0 } else { ratio } }
    }

    pub(super) fn regular(&self) -> bool {
        self.ratio > PIVOT_RATIO
    }

    /// -J^-1 b.
    pub(super) fn step(&self, b: &DVector<f64>) -> Option<DVector<f64>> {
        self.lu.solve(b).map(|x| -x).filter(|x| x.iter().all(|v| v.is_finite()))
    }
}

pub(super) fn norm(v: &DVector<f64>) -> f64 {
    v.iter().fold(0.0_f64, |m, x| if x.abs() > m || x.is_nan() { x.abs() } else { m })
}

impl System {
    pub(super) fn new(sc: &Scene, fixed: &[bool], rows: Vec<Row>) -> System {
        let mut col = vec![None; fixed.len()];
        let mut n = 0;
        for (p, &f) in fixed.iter().enumerate() {
            if !f {
                col[p] = Some(n);
                n += 2;
            }
        }
        let mut start = Vec::with_capacity(rows.len());
        let mut m = 0;
        for r in &rows {
            start.push(m);
            m += r.kind.len();
        }
        System { rows, col, start, n, rows_len: m, fixed_xy: sc.xy.clone() }
    }

    pub(super) fn pos(&self, x: &DVector<f64>, p: usize) -> Xy {
        match self.col[p] {
            Some(c) => [x[c], x[c + 1]],
            None => self.fixed_xy[p],
        }
    }

    /// Residuals at (x, lam) into `f`; with `jac`, the Jacobian too.
    pub(super) fn eval(&self, x: &DVector<f64>, lam: f64, f: &mut DVector<f64>, mut jac: Option<&mut DMatrix<f64>>) {
        if let Some(j) = jac.as_deref_mut() {
            j.fill(0.0);
        }
        let col = &self.col;
        let put = |j: &mut Option<&mut DMatrix<f64>>, r: usize, p: usize, g: Xy| {
            if let (Some(j), Some(c)) = (j.as_deref_mut(), col[p]) {
                j[(r, c)] += g[0];
                j[(r, c + 1)] += g[1];
            }
        };
        for (row, &r) in self.rows.iter().zip(&self.start) {
            let t = [row.from[0] + lam * (row.to[0] - row.from[0]), row.from[1] + lam * (row.to[1] - row.from[1])];
            match row.kind {
                Kind::Dist { a, b } => {
                    let e = sub(self.pos(x, b), self.pos(x, a));
                    let n = dist(e);
                    f[r] = n - t[0];
                    let g = [e[0] / n, e[1] / n];
                    put(&mut jac, r, b, g);
                    put(&mut jac, r, a, [-g[0], -g[1]]);
                }
                Kind::Affine { a, b, c } => {
                    let (pa, pb, pc) = (self.pos(x, a), self.pos(x, b), self.pos(x, c));
                    let e = sub(pb, pa);
                    let q = perp(e);
                    let (al, be) = (t[0], t[1]);
                    f[r] = pc[0] - pa[0] - al * e[0] - be * q[0];
                    f[r + 1] = pc[1] - pa[1] - al * e[1] - be * q[1];
                    put(&mut jac, r, c, [1.0, 0.0]);
                    put(&mut jac, r + 1, c, [0.0, 1.0]);
                    put(&mut jac, r, a, [al - 1.0, -be]);
                    put(&mut jac, r + 1, a, [be, al - 1.0]);
                    put(&mut jac, r, b, [-al, be]);
                    put(&mut jac, r + 1, b, [-be, -al]);
                }
                Kind::Off { l0, l1, p } | Kind::Along { l0, l1, p } => {
                    let d = sub(self.pos(x, l1), self.pos(x, l0));
                    let w = sub(self.pos(x, p), self.pos(x, l0));
                    let n = dist(d);
                    let (gp, gd) = if let Kind::Off { .. } = row.kind {
                        let c = cross(d, w);
                        f[r] = c / n - t[0];
                        let gp = [-d[1] / n, d[0] / n];
                        let pw = perp(w);
                        (gp, [-pw[0] / n - c * d[0] / (n * n * n), -pw[1] / n - c * d[1] / (n * n * n)])
                    } else {
                        let s = dot(d, w);
                        f[r] = s / n - t[0];
                        ([d[0] / n, d[1] / n], [w[0] / n - s * d[0] / (n * n * n), w[1] / n - s * d[1] / (n * n * n)])
                    };
                    put(&mut jac, r, p, gp);
                    put(&mut jac, r, l1, gd);
                    put(&mut jac, r, l0, [-gp[0] - gd[0], -gp[1] - gd[1]]);
                }
                Kind::Angle { pivot, tip, u } => {
                    f[r] = cross(u, sub(self.pos(x, tip), self.pos(x, pivot)));
                    let g = perp(u);
                    put(&mut jac, r, tip, g);
                    put(&mut jac, r, pivot, [-g[0], -g[1]]);
                }
            }
        }
    }

    /// d residuals / d lam at x.
    pub(super) fn dlam(&self, x: &DVector<f64>) -> DVector<f64> {
        let mut v = DVector::zeros(self.rows_len);
        for (row, &r) in self.rows.iter().zip(&self.start) {
            let dt = [row.to[0] - row.from[0], row.to[1] - row.from[1]];
            match row.kind {
                Kind::Affine { a, b, .. } => {
                    let e = sub(self.pos(x, b), self.pos(x, a));
                    let q = perp(e);
                    v[r] = -(dt[0] * e[0] + dt[1] * q[0]);
                    v[r + 1] = -(dt[0] * e[1] + dt[1] * q[1]);
                }
                _ => v[r] = -dt[0],
            }
        }
        v
    }

    pub(super) fn jacobian(&self, x: &DVector<f64>, lam: f64) -> (DVector<f64>, DMatrix<f64>) {
        let mut f = DVector::zeros(self.rows_len);
        let mut j = DMatrix::zeros(self.rows_len, self.n);
        self.eval(x, lam, &mut f, Some(&mut j));
        (f, j)
    }

    /// Newton at `lam` from `x`: the converged point and its factorisation, or None when it
    /// does not converge the way a nearby solution would (see [`FIRST_MAX`]).
    pub(super) fn correct(&self, mut x: DVector<f64>, lam: f64) -> Option<(DVector<f64>, Lu)> {
        let mut last = f64::INFINITY;
        for it in 0..STEP_ITERS {
            let (f, j) = self.jacobian(&x, lam);
            let lu = Lu::new(j);
            if !lu.regular() {
                return None;
            }
            let dx = lu.step(&f)?;
            let size = norm(&dx);
            if (it == 0 && !(size <= FIRST_MAX)) || (it > 0 && !(size <= 0.5 * last)) {
                return None;
            }
            x += dx;
            if size <= STEP_TOL {
                let (_, j) = self.jacobian(&x, lam);
                return Some((x, Lu::new(j)));
            }
            last = size;
        }
        None
    }

    /// From the sketch (lam = 0, where every condition holds as sketched) to the given
    /// lengths (lam = 1), keeping the sign of the Jacobian's determinant (the assembly
    /// mode); then Newton to rounding.
    pub(super) fn solve(&self, sc: &Scene, interrupt: &dyn Interrupt) -> Result<DVector<f64>, Error> {
        let mut x = DVector::zeros(self.n);
        for (p, c) in self.col.iter().enumerate() {
            if let Some(c) = *c {
                x[c] = sc.xy[p][0];
                x[c + 1] = sc.xy[p][1];
            }
        }
        if self.n == 0 {
            return Ok(x);
        }
        let (f1, _) = self.jacobian(&x, 1.0);
        // a sketch that is already exact (a saved scene read back) needs no continuation:
        // the rank check that follows judges its pose
        if !(norm(&f1) <= CLOSE_TOL) {
            let (_, j0) = self.jacobian(&x, 0.0);
            let mut lu = Lu::new(j0.clone());
            if !lu.regular() {
                self.dead_start(sc, &j0)?;
            }
            let sign = lu.sign;
            let (mut lam, mut h, mut steps) = (0.0, 1.0_f64, 0);
            while lam < 1.0 {
                steps += 1;
                if interrupt.interrupted() {
                    return Err(Error::Interrupted);
                }
                if steps > MAX_STEPS || h < H_MIN {
                    return Err(self.cannot_close(sc, &x, lam));
                }
                let h1 = h.min(1.0 - lam);
                let next = if h1 == 1.0 - lam { 1.0 } else { lam + h1 };
                let tried = lu.step(&self.dlam(&x)).and_then(|t| self.correct(&x + t * h1, next));
                match tried {
                    Some((xn, lun)) if lun.regular() && lun.sign == sign => {
                        (x, lu, lam) = (xn, lun, next);
                        h = (2.0 * h1).min(1.0);
                    }
                    _ => h = h1 / 2.0,
                }
            }
        }
        // Newton to rounding at the given lengths
        let mut last = f64::INFINITY;
        for _ in 0..FINAL_ITERS {
            let (f, j) = self.jacobian(&x, 1.0);
            let lu = Lu::new(j);
            let Some(dx) = lu.step(&f) else { break };
            let size = norm(&dx);
            if size <= 4.0 * f64::EPSILON || (size >= last && last <= 1e3 * CLOSE_TOL) {
                break;
            }
            x += dx;
            last = size;
        }
        let (f, _) = self.jacobian(&x, 1.0);
        if !(norm(&f) <= CLOSE_TOL) {
            return Err(self.cannot_close(sc, &x, f64::NAN));
        }
        Ok(x)
    }

    /// The owner a failure is blamed on, and the point that moves most at it. At a dead
    /// point the Jacobian's smallest singular direction says which points move (right
    /// vector) and which conditions cannot hold together (left vector): of the owners with
    /// a moving point, the one those conditions weigh most, a link where one weighs at
    /// least a quarter of the heaviest.
    pub(super) fn blame(&self, j: &DMatrix<f64>) -> (Owner, Option<usize>) {
        let svd = j.clone().svd(true, true);
        let sv = &svd.singular_values;
        let k = (0..sv.len()).fold(0, |b, i| if sv[i] < sv[b] { i } else { b });
        let (Some(u), Some(vt)) = (&svd.u, &svd.v_t) else { return (Owner::Input, None) };
        let motion: Vec<f64> = self.col.iter().map(|c| c.map_or(0.0, |c| vt[(k, c)].hypot(vt[(k, c + 1)]))).collect();
        let top_motion = motion.iter().fold(0.0_f64, |m, &x| m.max(x));
        let point = (0..motion.len()).fold(None, |b: Option<usize>, p| match b {
            Some(q) if motion[q] >= motion[p] => Some(q),
            _ if self.col[p].is_some() => Some(p),
            _ => b,
        });
        let mut weight: Vec<(Owner, f64, bool)> = Vec::new();
        for (row, &r) in self.rows.iter().zip(&self.start) {
            let w: f64 = (0..row.kind.len()).map(|i| u[(r + i, k)].powi(2)).sum();
            let moves = row.kind.points().iter().any(|&p| motion[p] >= 0.1 * top_motion && motion[p] > 0.0);
            match weight.iter_mut().find(|(o, ..)| *o == row.owner) {
                Some(x) => {
                    x.1 += w;
                    x.2 |= moves;
                }
                None => weight.push((row.owner, w, moves)),
            }
        }
        let heaviest = |links_only: bool| {
            weight.iter().filter(|w| w.2 && (!links_only || matches!(w.0, Owner::Link(_)))).fold(
                None,
                |b: Option<(Owner, f64)>, w| match b {
                    Some(x) if x.1 >= w.1 => Some(x),
                    _ => Some((w.0, w.1)),
                },
            )
        };
        let owner = match (heaviest(true), heaviest(false)) {
            (Some(l), Some(t)) if l.1 >= 0.25 * t.1 => l.0,
            (_, Some(t)) => t.0,
            _ => Owner::Input,
        };
        (owner, point)
    }

    /// The error when the lengths do not close: the continuation stopped at `lam` (NaN: the
    /// last Newton solve at the given lengths did not converge).
    pub(super) fn cannot_close(&self, sc: &Scene, x: &DVector<f64>, lam: f64) -> Error {
        let (_, j) = self.jacobian(x, if lam.is_nan() { 1.0 } else { lam });
        let (owner, _) = self.blame(&j);
        let why = if lam.is_nan() {
            "Newton's method does not close them".to_string()
        } else {
            format!(
                "changing the sketch's own lengths into the given ones, the pose meets a dead point {:.0}% of the way",
                100.0 * lam
            )
        };
        Error::scene(
            owner.entry(sc),
            format!(
                "no assembly near the sketch: its lengths cannot close at the sketched input in the sketched \
                 assembly mode ({why})"
            ),
        )
    }

    /// Err when the sketch itself is at a dead point (it then names no assembly mode).
    pub(super) fn dead_start(&self, sc: &Scene, j: &DMatrix<f64>) -> Result<(), Error> {
        let sv = j.singular_values();
        let (lo, hi) = (sv.min(), sv.max());
        if lo > DEAD * hi {
            return Ok(());
        }
        let (owner, point) = self.blame(j);
        let point = point.map_or(String::new(), |p| format!(": draw {:?} off it", sc.names[p]));
        Err(Error::scene(
            owner.entry(sc),
            format!(
                "the sketch is drawn at a dead point (its points can move to first order with every condition held), \
                 so it does not say which assembly it means{point}"
            ),
        ))
    }
}
