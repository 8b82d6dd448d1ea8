//! The four-bar's closed form: the triangle A-B-O4 at a crank angle (or why there is
//! none), and the coupler and rocker angles of either assembly mode from it, with no
//! iteration and no trigonometry but two atan2.

use nalgebra::Vector2;

use super::model::{FourBar, Mode, FLAT_ULPS};

/// What the closed form finds at one crank angle.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum ClosedForm {
    /// The solution of the requested mode, wrapped to (-pi, pi], with its branch
    /// indicator sin(theta4 - theta3) (its sign is the mode's, or 0 at a toggle).
    Solved { theta3: f64, theta4: f64, sin34: f64 },
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

impl FourBar {
    /// Closed form (circle intersection) for `mode` at `theta2`.
    pub fn closed_form(&self, theta2: f64, mode: Mode) -> ClosedForm {
        let (s2, c2) = theta2.sin_cos();
        self.closed_form_cs(c2, s2, mode)
    }

    /// Closed form from cos/sin of the crank angle.
    pub(crate) fn closed_form_cs(&self, c2: f64, s2: f64, mode: Mode) -> ClosedForm {
        match self.geometry(c2, s2) {
            Geometry::Triangle(t) => {
                let (x, sin34) = t.angles(mode);
                ClosedForm::Solved { theta3: x[0], theta4: x[1], sin34 }
            }
            Geometry::NotAssemblable => ClosedForm::NotAssemblable,
            Geometry::Indeterminate => ClosedForm::Indeterminate,
        }
    }

    /// The triangle A-B-O4 at a crank angle, or why there is none: one square root for
    /// d = |A O4| and one for the height of B, no trigonometry. B lies at distance r3
    /// from A and r4 from O4; 2 d h comes from Heron's formula in exactly factored form,
    /// so nothing cancels near a toggle and power-of-two scaling is exact.
    #[inline]
    pub(crate) fn geometry(&self, c2: f64, s2: f64) -> Geometry {
        let [r1, r2, r3, r4] = self.unit_lengths();
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
        let slack = FLAT_ULPS * f64::EPSILON * self.longest();
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
}
