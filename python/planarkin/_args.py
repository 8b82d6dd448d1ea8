"""Argument normalisation shared by the API and the NumPy reference: real scalars, angle
arrays, modes, tolerances and the sweep options, each checked once at the boundary
(ValueError naming the parameter), so both implementations refuse the same inputs."""

from __future__ import annotations

import math
import operator
from typing import TYPE_CHECKING, NamedTuple, cast

import numpy as np

from ._angles import DEFAULT_THETA2

if TYPE_CHECKING:
    from collections.abc import Iterable

    from numpy.typing import ArrayLike

MODES = ("open", "crossed")
PREDICTORS = ("previous", "tangent", "quadratic")
METHODS = ("newton", "closed-form")


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
