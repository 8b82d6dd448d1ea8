"""Argument normalisation at the Python boundary, shared by the API and the NumPy
reference: real scalars, integers, strings, angle arrays, guesses and crank rates become
the plain types the kernel takes, or a ValueError naming the parameter.

Ranges and choices (tol > 0, a known mode, 1..=16 homotopy runs) are not checked here:
the core's validating constructors check them, once, for the API; the reference, which
may not call the kernel, mirrors those rules in ``reference/_rules.py``, and a test checks
that both refuse the same inputs with the same message."""

from __future__ import annotations

import operator
from typing import TYPE_CHECKING, NamedTuple, cast

import numpy as np

from ._angles import DEFAULT_THETA2

if TYPE_CHECKING:
    from collections.abc import Iterable

    from numpy.typing import ArrayLike

#: The choices the kernel accepts (the command line offers them; the core checks them).
MODES = ("open", "crossed")
PREDICTORS = ("previous", "tangent", "quadratic", "closed-form")
METHODS = ("newton", "closed-form")
#: The native float64 dtype (NumPy's builtin dtypes are singletons).
_F64 = np.dtype(np.float64)


def as_float(name: str, value: object) -> float:
    """A real scalar, or ValueError naming the parameter."""
    if type(value) is float:  # the common case, without NumPy calls
        return value
    if type(value) is int:
        try:
            return float(value)
        except OverflowError:
            raise ValueError(
                f"{name} must be a real number within the float range, got an integer of "
                f"{value.bit_length()} bits"
            ) from None
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


def as_i64(name: str, value: object) -> int:
    """An integer the kernel can take (64 bits, signed), or ValueError naming the
    parameter; its range is the kernel's to check."""
    v = value if type(value) is int else as_int(name, value)  # a plain int: no calls
    if not -(2**63) <= v < 2**63:
        raise ValueError(f"{name} must be an integer of at most 64 bits, got {v}")
    return v


def as_u64(name: str, value: object) -> int:
    """A non-negative integer of at most 64 bits (a seed), or ValueError naming it."""
    v = as_int(name, value)
    if not 0 <= v < 2**64:
        raise ValueError(f"{name} must be an integer in 0..2**64, got {v}")
    return v


def as_str(name: str, value: object) -> str:
    """A string (an option's name, e.g. a mode), or ValueError naming the parameter; which
    strings are valid is the kernel's to check."""
    if not isinstance(value, str):
        raise ValueError(f"{name} must be a string, got {value!r}")
    return value


def as_angles(name: str, value: object) -> np.ndarray:
    """A float64 array (any shape), or ValueError naming the parameter."""
    if type(value) is np.ndarray and value.dtype is _F64 and value.flags.c_contiguous:
        return value  # what np.asarray below returns for it, without its two calls
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


def check_guess(guess: object) -> tuple[float, float] | None:
    if guess is None:
        return None
    try:
        a, b = cast("Iterable[object]", guess)  # not iterable or not a pair: caught below
    except (TypeError, ValueError):
        raise ValueError(f"guess must be a pair (theta3, theta4), got {guess!r}") from None
    return as_float("guess[0]", a), as_float("guess[1]", b)


def crank_rates(omega2: object, alpha2: object) -> tuple[float | None, float | None]:
    """Crank speed and acceleration for a sweep's velocities and accelerations, as floats
    (None where not asked for); accelerations need a speed."""
    if alpha2 is not None and omega2 is None:
        raise ValueError("alpha2 needs omega2: accelerations depend on the crank speed")
    w2 = None if omega2 is None else as_float("omega2", omega2)
    a2 = None if alpha2 is None else as_float("alpha2", alpha2)
    return w2, a2


class SweepArgs(NamedTuple):
    """A sweep's arguments as the kernel takes them (types normalised, not yet checked)."""

    theta2: np.ndarray
    mode: str
    tol: float
    max_iter: int
    predictor: str
    method: str


def sweep_inputs(theta2, mode, tol, max_iter, predictor, method) -> SweepArgs:  # noqa: ANN001
    """Normalises the arguments every four-bar sweep takes (ValueError naming the
    parameter for a wrong type); the kernel checks their values."""
    return SweepArgs(
        as_theta2_1d(theta2), as_str("mode", mode), as_float("tol", tol),
        as_i64("max_iter", max_iter), as_str("predictor", predictor), as_str("method", method),
    )  # fmt: skip
