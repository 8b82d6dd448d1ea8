//! The lane types of the four-bar's SIMD Newton kernels and their portable per-lane
//! operations: one Newton evaluation of [`W`] linkages, the predictor's rates and the
//! wrap to (-pi, pi], lane by lane, in the scalar code's operation order.

use std::f64::consts::PI;

use crate::simd::math::sin_cos;
use crate::wrap_angle;

use crate::fourbar::options::Predictor;

/// Lanes per group: 4 f64 in an AVX2 register.
pub(crate) const W: usize = 4;
/// One f64 per lane.
pub(crate) type V = [f64; W];
/// One flag per lane.
pub(crate) type M = [bool; W];

/// `[expr for each lane l]`, as a plain loop: a closure (`array::from_fn`) would not be
/// inlined into the `target_feature` function and would lose AVX2 and FMA.
macro_rules! lanes {
    (|$l:ident| $e:expr) => {{
        let mut o = [Default::default(); W];
        for $l in 0..W {
            o[$l] = $e;
        }
        o
    }};
}
pub(crate) use lanes;

/// `sweep::predictor_rates` lane by lane (same operations), from the Jacobians of
/// converged lanes (whose determinants are non-zero: the step was taken with them).
#[inline(always)]
pub(crate) fn rates(r2: &V, s2: f64, c2: f64, j: &[V; 4], p: Predictor) -> ([V; 2], [V; 2]) {
    let zero = [[0.0; W]; 2];
    if p == Predictor::Previous {
        return (zero, zero);
    }
    let [j00, j01, j10, j11] = j;
    let d: V = lanes!(|l| j00[l] * j11[l] - j01[l] * j10[l]);
    let (b0, b1): (V, V) = (lanes!(|l| r2[l] * s2), lanes!(|l| -(r2[l] * c2)));
    let v0: V = lanes!(|l| (b0[l] * j11[l] - b1[l] * j01[l]) / d[l]);
    let v1: V = lanes!(|l| (j00[l] * b1[l] - j10[l] * b0[l]) / d[l]);
    if p == Predictor::Tangent {
        return ([v0, v1], zero);
    }
    let (w3s, w4s): (V, V) = (lanes!(|l| v0[l] * v0[l]), lanes!(|l| v1[l] * v1[l]));
    let c0: V = lanes!(|l| r2[l] * c2 + j10[l] * w3s[l] + j11[l] * w4s[l]);
    let c1: V = lanes!(|l| r2[l] * s2 - j00[l] * w3s[l] - j01[l] * w4s[l]);
    let a0: V = lanes!(|l| (c0[l] * j11[l] - c1[l] * j01[l]) / d[l]);
    let a1: V = lanes!(|l| (j00[l] * c1[l] - j10[l] * c0[l]) / d[l]);
    ([v0, v1], [a0, a1])
}

/// Lane-wise wrap to (-pi, pi]: the identity in range (as `wrap_angle`), libm's remainder
/// only for the lanes out of range.
#[inline(always)]
pub(crate) fn wrap(x: V) -> V {
    let mut x = x;
    if !x.iter().all(|&a| a > -PI && a <= PI) {
        for a in x.iter_mut() {
            *a = wrap_angle(*a);
        }
    }
    x
}

/// One Newton evaluation of [`W`] linkages at crank (sin, cos) = (s2, c2) and iterates
/// (x3, x4): residuals, the residual over the scale, the Jacobian, its determinant,
/// sin(theta4 - theta3), the Newton correction and its largest component.
pub(crate) struct Eval {
    pub f1: V,
    pub f2: V,
    pub j: [V; 4],
    pub residual: V,
    pub det: V,
    pub sin34: V,
    pub dx: [V; 2],
    pub step: V,
}

/// The scalar `Loop::eval`, `newton::solve` and `cramer` lane by lane, in their
/// operation order (with the polynomial sin/cos), at one crank angle per lane.
#[inline(always)]
pub(crate) fn eval_lanes(r: &[V; 4], scale: &V, r3r4: &V, s2: &V, c2: &V, x: &[V; 2]) -> Eval {
    let [r1, r2, r3, r4] = r;
    let sc3: [(f64, f64); W] = lanes!(|l| sin_cos(x[0][l]));
    let sc4: [(f64, f64); W] = lanes!(|l| sin_cos(x[1][l]));
    let (s3, c3): (V, V) = (lanes!(|l| sc3[l].0), lanes!(|l| sc3[l].1));
    let (s4, c4): (V, V) = (lanes!(|l| sc4[l].0), lanes!(|l| sc4[l].1));
    let f1: V = lanes!(|l| r2[l] * c2[l] + r3[l] * c3[l] - r4[l] * c4[l] - r1[l]);
    let f2: V = lanes!(|l| r2[l] * s2[l] + r3[l] * s3[l] - r4[l] * s4[l]);
    let j00: V = lanes!(|l| -r3[l] * s3[l]);
    let j01: V = lanes!(|l| r4[l] * s4[l]);
    let j10: V = lanes!(|l| r3[l] * c3[l]);
    let j11: V = lanes!(|l| -r4[l] * c4[l]);
    let residual: V = lanes!(|l| 0.0f64.max(f1[l].abs()).max(f2[l].abs()) / scale[l]);
    let det: V = lanes!(|l| j00[l] * j11[l] - j01[l] * j10[l]);
    let sin34: V = lanes!(|l| -det[l] / r3r4[l]);
    let dx0: V = lanes!(|l| (-f1[l] * j11[l] - -f2[l] * j01[l]) / det[l]);
    let dx1: V = lanes!(|l| (j00[l] * -f2[l] - j10[l] * -f1[l]) / det[l]);
    let step: V = lanes!(|l| dx0[l].abs().max(dx1[l].abs()));
    Eval { f1, f2, j: [j00, j01, j10, j11], residual, det, sin34, dx: [dx0, dx1], step }
}

/// What the closed-form predictor's check of a point needs besides the point (`across`):
/// the linkage and the criteria.
pub(crate) struct Check {
    pub r: [V; 4],
    pub scale: V,
    pub r3r4: V,
    pub cond_scale: f64,
    pub tol: f64,
    pub singular: f64,
    pub sign: f64,
}

/// [`W`] consecutive points of that check: their closed forms (replaced where accepted)
/// and where the accepted ones' residuals go.
pub(crate) struct Block<'a> {
    pub theta3: &'a mut [f64],
    pub theta4: &'a mut [f64],
    pub residual: &'a mut [f64],
    pub trig: &'a [(f64, f64)],
}
