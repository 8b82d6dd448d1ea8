"""planarkin: planar linkage kinematics with a Rust core.

>>> import planarkin as pk
>>> fb = pk.FourBar(6, 2, 5, 5)
>>> fb.sweep().summary().converged
361
"""

from . import reference, scenes
from ._core import BUILD_PROFILE
from ._core import __version__ as __version__
from ._types import (
    DEFAULT_THETA2,
    SINGULAR_THRESHOLD,
    BatchSweep,
    Grashof,
    Limits,
    Solution,
    Status,
    Sweep,
    SweepSummary,
)
from .fourbar import FourBar, closed_form_batch, sweep_batch
from .scene import Plan, Scene, SceneSweep, Step
from .simd import set_simd, simd_available, simd_enabled, use_simd

__all__ = [
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
    "reference",
    "scenes",
    "set_simd",
    "simd_available",
    "simd_enabled",
    "sweep_batch",
    "use_simd",
]
