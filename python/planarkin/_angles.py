"""Angle conventions shared by the API and the NumPy reference: one turn (TAU), the
default crank angles of a sweep, the one wrap to (-pi, pi] (the core's ``wrap_angle``,
which every solver applies) for one angle and for arrays, and radians as people read them
(``wrap_deg``: the same interval in degrees, for display; or unwrapped for a continuous
curve)."""

from __future__ import annotations

import math

import numpy as np

TAU = 2.0 * math.pi

#: Default crank angles: 0 to 360 degrees in 1 degree steps (361 points), in radians.
DEFAULT_THETA2 = np.arange(361) * (TAU / 360)
DEFAULT_THETA2.setflags(write=False)


def wrap(a: float) -> float:
    """Wraps to (-pi, pi]; angles already there are returned unchanged."""
    if -math.pi < a <= math.pi:
        return a
    if not math.isfinite(a):
        return float("nan")
    r = math.fmod(a + math.pi, TAU)
    if r < 0.0:
        r += TAU
    r -= math.pi
    return math.pi if r <= -math.pi else r


def wrap_array(a: object) -> np.ndarray:
    """An array of angles (radians) wrapped to (-pi, pi], through the unit circle (the
    argument of e^(ia)): for differences of computed angles (synthesis), where a result
    within an ulp or two of :func:`wrap`'s is what is wanted; NaN stays NaN."""
    return np.angle(np.exp(1j * np.asarray(a)))


def unwrap_deg(angles: object) -> np.ndarray:
    """Angles (radians) to degrees, unwrapped over the finite entries so a curve is
    continuous; NaN entries (unsolved points) stay NaN."""
    a = np.asarray(angles, dtype=np.float64)
    out = np.full(a.shape, np.nan)
    ok = np.isfinite(a)
    out[ok] = np.degrees(np.unwrap(a[ok]))
    return out


def wrap_deg(angles: object) -> np.ndarray:
    """Angles (radians, any turn) to degrees in (-180, 180]; NaN stays NaN."""
    d = np.degrees(np.asarray(angles, dtype=np.float64))
    w = 180.0 - np.remainder(180.0 - d, 360.0)
    # remainder of an exact multiple is 0: 180 stays 180, -180 becomes 180
    return np.where(np.isfinite(w), w, np.nan)


def wrapped(angle: float) -> float:
    """One angle (radians) in degrees in (-180, 180]."""
    return float(wrap_deg(angle)) if math.isfinite(angle) else math.nan


def rpm(omega: float) -> float:
    """rad/s to rev/min."""
    return omega * 60.0 / math.tau
