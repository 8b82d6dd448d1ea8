"""Helpers that more than one test folder needs and that use planarkin (the independent
truth, which must not, is in truth.py): reading a scene's output rotation from the scene
solver, and hand-made rows of the speed/accuracy table."""

from __future__ import annotations

import math

import numpy as np
import planarkin as pk
from planarkin.fourbar import tradeoff as tr


def out_rotation(sc: pk.Scene, phi: np.ndarray) -> np.ndarray:
    """The output link's rotation from the drawn pose, read from swept points."""
    link, pivot = sc.output
    first = next(p for p in sc.links[link] if p != pivot)
    sw = sc.sweep(sc.input_angle + phi, outputs=[first], tol=1e-12)
    assert np.all(sw.status == 0)
    p0, q0 = np.array(sc.points[pivot]), np.array(sc.points[first])
    v = sw.points[first] - p0
    a = np.arctan2(v[:, 1], v[:, 0]) - math.atan2(*(q0 - p0)[::-1])
    return np.angle(np.exp(1j * a))


def tradeoff_rows(times, errs, tols, method="quadratic"):
    """Rows of the speed/accuracy table with the given times, errors and tolerances."""
    from planarkin.fourbar.tradeoff import Row

    label = tr.METHODS[method][0]
    return [
        Row(method, label, tol, 1.0, 1.0, t, e, e, e, 0)
        for t, e, tol in zip(times, errs, tols, strict=True)
    ]
