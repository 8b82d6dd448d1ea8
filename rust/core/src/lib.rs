//! planarkin-core: planar linkage kinematics in pure Rust (no Python types).
//!
//! The crate is organised by subject, one folder each:
//! - [`fourbar`]: the four-bar linkage: validated lengths, closed form, Newton sweeps and
//!   batches, pointwise kernels, limit positions, Grashof and Barker classes, and the
//!   four-bar's SIMD kernels;
//! - [`scene`]: any one-degree-of-freedom planar linkage described as data: validation,
//!   the plan its outputs need, sweeps, every assembly, circuits;
//! - [`solve`]: the solvers the subjects share: Newton-Raphson generic over the number
//!   of unknowns, and the all-solutions homotopy.
//!
//! Shared leaves at the top, which the subjects use and which use no subject: [`error`],
//! [`status`], [`interrupt`], [`parallel`] (thread pools), [`simd`] (the SIMD switch and
//! polynomial sin/cos/atan2), and [`wrap_angle`].

pub mod atlas;
pub mod error;
pub mod forces;
pub mod fourbar;
pub mod interrupt;
pub mod parallel;
pub(crate) mod rng;
pub mod scene;
pub mod simd;
pub mod solve;
pub mod status;

pub use error::Error;
pub use fourbar::{ClosedForm, FourBar, Method, Mode, Predictor, SweepOptions};
pub use interrupt::{Interrupt, Never};
pub use solve::newton::{NewtonOptions, System};
pub use status::Status;

use std::f64::consts::{PI, TAU};

/// Wraps an angle into (-pi, pi]. Angles already there are returned bit-for-bit.
#[inline]
pub fn wrap_angle(a: f64) -> f64 {
    if a > -PI && a <= PI {
        return a;
    }
    let r = (a + PI).rem_euclid(TAU) - PI;
    if r <= -PI {
        PI
    } else {
        r
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn wrap_keeps_the_principal_interval() {
        assert_eq!(wrap_angle(PI), PI);
        assert_eq!(wrap_angle(-PI), PI);
        assert_eq!(wrap_angle(0.25), 0.25);
        assert!((wrap_angle(3.0 * PI + 0.5) - (-PI + 0.5)).abs() < 1e-15);
        assert!((wrap_angle(-7.0) - (-7.0 + TAU)).abs() < 1e-15);
        let w = wrap_angle(1e12);
        assert!(w > -PI && w <= PI);
    }
}
