"""The four-bar: ``FourBar`` (Newton-Raphson sweeps, closed form, limits, Grashof/Barker
class, velocities, accelerations, coupler curves), its results, batches of many linkages,
``analysis`` (spans, convergence order, rocking) and ``tradeoff`` (speed vs accuracy)."""

from ._batch import closed_form_batch, sweep_batch
from ._model import FourBar
from ._results import COUPLER_POINT, LINKS, POINTS, BatchSweep, Grashof, Limits, Solution, Sweep

__all__ = [
    "COUPLER_POINT",
    "LINKS",
    "POINTS",
    "BatchSweep",
    "FourBar",
    "Grashof",
    "Limits",
    "Solution",
    "Sweep",
    "closed_form_batch",
    "sweep_batch",
]
