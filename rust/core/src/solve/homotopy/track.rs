//! Path tracking: every run's paths from the start system to the target (RK4 predictor,
//! Newton corrector, adaptive step on a moving projective patch), their classification
//! and the merging of roots over runs.
//!
//! Method. The linear part is eliminated first: rows of `[A | b]` are scaled to unit
//! max-norm, an SVD checks that `A` (N x 2N) has full row rank and gives the
//! minimum-norm solution `z0` and an orthonormal basis `K` (2N x N) of its null space, so
//! `z = z0 + K t`. What is left is N quadrics in N unknowns,
//! `q_j(t) = c_j(t)^2 + s_j(t)^2 - 1`. They are solved by a total-degree homotopy
//! `H(t, tau) = (1 - tau) gamma G(t) + tau F(t)`, `G_j = t_j^2 - 1` (2^N start points
//! `t_j = +-1`), `gamma` a random unit complex number (the "gamma trick": no path meets a
//! singularity for tau < 1, with probability one). Each path is tracked in projective
//! coordinates `X = (x0, x)`, `t = x / x0`, on a moving orthogonal patch
//! (`conj(X_k) . X = 1`, renormalised after every accepted step), so paths whose `t`
//! diverges stay bounded and head for `x0 = 0`: once `|x0| < 1e-6 |X|` (or if they stop
//! or end with `|x0| < 1e-4 |X|` and no finite root) they are classified *infinite*, not
//! failed. Predictor: classical RK4 on the Davidenko equation `H_X dX/dtau = -H_tau`;
//! corrector: at most three Newton steps that must contract; adaptive step (halved on
//! rejection, doubled after three acceptances), bounded by `max_steps` per path and a
//! minimum step, so nothing hangs. Every endpoint that reached tau = 1 (or stopped within
//! 1e-6 of it, as paths to a singular root do) is finished by Newton on the affine target
//! `F(t)` and kept only if Newton converges near it with a small residual (a finite,
//! verified root). Roots are
//! deduplicated; two paths of one run ending on the same root (path jumping: the roots
//! are simple for generic geometry) are both tracked again with steps eight times
//! smaller; the whole tracking runs `runs` times (default 2) with independent
//! `gamma`s and the root sets are merged, so a root lost by one run to a path failure or
//! path jumping is still found if the other run finds it. Real assemblies: roots whose
//! imaginary parts are below a scale-aware tolerance, polished by real Newton in the
//! angles on `A z(phi) = b` (the circles then hold exactly) to about 1e-15 rad.

use super::eval::Work;
use super::lu::lu_solve;
use super::reduction::Reduced;
use super::{HomotopyOptions, Solutions, C, INFINITE_X0, PARALLEL_PATHS};
use crate::interrupt::{Flag, Interrupt, Poll};
use crate::parallel::prelude::*;
use crate::rng::SplitMix64;
use crate::{wrap_angle, Error};

#[derive(Clone, Copy, Debug, PartialEq)]
pub(super) enum End {
    /// Reached tau = 1.
    Reached,
    /// Stopped within 1e-6 of tau = 1 (the step fell below its minimum or the budget
    /// ran out): typical of a singular endpoint, e.g. a double root at a dead point.
    Near,
    /// x0 became negligible: t diverges.
    Infinite,
    /// Step below the minimum, step budget spent, or a singular / non-finite linear solve.
    Failed,
}

pub(super) struct RunResult {
    pub(super) roots: Vec<Vec<C>>,
    pub(super) paths: usize,
    pub(super) failed: usize,
    pub(super) infinite: usize,
    /// Paths that ended on a root another path of the run had reached.
    pub(super) jumps: usize,
    pub(super) steps: usize,
}

/// A path's classified end.
pub(super) enum PathEnd {
    /// A finite root t, verified by Newton on the target.
    Root(Vec<C>),
    Infinite,
    Failed,
}

impl Reduced {
    /// Every run (one gamma each), the roots t merged: the distinct roots and the paths'
    /// accounting (the caller fills in the real roots).
    pub(super) fn track_all(&self, opts: &HomotopyOptions, poll: &Poll<'_>) -> Result<(Vec<Vec<C>>, Solutions), Error> {
        let mut rng = SplitMix64(opts.seed);
        let mut out = Solutions::default();
        let mut roots: Vec<Vec<C>> = Vec::new(); // t of the merged roots
        for _ in 0..opts.runs {
            let theta = std::f64::consts::TAU * rng.uniform();
            let gamma = C::new(theta.cos(), theta.sin());
            let run = self.run(gamma, opts, poll)?;
            out.paths += run.paths;
            out.failed += run.failed;
            out.infinite += run.infinite;
            out.per_run_found.push(run.roots.len());
            out.per_run_failed.push(run.failed);
            out.per_run_jumps.push(run.jumps);
            out.steps += run.steps;
            for t in run.roots {
                insert_unique(&mut roots, t);
            }
        }
        Ok((roots, out))
    }

    /// One full tracking of the 2^N paths with one gamma; returns the distinct roots.
    pub(super) fn run(&self, gamma: C, opts: &HomotopyOptions, poll: &Poll<'_>) -> Result<RunResult, Error> {
        let mut res = RunResult { roots: Vec::new(), paths: 0, failed: 0, infinite: 0, jumps: 0, steps: 0 };
        let starts: Vec<usize> = (0..self.paths()).collect();
        // root index reached by each path (None: infinite or failed)
        let mut reached: Vec<Option<usize>> = Vec::with_capacity(starts.len());
        for end in self.track_paths(&starts, gamma, opts, poll, &mut res.steps)? {
            res.paths += 1;
            reached.push(match end {
                PathEnd::Root(t) => Some(insert_unique(&mut res.roots, t)),
                PathEnd::Infinite => {
                    res.infinite += 1;
                    None
                }
                PathEnd::Failed => {
                    res.failed += 1;
                    None
                }
            });
        }
        // Roots here are isolated and simple for generic geometry, so two paths ending at
        // one root means a path jumped (and another root was probably lost): retrack
        // every path of such a root with steps eight times smaller.
        let mut hits = vec![0usize; res.roots.len()];
        for r in reached.iter().flatten() {
            hits[*r] += 1;
        }
        res.jumps = hits.iter().map(|&h| h.saturating_sub(1)).sum();
        if res.jumps > 0 {
            let fine =
                HomotopyOptions { max_step: opts.max_step / 8.0, max_steps: opts.max_steps.saturating_mul(4), ..*opts };
            let again: Vec<usize> =
                (0..starts.len()).filter(|&s| matches!(reached[s], Some(r) if hits[r] > 1)).collect();
            for end in self.track_paths(&again, gamma, &fine, poll, &mut res.steps)? {
                if let PathEnd::Root(t) = end {
                    insert_unique(&mut res.roots, t);
                }
            }
        }
        Ok(res)
    }

    /// The ends of the paths from `starts`, in their order, and the steps they took added
    /// to `steps`. The paths are independent: with the `parallel` feature, a run of at
    /// least [`PARALLEL_PATHS`] is tracked on all cores (rayon's pool), each path by the
    /// same arithmetic as alone, so the ends are the same whatever the thread count.
    /// Interrupts are then asked by a watcher on this thread for long runs (as the
    /// batches do; not from inside a pool's worker), else once the paths are tracked.
    pub(super) fn track_paths(
        &self,
        starts: &[usize],
        gamma: C,
        opts: &HomotopyOptions,
        poll: &Poll<'_>,
        steps: &mut usize,
    ) -> Result<Vec<PathEnd>, Error> {
        let one = |start: usize, poll: &Poll<'_>| -> Result<(PathEnd, usize), Error> {
            let mut work = self.work();
            let end = self.path(start, gamma, opts, &mut work, poll)?;
            Ok((end, work.steps))
        };
        // (the paths tracked here tick the caller's countdown as they step)
        let (ends, ticked): (Vec<(PathEnd, usize)>, bool) =
            if cfg!(feature = "parallel") && starts.len() >= PARALLEL_PATHS {
                // (from inside a pool's worker, no watcher: the pool is already busy with us)
                let size =
                    if crate::parallel::in_worker() { 0 } else { starts.len() as u128 * u128::from(opts.max_steps) };
                let ends =
                    crate::parallel::run(None, size, poll.source(), |stop| {
                        let flag = Flag(stop);
                        starts
                            .par_iter()
                            .map(|&start| {
                                if flag.interrupted() {
                                    Err(Error::Interrupted)
                                } else {
                                    one(start, &Poll::new(&flag))
                                }
                            })
                            .collect::<Result<Vec<_>, Error>>()
                    })?;
                (ends, false)
            } else {
                (starts.iter().map(|&start| one(start, poll)).collect::<Result<Vec<_>, Error>>()?, true)
            };
        let taken: usize = ends.iter().map(|e| e.1).sum();
        if !ticked {
            // the caller's countdown counts the pool's steps as if it had taken them (it
            // asks the interrupt as often as on one thread)
            for _ in 0..taken {
                poll.tick()?;
            }
        }
        *steps += taken;
        Ok(ends.into_iter().map(|e| e.0).collect())
    }

    /// Tracks the path from start point number `start` (bit k set: t_k = -1) and
    /// classifies its end.
    pub(super) fn path(
        &self,
        start: usize,
        gamma: C,
        opts: &HomotopyOptions,
        work: &mut Work,
        poll: &Poll<'_>,
    ) -> Result<PathEnd, Error> {
        let m = self.n + 1;
        let norm0 = 1.0 / (m as f64).sqrt();
        let mut x: Vec<C> = match &self.iso {
            Some(iso) => iso.starts[start].clone(),
            None => (0..m)
                .map(|k| {
                    let sign = if k > 0 && (start >> (k - 1)) & 1 == 1 { -1.0 } else { 1.0 };
                    C::new(sign * norm0, 0.0)
                })
                .collect(),
        };
        let end = self.track(&mut x, gamma, opts, work, poll)?;
        // A path that stopped just short of tau = 1 usually sits by a singular root, where
        // Newton still converges (linearly): keep it if Newton verifies it.
        let root = if matches!(end, End::Reached | End::Near) && x[0].norm() > 1e-12 {
            let t0: Vec<C> = x[1..].iter().map(|v| v / x[0]).collect();
            self.affine_newton(&t0)
        } else {
            None
        };
        Ok(match (end, root) {
            (End::Infinite, _) => PathEnd::Infinite,
            (_, Some(t)) => PathEnd::Root(t),
            // stopped (or arrived) near x0 = 0 without a finite root
            _ if x[0].norm() < 1e-4 => PathEnd::Infinite,
            _ => PathEnd::Failed,
        })
    }

    /// Tracks one path from tau = 0 to 1; `x` is updated in place (unit norm).
    pub(super) fn track(
        &self,
        x: &mut [C],
        gamma: C,
        opts: &HomotopyOptions,
        work: &mut Work,
        poll: &Poll<'_>,
    ) -> Result<End, Error> {
        let m = work.m;
        let mut tau = 0.0_f64;
        let mut h = opts.max_step.min(0.02);
        let h_min = 1e-13;
        let mut good = 0;
        let mut patch = vec![C::default(); m];
        let mut k1 = vec![C::default(); m];
        let mut k2 = vec![C::default(); m];
        let mut k3 = vec![C::default(); m];
        let mut k4 = vec![C::default(); m];
        let mut y = vec![C::default(); m];
        for _ in 0..opts.max_steps {
            poll.tick()?;
            work.steps += 1;
            if x[0].norm() < INFINITE_X0 {
                return Ok(End::Infinite);
            }
            for k in 0..m {
                patch[k] = x[k].conj();
            }
            let step = h.min(1.0 - tau);
            let ok = 'step: {
                if !self.tangent(x, tau, gamma, &patch, work, &mut k1) {
                    break 'step false;
                }
                axpy(&mut y, x, 0.5 * step, &k1);
                if !self.tangent(&y, tau + 0.5 * step, gamma, &patch, work, &mut k2) {
                    break 'step false;
                }
                axpy(&mut y, x, 0.5 * step, &k2);
                if !self.tangent(&y, tau + 0.5 * step, gamma, &patch, work, &mut k3) {
                    break 'step false;
                }
                axpy(&mut y, x, step, &k3);
                let t1 = if tau + step >= 1.0 { 1.0 } else { tau + step };
                if !self.tangent(&y, t1, gamma, &patch, work, &mut k4) {
                    break 'step false;
                }
                for k in 0..m {
                    y[k] = x[k] + (k1[k] + (k2[k] + k3[k]) * 2.0 + k4[k]) * (step / 6.0);
                }
                // Corrector: at most three Newton steps, each contracting.
                let mut last = f64::INFINITY;
                for it in 0..3 {
                    self.eval(&y, t1, gamma, &patch, work, false);
                    for v in work.rhs.iter_mut() {
                        *v = -*v;
                    }
                    if !lu_solve(&mut work.jac, m, &mut work.rhs) {
                        break 'step false;
                    }
                    let d = work.rhs.iter().map(|v| v.norm()).fold(0.0, f64::max);
                    if !d.is_finite() || d > 0.1 || (it > 0 && d > 0.25 * last) {
                        break 'step false;
                    }
                    for (yk, dk) in y.iter_mut().zip(&work.rhs) {
                        *yk += dk;
                    }
                    last = d;
                    if d < 1e-10 {
                        break 'step true;
                    }
                }
                last < 1e-8
            };
            if ok {
                let norm = y.iter().map(|v| v.norm_sqr()).sum::<f64>().sqrt();
                for k in 0..m {
                    x[k] = y[k] / norm;
                }
                tau = if tau + step >= 1.0 { 1.0 } else { tau + step };
                if tau >= 1.0 {
                    return Ok(End::Reached);
                }
                good += 1;
                if good >= 3 {
                    h = (2.0 * h).min(opts.max_step);
                    good = 0;
                }
            } else {
                good = 0;
                h *= 0.5;
                if h < h_min {
                    return Ok(if 1.0 - tau < 1e-6 { End::Near } else { End::Failed });
                }
            }
        }
        Ok(if 1.0 - tau < 1e-6 { End::Near } else { End::Failed })
    }
}

/// y = x + a k.
pub(super) fn axpy(y: &mut [C], x: &[C], a: f64, k: &[C]) {
    for i in 0..y.len() {
        y[i] = x[i] + k[i] * a;
    }
}

/// Adds `t` to `roots` unless a root within 1e-8 (relative) is there already; returns
/// its index.
pub(super) fn insert_unique(roots: &mut Vec<Vec<C>>, t: Vec<C>) -> usize {
    let scale = t.iter().map(|v| v.norm()).fold(1.0, f64::max);
    match roots.iter().position(|r| r.iter().zip(&t).all(|(a, b)| (a - b).norm() <= 1e-8 * scale)) {
        Some(i) => i,
        None => {
            roots.push(t);
            roots.len() - 1
        }
    }
}

pub(super) fn angles_close(a: &[f64], b: &[f64], tol: f64) -> bool {
    a.iter().zip(b).all(|(x, y)| wrap_angle(x - y).abs() <= tol)
}
