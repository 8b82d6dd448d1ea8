"""Forces on a scene along a sweep: statics (the input effort that holds every pose, and
every joint reaction) and inverse dynamics (the same with the links' inertia), checked by
virtual work against Newton-Euler and by the energy balance. ``Scene.statics`` and
``Scene.dynamics`` are the doors; this package takes the scene's plain data."""

from __future__ import annotations

import math
from collections.abc import Mapping
from typing import Any

import numpy as np

from ._gradient import effort_gradient
from ._native import native
from ._results import EffortGradient, Forces
from ._solve import solve
from ._structure import Structure
from ._units import inertia_factor, unit_names

__all__ = [
    "EffortGradient",
    "Forces",
    "Structure",
    "analyse",
    "effort_gradient",
    "inertia_factor",
    "unit_names",
]


def analyse(
    structure: Structure,
    data: Mapping[str, Any],
    sweep: Any,
    loads: Mapping[str, Any] | None,
    *,
    omega: Any = None,
    alpha: Any = None,
    engine: str = "rust",
) -> Forces:
    """Statics (``omega`` None) or inverse dynamics at input rate ``omega`` (a number or
    one per sweep point) and rate of change ``alpha`` (default 0) along ``sweep``, which
    reports every point with velocities (and accelerations, for dynamics) at a nonzero
    rate. ``data`` is the scene's data, ``loads`` its normalised loads. ``engine``: "rust"
    (the core's kernel) or "numpy" (the reference, the same algorithm in NumPy)."""
    if engine not in ("rust", "numpy"):
        raise ValueError(f"engine must be 'rust' or 'numpy', got {engine!r}")
    n = len(sweep.theta)
    units = unit_names(data["units"], data.get("unit_table"))
    w = a = None
    if omega is not None:
        w = _per_point("omega", omega, n)
        a = np.zeros(n) if alpha is None else _per_point("alpha", alpha, n)
    if engine == "numpy":
        return solve(structure, data, sweep, loads, units, w, a)
    return native(structure, data, loads, units).run(sweep, units, w, a)


def _per_point(name: str, v: Any, n: int) -> np.ndarray:
    a = np.asarray(v, dtype=np.float64)
    if a.ndim == 0:
        if not math.isfinite(a):
            raise ValueError(f"{name} must be finite")
        return np.full(n, float(a))
    if a.shape != (n,):
        raise ValueError(
            f"{name} must be a number or one value per sweep point ({n}), got shape {a.shape}"
        )
    if not np.isfinite(a).all():
        raise ValueError(f"{name} must be finite")
    return np.ascontiguousarray(a)
