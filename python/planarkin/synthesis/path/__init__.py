"""Path synthesis: from a curve (points, a CSV/JSON file, an SVG path) to linkages whose
tracer point follows it. Candidates come from an atlas of normalised coupler curves
(:mod:`planarkin.atlas`), are placed onto the target, refined by SLSQP with the scenes'
exact gradients under branch, order and transmission constraints, and re-verified on a
dense sweep of the real linkage."""

import sys
import types
from typing import Any

from .results import Defects, Design, PathError, PathResult
from .search import TOPOLOGIES, Placed, path, place, retrieve
from .targets import KINDS, CurveTarget, load_target

__all__ = [
    "KINDS",
    "TOPOLOGIES",
    "CurveTarget",
    "Defects",
    "Design",
    "PathError",
    "PathResult",
    "Placed",
    "load_target",
    "path",
    "place",
    "retrieve",
]


class _CallableModule(types.ModuleType):
    """``pk.synthesis.path(target, ...)`` calls :func:`path` (DESIGN.md's spelling), while
    ``pk.synthesis.path.load_target`` and the rest stay this package's names."""

    def __call__(self, *args: Any, **kwargs: Any) -> PathResult:
        return path(*args, **kwargs)


sys.modules[__name__].__class__ = _CallableModule
