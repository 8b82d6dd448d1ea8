"""Scenes: any one-degree-of-freedom planar linkage of revolute joints described as data
(named points in one drawn pose, links as lists of points), solved by a plan of dyads and
rigid groups compiled for the outputs asked for; ``builtin`` holds the classic ones
(``pk.scenes``)."""

from . import builtin
from ._model import FourBarView, Scene
from ._results import (
    Assemblies,
    Assembly,
    Circuit,
    Plan,
    SceneGradient,
    SceneSweep,
    Step,
    Trace,
)

__all__ = [
    "Assemblies",
    "Assembly",
    "Circuit",
    "FourBarView",
    "Plan",
    "Scene",
    "SceneGradient",
    "SceneSweep",
    "Step",
    "Trace",
    "builtin",
]
