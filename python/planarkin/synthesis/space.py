"""The design space of any scene: the joint coordinates the user names free (``"A.x"``,
``"A.y"``, or ``"B"`` for both), the others held as drawn, each free one within bounds.
A design vector is these coordinates in the order named; its scene is the drawing with
them put in (the linkage drawn at its design pose)."""

from __future__ import annotations

import math
from collections.abc import Mapping, Sequence
from dataclasses import dataclass, field
from typing import Any

import numpy as np

from ..scene import Scene

AXES = {"x": 0, "y": 1}


def _coords(scene: Scene, free: Sequence[str]) -> tuple[tuple[str, int], ...]:
    if isinstance(free, str) or not isinstance(free, Sequence):
        raise ValueError(f"free must be a list of joint coordinates, got {free!r}")
    names = scene.points
    out: list[tuple[str, int]] = []
    for entry in free:
        if not isinstance(entry, str):
            raise ValueError(f"free entries must be strings like 'A.x' or 'B', got {entry!r}")
        point, dot, axis = entry.rpartition(".")
        axes: tuple[int, ...] = (0, 1)
        if not dot or axis not in AXES:
            point = entry
        else:
            axes = (AXES[axis],)
        if point not in names:
            raise ValueError(
                f"free entry {entry!r} names no point of the scene (points: {', '.join(names)})"
            )
        for a in axes:
            if (point, a) in out:
                raise ValueError(f"free entry {entry!r} repeats {point}.{'xy'[a]}")
            out.append((point, a))
    if not out:
        raise ValueError("free must name at least one joint coordinate")
    return tuple(out)


@dataclass(frozen=True)
class SceneSpace:
    """The design vector of the scene ``drawn``: the coordinates named in ``free`` (``"A.x"``,
    ``"A.y"``, ``"B"`` for both of B's), in that order; every other coordinate is held as
    drawn. ``lower`` / ``upper``: bounds per coordinate (or one number for all; absolute
    scene coordinates), by default the drawn value -/+ twice the drawing's size.
    ``min_link``: the shortest allowed distance between two joints of one link."""

    drawn: Scene
    free: Sequence[str]
    lower: Any = None
    upper: Any = None
    min_link: float = 0.0
    coords: tuple[tuple[str, int], ...] = field(init=False)
    #: the scene as data, without ``lengths`` (the design is the drawing itself)
    base: dict[str, Any] = field(init=False, repr=False, compare=False)

    def __post_init__(self) -> None:
        if not isinstance(self.drawn, Scene):
            raise ValueError(f"drawn must be a planarkin.Scene, got {type(self.drawn).__name__}")
        coords = _coords(self.drawn, self.free)
        object.__setattr__(self, "free", tuple(self.free))
        object.__setattr__(self, "coords", coords)
        base = self.drawn.to_dict()
        base.pop("lengths", None)
        object.__setattr__(self, "base", base)
        x0 = self.x_of(self.drawn.points)
        pts = np.array(list(self.drawn.points.values()))
        size = float(np.ptp(pts, axis=0).max()) or 1.0
        n = len(coords)
        for name, default in (("lower", x0 - 2 * size), ("upper", x0 + 2 * size)):
            v = getattr(self, name)
            a = default if v is None else np.asarray(v, dtype=np.float64)
            try:
                a = np.broadcast_to(a, (n,)).astype(np.float64)
            except ValueError:
                raise ValueError(
                    f"{name} must be one number or {n} (one per free coordinate)"
                ) from None
            if not np.all(np.isfinite(a)):
                raise ValueError(f"{name} must be finite")
            object.__setattr__(self, name, a)
        if not np.all(self.lower < self.upper):
            raise ValueError("lower must be below upper in every free coordinate")
        if not (math.isfinite(self.min_link) and self.min_link >= 0):
            raise ValueError(f"min_link must be finite and >= 0, got {self.min_link}")

    def __reduce__(self) -> tuple[Any, tuple[Any, ...]]:
        # a Scene holds its compiled core, which does not pickle: a space travels to
        # worker processes as its data and is built again there
        return (_rebuild, (self.base, self.free, self.lower, self.upper, self.min_link))

    # --- the interface Problem reads (shared with DesignSpace) ----------------------------

    @property
    def size(self) -> int:
        return len(self.coords)

    @property
    def points(self) -> dict[str, tuple[float, float]]:
        """Every point as drawn."""
        return self.drawn.points

    @property
    def links(self) -> dict[str, tuple[str, ...]]:
        return self.drawn.links

    @property
    def names(self) -> list[str]:
        """The design vector's entries: "A.x", "A.y", ..."""
        return [f"{p}.{'xy'[a]}" for p, a in self.coords]

    def x_of(self, points: Mapping[str, Sequence[float]]) -> np.ndarray:
        return np.array([float(points[p][a]) for p, a in self.coords])

    def points_of(self, x: np.ndarray) -> dict[str, tuple[float, float]]:
        pts = {k: [float(v[0]), float(v[1])] for k, v in self.drawn.points.items()}
        for (p, a), v in zip(self.coords, np.asarray(x, dtype=np.float64), strict=True):
            pts[p][a] = float(v)
        return {k: (v[0], v[1]) for k, v in pts.items()}

    def scene_dict(self, x: np.ndarray, name: str | None = None) -> dict[str, Any]:
        d = dict(self.base)
        d["points"] = {k: [v[0], v[1]] for k, v in self.points_of(x).items()}
        if name is not None:
            d["name"] = name
        return d

    def scene(self, x: np.ndarray) -> Scene:
        return Scene.from_dict(self.scene_dict(x))

    def link_pairs(self) -> list[tuple[str, str]]:
        """Every pair of points on one link (their distances are the link dimensions)."""
        out = []
        for pts in self.links.values():
            for i, a in enumerate(pts):
                for b in pts[i + 1 :]:
                    out.append((a, b))
        return out

    def lengths(self, points: Mapping[str, Sequence[float]]) -> np.ndarray:
        """Every distance between two points of one link."""
        return np.array([math.dist(points[a], points[b]) for a, b in self.link_pairs()])


def _rebuild(
    base: dict[str, Any], free: tuple[str, ...], lower: Any, upper: Any, min_link: float
) -> SceneSpace:
    return SceneSpace(Scene.from_dict(base), free, lower, upper, min_link)
