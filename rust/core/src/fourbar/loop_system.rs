//! The four-bar's loop equations at a fixed crank angle as a Newton [`System`] in
//! (theta3, theta4), with the sines and cosines of nearby iterates by angle addition.

use std::cell::Cell;

use nalgebra::{Matrix2, Vector2};

use super::model::{cramer, FourBar};
use crate::solve::newton::System;
use crate::wrap_angle;

impl FourBar {
    /// The loop equations at crank angle `theta2`, as a Newton system in (theta3, theta4).
    pub fn at(&self, theta2: f64) -> Loop<'_> {
        let (s2, c2) = theta2.sin_cos();
        self.at_sin_cos(s2, c2)
    }

    /// [`FourBar::at`] from sin and cos of the crank angle (shared across a batch).
    pub fn at_sin_cos(&self, s2: f64, c2: f64) -> Loop<'_> {
        Loop { fb: self, c2, s2, last: Cell::new(None) }
    }
}

/// The four-bar loop at a fixed crank angle: f1, f2 in the unknowns (theta3, theta4).
///
/// It remembers the sines and cosines of its last libm evaluation: an iterate within
/// 2^-7 rad of it in both angles gets them by angle addition from there instead
/// of calling libm. Shifts start only from libm values and never chain, so every
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
const INCREMENT_MAX: f64 = 0.0078125;

/// Taylor coefficients of sin dx - dx (odd powers 3..7) and cos dx - 1 (even powers 2..8).
const SIN_C: [f64; 3] = [-1.0 / 6.0, 1.0 / 120.0, -1.0 / 5040.0];
const COS_C: [f64; 4] = [-0.5, 1.0 / 24.0, -1.0 / 720.0, 1.0 / 40320.0];

/// sin(x + dx), cos(x + dx) from s = sin x, c = cos x for |dx| <= 2^-7: Taylor series of
/// sin dx and cos dx - 1 to degrees 7 and 8 (truncation below 1e-22), added as
/// corrections so nothing rounds against 1.
#[inline]
fn sin_cos_shifted(s: f64, c: f64, dx: f64) -> (f64, f64) {
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
        let [r1, r2, r3, r4] = self.fb.unit_lengths();
        let [s3, c3, s4, c4] = match self.last.get() {
            Some((p, [s3, c3, s4, c4]))
                if (x[0] - p[0]).abs() < INCREMENT_MAX && (x[1] - p[1]).abs() < INCREMENT_MAX =>
            {
                let (s3, c3) = sin_cos_shifted(s3, c3, x[0] - p[0]);
                let (s4, c4) = sin_cos_shifted(s4, c4, x[1] - p[1]);
                [s3, c3, s4, c4]
            }
            _ => {
                let (s3, c3) = x[0].sin_cos();
                let (s4, c4) = x[1].sin_cos();
                // only libm values anchor later shifts: shifts never chain
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
        self.fb.longest()
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
