"""The one door to the compiled extension ``planarkin._core`` (typed by ``_core.pyi``).

API modules take the kernel from here, never from the extension itself: static import
graphs (``lint-imports``) cannot see into an extension module, and this name lets the
import contracts in pyproject.toml say who may reach the kernel (the reference may not).
"""

from ._core import (
    BUILD_PROFILE,
    FourBar,
    Scene,
    __version__,
    closed_form_batch,
    set_simd,
    simd_available,
    simd_enabled,
    sketch,
    sweep_batch,
    transmission,
)

__all__ = [
    "BUILD_PROFILE",
    "FourBar",
    "Scene",
    "__version__",
    "closed_form_batch",
    "set_simd",
    "simd_available",
    "simd_enabled",
    "sketch",
    "sweep_batch",
    "transmission",
]
