"""A torque objective for design: the peak or RMS statics input effort of a loaded scene
over a sweep, minimised over chosen drawn coordinates by SLSQP with its exact gradient
(``Scene.effort_gradient``); and the template it comes with, an arm lifted against gravity
by a spring from a ground anchor (the anchor is the design)."""

from __future__ import annotations

from collections.abc import Iterable, Sequence
from dataclasses import dataclass
from typing import Any

import numpy as np

from ..scene import Scene

__all__ = ["EffortDesign", "balanced_arm", "minimise_effort"]


@dataclass(frozen=True, eq=False)
class EffortDesign:
    """The design that :func:`minimise_effort` found, with scipy's words for how it ended."""

    #: The scene with the designed coordinates.
    scene: Scene
    #: The designed coordinates ("S.x", "S.y") and their values.
    free: tuple[str, ...]
    x: np.ndarray
    #: "peak" or "rms", its value at the design and as drawn (effort units).
    measure: str
    value: float
    start: float
    #: SLSQP's outcome.
    success: bool
    status: int
    message: str
    nit: int


def _moved(scene: Scene, free: Sequence[str], x: np.ndarray) -> Scene:
    d = scene.to_dict()
    pts = {k: list(v) for k, v in d["points"].items()}
    for label, v in zip(free, x, strict=True):
        name, axis = label.split(".")
        pts[name]["xy".index(axis)] = float(v)
    return Scene.from_dict({**d, "points": pts})


def minimise_effort(
    scene: Scene,
    free: Iterable[str],
    theta: object = None,
    *,
    measure: str = "rms",
    span: float | None = None,
    maxiter: int = 100,
) -> EffortDesign:
    """Minimise the ``measure`` ("rms", smooth; or "peak") of the statics input effort of
    ``scene`` under its loads over the sweep at ``theta`` (default as ``Scene.sweep``,
    input values held absolute) by the drawn coordinates ``free`` ("A.x", "A.y", "A"),
    each within ``span`` of its drawn value (default a third of the drawing's size), by
    SLSQP on the exact gradient. A design whose sweep does not solve every point is
    refused by SLSQP's line search (the measure is then infinite)."""
    if measure not in ("peak", "rms"):
        raise ValueError(f"measure must be 'peak' or 'rms', got {measure!r}")
    from scipy.optimize import minimize  # imported here: the package stays light to import

    first = scene.effort_gradient(free, theta, measure=measure)
    labels = first.free
    pts = scene.points
    x0 = np.array([pts[f.split(".")[0]]["xy".index(f[-1])] for f in labels])
    if span is None:
        size = float(np.ptp(np.array(list(pts.values())), axis=0).max())
        span = size / 3.0
    if not (np.isfinite(span) and span > 0):
        raise ValueError(f"span must be finite and > 0, got {span!r}")
    # the gradient's points and effort change with the design: a fresh scene per design
    seen: dict[bytes, tuple[float, np.ndarray]] = {}

    def fun(x: np.ndarray) -> tuple[float, np.ndarray]:
        key = np.asarray(x, dtype=np.float64).tobytes()
        if key not in seen:
            g: Any = _moved(scene, labels, x).effort_gradient(labels, theta, measure=measure)
            ok = np.isfinite(g.input).all() and np.isfinite(g.gradient).all()
            seen[key] = (float(g.value), g.gradient) if ok else (np.inf, np.zeros(len(x)))
        v, d = seen[key]
        return v, d

    res = minimize(
        fun,
        x0,
        jac=True,
        method="SLSQP",
        bounds=[(v - span, v + span) for v in x0],
        options={"maxiter": maxiter, "ftol": 1e-14 * max(first.value, 1e-300)},
    )
    x = np.asarray(res.x, dtype=np.float64)
    return EffortDesign(
        scene=_moved(scene, labels, x),
        free=labels,
        x=x,
        measure=measure,
        value=fun(x)[0],
        start=float(first.value),
        success=bool(res.success),
        status=int(res.status),
        message=str(res.message),
        nit=int(res.nit),
    )


def balanced_arm(
    *,
    length: float = 1.0,
    mass: float = 2.0,
    center: float = 0.5,
    attach: float = 0.4,
    k: float = 100.0,
    gravity: float = 9.81,
    anchor: tuple[float, float] = (0.3, 0.5),
) -> Scene:
    """The template: an arm of ``length`` on a ground pivot O, driven there, its ``mass``
    at ``center`` along it (point G), lifted by a zero-free-length spring of stiffness
    ``k`` from ground point S (at ``anchor``) to point A at ``attach`` along the arm.
    With S straight above O at k * attach * S.y = mass * gravity * center the spring
    balances the arm at every angle (zero input torque): the design to find, by S."""
    return Scene.from_dict(
        {
            "name": "spring-balanced arm",
            "points": {
                "O": [0.0, 0.0],
                "X": [-0.25 * length, 0.0],
                "S": [float(anchor[0]), float(anchor[1])],
                "T": [length, 0.0],
                "G": [center, 0.0],
                "A": [attach, 0.0],
            },
            "links": {"ground": ["O", "X", "S"], "arm": ["O", "T", "G", "A"]},
            "ground": "ground",
            "input": {"link": "arm", "pivot": "O"},
            "loads": {
                "gravity": [0.0, -gravity],
                "masses": {"arm": {"mass": mass, "center": "G", "inertia": 0.0}},
                "springs": [{"between": ["S", "A"], "k": k, "free_length": 0.0}],
            },
        }
    )
