"""The NumPy reference: the kernel's algorithms written plainly in NumPy and ``math``, so
tests can prove the Rust kernel computes the same thing and benchmarks can show what it
buys. ``fourbar`` mirrors ``FourBar`` (sweep, solve, closed form, velocity, acceleration);
``scene`` solves any scene by another route (every joint equation at once, no plan).

It reaches no kernel: neither the extension nor the API modules that wrap it (an import
contract in pyproject.toml checks it), or the parity tests would check the kernel against
itself. It builds the same result objects (``Sweep``, ``SceneSweep``) and shares the
plain leaves (statuses, argument normalisation, the angle wrap), and checks the options
by its own copy of the kernel's rules (``_rules``).
"""

from .._angles import TAU, wrap
from .._args import as_float, check_guess
from .._status import SINGULAR_THRESHOLD, Status
from ..fourbar._results import Solution, Sweep
from ..scene._results import SceneSweep
from ._rules import check_mode, check_options, motion_args, sweep_args
from .fourbar import (
    EPS,
    FLAT_ULPS,
    INCREMENT_MAX,
    acceleration,
    closed_form,
    closed_form_vectorized,
    sin_cos_shifted,
    solve,
    sweep,
    unit_lengths,
    velocity,
)
from .scene import JUMP, RCOND_THRESHOLD, scene_assemble_check, scene_mobility, scene_sweep

#: The scene reference's result type before it became the same SceneSweep that
#: ``Scene.sweep`` returns; kept as an alias so code naming it keeps working.
SceneReference = SceneSweep

__all__ = [
    "EPS",
    "FLAT_ULPS",
    "INCREMENT_MAX",
    "JUMP",
    "RCOND_THRESHOLD",
    "SINGULAR_THRESHOLD",
    "TAU",
    "SceneReference",
    "SceneSweep",
    "Solution",
    "Status",
    "Sweep",
    "acceleration",
    "as_float",
    "check_guess",
    "check_mode",
    "check_options",
    "closed_form",
    "closed_form_vectorized",
    "motion_args",
    "sin_cos_shifted",
    "scene_assemble_check",
    "scene_mobility",
    "scene_sweep",
    "solve",
    "sweep",
    "sweep_args",
    "unit_lengths",
    "velocity",
    "wrap",
]
