//! Mobility: Gruebler's count, then the rank of the constraint Jacobian at the drawn pose,
//! so that a special geometry that moves although the count says it cannot is reported.

use nalgebra::DMatrix;

use crate::error::Error;
use crate::scene::build::compile::compile;
use crate::scene::input::LinearKind;
use crate::scene::model::{gruebler, Scene};
use crate::scene::vec2::{cross, dot, perp, sub, Xy};

/// The constraint Jacobian at the drawn pose is rank deficient when its smallest singular
/// value is below this fraction of its largest.
const RANK_TOL: f64 = 1e-9;
/// Largest Jacobian (unknowns) whose singular values are computed when the plan cannot
/// prove full rank (cubic time: about 0.1 s at this size).
const DENSE_COLUMNS: usize = 600;

/// Gruebler's count with the slots and prismatic pairs must be 1.
pub(super) fn count(nlinks: usize, point_links: &[Vec<usize>], nslots: usize, nprism: usize) -> Result<(), Error> {
    let m = gruebler(nlinks, point_links) - nslots as i64 - 2 * nprism as i64;
    if m != 1 {
        let joints: usize = point_links.iter().map(|l| l.len().saturating_sub(1)).sum();
        let extra = if nslots == 0 && nprism == 0 {
            String::new()
        } else {
            format!(" - {nslots} slots - 2 x {nprism} prismatic pairs")
        };
        return Err(Error::scene(
            "mobility",
            format!(
                "Gruebler's count gives M = {m} (3 x ({nlinks} links - 1) - 2 x {joints} joints{extra}), expected 1 \
                 (a one-degree-of-freedom linkage)"
            ),
        ));
    }
    Ok(())
}

/// The constraint Jacobian at the drawn pose, with the input angle held, must be square and
/// of full rank: otherwise the drawn pose is a dead point, or the linkage has more freedom
/// there than its count says (e.g. a structure that moves because of special geometry).
///
/// The plan is the cheap proof: it solves the constraints in order, so where each of its
/// steps is regular at the drawn pose the Jacobian is block triangular with regular blocks
/// (time linear in the scene's size). Otherwise, up to [`DENSE_COLUMNS`] unknowns, the
/// singular values decide (and say why); a larger scene gets the plan's own answer.
pub(super) fn rank_check(sc: &Scene) -> Result<(), Error> {
    let points: Vec<usize> = (0..sc.names.len()).collect();
    let links: Vec<usize> = (0..sc.links.len()).collect();
    let planned = compile(sc, &points, &links);
    if let Ok(p) = &planned {
        let (_, dets) = p.dets_at(&sc.xy);
        match dets.iter().position(|d| !(d.abs() > RANK_TOL)) {
            None => return Ok(()),
            Some(k) if 3 * (sc.links.len() - 1) > DENSE_COLUMNS => {
                let step = &p.steps()[k];
                let at: Vec<&str> = step.points.iter().map(|&q| sc.names[q].as_str()).collect();
                return Err(Error::scene(
                    "mobility",
                    format!(
                        "the drawn pose is a dead point: the {} solving {at:?} has conditioning {:.1e}",
                        step.kind.name(),
                        dets[k]
                    ),
                ));
            }
            Some(_) => {}
        }
    }
    if 3 * (sc.links.len() - 1) > DENSE_COLUMNS {
        return planned.map(|_| ());
    }
    dense_rank_check(sc)
}

/// [`rank_check`] by the singular values of the whole Jacobian.
fn dense_rank_check(sc: &Scene) -> Result<(), Error> {
    let mut jac = Jacobian::new(sc);
    jac.joints();
    jac.slots();
    jac.prismatic();
    let (rows, ncol) = (jac.rows, jac.ncol);
    debug_assert_eq!(rows.len(), ncol, "Gruebler M = 1 makes the system square");
    let j = DMatrix::from_fn(rows.len(), ncol, |r, c| rows[r][c]);
    let sv = j.singular_values();
    let (lo, hi) = (sv.min(), sv.max());
    if !(lo > RANK_TOL * hi) {
        return Err(Error::scene(
            "mobility",
            format!(
                "the constraint Jacobian at the drawn pose is rank deficient (smallest / largest singular value \
                 {:.1e}): the drawn pose is a dead point, or the linkage moves with more than one degree of \
                 freedom there although Gruebler's count is 1",
                lo / hi
            ),
        ));
    }
    Ok(())
}

/// The constraint Jacobian's rows, built joint by joint. Unknowns: (tx, ty, phi) of every
/// non-ground link; a link's points are t + R(phi) (p - p_first).
struct Jacobian<'s> {
    sc: &'s Scene,
    col: Vec<Option<usize>>,
    ncol: usize,
    rows: Vec<Vec<f64>>,
    /// The linear input's kind and index.
    linear: Option<(LinearKind, usize)>,
}

impl<'s> Jacobian<'s> {
    fn new(sc: &'s Scene) -> Self {
        let col: Vec<Option<usize>> = {
            let mut next = 0;
            (0..sc.links.len())
                .map(|k| {
                    (k != sc.ground).then(|| {
                        next += 3;
                        next - 3
                    })
                })
                .collect()
        };
        let ncol = 3 * (sc.links.len() - 1);
        Jacobian { sc, col, ncol, rows: Vec::new(), linear: sc.linear.map(|l| (l.kind, l.index)) }
    }

    /// d position of point p via link k.
    fn grad(&self, k: usize, p: usize, row: &mut [f64], comp: usize, sign: f64) {
        let sc = self.sc;
        if let Some(c) = self.col[k] {
            let first = sc.links[k].points[0];
            let r = perp(sub(sc.xy[p], sc.xy[first]));
            row[c + comp] += sign;
            row[c + 2] += sign * r[comp];
        }
    }

    /// A point's position derivative row: d p / d (tx, ty, phi) of link k, along `w`.
    fn dpos(&self, k: usize, p: usize, row: &mut [f64], w: Xy) {
        let sc = self.sc;
        if let Some(c) = self.col[k] {
            let first = sc.links[k].points[0];
            let r = perp(sub(sc.xy[p], sc.xy[first]));
            row[c] += w[0];
            row[c + 1] += w[1];
            row[c + 2] += dot(w, r);
        }
    }

    /// A point on a line: cross(u, p - l0) with u the guide's unit direction; d =
    /// cross(du, p - l0) + cross(u, dp - dl0), du = dphi_guide perp(u).
    fn on_line(&self, guide: usize, line: (usize, usize), p: usize, pl: usize, row: &mut [f64]) {
        let sc = self.sc;
        let u = {
            let d = sub(sc.xy[line.1], sc.xy[line.0]);
            let n = dot(d, d).sqrt();
            [d[0] / n, d[1] / n]
        };
        let n = perp(u); // cross(u, v) = n . v
        self.dpos(pl, p, row, n);
        self.dpos(guide, line.0, row, [-n[0], -n[1]]);
        if let Some(c) = self.col[guide] {
            // cross(perp(u), p - l0) = -u . (p - l0)
            row[c + 2] -= dot(u, sub(sc.xy[p], sc.xy[line.0]));
        }
    }

    /// The input holds a point's place along a line (a linear input's row).
    fn along(&self, (link, p): (usize, usize), guide: usize, line: (usize, usize)) -> Vec<f64> {
        let sc = self.sc;
        let mut row = vec![0.0; self.ncol];
        let u = sub(sc.xy[line.1], sc.xy[line.0]);
        self.dpos(link, p, &mut row, u);
        self.dpos(guide, line.0, &mut row, [-u[0], -u[1]]);
        if let Some(c) = self.col[guide] {
            row[c + 2] += cross(u, sub(sc.xy[p], sc.xy[line.0]));
        }
        row
    }

    /// Two rows per extra link at each joint.
    fn joints(&mut self) {
        let sc = self.sc;
        for (p, ls) in sc.point_links.iter().enumerate() {
            for &k in &ls[1..] {
                for comp in 0..2 {
                    let mut row = vec![0.0; self.ncol];
                    self.grad(k, p, &mut row, comp, 1.0);
                    self.grad(ls[0], p, &mut row, comp, -1.0);
                    self.rows.push(row);
                }
            }
        }
    }

    /// A row per slot, and the linear input's if it is a slot.
    fn slots(&mut self) {
        let sc = self.sc;
        let link_of = |p: usize| sc.point_links[p][0];
        for (i, sl) in sc.slots.iter().enumerate() {
            let mut row = vec![0.0; self.ncol];
            self.on_line(sl.guide, sl.line, sl.point, link_of(sl.point), &mut row);
            self.rows.push(row);
            if self.linear == Some((LinearKind::Slot, i)) {
                // the input holds the point's place along the line
                let row = self.along((link_of(sl.point), sl.point), sl.guide, sl.line);
                self.rows.push(row);
            }
        }
    }

    /// Two rows per prismatic pair (on the line, the same rotation), the linear input's if
    /// it is one, and the angle input's.
    fn prismatic(&mut self) {
        let sc = self.sc;
        for (i, pr) in sc.prismatic.iter().enumerate() {
            let q = sc.links[pr.link].points[0];
            let mut row = vec![0.0; self.ncol];
            self.on_line(pr.guide, pr.line, q, pr.link, &mut row);
            self.rows.push(row);
            let mut row = vec![0.0; self.ncol];
            if let Some(c) = self.col[pr.link] {
                row[c + 2] += 1.0;
            }
            if let Some(c) = self.col[pr.guide] {
                row[c + 2] -= 1.0;
            }
            self.rows.push(row);
            if self.linear == Some((LinearKind::Prismatic, i)) {
                let row = self.along((pr.link, q), pr.guide, pr.line);
                self.rows.push(row);
            }
        }
        if let Some(input) = sc.input {
            let mut row = vec![0.0; self.ncol];
            row[self.col[input.link].expect("input is not ground") + 2] = 1.0;
            self.rows.push(row);
        }
    }
}
