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
pub(super) fn angular_acceleration(d: Xy, dv: Xy, dw: Xy) -> f64 {
    let n = dot(d, d);
    cross(d, dw) / n - 2.0 * dot(d, dv) * cross(d, dv) / (n * n)
}
