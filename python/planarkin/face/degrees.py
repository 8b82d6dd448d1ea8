"""Angles as people read them: radians to degrees, unwrapped so a curve through a full
turn stays continuous (the API keeps radians wrapped to (-pi, pi])."""

from __future__ import annotations

import numpy as np

__all__ = ["unwrap_deg"]


def unwrap_deg(angles: object) -> np.ndarray:
    """Angles (radians) to degrees, unwrapped over the finite entries so a curve is
    continuous; NaN entries (unsolved points) stay NaN."""
    a = np.asarray(angles, dtype=np.float64)
    out = np.full(a.shape, np.nan)
    ok = np.isfinite(a)
    out[ok] = np.degrees(np.unwrap(a[ok]))
    return out
