//! A candidate's coupler curve placed onto a target path: the similarity (scale, turn,
//! shift), the stretch of the curve (the fraction of its arc length) and its start and
//! direction that fit the target best in least squares, and the input angle that reaches
//! each target point. A closed target is matched against the whole of a closed curve;
//! an open or partial one against arcs of any curve.

use std::f64::consts::TAU;

use super::curve::{coupler_curve, Curve};
use super::descriptor::{arc_positions, cumulative, resample};
use super::Topology;
use crate::error::Error;
use crate::interrupt::Interrupt;
use crate::parallel::prelude::*;
use crate::scene::Xy;

/// The fractions of a candidate's arc length tried for an open or partial target.
pub const FRACTIONS: [f64; 9] = [1.0, 0.8, 0.65, 0.5, 0.4, 0.3, 0.22, 0.16, 0.12];
/// Points of a candidate's arc-length resampling.
const ARC: usize = 256;
/// How finely a placement is searched: `offsets` starts per direction along an arc (around
/// a closed target every start, or four times `offsets` in a quick pass) and the target
/// resampled to `resolution` points.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct Search {
    /// Starts per direction.
    pub offsets: usize,
    /// Points of the target's resampling.
    pub resolution: usize,
    /// Search the stretch and start near the best finely (an open or partial target).
    pub local: bool,
}

impl Search {
    /// The placement a refinement starts from.
    pub const FINE: Search = Search { offsets: 64, resolution: 64, local: true };
    /// A quick pass over many candidates (an open target scanned over an atlas), about
    /// 40 times cheaper, whose best are then placed finely.
    pub const COARSE: Search = Search { offsets: 12, resolution: 16, local: false };
}

/// (cost, a, b, fraction, direction, start) of the best fit so far.
type Best = (f64, Xy, Xy, f64, f64, f64);

/// The best placement of a curve onto a target.
#[derive(Clone, Debug)]
pub struct Placement {
    /// Residual of the fit over the target's spread (0: a perfect fit, 1: none).
    pub cost: f64,
    /// Complex factor a (scale and turn) of `target ~ a * curve + b`.
    pub a: Xy,
    /// Complex shift b.
    pub b: Xy,
    /// The fraction of the curve's arc length the target spans.
    pub fraction: f64,
    /// The curve runs against the target's order (the input decreases along it).
    pub reversed: bool,
    /// The input angle reaching each target point (unwrapped along the arc).
    pub theta: Vec<f64>,
}

/// The point at float position x (in arc-length samples) of `v`, wrapping a closed one.
fn at_position(v: &[Xy], closed: bool, x: f64) -> Xy {
    let n = v.len();
    let x = if closed { x.rem_euclid(n as f64) } else { x.clamp(0.0, (n - 1) as f64) };
    let i = (x.floor() as usize).min(n - 1);
    let w = x - i as f64;
    let j = if closed { (i + 1) % n } else { (i + 1).min(n - 1) };
    let (a, b) = (v[i], v[j]);
    [a[0] + w * (b[0] - a[0]), a[1] + w * (b[1] - a[1])]
}

/// Resamples a curve to `ARC` points by arc length, with the input angle at each.
fn arc_samples(curve: &Curve) -> (Vec<Xy>, Vec<f64>) {
    let (pts, th) = (&curve.points, &curve.theta);
    let m = pts.len();
    arc_positions(pts, curve.closed, ARC)
        .into_iter()
        .map(|(i, w)| {
            let k = (i + 1) % m;
            let (a, b) = (pts[i], pts[k]);
            // past the last sample of a closed curve the input has turned once more
            let tb = if k == 0 { th[0] + TAU } else { th[k] };
            ([a[0] + w * (b[0] - a[0]), a[1] + w * (b[1] - a[1])], th[i] + w * (tb - th[i]))
        })
        .unzip()
}

/// The best placement of `curve` onto the target `target` (points in order, `closed` or
/// not) over `fractions` of the curve's arc length (a closed target takes the whole of
/// a closed curve) and the starts and resolution of `search`; None where no arc of the
/// curve can carry the target (a closed target on a rocking input's arc).
pub fn match_curve(curve: &Curve, target: &[Xy], closed: bool, fractions: &[f64], search: Search) -> Option<Placement> {
    let (offsets, res) = (search.offsets.max(2), search.resolution.max(3));
    if target.len() < 2 || curve.points.len() < 2 || (closed && !curve.closed) {
        return None;
    }
    let (cand, ang) = arc_samples(curve);
    // the target by arc length, centred, and each given point's arc fraction
    let tcum = cumulative(target, closed);
    let ttotal = *tcum.last()?;
    if !(ttotal > 0.0) {
        return None;
    }
    let at: Vec<f64> = tcum[..target.len()].iter().map(|s| s / ttotal).collect();
    let tz = resample(target, closed, res);
    let tdiv = if closed { res } else { res - 1 } as f64;
    let mean = |v: &[Xy]| {
        let n = v.len() as f64;
        let s = v.iter().fold([0.0, 0.0], |a, p| [a[0] + p[0], a[1] + p[1]]);
        [s[0] / n, s[1] / n]
    };
    let zc = mean(&tz);
    let tz: Vec<Xy> = tz.iter().map(|p| [p[0] - zc[0], p[1] - zc[1]]).collect();
    let szz: f64 = tz.iter().map(|p| p[0] * p[0] + p[1] * p[1]).sum();
    if !(szz > 0.0) {
        return None;
    }
    let cclosed = curve.closed;
    let span = if cclosed { ARC as f64 } else { (ARC - 1) as f64 };
    let fr: &[f64] = if closed { &[1.0] } else { fractions };
    let mut w = vec![[0.0; 2]; res];
    // the least-squares similarity of the arc (fraction f, direction dir, start x0)
    let mut fit = |f: f64, dir: f64, x0: f64| -> Option<(f64, Xy, Xy)> {
        for (i, wi) in w.iter_mut().enumerate() {
            *wi = at_position(&cand, cclosed, x0 + dir * f * span * (i as f64 / tdiv));
        }
        let wc = mean(&w);
        let (mut sww, mut re, mut im) = (0.0, 0.0, 0.0);
        for (z, p) in tz.iter().zip(&w) {
            let (px, py) = (p[0] - wc[0], p[1] - wc[1]);
            sww += px * px + py * py;
            // z * conj(p)
            re += z[0] * px + z[1] * py;
            im += z[1] * px - z[0] * py;
        }
        if !(sww > 0.0) {
            return None;
        }
        let cost = (szz - (re * re + im * im) / sww) / szz;
        let a = [re / sww, im / sww];
        let b = [zc[0] - (a[0] * wc[0] - a[1] * wc[1]), zc[1] - (a[0] * wc[1] + a[1] * wc[0])];
        Some((cost, a, b))
    };
    // the start range of an arc of fraction f in direction dir
    let range = |f: f64, dir: f64| -> (f64, f64) {
        if cclosed {
            (0.0, span)
        } else if dir > 0.0 {
            (0.0, span * (1.0 - f))
        } else {
            (f * span, span)
        }
    };
    let mut best: Option<Best> = None;
    let keep = |best: &mut Option<Best>, r: Option<(f64, Xy, Xy)>, f, dir, x0| {
        if let Some((cost, a, b)) = r {
            if best.is_none_or(|q| cost < q.0) {
                *best = Some((cost, a, b, f, dir, x0));
            }
        }
    };
    for &f in fr {
        if !(f > 0.0 && f <= 1.0) {
            continue;
        }
        for dir in [1.0, -1.0] {
            let (lo, hi) = range(f, dir);
            // around a closed target every start of the curve's resampling, unless quick
            let starts = match (closed, search.local) {
                (true, true) => ARC,
                (true, false) => (4 * offsets).min(ARC),
                (false, _) => offsets,
            };
            let div = if cclosed { starts } else { starts - 1 } as f64;
            for o in 0..starts {
                let x0 = lo + (hi - lo) * o as f64 / div;
                keep(&mut best, fit(f, dir, x0), f, dir, x0);
            }
        }
    }
    // then the stretch and start near the best, finer (an open or partial target)
    if let (false, true, Some((_, _, _, f0, dir, x00))) = (closed, search.local, best) {
        let step = span / offsets as f64;
        for i in -6..=6 {
            let f = (f0 * (1.0 + 0.02 * i as f64)).min(1.0);
            let (lo, hi) = range(f, dir);
            for j in -8..=8 {
                let x0 = x00 + step * j as f64 / 8.0;
                if cclosed || (lo..=hi).contains(&x0) {
                    keep(&mut best, fit(f, dir, x0), f, dir, x0);
                }
            }
        }
    }
    let (cost, a, b, fraction, dir, x0) = best?;
    let theta = at.iter().map(|u| unwrapped(&ang, cclosed, x0 + dir * fraction * span * u)).collect();
    Some(Placement { cost: cost.max(0.0), a, b, fraction, reversed: dir < 0.0, theta })
}

/// The input angle at float arc position x, counting whole turns of a closed curve.
fn unwrapped(ang: &[f64], closed: bool, x: f64) -> f64 {
    let n = ang.len();
    let (turns, x) = if closed {
        let t = (x / n as f64).floor();
        (t, x - t * n as f64)
    } else {
        (0.0, x.clamp(0.0, (n - 1) as f64))
    };
    let i = (x.floor() as usize).min(n - 1);
    let w = x - i as f64;
    let next = if i + 1 < n {
        ang[i + 1]
    } else if closed {
        ang[0] + TAU
    } else {
        ang[i]
    };
    ang[i] + w * (next - ang[i]) + turns * TAU
}

/// [`match_curve`] for many candidates of `topology` (`params` rows of
/// [`Topology::params`], `signs` rows of [`Topology::signs`]), their curves made with
/// `samples` points, in parallel; None for a candidate with no curve or no placement.
#[allow(clippy::too_many_arguments)]
pub fn match_many(
    topology: Topology,
    params: &[f64],
    signs: &[f64],
    samples: usize,
    target: &[Xy],
    closed: bool,
    search: Search,
    interrupt: &dyn Interrupt,
) -> Result<Vec<Option<Placement>>, Error> {
    let (np, ns) = (topology.params(), topology.signs());
    if !params.len().is_multiple_of(np) || signs.len() != params.len() / np * ns {
        return Err(Error::Shape { name: "signs".into(), got: signs.len(), expected: params.len() / np * ns });
    }
    let n = params.len() / np;
    let mut out = Vec::with_capacity(n);
    let rows: Vec<usize> = (0..n).collect();
    for chunk in rows.chunks(256) {
        if interrupt.interrupted() {
            return Err(Error::Interrupted);
        }
        let part: Vec<Option<Placement>> = chunk
            .par_iter()
            .map(|&i| {
                let c = coupler_curve(topology, &params[i * np..(i + 1) * np], &signs[i * ns..(i + 1) * ns], samples)?;
                match_curve(&c, target, closed, &FRACTIONS, search)
            })
            .collect();
        out.extend(part);
    }
    Ok(out)
}

/// [`match_curve`] for curves already made (a scene's sweep), in parallel.
pub fn match_curves(
    curves: &[Curve],
    target: &[Xy],
    closed: bool,
    search: Search,
    interrupt: &dyn Interrupt,
) -> Result<Vec<Option<Placement>>, Error> {
    let mut out = Vec::with_capacity(curves.len());
    for chunk in curves.chunks(256) {
        if interrupt.interrupted() {
            return Err(Error::Interrupted);
        }
        out.extend(chunk.par_iter().map(|c| match_curve(c, target, closed, &FRACTIONS, search)).collect::<Vec<_>>());
    }
    Ok(out)
}
