//! The ways from the drawn pose to each input value of a sweep, which make a value's pose
//! independent of the rest of the array (DESIGN, "Scenes"): the direct way (the input moved
//! from its drawn value straight to t, up or down), and for an angle the other way round
//! (to the same angle the opposite way, less than a turn). The values are visited in order
//! of their distance from the drawn value along each way, so one continuation per way and
//! direction serves them all, whatever the order of the array.

use std::f64::consts::TAU;

/// One continuation from the drawn value: the indices it visits with the input value it
/// solves each at, in the order it reaches them.
pub(super) type Run = Vec<(usize, f64)>;

/// The direct ways of the finite values of `theta` from `theta0`: the values above it in
/// increasing order, those below in decreasing order.
pub(super) fn direct(theta: &[f64], theta0: f64) -> [Run; 2] {
    let mut up: Run = Vec::new();
    let mut down: Run = Vec::new();
    for (k, &t) in theta.iter().enumerate() {
        if !t.is_finite() {
            continue;
        }
        if t >= theta0 {
            up.push((k, t));
        } else {
            down.push((k, t));
        }
    }
    // a stable sort keeps repeated values in array order (their answers are equal anyway)
    up.sort_by(|a, b| a.1.total_cmp(&b.1));
    down.sort_by(|a, b| b.1.total_cmp(&a.1));
    [up, down]
}

/// The other way round to the angles `theta[k]` for the indices `ks`: the same angle less
/// than a turn the opposite way from `theta0` (no way at all for a whole number of turns:
/// the drawn angle), as runs up and down (see [`direct`]).
pub(super) fn other(theta: &[f64], theta0: f64, ks: impl Iterator<Item = usize>) -> [Run; 2] {
    let mut up: Run = Vec::new();
    let mut down: Run = Vec::new();
    for k in ks {
        let d = theta[k] - theta0;
        if d >= 0.0 {
            // reached going down by less than a turn (a whole number of turns up is the
            // drawn angle itself: no way at all)
            let back = d.rem_euclid(TAU);
            down.push((k, if back > 0.0 { theta0 + back - TAU } else { theta0 }));
        } else {
            let ahead = (-d).rem_euclid(TAU);
            up.push((k, if ahead > 0.0 { theta0 + TAU - ahead } else { theta0 }));
        }
    }
    up.sort_by(|a, b| a.1.total_cmp(&b.1));
    down.sort_by(|a, b| b.1.total_cmp(&a.1));
    [up, down]
}

/// True when the continuation along every direct way moves in steps of at most `max_step`
/// (from the drawn value, through the values in the order [`direct`] visits them), or, for
/// an angle, when the values cover the whole turn that way (taken modulo a turn, the gaps
/// between neighbours at most `max_step`): then a column sweep whose every step is far from
/// a dead point is the motion reached either way, and the values' order does not matter.
pub(super) fn covered(theta: &[f64], theta0: f64, max_step: f64, linear: bool) -> bool {
    let gaps_ok = |run: &Run| {
        let mut at = theta0;
        run.iter().all(|&(_, t)| {
            let ok = (t - at).abs() <= max_step;
            at = t;
            ok
        })
    };
    let [up, down] = direct(theta, theta0);
    if gaps_ok(&up) && gaps_ok(&down) {
        return true;
    }
    if linear {
        return false;
    }
    let mut turn: Vec<f64> = theta.iter().filter(|t| t.is_finite()).map(|t| (t - theta0).rem_euclid(TAU)).collect();
    turn.sort_by(f64::total_cmp);
    let mut at = 0.0;
    turn.iter().chain(std::iter::once(&TAU)).all(|&x| {
        let ok = x - at <= max_step;
        at = x;
        ok
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn direct_ways_sort_each_side_away_from_the_drawn_value() {
        let theta = [0.3, -0.1, 0.1, f64::NAN, -0.4, 0.2];
        let [up, down] = direct(&theta, 0.0);
        assert_eq!(up, vec![(2, 0.1), (5, 0.2), (0, 0.3)]);
        assert_eq!(down, vec![(1, -0.1), (4, -0.4)]);
    }

    #[test]
    fn the_other_way_reaches_the_same_angle_the_opposite_way() {
        let theta = [0.0 + 3.0, -1.0, 7.0];
        let [up, down] = other(&theta, 0.0, 0..3);
        assert_eq!(up.len(), 1);
        assert_eq!(up[0].0, 1);
        assert!((up[0].1 - (TAU - 1.0)).abs() < 1e-15);
        // 3 rad up is 2pi - 3 down; 7 rad up (a turn and a bit) is 2pi - (7 - 2pi) down
        assert_eq!(down.iter().map(|r| r.0).collect::<Vec<_>>(), vec![0, 2]);
        assert!((down[0].1 - (3.0 - TAU)).abs() < 1e-15);
        assert!((down[1].1 - ((7.0 - TAU) - TAU)).abs() < 1e-15);
    }

    #[test]
    fn a_shifted_full_turn_is_covered_modulo_the_turn() {
        let n = 361;
        let step = TAU / (n - 1) as f64;
        let shifted: Vec<f64> = (0..n).map(|k| 0.5 + k as f64 * step).collect();
        assert!(!covered(&shifted, 0.0, 1.5 * step, true));
        assert!(covered(&shifted, 0.0, 1.5 * step, false));
        let half: Vec<f64> = (0..n / 2).map(|k| 0.5 + k as f64 * step).collect();
        assert!(!covered(&half, 0.0, 1.5 * step, false));
    }
}
