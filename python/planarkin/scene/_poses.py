"""A pose given as data (every point, as ``Scene.assemblies`` lists them), checked to be an
assembly of the scene, and the scene redrawn in it (``Scene.at``, ``Scene.trace``)."""

from __future__ import annotations

import math
from collections.abc import Mapping
from typing import Any

import numpy as np

from .._args import as_float


def _entry(cond: bool, entry: str, message: str) -> None:
    if not cond:
        raise ValueError(f"{entry}: {message}")


def _xy(name: str, v: object) -> tuple[float, float]:
    ok = isinstance(v, (list, tuple, np.ndarray)) and len(v) == 2
    _entry(ok, f"points.{name}", f"must be a pair [x, y], got {v!r}")
    seq: Any = v
    return as_float(f"points.{name}[0]", seq[0]), as_float(f"points.{name}[1]", seq[1])


def pose_array(data: Mapping[str, Any], pose: Mapping[str, Any], what: str) -> np.ndarray:
    """The (P, 2) points of ``pose`` in the scene's point order; ValueError naming ``what``
    where a point is missing or a link's distances differ from the drawn ones."""
    names = list(data["points"])
    missing = [n for n in names if n not in pose]
    _entry(isinstance(pose, Mapping) and not missing, what,
           f"must give every point of the scene; missing {missing}")  # fmt: skip
    arr = np.array([_xy(n, pose[n]) for n in names], dtype=np.float64)
    # the pose must be this linkage: every link's distances as drawn
    drawn = data["points"]
    size = max(np.ptp(np.array(list(drawn.values())), axis=0).max(), 1e-300)
    for link, pts in data["links"].items():
        for i, a in enumerate(pts):
            for b in pts[i + 1 :]:
                d0 = math.dist(drawn[a], drawn[b])
                d1 = math.dist(arr[names.index(a)], arr[names.index(b)])
                _entry(abs(d1 - d0) <= 1e-9 * size, what,
                       f"is not an assembly of this scene: link {link!r} has |{a}{b}| = "
                       f"{d1!r}, drawn {d0!r}")  # fmt: skip
    return arr


def redrawn(data: Mapping[str, Any], d: dict[str, Any], arr: np.ndarray) -> dict[str, Any]:
    """The file-format dict ``d`` of a scene (its ``data``) drawn at the points ``arr``: a
    mass centre given in the drawing moves with its link."""
    old = {n: np.asarray(v, dtype=np.float64) for n, v in d["points"].items()}
    d["points"] = {n: [float(x), float(y)] for n, (x, y) in zip(d["points"], arr, strict=True)}
    for link, m in d.get("loads", {}).get("masses", {}).items():
        if not isinstance(m["center"], str):
            a, b = data["links"][link][:2]
            u0, u1 = old[b] - old[a], np.subtract(d["points"][b], d["points"][a])
            c, s_ = np.dot(u0, u1), u0[0] * u1[1] - u0[1] * u1[0]
            r = np.hypot(c, s_)
            c, s_ = c / r, s_ / r
            v = np.asarray(m["center"], dtype=np.float64) - old[a]
            turned = np.array([c * v[0] - s_ * v[1], s_ * v[0] + c * v[1]])
            m["center"] = (np.array(d["points"][a]) + turned).tolist()
    return d
