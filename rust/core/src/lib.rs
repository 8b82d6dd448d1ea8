//! planarkin-core: planar linkage kinematics in pure Rust (no Python types).
//!
//! A Newton-Raphson solver generic over the number of unknowns ([`newton`]), the
//! four-bar linkage that plugs into it ([`fourbar`]), continuation sweeps over crank
//! angles ([`sweep`]) and rayon-parallel batches of linkages ([`batch`]).

// `!(x >= t)` is deliberate throughout: it is true for NaN, which must fail every check.
#![allow(clippy::neg_cmp_op_on_partial_ord)]

pub mod arrays;
pub mod batch;
pub mod error;
pub mod fourbar;
pub mod grashof;
pub mod homotopy;
pub mod interrupt;
pub mod limits;
pub mod newton;
pub mod scene;
pub mod simd;
pub mod status;
pub mod sweep;

pub use error::Error;
pub use fourbar::{Assembly, FourBar, Mode};
pub use grashof::{Barker, Grashof, GrashofClass};
pub use interrupt::{Interrupt, Never};
pub use newton::{NewtonOptions, System};
pub use status::Status;
pub use sweep::{Method, Predictor, SweepOptions};

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
