"""The report of a four-bar's sweep as plain data: the summary (what ``planarkin analyze``
prints and writes as summary.json) and the per-angle columns (results.csv), in degrees,
with the objects the figures are drawn from. The face prints and writes it; nothing here
draws or formats text."""

from __future__ import annotations

import math
from typing import NamedTuple

import numpy as np

from .._angles import unwrap_deg, wrap_array
from .._status import Status
from ._model import FourBar
from ._results import Limits, Solution, Sweep
from .analysis import convergence_order, unreachable_spans

__all__ = ["CSV_COLUMNS", "NEWTON_GUESS_DEG", "NEWTON_THETA2_DEG", "Report", "report"]

#: The seeds' convergence study: theta2 = 45 deg from the cold guess (80, 100) deg.
NEWTON_THETA2_DEG = 45.0
NEWTON_GUESS_DEG = {"open": (80.0, 100.0), "crossed": (-80.0, -100.0)}

#: The columns, units in brackets; one row per crank angle. Angles in degrees as computed
#: (wrapped to (-180, 180]), NaN where the status is not CONVERGED.
CSV_COLUMNS = (
    "theta2 [deg]",
    "theta3 [deg]",
    "theta4 [deg]",
    "status [code]",
    "status_name",
    "nit [-]",
    "residual [-]",
    "closed_form_deviation [deg]",
    "omega3 [rad/s]",
    "omega4 [rad/s]",
    "alpha3 [rad/s^2]",
    "alpha4 [rad/s^2]",
    "transmission_angle [deg]",
    "branch_indicator [-]",
    "coupler_x [length]",
    "coupler_y [length]",
)


class Report(NamedTuple):
    """What a four-bar's analysis reports: the summary (JSON-ready), the columns (name ->
    one value per crank angle, in :data:`CSV_COLUMNS` order), and the objects the figures
    are drawn from (the Newton study's guess in radians)."""

    summary: dict
    columns: dict
    sweep: Sweep
    limits: Limits
    newton: Solution
    guess: tuple[float, float]


def _max_abs(x: object) -> float | None:
    """Largest finite |x|, or None when there is none."""
    a = np.abs(np.asarray(x, dtype=np.float64))
    a = a[np.isfinite(a)]
    return float(a.max()) if a.size else None


def _frame(sweep: Sweep, theta2: object) -> list[float]:
    """Crank angles (radians, any turn) as sorted degrees in the sweep's frame
    [start, start + 360)."""
    t0 = float(sweep.theta2[0]) if len(sweep.theta2) else 0.0
    t = np.ravel(np.asarray(theta2, dtype=np.float64))
    return sorted(math.degrees(t0 + v) for v in np.remainder(t - t0, math.tau))


def _extremes(sweep: Sweep, y_deg: np.ndarray) -> dict:
    """min/max of ``y_deg`` over the sweep with the crank angles where they occur; the
    repeated last pose of a sweep that closes the circle is left out."""
    y = np.asarray(y_deg, dtype=np.float64)
    t2 = sweep.theta2
    if len(t2) > 1 and math.isclose(abs(t2[-1] - t2[0]), math.tau):
        y, t2 = y[:-1], t2[:-1]
    if not np.isfinite(y).any():
        return dict.fromkeys(("min", "max", "span", "theta2_at_min", "theta2_at_max"))
    i, j = np.nanargmin(y), np.nanargmax(y)
    return {
        "min": float(y[i]),
        "max": float(y[j]),
        "span": float(y[j] - y[i]),
        "theta2_at_min": math.degrees(t2[i]),
        "theta2_at_max": math.degrees(t2[j]),
    }


def _rocker(sweep: Sweep, limits: Limits) -> dict | None:
    """The rocker's swing from the limits (None when the output link turns fully)."""
    if limits.rocker_min is None or limits.rocker_max is None:
        return None
    lo = math.degrees(limits.rocker_min)
    assert limits.rocker_swing is not None  # set whenever rocker_min and rocker_max are
    swing = math.degrees(limits.rocker_swing)
    return {
        "min": lo,
        "max": lo + swing,  # counter-clockwise from min, so max >= min
        "swing": swing,
        "theta2_at_min": _frame(sweep, limits.rocker_min_theta2)[0],
        "theta2_at_max": _frame(sweep, limits.rocker_max_theta2)[0],
    }


def report(
    fb: FourBar,
    sweep: Sweep,
    *,
    step_deg: float,
    tol: float,
    max_iter: int,
    predictor: str,
    rpm: float,
    coupler: tuple[float, float],
    newton_at_deg: float = NEWTON_THETA2_DEG,
) -> Report:
    """Everything ``planarkin analyze`` reports of ``sweep`` (a sweep of ``fb`` at ``rpm``,
    the options it was solved with echoed in the summary): the closed form's deviation,
    transmission angle, coupler curve (``coupler``: distance P, angle DELTA in degrees),
    limits and spans, and a Newton solve at ``newton_at_deg`` from the cold guess."""
    t2, t3, t4, ok = sweep.theta2, sweep.theta3, sweep.theta4, sweep.success
    s, g, limits = sweep.summary(), fb.grashof(), fb.limits(sweep.mode)
    cf3, cf4 = (np.asarray(v) for v in fb.closed_form(t2, sweep.mode))
    dev = np.degrees(np.fmax(np.abs(wrap_array(t3 - cf3)), np.abs(wrap_array(t4 - cf4))))
    dev[~ok] = np.nan
    mu = np.degrees(np.asarray(FourBar.transmission_angle(t3, t4)))
    p, delta = coupler[0], math.radians(coupler[1])
    px, py = (np.asarray(v) for v in fb.coupler_curve(sweep, p, delta))
    guess_deg = NEWTON_GUESS_DEG[sweep.mode]
    guess = (math.radians(guess_deg[0]), math.radians(guess_deg[1]))
    sol = fb.solve(
        math.radians(newton_at_deg),
        mode=sweep.mode,
        guess=guess,
        tol=tol,
        max_iter=max_iter,
        history=True,
    )
    assert sol.history is not None  # asked for with history=True
    r1, r2, r3, r4 = fb.lengths
    closes = s.converged == s.points > 1 and math.isclose(abs(t2[-1] - t2[0]), math.tau)
    theta3: dict[str, object] = {}
    theta4: dict[str, object] = {}
    for d, t in ((theta3, t3), (theta4, t4)):
        u = unwrap_deg(t)
        d.update(_extremes(sweep, u))
        # over a full crank turn a link that turns fully comes back one turn further on
        d["full_rotation"] = bool(closes and abs(u[-1] - u[0]) > 180)
    unsolved = {
        Status(int(c)).name: [math.degrees(v) for v in t2[sweep.status == c]]
        for c in np.unique(sweep.status)
        if c not in (Status.CONVERGED, Status.NOT_ASSEMBLABLE)
    }
    summary = {
        "linkage": {"r1": r1, "r2": r2, "r3": r3, "r4": r4, "mode": sweep.mode},
        "grashof": {k: getattr(g, k) for k in ("condition", "barker", "kind", "description")},
        "options": {
            "theta2_start_deg": math.degrees(t2[0]),
            "theta2_stop_deg": math.degrees(t2[-1]),
            "step_deg": step_deg,
            "tol": tol,
            "max_iter": max_iter,
            "predictor": predictor,
            "rpm": rpm,
            "omega2_rad_s": sweep.omega2,
            "alpha2_rad_s2": sweep.alpha2,
            "coupler_p": p,
            "coupler_delta_deg": coupler[1],
        },
        "sweep": {
            "points": s.points,
            "converged": s.converged,
            "success_rate": s.success_rate,
            "nit_total": s.nit_total,
            "nit_mean": s.nit_mean,
            "residual_max": s.residual_max,
            "statuses": s.statuses,
        },
        "closed_form_max_deviation_deg": _max_abs(dev),
        "rocker_deg": _rocker(sweep, limits),
        "theta3_deg": theta3,
        "theta4_deg": theta4,
        "transmission_angle_deg": _extremes(sweep, mu),
        "peak_abs": {
            name: _max_abs(getattr(sweep, attr))
            for name, attr in (
                ("omega3_rad_s", "omega3"),
                ("omega4_rad_s", "omega4"),
                ("alpha3_rad_s2", "alpha3"),
                ("alpha4_rad_s2", "alpha4"),
            )
        },
        "limits": {
            "full_rotation": limits.full_rotation,
            "toggles_deg": _frame(sweep, limits.toggles),
            "dead_points_deg": _frame(sweep, limits.dead_points),
            "assemblable_intervals_deg": [
                [math.degrees(a), math.degrees(b)] for a, b in limits.intervals
            ],
        },
        "unreachable_spans_deg": [
            [math.degrees(a), math.degrees(b)] for a, b in unreachable_spans(sweep, limits)
        ],
        "unsolved_deg": unsolved,
        "newton": {
            "theta2_deg": newton_at_deg,
            "guess_deg": list(guess_deg),
            "status": sol.status.name,
            "nit": sol.nit,
            "residual": sol.residual,
            "history": sol.history.tolist(),
            "order": convergence_order(sol.history),
        },
    }
    columns = {
        "theta2 [deg]": np.degrees(t2),
        "theta3 [deg]": np.degrees(t3),
        "theta4 [deg]": np.degrees(t4),
        "status [code]": sweep.status,
        "status_name": [Status(int(c)).name for c in sweep.status],
        "nit [-]": sweep.nit,
        "residual [-]": sweep.residual,
        "closed_form_deviation [deg]": dev,
        "omega3 [rad/s]": sweep.omega3,
        "omega4 [rad/s]": sweep.omega4,
        "alpha3 [rad/s^2]": sweep.alpha3,
        "alpha4 [rad/s^2]": sweep.alpha4,
        "transmission_angle [deg]": mu,
        "branch_indicator [-]": FourBar.branch_indicator(t3, t4),
        "coupler_x [length]": px,
        "coupler_y [length]": py,
    }
    assert tuple(columns) == CSV_COLUMNS
    return Report(summary, columns, sweep, limits, sol, guess)
