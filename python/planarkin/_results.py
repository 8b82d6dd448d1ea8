"""The vocabulary every result over the input shares, whichever subject (four-bar, scene)
or implementation (kernel, NumPy reference) made it: the base classes (a result over the
input, with a status, a sweep), the summary they give, and the runs of a per-point mask.
scipy's ``OptimizeResult`` is the model: a shared name means the same thing everywhere,
and each subject adds its own names."""

from __future__ import annotations

from dataclasses import dataclass
from typing import TYPE_CHECKING, Any, ClassVar

import numpy as np

from ._status import Status
from ._svg import picture, png


@dataclass(frozen=True)
class SweepSummary:
    """Totals over a sweep."""

    points: int
    converged: int
    success_rate: float
    nit_total: int
    nit_mean: float
    #: Largest residual of the converged points (NaN when none converged); None for
    #: results that keep no residual (scenes).
    residual_max: float | None
    #: Count of points per status name (only statuses that occur).
    statuses: dict[str, int]

    def __str__(self) -> str:
        counts = ", ".join(f"{k}={v}" for k, v in self.statuses.items())
        residual = "" if self.residual_max is None else f"; max residual {self.residual_max:.3g}"
        return (
            f"{self.converged}/{self.points} converged ({counts}); iterations total "
            f"{self.nit_total}, mean {self.nit_mean:.3f}{residual}"
        )


def status_counts(status: np.ndarray) -> dict[str, int]:
    """Count per status name of an array of status codes (only statuses that occur)."""
    codes, counts = np.unique(np.asarray(status), return_counts=True)
    return {Status(int(c)).name: int(k) for c, k in zip(codes, counts, strict=True)}


def true_runs(mask: np.ndarray) -> list[tuple[int, int]]:
    """[start, stop) index ranges where a per-point ``mask`` is True (e.g. the runs of
    unassemblable points of a sweep, or of solved ones)."""
    d = np.diff(np.concatenate(([0], np.asarray(mask).astype(np.int8), [0])))
    return list(zip(np.flatnonzero(d == 1).tolist(), np.flatnonzero(d == -1).tolist(), strict=True))


#: The input kinds and the words a result's repr uses for each: what its points are
#: called, the coordinate's symbol and its unit (a displacement's unit is the scene's
#: ``units`` when it names one).
INPUT_KINDS = ("angle", "displacement")
LENGTH_UNITS = "length units"


class InputResult:
    """A result over N values of the input: ``theta`` (N,) the input coordinate at each
    (an angle in radians, or a linear input's displacement s from the drawn pose, in
    length units), ``input_kind`` ("angle" or "displacement"), ``units`` (the length unit's
    name, None: not named), ``len()`` and a one-line repr naming the input's span in its
    unit. Subclasses say what they are in :meth:`_describe`."""

    __slots__ = ()
    #: What ``len(theta)`` counts when the input is an angle, as the repr names it.
    _points_name = "input angles"
    #: The input angle's symbol in the repr.
    _symbol = "theta"
    #: "angle" or "displacement" (a subclass's field where it can be either).
    input_kind = "angle"
    #: The name of the length unit (None: not named; "length units" in the repr).
    units: str | None = None

    if TYPE_CHECKING:  # provided by the subclasses (fields or properties)

        @property
        def theta(self) -> np.ndarray: ...

    def __len__(self) -> int:
        return len(self.theta)

    def _describe(self) -> str:
        """What the result is, for the repr (after the class name)."""
        return ""

    def _span(self) -> str:
        """The input's count and span, e.g. ``361 input angles, theta from 0 to 6.28319
        rad`` or ``361 input values, s from -726.477 to 715.743 mm``."""
        t = np.asarray(self.theta)
        if self.input_kind == "angle":
            words, symbol, unit = self._points_name, self._symbol, "rad"
        else:
            words, symbol, unit = "input values", "s", self.units or LENGTH_UNITS
        span = f", {symbol} from {t[0]:.6g} to {t[-1]:.6g} {unit}" if t.size else ""
        return f"{t.size} {words}{span}"

    def _tail(self) -> str:
        """What the repr says after the span (subclasses add theirs)."""
        return ""

    def __repr__(self) -> str:
        # one line: the arrays are attributes, not part of the repr
        what = self._describe()
        return f"<{type(self).__name__}{' ' + what if what else ''}, {self._span()}{self._tail()}>"


class StatusResult(InputResult):
    """A result with a status code per point: besides :class:`InputResult`'s names,
    ``status`` (int8 codes of :class:`planarkin.Status`), ``success`` and ``statuses()``;
    its repr ends with the count of each status."""

    __slots__ = ()

    if TYPE_CHECKING:  # provided by the subclasses (fields or properties)

        @property
        def status(self) -> np.ndarray: ...
        @property
        def nit(self) -> np.ndarray: ...

    @property
    def success(self) -> np.ndarray:
        """Boolean array: status == CONVERGED."""
        return self.status == Status.CONVERGED

    def statuses(self) -> dict[str, int]:
        """Count of points per status name (only statuses that occur)."""
        return status_counts(self.status)

    def _tail(self) -> str:
        counts = ", ".join(f"{k}={v}" for k, v in self.statuses().items())
        return f"; {counts or 'no points'}"

    def summary(self) -> SweepSummary:
        """Totals over every point (all M x N of a batch): points, how many converged,
        iterations (total and mean per point), the largest residual of the converged
        points (None for results that keep no residual) and the count of each status that
        occurs."""
        ok = np.asarray(self.success)
        n = int(ok.size)
        converged = int(np.count_nonzero(ok))
        nit_total = int(np.asarray(self.nit).sum(dtype=np.int64))
        residual = getattr(self, "residual", None)  # only the four-bar keeps one
        residual_max: float | None = None
        if residual is not None:
            res = np.asarray(residual)[ok]
            residual_max = float(res.max()) if res.size else float("nan")
        return SweepSummary(
            points=n,
            converged=converged,
            success_rate=converged / n if n else float("nan"),
            nit_total=nit_total,
            nit_mean=nit_total / n if n else float("nan"),
            residual_max=residual_max,
            statuses=self.statuses(),
        )


class SweepResult(StatusResult):
    """One sweep over N input values: the names every sweep result shares.

    - ``theta`` (N,): the input coordinate at each point (a four-bar's crank angle theta2)
    - ``status`` (N,) int8, ``success`` (N,) bool, ``nit`` (N,): Newton iterations
    - ``det`` (N,): signed, scale-free conditioning; its sign names the branch followed,
      its size the distance from a dead point (0 there); NaN where unsolved
    - ``points``: point name -> (N, 2) positions; ``angles``: link name -> (N,) angles
      (radians); NaN where unsolved
    - ``statuses()``, ``summary()``, ``len()`` and a one-line repr

    Each subject adds its own names (a four-bar's ``theta3``, ``residual``, ``omega4``; a
    scene's ``plan``, ``step_det``, ``velocities``).
    """

    __slots__ = ()

    if TYPE_CHECKING:  # provided by the subclasses (fields or cached properties)

        @property
        def det(self) -> np.ndarray: ...
        @property
        def points(self) -> dict[str, np.ndarray]: ...
        @property
        def angles(self) -> dict[str, np.ndarray]: ...

    #: Links (point names) and ground points a notebook picture draws (subclasses set them).
    _svg_links: ClassVar[tuple[tuple[str, ...], ...]] = ()
    _svg_ground: ClassVar[tuple[str, ...]] = ()

    def _picture(self) -> dict[str, Any] | None:
        ok = np.flatnonzero(self.success)
        if not len(ok):
            return None
        pts = self.points
        pose = {n: v[ok[0]] for n, v in pts.items()}
        title = f"{type(self).__name__}: {len(ok)} of {len(self)} solved"
        return {"pose": pose, "links": self._svg_links, "ground": self._svg_ground,
                "paths": pts, "title": title}  # fmt: skip

    def _repr_svg_(self) -> str | None:
        """A notebook's picture (a few KB of SVG): every reported point's path, and the
        first solved pose with its links; None when nothing is solved."""
        kw = self._picture()
        return None if kw is None else picture(**kw)

    def _repr_png_(self) -> bytes | None:
        """The same picture as PNG (for notebook front ends and exports without SVG)."""
        kw = self._picture()
        return None if kw is None else png(**kw)
