//! Plane vectors as `[x, y]` and the few operations the scene solvers use on them.

/// A 2-D point or vector.
pub type Xy = [f64; 2];

/// (a - b)
#[inline]
pub(crate) fn sub(a: Xy, b: Xy) -> Xy {
    [a[0] - b[0], a[1] - b[1]]
}

/// z-component of a x b.
#[inline]
pub(crate) fn cross(a: Xy, b: Xy) -> f64 {
    a[0] * b[1] - a[1] * b[0]
}

/// a . b
#[inline]
pub(crate) fn dot(a: Xy, b: Xy) -> f64 {
    a[0] * b[0] + a[1] * b[1]
}

/// `v` turned by +90 degrees.
#[inline]
pub(crate) fn perp(v: Xy) -> Xy {
    [-v[1], v[0]]
}

/// d2/dt2 of a direction's angle atan2(d), from d, d' and d'':
/// cross(d, d'') / |d|^2 - 2 (d . d') cross(d, d') / |d|^4.
#[inline]
pub(crate) fn angular_acceleration(d: Xy, dv: Xy, dw: Xy) -> f64 {
    let n = dot(d, d);
    cross(d, dw) / n - 2.0 * dot(d, dv) * cross(d, dv) / (n * n)
}

/// Complex product: `m` applied to `v` (scale and turn).
#[inline]
pub(crate) fn cmul(m: Xy, v: Xy) -> Xy {
    [m[0] * v[0] - m[1] * v[1], m[1] * v[0] + m[0] * v[1]]
}

/// Complex quotient a / b.
#[inline]
pub(crate) fn cdiv(a: Xy, b: Xy) -> Xy {
    let n = dot(b, b);
    [(a[0] * b[0] + a[1] * b[1]) / n, (a[1] * b[0] - a[0] * b[1]) / n]
}

/// `d` divided by its length.
#[inline]
pub(crate) fn unit(d: Xy) -> Xy {
    let n = dot(d, d).sqrt();
    [d[0] / n, d[1] / n]
}

/// x with e1 . x = c1 and e2 . x = c2; `None` when e1 and e2 are parallel.
#[inline]
pub(crate) fn solve2(e1: Xy, e2: Xy, c1: f64, c2: f64) -> Option<Xy> {
    let det = cross(e1, e2);
    if det == 0.0 {
        return None;
    }
    Some([(c1 * e2[1] - c2 * e1[1]) / det, (e1[0] * c2 - e2[0] * c1) / det])
}

/// a + b
#[inline]
pub(crate) fn add(a: Xy, b: Xy) -> Xy {
    [a[0] + b[0], a[1] + b[1]]
}

/// a scaled by k.
#[inline]
pub(crate) fn scale(a: Xy, k: f64) -> Xy {
    [a[0] * k, a[1] * k]
}
