"""Angle conventions shared by the API and the NumPy reference: one turn (TAU), the
default crank angles of a sweep, and the one wrap to (-pi, pi] (the core's ``wrap_angle``,
which every solver applies), for one angle and for arrays. The face's ``wrap_deg`` is the
same interval in degrees, for display only."""

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
