"""The multistart's results: one SLSQP start (:class:`StartResult`), the whole search
(:class:`SynthesisResult`), the Ctrl-C that carries what finished, and the words saying
why a search or start stopped early. Plain data: nothing here runs anything."""

from __future__ import annotations

import math
import platform
from dataclasses import dataclass, field
from typing import Any

import numpy as np


def versions() -> dict[str, str]:
    """What a run ran with, for its report: planarkin, NumPy, SciPy, Python and the
    platform."""
    import scipy

    from .._kernel import __version__  # the package's own, without importing the package

    return {
        "planarkin": __version__,
        "numpy": np.__version__,
        "scipy": scipy.__version__,
        "python": platform.python_version(),
        "platform": platform.platform(),
        "machine": platform.machine(),
    }


#: what :attr:`StartResult.stopped` and :attr:`SynthesisResult.stopped` say
TIME_LIMIT, INTERRUPTED = "time limit", "interrupted"


@dataclass
class StartResult:
    """One SLSQP run: where it started and ended, scipy's status, and the true figures.
    ``optimizer_status``, ``message`` and ``success`` are scipy's, of the phase whose ``x``
    this is (scipy's integer exit code; 99: stopped at the time limit, as scipy reports a
    callback's stop; -1: the start raised); ``fun`` is the least-squares phase's final
    objective; ``feasible``: every constraint and bound holds at ``x``, checked again here
    (not taken from scipy). ``status`` is ``optimizer_status`` under its former name (as
    scipy's ``OptimizeResult.status``): an integer code of scipy's, not a
    :class:`planarkin.Status`."""

    x0: np.ndarray
    x: np.ndarray
    fun: float
    max_error: float
    rms_error: float
    min_abs_det: float
    feasible: bool
    optimizer_status: int
    message: str
    nit: int
    phases: list[dict[str, Any]] = field(default_factory=list)
    #: the branch combination of the closed form (relative to the drawn pose)
    signs: tuple[int, int, int] = (1, 1, 1)
    #: scipy's ``success`` for the phase whose ``x`` this is
    success: bool = False
    #: the start's index in the multistart (its results are collected by it)
    index: int = 0
    #: why the run stopped early ("" ran to scipy's own end; TIME_LIMIT)
    stopped: str = ""

    @property
    def status(self) -> int:
        """scipy's integer exit code: :attr:`optimizer_status` (its former name, kept)."""
        return self.optimizer_status

    @property
    def converged(self) -> bool:
        """scipy reported success AND the constraints were verified to hold at ``x``."""
        return self.success and self.feasible

    @classmethod
    def failed(
        cls, x0: np.ndarray, message: str, *, index: int, signs: tuple[int, int, int]
    ) -> StartResult:
        """A start that raised: its status (-1) and ``message``, ``x`` its start."""
        return cls(
            x0=x0,
            x=x0,
            fun=math.nan,
            max_error=math.inf,
            rms_error=math.inf,
            min_abs_det=0.0,
            feasible=False,
            optimizer_status=-1,
            message=message,
            nit=0,
            signs=signs,
            index=index,
        )


@dataclass
class SynthesisResult:
    """The best run, every run that finished (by start index), and how the search went."""

    #: feasible before infeasible, then the smallest max_error, then the lowest index
    #: (None: no start finished)
    best: StartResult | None
    runs: list[StartResult]
    #: starts planned (the given x0 and the candidates kept from screening)
    starts: int
    #: candidates asked for (``samples``) and screened (fewer when stopped)
    sampled: int
    wall_s: float
    objective: str
    screened: int = 0
    #: "" (every start ran to its end), TIME_LIMIT or INTERRUPTED
    stopped: str = ""
    seed: int = 0
    #: how the derivatives were taken: "exact" or "fd"
    gradient: str = "exact"

    @property
    def feasible(self) -> list[StartResult]:
        """The runs whose constraints hold at their end, by start index."""
        return [r for r in self.runs if r.feasible]


class SynthesisInterrupted(KeyboardInterrupt):
    """Ctrl-C during :func:`synthesize`: the workers are stopped, and ``result`` holds the
    runs that had finished (``stopped`` is INTERRUPTED). A KeyboardInterrupt: code that
    does not look for it stops as on any Ctrl-C."""

    def __init__(self, result: SynthesisResult) -> None:
        super().__init__("interrupted")
        self.result = result
