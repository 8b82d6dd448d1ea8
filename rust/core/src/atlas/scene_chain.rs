//! Atlas linkages with no closed form, solved by the scene solver: the Stephenson III
//! six-bar, whose input crank drives a loop of two ternary links (a Newton group). Its
//! parameters are the drawn points; the drawing is its own assembly, and the curve is what
//! the scene's sweep reaches from it (the whole turn, or the arc between its dead points).

use std::f64::consts::TAU;

use super::shape::{Curve, Pose, MAX_POINTS};
use crate::interrupt::Never;
use crate::scene::format::sweep_options;
use crate::scene::{Plan, Scene, SceneSpec, SceneSweepBuffers, Xy};

/// The Stephenson III's points: ground pivots j3 (0, 0) and j7 (1, 0), then the drawn
/// ones its 12 parameters give in pairs (crank tip j6, ternary T1's j1 and j2, ternary
/// T2's j4 and j5, the tracer P on T2).
pub const STEPHENSON3_POINTS: [&str; 8] = ["j3", "j7", "j6", "j1", "j2", "j4", "j5", "P"];
/// Fewest points of an arc worth keeping.
const MIN_ARC: usize = 16;

/// The scene of a Stephenson III drawn as `p` (see [`STEPHENSON3_POINTS`]): ground j3-j7,
/// crank j7-j6 (the input), T1 {j1, j2, j3}, T2 {j4, j5, j6, P}, B1 {j1, j4}, B2 {j2, j5}.
pub fn stephenson3_spec(p: &[f64]) -> SceneSpec {
    let mut points: Vec<(String, Xy)> = vec![("j3".into(), [0.0, 0.0]), ("j7".into(), [1.0, 0.0])];
    for (k, name) in STEPHENSON3_POINTS[2..].iter().enumerate() {
        points.push(((*name).into(), [p[2 * k], p[2 * k + 1]]));
    }
    let link = |name: &str, pts: &[&str]| (name.to_string(), pts.iter().map(|s| s.to_string()).collect());
    SceneSpec {
        points,
        links: vec![
            link("ground", &["j3", "j7"]),
            link("crank", &["j7", "j6"]),
            link("T1", &["j1", "j2", "j3"]),
            link("T2", &["j4", "j5", "j6", "P"]),
            link("B1", &["j1", "j4"]),
            link("B2", &["j2", "j5"]),
        ],
        ground: "ground".into(),
        input: ("crank".into(), "j7".into()),
        ..SceneSpec::default()
    }
}

/// A plan solving every point, with the drawn input angle; None for a drawing the scene
/// format refuses.
fn plan(p: &[f64]) -> Option<(Plan, f64)> {
    let scene = Scene::new(stephenson3_spec(p)).ok()?;
    let theta0 = scene.input_angle();
    Some((scene.plan(None).ok()?, theta0))
}

/// A solved value: the 8 points and the conditioning.
type Solved = ([Xy; 8], f64);

/// Sweeps `p`'s plan at `theta`: per value, the points (all 8) and conditioning, or None.
fn solve(plan: &Plan, theta: &[f64]) -> Option<Vec<Option<Solved>>> {
    // what the drawn circuit does not reach is all the atlas needs to know of it
    let opts = sweep_options(false, 1.0).ok()?.with_classify(false);
    let mut buf = SceneSweepBuffers::new(plan, theta.len(), false).ok()?;
    plan.sweep(theta, &opts, buf.out(), &Never).ok()?;
    let np = plan.points.len();
    Some(
        (0..theta.len())
            .map(|i| {
                (buf.status[i] == 0).then(|| {
                    let mut pts = [[0.0; 2]; 8];
                    for (k, &q) in plan.points.iter().enumerate().take(8) {
                        let at = (i * np + k) * 2;
                        pts[q] = [buf.points[at], buf.points[at + 1]];
                    }
                    (pts, buf.det[i].abs())
                })
            })
            .collect(),
    )
}

/// The pose of the Stephenson III drawn as `p` at input angle `theta` (reached from the
/// drawing).
pub(super) fn stephenson3_pose(p: &[f64], theta: f64) -> Option<Pose> {
    let (plan, _) = plan(p)?;
    let (pts, cond) = solve(&plan, &[theta])?.pop()??;
    let mut out = Pose { points: [[0.0; 2]; MAX_POINTS], count: 8, conditioning: cond };
    out.points[..8].copy_from_slice(&pts);
    Some(out)
}

/// The coupler curve of the Stephenson III drawn as `p` at `samples` input angles from
/// the drawn one: the whole turn, or the arc of them the sweep reaches (at least
/// [`MIN_ARC`] points).
pub(super) fn stephenson3_curve(p: &[f64], samples: usize) -> Option<Curve> {
    let (plan, theta0) = plan(p)?;
    let theta: Vec<f64> = (0..samples).map(|k| theta0 + TAU * k as f64 / samples as f64).collect();
    let rows = solve(&plan, &theta)?;
    let ok = |k: usize| rows[k].is_some();
    let closed = (0..samples).all(ok);
    let (lo, len) = if closed {
        (0, samples)
    } else {
        let fwd = (0..samples).take_while(|&k| ok(k)).count();
        let back = (1..samples).take_while(|&k| ok(samples - k)).count();
        (samples - back, fwd + back)
    };
    if len < MIN_ARC.min(samples) {
        return None;
    }
    let mut curve =
        Curve { points: Vec::with_capacity(len), theta: Vec::with_capacity(len), closed, conditioning: f64::INFINITY };
    for j in 0..len {
        let k = (lo + j) % samples;
        let (pts, cond) = rows[k]?;
        // past the drawn angle backwards the input sits a turn lower
        let turn = if !closed && k >= lo { TAU } else { 0.0 };
        curve.points.push(pts[7]);
        curve.theta.push(theta[k] - turn);
        curve.conditioning = curve.conditioning.min(cond);
    }
    Some(curve)
}
