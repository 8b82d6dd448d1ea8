"""Exact derivatives of the statics input effort by the drawing's coordinates, for design:
the poses' derivatives (the scene's implicit differentiation) carried through the loads
and the Newton-Euler solve by a complex step (every step of it is analytic in the poses
and the drawing, so the step's imaginary part is the derivative to rounding). A kernel of
the forces subject, beside the solve."""

from __future__ import annotations

from collections.abc import Mapping, Sequence
from typing import Any

import numpy as np

from ._results import EffortGradient
from ._solve import effort
from ._structure import Structure

__all__ = ["effort_gradient"]


def effort_gradient(
    st: Structure,
    data: Mapping[str, Any],
    sweep: Any,
    loads: Mapping[str, Any] | None,
    units: dict[str, str | None],
    dpose: np.ndarray,
    free: Sequence[tuple[int, int]],
    labels: tuple[str, ...],
    measure: str,
) -> EffortGradient:
    """``dpose`` (N, points, 2, F): the sweep's poses' derivatives by the F coordinates
    ``free`` ((point index, axis) in the scene's order), points in ``sweep.point_names``
    order; ``measure`` "peak" (the largest |effort|) or "rms"."""
    col = {p: i for i, p in enumerate(sweep.point_names)}
    idx = np.array([col[p] for p in st.point_names], dtype=np.intp)
    P = sweep.coords[:, idx]
    dP = dpose[:, idx]
    D = np.array([data["points"][p] for p in st.point_names], dtype=np.float64)
    h = 1e-30 * st.size  # far below rounding: the step's square vanishes
    value = effort(st, data, sweep, loads, units, P, D).real
    n = len(sweep.theta)
    grads = np.empty((n, len(free)))
    for f, (point, axis) in enumerate(free):
        Dc = D.astype(np.complex128)
        Dc[point, axis] += 1j * h
        t = effort(st, data, sweep, loads, units, P + 1j * h * dP[..., f], Dc)
        grads[:, f] = t.imag / h
    ok = np.isfinite(value) & np.isfinite(grads).all(axis=1)
    if not ok.any():
        total, g = float("nan"), np.full(len(free), np.nan)
    elif measure == "peak":
        i = int(np.flatnonzero(ok)[np.argmax(np.abs(value[ok]))])
        total, g = float(abs(value[i])), np.sign(value[i]) * grads[i]
    else:
        v = value[ok]
        total = float(np.sqrt(np.mean(v**2)))
        g = (v[:, None] * grads[ok]).mean(axis=0) / total if total > 0 else np.zeros(len(free))
    return EffortGradient(
        free=labels, measure=measure, value=total, gradient=g, input=value, input_gradient=grads
    )
