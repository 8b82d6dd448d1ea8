"""Plain result types shared by the Rust-backed API and the NumPy reference.

Nothing here imports the extension: the reference builds the same objects on its own,
so parity tests compare two independent implementations.
"""

from __future__ import annotations

import math
import operator
from dataclasses import dataclass, field
from enum import IntEnum
from typing import TYPE_CHECKING, NamedTuple, cast

import numpy as np

if TYPE_CHECKING:
    from collections.abc import Iterable

    from numpy.typing import ArrayLike

TAU = 2.0 * math.pi

#: Default crank angles: 0 to 360 degrees in 1 degree steps (361 points), in radians.
DEFAULT_THETA2 = np.arange(361) * (TAU / 360)
DEFAULT_THETA2.setflags(write=False)

#: A position whose conditioning |sin(theta4 - theta3)| min(r3, r4) / L is below this is
#: SINGULAR: rounding moves the angles by about c eps / conditioning (c measured up to
#: 1.75 near toggles), so above it every converged angle is within 1e-9 rad.
SINGULAR_THRESHOLD = 1e-6

MODES = ("open", "crossed")
PREDICTORS = ("previous", "tangent", "quadratic")
METHODS = ("newton", "closed-form")


def wrap(a: float) -> float:
    """Wraps to (-pi, pi]; angles already there are returned unchanged."""
    if -math.pi < a <= math.pi:
        return a
    if not math.isfinite(a):
        return float("nan")
    r = math.fmod(a + math.pi, TAU)
    if r < 0.0:
        r += TAU
    r -= math.pi
    return math.pi if r <= -math.pi else r


class Status(IntEnum):
    """How one solve ended. Arrays of results carry these codes as ``int8``."""

    #: Residual and next Newton correction below ``tol``, on the requested assembly mode.
    CONVERGED = 0
    #: ``max_iter`` Newton steps were taken without reaching ``tol``.
    MAX_ITERATIONS = -2
    #: The crank angle, a residual or an iterate was NaN or infinite.
    NON_FINITE = -3
    #: Conditioning |sin(theta4 - theta3)| min(r3, r4) / L below the singular threshold:
    #: a dead (toggle) or change point, where the two assembly modes meet.
    SINGULAR = -4
    #: The loop cannot close at this crank angle (known before any iteration).
    NOT_ASSEMBLABLE = -5
    #: Newton converged, but on the other assembly mode than the one requested.
    BRANCH_JUMP = -6
    #: The residual is below ``tol`` but rounding keeps the Newton correction above it:
    #: ``tol`` asks for more than double precision resolves at this point.
    PRECISION_LOSS = -7
    #: The input angle lies past a dead point of a group on the circuit being followed:
    #: the motion must reverse there (scene sweeps report the dead point's input angle).
    LIMIT = -8

    @property
    def message(self) -> str:
        """A one-line description."""
        return _MESSAGES[self]


_MESSAGES = {
    Status.CONVERGED: (
        "converged: residual and Newton correction below tolerance on the requested mode"
    ),
    Status.MAX_ITERATIONS: "maximum number of iterations reached without convergence",
    Status.NON_FINITE: "a non-finite value (NaN or infinity) was met",
    Status.SINGULAR: "singular: dead (toggle) or change point, the two modes meet",
    Status.NOT_ASSEMBLABLE: "not assemblable: the loop cannot close at this crank angle",
    Status.BRANCH_JUMP: "converged on the other assembly mode than the one requested",
    Status.PRECISION_LOSS: "tolerance below what double precision resolves at this point",
    Status.LIMIT: "past a dead point of the circuit followed: the input must reverse there",
}


@dataclass(frozen=True)
class Solution:
    """One crank angle solved by Newton-Raphson (scipy's vocabulary: success, status, nit)."""

    theta2: float
    #: Coupler angle in (-pi, pi]; NaN unless converged.
    theta3: float
    #: Rocker angle in (-pi, pi]; NaN unless converged.
    theta4: float
    success: bool
    status: Status
    #: Newton steps taken.
    nit: int
    #: Dimensionless residual max(|f1|, |f2|) / longest link at the last evaluation
    #: (the returned angles add the last Newton correction to that iterate).
    residual: float
    #: Residual per iteration (length nit + 1) when asked for with ``history=True``.
    history: np.ndarray | None = field(default=None, compare=False)

    @property
    def message(self) -> str:
        """One line saying how the solve ended (the status's message)."""
        return self.status.message


@dataclass(frozen=True)
class SweepSummary:
    """Totals over a sweep."""

    points: int
    converged: int
    success_rate: float
    nit_total: int
    nit_mean: float
    residual_max: float
    #: Count of points per status name (only statuses that occur).
    statuses: dict[str, int]

    def __str__(self) -> str:
        counts = ", ".join(f"{k}={v}" for k, v in self.statuses.items())
        return (
            f"{self.converged}/{self.points} converged ({counts}); iterations total "
            f"{self.nit_total}, mean {self.nit_mean:.3f}; max residual {self.residual_max:.3g}"
        )


@dataclass(frozen=True, eq=False)
class Sweep:
    """A crank sweep: one entry per crank angle, NaN angles wherever status != CONVERGED."""

    lengths: tuple[float, float, float, float]
    mode: str
    theta2: np.ndarray
    theta3: np.ndarray
    theta4: np.ndarray
    status: np.ndarray
    nit: np.ndarray
    residual: np.ndarray
    omega2: float | None = None
    omega3: np.ndarray | None = None
    omega4: np.ndarray | None = None
    alpha2: float | None = None
    alpha3: np.ndarray | None = None
    alpha4: np.ndarray | None = None
    #: "newton" or "closed-form" (no iterations; residual not computed, NaN).
    method: str = "newton"

    @property
    def success(self) -> np.ndarray:
        """Boolean array: status == CONVERGED."""
        return self.status == Status.CONVERGED

    def __len__(self) -> int:
        return len(self.theta2)

    def __repr__(self) -> str:
        return _sweep_repr("Sweep", self, self.lengths)

    def summary(self) -> SweepSummary:
        """Totals over the sweep: points, how many converged, iterations (total and mean
        per point), the largest residual of the converged points and the count of each
        status that occurs."""
        n = len(self.theta2)
        ok = int(np.count_nonzero(self.success))
        codes, counts = np.unique(self.status, return_counts=True)
        statuses = {Status(int(c)).name: int(k) for c, k in zip(codes, counts, strict=True)}
        nit_total = int(self.nit.sum(dtype=np.int64))
        res = self.residual[self.success]
        return SweepSummary(
            points=n,
            converged=ok,
            success_rate=ok / n if n else float("nan"),
            nit_total=nit_total,
            nit_mean=nit_total / n if n else float("nan"),
            residual_max=float(res.max()) if res.size else float("nan"),
            statuses=statuses,
        )


@dataclass(frozen=True)
class Grashof:
    """Grashof condition and Barker class (Norton, Design of Machinery, Table 2-4)."""

    #: "grashof", "change-point" or "non-grashof"
    condition: str
    #: Barker code: GCRR, GCCC, GRCR, GRRC, RRR1-4, SCCC, SCRR, SRCR, SRRC, S2X, S3X
    barker: str
    #: crank-rocker, double-crank, rocker-crank, double-rocker, change-point, triple-rocker
    kind: str
    description: str
    s: float
    l: float  # noqa: E741 - the textbook's name
    p: float
    q: float

    @property
    def is_grashof(self) -> bool:
        """S + L < P + Q (decided exactly on the float inputs)."""
        return self.condition == "grashof"


@dataclass(frozen=True, eq=False)
class Limits:
    """Limit positions on one assembly mode, from the closed form (radians)."""

    mode: str
    #: Crank angles in (-pi, pi], sorted, where det J = 0 and the crank stops.
    #: Empty when the crank turns fully.
    toggles: np.ndarray
    #: Every crank angle where det J = 0: the toggles, plus the change points a fully
    #: turning crank passes through (where the two modes meet).
    dead_points: np.ndarray
    #: Assemblable crank-angle intervals (start, end), counter-clockwise, start in
    #: [-pi, pi]; end may exceed pi when an interval contains theta2 = pi.
    intervals: tuple[tuple[float, float], ...]
    #: The crank turns a full revolution.
    full_rotation: bool
    #: The rocker's interval on this mode: it sweeps counter-clockwise from rocker_min
    #: (wrapped to (-pi, pi]) to rocker_max = rocker_min + swing, which is never below
    #: rocker_min (it exceeds pi when the interval contains 180 deg); with the crank
    #: angles where they occur. None when the output turns fully (or never assembles).
    rocker_min: float | None
    rocker_min_theta2: float | None
    rocker_max: float | None
    rocker_max_theta2: float | None

    @property
    def rocker_swing(self) -> float | None:
        """Rocker swing angle: rocker_max - rocker_min."""
        if self.rocker_min is None or self.rocker_max is None:
            return None
        return self.rocker_max - self.rocker_min

    def assemblable(self, theta2: object) -> np.ndarray:
        """Boolean mask: crank angles inside an assemblable interval."""
        t = np.asarray(theta2, dtype=np.float64)
        inside = np.zeros(t.shape, dtype=bool)
        for a, b in self.intervals:
            inside |= a + np.mod(t - a, TAU) <= b
        return inside


@dataclass(frozen=True, eq=False)
class BatchSweep:
    """Sweeps of M linkages over N crank angles: (M, N) arrays."""

    links: np.ndarray
    mode: str
    theta2: np.ndarray
    theta3: np.ndarray
    theta4: np.ndarray
    status: np.ndarray
    nit: np.ndarray
    residual: np.ndarray
    method: str = "newton"

    @property
    def success(self) -> np.ndarray:
        """Boolean (M, N) array: status == CONVERGED."""
        return self.status == Status.CONVERGED

    def __repr__(self) -> str:
        return _sweep_repr("BatchSweep", self, f"{len(self.links)} linkages")


def _sweep_repr(kind: str, s: Sweep | BatchSweep, what: object) -> str:
    """A one-line summary (the arrays are attributes, not part of the repr)."""
    t = np.asarray(s.theta2)
    span = f"{t[0]:.6g}..{t[-1]:.6g} rad" if t.size else "empty"
    codes, counts = np.unique(np.asarray(s.status), return_counts=True)
    statuses = ", ".join(
        f"{Status(int(c)).name}={int(k)}" for c, k in zip(codes, counts, strict=True)
    )
    return (
        f"<{kind} {what}, {s.mode} mode, {s.method}, {t.size} crank angles ({span}); "
        f"{statuses or 'no points'}>"
    )


# --- argument normalisation shared by the API and the reference -------------------


def as_float(name: str, value: object) -> float:
    """A real scalar, or ValueError naming the parameter."""
    if type(value) is float or type(value) is int:  # the common case, without NumPy calls
        return float(value)
    try:
        if isinstance(value, (str, bytes, complex, bool, np.bool_)) or np.iscomplexobj(
            cast("ArrayLike", value)  # any object at runtime; the stub wants ArrayLike
        ):
            raise TypeError
        return float(value)  # type: ignore[arg-type]
    except (TypeError, ValueError):
        raise ValueError(f"{name} must be a real number, got {value!r}") from None


def as_int(name: str, value: object) -> int:
    """An integer, or ValueError naming the parameter."""
    if isinstance(value, bool):
        raise ValueError(f"{name} must be an integer, got {value!r}")
    try:
        return operator.index(value)  # type: ignore[arg-type]
    except TypeError:
        raise ValueError(f"{name} must be an integer, got {value!r}") from None


def as_angles(name: str, value: object) -> np.ndarray:
    """A float64 array (any shape), or ValueError naming the parameter."""
    try:
        arr = np.asarray(value)
    except Exception:  # ragged nested sequences and the like
        raise ValueError(f"{name} must be an array of real numbers") from None
    if arr.dtype.kind not in "biuf":
        raise ValueError(f"{name} must be an array of real numbers, got dtype {arr.dtype}")
    return np.asarray(arr, dtype=np.float64, order="C")  # keeps 0-d: scalars stay scalars


def as_theta2_1d(value: object | None) -> np.ndarray:
    """Crank angles for a sweep: a 1-D float64 array (default: 0..360 deg, 1 deg steps)."""
    if value is None:
        return DEFAULT_THETA2
    arr = as_angles("theta2", value)
    if arr.ndim != 1:
        raise ValueError(f"theta2 must be a 1-D array of crank angles, got shape {arr.shape}")
    return arr


def check_mode(mode: object) -> str:
    if mode not in MODES:
        raise ValueError(f"mode must be 'open' or 'crossed', got {mode!r}")
    return mode  # type: ignore[return-value]


def check_options(tol: object, max_iter: object) -> tuple[float, int]:
    t = as_float("tol", tol)
    if not (math.isfinite(t) and t > 0):
        raise ValueError(f"tol must be finite and > 0, got {t}")
    m = as_int("max_iter", max_iter)
    if not 1 <= m <= 0xFFFFFFFF:
        raise ValueError(f"max_iter must be an integer in 1..=4294967295, got {m}")
    return t, m


def check_guess(guess: object) -> tuple[float, float] | None:
    if guess is None:
        return None
    try:
        a, b = cast("Iterable[object]", guess)  # not iterable or not a pair: caught below
    except (TypeError, ValueError):
        raise ValueError(f"guess must be a pair (theta3, theta4), got {guess!r}") from None
    return as_float("guess[0]", a), as_float("guess[1]", b)


class SweepArgs(NamedTuple):
    """Validated sweep arguments, shared by the API, the batch and the reference."""

    theta2: np.ndarray
    mode: str
    tol: float
    max_iter: int
    predictor: str
    method: str


def sweep_args(theta2, mode, tol, max_iter, predictor, method) -> SweepArgs:  # noqa: ANN001
    """Validates the arguments every sweep takes (ValueError naming the parameter)."""
    t, m = check_options(tol, max_iter)
    return SweepArgs(
        as_theta2_1d(theta2), check_mode(mode), t, m, check_predictor(predictor),
        check_method(method),
    )  # fmt: skip


def motion_args(omega2: object, alpha2: object) -> tuple[float | None, float | None]:
    """Crank speed and acceleration for a sweep's velocities/accelerations."""
    if alpha2 is not None and omega2 is None:
        raise ValueError("alpha2 needs omega2: accelerations depend on the crank speed")
    w2 = None if omega2 is None else as_float("omega2", omega2)
    a2 = None if alpha2 is None else as_float("alpha2", alpha2)
    for name, v in (("omega2", w2), ("alpha2", a2)):
        if v is not None and not math.isfinite(v):
            raise ValueError(f"{name} must be finite, got {v}")
    return w2, a2


def check_method(method: object) -> str:
    if method not in METHODS:
        raise ValueError(f"method must be 'newton' or 'closed-form', got {method!r}")
    return method  # type: ignore[return-value]


def check_predictor(predictor: object) -> str:
    if predictor not in PREDICTORS:
        raise ValueError(
            f"predictor must be 'previous', 'tangent' or 'quadratic', got {predictor!r}"
        )
    return predictor  # type: ignore[return-value]
