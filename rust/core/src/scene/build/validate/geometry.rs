//! The drawing's measure: its size (exact power-of-two scalings of it give the same
//! answers), points of one link that coincide, and the solving frame (origin at the
//! input, divided by a power of two near the size) with the input as drawn.

use crate::error::Error;
use crate::scene::input::{Linear, LinearKind, Pivoted};
use crate::scene::model::{Link, Prismatic, Slot};
use crate::scene::vec2::{cross, sub, Xy};

/// Two points of one link closer than this, relative to the scene's size, coincide.
pub(super) const COINCIDENT: f64 = 1e-12;

/// Size of the scene: the largest diagonal of a link's bounding box, measured after an
/// exact power-of-two scaling by its largest side (no square overflows or underflows,
/// from 1e-300 to 1e300): (that power of two, the size in its units). Errors name a link
/// two of whose points coincide.
pub(super) fn measure(parsed: &[Link], drawn: &[Xy], names: &[String]) -> Result<(f64, f64), Error> {
    let mut side = 0.0_f64;
    let boxes: Vec<(Xy, Xy)> = parsed.iter().map(|l| bounding_box(l.points.iter().map(|&p| drawn[p]))).collect();
    for (lo, hi) in &boxes {
        side = side.max(hi[0] - lo[0]).max(hi[1] - lo[1]);
    }
    if !side.is_finite() {
        return Err(Error::scene("points", "coordinates are too large to measure (a distance overflows)"));
    }
    let pre = power_of_two_below(side);
    let size = boxes.iter().map(|(lo, hi)| ((hi[0] - lo[0]) / pre).hypot((hi[1] - lo[1]) / pre)).fold(0.0, f64::max);
    for l in parsed {
        if let Some((a, b, d)) = coincident(&l.points, drawn, pre, COINCIDENT * size) {
            return Err(Error::scene(
                format!("links.{}", l.name),
                format!("points {:?} and {:?} coincide (distance {:e})", names[a], names[b], d * pre),
            ));
        }
    }
    Ok((pre, size))
}

/// The solving frame and what is measured in it.
pub(super) struct Frame {
    pub(super) scale: f64,
    pub(super) origin: Xy,
    pub(super) xy: Vec<Xy>,
    pub(super) theta0: f64,
    /// The linear input with its unit direction.
    pub(super) linear: Option<Linear>,
}

/// The frame of a scene of size `size` (drawing units): its origin at the input pivot (or
/// the linear input's line), the drawn input angle, and the slots' offsets (set in
/// `slot_list`).
pub(super) fn frame(
    size: f64,
    drawn: &[Xy],
    input: Option<Pivoted>,
    linear: Option<Linear>,
    slot_list: &mut [Slot],
    prism_list: &[Prismatic],
) -> Frame {
    let scale = power_of_two_below(size);
    let origin = match (input, linear) {
        (Some(i), _) => drawn[i.pivot],
        (None, Some(l)) => match l.kind {
            LinearKind::Slot => drawn[slot_list[l.index].line.0],
            LinearKind::Prismatic => drawn[prism_list[l.index].line.0],
        },
        (None, None) => unreachable!("a scene has an angle or a linear input"),
    };
    let xy: Vec<Xy> = drawn.iter().map(|&p| [(p[0] - origin[0]) / scale, (p[1] - origin[1]) / scale]).collect();
    let theta0 = match input {
        Some(i) => {
            let d = sub(xy[i.tip], xy[i.pivot]);
            (d[1] + 0.0).atan2(d[0])
        }
        None => 0.0,
    };
    let unit = |a: usize, b: usize| {
        let d = sub(xy[b], xy[a]);
        let n = d[0].hypot(d[1]);
        [d[0] / n, d[1] / n]
    };
    for sl in slot_list.iter_mut() {
        sl.offset = cross(unit(sl.line.0, sl.line.1), sub(xy[sl.point], xy[sl.line.0]));
    }
    let linear = linear.map(|l| {
        let line = match l.kind {
            LinearKind::Slot => slot_list[l.index].line,
            LinearKind::Prismatic => prism_list[l.index].line,
        };
        Linear { dir: unit(line.0, line.1), ..l }
    });
    Frame { scale, origin, xy, theta0, linear }
}

/// The largest power of two at most `x` (> 0, finite; subnormal sizes included).
fn power_of_two_below(x: f64) -> f64 {
    if !(x > 0.0) {
        return 1.0;
    }
    // exact for normal and subnormal x: powi would over- or underflow past 2^1023 / 2^-1022
    let e = x.log2().floor() as i32;
    let p = 2f64.powi(e.clamp(-1022, 1023));
    let p = if e < -1022 { p * 2f64.powi(e + 1022) } else { p };
    if p > x {
        p / 2.0
    } else {
        p
    }
}

fn bounding_box(points: impl Iterator<Item = Xy>) -> (Xy, Xy) {
    points.fold(([f64::INFINITY; 2], [f64::NEG_INFINITY; 2]), |(lo, hi), p| {
        ([lo[0].min(p[0]), lo[1].min(p[1])], [hi[0].max(p[0]), hi[1].max(p[1])])
    })
}

/// Two of `points` closer than `tol` (in units of `pre`): the first such pair and its
/// distance. Sorted by x, each point is compared with those within `tol` of it in x: near
/// linear for the points of one link, however many.
fn coincident(points: &[usize], drawn: &[Xy], pre: f64, tol: f64) -> Option<(usize, usize, f64)> {
    // (x, y, position in the link's list)
    let mut order: Vec<(f64, f64, usize)> =
        points.iter().enumerate().map(|(k, &p)| (drawn[p][0] / pre, drawn[p][1] / pre, k)).collect();
    order.sort_by(|a, b| a.0.total_cmp(&b.0));
    // the pair first in the link's listed order, as a reader scans it
    let mut found: Option<(usize, usize, f64)> = None;
    for (i, a) in order.iter().enumerate() {
        for b in order[i + 1..].iter().take_while(|b| b.0 - a.0 <= tol) {
            let d = (b.0 - a.0).hypot(b.1 - a.1);
            let pair = (a.2.min(b.2), a.2.max(b.2));
            if !(d > tol) && found.is_none_or(|f| pair < (f.0, f.1)) {
                found = Some((pair.0, pair.1, d));
            }
        }
    }
    found.map(|(i, j, d)| (points[i], points[j], d))
}
