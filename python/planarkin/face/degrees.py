"""Angles as people read them: radians to degrees, in (-180, 180] wherever a user reads an
angle (tables, JSON, CSV, axes), or unwrapped so a curve through a full turn stays
continuous (the API keeps radians wrapped to (-pi, pi]); the conversions themselves are the
API's (``planarkin._angles``), the axis helpers the face's own."""

from __future__ import annotations

import math

import numpy as np

from .._angles import unwrap_deg, wrap_deg, wrapped

__all__ = ["AXIS_TICKS", "on_wrapped_axis", "unwrap_deg", "wrap_deg", "wrapped"]

#: Ticks of an input-angle axis in (-180, 180].
AXIS_TICKS = np.arange(-180, 181, 60)


def on_wrapped_axis(theta: object, *ys: object) -> tuple[np.ndarray, ...]:
    """A sweep's input angles ``theta`` (radians, a continuous run) and its values ``ys``
    ((N,) or (N, k) each) reordered for a (-180, 180] axis: sorted by the wrapped angle,
    with a NaN row wherever two neighbours on the axis are not neighbours in the sweep (the
    seam where the sweep's turn crosses 180), so no line joins them. A sweep of one full
    turn whose last pose repeats its first plots as one curve from -180 to 180. Returns
    (x in degrees, *ys)."""
    t = np.asarray(theta, dtype=np.float64)
    n = len(t)
    x = wrap_deg(t)
    order = np.argsort(x, kind="stable")
    cols = [np.asarray(y, dtype=np.float64) for y in ys]
    if n == 0:
        return (x, *cols)
    # neighbours on the axis that are not neighbours in the sweep get a NaN row between
    step = np.abs(np.diff(order))
    full = n > 1 and math.isclose(abs(t[-1] - t[0]), math.tau, rel_tol=0, abs_tol=1e-9)
    breaks = step != 1
    if full:
        # the first and last poses are one pose: next to each other on the axis are fine
        breaks &= ~(np.isin(order[:-1], (0, n - 1)) & np.isin(order[1:], (0, n - 1)))
        breaks &= ~((order[:-1] == n - 2) & (order[1:] == 0))
        breaks &= ~((order[:-1] == n - 1) & (order[1:] == 1))
    cut = np.flatnonzero(breaks) + 1

    def place(a: np.ndarray) -> np.ndarray:
        a = a[order]
        fill = np.full((len(cut), *a.shape[1:]), np.nan)
        return np.insert(a, cut, fill, axis=0)

    return (place(x), *(place(c) for c in cols))
