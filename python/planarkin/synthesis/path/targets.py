"""A path target: points in order, closed, open or partial, with optional input values per
point (timing); read from an array, a CSV, a JSON file or an SVG path, and checked."""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

#: the kinds of target: the whole closed coupler curve, an open path, or part of a curve
KINDS = ("closed", "open", "partial")


@dataclass(frozen=True)
class CurveTarget:
    """``points`` (n, 2) in order; ``kind`` one of :data:`KINDS`; ``inputs`` (n,) input
    values per point (timing) or None (free)."""

    points: np.ndarray
    kind: str = "closed"
    inputs: np.ndarray | None = None

    @property
    def size(self) -> float:
        """The diagonal of the points' bounding box: errors are divided by it."""
        return float(np.hypot(*np.ptp(self.points, axis=0)))
