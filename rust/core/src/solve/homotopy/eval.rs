//! The homotopy `H(X, tau)` at a point: its residual, its Jacobian in the projective
//! coordinates and its tau-derivative (the tracker's hot path), and the path tangent.

use super::lu::lu_solve;
use super::reduction::{Iso, Reduced};
use super::{Quadric, C};

/// Scratch buffers of one path (no allocation inside the step loop).
pub(super) struct Work {
    /// Predictor-corrector steps taken (accepted and rejected), all paths of the run.
    pub(super) steps: usize,
    pub(super) m: usize,
    pub(super) jac: Vec<C>,
    pub(super) rhs: Vec<C>,
    pub(super) w: Vec<C>,
}

impl Reduced {
    /// A path's linear-algebra buffers.
    pub(super) fn work(&self) -> Work {
        let m = self.n + 1;
        Work { steps: 0, m, jac: vec![C::default(); m * m], rhs: vec![C::default(); m], w: vec![C::default(); self.d] }
    }

    /// Homotopy residual (rows 0..N, plus the patch row N) into `work.rhs` and its
    /// Jacobian in X into `work.jac`; with `dtau`, `rhs` gets H_tau instead (patch row 0).
    pub(super) fn eval(&self, x: &[C], tau: f64, gamma: C, patch: &[C], work: &mut Work, dtau: bool) {
        if let Some(iso) = &self.iso {
            iso.eval(x, tau, gamma, work, dtau);
            Self::patch_row(self.n, x, patch, work, dtau);
            return;
        }
        let n = self.n;
        let m = work.m;
        for r in 0..self.d {
            let row = &self.p[r * m..(r + 1) * m];
            let mut s = C::default();
            for k in 0..m {
                s += x[k] * row[k];
            }
            work.w[r] = s;
        }
        let x0 = x[0];
        let g_w = gamma * (1.0 - tau);
        for j in 0..n {
            let g = x[j + 1] * x[j + 1] - x0 * x0;
            let row_of = |i: usize| &self.p[i * m..(i + 1) * m];
            let f = match self.quads[j] {
                Quadric::Circle { c: ic, s: is } => {
                    let (c, s) = (work.w[ic], work.w[is]);
                    let (rc, rs) = (row_of(ic), row_of(is));
                    let row = &mut work.jac[j * m..(j + 1) * m];
                    let (c2, s2) = (c * (2.0 * tau), s * (2.0 * tau));
                    for k in 0..m {
                        row[k] = c2 * rc[k] + s2 * rs[k];
                    }
                    row[0] -= x0 * (2.0 * tau) + g_w * x0 * 2.0;
                    c * c + s * s - x0 * x0
                }
                Quadric::Bilinear { a, b, c, d } => {
                    let (wa, wb, wc, wd) = (work.w[a], work.w[b], work.w[c], work.w[d]);
                    let (ra, rb, rc, rd) = (row_of(a), row_of(b), row_of(c), row_of(d));
                    let row = &mut work.jac[j * m..(j + 1) * m];
                    for k in 0..m {
                        row[k] = (wa * rb[k] + wb * ra[k] - wc * rd[k] - wd * rc[k]) * tau;
                    }
                    row[0] -= g_w * x0 * 2.0;
                    wa * wb - wc * wd
                }
            };
            work.rhs[j] = if dtau { f - gamma * g } else { g_w * g + f * tau };
            work.jac[j * m + j + 1] += g_w * x[j + 1] * 2.0;
        }
        Self::patch_row(n, x, patch, work, dtau);
    }

    /// The patch row N of the homotopy's residual and Jacobian.
    pub(super) fn patch_row(n: usize, x: &[C], patch: &[C], work: &mut Work, dtau: bool) {
        let m = work.m;
        work.jac[n * m..(n + 1) * m].copy_from_slice(patch);
        work.rhs[n] = if dtau {
            C::default()
        } else {
            let mut s = C::new(-1.0, 0.0);
            for k in 0..m {
                s += patch[k] * x[k];
            }
            s
        };
    }

    /// dX/dtau at (x, tau) on the patch, into `out`. False on a singular solve.
    pub(super) fn tangent(&self, x: &[C], tau: f64, gamma: C, patch: &[C], work: &mut Work, out: &mut [C]) -> bool {
        self.eval(x, tau, gamma, patch, work, true);
        for v in work.rhs.iter_mut() {
            *v = -*v;
        }
        if !lu_solve(&mut work.jac, work.m, &mut work.rhs) {
            return false;
        }
        out.copy_from_slice(&work.rhs);
        true
    }
}

impl Iso {
    /// H = (1 - tau) gamma G + tau F (or H_tau with `dtau`) and its Jacobian in X, rows 0..N.
    pub(super) fn eval(&self, x: &[C], tau: f64, gamma: C, work: &mut Work, dtau: bool) {
        // the same arithmetic at a size known to the compiler (C = N / 2 <= MAX_LINKS / 2)
        macro_rules! fixed {
            ($($n:literal)*) => {
                match self.c {
                    $($n => self.eval_n($n, x, tau, gamma, work, dtau),)*
                    nc => self.eval_n(nc, x, tau, gamma, work, dtau),
                }
            };
        }
        fixed!(1 2 3 4 5 6 7 8);
    }

    #[inline(always)]
    pub(super) fn eval_n(&self, nc: usize, x: &[C], tau: f64, gamma: C, work: &mut Work, dtau: bool) {
        let cols = nc + 1;
        let n = 2 * nc;
        let m = work.m;
        let (x0, tu) = (x[0], &x[1..]);
        let Work { w, rhs, jac, .. } = work;
        self.e_ebar_into(nc, x0, tu, &mut w[..2 * n]);
        let (e, eb) = w.split_at(n);
        let dotp = |p: &[C], w: &[C]| p[0] * x0 + p[1..].iter().zip(w).map(|(a, b)| a * b).sum::<C>();
        let g_w = gamma * (1.0 - tau);
        for j in 0..n {
            let (pe, pb) = (&self.pe[j * cols..(j + 1) * cols], &self.pb[j * cols..(j + 1) * cols]);
            let (la, lb) = (&self.la[j * cols..(j + 1) * cols], &self.lb[j * cols..(j + 1) * cols]);
            let (l, mm) = (dotp(la, &tu[..nc]), dotp(lb, &tu[nc..]));
            let f = e[j] * eb[j] - x0 * x0;
            let g = l * mm;
            rhs[j] = if dtau { f - gamma * g } else { g_w * g + f * tau };
            let row = &mut jac[j * m..(j + 1) * m];
            let (ft, gt) = (C::new(tau, 0.0), g_w);
            row[0] = ft * (pe[0] * eb[j] + e[j] * pb[0] - x0 * 2.0) + gt * (la[0] * mm + l * lb[0]);
            for k in 0..nc {
                row[1 + k] = ft * pe[1 + k] * eb[j] + gt * la[1 + k] * mm;
                row[1 + nc + k] = ft * e[j] * pb[1 + k] + gt * l * lb[1 + k];
            }
        }
    }
}
