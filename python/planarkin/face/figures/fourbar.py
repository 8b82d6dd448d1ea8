"""Figures of four-bar results: each function takes result objects (a Sweep, a Solution,
optionally the linkage's limits) and returns a matplotlib Figure.

Built on matplotlib's object API (``matplotlib.figure.Figure``), never pyplot: it works on a
headless machine, leaves the caller's backend alone and keeps no global list of figures.
Angles are plotted in degrees, unwrapped so curves are continuous; crank-angle spans where
the linkage cannot assemble are shaded and dead points marked.
"""

from __future__ import annotations

import math
from typing import Any

import numpy as np
from matplotlib import colormaps
from matplotlib.axes import Axes
from matplotlib.figure import Figure
from matplotlib.ticker import MultipleLocator

from ..._status import Status
from ...fourbar import COUPLER_POINT, FourBar, Solution, Sweep
from ...fourbar.analysis import convergence_order, unreachable_spans
from .. import draw
from ..degrees import unwrap_deg
from ..titles import fit_titles

__all__ = [
    "acceleration",
    "convergence",
    "coupler_curve",
    "linkage",
    "position",
    "positions_combined",
    "transmission",
    "velocity",
]

_C3, _C4, _CP = "tab:blue", "tab:orange", "tab:purple"
_SHADE: dict[str, Any] = {"color": "0.6", "alpha": 0.25, "lw": 0}


def _title(sweep: Sweep) -> str:
    r = ", ".join(f"{x:g}" for x in sweep.lengths)
    return f"r = ({r}), {sweep.mode} mode"


def _deg_axis(ax: Axes, sweep: Sweep) -> None:
    x = np.degrees(sweep.theta2)
    if len(x):
        lo, hi = float(np.min(x)), float(np.max(x))
        if hi > lo:
            ax.set_xlim(lo, hi)
        if 180 <= hi - lo <= 720:
            ax.xaxis.set_major_locator(MultipleLocator(45))
    ax.grid(True, alpha=0.35)


def _all_turns(angles: object, sweep: Sweep) -> np.ndarray:
    """Crank angles (radians) repeated every turn, in degrees, within the sweep's range."""
    t = np.asarray(angles if angles is not None else (), dtype=np.float64).ravel()
    t2 = np.asarray(sweep.theta2)
    if not (t.size and t2.size):
        return np.empty(0)
    lo, hi = float(t2.min()), float(t2.max())
    k = np.arange(math.floor((lo - t.max()) / math.tau), math.ceil((hi - t.min()) / math.tau) + 1)
    x = (t[:, None] + math.tau * k[None, :]).ravel()
    return np.degrees(np.sort(x[(x >= lo - 1e-12) & (x <= hi + 1e-12)]))


def _mark_status(ax: Axes, sweep: Sweep, limits: object) -> None:
    """Shades unreachable spans; marks dead points (SINGULAR in the sweep, or known from
    ``limits.dead_points``) and points that failed otherwise as vertical lines."""
    for n, (a, b) in enumerate(unreachable_spans(sweep, limits)):
        ax.axvspan(
            math.degrees(a), math.degrees(b), **_SHADE, label="not assemblable" if n == 0 else None
        )
    st = np.asarray(sweep.status)
    dead = np.concatenate((
        np.degrees(sweep.theta2[st == Status.SINGULAR]),
        _all_turns(getattr(limits, "dead_points", None), sweep),
    ))  # fmt: skip
    for n, x in enumerate(np.unique(np.round(dead, 9))):
        ax.axvline(x, color="tab:red", ls=":", lw=1.2, label="dead point" if n == 0 else None)
    for code in np.unique(st):
        if code in (Status.CONVERGED, Status.NOT_ASSEMBLABLE, Status.SINGULAR):
            continue
        label = Status(int(code)).name.lower().replace("_", " ")
        for n, x in enumerate(np.degrees(sweep.theta2[st == code])):
            ax.axvline(x, color="tab:red", ls="--", lw=1.0, label=label if n == 0 else None)


def _figure(nrows: int = 1, *, figsize: tuple[float, float] = (8.0, 5.0), sharex: bool = True):
    fig = Figure(figsize=figsize, layout="constrained")
    axes = fig.subplots(nrows, 1, sharex=sharex, squeeze=False)[:, 0]
    return fig, axes


def _need(sweep: Sweep, *names: str) -> list[np.ndarray]:
    vals = [getattr(sweep, n) for n in names]
    if any(v is None for v in vals):
        raise ValueError(
            f"the sweep has no {'/'.join(names)}: sweep with omega2 (and alpha2) to compute them"
        )
    return vals


# --- position, velocity, acceleration, transmission -------------------------------------


def position(sweep: Sweep, *, limits: object = None) -> Figure:
    """theta3 and theta4 against theta2, in separate panels (the seeds' figure A)."""
    fig, (a3, a4) = _figure(2, figsize=(8.0, 6.0))
    x = np.degrees(sweep.theta2)
    for ax, y, c, name in (
        (a3, sweep.theta3, _C3, "coupler θ3"),
        (a4, sweep.theta4, _C4, "rocker θ4"),
    ):
        ax.plot(x, unwrap_deg(y), color=c, lw=1.8, label=name)
        _mark_status(ax, sweep, limits)
        ax.set_ylabel(f"{name} [deg]")
        _deg_axis(ax, sweep)
        ax.legend(loc="best", fontsize="small")
    a4.set_xlabel("crank angle θ2 [deg]")
    fig.suptitle(f"Position analysis: {_title(sweep)}")
    return fit_titles(fig)


def positions_combined(sweep: Sweep, *, limits: object = None) -> Figure:
    """theta3 and theta4 against theta2 on one axes."""
    fig, (ax,) = _figure()
    x = np.degrees(sweep.theta2)
    ax.plot(x, unwrap_deg(sweep.theta3), color=_C3, lw=1.8, label="coupler θ3")
    ax.plot(x, unwrap_deg(sweep.theta4), color=_C4, lw=1.8, label="rocker θ4")
    _mark_status(ax, sweep, limits)
    _deg_axis(ax, sweep)
    ax.set_xlabel("crank angle θ2 [deg]")
    ax.set_ylabel("angle [deg]")
    ax.legend(loc="best", fontsize="small")
    ax.set_title(f"Link angles: {_title(sweep)}")
    return fit_titles(fig)


def velocity(sweep: Sweep, *, limits: object = None) -> Figure:
    """Angular velocities omega3 and omega4 against theta2 (needs a sweep with omega2)."""
    w3, w4 = _need(sweep, "omega3", "omega4")
    return _rates(sweep, w3, w4, "ω", "rad/s", "Angular velocity", limits)


def acceleration(sweep: Sweep, *, limits: object = None) -> Figure:
    """Angular accelerations alpha3 and alpha4 against theta2 (needs omega2 and alpha2)."""
    a3, a4 = _need(sweep, "alpha3", "alpha4")
    return _rates(sweep, a3, a4, "α", "rad/s²", "Angular acceleration", limits)


def _rates(sweep, y3, y4, sym, unit, what, limits) -> Figure:
    fig, (ax,) = _figure()
    x = np.degrees(sweep.theta2)
    ax.plot(x, y3, color=_C3, lw=1.8, label=f"coupler {sym}3")
    ax.plot(x, y4, color=_C4, lw=1.8, label=f"rocker {sym}4")
    ax.axhline(0, color="0.3", lw=0.8)
    _mark_status(ax, sweep, limits)
    _deg_axis(ax, sweep)
    ax.set_xlabel("crank angle θ2 [deg]")
    ax.set_ylabel(f"{what.lower()} [{unit}]")
    ax.legend(loc="best", fontsize="small")
    crank = ""
    if sweep.omega2 is not None:  # the crank's motion on a line of its own
        crank = f"\nω2 = {sweep.omega2:.4g} rad/s ({sweep.omega2 * 60 / math.tau:.4g} rpm)"
        if sym == "α" and sweep.alpha2 is not None:
            crank += f", α2 = {sweep.alpha2:.4g} rad/s²"
    ax.set_title(f"{what}: {_title(sweep)}{crank}")
    return fit_titles(fig)


def transmission(sweep: Sweep, *, limits: object = None, guideline_deg: float = 40.0) -> Figure:
    """Transmission angle (acute angle between coupler and rocker) and the branch indicator
    sin(theta4 - theta3) (> 0 open, < 0 crossed, 0 at a dead point)."""
    fig, (am, ab) = _figure(2, figsize=(8.0, 6.0))
    x = np.degrees(sweep.theta2)
    mu = np.degrees(np.asarray(FourBar.transmission_angle(sweep.theta3, sweep.theta4)))
    am.plot(x, mu, color="tab:green", lw=1.8, label="transmission angle μ")
    am.axhline(guideline_deg, color="tab:red", ls="--", lw=1, label=f"{guideline_deg:g}° guideline")
    am.set_ylim(0, 92)
    am.set_ylabel("μ [deg]")
    ab.plot(
        x,
        FourBar.branch_indicator(sweep.theta3, sweep.theta4),
        color="tab:brown",
        lw=1.8,
        label="sin(θ4 − θ3)",
    )
    ab.axhline(0, color="0.3", lw=0.8)
    ab.set_ylim(-1.05, 1.05)
    ab.set_ylabel("branch indicator")
    ab.set_xlabel("crank angle θ2 [deg]")
    for ax in (am, ab):
        _mark_status(ax, sweep, limits)
        _deg_axis(ax, sweep)
        ax.legend(loc="best", fontsize="small")
    fig.suptitle(f"Transmission angle and branch: {_title(sweep)}")
    return fit_titles(fig)


def convergence(
    solution: Solution, *, guess: tuple[float, float] | None = None, tol: float | None = None
) -> Figure:
    """Residual norm per Newton iteration on a log scale (needs ``solve(..., history=True)``),
    with the estimated order of convergence in the legend. ``guess`` (radians) and ``tol``
    only annotate the figure."""
    hist = solution.history
    if hist is None:
        raise ValueError("the solution has no history: solve with history=True")
    e = np.asarray(hist, dtype=np.float64)
    fig, (ax,) = _figure(figsize=(7.0, 4.8))
    k = np.arange(len(e))
    shown = np.where(e > 0, e, np.nan)  # an exact zero has no place on a log axis
    order = convergence_order(e)
    lab = "residual max(|f1|, |f2|) / longest link"
    lab += f"\nestimated order of convergence p ≈ {order:.2f}" if np.isfinite(order) else ""
    ax.semilogy(k, shown, "-o", color="tab:blue", lw=1.8, ms=6, label=lab)
    if tol is not None:
        ax.axhline(tol, color="tab:red", ls="--", lw=1, label=f"tolerance {tol:g}")
    ax.set_xlabel("iteration k")
    ax.set_ylabel("residual norm")
    ax.xaxis.set_major_locator(MultipleLocator(1))
    ax.grid(True, which="both", alpha=0.3)
    start = ""
    if guess is not None:
        start = f" from (θ3, θ4) = ({math.degrees(guess[0]):g}°, {math.degrees(guess[1]):g}°)"
    verdict = f"converged in {solution.nit} iterations"
    if not solution.success:
        verdict = f"after {solution.nit} iterations: {solution.status.message}"
    ax.set_title(f"Newton-Raphson at θ2 = {math.degrees(solution.theta2):g}°{start}\n{verdict}")
    if len(e) == 0 or not np.isfinite(shown).any():
        ax.text(0.5, 0.5, solution.status.message, transform=ax.transAxes, ha="center")
    ax.legend(loc="best", fontsize="small")
    return fit_titles(fig)


# --- geometry: the coupler curve, the linkage drawn -------------------------------------


def pose_points(sweep: Sweep, p: float, delta: float) -> dict[str, np.ndarray]:
    """The sweep's points (O2, O4, A, B) and the coupler point P at distance ``p`` from A,
    at angle ``delta`` from the line A-B, as (N, 2) arrays (NaN where unsolved)."""
    px, py = FourBar(*sweep.lengths).coupler_curve(sweep, p, delta)
    return {**sweep.points, COUPLER_POINT: np.column_stack((px, py))}


def _at(points: dict[str, np.ndarray], i: int) -> dict[str, np.ndarray]:
    return {n: v[i] for n, v in points.items()}


def _ground_size(sweep: Sweep) -> float:
    return 0.03 * max(sweep.lengths)


def coupler_curve(sweep: Sweep, p: float, delta: float, *, limits: object = None) -> Figure:
    """The coupler-point curve: the path of the point at distance ``p`` from the crank pin,
    at angle ``delta`` (radians) from the coupler line, coloured by crank angle."""
    pts = pose_points(sweep, p, delta)
    pt = pts[COUPLER_POINT]
    fig = Figure(figsize=(7.0, 5.5), layout="constrained")
    ax = fig.subplots()
    ax.plot(pt[:, 0], pt[:, 1], color="0.25", lw=1.2, zorder=2)
    sc = ax.scatter(pt[:, 0], pt[:, 1], c=np.degrees(sweep.theta2), cmap="viridis", s=9, zorder=3)
    fig.colorbar(sc, ax=ax, label="crank angle θ2 [deg]", shrink=0.8)
    ok = np.flatnonzero(np.isfinite(pt).all(axis=1))
    if ok.size:
        ax.plot(
            *pt[ok[0]],
            "s",
            color="k",
            ms=6,
            zorder=4,
            label=f"θ2 = {np.degrees(sweep.theta2[ok[0]]):.0f}°",
        )
    st = draw.fourbar()
    draw.ground(ax, st, _at(pts, 0), _ground_size(sweep))
    n_bad = len(unreachable_spans(sweep, limits))
    ax.set_title(
        f"Coupler curve (p = {p:g}, δ = {math.degrees(delta):g}°): {_title(sweep)}"
        + (f"\n{n_bad} unreachable crank span(s): the curve has gaps" if n_bad else "")
    )
    ax.set_xlabel("x [length]")
    ax.set_ylabel("y [length]")
    ax.grid(True, alpha=0.35)
    if ok.size:
        ax.legend(loc="best", fontsize="small")
    draw.frame(ax, pt, pts["O2"][:1], pts["O4"][:1])
    return fit_titles(fig)


def _pose_indices(status: np.ndarray, theta: np.ndarray, n: int) -> np.ndarray:
    """Indices of at most ``n`` solved points, evenly spaced among them; a sweep that
    closes the circle does not show its first pose twice."""
    ok = np.flatnonzero(np.asarray(status) == Status.CONVERGED)
    if ok.size == 0:
        return ok
    t = np.asarray(theta)
    m = (
        ok.size - 1
        if ok.size > 1 and math.isclose(abs(t[ok[-1]] - t[ok[0]]), math.tau)
        else ok.size
    )
    return ok[np.unique(np.linspace(0, m, n, endpoint=False).astype(int))]


def linkage(sweep: Sweep, p: float, delta: float, *, poses: int = 6) -> Figure:
    """A drawing of the linkage at several crank angles: ground pivots, crank, coupler
    (with its coupler point) and rocker, over the traced coupler curve."""
    pts = pose_points(sweep, p, delta)
    pt = pts[COUPLER_POINT]
    fig = Figure(figsize=(7.5, 6.0), layout="constrained")
    ax = fig.subplots()
    ax.plot(pt[:, 0], pt[:, 1], color=_CP, lw=1.6, zorder=1, label="coupler curve")
    idx = _pose_indices(sweep.status, sweep.theta2, poses)
    cmap = colormaps["viridis"]
    st = draw.fourbar()
    for n, i in enumerate(idx):
        c = cmap(n / max(len(idx) - 1, 1))
        draw.pose(ax, st, _at(pts, i), color=c, lw=2.0, ms=4, fill_alpha=0.12,
                  label=f"θ2 = {np.degrees(sweep.theta2[i]):.0f}°")  # fmt: skip
    draw.ground(ax, st, _at(pts, 0), _ground_size(sweep))
    ax.set_title(
        f"Linkage at {len(idx)} crank angles: {_title(sweep)}\n"
        f"coupler point ★ p = {p:g}, δ = {math.degrees(delta):g}°"
    )
    ax.set_xlabel("x [length]")
    ax.set_ylabel("y [length]")
    ax.grid(True, alpha=0.35)
    fig.legend(loc="outside right center", fontsize="small")
    draw.frame(ax, pts["A"], pts["B"], pt, pts["O2"][:1], pts["O4"][:1])
    return fit_titles(fig)
