//! Every assembly of a rigid group of links, by homotopy continuation: all finite complex
//! solutions of the closure equations `A z = b` (linear in `z = (cos phi, sin phi)`) with
//! the unit circles `c_j^2 + s_j^2 = 1`, and the real assemblies among them.
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

use nalgebra::{Complex, DMatrix, DVector};

use crate::error::Real;
use crate::interrupt::{Flag, Interrupt, Never, Poll};
use crate::parallel::prelude::*;
use crate::{wrap_angle, Error};

type C = Complex<f64>;

/// Largest number of unknown rotations accepted (2^16 paths per run).
pub const MAX_LINKS: usize = 16;

/// Paths of one run from which they are tracked on all cores (with the `parallel`
/// feature): a path of a six-link group takes about 0.2 ms, a task costs microseconds.
const PARALLEL_PATHS: usize = 8;

/// A path whose homogenizing coordinate |x0| (with |X| = 1) falls below this is declared
/// infinite: its t exceeds 1e6 times the scale of the row-normalised problem. Paths to
/// singular points at infinity approach them with |x0| ~ 1 - tau and would otherwise
/// spend ~30 more steps shrinking towards the precision floor (measured on the double
/// butterfly). A finite root that large (|cos phi| ~ 1e6, |Im phi| ~ 14) is lost.
const INFINITE_X0: f64 = 1e-6;

/// Tracking options, all with defaults ([`HomotopyOptions::default`]); [`HomotopyOptions::new`]
/// validates what a caller chooses.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct HomotopyOptions {
    /// Seed of the random `gamma` of each run (splitmix64): the result is deterministic
    /// for a given seed.
    pub seed: u64,
    /// Independent trackings (each with its own `gamma`) whose roots are merged;
    /// 1..=[`MAX_RUNS`].
    pub runs: u32,
    /// At most this many predictor-corrector steps (accepted or rejected) per path; >= 1.
    pub max_steps: u32,
    /// Largest step in tau, in (0, 1].
    pub max_step: f64,
}

impl Default for HomotopyOptions {
    fn default() -> Self {
        Self { seed: 0x5EED_2026, runs: 2, max_steps: 3000, max_step: 0.05 }
    }
}

/// Most independent trackings a caller may ask for: each run tracks 2^N paths again.
pub const MAX_RUNS: u32 = 16;

impl HomotopyOptions {
    /// The default tracking with the caller's `seed` and `runs` (1..=[`MAX_RUNS`]); the
    /// error names the parameter.
    pub fn new(seed: u64, runs: i64) -> Result<Self, Error> {
        let runs = u32::try_from(runs)
            .ok()
            .filter(|r| (1..=MAX_RUNS).contains(r))
            .ok_or_else(|| Error::invalid("runs", "must be an integer in 1..=16", runs))?;
        Ok(Self { seed, runs, ..Self::default() })
    }

    fn check(&self) -> Result<(), Error> {
        if !(1..=MAX_RUNS).contains(&self.runs) {
            return Err(Error::invalid("runs", "must be an integer in 1..=16", self.runs));
        }
        if self.max_steps == 0 {
            return Err(Error::invalid("max_steps", "must be >= 1", 0));
        }
        if !(self.max_step > 0.0 && self.max_step <= 1.0) {
            return Err(Error::invalid("max_step", "must be in (0, 1]", Real(self.max_step)));
        }
        Ok(())
    }
}

/// All assemblies found.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct Solutions {
    /// Finite complex solutions `z = (c_1..c_N, s_1..s_N)` (length 2N), deduplicated over
    /// all runs: the non-real ones first, then the real ones, given exactly as
    /// `(cos phi, sin phi)` of their polished angles (zero imaginary parts) in the order
    /// of [`Solutions::real`].
    pub complex: Vec<Vec<Complex<f64>>>,
    /// Real solutions as angles `phi` (length N) in (-pi, pi], polished by real Newton
    /// (to ~1e-15 rad at simple roots; a double root, at a dead point, is resolved only
    /// to ~1e-8 and may be listed twice, about that far apart).
    pub real: Vec<Vec<f64>>,
    /// Paths tracked, over all runs: `runs * C(N, N/2)` for loop equations (the
    /// isotropic start system), `runs * 2^N` otherwise (total degree).
    pub paths: usize,
    /// Paths that ended neither at a verified finite root nor at infinity, over all runs.
    pub failed: usize,
    /// Paths classified as diverging to infinity, over all runs.
    pub infinite: usize,
    /// Distinct finite roots found by each run.
    pub per_run_found: Vec<usize>,
    /// Failed paths in each run.
    pub per_run_failed: Vec<usize>,
    /// Paths in each run that ended on a root another path of the run had already
    /// reached (path jumping, for isolated simple roots); those paths were tracked again
    /// with steps eight times smaller, and `per_run_found` counts what that recovered.
    pub per_run_jumps: Vec<usize>,
    /// Predictor-corrector steps (accepted and rejected, retracking included) over all
    /// paths and runs: the machine-independent cost of the solve (each step is an RK4
    /// predictor, four (N+1)-square complex LU solves, plus 1-3 Newton solves).
    pub steps: usize,
}

/// All finite complex solutions of `A z = b`, `c_j^2 + s_j^2 = 1` (`a` is N x 2N, `b` has
/// length N, `z = (c_1..c_N, s_1..s_N)`), and the real ones as angles. See the module docs
/// for the method.
///
/// Errors (misuse only): N = 0 or N > [`MAX_LINKS`], shapes that disagree, non-finite
/// entries, invalid options, or `A` without full row rank (dependent closure equations:
/// the solution set is not finite). Path failures are data ([`Solutions::failed`]).
pub fn unit_circle_solutions(a: &DMatrix<f64>, b: &DVector<f64>, opts: &HomotopyOptions) -> Result<Solutions, Error> {
    unit_circle_solutions_polled(a, b, opts, &Poll::new(&Never))
}

/// [`unit_circle_solutions`] that counts every predictor-corrector step on `poll` and
/// returns [`Error::Interrupted`] when the poll's interrupt asks to stop.
pub fn unit_circle_solutions_polled(
    a: &DMatrix<f64>,
    b: &DVector<f64>,
    opts: &HomotopyOptions,
    poll: &Poll<'_>,
) -> Result<Solutions, Error> {
    circle_solutions(a, b, opts, poll, true)
}

/// [`unit_circle_solutions_polled`], with the isotropic start system where `a` has the
/// loop equations' form and `isotropic` allows it, else the total-degree one.
pub(crate) fn circle_solutions(
    a: &DMatrix<f64>,
    b: &DVector<f64>,
    opts: &HomotopyOptions,
    poll: &Poll<'_>,
    isotropic: bool,
) -> Result<Solutions, Error> {
    let n = a.nrows();
    if n == 0 {
        return Err(Error::invalid("a", "must have at least one row", "0 rows"));
    }
    if n > MAX_LINKS {
        return Err(Error::invalid("a", "must have at most 16 rows (2^N paths)", format!("{n} rows")));
    }
    if a.ncols() != 2 * n {
        return Err(Error::Shape { name: "a columns".into(), got: a.ncols(), expected: 2 * n });
    }
    if b.len() != n {
        return Err(Error::Shape { name: "b".into(), got: b.len(), expected: n });
    }
    if let Some(v) = a.iter().chain(b.iter()).find(|v| !v.is_finite()) {
        return Err(Error::invalid("a, b", "must be finite", v));
    }
    opts.check()?;
    let iso = if isotropic { Reduced::isotropic(a, b, opts.seed)? } else { None };
    let red = match iso {
        Some(red) => red,
        None => Reduced::new(a, b, (0..n).map(|j| Quadric::Circle { c: j, s: n + j }).collect())?,
    };
    let (roots, mut out) = red.track_all(opts, poll)?;

    let mut real: Vec<Vec<f64>> = Vec::new();
    for t in &roots {
        let z = red.z_of(t);
        let zmax = z.iter().map(|v| v.norm()).fold(1.0, f64::max);
        let imag = z.iter().map(|v| v.im.abs()).fold(0.0, f64::max);
        if imag <= 1e-6 * zmax {
            if let Some(phi) = red.real_polish(&z) {
                if !real.iter().any(|p| angles_close(p, &phi, 1e-9)) {
                    real.push(phi);
                }
                continue;
            }
        }
        out.complex.push(z);
    }
    // Real roots are stored exactly; a complex root that polished to the same real
    // assembly as another (a near-conjugate pair) is not listed twice.
    for phi in &real {
        out.complex
            .push(phi.iter().map(|p| C::new(p.cos(), 0.0)).chain(phi.iter().map(|p| C::new(p.sin(), 0.0))).collect());
    }
    out.real = real;
    Ok(out)
}

/// One quadric of a system the homotopy solves, on the unknowns `z`.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum Quadric {
    /// `z_c^2 + z_s^2 = 1`: a link's (cos, sin).
    Circle { c: usize, s: usize },
    /// `z_a z_b = z_c z_d`: a slider's (s cos, s sin) parallel to its guide's (cos, sin).
    Bilinear { a: usize, b: usize, c: usize, d: usize },
}

/// Finite complex solutions of a general system: the distinct roots `z` and the paths'
/// accounting (see [`Solutions`] for the fields' meaning).
#[derive(Clone, Debug, Default, PartialEq)]
pub struct Roots {
    /// Distinct finite complex roots `z` (one entry per unknown of `A`), unpolished.
    pub complex: Vec<Vec<Complex<f64>>>,
    /// Paths tracked, over all runs (`runs * 2^N`, N the number of quadrics).
    pub paths: usize,
    /// Paths that ended neither at a verified finite root nor at infinity.
    pub failed: usize,
    /// Paths classified as diverging to infinity.
    pub infinite: usize,
}

/// All finite complex solutions of `A z = b` (`a` is L x D, D - L = N quadrics) with the
/// `quadrics`, by the same total-degree homotopy as [`unit_circle_solutions`]; the roots
/// are left to the caller to classify and polish (a slider group's real assemblies are
/// polished by its own Newton). Errors as [`unit_circle_solutions`].
pub fn quadric_solutions_polled(
    a: &DMatrix<f64>,
    b: &DVector<f64>,
    quadrics: &[Quadric],
    opts: &HomotopyOptions,
    poll: &Poll<'_>,
) -> Result<Roots, Error> {
    let (l, d) = (a.nrows(), a.ncols());
    let n = quadrics.len();
    if n == 0 || n > MAX_LINKS {
        return Err(Error::invalid("quadrics", "must number 1..=16 (2^N paths)", n));
    }
    if d != l + n {
        return Err(Error::Shape { name: "a columns".into(), got: d, expected: l + n });
    }
    if b.len() != l {
        return Err(Error::Shape { name: "b".into(), got: b.len(), expected: l });
    }
    let inside = |q: &Quadric| match *q {
        Quadric::Circle { c, s } => c < d && s < d,
        Quadric::Bilinear { a, b, c, d: e } => [a, b, c, e].iter().all(|&i| i < d),
    };
    if !quadrics.iter().all(inside) {
        return Err(Error::invalid("quadrics", "must index the unknowns of a", format!("{d} unknowns")));
    }
    if let Some(v) = a.iter().chain(b.iter()).find(|v| !v.is_finite()) {
        return Err(Error::invalid("a, b", "must be finite", v));
    }
    opts.check()?;
    let red = Reduced::new(a, b, quadrics.to_vec())?;
    let (roots, stats) = red.track_all(opts, poll)?;
    Ok(Roots {
        complex: roots.iter().map(|t| red.z_of(t)).collect(),
        paths: stats.paths,
        failed: stats.failed,
        infinite: stats.infinite,
    })
}

/// The system after eliminating the linear part: `z = P (x0, x)` with `P = [z0 | K]`.
struct Reduced {
    /// Number of quadrics (and of path coordinates t).
    n: usize,
    /// Number of unknowns z (2N for unit circles alone).
    d: usize,
    quads: Vec<Quadric>,
    /// D x (N + 1), row major: column 0 is z0, columns 1..=N are K.
    p: Vec<f64>,
    /// Row-scaled `A` and `b` (same solutions), for the real polish.
    a: DMatrix<f64>,
    b: DVector<f64>,
    /// The isotropic form with its linear-product start system, for loop equations.
    iso: Option<Iso>,
}

/// Loop equations in isotropic coordinates (Wampler): a closure's two rows are one complex
/// equation sum_j u_j e_j = beta in e_j = c_j + i s_j, and its conjugate in
/// ebar_j = c_j - i s_j, so e = e0 + K t and ebar = conj(e0) + conj(K) u with t, u of
/// C = N/2 coordinates each, and the circles are the N bilinear equations e_j ebar_j = 1.
/// Their two-homogeneous Bezout number, C(N, N/2) (20 for the double butterfly's six
/// links, against 2^6 = 64 for total degree), is the number of paths of the
/// linear-product start system G_j = L_j(t) M_j(u) (random linear factors): a start point
/// takes L_j = 0 for N/2 of the equations and M_j = 0 for the others.
struct Iso {
    c: usize,
    /// N x (C + 1), row major: e_j = pe_j . (x0, t).
    pe: Vec<C>,
    /// N x (C + 1): ebar_j = pb_j . (x0, u).
    pb: Vec<C>,
    /// N x (C + 1): the start system's factors L_j = la_j . (x0, t), M_j = lb_j . (x0, u).
    la: Vec<C>,
    lb: Vec<C>,
    /// Start points X = (x0, t, u), unit norm.
    starts: Vec<Vec<C>>,
}

/// How one path ended.
#[derive(Clone, Copy, Debug, PartialEq)]
enum End {
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

struct RunResult {
    roots: Vec<Vec<C>>,
    paths: usize,
    failed: usize,
    infinite: usize,
    /// Paths that ended on a root another path of the run had reached.
    jumps: usize,
    steps: usize,
}

/// A path's classified end.
enum PathEnd {
    /// A finite root t, verified by Newton on the target.
    Root(Vec<C>),
    Infinite,
    Failed,
}

/// Scratch buffers of one path (no allocation inside the step loop).
struct Work {
    /// Predictor-corrector steps taken (accepted and rejected), all paths of the run.
    steps: usize,
    m: usize,
    jac: Vec<C>,
    rhs: Vec<C>,
    w: Vec<C>,
}

impl Reduced {
    fn new(a: &DMatrix<f64>, b: &DVector<f64>, quads: Vec<Quadric>) -> Result<Self, Error> {
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
    fn isotropic(a: &DMatrix<f64>, b: &DVector<f64>, seed: u64) -> Result<Option<Self>, Error> {
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
    fn paths(&self) -> usize {
        self.iso.as_ref().map_or(1usize << self.n, |iso| iso.starts.len())
    }

    /// z = z0 + K t (or, in isotropic form, c = (e + ebar) / 2, s = (e - ebar) / 2i).
    fn z_of(&self, t: &[C]) -> Vec<C> {
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

    /// Every run (one gamma each), the roots t merged: the distinct roots and the paths'
    /// accounting (the caller fills in the real roots).
    fn track_all(&self, opts: &HomotopyOptions, poll: &Poll<'_>) -> Result<(Vec<Vec<C>>, Solutions), Error> {
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
    fn run(&self, gamma: C, opts: &HomotopyOptions, poll: &Poll<'_>) -> Result<RunResult, Error> {
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
    fn track_paths(
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

    /// A path's linear-algebra buffers.
    fn work(&self) -> Work {
        let m = self.n + 1;
        Work { steps: 0, m, jac: vec![C::default(); m * m], rhs: vec![C::default(); m], w: vec![C::default(); self.d] }
    }

    /// Tracks the path from start point number `start` (bit k set: t_k = -1) and
    /// classifies its end.
    fn path(
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

    /// Homotopy residual (rows 0..N, plus the patch row N) into `work.rhs` and its
    /// Jacobian in X into `work.jac`; with `dtau`, `rhs` gets H_tau instead (patch row 0).
    fn eval(&self, x: &[C], tau: f64, gamma: C, patch: &[C], work: &mut Work, dtau: bool) {
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
    fn patch_row(n: usize, x: &[C], patch: &[C], work: &mut Work, dtau: bool) {
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
    fn tangent(&self, x: &[C], tau: f64, gamma: C, patch: &[C], work: &mut Work, out: &mut [C]) -> bool {
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

    /// Tracks one path from tau = 0 to 1; `x` is updated in place (unit norm).
    fn track(
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

    /// Newton on the affine target q(t) = 0 from `t0`: the root if it converges near `t0`
    /// with a small residual.
    fn affine_newton(&self, t0: &[C]) -> Option<Vec<C>> {
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
    fn real_polish(&self, z: &[C]) -> Option<Vec<f64>> {
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
    fn real_residual(&self, phi: &[f64]) -> f64 {
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
    fn e_ebar(&self, x0: C, tu: &[C]) -> (Vec<C>, Vec<C>) {
        let n = 2 * self.c;
        let mut out = vec![C::default(); 2 * n];
        self.e_ebar_into(self.c, x0, tu, &mut out);
        let eb = out.split_off(n);
        (out, eb)
    }

    /// [`Iso::e_ebar`] into `out` (e, then ebar), no allocation: the tracker's hot path.
    #[inline(always)]
    fn e_ebar_into(&self, nc: usize, x0: C, tu: &[C], out: &mut [C]) {
        let cols = nc + 1;
        let n = 2 * nc;
        let dotp = |p: &[C], w: &[C]| p[0] * x0 + p[1..].iter().zip(w).map(|(a, b)| a * b).sum::<C>();
        let (e, eb) = out.split_at_mut(n);
        for j in 0..n {
            e[j] = dotp(&self.pe[j * cols..(j + 1) * cols], &tu[..nc]);
            eb[j] = dotp(&self.pb[j * cols..(j + 1) * cols], &tu[nc..]);
        }
    }

    /// H = (1 - tau) gamma G + tau F (or H_tau with `dtau`) and its Jacobian in X, rows 0..N.
    fn eval(&self, x: &[C], tau: f64, gamma: C, work: &mut Work, dtau: bool) {
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
    fn eval_n(&self, nc: usize, x: &[C], tau: f64, gamma: C, work: &mut Work, dtau: bool) {
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

    /// Residuals -(e_j ebar_j - 1) into `rhs` and their Jacobian in (t, u) into `jac` at
    /// affine `tu`; returns the largest residual.
    fn affine_terms(&self, tu: &[C], jac: &mut [C], rhs: &mut [C]) -> f64 {
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

/// y = x + a k.
fn axpy(y: &mut [C], x: &[C], a: f64, k: &[C]) {
    for i in 0..y.len() {
        y[i] = x[i] + k[i] * a;
    }
}

/// Adds `t` to `roots` unless a root within 1e-8 (relative) is there already; returns
/// its index.
fn insert_unique(roots: &mut Vec<Vec<C>>, t: Vec<C>) -> usize {
    let scale = t.iter().map(|v| v.norm()).fold(1.0, f64::max);
    match roots.iter().position(|r| r.iter().zip(&t).all(|(a, b)| (a - b).norm() <= 1e-8 * scale)) {
        Some(i) => i,
        None => {
            roots.push(t);
            roots.len() - 1
        }
    }
}

fn angles_close(a: &[f64], b: &[f64], tol: f64) -> bool {
    a.iter().zip(b).all(|(x, y)| wrap_angle(x - y).abs() <= tol)
}

/// Solves the m x m system in place by Gaussian elimination with partial pivoting (row
/// major `a`); the solution replaces `b`. False on a zero or non-finite pivot.
fn lu_solve(a: &mut [C], m: usize, b: &mut [C]) -> bool {
    // the tracker's systems are (N + 1) square, N <= MAX_LINKS: the same elimination at a
    // size known to the compiler (constant loop bounds), bit for bit
    macro_rules! fixed {
        ($($n:literal)*) => {
            match m {
                $($n => return lu_fixed::<$n>(a, b),)*
                _ => {}
            }
        };
    }
    fixed!(2 3 4 5 6 7 8 9 10 11 12 13 14 15 16 17);
    lu_dynamic(a, m, b)
}

/// [`lu_solve`] for an M x M system: the same operations in the same order.
fn lu_fixed<const M: usize>(a: &mut [C], b: &mut [C]) -> bool {
    lu_dynamic(&mut a[..M * M], M, &mut b[..M])
}

#[inline(always)]
fn lu_dynamic(a: &mut [C], m: usize, b: &mut [C]) -> bool {
    for k in 0..m {
        let mut p = k;
        let mut best = a[k * m + k].norm_sqr();
        for i in k + 1..m {
            let v = a[i * m + k].norm_sqr();
            if v > best {
                best = v;
                p = i;
            }
        }
        if !(best > 0.0 && best.is_finite()) {
            return false;
        }
        if p != k {
            for c in 0..m {
                a.swap(k * m + c, p * m + c);
            }
            b.swap(k, p);
        }
        let inv = C::new(1.0, 0.0) / a[k * m + k];
        let bk = b[k];
        // rows below k minus f times row k (the same operations, on row slices)
        let (top, rest) = a.split_at_mut((k + 1) * m);
        let rk = &top[k * m + k + 1..(k + 1) * m];
        for (row, bi) in rest.chunks_exact_mut(m).zip(&mut b[k + 1..]) {
            let f = row[k] * inv;
            if f == C::default() {
                continue;
            }
            for (x, &v) in row[k + 1..].iter_mut().zip(rk) {
                *x -= f * v;
            }
            *bi -= f * bk;
        }
    }
    for k in (0..m).rev() {
        let mut s = b[k];
        for c in k + 1..m {
            s -= a[k * m + c] * b[c];
        }
        b[k] = s / a[k * m + k];
    }
    b.iter().all(|v| v.re.is_finite() && v.im.is_finite())
}

/// splitmix64: a tiny, good-enough PRNG for the random gammas (no dependency).
#[derive(Clone, Debug)]
pub(crate) struct SplitMix64(pub(crate) u64);

impl SplitMix64 {
    pub(crate) fn next_u64(&mut self) -> u64 {
        self.0 = self.0.wrapping_add(0x9E37_79B9_7F4A_7C15);
        let mut z = self.0;
        z = (z ^ (z >> 30)).wrapping_mul(0xBF58_476D_1CE4_E5B9);
        z = (z ^ (z >> 27)).wrapping_mul(0x94D0_49BB_1331_11EB);
        z ^ (z >> 31)
    }

    /// Uniform in [0, 1).
    pub(crate) fn uniform(&mut self) -> f64 {
        (self.next_u64() >> 11) as f64 / (1u64 << 53) as f64
    }
}

#[cfg(test)]
mod tests;
