"""planarkin: planar linkage kinematics with a Rust core. Four-bars (Newton-Raphson
sweeps, closed forms, limits, Grashof/Barker classes), any planar linkage as data
(scenes: plans of dyads and groups, every assembly, circuits through dead points), the
synthesis of double butterflies, a NumPy reference of it all, figures and a command.

>>> import planarkin as pk
>>> fb = pk.FourBar(6, 2, 5, 5)
>>> fb.sweep().summary().converged
361
>>> pk.scenes.load("jansen").sweep(outputs=["foot"]).points["foot"].shape
(361, 2)
"""

from . import atlas, forces, interop, reference
from ._angles import DEFAULT_THETA2
from ._kernel import BUILD_PROFILE
from ._kernel import __version__ as __version__
from ._results import SweepSummary
from ._status import SINGULAR_THRESHOLD, Status
from .fourbar import (
    BatchSweep,
    FourBar,
    Grashof,
    Limits,
    Solution,
    Sweep,
    closed_form_batch,
    sweep_batch,
)
from .scene import Plan, Scene, SceneSweep, Step
from .scene import builtin as scenes
from .simd import set_simd, simd_available, simd_enabled, use_simd

__all__ = [
    "atlas",
    "BUILD_PROFILE",
    "DEFAULT_THETA2",
    "SINGULAR_THRESHOLD",
    "BatchSweep",
    "FourBar",
    "Grashof",
    "Limits",
    "Plan",
    "Scene",
    "SceneSweep",
    "Step",
    "Solution",
    "Status",
    "Sweep",
    "SweepSummary",
    "closed_form_batch",
    "forces",
    "interop",
    "reference",
    "scenes",
    "set_simd",
    "simd_available",
    "simd_enabled",
    "sweep_batch",
    "use_simd",
]


def __getattr__(name: str) -> object:
    # pk.synthesis on first use: it brings SciPy's optimizers, which `import planarkin`
    # need not pay for
    if name == "synthesis":
        import importlib

        return importlib.import_module(".synthesis", __name__)
    raise AttributeError(f"module 'planarkin' has no attribute {name!r}")
