//! The four-bar linkage: validated lengths, its loop equations as a Newton [`System`],
//! the closed form of both assembly modes, and velocity/acceleration from the same
//! Jacobian. Ground O2 = (0, 0) to O4 = (r1, 0); angles in radians, counter-clockwise.

use std::cell::Cell;

use nalgebra::{Matrix2, Vector2};

use crate::error::{positive_finite, Error};
use crate::interrupt::{Never, Poll};
use crate::newton::{self, NewtonOptions, System};
use crate::{wrap_angle, Status};

/// Assembly mode: which of the (up to) two solutions at a crank angle.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub enum Mode {
    /// sin(theta4 - theta3) > 0: rocker pin B left of the line from crank pin A to O4.
    Open,
    /// sin(theta4 - theta3) < 0: the mirror of open about the line A-O4.
    Crossed,
}

impl Mode {
    /// +1 for open, -1 for crossed: the sign sin(theta4 - theta3) must have.
    #[inline]
    pub fn sign(self) -> f64 {
        match self {
            Mode::Open => 1.0,
            Mode::Crossed => -1.0,
        }
    }

    /// Parses "open" / "crossed".
    pub fn parse(s: &str) -> Result<Self, Error> {
        match s {
            "open" => Ok(Mode::Open),
            "crossed" => Ok(Mode::Crossed),
            other => Err(Error::invalid("mode", "must be 'open' or 'crossed'", format!("{other:?}"))),
        }
    }
}

/// What the closed form finds at one crank angle.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum Assembly {
    /// The solution of the requested mode, wrapped to (-pi, pi], with its branch
    /// indicator sin(theta4 - theta3) (its sign is the mode's, or 0 at a toggle).
    Closed { theta3: f64, theta4: f64, sin34: f64 },
    /// No real solution: |r3 - r4| <= |A O4| <= r3 + r4 fails.
    NotAssemblable,
    /// Crank pin A on O4 with r3 = r4: every coupler angle closes the loop.
    Indeterminate,
}

/// The result of the assemblability check at one crank angle.
#[derive(Clone, Copy, Debug, PartialEq)]
pub(crate) enum Geometry {
    Triangle(Triangle),
    NotAssemblable,
    Indeterminate,
}

/// Triangle A-B-O4: u = O4 - A, d2 = |u|^2, 2 d h, k = r3^2 - r4^2 (factored).
#[derive(Clone, Copy, Debug, PartialEq)]
pub(crate) struct Triangle {
    ux: f64,
    uy: f64,
    d2: f64,
    two_dh: f64,
    k: f64,
    r3r4: f64,
}

impl Triangle {
    /// Angles of `mode`: AB and O4B are u turned by the angles at A and at O4, whose
    /// (cos, sin) are proportional to (k + d^2, 2dh) and (k - d^2, 2dh); two atan2 of the
    /// turned vectors, already in (-pi, pi] (`+ 0.0` turns atan2(-0, x < 0) = -pi into pi).
    /// Returns (theta3, theta4) and sin(theta4 - theta3).
    #[inline]
    pub(crate) fn angles(&self, mode: Mode) -> (Vector2<f64>, f64) {
        let Triangle { ux, uy, d2, two_dh, k, r3r4 } = *self;
        let h = mode.sign() * two_dh;
        let (ca, cb) = (k + d2, k - d2);
        let theta3 = (uy * ca + ux * h + 0.0).atan2(ux * ca - uy * h);
        let theta4 = (uy * cb + ux * h + 0.0).atan2(ux * cb - uy * h);
        (Vector2::new(theta3, theta4), h / (2.0 * r3r4))
    }
}

/// One solved point.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Point {
    /// Coupler angle, wrapped to (-pi, pi]; NaN unless converged.
    pub theta3: f64,
    /// Rocker angle, wrapped to (-pi, pi]; NaN unless converged.
    pub theta4: f64,
    /// How the solve ended.
    pub status: Status,
    /// Newton steps taken.
    pub nit: u32,
    /// Dimensionless residual max(|f1|, |f2|) / longest link at the last iterate.
    pub residual: f64,
}

impl Point {
    pub(crate) fn failed(status: Status, nit: u32, residual: f64) -> Self {
        Point { theta3: f64::NAN, theta4: f64::NAN, status, nit, residual }
    }

    /// A point decided before any iteration, with no Jacobian to hand back.
    pub(crate) fn unsolved(status: Status) -> (Self, Matrix2<f64>) {
        (Point::failed(status, 0, f64::NAN), Matrix2::repeat(f64::NAN))
    }
}

/// A four-bar linkage with validated lengths: r1 ground, r2 crank, r3 coupler, r4 rocker.
///
/// The problem is scale-free: every kernel works on the lengths divided by the power of
/// two 2^e <= L < 2^(e+1) of the longest link L (an exact division), so the longest unit
/// length lies in [1, 2) and nothing overflows or underflows however large or small the
/// lengths are, and lengths scaled by a power of two give bit-identical results.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct FourBar {
    /// The lengths as given.
    raw: [f64; 4],
    /// The lengths divided by 2^e: what every computation uses.
    r: [f64; 4],
    /// The longest unit length, in [1, 2).
    longest: f64,
    /// min(r3, r4) / longest: turns |sin(theta4 - theta3)| into the conditioning measure.
    cond_scale: f64,
}

/// A triangle A-B-O4 whose sides close within this many ulp of the longest link is
/// taken as flat (the rounding of |A O4| and of the sums of lengths).
pub const FLAT_ULPS: f64 = 8.0;

/// Why a length is refused when the unit problem cannot hold it.
const TOO_SHORT: &str = "is too short relative to the longest link to be represented (ratio below ~1e-308)";

/// 2^k for k in -1022..=1023 (a normal number).
fn pow2(k: i32) -> f64 {
    f64::from_bits(((k + 1023) as u64) << 52)
}

/// The exponent e with 2^e <= x < 2^(e+1), for finite x > 0 (subnormal x too).
fn exponent(x: f64) -> i32 {
    let bits = x.to_bits();
    let e = ((bits >> 52) & 0x7ff) as i32;
    if e == 0 {
        63 - (bits & ((1 << 52) - 1)).leading_zeros() as i32 - 1074
    } else {
        e - 1023
    }
}

/// x 2^k, in steps that keep every factor normal: exact whenever the result is normal.
fn times_pow2(mut x: f64, mut k: i32) -> f64 {
    while k != 0 {
        let s = k.clamp(-1000, 1000);
        x *= pow2(s);
        k -= s;
    }
    x
}

impl FourBar {
    /// Validates every length (finite and > 0, and representable exactly once divided by
    /// the power of two of the longest: a length below about 1e-308 times the longest
    /// may not be); the error names the parameter.
    pub fn new(r1: f64, r2: f64, r3: f64, r4: f64) -> Result<Self, Error> {
        const NAMES: [&str; 4] = ["r1", "r2", "r3", "r4"];
        Self::validated([r1, r2, r3, r4], |i| NAMES[i].to_string())
    }

    /// Validates `raw`, naming entry `i` by `name(i)` in errors (built only on error).
    pub(crate) fn validated(raw: [f64; 4], name: impl Fn(usize) -> String) -> Result<Self, Error> {
        for (i, &v) in raw.iter().enumerate() {
            if !(v.is_finite() && v > 0.0) {
                positive_finite(name(i), v)?;
            }
        }
        let big = raw[0].max(raw[1]).max(raw[2]).max(raw[3]);
        let e = exponent(big);
        let r = raw.map(|v| times_pow2(v, -e));
        for (i, &v) in r.iter().enumerate() {
            // below ~1e-308 times the longest the unit length is subnormal: kept if exact
            if v == 0.0 || times_pow2(v, e) != raw[i] {
                return Err(Error::invalid(name(i), TOO_SHORT, raw[i]));
            }
        }
        let longest = times_pow2(big, -e);
        Ok(FourBar { raw, r, longest, cond_scale: r[2].min(r[3]) / longest })
    }

    /// The lengths [r1, r2, r3, r4] as given.
    pub fn lengths(&self) -> [f64; 4] {
        self.raw
    }

    /// The lengths divided by the power of two of the longest (longest in [1, 2)): the
    /// scale-free problem every kernel solves.
    pub fn unit_lengths(&self) -> [f64; 4] {
        self.r
    }

    /// The longest unit length, in [1, 2): the scale that makes residuals dimensionless.
    pub fn longest(&self) -> f64 {
        self.longest
    }

    /// The loop equations at crank angle `theta2`, as a Newton system in (theta3, theta4).
    pub fn at(&self, theta2: f64) -> Loop<'_> {
        let (s2, c2) = theta2.sin_cos();
        self.at_sin_cos(s2, c2)
    }

    /// [`FourBar::at`] from sin and cos of the crank angle (shared across a batch).
    pub fn at_sin_cos(&self, s2: f64, c2: f64) -> Loop<'_> {
        Loop { fb: self, c2, s2, last: Cell::new(None) }
    }

    /// Closed form (circle intersection) for `mode` at `theta2`.
    pub fn closed_form(&self, theta2: f64, mode: Mode) -> Assembly {
        let (s2, c2) = theta2.sin_cos();
        self.closed_form_cs(c2, s2, mode)
    }

    /// Closed form from cos/sin of the crank angle.
    pub(crate) fn closed_form_cs(&self, c2: f64, s2: f64, mode: Mode) -> Assembly {
        match self.geometry(c2, s2) {
            Geometry::Triangle(t) => {
                let (x, sin34) = t.angles(mode);
                Assembly::Closed { theta3: x[0], theta4: x[1], sin34 }
            }
            Geometry::NotAssemblable => Assembly::NotAssemblable,
            Geometry::Indeterminate => Assembly::Indeterminate,
        }
    }

    /// The triangle A-B-O4 at a crank angle, or why there is none: one square root for
    /// d = |A O4| and one for the height of B, no trigonometry. B lies at distance r3
    /// from A and r4 from O4; 2 d h comes from Heron's formula in exactly factored form,
    /// so nothing cancels near a toggle and power-of-two scaling is exact.
    #[inline]
    pub(crate) fn geometry(&self, c2: f64, s2: f64) -> Geometry {
        let [r1, r2, r3, r4] = self.r;
        let ux = r1 - r2 * c2; // O4 - A
        let uy = -(r2 * s2);
        let d2 = ux * ux + uy * uy;
        let d = d2.sqrt(); // not hypot: CPython's math.hypot differs from libm's
        if d == 0.0 {
            return if r3 == r4 { Geometry::Indeterminate } else { Geometry::NotAssemblable };
        }
        // d and the sums are rounded by a few ulp of the longest link: a triangle that
        // closes within that is flat (a dead point: SINGULAR), not one that cannot close
        // (e.g. the fold of the change point (1.8, 0.6, 1.8, 0.6) at theta2 = 0)
        let slack = FLAT_ULPS * f64::EPSILON * self.longest;
        let flat = |q: f64| if q < 0.0 && q >= -slack { 0.0 } else { q };
        let q1 = flat(d + r3 - r4);
        let q2 = flat(d - r3 + r4);
        let q3 = flat(r3 + r4 - d);
        if !(q1 >= 0.0 && q2 >= 0.0 && q3 >= 0.0) {
            return Geometry::NotAssemblable;
        }
        let two_dh = ((r3 + r4 + d) * q1 * q2 * q3).sqrt();
        Geometry::Triangle(Triangle { ux, uy, d2, two_dh, k: (r3 - r4) * (r3 + r4), r3r4: r3 * r4 })
    }

    /// Solves one crank angle by Newton-Raphson from `guess` (default: the closed form of
    /// `mode`). Not-assemblable angles are reported before any iteration; a converged
    /// point on the other mode is reported [`Status::BranchJump`].
    pub fn solve(
        &self,
        theta2: f64,
        mode: Mode,
        guess: Option<[f64; 2]>,
        opts: &NewtonOptions,
        history: Option<&mut Vec<f64>>,
    ) -> Point {
        let never = Poll::new(&Never);
        // Never does not interrupt: the error branch is unreachable, and harmless
        self.solve_polled(theta2, mode, guess, opts, history, &never)
            .unwrap_or_else(|_| Point::failed(Status::MaxIterations, 0, f64::NAN))
    }

    /// [`FourBar::solve`] that counts its Newton steps on `poll` and returns
    /// [`Error::Interrupted`] when the poll's interrupt asks to stop.
    pub fn solve_polled(
        &self,
        theta2: f64,
        mode: Mode,
        guess: Option<[f64; 2]>,
        opts: &NewtonOptions,
        history: Option<&mut Vec<f64>>,
        poll: &Poll<'_>,
    ) -> Result<Point, Error> {
        if !theta2.is_finite() {
            return Ok(Point::unsolved(Status::NonFinite).0);
        }
        Ok(self.solve_on(&self.at(theta2), mode, guess, opts, history, poll)?.0)
    }

    /// Solves on a loop already set up at a finite crank angle; also hands back the
    /// Jacobian at the solution.
    pub(crate) fn solve_on(
        &self,
        sys: &Loop<'_>,
        mode: Mode,
        guess: Option<[f64; 2]>,
        opts: &NewtonOptions,
        history: Option<&mut Vec<f64>>,
        poll: &Poll<'_>,
    ) -> Result<(Point, Matrix2<f64>), Error> {
        let start = match (self.geometry(sys.c2, sys.s2), guess) {
            (Geometry::NotAssemblable, _) => return Ok(Point::unsolved(Status::NotAssemblable)),
            (_, Some(g)) => Vector2::from(g),
            (Geometry::Triangle(t), None) => t.angles(mode).0,
            (Geometry::Indeterminate, None) => return Ok(Point::unsolved(Status::Singular)),
        };
        self.solve_from(sys, start, mode, opts, history, poll)
    }

    /// Newton from `start` on the loop `sys`, then the mode check.
    pub(crate) fn solve_from(
        &self,
        sys: &Loop<'_>,
        start: Vector2<f64>,
        mode: Mode,
        opts: &NewtonOptions,
        history: Option<&mut Vec<f64>>,
        poll: &Poll<'_>,
    ) -> Result<(Point, Matrix2<f64>), Error> {
        let out = newton::solve_polled(sys, start, opts, history, poll)?;
        let mut status = out.status;
        if status == Status::Converged && sys.sin34(&out.jacobian) * mode.sign() < 0.0 {
            status = Status::BranchJump;
        }
        let point = if status == Status::Converged {
            Point {
                theta3: wrap_angle(out.x[0]),
                theta4: wrap_angle(out.x[1]),
                status,
                nit: out.nit,
                residual: out.residual,
            }
        } else {
            Point::failed(status, out.nit, out.residual)
        };
        Ok((point, out.jacobian))
    }

    /// Jacobian of the unit-length loop ([`FourBar::unit_lengths`]) at (theta3, theta4).
    pub fn jacobian(&self, theta3: f64, theta4: f64) -> Matrix2<f64> {
        let [_, _, r3, r4] = self.r;
        let (s3, c3) = theta3.sin_cos();
        let (s4, c4) = theta4.sin_cos();
        Matrix2::new(-r3 * s3, r4 * s4, r3 * c3, -r4 * c4)
    }

    /// Angular velocities (omega3, omega4) for crank speed `omega2`, solving
    /// J w = -dF/dtheta2 omega2. NaN with [`Status::Singular`] at a dead point.
    pub fn velocity(&self, theta2: f64, theta3: f64, theta4: f64, omega2: f64, singular: f64) -> ([f64; 2], Status) {
        let j = self.jacobian(theta3, theta4);
        let (r2, s2, c2) = (self.r[1], theta2.sin(), theta2.cos());
        self.solve_linear(&j, Vector2::new(r2 * s2 * omega2, -(r2 * c2) * omega2), singular)
    }

    /// Angular accelerations (alpha3, alpha4), differentiating the loop twice: the same
    /// Jacobian with a right-hand side of centripetal terms and the crank's alpha2.
    #[allow(clippy::too_many_arguments)]
    pub fn acceleration(
        &self,
        theta2: f64,
        theta3: f64,
        theta4: f64,
        omega2: f64,
        omega3: f64,
        omega4: f64,
        alpha2: f64,
        singular: f64,
    ) -> ([f64; 2], Status) {
        let [_, r2, r3, r4] = self.r;
        let (s2, c2) = theta2.sin_cos();
        let (s3, c3) = theta3.sin_cos();
        let (s4, c4) = theta4.sin_cos();
        let j = Matrix2::new(-r3 * s3, r4 * s4, r3 * c3, -r4 * c4);
        let (w2s, w3s, w4s) = (omega2 * omega2, omega3 * omega3, omega4 * omega4);
        let b1 = r2 * s2 * alpha2 + r2 * c2 * w2s + r3 * c3 * w3s - r4 * c4 * w4s;
        let b2 = -(r2 * c2) * alpha2 + r2 * s2 * w2s + r3 * s3 * w3s - r4 * s4 * w4s;
        self.solve_linear(&j, Vector2::new(b1, b2), singular)
    }

    /// Dimensionless conditioning of a position with branch indicator `sin34`:
    /// |sin(theta4 - theta3)| min(r3, r4) / L. Rounding of the loop residual (~eps L)
    /// moves the angles by about eps / conditioning.
    #[inline]
    pub fn conditioning(&self, sin34: f64) -> f64 {
        sin34.abs() * self.cond_scale
    }

    /// Solves J x = b by Cramer's rule, refusing when the conditioning is below `singular`.
    fn solve_linear(&self, j: &Matrix2<f64>, b: Vector2<f64>, singular: f64) -> ([f64; 2], Status) {
        let ok = j.iter().chain(b.iter()).all(|v| v.is_finite());
        if !ok {
            return ([f64::NAN; 2], Status::NonFinite);
        }
        if self.conditioning(self.sin34_of(j)) < singular {
            return ([f64::NAN; 2], Status::Singular);
        }
        match cramer(j, &b) {
            Some(x) => ([x[0], x[1]], Status::Converged),
            None => ([f64::NAN; 2], Status::Singular),
        }
    }

    /// sin(theta4 - theta3) from the loop Jacobian: det J = r3 r4 sin(theta3 - theta4).
    #[inline]
    pub(crate) fn sin34_of(&self, j: &Matrix2<f64>) -> f64 {
        -det2(j) / (self.r[2] * self.r[3])
    }

    /// Position of a coupler point at distance `p` from the crank pin A, at angle `delta`
    /// from the coupler line A-B.
    pub fn coupler_point(&self, theta2: f64, theta3: f64, p: f64, delta: f64) -> [f64; 2] {
        let r2 = self.raw[1];
        let (s2, c2) = theta2.sin_cos();
        let (s, c) = (theta3 + delta).sin_cos();
        [r2 * c2 + p * c, r2 * s2 + p * s]
    }
}

/// Transmission angle (Norton): the acute angle between coupler and rocker, in [0, pi/2].
pub fn transmission_angle(theta3: f64, theta4: f64) -> f64 {
    let mu = wrap_angle(theta4 - theta3).abs();
    if mu > std::f64::consts::FRAC_PI_2 {
        std::f64::consts::PI - mu
    } else {
        mu
    }
}

#[inline]
fn det2(j: &Matrix2<f64>) -> f64 {
    j[(0, 0)] * j[(1, 1)] - j[(0, 1)] * j[(1, 0)]
}

/// Cramer's rule, as the seed reports write it (same operation order as the NumPy reference).
#[inline]
pub(crate) fn cramer(j: &Matrix2<f64>, b: &Vector2<f64>) -> Option<Vector2<f64>> {
    let d = det2(j);
    if d == 0.0 {
        return None;
    }
    let x0 = (b[0] * j[(1, 1)] - b[1] * j[(0, 1)]) / d;
    let x1 = (j[(0, 0)] * b[1] - j[(1, 0)] * b[0]) / d;
    Some(Vector2::new(x0, x1))
}

/// The four-bar loop at a fixed crank angle: f1, f2 in the unknowns (theta3, theta4).
///
/// It remembers the sines and cosines of its last libm evaluation: an iterate within
/// [`INCREMENT_MAX`] of it in both angles gets them by angle addition from there instead
/// of calling libm. Rotations start only from libm values and never chain, so every
/// evaluation is within about an ulp of libm however long the Newton path. This halves
/// the trigonometry of a sweep.
#[derive(Clone, Debug)]
pub struct Loop<'a> {
    fb: &'a FourBar,
    pub(crate) c2: f64,
    pub(crate) s2: f64,
    last: Cell<Option<(Vector2<f64>, [f64; 4])>>,
}

/// Largest angle change (rad) updated by angle addition rather than libm: 2^-7.
pub const INCREMENT_MAX: f64 = 0.0078125;

/// Taylor coefficients of sin dx - dx (odd powers 3..7) and cos dx - 1 (even powers 2..8).
const SIN_C: [f64; 3] = [-1.0 / 6.0, 1.0 / 120.0, -1.0 / 5040.0];
const COS_C: [f64; 4] = [-0.5, 1.0 / 24.0, -1.0 / 720.0, 1.0 / 40320.0];

/// sin(x + dx), cos(x + dx) from s = sin x, c = cos x for |dx| <= 2^-7: Taylor series of
/// sin dx and cos dx - 1 to degrees 7 and 8 (truncation below 1e-22), added as
/// corrections so nothing rounds against 1.
#[inline]
pub fn rotate(s: f64, c: f64, dx: f64) -> (f64, f64) {
    let x2 = dx * dx;
    let sd = dx + dx * x2 * (SIN_C[0] + x2 * (SIN_C[1] + x2 * SIN_C[2]));
    let cm = x2 * (COS_C[0] + x2 * (COS_C[1] + x2 * (COS_C[2] + x2 * COS_C[3])));
    (s + (s * cm + c * sd), c + (c * cm - s * sd))
}

impl Loop<'_> {
    #[inline]
    pub(crate) fn sin34(&self, j: &Matrix2<f64>) -> f64 {
        self.fb.sin34_of(j)
    }
}

impl System<2> for Loop<'_> {
    #[inline]
    fn eval(&self, x: &Vector2<f64>) -> (Vector2<f64>, Matrix2<f64>) {
        let [r1, r2, r3, r4] = self.fb.r;
        let [s3, c3, s4, c4] = match self.last.get() {
            Some((p, [s3, c3, s4, c4]))
                if (x[0] - p[0]).abs() < INCREMENT_MAX && (x[1] - p[1]).abs() < INCREMENT_MAX =>
            {
                let (s3, c3) = rotate(s3, c3, x[0] - p[0]);
                let (s4, c4) = rotate(s4, c4, x[1] - p[1]);
                [s3, c3, s4, c4]
            }
            _ => {
                let (s3, c3) = x[0].sin_cos();
                let (s4, c4) = x[1].sin_cos();
                // only libm values anchor later rotations: rotations never chain
                self.last.set(Some((*x, [s3, c3, s4, c4])));
                [s3, c3, s4, c4]
            }
        };
        let f1 = r2 * self.c2 + r3 * c3 - r4 * c4 - r1;
        let f2 = r2 * self.s2 + r3 * s3 - r4 * s4;
        let j = Matrix2::new(-r3 * s3, r4 * s4, r3 * c3, -r4 * c4);
        (Vector2::new(f1, f2), j)
    }

    #[inline]
    fn scale(&self) -> f64 {
        self.fb.longest
    }

    /// |sin(theta4 - theta3)| min(r3, r4) / L: the Hadamard ratio |det J| / (r3 r4) times
    /// the ratio that turns residual rounding into angle error.
    #[inline]
    fn conditioning(&self, j: &Matrix2<f64>) -> f64 {
        self.fb.conditioning(self.sin34(j))
    }

    #[inline]
    fn step(&self, j: &Matrix2<f64>, f: &Vector2<f64>) -> Option<Vector2<f64>> {
        cramer(j, &-f)
    }

    /// Both unknowns are angles: keep them in (-pi, pi] (the identity when already there).
    #[inline]
    fn normalize(&self, x: &mut Vector2<f64>) {
        x[0] = wrap_angle(x[0]);
        x[1] = wrap_angle(x[1]);
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use std::f64::consts::PI;

    const DEG: f64 = PI / 180.0;

    fn seed() -> FourBar {
        FourBar::new(6.0, 2.0, 5.0, 5.0).unwrap()
    }

    #[test]
    fn design_note_open_mode_at_zero() {
        // DESIGN.md: r = (6, 2, 5, 5), theta2 = 0, open: theta3 = 66.42 deg, theta4 = 113.58 deg
        let Assembly::Closed { theta3, theta4, sin34 } = seed().closed_form(0.0, Mode::Open) else { panic!() };
        assert!((theta3 / DEG - 66.42).abs() < 5e-3);
        assert!((theta4 / DEG - 113.58).abs() < 5e-3);
        assert!(sin34 > 0.0);
    }

    #[test]
    fn norton_example_4_1() {
        // Norton, Design of Machinery, Example 4-1: a=40, b=120, c=80, d=100, theta2=40 deg
        let fb = FourBar::new(100.0, 40.0, 120.0, 80.0).unwrap();
        for (mode, t3, t4) in [(Mode::Open, 20.30, 57.32), (Mode::Crossed, -60.98, -98.00)] {
            let Assembly::Closed { theta3, theta4, .. } = fb.closed_form(40.0 * DEG, mode) else { panic!() };
            assert!((theta3 / DEG - t3).abs() < 5e-3, "{mode:?} theta3 {}", theta3 / DEG);
            assert!((theta4 / DEG - t4).abs() < 5e-3, "{mode:?} theta4 {}", theta4 / DEG);
        }
    }

    #[test]
    fn newton_matches_closed_form_from_a_cold_guess() {
        let fb = seed();
        let opts = NewtonOptions::default();
        let p = fb.solve(45.0 * DEG, Mode::Open, Some([80.0 * DEG, 100.0 * DEG]), &opts, None);
        assert_eq!(p.status, Status::Converged);
        let Assembly::Closed { theta3, theta4, .. } = fb.closed_form(45.0 * DEG, Mode::Open) else { panic!() };
        assert!((p.theta3 - theta3).abs() < 1e-9 && (p.theta4 - theta4).abs() < 1e-9);
        assert!(p.residual < 1e-9);
    }

    #[test]
    fn crossed_guess_for_open_request_is_a_branch_jump() {
        let fb = seed();
        let Assembly::Closed { theta3, theta4, .. } = fb.closed_form(0.3, Mode::Crossed) else { panic!() };
        let p = fb.solve(0.3, Mode::Open, Some([theta3, theta4]), &NewtonOptions::default(), None);
        assert_eq!(p.status, Status::BranchJump);
        assert!(p.theta3.is_nan());
    }

    #[test]
    fn not_assemblable_before_any_iteration() {
        // triple rocker: r2 too long to turn fully
        let fb = FourBar::new(2.0, 5.0, 2.5, 2.0).unwrap();
        let p = fb.solve(PI, Mode::Open, None, &NewtonOptions::default(), None);
        assert_eq!((p.status, p.nit), (Status::NotAssemblable, 0));
    }

    #[test]
    fn invalid_lengths_name_the_parameter() {
        for (i, name) in ["r1", "r2", "r3", "r4"].iter().enumerate() {
            for bad in [0.0, -1.0, f64::NAN, f64::INFINITY] {
                let mut r = [6.0, 2.0, 5.0, 5.0];
                r[i] = bad;
                let e = FourBar::new(r[0], r[1], r[2], r[3]).unwrap_err().to_string();
                assert!(e.starts_with(name), "{e}");
            }
        }
    }

    #[test]
    fn any_scale_gives_the_seed_results() {
        // the problem is scale-free: power-of-two scales are bit-identical, others agree
        // to rounding, down to the smallest and up to the largest lengths a double holds
        let t2: Vec<f64> = crate::sweep::default_angles(361);
        let opts = crate::sweep::SweepOptions {
            mode: Mode::Open,
            newton: NewtonOptions::default(),
            predictor: crate::sweep::Predictor::Quadratic,
            method: crate::sweep::Method::Newton,
        };
        let base = crate::sweep::sweep(&seed(), &t2, None, &opts);
        let lim = seed().limits(Mode::Open);
        for k in [-1070, -1000, -340, -200, 0, 200, 340, 1020] {
            let s = times_pow2(1.0, k);
            let fb = FourBar::new(6.0 * s, 2.0 * s, 5.0 * s, 5.0 * s).unwrap();
            let sw = crate::sweep::sweep(&fb, &t2, None, &opts);
            assert_eq!(sw.status, base.status, "2^{k}");
            assert!(sw.theta3.iter().zip(&base.theta3).all(|(a, b)| a.to_bits() == b.to_bits()), "2^{k}");
            assert_eq!(fb.limits(Mode::Open), lim, "2^{k}");
        }
        for s in [1e-300, 1e-100, 1e-9, 3.0, 1e100, 1e160, 1e300] {
            let fb = FourBar::new(6.0 * s, 2.0 * s, 5.0 * s, 5.0 * s).unwrap();
            let sw = crate::sweep::sweep(&fb, &t2, None, &opts);
            assert_eq!(sw.status, base.status, "{s}");
            assert!(sw.theta4.iter().zip(&base.theta4).all(|(a, b)| (a - b).abs() < 1e-12), "{s}");
            let l = fb.limits(Mode::Open);
            assert!(l.full_rotation && l.dead_points.is_empty(), "{s}");
        }
    }

    #[test]
    fn lengths_the_unit_problem_cannot_hold_are_rejected() {
        let e = FourBar::new(1e300, 1e-300, 1e300, 1e300).unwrap_err().to_string();
        assert!(e.starts_with("r2 is too short"), "{e}");
        assert!(FourBar::new(5e-324, 1.0, 1.0, 1.0).is_ok());
        assert!(FourBar::new(1.0, 1e-300, 1.0, 1.0).is_ok());
        assert!(FourBar::new(5e-324, 5e-324, 5e-324, 5e-324).is_ok());
    }

    #[test]
    fn an_interrupt_stops_a_long_solve() {
        let opts = NewtonOptions::new(1e-300, 4_294_967_295).unwrap();
        let yes = || true;
        let p = seed().solve_polled(0.5, Mode::Open, Some([1.0, 2.0]), &opts, None, &Poll::new(&yes));
        assert_eq!(p, Err(Error::Interrupted));
    }

    #[test]
    fn velocity_matches_finite_difference_of_closed_form() {
        let fb = seed();
        let (t2, h) = (0.7, 1e-6);
        let cf = |t: f64| match fb.closed_form(t, Mode::Open) {
            Assembly::Closed { theta3, theta4, .. } => [theta3, theta4],
            _ => panic!(),
        };
        let [t3, t4] = cf(t2);
        let (w, st) = fb.velocity(t2, t3, t4, 1.0, 1e-7);
        assert_eq!(st, Status::Converged);
        let (p, m) = (cf(t2 + h), cf(t2 - h));
        assert!((w[0] - (p[0] - m[0]) / (2.0 * h)).abs() < 1e-7);
        assert!((w[1] - (p[1] - m[1]) / (2.0 * h)).abs() < 1e-7);
        let (wp, _) = fb.velocity(t2 + h, p[0], p[1], 1.0, 1e-7);
        let (wm, _) = fb.velocity(t2 - h, m[0], m[1], 1.0, 1e-7);
        let (a, _) = fb.acceleration(t2, t3, t4, 1.0, w[0], w[1], 0.0, 1e-7);
        assert!((a[0] - (wp[0] - wm[0]) / (2.0 * h)).abs() < 1e-6);
        assert!((a[1] - (wp[1] - wm[1]) / (2.0 * h)).abs() < 1e-6);
    }
}
