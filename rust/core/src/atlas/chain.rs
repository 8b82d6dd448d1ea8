//! The coupler point of an atlas linkage at one input angle, in closed form: a crank and
//! one or two dyads (circle-circle or circle-line intersections) in the normalised frame
//! of [`Topology`], with each dyad's conditioning (the sine of its transmission angle).

pub use super::shape::{Pose, MAX_POINTS};
use super::Topology;
use crate::scene::Xy;

/// The names of a topology's points, in the order of [`Pose::points`] (the tracer last).
pub fn pose_names(topology: Topology) -> &'static [&'static str] {
    match topology {
        Topology::FourBar => &["O2", "O4", "A", "B", "P"],
        Topology::SliderCrank => &["O2", "A", "B", "P"],
        Topology::Watt2 => &["O2", "O4", "O6", "A", "B", "C", "D", "P"],
        Topology::Stephenson3 => &super::scene_chain::STEPHENSON3_POINTS,
    }
}

/// Intersection of the circles (q, lq) and (r, lr) on the side `sign` of q -> r (+1: to
/// its left), and the transmission sine at it; None where they do not meet.
#[inline]
fn dyad(q: Xy, lq: f64, r: Xy, lr: f64, sign: f64) -> Option<(Xy, f64)> {
    let (dx, dy) = (r[0] - q[0], r[1] - q[1]);
    let d2 = dx * dx + dy * dy;
    let d = d2.sqrt();
    let a = (lq * lq - lr * lr + d2) / (2.0 * d);
    let h2 = lq * lq - a * a;
    if !(h2 >= 0.0) || d == 0.0 {
        return None;
    }
    let h = sign * h2.sqrt();
    let (ex, ey) = (dx / d, dy / d);
    let p = [q[0] + a * ex - h * ey, q[1] + a * ey + h * ex];
    Some((p, h.abs() * d / (lq * lr)))
}

/// The point of a link drawn from `a` to `b` at (u, v) in units of |b - a|.
#[inline]
fn on_link(a: Xy, b: Xy, u: f64, v: f64) -> Xy {
    let (dx, dy) = (b[0] - a[0], b[1] - a[1]);
    [a[0] + u * dx - v * dy, a[1] + u * dy + v * dx]
}

/// The pose of `topology` with parameters `p` and assembly signs `s` at input angle
/// `theta` (the crank's angle from the ground line O2 -> O4, or from +x for the
/// slider-crank); None where it does not assemble. The Stephenson III has no closed
/// form: its pose is the scene solver's, reached from its drawing.
pub fn pose(topology: Topology, p: &[f64], s: &[f64], theta: f64) -> Option<Pose> {
    if topology == Topology::Stephenson3 {
        return super::scene_chain::stephenson3_pose(p, theta);
    }
    let (sn, cs) = theta.sin_cos();
    let mut out = Pose { points: [[0.0; 2]; MAX_POINTS], count: 0, conditioning: 1.0 };
    let mut put = |pts: &[Xy], cond: f64| {
        out.points[..pts.len()].copy_from_slice(pts);
        out.count = pts.len();
        out.conditioning = cond;
    };
    match topology {
        Topology::FourBar => {
            let (o2, o4) = ([0.0, 0.0], [1.0, 0.0]);
            let a = [p[0] * cs, p[0] * sn];
            let (b, c) = dyad(a, p[1], o4, p[2], s[0])?;
            put(&[o2, o4, a, b, on_link(a, b, p[3], p[4])], c);
        }
        Topology::SliderCrank => {
            let a = [cs, sn];
            let dy = p[1] - a[1];
            let w2 = p[0] * p[0] - dy * dy;
            if !(w2 >= 0.0) {
                return None;
            }
            let w = w2.sqrt();
            let b = [a[0] + s[0] * w, p[1]];
            put(&[[0.0, 0.0], a, b, on_link(a, b, p[2], p[3])], w / p[0]);
        }
        Topology::Watt2 => {
            let (o2, o4, o6) = ([0.0, 0.0], [1.0, 0.0], [p[5], p[6]]);
            let a = [p[0] * cs, p[0] * sn];
            let (b, c1) = dyad(a, p[1], o4, p[2], s[0])?;
            let phi = (b[1] - o4[1]).atan2(b[0] - o4[0]) + p[4];
            let c = [o4[0] + p[3] * phi.cos(), o4[1] + p[3] * phi.sin()];
            let (d, c2) = dyad(c, p[7], o6, p[8], s[1])?;
            put(&[o2, o4, o6, a, b, c, d, on_link(c, d, p[9], p[10])], c1.min(c2));
        }
        Topology::Stephenson3 => unreachable!("solved by the scene solver above"),
    }
    Some(out)
}
