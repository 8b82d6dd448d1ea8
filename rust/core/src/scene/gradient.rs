//! Exact derivatives of a solved pose with respect to the drawn coordinates (the design
//! variables of synthesis), by implicit differentiation of the whole linkage.
//!
//! Each moving link l is a rigid body whose point p sits at `t_l + R(phi_l) (xi_p - xi_o)`
//! (xi the drawn coordinates, o the link's first point); its pose (t_l, phi_l) is unknown.
//! The equations G(X, xi, theta) = 0 say that every joint's links put it at one place
//! (and a ground point where it is drawn), and that the input link has turned by
//! theta - theta0(xi) from the drawn pose. With Gruebler's count 1 they are square in X,
//! so at a solved pose dX/dxi = -G_X^-1 G_xi: one factorisation per input value, reused for
//! every design variable, and the points follow by the chain rule. A drawn coordinate moves
//! the shapes of the links through it (the drawing is its own assembly), the ground pivots
//! drawn on it, and the drawn input angle.

use nalgebra::{DMatrix, DVector};

use super::vec2::{perp, sub, Xy};
use super::Scene;
use crate::error::Error;

/// A free design variable: a point's drawn x (0) or y (1).
pub type Free = (usize, usize);

impl Scene {
    /// Derivatives of every point of a solved pose with respect to the `free` drawn
    /// coordinates: `out[(p * 2 + k) * F + f]` = d(point p, coordinate k) / d(free f).
    /// `pos` holds every point's position (scene units) at input angle `theta`. `None` where
    /// the pose is not finite or the linkage is singular there (a dead point). Scenes with
    /// slots, prismatic pairs or a linear input are refused.
    pub fn pose_gradient(&self, pos: &[Xy], free: &[Free]) -> Result<Option<Vec<f64>>, Error> {
        if !self.slots.is_empty() || !self.prismatic.is_empty() || self.input.is_none() {
            return Err(Error::scene(
                "gradient",
                "exact gradients of scenes with slots or prismatic pairs are not available yet",
            ));
        }
        let np = self.names.len();
        if pos.len() != np {
            return Err(Error::Shape { name: "pos".into(), got: pos.len(), expected: np });
        }
        if let Some(&(p, k)) = free.iter().find(|&&(p, k)| p >= np || k > 1) {
            return Err(Error::invalid("free", "must name a point's x (0) or y (1)", format!("({p}, {k})")));
        }
        if pos.iter().any(|p| !(p[0].is_finite() && p[1].is_finite())) {
            return Ok(None);
        }
        // solving frame: positions and drawn coordinates divided by the scale (derivatives
        // of lengths by lengths are scale-free)
        let at: Vec<Xy> = pos.iter().map(|&p| self.to_frame(p)).collect();
        let xi = &self.xy;
        let moving: Vec<usize> = (0..self.links.len()).filter(|&l| l != self.ground).collect();
        let col = |l: usize| 3 * moving.iter().position(|&m| m == l).expect("a moving link");
        let n = 3 * moving.len();
        // each link's first point and rotation from the drawn pose
        let origin = |l: usize| self.links[l].points[0];
        let rot = |l: usize| {
            let pts = &self.links[l].points;
            let (a, b) = (pts[0], pts[1]);
            let (d, e) = (sub(at[b], at[a]), sub(xi[b], xi[a]));
            d[1].atan2(d[0]) - e[1].atan2(e[0])
        };
        let phi: Vec<f64> = (0..self.links.len()).map(|l| if l == self.ground { 0.0 } else { rot(l) }).collect();
        let turn = |l: usize, v: Xy| {
            let (sn, cs) = phi[l].sin_cos();
            [cs * v[0] - sn * v[1], sn * v[0] + cs * v[1]]
        };
        let on_ground: Vec<bool> = (0..np).map(|p| self.links[self.ground].points.contains(&p)).collect();

        // rows: per point, each moving link through it against its owner (the ground, or
        // its first moving link); then the input's rotation
        let mut rows: Vec<(usize, usize, usize)> = Vec::new(); // (point, link, owner or MAX for ground)
        for (p, &ground) in on_ground.iter().enumerate() {
            let links: Vec<usize> = self.point_links[p].iter().copied().filter(|&l| l != self.ground).collect();
            let (owner, rest) = if ground { (usize::MAX, &links[..]) } else { (links[0], &links[1..]) };
            for &l in rest {
                rows.push((p, l, owner));
            }
        }
        let m = 2 * rows.len() + 1;
        if m != n {
            return Err(Error::scene("gradient", format!("{m} equations for {n} unknowns: not one degree of freedom")));
        }
        let mut gx = DMatrix::<f64>::zeros(n, n);
        let mut gxi = DMatrix::<f64>::zeros(n, free.len());
        let fcol = |p: usize, k: usize| free.iter().position(|&f| f == (p, k));
        // d pos_l(p): t_l + R(phi_l) (xi_p - xi_o), into row r with sign sg
        let body = |r: usize, p: usize, l: usize, sg: f64, gx: &mut DMatrix<f64>, gxi: &mut DMatrix<f64>| {
            let c = col(l);
            let w = turn(l, sub(xi[p], xi[origin(l)]));
            let pw = perp(w);
            for k in 0..2 {
                gx[(r + k, c + k)] += sg;
                gx[(r + k, c + 2)] += sg * pw[k];
            }
            // R(phi) e_j for the drawn coordinate j of p (+) and of the link's origin (-);
            // nothing for the origin itself (its drawn vector is 0)
            if p == origin(l) {
                return;
            }
            for (q, sq) in [(p, 1.0), (origin(l), -1.0)] {
                for j in 0..2 {
                    if let Some(f) = fcol(q, j) {
                        let mut e = [0.0; 2];
                        e[j] = 1.0;
                        let re = turn(l, e);
                        for k in 0..2 {
                            gxi[(r + k, f)] += sg * sq * re[k];
                        }
                    }
                }
            }
        };
        for (i, &(p, l, owner)) in rows.iter().enumerate() {
            let r = 2 * i;
            body(r, p, l, 1.0, &mut gx, &mut gxi);
            if owner == usize::MAX {
                for k in 0..2 {
                    if let Some(f) = fcol(p, k) {
                        gxi[(r + k, f)] -= 1.0;
                    }
                }
            } else {
                body(r, p, owner, -1.0, &mut gx, &mut gxi);
            }
        }
        // the input: phi_in + theta0(xi) - theta = 0 (theta0 the drawn input angle)
        let input = self.input.expect("checked above");
        let r = m - 1;
        gx[(r, col(input.link) + 2)] = 1.0;
        let d = sub(xi[input.tip], xi[input.pivot]);
        let d2 = d[0] * d[0] + d[1] * d[1];
        let dtheta = [-d[1] / d2, d[0] / d2];
        for (q, sq) in [(input.tip, 1.0), (input.pivot, -1.0)] {
            for (k, dt) in dtheta.iter().enumerate() {
                if let Some(f) = fcol(q, k) {
                    gxi[(r, f)] += sq * dt;
                }
            }
        }
        let lu = gx.lu();
        let Some(dx) = lu.solve(&(-gxi)) else { return Ok(None) };
        if !dx.iter().all(|v| v.is_finite()) {
            return Ok(None);
        }
        // the points: through their owner (ground points move only with their own drawing)
        let nf = free.len();
        let mut out = vec![0.0; np * 2 * nf];
        for p in 0..np {
            if on_ground[p] {
                for k in 0..2 {
                    if let Some(f) = fcol(p, k) {
                        out[(p * 2 + k) * nf + f] = 1.0;
                    }
                }
                continue;
            }
            let l = self.point_links[p].iter().copied().find(|&l| l != self.ground).expect("a moving point");
            let c = col(l);
            let pw = perp(turn(l, sub(xi[p], xi[origin(l)])));
            for f in 0..nf {
                let dxf = DVector::from_fn(3, |i, _| dx[(c + i, f)]);
                let (q, j) = free[f];
                let mut e = [0.0; 2];
                if p != origin(l) {
                    if q == p {
                        e[j] += 1.0;
                    }
                    if q == origin(l) {
                        e[j] -= 1.0;
                    }
                }
                let re = turn(l, e);
                for k in 0..2 {
                    out[(p * 2 + k) * nf + f] = dxf[k] + pw[k] * dxf[2] + re[k];
                }
            }
        }
        Ok(Some(out))
    }
}
