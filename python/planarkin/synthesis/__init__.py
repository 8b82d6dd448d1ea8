"""Dimensional synthesis of any scene (``Problem(scene, free=[...], target=...)``: function
and path generation with branch and order constraints on the real linkage) and the
defect-free synthesis of double butterfly linkages (seed 003): the seed's loop choice and
generated output in closed form, SLSQP multistarts on the true linkage (the Rust scene
solver), verification, and the Ackermann steering example; a torque objective
(``minimise_effort``: the peak or RMS input effort of a loaded scene, exact gradient) with
its template (``balanced_arm``).

>>> from planarkin.synthesis import admissible_loop_choices, TYPE_I_LINKS
>>> len(admissible_loop_choices(TYPE_I_LINKS, "1", "2", "5"))
26
"""

from . import ackermann, path
from .driver import synthesize
from .effort import EffortDesign, balanced_arm, minimise_effort
from .generated import SIGN_COMBINATIONS, Generated, SeedPlan, half_angle
from .pool import process_pool, stop_pool
from .problem import (
    OBJECTIVES,
    DesignSpace,
    FunctionTarget,
    PathPoints,
    PathTarget,
    Problem,
    Residuals,
)
from .results import StartResult, SynthesisInterrupted, SynthesisResult
from .robust import linearized_tolerance, robust_start
from .space import SceneSpace
from .start import run_start
from .topology import (
    STEERING_KNUCKLE,
    STEERING_LEVER,
    TEMPLATES,
    TYPE_I,
    TYPE_I_LINKS,
    LoopChoice,
    Template,
    admissible_loop_choices,
    loops,
)
from .verify import linear_sensitivity, tolerance_sensitivity, true_error, verify, verify_scene

__all__ = [
    "balanced_arm",
    "minimise_effort",
    "OBJECTIVES",
    "SIGN_COMBINATIONS",
    "STEERING_KNUCKLE",
    "STEERING_LEVER",
    "TEMPLATES",
    "TYPE_I",
    "TYPE_I_LINKS",
    "DesignSpace",
    "EffortDesign",
    "FunctionTarget",
    "Generated",
    "LoopChoice",
    "PathPoints",
    "PathTarget",
    "Residuals",
    "Problem",
    "SceneSpace",
    "SeedPlan",
    "StartResult",
    "SynthesisInterrupted",
    "SynthesisResult",
    "Template",
    "ackermann",
    "path",
    "admissible_loop_choices",
    "half_angle",
    "linear_sensitivity",
    "linearized_tolerance",
    "loops",
    "process_pool",
    "robust_start",
    "run_start",
    "stop_pool",
    "synthesize",
    "tolerance_sensitivity",
    "true_error",
    "verify",
    "verify_scene",
]
