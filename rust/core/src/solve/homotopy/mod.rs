//! Every assembly of a rigid group of links, by homotopy continuation: all finite complex
//! solutions of the closure equations `A z = b` (linear in `z = (cos phi, sin phi)`) with
//! the unit circles `c_j^2 + s_j^2 = 1`, and the real assemblies among them.

use nalgebra::{Complex, DMatrix, DVector};

use crate::error::Real;
use crate::interrupt::{Never, Poll};
use crate::Error;

// Inside: this file is the API (options, results, the entry functions); `track` follows
// the paths (the method is described there), on `eval` (H and its derivatives at a point),
// on `reduction` (the reduced system, its start points and the finishing Newton steps);
// `lu` and `rng` are leaves.
mod eval;
mod lu;
mod reduction;
mod track;

use reduction::Reduced;
use track::angles_close;

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

/// The default seed of the random gammas (results are reproducible).
pub const DEFAULT_SEED: u64 = 0x5EED_2026;
/// The default number of independent trackings merged.
pub const DEFAULT_RUNS: u32 = 2;

impl Default for HomotopyOptions {
    fn default() -> Self {
        Self { seed: DEFAULT_SEED, runs: DEFAULT_RUNS, max_steps: 3000, max_step: 0.05 }
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

#[cfg(test)]
mod tests;
