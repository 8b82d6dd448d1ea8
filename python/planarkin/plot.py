"""Figures of four-bar results: each function takes result objects (a Sweep, a Solution,
optionally the linkage's limits) and returns a matplotlib Figure or Animation.

Built on matplotlib's object API (``matplotlib.figure.Figure``), never pyplot: it works on a
headless machine, leaves the caller's backend alone and keeps no global list of figures.
Angles are plotted in degrees, unwrapped so curves are continuous; crank-angle spans where
the linkage cannot assemble are shaded and dead points marked.
"""

from __future__ import annotations

import html
import math
import re
import textwrap
from collections.abc import Sequence
from typing import Any

import numpy as np
from matplotlib import colormaps
from matplotlib.animation import FuncAnimation, HTMLWriter
from matplotlib.axes import Axes
from matplotlib.figure import Figure
from matplotlib.patches import Polygon
from matplotlib.ticker import MultipleLocator

from ._types import Solution, Status, Sweep
from .fourbar import FourBar

__all__ = [
    "acceleration",
    "animation",
    "animation_frames",
    "animation_html",
    "convergence",
    "convergence_order",
    "coupler_curve",
    "linkage",
    "position",
    "positions_combined",
    "rocking",
    "transmission",
    "unreachable_spans",
    "unwrap_deg",
    "velocity",
]

_C3, _C4, _CP = "tab:blue", "tab:orange", "tab:purple"
_SHADE: dict[str, Any] = {"color": "0.6", "alpha": 0.25, "lw": 0}


# --- helpers shared with the CLI ------------------------------------------------------


def unwrap_deg(angles: object) -> np.ndarray:
    """Angles (radians) to degrees, unwrapped over the finite entries so a curve is
    continuous; NaN entries (unsolved points) stay NaN."""
    a = np.asarray(angles, dtype=np.float64)
    out = np.full(a.shape, np.nan)
    ok = np.isfinite(a)
    out[ok] = np.degrees(np.unwrap(a[ok]))
    return out


def _runs(mask: np.ndarray) -> list[tuple[int, int]]:
    """[start, stop) index ranges where ``mask`` is True."""
    d = np.diff(np.concatenate(([0], mask.astype(np.int8), [0])))
    return list(zip(np.flatnonzero(d == 1).tolist(), np.flatnonzero(d == -1).tolist(), strict=True))


def _edge(a: float, b: float, toggles: np.ndarray) -> float:
    """The boundary between crank angles a (one side) and b (the other): a toggle angle of
    the linkage (any turn) lying between them when one is known, else the midpoint."""
    lo, hi = min(a, b), max(a, b)
    for t in toggles:
        k = math.ceil((lo - t) / math.tau)
        c = t + k * math.tau
        if c <= hi:
            return float(c)
    return 0.5 * (a + b)


def unreachable_spans(sweep: Sweep, limits: object = None) -> list[tuple[float, float]]:
    """Crank-angle spans (radians, in sweep order) where the linkage cannot assemble.

    Derived from the NOT_ASSEMBLABLE runs of the sweep. A span's edge lies between the last
    assembled and the first unassemblable crank angle: it is placed at a toggle angle from
    ``limits`` (anything with a ``toggles`` array, e.g. ``FourBar.limits()``) when one lies
    there, else halfway. A span reaching an end of the sweep ends at that crank angle.
    """
    t2 = np.asarray(sweep.theta2, dtype=np.float64)
    toggles = np.asarray(getattr(limits, "toggles", ()), dtype=np.float64).ravel()
    toggles = toggles[np.isfinite(toggles)]
    spans = []
    for i, j in _runs(np.asarray(sweep.status) == Status.NOT_ASSEMBLABLE):
        start = t2[i] if i == 0 else _edge(t2[i - 1], t2[i], toggles)
        stop = t2[j - 1] if j == len(t2) else _edge(t2[j - 1], t2[j], toggles)
        spans.append((float(start), float(stop)))
    return spans


def convergence_order(history: Sequence[float] | np.ndarray) -> float:
    """Estimated order of convergence p = log(e[k+1]/e[k]) / log(e[k]/e[k-1]) from the last
    triple of strictly decreasing positive residuals; NaN when there is none."""
    e = np.asarray(history, dtype=np.float64).ravel()
    for k in range(len(e) - 2, 0, -1):
        e0, e1, e2 = e[k - 1], e[k], e[k + 1]
        if np.isfinite(e0) and e0 > e1 > e2 > 0:
            return float(math.log(e2 / e1) / math.log(e1 / e0))
    return float("nan")


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


def _fit_titles(fig: Figure) -> Figure:
    """Wraps every title (of the figure and of its axes) onto more lines wherever it
    would leave the canvas; constrained layout then makes room for the lines. Text and
    canvas both scale with the resolution, so what fits at one dpi fits at any."""
    sup = getattr(fig, "_suptitle", None)  # set by fig.suptitle(); no public getter of the Text
    titles = [sup, *(ax.title for ax in fig.axes)]
    for _ in range(4):
        fig.draw_without_rendering()  # lays out (constrained layout) without drawing
        page = fig.bbox
        changed = False
        for t in titles:
            if t is None or not t.get_text():
                continue
            e = t.get_window_extent()
            centre = 0.5 * (e.x0 + e.x1)
            room = 0.96 * 2.0 * min(centre - page.x0, page.x1 - centre)
            if e.width <= room:
                continue
            lines = t.get_text().split("\n")
            chars = max(12, int(max(map(len, lines)) * room / e.width))
            t.set_text("\n".join(textwrap.fill(line, chars) for line in lines))
            changed = True
        if not changed:
            break
    return fig


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
    return _fit_titles(fig)


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
    return _fit_titles(fig)


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
    return _fit_titles(fig)


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
    return _fit_titles(fig)


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
    return _fit_titles(fig)


# --- geometry: coupler curve, linkage drawing, animation ---------------------------------


def _joints(sweep: Sweep, p: float, delta: float):
    """Crank pin A, rocker pin B and coupler point P as (n, 2) arrays (NaN where unsolved)."""
    fb = FourBar(*sweep.lengths)
    r1, r2, r3, _ = sweep.lengths
    t2, t3 = np.asarray(sweep.theta2), np.asarray(sweep.theta3)
    a = np.column_stack((r2 * np.cos(t2), r2 * np.sin(t2)))
    b = a + np.column_stack((r3 * np.cos(t3), r3 * np.sin(t3)))
    b[~np.isfinite(t3)] = np.nan
    px, py = fb.coupler_curve(sweep, p, delta)
    return a, b, np.column_stack((px, py)), np.array([[0.0, 0.0], [r1, 0.0]])


def _ground(ax: Axes, ground: np.ndarray, size: float) -> None:
    ax.plot(*ground.T, color="0.35", ls="--", lw=1.2, zorder=1)
    for gx, gy in ground:
        tri = np.array([[gx, gy], [gx - size, gy - 1.6 * size], [gx + size, gy - 1.6 * size]])
        ax.add_patch(Polygon(tri, closed=True, fc="0.75", ec="0.2", lw=1.0, zorder=2))
    ax.plot(*ground.T, "o", color="k", ms=5, zorder=5)


def _frame_limits(ax: Axes, *arrays: np.ndarray, pad: float = 0.08) -> None:
    pts = np.concatenate([np.asarray(a).reshape(-1, 2) for a in arrays])
    pts = pts[np.isfinite(pts).all(axis=1)]
    lo, hi = pts.min(axis=0), pts.max(axis=0)
    m = pad * float(max(hi - lo)) + 1e-12
    ax.set_xlim(lo[0] - m, hi[0] + m)
    ax.set_ylim(lo[1] - 2.5 * m, hi[1] + m)
    ax.set_aspect("equal", adjustable="box")


def coupler_curve(sweep: Sweep, p: float, delta: float, *, limits: object = None) -> Figure:
    """The coupler-point curve: the path of the point at distance ``p`` from the crank pin,
    at angle ``delta`` (radians) from the coupler line, coloured by crank angle."""
    a, b, pt, ground = _joints(sweep, p, delta)
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
    _ground(ax, ground, 0.03 * max(sweep.lengths))
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
    _frame_limits(ax, pt, ground)
    return _fit_titles(fig)


def _pose_indices(sweep: Sweep, n: int) -> np.ndarray:
    ok = np.flatnonzero(np.asarray(sweep.status) == Status.CONVERGED)
    if ok.size == 0:
        return ok
    t2 = np.asarray(sweep.theta2)
    # a sweep that closes the circle repeats its first pose at the end
    m = (
        ok.size - 1
        if ok.size > 1 and math.isclose(abs(t2[ok[-1]] - t2[ok[0]]), math.tau)
        else ok.size
    )
    return ok[np.unique(np.linspace(0, m, n, endpoint=False).astype(int))]


def linkage(sweep: Sweep, p: float, delta: float, *, poses: int = 6) -> Figure:
    """A drawing of the linkage at several crank angles: ground pivots, crank, coupler
    (with its coupler point) and rocker, over the traced coupler curve."""
    a, b, pt, ground = _joints(sweep, p, delta)
    fig = Figure(figsize=(7.5, 6.0), layout="constrained")
    ax = fig.subplots()
    ax.plot(pt[:, 0], pt[:, 1], color=_CP, lw=1.6, zorder=1, label="coupler curve")
    idx = _pose_indices(sweep, poses)
    cmap = colormaps["viridis"]
    for n, i in enumerate(idx):
        c = cmap(n / max(len(idx) - 1, 1))
        tri = np.array([a[i], b[i], pt[i]])
        ax.add_patch(Polygon(tri, closed=True, fc=c, ec=c, alpha=0.12, zorder=2))
        chain = np.array([ground[0], a[i], b[i], ground[1]])
        ax.plot(
            chain[:, 0],
            chain[:, 1],
            "-o",
            color=c,
            lw=2.0,
            ms=4,
            zorder=3,
            label=f"θ2 = {np.degrees(sweep.theta2[i]):.0f}°",
        )
        ax.plot(*pt[i], "*", color=c, ms=9, zorder=4)
    _ground(ax, ground, 0.03 * max(sweep.lengths))
    ax.set_title(
        f"Linkage at {len(idx)} crank angles: {_title(sweep)}\n"
        f"coupler point ★ p = {p:g}, δ = {math.degrees(delta):g}°"
    )
    ax.set_xlabel("x [length]")
    ax.set_ylabel("y [length]")
    ax.grid(True, alpha=0.35)
    fig.legend(loc="outside right center", fontsize="small")
    _frame_limits(ax, a, b, pt, ground)
    return _fit_titles(fig)


def rocking(fb: FourBar, limits: Any, sweep: Sweep, *, points: int = 181) -> list[Sweep]:
    """The motion a linkage whose crank cannot turn fully can make, as the sweeps to play
    one after another: the crank rocks between the two toggles bounding an assemblable
    interval (the one holding the first solved point of ``sweep``, else the first), on
    ``sweep.mode`` one way, then, the crank having reversed at the toggle, back on the
    other mode (the assembly passes through the toggle onto the other mode), and so on.
    ``points`` crank angles each way, bunched towards the toggles and 1e-6 rad inside them
    (at a toggle itself the position is a dead point: SINGULAR). A crank that turns
    fully: ``[sweep]``."""
    if limits.full_rotation or not limits.intervals:
        return [sweep]
    ok = np.flatnonzero(np.asarray(sweep.status) == Status.CONVERGED)
    a, b = limits.intervals[0]
    if ok.size:
        t0 = float(sweep.theta2[ok[0]])
        for lo, hi in limits.intervals:
            if lo + (t0 - lo) % math.tau <= hi:
                a, b = lo, hi
                break
    # crank angles bunched towards the toggles (cosine spacing), where the rest of the
    # linkage moves fastest (as the square root of the distance to the toggle): the
    # pins then move by about equal steps
    inset = min(1e-6, 0.25 * (b - a))
    u = np.linspace(0.0, math.pi, points)
    there = np.clip(a + (b - a) * 0.5 * (1.0 - np.cos(u)), a + inset, b - inset)
    other = "crossed" if sweep.mode == "open" else "open"
    return [
        fb.sweep(there, mode=sweep.mode, method="closed-form"),
        fb.sweep(there[::-1], mode=other, method="closed-form"),
    ]


def _parts(sweep: Sweep | Sequence[Sweep]) -> list[Sweep]:
    return [sweep] if isinstance(sweep, Sweep) else list(sweep)


def animation_frames(sweep: Sweep | Sequence[Sweep], frames: int) -> np.ndarray:
    """Indices, into the sweeps played one after another (their points concatenated), of
    the points that :func:`animation` shows: at most ``frames``, evenly spaced; a single
    sweep that closes the circle does not repeat its first pose."""
    parts = _parts(sweep)
    t2 = np.concatenate([np.asarray(p.theta2) for p in parts]) if parts else np.empty(0)
    n = len(t2)
    closes = len(parts) == 1 and n > 1 and math.isclose(abs(t2[-1] - t2[0]), math.tau)
    idx = np.unique(np.linspace(0, n - 1 if closes else n, frames, endpoint=False).astype(int))
    return idx[idx < n]


def animation(
    sweep: Sweep | Sequence[Sweep],
    p: float,
    delta: float,
    *,
    frames: int = 72,
    fps: float = 12,
    dpi: float = 80,
) -> FuncAnimation:
    """The linkage moving through the sweep with its coupler curve traced; several sweeps
    (e.g. :func:`rocking`) are played one after another, each frame labelled with its
    assembly mode. Save it with ``anim.save("x.gif", writer=PillowWriter(fps))`` or
    :func:`animation_html`."""
    if frames < 1:
        raise ValueError(f"frames must be >= 1, got {frames}")
    parts = _parts(sweep)
    if not parts:
        raise ValueError("sweep: nothing to animate")
    joints = [_joints(s, p, delta) for s in parts]
    a, b, pt = (np.concatenate([j[k] for j in joints]) for k in range(3))
    ground = joints[0][3]
    t2 = np.concatenate([np.asarray(s.theta2) for s in parts])
    status = np.concatenate([np.asarray(s.status) for s in parts])
    modes = [s.mode for s in parts for _ in range(len(s.theta2))]
    idx = animation_frames(parts, frames)

    fig = Figure(figsize=(6.0, 4.8), dpi=dpi, layout="constrained")
    ax = fig.subplots()
    ax.plot(pt[:, 0], pt[:, 1], color="0.8", lw=1.0, zorder=1)
    _ground(ax, ground, 0.03 * max(parts[0].lengths))
    (trace,) = ax.plot([], [], color=_CP, lw=1.8, zorder=2)
    coupler = Polygon(np.zeros((3, 2)), closed=True, fc="tab:blue", alpha=0.25, zorder=3)
    ax.add_patch(coupler)
    (crank,) = ax.plot([], [], "-o", color="tab:red", lw=3, ms=5, zorder=4)
    (links,) = ax.plot([], [], "-o", color="tab:blue", lw=3, ms=5, zorder=4)
    (point,) = ax.plot([], [], "*", color=_CP, ms=12, zorder=5)
    label = ax.text(0.02, 0.97, "", transform=ax.transAxes, va="top", family="monospace")
    how = _title(parts[0]) if len(parts) == 1 else _title(parts[0]).rsplit(",", 1)[0]
    if len(parts) > 1:
        how += ", crank rocking between its toggles"
    ax.set_title(f"{how}, p = {p:g}, δ = {math.degrees(delta):g}°", fontsize="medium")
    ax.grid(True, alpha=0.3)
    _frame_limits(ax, a, b, pt, ground)
    _fit_titles(fig)

    def draw(i: int):
        ok = status[i] == Status.CONVERGED
        crank.set_data([0.0, a[i, 0]], [0.0, a[i, 1]])
        seen = pt[: i + 1]
        trace.set_data(seen[:, 0], seen[:, 1])
        if ok:
            links.set_data([a[i, 0], b[i, 0], ground[1, 0]], [a[i, 1], b[i, 1], ground[1, 1]])
            point.set_data([pt[i, 0]], [pt[i, 1]])
            coupler.set_xy(np.array([a[i], b[i], pt[i]]))
        else:
            links.set_data([], [])
            point.set_data([], [])
            coupler.set_xy(np.full((3, 2), np.nan))
        state = "" if ok else "  " + Status(int(status[i])).name.lower().replace("_", " ")
        mode = f"  {modes[i]}" if len(parts) > 1 else ""
        label.set_text(f"θ2 = {math.degrees(t2[i]):6.1f}°{mode}{state}")
        return trace, coupler, crank, links, point, label

    return FuncAnimation(fig, draw, frames=idx.tolist(), interval=1000.0 / fps, blit=False)


def _svg(*shapes: str) -> str:
    """A 16 x 16 inline SVG icon in the button's text colour: no font needed."""
    return (
        '<svg viewBox="0 0 16 16" width="16" height="16" fill="currentColor" '
        'aria-hidden="true" style="vertical-align:middle">' + "".join(shapes) + "</svg>"
    )


_BAR = '<rect x="{}" y="3" width="2.5" height="10"/>'
_LEFT = '<polygon points="{},3 {},13 {},8"/>'  # a triangle pointing left
_ICONS = {  # matplotlib's Font Awesome classes -> inline SVG
    "fa-minus": _svg('<rect x="3" y="7" width="10" height="2.5"/>'),
    "fa-fast-backward": _svg(_BAR.format(1.5), _LEFT.format(9, 9, 4), _LEFT.format(14, 14, 9)),
    "fa-step-backward": _svg(_BAR.format(3), _LEFT.format(13, 13, 6)),
    "fa-play fa-flip-horizontal": _svg(_LEFT.format(12.5, 12.5, 3.5)),
    "fa-pause": _svg(_BAR.format(4), _BAR.format(9.5)),
    "fa-play": _svg('<polygon points="3.5,3 3.5,13 12.5,8"/>'),
    "fa-step-forward": _svg('<polygon points="3,3 3,13 10,8"/>', _BAR.format(10.5)),
    "fa-fast-forward": _svg(
        '<polygon points="2,3 2,13 7,8"/>', '<polygon points="7,3 7,13 12,8"/>', _BAR.format(12)
    ),
    "fa-plus": _svg('<rect x="3" y="6.75" width="10" height="2.5"/>',
                    '<rect x="6.75" y="3" width="2.5" height="10"/>'),
}  # fmt: skip


def animation_html(anim: FuncAnimation, *, fps: float = 12, title: str = "planarkin") -> str:
    """A self-contained HTML page (frames embedded as base64 PNG, play controls in plain
    JavaScript) for an animation, playing (looped) as soon as it loads. matplotlib's player
    loads its button icons from a web font; they are drawn as inline SVG instead, so the
    page needs no network and no particular font."""
    import tempfile
    from pathlib import Path

    with tempfile.TemporaryDirectory() as tmp:
        path = Path(tmp, "anim.html")
        # matplotlib's stub types fps as int, but the writers take any positive number
        # (Animation.save itself passes fps=1000.0 / interval); a float fps is kept as is.
        writer = HTMLWriter(
            fps=fps,  # type: ignore[arg-type]
            embed_frames=True,
            default_mode="loop",
            embed_limit=1e6,
        )
        anim.save(str(path), writer=writer)
        body = path.read_text(encoding="utf-8")
    body = re.sub(r"<link\b[^>]*\bhref=[\"']https?://[^>]*>", "", body)
    body = re.sub(
        r'<i class="fa ([^"]*)"></i>',
        lambda m: _ICONS.get(m.group(1).strip(), _svg('<circle cx="8" cy="8" r="3"/>')),
        body,
    )
    # start playing once matplotlib's player object exists (it is made in a timeout)
    names = sorted(set(re.findall(r"\b(anim[0-9a-f]{32})\s*=\s*new Animation", body)))
    autoplay = "".join(
        f'(function start() {{ var a = window["{n}"]; '
        "if (a) { a.play_animation(); } else { setTimeout(start, 10); } })();"
        for n in names
    )
    title = html.escape(title)
    return (
        '<!DOCTYPE html>\n<html lang="en">\n<head>\n<meta charset="utf-8">\n'
        f"<title>{title}</title>\n<style>body{{font-family:sans-serif;margin:1.5em}}"
        ".anim-buttons button{min-width:2.6em;font-size:1em}</style>\n</head>\n<body>\n"
        f"<h3>{title}</h3>\n{body}\n<script>{autoplay}</script>\n</body>\n</html>\n"
    )
