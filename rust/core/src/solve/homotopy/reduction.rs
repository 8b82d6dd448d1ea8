//! The reduction of the closure equations to the homotopy's unknowns: the linear part
//! eliminated (`z = z0 + K t`), the isotropic form of loop equations with its
//! linear-product start system, and the finishing Newton steps (affine and real polish).

use nalgebra::{DMatrix, DVector};

use super::lu::lu_solve;
use super::{Quadric, C};
use crate::rng::SplitMix64;
use crate::wrap_angle;
use crate::Error;

/// The system after eliminating the linear part: `z = P (x0, x)` with `P = [z0 | K]`.
pub(super) struct Reduced {
    /// Number of quadrics (and of path coordinates t).
    pub(super) n: usize,
    /// Number of unknowns z (2N for unit circles alone).
    pub(super) d: usize,
    pub(super) quads: Vec<Quadric>,
    /// D x (N + 1), row major: column 0 is z0, columns 1..=N are K.
    pub(super) p: Vec<f64>,
    /// Row-scaled `A` and `b` (same solutions), for the real polish.
    pub(super) a: DMatrix<f64>,
    pub(super) b: DVector<f64>,
    /// The isotropic form with its linear-product start system, for loop equations.
    pub(super) iso: Option<Iso>,
}

/// Loop equations in isotropic coordinates (Wampler): a closure's two rows are one complex
/// equation sum_j u_j e_j = beta in e_j = c_j + i s_j, and its conjugate in
/// ebar_j = c_j - i s_j, so e = e0 + K t and ebar = conj(e0) + conj(K) u with t, u of
/// C = N/2 coordinates each, and the circles are the N bilinear equations e_j ebar_j = 1.
/// Their two-homogeneous Bezout number, C(N, N/2) (20 for the double butterfly's six
/// links, against 2^6 = 64 for total degree), is the number of paths of the
/// linear-product start system G_j = L_j(t) M_j(u) (random linear factors): a start point
/// takes L_j = 0 for N/2 of the equations and M_j = 0 for the others.
pub(super) struct Iso {
    pub(super) c: usize,
    /// N x (C + 1), row major: e_j = pe_j . (x0, t).
    pub(super) pe: Vec<C>,
    /// N x (C + 1): ebar_j = pb_j . (x0, u).
    pub(super) pb: Vec<C>,
    /// N x (C + 1): the start system's factors L_j = la_j . (x0, t), M_j = lb_j . (x0, u).
    pub(super) la: Vec<C>,
    pub(super) lb: Vec<C>,
    /// Start points X = (x0, t, u), unit norm.
    pub(super) starts: Vec<Vec<C>>,
}

/// How one path ended.
impl Reduced {
    pub(super) fn new(a: &DMatrix<f64>, b: &DVector<f64>, quads: Vec<Quadric>) -> Result<Self, Error> {
        let (l, d) = (a.nrows(), a.ncols());
        let n = d - l;
        let mut a_s = a.clone();
        let mut b_s = b.clone();
        for i in 0..l {
            let s = a.row(i).amax();
            if s == 0.0 {
                return Err(Error::invalid("a", "must have full row rank", format!("row {i} is zero")));
            }
            a_s.row_mut(i).scale_mut(1.0 / s);
            b_s[i] /= s;
        }
        // never hand the SVD a non-finite entry
        if let Some(v) = b_s.iter().find(|v| !v.is_finite()) {
            return Err(Error::invalid("b", "must be finite after dividing each row by its largest |a|", v));
        }
        // Pad to square so the SVD returns a full V^T: its N rows of zero singular value
        // span the null space of A.
        let mut m = DMatrix::<f64>::zeros(d, d);
        m.rows_mut(0, l).copy_from(&a_s);
        // bounded iterations (plain `svd` iterates until convergence)
        let svd = m
            .try_svd(true, true, 5.0 * f64::EPSILON, 10_000)
            .ok_or_else(|| Error::invalid("a", "must have a computable SVD", "no convergence in 10000 sweeps"))?;
        let (Some(u), Some(vt)) = (svd.u.as_ref(), svd.v_t.as_ref()) else {
            return Err(Error::invalid("a", "must have a computable SVD", "SVD failed"));
        };
        let sv = &svd.singular_values;
        let mut order: Vec<usize> = (0..d).collect();
        order.sort_by(|&i, &j| sv[j].total_cmp(&sv[i]));
        let smax = sv[order[0]];
        let smin = sv[order[l - 1]];
        if smin.is_nan() || smin <= 1e-10 * smax {
            return Err(Error::invalid(
                "a",
                "must have full row rank (independent closure equations)",
                format!("sigma_min / sigma_max = {:e}", smin / smax),
            ));
        }
        let mut z0 = vec![0.0; d];
        for &k in &order[..l] {
            let mut ub = 0.0;
            for i in 0..l {
                ub += u[(i, k)] * b_s[i];
            }
            let coef = ub / sv[k];
            for (r, zr) in z0.iter_mut().enumerate() {
                *zr += coef * vt[(k, r)];
            }
        }
        let cols = n + 1;
        let mut p = vec![0.0; d * cols];
        for r in 0..d {
            p[r * cols] = z0[r];
            for (c, &k) in order[l..].iter().enumerate() {
                p[r * cols + 1 + c] = vt[(k, r)];
            }
        }
        Ok(Self { n, d, quads, p, a: a_s, b: b_s, iso: None })
    }

    /// The isotropic form of unit-circle loop equations `a z = b` whose rows pair as the x
    /// and y parts of complex closures (as a group's `linear_form` writes them), with its
    /// start system from `seed`; `None` for any other `a` (or N odd).
    pub(super) fn isotropic(a: &DMatrix<f64>, b: &DVector<f64>, seed: u64) -> Result<Option<Self>, Error> {
        let n = a.nrows();
        let paired = n.is_multiple_of(2)
            && (0..n / 2).all(|c| {
                (0..n).all(|k| a[(2 * c, n + k)] == -a[(2 * c + 1, k)] && a[(2 * c + 1, n + k)] == a[(2 * c, k)])
            });
        if !paired {
            return Ok(None);
        }
        let circles: Vec<Quadric> = (0..n).map(|j| Quadric::Circle { c: j, s: n + j }).collect();
        // the real reduction is kept for the real polish and the checks it makes
        let mut red = Self::new(a, b, circles)?;
        let nc = n / 2;
        // complex rows, each scaled to unit max-norm
        let mut u = nalgebra::DMatrix::<C>::zeros(n, n);
        let mut beta = nalgebra::DVector::<C>::zeros(n);
        for c in 0..nc {
            let row: Vec<C> = (0..n).map(|k| C::new(a[(2 * c, k)], a[(2 * c + 1, k)])).collect();
            let scale = row.iter().map(|v| v.norm()).fold(0.0, f64::max);
            for (k, v) in row.iter().enumerate() {
                u[(c, k)] = v / scale;
            }
            beta[c] = C::new(b[2 * c], b[2 * c + 1]) / scale;
        }
        let Some(svd) = u.try_svd(true, true, 5.0 * f64::EPSILON, 10_000) else {
            return Ok(None);
        };
        let (Some(uu), Some(vt)) = (svd.u.as_ref(), svd.v_t.as_ref()) else { return Ok(None) };
        let sv = &svd.singular_values;
        let mut order: Vec<usize> = (0..n).collect();
        order.sort_by(|&i, &j| sv[j].total_cmp(&sv[i]));
        if !(sv[order[nc - 1]] > 1e-10 * sv[order[0]]) {
            return Ok(None);
        }
        // e0 = V S^-1 U^H beta (minimum norm), K = the null rows of V^H, conjugated
        let mut e0 = vec![C::default(); n];
        for &k in &order[..nc] {
            let mut ub = C::default();
            for i in 0..nc {
                ub += uu[(i, k)].conj() * beta[i];
            }
            let coef = ub / sv[k];
            for (r, er) in e0.iter_mut().enumerate() {
                *er += coef * vt[(k, r)].conj();
            }
        }
        let cols = nc + 1;
        let mut pe = vec![C::default(); n * cols];
        let mut pb = vec![C::default(); n * cols];
        for r in 0..n {
            pe[r * cols] = e0[r];
            pb[r * cols] = e0[r].conj();
            for (c, &k) in order[nc..].iter().enumerate() {
                pe[r * cols + 1 + c] = vt[(k, r)].conj();
                pb[r * cols + 1 + c] = vt[(k, r)];
            }
        }
        let mut rng = SplitMix64(seed ^ 0x150_7407_1C00);
        let mut draw = || C::new(2.0 * rng.uniform() - 1.0, 2.0 * rng.uniform() - 1.0);
        let la: Vec<C> = (0..n * cols).map(|_| draw()).collect();
        let lb: Vec<C> = (0..n * cols).map(|_| draw()).collect();
        // start points: every choice of N/2 equations whose L vanishes (M for the rest)
        let mut starts = Vec::new();
        for mask in 0..(1usize << n) {
            if mask.count_ones() as usize != nc {
                continue;
            }
            let solve = |coef: &[C], rows: &mut dyn Iterator<Item = usize>| -> Option<Vec<C>> {
                let mut m = vec![C::default(); nc * nc];
                let mut rhs = vec![C::default(); nc];
                for (i, j) in rows.enumerate() {
                    rhs[i] = -coef[j * cols];
                    m[i * nc..(i + 1) * nc].copy_from_slice(&coef[j * cols + 1..(j + 1) * cols]);
                }
                lu_solve(&mut m, nc, &mut rhs).then_some(rhs)
            };
            let t = solve(&la, &mut (0..n).filter(|j| mask >> j & 1 == 1));
            let w = solve(&lb, &mut (0..n).filter(|j| mask >> j & 1 == 0));
            let (Some(t), Some(w)) = (t, w) else { return Ok(None) };
            let mut x: Vec<C> = std::iter::once(C::new(1.0, 0.0)).chain(t).chain(w).collect();
            let norm = x.iter().map(|v| v.norm_sqr()).sum::<f64>().sqrt();
            for v in &mut x {
                *v /= norm;
            }
            starts.push(x);
        }
        red.iso = Some(Iso { c: nc, pe, pb, la, lb, starts });
        Ok(Some(red))
    }

    /// Paths of one run.
    pub(super) fn paths(&self) -> usize {
        self.iso.as_ref().map_or(1usize << self.n, |iso| iso.starts.len())
    }

    /// z = z0 + K t (or, in isotropic form, c = (e + ebar) / 2, s = (e - ebar) / 2i).
    pub(super) fn z_of(&self, t: &[C]) -> Vec<C> {
        if let Some(iso) = &self.iso {
            let (e, eb) = iso.e_ebar(C::new(1.0, 0.0), t);
            let half = C::new(0.5, 0.0);
            let c: Vec<C> = e.iter().zip(&eb).map(|(a, b)| (a + b) * half).collect();
            let s: Vec<C> = e.iter().zip(&eb).map(|(a, b)| (a - b) * C::new(0.0, -0.5)).collect();
            return c.into_iter().chain(s).collect();
        }
        let cols = self.n + 1;
        (0..self.d)
            .map(|r| {
                let row = &self.p[r * cols..(r + 1) * cols];
                let mut s = C::new(row[0], 0.0);
                for k in 0..self.n {
                    s += t[k] * row[k + 1];
                }
                s
            })
            .collect()
    }
}

impl Reduced {
    /// Newton on the affine target q(t) = 0 from `t0`: the root if it converges near `t0`
    /// with a small residual.
    pub(super) fn affine_newton(&self, t0: &[C]) -> Option<Vec<C>> {
        let n = self.n;
        let cols = n + 1;
        let mut t = t0.to_vec();
        let mut jac = vec![C::default(); n * n];
        let mut rhs = vec![C::default(); n];
        let mut last = f64::INFINITY;
        for _ in 0..60 {
            let z = self.z_of(&t);
            let mut res = 0.0_f64;
            let row_of = |i: usize| &self.p[i * cols + 1..(i + 1) * cols];
            if let Some(iso) = &self.iso {
                res = iso.affine_terms(&t, &mut jac, &mut rhs);
            }
            for j in (0..n).filter(|_| self.iso.is_none()) {
                match self.quads[j] {
                    Quadric::Circle { c: ic, s: is } => {
                        let (c, s) = (z[ic], z[is]);
                        rhs[j] = -(c * c + s * s - 1.0);
                        let (rc, rs) = (row_of(ic), row_of(is));
                        for k in 0..n {
                            jac[j * n + k] = c * (2.0 * rc[k]) + s * (2.0 * rs[k]);
                        }
                    }
                    Quadric::Bilinear { a, b, c, d } => {
                        rhs[j] = -(z[a] * z[b] - z[c] * z[d]);
                        let (ra, rb, rc, rd) = (row_of(a), row_of(b), row_of(c), row_of(d));
                        for k in 0..n {
                            jac[j * n + k] = z[a] * rb[k] + z[b] * ra[k] - z[c] * rd[k] - z[d] * rc[k];
                        }
                    }
                }
                res = res.max(rhs[j].norm());
            }
            if !res.is_finite() || !lu_solve(&mut jac, n, &mut rhs) {
                return None;
            }
            let d = rhs.iter().map(|v| v.norm()).fold(0.0, f64::max);
            for k in 0..n {
                t[k] += rhs[k];
            }
            let tn = t.iter().map(|v| v.norm()).fold(1.0, f64::max);
            // Converged, or stagnating at the rounding floor: ~eps / conditioning for a simple
            // root, ~sqrt(eps) for a double one (the residual check below still applies).
            if d <= 1e-14 * tn || (d <= 1e-6 * tn && d >= 0.5 * last) {
                let dist = t.iter().zip(t0).map(|(a, b)| (a - b).norm()).fold(0.0, f64::max);
                let zmax = self.z_of(&t).iter().map(|v| v.norm()).fold(1.0, f64::max);
                let ok = dist <= 1e-3 * tn && res <= 1e-8 * zmax * zmax;
                return ok.then_some(t);
            }
            last = d;
        }
        None
    }

    /// Real Newton in the angles on the row-scaled `A z(phi) = b`, from the real part of a
    /// nearly real root `z`: the polished angles in (-pi, pi], or `None` when it does not
    /// converge to a real root near `z`.
    pub(super) fn real_polish(&self, z: &[C]) -> Option<Vec<f64>> {
        let n = self.n;
        let phi0: Vec<f64> = (0..n).map(|j| z[n + j].re.atan2(z[j].re)).collect();
        let mut phi = phi0.clone();
        let mut last = f64::INFINITY;
        for _ in 0..30 {
            let (s, c): (Vec<f64>, Vec<f64>) = phi.iter().map(|p| p.sin_cos()).unzip();
            let mut jac = DMatrix::<f64>::zeros(n, n);
            let mut r = DVector::<f64>::zeros(n);
            for i in 0..n {
                let mut v = -self.b[i];
                for j in 0..n {
                    let (ac, as_) = (self.a[(i, j)], self.a[(i, n + j)]);
                    v += ac * c[j] + as_ * s[j];
                    jac[(i, j)] = -ac * s[j] + as_ * c[j];
                }
                r[i] = -v;
            }
            let d = jac.lu().solve(&r)?;
            let step = d.amax();
            if !step.is_finite() {
                return None;
            }
            for j in 0..n {
                phi[j] += d[j];
            }
            // As in `affine_newton`: a double root (dead point) stagnates near sqrt(eps).
            if step <= 1e-15 || (step <= 1e-6 && step >= 0.5 * last) {
                let res = self.real_residual(&phi);
                let moved = phi.iter().zip(&phi0).map(|(a, b)| wrap_angle(a - b).abs()).fold(0.0, f64::max);
                return (res <= 1e-12 && moved <= 1e-4).then(|| phi.iter().map(|&p| wrap_angle(p)).collect());
            }
            last = step;
        }
        None
    }

    /// max |A z(phi) - b| on the row-scaled system.
    pub(super) fn real_residual(&self, phi: &[f64]) -> f64 {
        let n = self.n;
        let mut res = 0.0_f64;
        for i in 0..n {
            let mut v = -self.b[i];
            for (j, p) in phi.iter().enumerate() {
                let (s, c) = p.sin_cos();
                v += self.a[(i, j)] * c + self.a[(i, n + j)] * s;
            }
            res = res.max(v.abs());
        }
        res
    }
}

impl Iso {
    /// e and ebar at projective coordinates (x0, t, u) = (`x0`, `tu`).
    pub(super) fn e_ebar(&self, x0: C, tu: &[C]) -> (Vec<C>, Vec<C>) {
        let n = 2 * self.c;
        let mut out = vec![C::default(); 2 * n];
        self.e_ebar_into(self.c, x0, tu, &mut out);
        let eb = out.split_off(n);
        (out, eb)
    }

    /// [`Iso::e_ebar`] into `out` (e, then ebar), no allocation: the tracker's hot path.
    #[inline(always)]
    pub(super) fn e_ebar_into(&self, nc: usize, x0: C, tu: &[C], out: &mut [C]) {
        let cols = nc + 1;
        let n = 2 * nc;
        let dotp = |p: &[C], w: &[C]| p[0] * x0 + p[1..].iter().zip(w).map(|(a, b)| a * b).sum::<C>();
        let (e, eb) = out.split_at_mut(n);
        for j in 0..n {
            e[j] = dotp(&self.pe[j * cols..(j + 1) * cols], &tu[..nc]);
            eb[j] = dotp(&self.pb[j * cols..(j + 1) * cols], &tu[nc..]);
        }
    }

    /// Residuals -(e_j ebar_j - 1) into `rhs` and their Jacobian in (t, u) into `jac` at
    /// affine `tu`; returns the largest residual.
    pub(super) fn affine_terms(&self, tu: &[C], jac: &mut [C], rhs: &mut [C]) -> f64 {
        let (nc, cols) = (self.c, self.c + 1);
        let n = 2 * nc;
        let one = C::new(1.0, 0.0);
        let (e, eb) = self.e_ebar(one, tu);
        let mut res = 0.0_f64;
        for j in 0..n {
            rhs[j] = -(e[j] * eb[j] - one);
            res = res.max(rhs[j].norm());
            for k in 0..nc {
                jac[j * n + k] = self.pe[j * cols + 1 + k] * eb[j];
                jac[j * n + nc + k] = e[j] * self.pb[j * cols + 1 + k];
            }
        }
        res
    }
}
