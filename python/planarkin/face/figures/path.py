"""Figures of a path synthesis: each design's linkage drawn over its coupler curve and the
target, and the error along the target (the distance from each target point to where the
design's tracer is at that point's input value, over the target's size)."""

from __future__ import annotations

import math
from collections.abc import Sequence

import numpy as np
from matplotlib import colormaps
from matplotlib.axes import Axes
from matplotlib.figure import Figure

from ...synthesis.path.results import Design
from ...synthesis.path.targets import CurveTarget
from .. import draw
from ..titles import fit_titles
from .scene import ground_size

__all__ = ["coupler_curve", "design", "distances", "error", "traced"]

#: input values the whole coupler curve is drawn from (one full turn)
CURVE_POINTS = 721


def coupler_curve(d: Design, n: int = CURVE_POINTS) -> np.ndarray:
    """The tracer's path over one full turn of the input from the drawn angle (a rocking
    input: the arcs its circuit reaches; unreachable values are NaN), or across a linear
    input's stroke: (n, 2)."""
    sc = d.scene
    if sc.input_kind == "angle":
        a0 = sc.input_angle
        sw = sc.sweep(np.linspace(a0, a0 + math.tau, n), outputs=[d.tracer])
    else:
        sw = sc.sweep(outputs=[d.tracer])
    return np.where(sw.success[:, None], sw.points[d.tracer], np.nan)


def traced(d: Design) -> tuple[np.ndarray, dict[str, np.ndarray]]:
    """Where the tracer is at each of the design's input values (n, 2), and every point
    of the linkage there (name -> (n, 2)); NaN where the linkage does not assemble."""
    sw = d.scene.sweep(d.inputs, outputs="all")
    ok = sw.success[:, None]
    pts = {k: np.where(ok, v, np.nan) for k, v in sw.points.items()}
    return pts[d.tracer], pts


def distances(target: CurveTarget, d: Design) -> np.ndarray:
    """The distance from each target point to the tracer at that point's input value,
    over the target's size (NaN where the linkage does not assemble)."""
    at, _ = traced(d)
    return np.hypot(*(at - target.points).T) / target.size


def _words(d: Design) -> str:
    check = "verified, no defect" if d.verified else "NOT verified"
    bad = [k for k in ("circuit", "branch", "order") if getattr(d.defects, k)]
    if bad:
        check += f" ({', '.join(bad)} defect)"
    return f"error max {d.error.max:.3g}, rms {d.error.rms:.3g} of the target's size; {check}"


def design(target: CurveTarget, d: Design, rank: int = 1) -> Figure:
    """The target's points over the design's coupler curve (grey: one full turn; blue: the
    traced arc through the tracer's positions at the design's inputs), each target point
    joined to where the tracer reaches it, and the linkage drawn at the first target
    point's input value."""
    fig = Figure(figsize=(7.5, 6.5), layout="constrained")
    ax = fig.subplots()
    curve = coupler_curve(d)
    at, pts = traced(d)
    ax.plot(*curve.T, "-", color="0.7", lw=1.2, label="coupler curve (full turn)", zorder=1)
    ax.plot(*at.T, "-", color="tab:blue", lw=1.8, label=f"traced by {d.tracer}", zorder=2)
    tp = target.points
    loop = np.vstack([tp, tp[:1]]) if target.closed else tp
    ax.plot(*loop.T, ":", color="tab:red", lw=1.0, zorder=3)
    ax.plot(*tp.T, "o", mfc="none", mec="tab:red", ms=5, label=f"target ({target.kind})",
            zorder=4)  # fmt: skip
    for p, q in zip(tp, at, strict=True):
        if np.isfinite(q).all():
            ax.plot([p[0], q[0]], [p[1], q[1]], "-", color="tab:red", lw=0.8, zorder=3)
    st = draw.Structure.of(d.scene)
    first = {k: v[0] for k, v in pts.items()}
    if all(np.isfinite(v).all() for v in first.values()):
        pose = first
    else:  # the linkage as drawn, where it does not reach the first point
        pose = {k: np.asarray(v) for k, v in d.scene.points.items()}
    draw.ground(ax, st, pose, ground_size(d.scene))
    draw.pose(ax, st, pose, zorder=5)
    draw.frame(ax, curve, tp, list(pose.values()))
    ax.grid(True, alpha=0.25)
    unit = d.scene.units or "length"
    ax.set_xlabel(f"x [{unit}]")
    ax.set_ylabel(f"y [{unit}]")
    ax.set_title(f"design {rank}: {d.topology}\n{_words(d)}", fontsize="medium")
    ax.legend(loc="best", fontsize="small")
    return fit_titles(fig)


def error(target: CurveTarget, designs: Sequence[Design]) -> Figure:
    """The distance from each target point to the tracer at its input value, over the
    target's size, against the point's position along the target (arc-length fraction),
    one line per design; the largest is each design's max error."""
    fig = Figure(figsize=(8.0, 4.5), layout="constrained")
    ax = fig.subplots()
    s = target.arc_fractions()
    cmap = colormaps["viridis"]
    shown: list[np.ndarray] = []
    for k, d in enumerate(designs):
        e = distances(target, d)
        shown.append(e)
        c = cmap(0.85 * k / max(1, len(designs) - 1))
        top = float(np.nanmax(e)) if np.isfinite(e).any() else math.nan
        ax.plot(s, e, "-o", color=c, ms=3, lw=1.2, label=f"design {k + 1} (max {top:.3g})")
    _error_axis(ax, shown)
    ax.set_xlabel("position along the target (arc length, fraction of its length)")
    ax.set_ylabel("distance / target size [-]")
    ax.set_title(f"error along the target ({len(target)} points, size {target.size:.4g})")
    ax.grid(True, alpha=0.3)
    if designs:
        ax.legend(loc="best", fontsize="small")
    return fit_titles(fig)


def _error_axis(ax: Axes, values: list[np.ndarray]) -> None:
    """A log axis where the errors span more than two decades (designs near exact beside
    rough ones), else a linear one from 0 without an offset."""
    v = np.concatenate([np.ravel(x) for x in values]) if values else np.zeros(0)
    v = v[np.isfinite(v) & (v > 0)]
    if len(v) and float(v.max()) > 100.0 * float(v.min()):
        ax.set_yscale("log")
        return
    ax.ticklabel_format(axis="y", useOffset=False)
    ax.set_ylim(bottom=0.0, top=1.1 * float(v.max()) if len(v) else 1.0)
