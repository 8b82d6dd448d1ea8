//! A curve's shape as a vector, invariant to translation, rotation, scale, start point and
//! direction: complex Fourier coefficients of the curve resampled by arc length (an open
//! curve is traced there and back, so it closes), normalised on the first harmonic pair.
//!
//! Why not elliptic Fourier descriptors (Kuhl and Giardina 1982): they are the same
//! coefficients written as real ellipses; the complex form makes each invariance one line
//! (translation: drop Z0; scale: divide by the energy; start point tau and rotation alpha:
//! Z_k -> Z_k e^{i (alpha + k tau)}, fixed by making Z1 and Z-1 real and positive;
//! direction: Z_k <-> Z-k, fixed by |Z1| >= |Z-1|). The normalisation leaves one
//! ambiguity, (alpha, tau) + (pi, pi), which flips the sign of the even harmonics: a query
//! asks with both signs (and both directions where |Z1| and |Z-1| nearly tie).

use std::f64::consts::TAU;
use std::sync::OnceLock;

use crate::scene::Xy;

/// Harmonics kept on each side (k = 1..HARMONICS and -1..-HARMONICS).
pub const HARMONICS: usize = 8;
/// Length of a descriptor: (Re, Im) of Z_k then Z_-k for k = 1..HARMONICS.
pub const DESCRIPTOR: usize = 4 * HARMONICS;
/// Points of the arc-length resampling the coefficients are taken from.
pub const RESAMPLED: usize = 128;

/// Cumulative arc length along `points` (closed: back to the first point).
pub(super) fn cumulative(points: &[Xy], closed: bool) -> Vec<f64> {
    let m = points.len();
    let segs = if closed { m } else { m - 1 };
    let mut cum = Vec::with_capacity(segs + 1);
    cum.push(0.0);
    for i in 0..segs {
        let (a, b) = (points[i], points[(i + 1) % m]);
        cum.push(cum[i] + (b[0] - a[0]).hypot(b[1] - a[1]));
    }
    cum
}

/// Where `n` positions equally spaced by arc length along `points` fall (closed: around
/// the loop, the first point first; open: from the first point to the last, both
/// included): each as (segment, weight) between point `segment` and the next.
pub(super) fn arc_positions(points: &[Xy], closed: bool, n: usize) -> Vec<(usize, f64)> {
    let cum = cumulative(points, closed);
    let segs = cum.len() - 1;
    let total = cum[segs];
    let div = if closed { n } else { n - 1 } as f64;
    let mut out = Vec::with_capacity(n);
    let mut i = 0;
    for j in 0..n {
        let s = total * j as f64 / div;
        while i + 1 < segs && cum[i + 1] < s {
            i += 1;
        }
        let len = cum[i + 1] - cum[i];
        out.push((i, if len > 0.0 { ((s - cum[i]) / len).clamp(0.0, 1.0) } else { 0.0 }));
    }
    out
}

/// `n` points equally spaced by arc length along `points` (closed: around the loop, the
/// first point first; open: from the first point to the last, both included).
pub fn resample(points: &[Xy], closed: bool, n: usize) -> Vec<Xy> {
    let m = points.len();
    arc_positions(points, closed, n)
        .into_iter()
        .map(|(i, w)| {
            let (a, b) = (points[i], points[(i + 1) % m]);
            [a[0] + w * (b[0] - a[0]), a[1] + w * (b[1] - a[1])]
        })
        .collect()
}

fn twiddles() -> &'static [(f64, f64)] {
    static T: OnceLock<Vec<(f64, f64)>> = OnceLock::new();
    T.get_or_init(|| (0..RESAMPLED).map(|j| (TAU * j as f64 / RESAMPLED as f64).sin_cos()).collect())
}

/// The descriptor of the curve through `points` (closed or open) into `out`; false where
/// the curve has no extent (all its points at one place) or a point is not finite.
pub fn describe(points: &[Xy], closed: bool, out: &mut [f32; DESCRIPTOR]) -> bool {
    if points.len() < 2 || points.iter().any(|p| !(p[0].is_finite() && p[1].is_finite())) {
        return false;
    }
    let z: Vec<Xy> = if closed {
        resample(points, true, RESAMPLED)
    } else {
        // there and back: the open curve closes on itself
        let half = resample(points, false, RESAMPLED / 2 + 1);
        half.iter().chain(half[1..RESAMPLED / 2].iter().rev()).copied().collect()
    };
    let tw = twiddles();
    let n = RESAMPLED;
    // zk[k + H]: Z_k for k = -H..=H (Z_0 unused)
    let mut zk = [[0.0f64; 2]; 2 * HARMONICS + 1];
    for (idx, k) in (-(HARMONICS as i64)..=HARMONICS as i64).enumerate() {
        if k == 0 {
            continue;
        }
        let (mut re, mut im) = (0.0, 0.0);
        for (j, p) in z.iter().enumerate() {
            // e^{-i 2 pi k j / n}
            let (s, c) = tw[((k * j as i64).rem_euclid(n as i64)) as usize];
            re += p[0] * c + p[1] * s;
            im += p[1] * c - p[0] * s;
        }
        zk[idx] = [re / n as f64, im / n as f64];
    }
    let h = HARMONICS;
    let norm2 = |v: [f64; 2]| v[0] * v[0] + v[1] * v[1];
    if norm2(zk[h + 1]) < norm2(zk[h - 1]) {
        // the other direction: Z_k <-> Z_-k (a start shift the normalisation absorbs)
        zk.reverse();
    }
    let energy: f64 = zk.iter().map(|&v| norm2(v)).sum();
    // a curve with no extent has only rounding left in its harmonics
    let size = z.iter().fold(0.0f64, |m, p| m.max(p[0].abs()).max(p[1].abs()));
    if !(energy > (1e-12 * size.max(f64::MIN_POSITIVE)).powi(2)) || !energy.is_finite() {
        return false;
    }
    let scale = 1.0 / energy.sqrt();
    let (p1, m1) = (zk[h + 1][1].atan2(zk[h + 1][0]), zk[h - 1][1].atan2(zk[h - 1][0]));
    let (alpha, tau) = (-(p1 + m1) / 2.0, -(p1 - m1) / 2.0);
    for k in 1..=h {
        for (slot, kk) in [(4 * (k - 1), k as f64), (4 * (k - 1) + 2, -(k as f64))] {
            let v = zk[(h as i64 + kk as i64) as usize];
            let (s, c) = (alpha + kk * tau).sin_cos();
            out[slot] = ((v[0] * c - v[1] * s) * scale) as f32;
            out[slot + 1] = ((v[0] * s + v[1] * c) * scale) as f32;
        }
    }
    true
}
