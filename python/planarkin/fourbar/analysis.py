"""Readings of four-bar results that are analysis, not drawing: the crank-angle spans a
linkage cannot reach, the order of convergence of a Newton history, and the rocking
motion of a crank that cannot turn fully (what an animation of it plays)."""

from __future__ import annotations

import math
from collections.abc import Sequence
from typing import TYPE_CHECKING, Any

import numpy as np

from .._results import true_runs
from .._status import Status
from ._results import Sweep

if TYPE_CHECKING:
    from ._model import FourBar

__all__ = ["convergence_order", "rocking", "unreachable_spans"]


def _edge(a: float, b: float, toggles: np.ndarray) -> float:
    """The boundary between crank angles a (one side) and b (the other): a toggle angle of
    the linkage (any turn) lying between them when one is known, else the midpoint."""
    lo, hi = min(a, b), max(a, b)
    for t in toggles:
        k = math.ceil((lo - t) / math.tau)
        c = t + k * math.tau
        if c <= hi:
            return float(c)
    return 0.5 * (a + b)


def unreachable_spans(sweep: Sweep, limits: object = None) -> list[tuple[float, float]]:
    """Crank-angle spans (radians, in sweep order) where the linkage cannot assemble.

    Derived from the NOT_ASSEMBLABLE runs of the sweep. A span's edge lies between the last
    assembled and the first unassemblable crank angle: it is placed at a toggle angle from
    ``limits`` (anything with a ``toggles`` array, e.g. ``FourBar.limits()``) when one lies
    there, else halfway. A span reaching an end of the sweep ends at that crank angle.
    """
    t2 = np.asarray(sweep.theta2, dtype=np.float64)
    toggles = np.asarray(getattr(limits, "toggles", ()), dtype=np.float64).ravel()
    toggles = toggles[np.isfinite(toggles)]
    spans = []
    for i, j in true_runs(np.asarray(sweep.status) == Status.NOT_ASSEMBLABLE):
        start = t2[i] if i == 0 else _edge(t2[i - 1], t2[i], toggles)
        stop = t2[j - 1] if j == len(t2) else _edge(t2[j - 1], t2[j], toggles)
        spans.append((float(start), float(stop)))
    return spans


def convergence_order(history: Sequence[float] | np.ndarray) -> float:
    """Estimated order of convergence p = log(e[k+1]/e[k]) / log(e[k]/e[k-1]) from the last
    triple of strictly decreasing positive residuals; NaN when there is none."""
    e = np.asarray(history, dtype=np.float64).ravel()
    for k in range(len(e) - 2, 0, -1):
        e0, e1, e2 = e[k - 1], e[k], e[k + 1]
        if np.isfinite(e0) and e0 > e1 > e2 > 0:
            return float(math.log(e2 / e1) / math.log(e1 / e0))
    return float("nan")


def rocking(fb: FourBar, limits: Any, sweep: Sweep, *, points: int = 181) -> list[Sweep]:
    """The motion a linkage whose crank cannot turn fully can make, as the sweeps to play
    one after another: the crank rocks between the two toggles bounding an assemblable
    interval (the one holding the first solved point of ``sweep``, else the first), on
    ``sweep.mode`` one way, then, the crank having reversed at the toggle, back on the
    other mode (the assembly passes through the toggle onto the other mode), and so on.
    ``points`` crank angles each way, bunched towards the toggles and 1e-6 rad inside them
    (at a toggle itself the position is a dead point: SINGULAR). A crank that turns
    fully: ``[sweep]``."""
    if limits.full_rotation or not limits.intervals:
        return [sweep]
    ok = np.flatnonzero(np.asarray(sweep.status) == Status.CONVERGED)
    a, b = limits.intervals[0]
    if ok.size:
        t0 = float(sweep.theta2[ok[0]])
        for lo, hi in limits.intervals:
            if lo + (t0 - lo) % math.tau <= hi:
                a, b = lo, hi
                break
    # crank angles bunched towards the toggles (cosine spacing), where the rest of the
    # linkage moves fastest (as the square root of the distance to the toggle): the
    # pins then move by about equal steps
    inset = min(1e-6, 0.25 * (b - a))
    u = np.linspace(0.0, math.pi, points)
    there = np.clip(a + (b - a) * 0.5 * (1.0 - np.cos(u)), a + inset, b - inset)
    other = "crossed" if sweep.mode == "open" else "open"
    return [
        fb.sweep(there, mode=sweep.mode, method="closed-form"),
        fb.sweep(there[::-1], mode=other, method="closed-form"),
    ]
