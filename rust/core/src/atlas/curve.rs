//! A linkage's coupler curve as the input moves: the whole turn where the input turns
//! fully, otherwise its reachable arc (the longest run of assembled input angles, its
//! ends refined by bisection to the dead points), on one assembly throughout.

use std::f64::consts::TAU;

use super::chain::pose;
pub use super::shape::Curve;
use super::Topology;

/// Input angles tried to tell a full turn from a rocking input.
pub const COARSE: usize = 72;
/// Points of an atlas curve (equally spaced input angles).
pub const SAMPLES: usize = 128;
/// Bisection steps refining each end of a rocking input's arc.
const BISECTIONS: usize = 40;

/// The coupler curve of `topology` with parameters `p` and signs `s` at `samples` input
/// angles; None where no two neighbouring coarse angles assemble.
pub fn coupler_curve(topology: Topology, p: &[f64], s: &[f64], samples: usize) -> Option<Curve> {
    if topology == Topology::Stephenson3 {
        return super::scene_chain::stephenson3_curve(p, samples);
    }
    let at = |t: f64| pose(topology, p, s, t);
    let step = TAU / COARSE as f64;
    let ok: Vec<bool> = (0..COARSE).map(|k| at(k as f64 * step).is_some()).collect();
    let (lo, hi, closed) = if ok.iter().all(|&o| o) {
        (0.0, TAU * (samples - 1) as f64 / samples as f64, true)
    } else {
        // the longest cyclic run of assembled coarse angles: [first, first + len)
        let (mut first, mut len) = (0usize, 0usize);
        let start = ok.iter().position(|&o| !o)?;
        let mut k = 0;
        while k < COARSE {
            let i = (start + k) % COARSE;
            if ok[i] {
                let run = (0..COARSE).take_while(|&j| ok[(i + j) % COARSE]).count();
                if run > len {
                    (first, len) = (i, run);
                }
                k += run;
            } else {
                k += 1;
            }
        }
        if len < 2 {
            return None;
        }
        let t0 = first as f64 * step;
        let t1 = t0 + (len - 1) as f64 * step;
        (edge(&at, t0, t0 - step), edge(&at, t1, t1 + step), false)
    };
    let mut points = Vec::with_capacity(samples);
    let mut theta = Vec::with_capacity(samples);
    let mut conditioning = f64::INFINITY;
    let div = (samples - 1).max(1) as f64;
    for j in 0..samples {
        let t = lo + (hi - lo) * j as f64 / div;
        let q = at(t)?;
        points.push(q.tracer());
        theta.push(t);
        conditioning = conditioning.min(q.conditioning);
    }
    Some(Curve { points, theta, closed, conditioning })
}

/// The last assembled angle from `good` towards `bad` (bisection).
fn edge(at: &impl Fn(f64) -> Option<super::shape::Pose>, mut good: f64, mut bad: f64) -> f64 {
    for _ in 0..BISECTIONS {
        let mid = 0.5 * (good + bad);
        if at(mid).is_some() {
            good = mid;
        } else {
            bad = mid;
        }
    }
    good
}
