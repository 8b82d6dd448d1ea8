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
//! drawn on it, and the drawn input angle. A slot adds one row (its point at its drawn
//! offset from the guide's line), a prismatic pair two (the link's first point at its drawn
//! offset from the line, and the link's rotation locked to the guide's).

use nalgebra::DMatrix;

use crate::error::Error;
use crate::scene::model::Scene;
use crate::scene::vec2::{cross, perp, sub, Xy};

/// Step of [`Scene::dets_gradient`]'s central difference, in solving-frame units (the
/// drawing's size is about 1 there).
pub const DET_STEP: f64 = 1e-5;

/// A free design variable: a point's drawn x (0) or y (1).
pub type Free = (usize, usize);

/// What the differentiation needs of a scene, built once for many poses.
struct Layout {
    /// The moving links (column blocks of 3: tx, ty, phi).
    moving: Vec<usize>,
    /// Column block of each link (usize::MAX for ground).
    block: Vec<usize>,
    /// Per row pair: (point, link, owner link or usize::MAX for ground).
    rows: Vec<(usize, usize, usize)>,
    /// Per point: the moving link its position is read through (None: a ground point).
    owner: Vec<Option<usize>>,
    /// Per point and coordinate: its column among the free ones.
    fcol: Vec<[Option<usize>; 2]>,
    /// The input is held at its rotation from the drawn pose (not at its absolute angle).
    relative: bool,
}

impl Scene {
    /// Derivatives of every point of a solved pose with respect to the `free` drawn
    /// coordinates: `out[(p * 2 + k) * F + f]` = d(point p, coordinate k) / d(free f).
    /// `pos` holds every point's position (scene units) at its input angle. `None` where
    /// the pose is not finite or the linkage is singular there (a dead point). Scenes with
    /// a linear input are refused.
    pub fn pose_gradient(&self, pos: &[Xy], free: &[Free]) -> Result<Option<Vec<f64>>, Error> {
        let layout = self.layout(free, false)?;
        let np = self.names.len();
        if pos.len() != np {
            return Err(Error::Shape { name: "pos".into(), got: pos.len(), expected: np });
        }
        let mut out = vec![0.0; np * 2 * free.len()];
        Ok(self.gradient_into(&layout, pos, free.len(), &mut out).then_some(out))
    }

    /// [`Scene::pose_gradient`] of N poses (`poses` holds N * P points) into `out`
    /// (N * P * 2 * F values), NaN for a pose that is not finite or singular; the layout is
    /// built once. With `relative`, the input is held at its rotation from the drawn pose
    /// (as synthesis measures it), so the drawn input angle's own change does not count.
    pub fn poses_gradient(&self, poses: &[Xy], free: &[Free], relative: bool, out: &mut [f64]) -> Result<(), Error> {
        let layout = self.layout(free, relative)?;
        let (np, nf) = (self.names.len(), free.len());
        if np == 0 || nf == 0 {
            return Ok(());
        }
        if !poses.len().is_multiple_of(np) || out.len() != poses.len() * 2 * nf {
            return Err(Error::Shape { name: "poses".into(), got: poses.len(), expected: out.len() / (2 * nf) });
        }
        for (pose, o) in poses.chunks(np).zip(out.chunks_mut(np * 2 * nf)) {
            if !self.gradient_into(&layout, pose, nf, o) {
                o.fill(f64::NAN);
            }
        }
        Ok(())
    }

    /// Derivatives of the signed conditioning that `plan(outputs)` reports (a sweep's
    /// `det`, the product of its steps') at N solved poses, by the free drawn coordinates:
    /// `out[n * F + f]`. `poses` holds N * P points (scene units) and `dpos` their
    /// derivatives from [`Scene::poses_gradient`] (N * P * 2 * F). The conditioning is a
    /// function of the drawing and the pose; it is differentiated along the exact tangent:
    /// a central difference (step [`DET_STEP`] of the solving frame) of the conditioning of
    /// the redrawn plan at the pose moved by the exact derivative, so no sweep is repeated
    /// and the error is O(step^2). NaN where a pose or its derivative is not finite.
    pub fn dets_gradient(
        &self,
        outputs: Option<&[String]>,
        poses: &[Xy],
        dpos: &[f64],
        free: &[Free],
        out: &mut [f64],
    ) -> Result<(), Error> {
        self.layout(free, true)?; // the same scenes as the pose gradient (and the checks)
        let (np, nf) = (self.names.len(), free.len());
        if np == 0 || nf == 0 {
            return Ok(());
        }
        let n = poses.len() / np;
        if !poses.len().is_multiple_of(np) || dpos.len() != poses.len() * 2 * nf || out.len() != n * nf {
            return Err(Error::Shape { name: "poses".into(), got: out.len(), expected: n * nf });
        }
        let frame: Vec<Xy> = poses.iter().map(|&p| self.to_frame(p)).collect();
        let h = DET_STEP;
        let mut moved = vec![[0.0; 2]; np];
        // one copy of the scene, each coordinate moved and put back in turn
        let mut sc = self.clone();
        for (f, &(p, k)) in free.iter().enumerate() {
            let mut dets = [vec![0.0; n], vec![0.0; n]];
            for (side, sg) in [1.0, -1.0].into_iter().enumerate() {
                sc.xy[p][k] = self.xy[p][k] + sg * h;
                sc.drawn[p][k] = self.drawn[p][k] + sg * h * self.scale;
                let plan = sc.plan(outputs)?;
                for (i, pose) in frame.chunks(np).enumerate() {
                    for (q, (m, x)) in moved.iter_mut().zip(pose).enumerate() {
                        for c in 0..2 {
                            m[c] = x[c] + sg * h * dpos[((i * np + q) * 2 + c) * nf + f];
                        }
                    }
                    dets[side][i] = plan.dets_at(&moved).0;
                }
            }
            (sc.xy[p][k], sc.drawn[p][k]) = (self.xy[p][k], self.drawn[p][k]);
            for (i, o) in out.iter_mut().skip(f).step_by(nf).enumerate() {
                *o = (dets[0][i] - dets[1][i]) / (2.0 * h * self.scale);
            }
        }
        Ok(())
    }

    fn layout(&self, free: &[Free], relative: bool) -> Result<Layout, Error> {
        if self.input.is_none() {
            return Err(Error::scene(
                "gradient",
                "exact gradients of scenes with a linear input are not available yet",
            ));
        }
        let np = self.names.len();
        let mut fcol = vec![[None; 2]; np];
        for (f, &(p, k)) in free.iter().enumerate() {
            if p >= np || k > 1 {
                return Err(Error::invalid("free", "must name a point's x (0) or y (1)", format!("({p}, {k})")));
            }
            fcol[p][k] = Some(f);
        }
        let moving: Vec<usize> = (0..self.links.len()).filter(|&l| l != self.ground).collect();
        let mut block = vec![usize::MAX; self.links.len()];
        for (i, &l) in moving.iter().enumerate() {
            block[l] = 3 * i;
        }
        let mut rows = Vec::new();
        let mut owner = vec![None; np];
        for (p, own) in owner.iter_mut().enumerate() {
            let on_ground = self.point_links[p].contains(&self.ground);
            let links: Vec<usize> = self.point_links[p].iter().copied().filter(|&l| l != self.ground).collect();
            let first = if on_ground { usize::MAX } else { links[0] };
            if !on_ground {
                *own = Some(first);
            }
            for &l in links.iter().skip(usize::from(!on_ground)) {
                rows.push((p, l, first));
            }
        }
        let (m, n) = (2 * rows.len() + self.slots.len() + 2 * self.prismatic.len() + 1, 3 * moving.len());
        if m != n {
            return Err(Error::scene("gradient", format!("{m} equations for {n} unknowns: not one degree of freedom")));
        }
        Ok(Layout { moving, block, rows, owner, fcol, relative })
    }

    /// One pose into `out`; false where it is not finite or singular.
    fn gradient_into(&self, lay: &Layout, pos: &[Xy], nf: usize, out: &mut [f64]) -> bool {
        if pos.iter().any(|p| !(p[0].is_finite() && p[1].is_finite())) {
            return false;
        }
        // solving frame: positions and drawn coordinates divided by the scale (derivatives
        // of lengths by lengths are scale-free)
        let xi = &self.xy;
        let at = |p: usize| self.to_frame(pos[p]);
        let origin = |l: usize| self.links[l].points[0];
        // each moving link's rotation from the drawn pose, as (cos, sin)
        let mut cs = vec![[1.0, 0.0]; self.links.len()];
        for &l in &lay.moving {
            let pts = &self.links[l].points;
            let (a, b) = (pts[0], pts[1]);
            let (d, e) = (sub(at(b), at(a)), sub(xi[b], xi[a]));
            let (sn, c) = (d[1].atan2(d[0]) - e[1].atan2(e[0])).sin_cos();
            cs[l] = [c, sn];
        }
        let turn = |l: usize, v: Xy| [cs[l][0] * v[0] - cs[l][1] * v[1], cs[l][1] * v[0] + cs[l][0] * v[1]];
        let n = 3 * lay.moving.len();
        let mut gx = DMatrix::<f64>::zeros(n, n);
        let mut gxi = DMatrix::<f64>::zeros(n, nf);
        // R d w of p's drawn vector on link l, w = xi_p - xi_o: for each free coordinate f
        // of p or o, add(f, R e) with e its change of w (times sg); nothing where p is the
        // origin (w is 0 whatever the drawing)
        let drawn = |p: usize, l: usize, sg: f64, add: &mut dyn FnMut(usize, Xy)| {
            if p == origin(l) {
                return;
            }
            for (q, sq) in [(p, 1.0), (origin(l), -1.0)] {
                for j in 0..2 {
                    if let Some(f) = lay.fcol[q][j] {
                        let mut e = [0.0; 2];
                        e[j] = sg * sq;
                        add(f, turn(l, e));
                    }
                }
            }
        };
        // d pos_l(p) = d t_l + perp(R w) d phi_l + R d w, w = xi_p - xi_o, into row r, sign sg
        let body = |r: usize, p: usize, l: usize, sg: f64, gx: &mut DMatrix<f64>, gxi: &mut DMatrix<f64>| {
            let c = lay.block[l];
            let pw = perp(turn(l, sub(xi[p], xi[origin(l)])));
            for k in 0..2 {
                gx[(r + k, c + k)] += sg;
                gx[(r + k, c + 2)] += sg * pw[k];
            }
            drawn(p, l, sg, &mut |f, re| {
                gxi[(r, f)] += re[0];
                gxi[(r + 1, f)] += re[1];
            });
        };
        for (i, &(p, l, owner)) in lay.rows.iter().enumerate() {
            let r = 2 * i;
            body(r, p, l, 1.0, &mut gx, &mut gxi);
            if owner == usize::MAX {
                for k in 0..2 {
                    if let Some(f) = lay.fcol[p][k] {
                        gxi[(r + k, f)] -= 1.0;
                    }
                }
            } else {
                body(r, p, owner, -1.0, &mut gx, &mut gxi);
            }
        }
        // c . d(position of p read through link l) into row r; through ground, p moves only
        // with its own drawing
        let point_dot = |r: usize, p: usize, l: usize, c: Xy, gx: &mut DMatrix<f64>, gxi: &mut DMatrix<f64>| {
            if l == self.ground {
                for (fc, ck) in lay.fcol[p].iter().zip(c) {
                    if let Some(f) = *fc {
                        gxi[(r, f)] += ck;
                    }
                }
                return;
            }
            let col = lay.block[l];
            let pw = perp(turn(l, sub(xi[p], xi[origin(l)])));
            gx[(r, col)] += c[0];
            gx[(r, col + 1)] += c[1];
            gx[(r, col + 2)] += c[0] * pw[0] + c[1] * pw[1];
            drawn(p, l, 1.0, &mut |f, re| gxi[(r, f)] += c[0] * re[0] + c[1] * re[1]);
        };
        // point p (read through link l) on the line (a, b) of guide g at its drawn offset:
        // cross(R_g v0, pos(p) - pos_g(a)) - cross(v0, xi_p - xi_a) = 0, v0 = xi_b - xi_a
        // (not normalised: the row is zero at the solution, so its scale does not matter)
        type Line = (usize, (usize, usize));
        let on_line =
            |r: usize, (p, l): (usize, usize), (g, (a, b)): Line, gx: &mut DMatrix<f64>, gxi: &mut DMatrix<f64>| {
                let v0 = sub(xi[b], xi[a]);
                let vg = if g == self.ground { v0 } else { turn(g, v0) };
                let d = sub(at(p), at(a));
                let c = perp(vg); // cross(vg, y) = perp(vg) . y
                point_dot(r, p, l, c, gx, gxi);
                point_dot(r, a, g, [-c[0], -c[1]], gx, gxi);
                if g != self.ground {
                    gx[(r, lay.block[g] + 2)] += cross(perp(vg), d);
                }
                let w0 = sub(xi[p], xi[a]);
                for (q, sq) in [(b, 1.0), (a, -1.0)] {
                    for j in 0..2 {
                        if let Some(f) = lay.fcol[q][j] {
                            let mut e = [0.0; 2];
                            e[j] = sq;
                            let re = if g == self.ground { e } else { turn(g, e) };
                            gxi[(r, f)] += cross(re, d) - cross(e, w0);
                        }
                    }
                }
                for (q, sq) in [(p, 1.0), (a, -1.0)] {
                    for j in 0..2 {
                        if let Some(f) = lay.fcol[q][j] {
                            let mut e = [0.0; 2];
                            e[j] = sq;
                            gxi[(r, f)] -= cross(v0, e);
                        }
                    }
                }
            };
        let slot_rows = 2 * lay.rows.len();
        for (i, s) in self.slots.iter().enumerate() {
            let l = lay.owner[s.point].unwrap_or(self.ground);
            on_line(slot_rows + i, (s.point, l), (s.guide, s.line), &mut gx, &mut gxi);
        }
        for (i, pr) in self.prismatic.iter().enumerate() {
            let r = slot_rows + self.slots.len() + 2 * i;
            on_line(r, (origin(pr.link), pr.link), (pr.guide, pr.line), &mut gx, &mut gxi);
            // the link keeps its drawn rotation relative to the guide
            gx[(r + 1, lay.block[pr.link] + 2)] += 1.0;
            if pr.guide != self.ground {
                gx[(r + 1, lay.block[pr.guide] + 2)] -= 1.0;
            }
        }
        // the input: phi_in + theta0(xi) - theta = 0 (theta0 the drawn input angle)
        let input = self.input.expect("checked by the layout");
        let r = n - 1;
        gx[(r, lay.block[input.link] + 2)] = 1.0;
        let d = sub(xi[input.tip], xi[input.pivot]);
        let d2 = d[0] * d[0] + d[1] * d[1];
        let dtheta = [-d[1] / d2, d[0] / d2];
        for (q, sq) in [(input.tip, 1.0), (input.pivot, -1.0)].into_iter().filter(|_| !lay.relative) {
            for (k, dt) in dtheta.iter().enumerate() {
                if let Some(f) = lay.fcol[q][k] {
                    gxi[(r, f)] += sq * dt;
                }
            }
        }
        gxi.neg_mut();
        if !gx.lu().solve_mut(&mut gxi) || !gxi.iter().all(|v| v.is_finite()) {
            return false;
        }
        let dx = gxi;
        // the points: through their owner (ground points move only with their own drawing)
        for (p, owner) in lay.owner.iter().enumerate() {
            let o = &mut out[p * 2 * nf..(p + 1) * 2 * nf];
            let Some(l) = *owner else {
                o.fill(0.0);
                for k in 0..2 {
                    if let Some(f) = lay.fcol[p][k] {
                        o[k * nf + f] = 1.0;
                    }
                }
                continue;
            };
            let c = lay.block[l];
            let pw = perp(turn(l, sub(xi[p], xi[origin(l)])));
            for f in 0..nf {
                for k in 0..2 {
                    o[k * nf + f] = dx[(c + k, f)] + pw[k] * dx[(c + 2, f)];
                }
            }
            drawn(p, l, 1.0, &mut |f, re| {
                o[f] += re[0];
                o[nf + f] += re[1];
            });
        }
        true
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::scene::model::{PrismaticSpec, SceneSpec, SlotSpec};

    /// An offset slider-crank with a coupler point P on the rod: B in a slot on the ground
    /// line O2 -> X, or (`prismatic`) carried by a block sliding along it.
    fn slider(xy: &[Xy], prismatic: bool) -> Scene {
        let names = ["O2", "X", "A", "B", "P", "Q"];
        let n = if prismatic { 6 } else { 5 };
        let s = |v: &[&str]| v.iter().map(|p| p.to_string()).collect::<Vec<_>>();
        let mut links = vec![
            ("ground".to_string(), s(&["O2", "X"])),
            ("crank".to_string(), s(&["O2", "A"])),
            ("rod".to_string(), s(&["A", "B", "P"])),
        ];
        let line = ("O2".to_string(), "X".to_string());
        let mut spec = SceneSpec {
            points: names[..n].iter().zip(xy).map(|(a, p)| (a.to_string(), *p)).collect(),
            ground: "ground".into(),
            input: ("crank".into(), "O2".into()),
            ..Default::default()
        };
        if prismatic {
            links.push(("block".to_string(), s(&["B", "Q"])));
            let pr = PrismaticSpec { link: "block".into(), guide: "ground".into(), line };
            spec.prismatic = vec![("piston".into(), pr)];
        } else {
            let sl = SlotSpec { point: "B".into(), guide: "ground".into(), line };
            spec.slots = vec![("piston".into(), sl)];
        }
        spec.links = links;
        Scene::new(spec).unwrap()
    }

    /// The closed form of the pose at absolute crank angle t, from the drawn coordinates.
    fn pose(xy: &[Xy], t: f64) -> Vec<Xy> {
        let (o, x, a0, b0, p0) = (xy[0], xy[1], xy[2], xy[3], xy[4]);
        let ul = sub(x, o);
        let len = ul[0].hypot(ul[1]);
        let u = [ul[0] / len, ul[1] / len];
        let nrm = perp(u);
        let dot = |a: Xy, b: Xy| a[0] * b[0] + a[1] * b[1];
        let r = sub(a0, o)[0].hypot(sub(a0, o)[1]);
        let l = sub(b0, a0)[0].hypot(sub(b0, a0)[1]);
        let e = dot(sub(b0, o), nrm);
        let side = dot(sub(b0, a0), u).signum();
        let a = [o[0] + r * t.cos(), o[1] + r * t.sin()];
        let (sa, ha) = (dot(sub(a, o), u), dot(sub(a, o), nrm));
        let sb = sa + side * (l * l - (e - ha) * (e - ha)).sqrt();
        let b = [o[0] + sb * u[0] + e * nrm[0], o[1] + sb * u[1] + e * nrm[1]];
        let (d0, d) = (sub(b0, a0), sub(b, a));
        let phi = d[1].atan2(d[0]) - d0[1].atan2(d0[0]);
        let (sn, c) = phi.sin_cos();
        let w = sub(p0, a0);
        let p = [a[0] + c * w[0] - sn * w[1], a[1] + sn * w[0] + c * w[1]];
        let mut out = vec![o, x, a, b, p];
        if xy.len() > 5 {
            out.push([b[0] + xy[5][0] - b0[0], b[1] + xy[5][1] - b0[1]]);
        }
        out
    }

    #[test]
    fn slider_crank_pose_gradient_matches_central_differences_of_the_closed_form() {
        let (o, x) = ([0.3, -0.2], [1.4, 0.1]);
        let a = [0.3 + 0.4 * 1.1f64.cos(), -0.2 + 0.4 * 1.1f64.sin()];
        // B on the line through O2 and X at offset 0.15, 1.3 from A
        let ul = sub(x, o);
        let len = ul[0].hypot(ul[1]);
        let (u, nrm) = ([ul[0] / len, ul[1] / len], perp([ul[0] / len, ul[1] / len]));
        let ha = (a[0] - o[0]) * nrm[0] + (a[1] - o[1]) * nrm[1];
        let sa = (a[0] - o[0]) * u[0] + (a[1] - o[1]) * u[1];
        let sb = sa + (1.3f64.powi(2) - (0.15 - ha).powi(2)).sqrt();
        let b = [o[0] + sb * u[0] + 0.15 * nrm[0], o[1] + sb * u[1] + 0.15 * nrm[1]];
        let p = [0.9, 0.7];
        for prismatic in [false, true] {
            let mut xy = vec![o, x, a, b, p];
            if prismatic {
                xy.push([b[0] + 0.2, b[1] + 0.3]);
            }
            let sc = slider(&xy, prismatic);
            let np = xy.len();
            let free: Vec<Free> = (0..np).flat_map(|q| [(q, 0), (q, 1)]).collect();
            for t in [0.3, 2.0, 4.0] {
                let g = sc.pose_gradient(&pose(&xy, t), &free).unwrap().unwrap();
                let h = 1e-6;
                for (f, &(q, k)) in free.iter().enumerate() {
                    let (mut hi, mut lo) = (xy.clone(), xy.clone());
                    hi[q][k] += h;
                    lo[q][k] -= h;
                    let (ph, pl) = (pose(&hi, t), pose(&lo, t));
                    for i in 0..np {
                        for c in 0..2 {
                            let fd = (ph[i][c] - pl[i][c]) / (2.0 * h);
                            let ex = g[(i * 2 + c) * free.len() + f];
                            assert!((fd - ex).abs() < 1e-7, "{prismatic} t {t} point {i}.{c} by {q}.{k}: {ex} vs {fd}");
                        }
                    }
                }
            }
        }
    }
}
