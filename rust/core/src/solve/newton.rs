//! Newton-Raphson written once, generic over the number of unknowns: a linkage supplies
//! its residual and Jacobian ([`System`]); the solver iterates on the stack (nalgebra
//! fixed-size types), checks conditioning against a dimensionless threshold and returns
//! a [`Status`] as data.

use nalgebra::{SMatrix, SVector};

use crate::error::{positive_finite, try_grow, Error};
use crate::interrupt::Poll;
use crate::Status;

/// Default dimensionless singular threshold on the system's conditioning measure.
/// For the four-bar the measure is |sin(theta4 - theta3)| min(r3, r4) / L: rounding moves
/// the angles by about c eps / measure (c measured up to 1.75 near toggles), so 1e-6
/// keeps every converged angle within 1e-9 rad, with margin.
pub const SINGULAR_THRESHOLD: f64 = 1e-6;

/// A square nonlinear system F(x) = 0 with N unknowns.
pub trait System<const N: usize> {
    /// Residual F(x) and Jacobian dF/dx at `x`, evaluated together (they share trigonometry).
    fn eval(&self, x: &SVector<f64, N>) -> (SVector<f64, N>, SMatrix<f64, N, N>);

    /// The length that makes residuals dimensionless (e.g. the longest link).
    fn scale(&self) -> f64;

    /// Dimensionless conditioning of `j` in [0, 1]; 0 means singular. The default is the
    /// Hadamard ratio |det J| / prod(column norms), invariant to scaling lengths.
    fn conditioning(&self, j: &SMatrix<f64, N, N>) -> f64 {
        hadamard_ratio(j).abs()
    }

    /// Brings an iterate back to a canonical representative after a step (angles to
    /// (-pi, pi]): an iterate that wanders to large angles loses bits it cannot regain.
    fn normalize(&self, _x: &mut SVector<f64, N>) {}

    /// The Newton step: solves J dx = -F. `None` when J is exactly singular.
    fn step(&self, j: &SMatrix<f64, N, N>, f: &SVector<f64, N>) -> Option<SVector<f64, N>> {
        eliminate(*j, -f, &mut 1.0)
    }

    /// [`System::conditioning`] (its size; it may carry a sign) and [`System::step`]
    /// together, for one Newton iteration. A system whose conditioning is the default
    /// Hadamard ratio may override it with [`hadamard_step`]: one elimination gives both.
    fn conditioned_step(&self, j: &SMatrix<f64, N, N>, f: &SVector<f64, N>) -> (f64, Option<SVector<f64, N>>) {
        (self.conditioning(j), self.step(j, f))
    }
}

/// The signed Hadamard ratio det J / prod(column norms) and the step J dx = -F from one
/// elimination (bit for bit what [`hadamard_ratio`] and the default step give).
pub fn hadamard_step<const N: usize>(j: &SMatrix<f64, N, N>, f: &SVector<f64, N>) -> (f64, Option<SVector<f64, N>>) {
    let norms: f64 = j.column_iter().map(|c| c.norm()).product();
    let mut det = 1.0;
    let dx = eliminate(*j, -f, &mut det);
    (if norms == 0.0 { 0.0 } else { det / norms }, dx)
}

/// Signed Hadamard ratio det J / prod(column norms), in [-1, 1]: its size is a scale-free
/// conditioning (0 at a singular J), its sign names the branch.
pub fn hadamard_ratio<const N: usize>(j: &SMatrix<f64, N, N>) -> f64 {
    let norms: f64 = j.column_iter().map(|c| c.norm()).product();
    if norms == 0.0 {
        return 0.0;
    }
    let mut det = 1.0;
    eliminate(*j, SVector::zeros(), &mut det);
    det / norms
}

/// Gaussian elimination with partial pivoting on the stack, for any N (nalgebra's LU needs
/// `DimMin` bounds a generic const N cannot name). Multiplies `det` by the determinant;
/// `None` on an exactly zero pivot. [`eliminate_rows`] does the work.
#[inline]
pub fn eliminate<const N: usize>(a: SMatrix<f64, N, N>, b: SVector<f64, N>, det: &mut f64) -> Option<SVector<f64, N>> {
    let mut m = [[0.0; N]; N];
    for (i, row) in m.iter_mut().enumerate() {
        for (c, v) in row.iter_mut().enumerate() {
            *v = a[(i, c)];
        }
    }
    let mut x = [[0.0; 1]; N];
    for (xi, bi) in x.iter_mut().zip(b.iter()) {
        xi[0] = *bi;
    }
    eliminate_rows(&mut m, &mut x, det).then(|| SVector::<f64, N>::from_fn(|i, _| x[i][0]))
}

/// Gaussian elimination with partial pivoting of the row-major `m` against `K` right-hand
/// sides at once (the rows of `x`), which it overwrites with the solutions; multiplies
/// `det` by the determinant. False on an exactly zero pivot.
///
/// Written for the small systems of a sweep (a 6x6 group is solved at every angle): rows
/// are arrays, so a row swap is a swap of two arrays, and each elimination updates a
/// whole row, a loop of constant length the compiler unrolls into packed operations. The
/// columns left of the pivot that this also updates are never read again (the pivot search
/// and the back substitution read only the columns from the pivot's on); every value that is
/// read is made by the same operations, in the same order, as in the textbook loop, and so
/// has the same bits; each right-hand side gets the operations it would get alone.
#[inline]
pub fn eliminate_rows<const N: usize, const K: usize>(
    m: &mut [[f64; N]; N],
    x: &mut [[f64; K]; N],
    det: &mut f64,
) -> bool {
    // the steps spelled out for the sizes the groups use, so each step's loops have
    // constant bounds and unroll (the same operations in the same order as the loop)
    macro_rules! steps {
        ($($k:literal)*) => {{
            $( if !eliminate_step(m, x, det, $k) { return false; } )*
        }};
    }
    match N {
        2 => steps!(0 1),
        4 => steps!(0 1 2 3),
        6 => steps!(0 1 2 3 4 5),
        8 => steps!(0 1 2 3 4 5 6 7),
        _ => {
            for k in 0..N {
                if !eliminate_step(m, x, det, k) {
                    return false;
                }
            }
        }
    }
    for k in (0..N).rev() {
        let mut s = x[k];
        for c in k + 1..N {
            for (sj, xj) in s.iter_mut().zip(x[c]) {
                *sj -= m[k][c] * xj;
            }
        }
        for (xj, sj) in x[k].iter_mut().zip(s) {
            *xj = sj / m[k][k];
        }
    }
    true
}

/// Step `k` of [`eliminate_rows`]: the pivot, the row swap, and the rows below it.
#[inline(always)]
fn eliminate_step<const N: usize, const K: usize>(
    m: &mut [[f64; N]; N],
    x: &mut [[f64; K]; N],
    det: &mut f64,
    k: usize,
) -> bool {
    // the last row of largest |a_ik| (as `max_by` on `total_cmp` picks among equals; for
    // numbers with a clear sign bit that order is the order of their bits)
    let mut p = k;
    let mut best = m[k][k].abs().to_bits();
    for (i, row) in m.iter().enumerate().skip(k + 1) {
        let v = row[k].abs().to_bits();
        if v >= best {
            (p, best) = (i, v);
        }
    }
    if p != k {
        m.swap(k, p);
        x.swap(k, p);
        *det = -*det;
    }
    let pivot = m[k][k];
    *det *= pivot;
    if pivot == 0.0 {
        return false;
    }
    let (rk, xk) = (m[k], x[k]);
    for i in k + 1..N {
        let f = m[i][k] / pivot;
        for (v, r) in m[i].iter_mut().zip(rk) {
            *v -= f * r;
        }
        for (v, r) in x[i].iter_mut().zip(xk) {
            *v -= f * r;
        }
    }
    true
}

/// Stopping criteria, validated once.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct NewtonOptions {
    /// Converged when max|F_i| / scale < tol.
    pub tol: f64,
    /// At most this many Newton steps.
    pub max_iter: u32,
    /// Singular when conditioning falls below this.
    pub singular: f64,
}

impl NewtonOptions {
    /// Validates: `tol` finite and > 0, `max_iter` in 1..=u32::MAX.
    pub fn new(tol: f64, max_iter: i64) -> Result<Self, Error> {
        positive_finite("tol", tol)?;
        let max_iter = u32::try_from(max_iter)
            .ok()
            .filter(|&m| m >= 1)
            .ok_or_else(|| Error::invalid("max_iter", "must be an integer in 1..=4294967295", max_iter))?;
        Ok(Self { tol, max_iter, singular: SINGULAR_THRESHOLD })
    }
}

/// The default tolerance (every binding's default `tol`).
pub const DEFAULT_TOL: f64 = 1e-9;
/// The default largest number of Newton steps.
pub const DEFAULT_MAX_ITER: u32 = 100;

impl Default for NewtonOptions {
    fn default() -> Self {
        Self { tol: DEFAULT_TOL, max_iter: DEFAULT_MAX_ITER, singular: SINGULAR_THRESHOLD }
    }
}

/// What one solve returns.
#[derive(Clone, Copy, Debug)]
pub struct Outcome<const N: usize> {
    /// The last iterate (the solution when converged).
    pub x: SVector<f64, N>,
    /// How it ended.
    pub status: Status,
    /// Newton steps taken.
    pub nit: u32,
    /// Dimensionless residual max|F_i| / scale at `x`.
    pub residual: f64,
    /// Jacobian at `x` (reused for velocities and predictors without re-evaluating).
    pub jacobian: SMatrix<f64, N, N>,
    /// The system's conditioning of `jacobian` as its last step computed it (signed where
    /// the system gives a sign, as [`hadamard_step`] does); NaN if no step was taken.
    pub conditioning: f64,
}

/// Newton-Raphson from `x0`.
///
/// Converged when the dimensionless residual is below `tol` *and* the Newton correction
/// that would follow, max|J^-1 F|, is below `tol` too: the unknowns are angles, so the
/// correction estimates the error of the iterate in radians, and a small residual at a
/// badly conditioned point is not taken for an accurate one. That last correction is
/// applied to the returned `x` (as scipy's `newton` returns the stepped point), so its
/// error is quadratic in the correction; `nit` and `residual` are those of the last
/// evaluation. Once the residual is below
/// `tol`, a correction that stops shrinking (it falls by less than half) means rounding
/// alone keeps it above `tol` there: `PrecisionLoss`. An iterate whose conditioning is
/// below `opts.singular` is `Singular`. Residual norms per iteration are
/// appended to `history` only when one is passed.
pub fn solve<S: System<N>, const N: usize>(
    sys: &S,
    x0: SVector<f64, N>,
    opts: &NewtonOptions,
    history: Option<&mut Vec<f64>>,
) -> Outcome<N> {
    iterate(sys, x0, opts, history, None, false).0
}

/// [`solve`] that gives up (`MaxIterations`) once the residual stalls: from the fourth step
/// on, a residual above half the one two steps before. Where a root is near, Newton's
/// residual falls by more than that every two steps, even at a double root (the error
/// halves, the residual quarters), and after an overshoot it comes back as fast; just past
/// a dead point, where no root is, it falls to the gap's size and then wanders, and a
/// continuation that is looking for the dead point learns that in a few steps instead of
/// `max_iter`.
pub fn solve_or_stall<S: System<N>, const N: usize>(sys: &S, x0: SVector<f64, N>, opts: &NewtonOptions) -> Outcome<N> {
    iterate(sys, x0, opts, None, None, true).0
}

/// [`solve`] that counts every Newton step on `poll` and returns [`Error::Interrupted`]
/// when the poll's interrupt asks to stop (or [`Error::Allocation`] when `history` cannot
/// grow).
pub fn solve_polled<S: System<N>, const N: usize>(
    sys: &S,
    x0: SVector<f64, N>,
    opts: &NewtonOptions,
    history: Option<&mut Vec<f64>>,
    poll: &Poll<'_>,
) -> Result<Outcome<N>, Error> {
    match iterate(sys, x0, opts, history, Some(poll), false) {
        (out, None) => Ok(out),
        (_, Some(e)) => Err(e),
    }
}

/// The Newton loop; the error is set only when `poll` interrupted it or `history` could
/// not grow.
#[inline]
fn iterate<S: System<N>, const N: usize>(
    sys: &S,
    x0: SVector<f64, N>,
    opts: &NewtonOptions,
    mut history: Option<&mut Vec<f64>>,
    poll: Option<&Poll<'_>>,
    stall: bool,
) -> (Outcome<N>, Option<Error>) {
    let scale = sys.scale();
    let mut x = x0;
    let mut nit = 0;
    let mut last_small_step = f64::INFINITY;
    // the residuals one and two steps before (for `stall`)
    let (mut r1, mut r2) = (f64::INFINITY, f64::INFINITY);
    loop {
        let (f, j) = sys.eval(&x);
        let mut residual = 0.0_f64;
        for v in f.iter() {
            residual = residual.max(v.abs());
        }
        residual /= scale;
        let finite = f.iter().chain(x.iter()).all(|v| v.is_finite());
        if let Some(h) = history.as_deref_mut() {
            // max_iter is the caller's: the history grows fallibly
            let len = h.len() + 1;
            if let Err(e) = try_grow(h, 1, || format!("history of {len} Newton iterations")) {
                return (
                    Outcome { x, status: Status::MaxIterations, nit, residual, jacobian: j, conditioning: f64::NAN },
                    Some(e),
                );
            }
            h.push(if finite { residual } else { f64::NAN });
        }
        if !finite {
            return (
                Outcome { x, status: Status::NonFinite, nit, residual: f64::NAN, jacobian: j, conditioning: f64::NAN },
                None,
            );
        }
        let (conditioning, dx) = sys.conditioned_step(&j, &f);
        let done = |status| (Outcome { x, status, nit, residual, jacobian: j, conditioning }, None);
        if conditioning.abs() < opts.singular {
            return done(Status::Singular);
        }
        let Some(dx) = dx else { return done(Status::Singular) };
        if residual < opts.tol {
            let step = dx.amax();
            if step < opts.tol {
                // The correction is already computed: apply it (no further evaluation), so
                // the answer's error is quadratic in it rather than of its size.
                return (
                    Outcome { x: x + dx, status: Status::Converged, nit, residual, jacobian: j, conditioning },
                    None,
                );
            }
            if step > 0.5 * last_small_step {
                return done(Status::PrecisionLoss);
            }
            last_small_step = step;
        }
        if nit >= opts.max_iter || (stall && nit >= 4 && residual > 0.5 * r2) {
            return done(Status::MaxIterations);
        }
        (r2, r1) = (r1, residual);
        if let Some(Err(e)) = poll.map(Poll::tick) {
            return (Outcome { x, status: Status::MaxIterations, nit, residual, jacobian: j, conditioning }, Some(e));
        }
        x += dx;
        sys.normalize(&mut x);
        nit += 1;
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use nalgebra::{Matrix3, Vector3};

    /// x^2 + y^2 + z^2 = 3, x = y, y = z: roots (1,1,1) and (-1,-1,-1). Uses the default
    /// LU step and Hadamard conditioning, so the generic path is exercised with N = 3.
    struct Sphere;
    impl System<3> for Sphere {
        fn eval(&self, x: &Vector3<f64>) -> (Vector3<f64>, Matrix3<f64>) {
            let f = Vector3::new(x.norm_squared() - 3.0, x[0] - x[1], x[1] - x[2]);
            let j = Matrix3::new(2.0 * x[0], 2.0 * x[1], 2.0 * x[2], 1.0, -1.0, 0.0, 0.0, 1.0, -1.0);
            (f, j)
        }
        fn scale(&self) -> f64 {
            1.0
        }
    }

    #[test]
    fn generic_solver_converges_quadratically_in_three_unknowns() {
        let mut h = Vec::new();
        let out = solve(&Sphere, Vector3::new(2.0, 0.5, 1.5), &NewtonOptions::default(), Some(&mut h));
        assert_eq!(out.status, Status::Converged);
        assert!((out.x - Vector3::new(1.0, 1.0, 1.0)).amax() < 1e-12);
        assert_eq!(h.len() as u32, out.nit + 1);
        // quadratic: the last ratios e_{k+1} / e_k^2 stay bounded
        let n = h.len();
        assert!(h[n - 2] / (h[n - 3] * h[n - 3]) < 10.0);
    }

    /// x^2 = c, y = x: two roots for c > 0 that meet at a fold (c = 0); none past it.
    struct Fold(f64);
    impl System<2> for Fold {
        fn eval(&self, x: &SVector<f64, 2>) -> (SVector<f64, 2>, SMatrix<f64, 2, 2>) {
            let f = SVector::<f64, 2>::new(x[0] * x[0] - self.0, x[1] - x[0]);
            (f, SMatrix::<f64, 2, 2>::new(2.0 * x[0], 0.0, -1.0, 1.0))
        }
        fn scale(&self) -> f64 {
            1.0
        }
    }

    #[test]
    fn a_stalled_newton_gives_up_past_a_fold_and_converges_before_it() {
        let opts = NewtonOptions { tol: 1e-12, max_iter: 60, singular: 1e-14 };
        let x0 = SVector::<f64, 2>::new(1e-2, 1e-2);
        // past the fold: no root; the plain solve runs to max_iter, the stalling one stops
        // a few steps after the residual reaches the gap
        let past = Fold(-1e-8);
        assert_eq!(solve(&past, x0, &opts, None).nit, 60);
        let out = solve_or_stall(&past, x0, &opts);
        assert_eq!(out.status, Status::MaxIterations);
        assert!(out.nit < 15, "{}", out.nit);
        // just before it (the roots 2e-4 apart, the error halving at first) and at a
        // regular root far from the start (the first step overshoots to 12.5) both
        // converge as the plain solve does
        for c in [4e-8, 0.25] {
            let (a, b) = (solve(&Fold(c), x0, &opts, None), solve_or_stall(&Fold(c), x0, &opts));
            assert_eq!((a.status, b.status), (Status::Converged, Status::Converged));
            assert_eq!((a.nit, a.x), (b.nit, b.x));
            assert!((b.x[0] - c.sqrt()).abs() < 1e-12);
        }
    }

    #[test]
    fn singular_start_is_reported() {
        let out = solve(&Sphere, Vector3::zeros(), &NewtonOptions::default(), None);
        assert_eq!(out.status, Status::Singular);
        assert_eq!(out.nit, 0);
    }

    #[test]
    fn max_iterations_and_non_finite() {
        let opts = NewtonOptions::new(1e-30, 3).unwrap();
        let out = solve(&Sphere, Vector3::new(2.0, 0.5, 1.5), &opts, None);
        assert_eq!(out.status, Status::MaxIterations);
        assert_eq!(out.nit, 3);
        let out = solve(&Sphere, Vector3::new(f64::NAN, 0.0, 0.0), &opts, None);
        assert_eq!(out.status, Status::NonFinite);
    }

    #[test]
    fn options_are_validated() {
        assert!(NewtonOptions::new(0.0, 10).is_err());
        assert!(NewtonOptions::new(f64::NAN, 10).is_err());
        assert!(NewtonOptions::new(1e-9, 0).is_err());
        assert!(NewtonOptions::new(1e-9, -3).is_err());
        let msg = NewtonOptions::new(-1.0, 10).unwrap_err().to_string();
        assert!(msg.starts_with("tol "), "{msg}");
    }
}
