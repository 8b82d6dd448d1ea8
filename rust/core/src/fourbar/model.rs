//! The four-bar linkage itself: validated lengths (kept scale-free), the assembly
//! modes, one solved point, and velocity and acceleration from the loop's Jacobian.
//! Ground O2 = (0, 0) to O4 = (r1, 0); angles in radians, counter-clockwise.

use nalgebra::{Matrix2, Vector2};

use crate::error::{positive_finite, quoted, Error, Real};
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
            other => Err(Error::invalid("mode", "must be 'open' or 'crossed'", quoted(other))),
        }
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
pub(crate) const FLAT_ULPS: f64 = 8.0;

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
pub(super) fn times_pow2(mut x: f64, mut k: i32) -> f64 {
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
                return Err(Error::invalid(name(i), TOO_SHORT, Real(raw[i])));
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

    /// min(r3, r4) / L: the conditioning of a position is |sin34| times this.
    #[inline]
    pub(crate) fn cond_scale(&self) -> f64 {
        self.cond_scale
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
