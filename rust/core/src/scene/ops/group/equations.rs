//! A group's loop-closure equations: residuals and Jacobian at given unknowns, their
//! rate by the input, second derivatives, and the generic Newton system over them.
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

use super::{Group, Term, Turn, HELD, MAX};
use crate::scene::vec2::{cmul, perp, sub, Xy};
use crate::solve::newton::{self, hadamard_ratio, System};
use crate::wrap_angle;

impl Group {
    /// (cos, sin) of the rotation columns, all at once (4 at a time where the SIMD kernels
    /// are on: see [`cs_of`]).
    #[inline]
    pub(super) fn turns(&self, x: &[f64], buf: &mut [Xy; MAX]) -> usize {
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
    pub(super) fn closure_terms_with(
        &self,
        x: &[f64],
        cs: &[Xy],
        anchors: &[Xy],
        mut f: impl FnMut(usize, f64),
        mut j: impl FnMut(usize, usize, f64),
    ) {
        let held = self.held_of(anchors);
        for (c, cl) in self.closures.iter().enumerate() {
            let d = sub(anchors[cl.plus], anchors[cl.minus]);
            let (mut fx, mut fy) = (d[0], d[1]);
            for t in &cl.terms {
                let m = t.m(cs, anchors);
                let r = cmul(m, t.arm(x, held));
                fx += r[0];
                fy += r[1];
                if let Turn::Col(k) = t.turn {
                    j(2 * c, k, -r[1]);
                    j(2 * c + 1, k, r[0]);
                }
                // (a held slide is the input, not an unknown: no column)
                if let Some((k, dv)) = t.slide.filter(|s| s.0 != HELD) {
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
    pub(super) fn rate_terms(&self, x: &[f64], cs: &[Xy], anchors: &[Xy], anchor_d: &[Xy]) -> [Xy; MAX] {
        let (held, dheld) = (self.held_of(anchors), self.held_of(anchor_d));
        let mut out = [[0.0; 2]; MAX];
        for (c, cl) in self.closures.iter().enumerate().take(MAX) {
            let mut r = sub(anchor_d[cl.plus], anchor_d[cl.minus]);
            for t in &cl.terms {
                if let Turn::Known(a, b) = t.turn {
                    let w = cmul(sub(anchor_d[b], anchor_d[a]), t.arm(x, held));
                    r = [r[0] + w[0], r[1] + w[1]];
                }
                if let Some((HELD, d)) = t.slide {
                    let w = cmul(t.m(cs, anchors), [dheld * d[0], dheld * d[1]]);
                    r = [r[0] + w[0], r[1] + w[1]];
                }
            }
            out[c] = r;
        }
        out
    }

    /// Signed Hadamard ratio of the group's Jacobian at unknowns `x`.
    pub(crate) fn conditioning_with(&self, x: &[f64], anchors: &[Xy]) -> f64 {
        dispatch!(self.n(), cond_n, self, anchors, x)
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
    pub(super) fn term_curvature(&self, t: &Term, cs: &[Xy], dx: &[f64], x: &[f64], k: [&[Xy]; 3]) -> Xy {
        // (a held slide's s'' is 0: the input moves at a constant rate)
        let arm = t.arm(x, self.held_of(k[0]));
        let sd = t.slide_rate(dx, self.held_of(k[1])).map_or([0.0; 2], |(w, d)| [w * d[0], w * d[1]]);
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
    pub(super) fn term_rate(&self, t: &Term, m: Xy, arm: Xy, dx: &[f64], anchor_vel: &[Xy]) -> Xy {
        let sd = t.slide_rate(dx, self.held_of(anchor_vel)).map_or([0.0; 2], |(w, d)| cmul(m, [w * d[0], w * d[1]]));
        let turn = match t.turn {
            Turn::Col(c) => {
                let r = perp(cmul(m, arm));
                [dx[c] * r[0], dx[c] * r[1]]
            }
            Turn::Known(a, b) => cmul(sub(anchor_vel[b], anchor_vel[a]), arm),
        };
        [turn[0] + sd[0], turn[1] + sd[1]]
    }
}

/// (cos, sin) of a rotation: the polynomial within 2 ulp of libm where the SIMD kernels
/// are on ([`crate::simd::sin_cos`]; about a third of libm's cost, and a group's
/// evaluations take a dozen a step), libm otherwise.
#[inline]
pub(super) fn cs_of(a: f64) -> Xy {
    let (s, c) = crate::simd::sin_cos(a);
    [c, s]
}

/// The group's loop equations at fixed anchors, as a Newton system.
pub(super) struct At<'a> {
    pub(super) g: &'a Group,
    pub(super) anchors: &'a [Xy],
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

pub(super) fn cond_n<const N: usize>(g: &Group, anchors: &[Xy], x: &[f64]) -> f64 {
    let x = SVector::<f64, N>::from_fn(|k, _| x[k]);
    let (_, j) = System::<N>::eval(&At { g, anchors }, &x);
    hadamard_ratio(&j)
}

pub(super) fn second_n<const N: usize>(g: &Group, x: &[f64], dx: &[f64], k: [&[Xy]; 3]) -> Option<[f64; MAX]> {
    let xs = SVector::<f64, N>::from_fn(|i, _| x[i]);
    let (_, j) = System::<N>::eval(&At { g, anchors: k[0] }, &xs);
    let cs: Vec<Xy> = x[..g.nrot].iter().map(|a| cs_of(*a)).collect();
    let mut rhs = SVector::<f64, N>::zeros();
    for (c, cl) in g.closures.iter().enumerate() {
        let mut r = sub(k[2][cl.plus], k[2][cl.minus]);
        for t in &cl.terms {
            let q = g.term_curvature(t, &cs, dx, x, k);
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
