//! The four-bar by its lengths, as the report's simulator shows it: the pose at a crank
//! angle on the chosen assembly mode (closed form, with its status), the coupler point's
//! path over a full turn, the Grashof condition and Barker class, and the limit positions
//! (dead points, the assemblable crank intervals). The same core calls as
//! `pk.FourBar(...).closed_form`, `.coupler_point`, `.grashof()` and `.limits(mode)`.

use planarkin_core::fourbar::{classify, closed_form_into, coupler_into, default_angles, transmission_angle};
use planarkin_core::solve::newton::SINGULAR_THRESHOLD;
use planarkin_core::{FourBar, Mode, Never};
use serde_json::{json, Value};

use crate::json::{number, pair, status_name};

/// Crank angles of the coupler path: 0 to 360 degrees in 1-degree steps.
const PATH_ANGLES: usize = 361;

fn err(e: planarkin_core::Error) -> String {
    e.to_string()
}

/// `{"r": [r1, r2, r3, r4], "theta2": t, "mode": "open" | "crossed", "p": p, "delta": d}`.
/// The coupler path (361 x 2: P's x, y at each crank angle of `path_theta2`) goes to `nums`.
pub(crate) fn solve(req: &Value, nums: &mut Vec<f64>) -> Result<Value, String> {
    let r = req.get("r").and_then(Value::as_array).filter(|r| r.len() == 4).ok_or("r must be [r1, r2, r3, r4]")?;
    let mut lengths = [0.0; 4];
    for (k, (v, slot)) in r.iter().zip(&mut lengths).enumerate() {
        *slot = v.as_f64().ok_or_else(|| format!("r{} must be a real number", k + 1))?;
    }
    let fb = FourBar::new(lengths[0], lengths[1], lengths[2], lengths[3]).map_err(err)?;
    let mode_name = req.get("mode").and_then(Value::as_str).unwrap_or("open");
    let mode = Mode::parse(mode_name).map_err(err)?;
    let theta2 = number(req, "theta2")?;
    let (p, delta) = (number(req, "p")?, number(req, "delta")?);
    let [r1, _, r3, _] = fb.lengths();

    let (mut t3, mut t4, mut st) = ([0.0], [0.0], [0i8]);
    closed_form_into(&fb, &[theta2], mode, SINGULAR_THRESHOLD, &mut t3, &mut t4, &mut st, &Never).map_err(err)?;
    // the pins as pk.FourBar's sweeps place them: A is the coupler point at p = 0
    let a = fb.coupler_point(theta2, 0.0, 0.0, 0.0);
    let b = fb.coupler_point(theta2, t3[0], r3, 0.0);
    let cp = fb.coupler_point(theta2, t3[0], p, delta);

    let angles = default_angles(PATH_ANGLES);
    let n = angles.len();
    let (mut pt3, mut pt4, mut pst) = (vec![0.0; n], vec![0.0; n], vec![0i8; n]);
    closed_form_into(&fb, &angles, mode, SINGULAR_THRESHOLD, &mut pt3, &mut pt4, &mut pst, &Never).map_err(err)?;
    let (mut x, mut y) = (vec![0.0; n], vec![0.0; n]);
    coupler_into(&fb, &angles, &pt3, p, delta, &mut x, &mut y, &Never).map_err(err)?;
    let offset = nums.len();
    nums.extend(x.iter().zip(&y).flat_map(|(&x, &y)| [x, y]));

    let g = classify(fb.lengths());
    let l = fb.limits(mode);
    let rocker = l.rocker.map(|(lo, hi)| json!([[lo.theta2, lo.theta4], [hi.theta2, hi.theta4]]));
    Ok(json!({
        "lengths": lengths,
        "mode": mode_name,
        "theta2": theta2,
        "theta3": t3[0],
        "theta4": t4[0],
        "status": status_name(st[0]),
        "transmission_angle": transmission_angle(t3[0], t4[0]),
        "points": {
            "O2": pair([0.0, 0.0]),
            "O4": pair([r1, 0.0]),
            "A": pair(a),
            "B": pair(b),
            "P": pair(cp),
        },
        "grashof": {"condition": g.class.name(), "barker": g.barker.code(), "kind": g.barker.kind(), "description": g.barker.description()},
        "limits": {
            "toggles": l.toggles,
            "dead_points": l.dead_points,
            "intervals": l.intervals,
            "full_rotation": l.full_rotation,
            "rocker": rocker,
        },
        "path": {"offset": offset, "n": n, "theta2": angles, "status": pst},
    }))
}
