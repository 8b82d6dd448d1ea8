"""Into and out of the tools users already have: Pyslvs expressions (``pyslvs``), cutting
sheets (``sheet``, written by ``dxf`` and ``svg``), MuJoCo models with closed loops
(``mujoco``, replayed by ``mujoco_replay``), an interactive Plotly figure (``plotly``).
Each format is one module; the heavy libraries are optional extras, imported when used."""

from ..scene import Scene
from . import pyslvs

__all__ = ["pyslvs"]

Scene.formats["pyslvs"] = (pyslvs.from_pyslvs, pyslvs.to_pyslvs)
