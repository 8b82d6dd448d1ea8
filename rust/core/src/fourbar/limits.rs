//! Limit positions of a four-bar, all from the closed form: the crank angles where
//! det J = 0 (dead points; toggles where a crank that cannot turn fully stops), the
//! assemblable crank-angle intervals, and the rocker's extreme angles on one mode.
//!
//! det J = 0 exactly when B lies on the line A-O4, i.e. d = |A O4| equals r3 + r4 or
//! |r3 - r4|. With d^2 = r1^2 + r2^2 - 2 r1 r2 cos(theta2), each such d gives the crank
//! angles +-t with t = 2 atan2(sqrt(1 - cos t), sqrt(1 + cos t)) from exact factorizations.

use std::f64::consts::{PI, TAU};

use super::closed_form::ClosedForm;
use super::grashof::sums_equal;
use super::model::{FourBar, Mode};
use crate::wrap_angle;

/// The angle t in [0, pi] at which a point at radius `r` from the origin, at polar angle
/// t, lies at distance `e` from (r1, 0). `Err(true)`: the distance always exceeds `e`;
/// `Err(false)`: it is always below `e`.
fn reach(r1: f64, r: f64, e: f64) -> Result<f64, bool> {
    let one_minus = (e - r1 + r) * (e + r1 - r); // 2 r1 r (1 - cos t)
    let one_plus = (r1 + r - e) * (r1 + r + e); // 2 r1 r (1 + cos t)
    if one_minus < 0.0 {
        Err(true)
    } else if one_plus < 0.0 {
        Err(false)
    } else {
        Ok(2.0 * one_minus.sqrt().atan2(one_plus.sqrt()))
    }
}

/// Extreme rocker angle on one mode and the crank angle where it occurs.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Extreme {
    pub theta2: f64,
    pub theta4: f64,
}

/// Limit positions of a linkage on one assembly mode.
#[derive(Clone, Debug, PartialEq)]
pub struct Limits {
    /// Crank angles in (-pi, pi], sorted, where det J = 0 and the crank stops (reverses).
    /// Empty when the crank turns fully.
    pub toggles: Vec<f64>,
    /// Every crank angle in (-pi, pi], sorted, where det J = 0: the toggles plus the change
    /// points a fully turning crank passes through (where the two modes meet).
    pub dead_points: Vec<f64>,
    /// Assemblable crank-angle intervals [start, end]: start in [-pi, pi], end > start,
    /// traversed counter-clockwise (end may exceed pi when an interval contains theta2 = pi).
    pub intervals: Vec<[f64; 2]>,
    /// The crank turns a full revolution.
    pub full_rotation: bool,
    /// The rocker's smallest and largest angle on this mode (None when the rocker turns
    /// fully or the linkage never assembles): the rocker sweeps the interval from the
    /// first to the second counter-clockwise. The smallest is wrapped to (-pi, pi]; the
    /// largest is the smallest plus the swing, so it is never below it (and may exceed pi
    /// when the interval contains theta4 = pi).
    pub rocker: Option<(Extreme, Extreme)>,
}

impl FourBar {
    /// Limit positions on `mode`, from the closed form.
    ///
    /// A change-point linkage folds flat (all links collinear) at theta2 = 0 when
    /// r1 + r4 = r2 + r3 or r1 + r3 = r2 + r4, and at theta2 = pi when r1 + r2 = r3 + r4:
    /// decided exactly on the binary values (as the Grashof class is), so these dead
    /// points are listed even where rounding the distances would miss them.
    pub fn limits(&self, mode: Mode) -> Limits {
        let [r1, r2, r3, r4] = self.unit_lengths();
        // d <= r3 + r4 for |theta2| <= hi; d >= |r3 - r4| for |theta2| >= lo.
        let mut outer = reach(r1, r2, r3 + r4);
        let mut inner = reach(r1, r2, (r3 - r4).abs());
        if sums_equal(r1, r2, r3, r4) {
            outer = Ok(PI); // d(pi) = r1 + r2 = r3 + r4
        }
        if sums_equal(r1, r4, r2, r3) || sums_equal(r1, r3, r2, r4) {
            inner = Ok(0.0); // d(0) = |r1 - r2| = |r3 - r4|
        }
        let mut dead: Vec<f64> =
            [outer, inner].iter().filter_map(|x| x.ok()).flat_map(|t| [t, -t]).map(|t| wrap_angle(t) + 0.0).collect();
        dead.sort_by(f64::total_cmp);
        dead.dedup();
        let hi = match outer {
            Ok(t) => Some(t),
            Err(false) => Some(PI),
            Err(true) => None, // never short enough: never assembles
        };
        let lo = match inner {
            Ok(t) => Some(t),
            Err(true) => Some(0.0),
            Err(false) => None, // never long enough
        };
        let (intervals, toggles) = match (lo, hi) {
            (Some(lo), Some(hi)) if lo <= hi => {
                let stops: Vec<f64> = [lo, hi].into_iter().filter(|&t| t > 0.0 && t < PI).collect();
                let mut toggles: Vec<f64> = stops.iter().flat_map(|&t| [t, -t]).collect();
                toggles.sort_by(f64::total_cmp);
                toggles.dedup();
                let iv = match (lo == 0.0, hi == PI) {
                    (true, true) => vec![[-PI, PI]],
                    (true, false) => vec![[-hi, hi]],
                    (false, true) => vec![[lo, TAU - lo]],
                    (false, false) => vec![[-hi, -lo], [lo, hi]],
                };
                (iv, toggles)
            }
            _ => (Vec::new(), Vec::new()),
        };
        let full_rotation = intervals == [[-PI, PI]];
        let rocker = self.rocker_extremes(mode, &intervals, &toggles);
        Limits { toggles, dead_points: dead, intervals, full_rotation, rocker }
    }

    /// theta4 at a toggle, where B is on the line A-O4 (no square root of a rounded zero).
    fn toggle_theta4(&self, theta2: f64) -> f64 {
        let [r1, r2, r3, r4] = self.unit_lengths();
        let (s2, c2) = theta2.sin_cos();
        let phi = (-(r2 * s2)).atan2(r1 - r2 * c2); // direction A -> O4
        let d2 = (r1 - r2 * c2).powi(2) + (r2 * s2).powi(2);
        // outer toggle (d = r3 + r4): B between A and O4; inner with r3 > r4: B beyond O4
        let beyond = r3 > r4 && (d2 - (r3 - r4).powi(2)).abs() < ((r3 + r4).powi(2) - d2).abs();
        wrap_angle(if beyond { phi } else { phi + PI })
    }

    /// Crank angles where crank and coupler are collinear on `mode` (omega4 = 0), with theta4.
    fn stationary(&self, mode: Mode) -> Vec<Extreme> {
        let [r1, r2, r3, r4] = self.unit_lengths();
        let mut out = Vec::new();
        for (rho, flip) in [(r2 + r3, false), ((r2 - r3).abs(), r3 > r2)] {
            if rho == 0.0 {
                continue;
            }
            let Ok(beta) = reach(r1, rho, r4) else { continue };
            for b in [beta, -beta] {
                let (bx, by) = (rho * b.cos(), rho * b.sin());
                let t2 = wrap_angle(if flip { b + PI } else { b });
                let (ax, ay) = (r2 * t2.cos(), r2 * t2.sin());
                // mode of this configuration: sign of cross(B - A, B - O4)
                let cross = (bx - ax) * by - (by - ay) * (bx - r1);
                if cross * mode.sign() >= 0.0 {
                    out.push(Extreme { theta2: t2, theta4: by.atan2(bx - r1) });
                }
            }
        }
        out
    }

    /// Extremes of theta4 over the assemblable intervals on `mode`. Candidates are the
    /// stationary points and the toggles; a dense closed-form sampling between them only
    /// serves to unwrap theta4 consistently, so the extremes are exact candidate values.
    fn rocker_extremes(&self, mode: Mode, intervals: &[[f64; 2]], toggles: &[f64]) -> Option<(Extreme, Extreme)> {
        const SAMPLES: usize = 720;
        let stationary = self.stationary(mode);
        let mut best: Option<(Extreme, f64, Extreme, f64)> = None;
        let mut anchor: Option<f64> = None;
        for &[a, b] in intervals {
            let mut pts: Vec<(f64, Option<f64>)> =
                (0..=SAMPLES).map(|i| (a + (b - a) * i as f64 / SAMPLES as f64, None)).collect();
            for s in &stationary {
                let t = a + (s.theta2 - a).rem_euclid(TAU);
                if t <= b {
                    pts.push((t, Some(s.theta4)));
                }
            }
            for &t in toggles {
                let t = a + (t - a).rem_euclid(TAU);
                if t <= b + 1e-12 {
                    pts.push((t, Some(self.toggle_theta4(t))));
                }
            }
            pts.sort_by(|x, y| x.0.total_cmp(&y.0));
            let mut prev = anchor;
            for (t2, exact) in pts {
                let t4 = match exact {
                    Some(v) => v,
                    None => match self.closed_form(t2, mode) {
                        ClosedForm::Solved { theta4, .. } => theta4,
                        _ => continue,
                    },
                };
                let u = match prev {
                    Some(p) => p + wrap_angle(t4 - p),
                    None => t4,
                };
                prev = Some(u);
                let e = Extreme { theta2: wrap_angle(t2), theta4: t4 };
                best = Some(match best {
                    None => (e, u, e, u),
                    Some((mn, umn, mx, umx)) => {
                        let (mn, umn) = if u < umn { (e, u) } else { (mn, umn) };
                        let (mx, umx) = if u > umx { (e, u) } else { (mx, umx) };
                        (mn, umn, mx, umx)
                    }
                });
            }
            anchor = prev;
        }
        let (mn, umn, mx, umx) = best?;
        if umx - umn >= TAU - 1e-9 {
            return None; // the output turns fully: it is a crank, not a rocker
        }
        // the largest as the smallest plus the swing: never below it, across +-pi too
        Some((mn, Extreme { theta2: mx.theta2, theta4: mn.theta4 + (umx - umn) }))
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    const DEG: f64 = PI / 180.0;

    #[test]
    fn seed_crank_rocker_turns_fully_with_the_closed_form_rocker_range() {
        let l = FourBar::new(6.0, 2.0, 5.0, 5.0).unwrap().limits(Mode::Open);
        assert!(l.full_rotation && l.toggles.is_empty() && l.dead_points.is_empty());
        let (mn, mx) = l.rocker.unwrap();
        assert!((mn.theta4 / DEG - 101.54).abs() < 5e-3, "{}", mn.theta4 / DEG);
        assert!((mx.theta4 / DEG - 150.07).abs() < 5e-3, "{}", mx.theta4 / DEG);
        // rocker extremes are where crank and coupler are collinear: omega4 = 0
        for e in [mn, mx] {
            let ClosedForm::Solved { theta3, theta4, .. } =
                FourBar::new(6.0, 2.0, 5.0, 5.0).unwrap().closed_form(e.theta2, Mode::Open)
            else {
                panic!()
            };
            assert!((theta4 - e.theta4).abs() < 1e-12);
            assert!(wrap_angle(theta3 - e.theta2).abs() < 1e-7 || wrap_angle(theta3 - e.theta2 - PI).abs() < 1e-7);
        }
    }

    #[test]
    fn triple_rocker_toggles_bound_the_assemblable_interval() {
        let fb = FourBar::new(2.0, 5.0, 2.5, 2.0).unwrap();
        let l = fb.limits(Mode::Open);
        assert!(!l.full_rotation && !l.toggles.is_empty());
        for &t in &l.toggles {
            // just inside: assembles; just outside: does not
            let inside = l.intervals.iter().any(|&[a, b]| {
                let x = a + (t - a).rem_euclid(TAU);
                x >= a - 1e-12 && x <= b + 1e-12
            });
            assert!(inside);
        }
        for &[a, b] in &l.intervals {
            assert!(matches!(fb.closed_form(a + 1e-9, Mode::Open), ClosedForm::Solved { .. }));
            assert!(matches!(fb.closed_form(b - 1e-9, Mode::Open), ClosedForm::Solved { .. }));
            assert_eq!(fb.closed_form(a - 1e-6, Mode::Open), ClosedForm::NotAssemblable);
            assert_eq!(fb.closed_form(b + 1e-6, Mode::Open), ClosedForm::NotAssemblable);
        }
    }

    #[test]
    fn double_crank_output_turns_fully() {
        let l = FourBar::new(2.0, 5.0, 6.0, 5.5).unwrap().limits(Mode::Open); // GCCC
        assert!(l.full_rotation && l.rocker.is_none());
    }

    #[test]
    fn change_point_folds_are_dead_points_even_where_distances_round() {
        // 1.8 = 3 * 0.6 rounded: |r1 - r2| and |r3 - r4| round apart, the sums do not
        for (r, want) in [
            ([6.0, 5.0, 3.0, 2.0], vec![0.0]),
            ([6.0, 2.0, 6.0, 2.0], vec![0.0, PI]),
            ([1.7999999999999998, 0.6, 1.7999999999999998, 0.6], vec![0.0, PI]),
            ([0.30000000000000004, 0.2, 0.5, 0.6000000000000001], vec![]), // not a change point
            ([0.003, 0.002, 0.005, 0.006], vec![0.0]),
        ] {
            let fb = FourBar::new(r[0], r[1], r[2], r[3]).unwrap();
            for mode in [Mode::Open, Mode::Crossed] {
                let l = fb.limits(mode);
                for &w in &want {
                    assert!(l.dead_points.contains(&w), "{r:?} {mode:?}: {:?}", l.dead_points);
                    assert!(!l.toggles.contains(&w), "{r:?} {mode:?}: {:?}", l.toggles);
                }
            }
        }
    }

    #[test]
    fn rocker_max_is_never_below_min() {
        for r in [[6.0, 5.0, 3.0, 2.0], [6.0, 2.0, 5.0, 5.0], [4.0, 3.0, 1.5, 2.0], [1.0, 0.3, 1.2, 0.5]] {
            let fb = FourBar::new(r[0], r[1], r[2], r[3]).unwrap();
            for mode in [Mode::Open, Mode::Crossed] {
                if let Some((mn, mx)) = fb.limits(mode).rocker {
                    assert!(mx.theta4 >= mn.theta4 && mx.theta4 - mn.theta4 < TAU, "{r:?} {mode:?}");
                    assert!(mn.theta4 > -PI && mn.theta4 <= PI);
                }
            }
        }
    }

    #[test]
    fn parallelogram_passes_its_change_points() {
        let l = FourBar::new(6.0, 2.0, 6.0, 2.0).unwrap().limits(Mode::Open);
        assert!(l.full_rotation && l.toggles.is_empty());
        assert_eq!(l.dead_points, vec![0.0, PI]);
    }
}
