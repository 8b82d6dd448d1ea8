"""The one door to the compiled extension ``planarkin._core`` (typed by ``_core.pyi``).

API modules take the kernel from here, never from the extension itself: static import
graphs (``lint-imports``) cannot see into an extension module, and this name lets the
import contracts in pyproject.toml say who may reach the kernel (the reference may not).
"""

from ._core import (
    BUILD_PROFILE,
    MAX_ITER,
    MAX_STEP,
    RUNS,
    SCENE_KEYS,
    SCENE_MAX_DEPTH,
    SCENE_REQUIRED,
    SEED,
    SWEEP_LEN,
    TOL,
    TRACE_MAX_POINTS,
    TRACE_STEP,
    ForceModel,
    FourBar,
    Scene,
    __version__,
    closed_form_batch,
    load_scene,
    set_simd,
    simd_available,
    simd_enabled,
    sweep_batch,
    transmission,
)

__all__ = [
    "BUILD_PROFILE",
    "MAX_ITER",
    "MAX_STEP",
    "RUNS",
    "SCENE_KEYS",
    "SCENE_MAX_DEPTH",
    "SCENE_REQUIRED",
    "SEED",
    "SWEEP_LEN",
    "TOL",
    "TRACE_MAX_POINTS",
    "TRACE_STEP",
    "ForceModel",
    "FourBar",
    "Scene",
    "__version__",
    "closed_form_batch",
    "load_scene",
    "set_simd",
    "simd_available",
    "simd_enabled",
    "sweep_batch",
    "transmission",
]
