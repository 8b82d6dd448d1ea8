//! The RRR dyad: a point reached by two links from two known points, in closed form
//! (circle intersection), on the side of the line K1 -> K2 it was drawn on.

use crate::scene::vec2::{cross, dot, perp, sub, Xy};

/// Known points closer than this fraction of r1 + r2 coincide.
const COINCIDENT: f64 = 1e-12;
/// Rounding of |k1 k2| and of the Heron factors, relative to d + r1 + r2.
const ROUNDING: f64 = 4.0 * f64::EPSILON;

/// What [`closed_form`] found, as a number (a block's cases are then a plain array).
pub(crate) const SOLVED: f64 = 0.0;
/// The known points coincide (to rounding).
pub(crate) const COINCIDE: f64 = 1.0;
/// |r1 - r2| <= |k1 k2| <= r1 + r2 fails.
pub(crate) const APART: f64 = 2.0;

/// The circle intersection, with no branch: the point on `side` at `r1` from `a` and `r2`
/// from `b`, its signed conditioning, and the case ([`SOLVED`], [`COINCIDE`], [`APART`]).
/// One square root for d = |ab| and one for 2 d h from Heron's formula in factored form
/// (nothing cancels near a dead point, and power-of-two scaling is exact), no
/// trigonometry. Coincident points give conditioning 0 with equal links (every point of
/// the circle closes the dyad: a continuum) and NaN otherwise; points out of reach NaN;
/// the point means something only where the case is `SOLVED`. [`Dyad::solve`] and the
/// column sweep's block of 128 values (where, with no branch, it vectorizes) both run it.
#[inline(always)]
pub(crate) fn closed_form(a: Xy, b: Xy, side: f64, r1: f64, r2: f64) -> (Xy, f64, f64) {
    let u = sub(b, a);
    let d2 = dot(u, u);
    let d = d2.sqrt();
    // known points that coincide to rounding: with equal links every point of the circle
    // closes the dyad (a continuum, not two assemblies)
    let tiny = COINCIDENT * (r1 + r2);
    // a factor below zero by no more than the rounding of d is a dead point (the two links
    // in line), not a failure to close: sweeps step over it
    let round = ROUNDING * (d + r1 + r2);
    let q1 = d + r1 - r2;
    let q2 = d - r1 + r2;
    let q3 = r1 + r2 - d;
    let meets = (q1 >= -round) & (q2 >= -round) & (q3 >= -round);
    let two_dh = ((r1 + r2 + d) * q1.max(0.0) * q2.max(0.0) * q3.max(0.0)).sqrt();
    let along = d2 + (r1 - r2) * (r1 + r2);
    let h = side * two_dh;
    let w = perp(u);
    let inv = 0.5 / d2;
    let p = [a[0] + (along * u[0] + h * w[0]) * inv, a[1] + (along * u[1] + h * w[1]) * inv];
    let coincident = d <= tiny;
    let equal = (r1 - r2).abs() <= tiny;
    let det = if coincident {
        if equal {
            0.0
        } else {
            f64::NAN
        }
    } else if meets {
        h / (2.0 * r1 * r2)
    } else {
        f64::NAN
    };
    let case = if coincident {
        COINCIDE
    } else if meets {
        SOLVED
    } else {
        APART
    };
    (p, det, case)
}

/// Point `p` at distance `r1` from known point `k1` and `r2` from `k2`, on side `side`
/// (+1: left of k1 -> k2) — the side of the drawn pose.
#[derive(Clone, Debug, PartialEq)]
pub(crate) struct Dyad {
    pub p: usize,
    pub k1: usize,
    pub k2: usize,
    pub r1: f64,
    pub r2: f64,
    pub side: f64,
    /// The two links meeting at `p` (through `k1` and `k2`).
    pub links: [usize; 2],
}

/// What the closed form finds.
#[derive(Clone, Copy, Debug, PartialEq)]
pub(crate) enum DyadOut {
    /// The point and the signed sine of the triangle's angle at it: its sign is the side,
    /// its size the distance from a dead point (the two links in line).
    Solved(Xy, f64),
    /// |r1 - r2| <= |k1 k2| <= r1 + r2 fails.
    NotAssemblable,
    /// k1 = k2 with r1 = r2 (to rounding): every point of the circle closes the dyad.
    Indeterminate,
}

impl Dyad {
    /// The dyad's point on its drawn side ([`closed_form`], its case as [`DyadOut`]).
    #[inline]
    pub(crate) fn solve(&self, a: Xy, b: Xy) -> DyadOut {
        self.solve_side(a, b, self.side)
    }

    /// [`Dyad::solve`] on a given side (+1 / -1) instead of the drawn one.
    #[inline]
    pub(crate) fn solve_side(&self, a: Xy, b: Xy, side: f64) -> DyadOut {
        self.solve_radii(a, b, side, self.r1, self.r2)
    }

    /// [`Dyad::solve_side`] with the arms' lengths given (they change with a linear input
    /// on a fused guide).
    #[inline]
    pub(crate) fn solve_radii(&self, a: Xy, b: Xy, side: f64, r1: f64, r2: f64) -> DyadOut {
        let (p, det, case) = closed_form(a, b, side, r1, r2);
        if case == SOLVED {
            DyadOut::Solved(p, det)
        } else if case == COINCIDE && det == 0.0 {
            DyadOut::Indeterminate
        } else {
            DyadOut::NotAssemblable
        }
    }

    /// Signed sine of the angle at `p` of the triangle k1-p-k2, from positions.
    #[inline]
    pub(crate) fn det_at(&self, p: Xy, a: Xy, b: Xy) -> f64 {
        cross(sub(a, p), sub(b, p)) / (self.r1 * self.r2)
    }

    /// Velocity of the solved point from the known points' velocities: the two link
    /// lengths stay fixed, (p - k_i) . (v - v_i) = 0. `None` at a dead point.
    #[inline]
    pub(crate) fn velocity(p: Xy, a: Xy, b: Xy, va: Xy, vb: Xy) -> Option<Xy> {
        let (e1, e2) = (sub(p, a), sub(p, b));
        solve2(e1, e2, dot(e1, va), dot(e2, vb))
    }

    /// Acceleration of the solved point (velocity `v`) from the known points' velocities
    /// and accelerations: (p - k_i) . (w - w_i) + |v - v_i|^2 = 0. `None` at a dead point.
    #[inline]
    pub(crate) fn acceleration(p: Xy, a: Xy, b: Xy, v: Xy, va: Xy, vb: Xy, wa: Xy, wb: Xy) -> Option<Xy> {
        let (e1, e2) = (sub(p, a), sub(p, b));
        let (d1, d2) = (sub(v, va), sub(v, vb));
        solve2(e1, e2, dot(e1, wa) - dot(d1, d1), dot(e2, wb) - dot(d2, d2))
    }
}

/// x with e1 . x = c1 and e2 . x = c2 (Cramer); `None` when e1 and e2 are parallel.
#[inline]
fn solve2(e1: Xy, e2: Xy, c1: f64, c2: f64) -> Option<Xy> {
    let det = cross(e1, e2);
    if det == 0.0 {
        return None;
    }
    Some([(c1 * e2[1] - c2 * e1[1]) / det, (e1[0] * c2 - e2[0] * c1) / det])
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn circle_intersection_and_side() {
        let d = Dyad { p: 0, k1: 0, k2: 0, r1: 5.0, r2: 5.0, side: 1.0, links: [0, 0] };
        // k1 = (2, 0), k2 = (6, 0): the seed four-bar at theta2 = 0, open mode
        let DyadOut::Solved(p, s) = d.solve([2.0, 0.0], [6.0, 0.0]) else { panic!() };
        assert!((p[0] - 4.0).abs() < 1e-15 && (p[1] - 21f64.sqrt()).abs() < 1e-15, "{p:?}");
        assert!((s - 4.0 * 21f64.sqrt() / 25.0).abs() < 1e-15, "{s}");
        let m = Dyad { side: -1.0, ..d.clone() };
        let DyadOut::Solved(q, t) = m.solve([2.0, 0.0], [6.0, 0.0]) else { panic!() };
        assert!((q[1] + 21f64.sqrt()).abs() < 1e-15 && t < 0.0);
        assert_eq!(d.solve([0.0, 0.0], [10.5, 0.0]), DyadOut::NotAssemblable);
        assert_eq!(d.solve([1.0, 1.0], [1.0, 1.0]), DyadOut::Indeterminate);
    }

    #[test]
    fn velocity_keeps_lengths() {
        let (a, b, p) = ([0.0, 0.0], [4.0, 0.0], [1.0, 2.0]);
        let (va, vb) = ([0.3, -0.2], [0.0, 0.5]);
        let v = Dyad::velocity(p, a, b, va, vb).unwrap();
        assert!(dot(sub(p, a), sub(v, va)).abs() < 1e-15);
        assert!(dot(sub(p, b), sub(v, vb)).abs() < 1e-15);
    }

    #[test]
    fn acceleration_is_the_second_derivative_of_the_closed_form() {
        // k1 turns on a unit circle (k1'' = -k1), k2 is fixed: central differences of the
        // solved point against the closed-form acceleration
        let d = Dyad { p: 0, k1: 0, k2: 0, r1: 2.5, r2: 2.0, side: 1.0, links: [0, 0] };
        let at = |t: f64| {
            let DyadOut::Solved(p, _) = d.solve([t.cos(), t.sin()], [3.0, 0.5]) else { panic!() };
            p
        };
        let (t, h) = (0.7_f64, 1e-4);
        let (pm, p0, pp) = (at(t - h), at(t), at(t + h));
        let a = [t.cos(), t.sin()];
        let va = [-a[1], a[0]];
        let v = Dyad::velocity(p0, a, [3.0, 0.5], va, [0.0; 2]).unwrap();
        let w = Dyad::acceleration(p0, a, [3.0, 0.5], v, va, [0.0; 2], [-a[0], -a[1]], [0.0; 2]).unwrap();
        for k in 0..2 {
            let fd = (pp[k] - 2.0 * p0[k] + pm[k]) / (h * h);
            assert!((fd - w[k]).abs() < 1e-6, "{k}: {fd} vs {}", w[k]);
        }
    }
}
