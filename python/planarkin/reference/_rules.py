"""The option rules of the kernel, as the reference applies them itself: the reference
may not call the kernel, so it mirrors the core's validating constructors
(``NewtonOptions::new``, ``SweepOptions::new``, the crank rates' check) here, with the
same words. A test checks that the API and the reference refuse the same inputs with the
same message, so the two copies cannot drift apart silently."""

from __future__ import annotations

import math

from .._args import (
    METHODS,
    MODES,
    PREDICTORS,
    SweepArgs,
    as_float,
    as_i64,
    as_str,
    crank_rates,
    sweep_inputs,
)


def _choice(name: str, value: object, choices: tuple[str, ...]) -> str:
    s = as_str(name, value)
    if s not in choices:
        quoted = [f"'{c}'" for c in choices]
        allowed = " or ".join([", ".join(quoted[:-1]), quoted[-1]] if len(quoted) > 1 else quoted)
        raise ValueError(f"{name} must be {allowed}, got {s!r}")
    return s


def check_mode(mode: object) -> str:
    """'open' or 'crossed' (``Mode::parse``)."""
    return _choice("mode", mode, MODES)


def check_predictor(predictor: object) -> str:
    """'previous', 'tangent', 'quadratic' or 'closed-form' (``Predictor::parse``)."""
    return _choice("predictor", predictor, PREDICTORS)


def check_method(method: object) -> str:
    """'newton' or 'closed-form' (``Method::parse``)."""
    return _choice("method", method, METHODS)


def positive_finite(name: str, value: object) -> float:
    """A real number, finite and > 0 (the core's ``positive_finite``)."""
    v = as_float(name, value)
    if not (math.isfinite(v) and v > 0):
        raise ValueError(f"{name} must be finite and > 0, got {v!r}")
    return v


def check_options(tol: object, max_iter: object) -> tuple[float, int]:
    """tol finite and > 0, max_iter an integer in 1..=4294967295 (``NewtonOptions::new``)."""
    t = positive_finite("tol", tol)
    m = as_i64("max_iter", max_iter)
    if not 1 <= m <= 0xFFFFFFFF:
        raise ValueError(f"max_iter must be an integer in 1..=4294967295, got {m}")
    return t, m


def sweep_args(theta2, mode, tol, max_iter, predictor, method) -> SweepArgs:  # noqa: ANN001
    """A sweep's arguments, normalised and checked as ``SweepOptions::new`` checks them
    (mode, tol, max_iter, predictor, method, in that order)."""
    a = sweep_inputs(theta2, mode, tol, max_iter, predictor, method)
    check_mode(a.mode)
    check_options(a.tol, a.max_iter)
    return a._replace(predictor=check_predictor(a.predictor), method=check_method(a.method))


def motion_args(omega2: object, alpha2: object) -> tuple[float | None, float | None]:
    """Crank speed and acceleration, finite where given (the kernel's sweep check)."""
    w2, a2 = crank_rates(omega2, alpha2)
    for name, v in (("omega2", w2), ("alpha2", a2)):
        if v is not None and not math.isfinite(v):
            raise ValueError(f"{name} must be finite, got {v!r}")
    return w2, a2
