"""Figures of a force analysis: the input effort over the input, the pin reactions'
magnitudes, a polar plot of one pin's force, and the linkage drawn at one input with its
pin forces as arrows. Each function returns a matplotlib Figure (object API, no pyplot)."""

from __future__ import annotations

import numpy as np
from matplotlib import colormaps
from matplotlib.figure import Figure

from ...forces import Forces
from ...scene import Scene, SceneSweep
from .. import draw
from ..fonts import clean
from .scene import ground_size

__all__ = ["arrows", "effort", "polar", "reactions"]


def _x(forces: Forces, units: str | None) -> tuple[np.ndarray, str]:
    if forces.input_kind == "angle":
        return np.degrees(forces.theta), "input angle θ [deg]"
    return forces.theta, f"input displacement s [{units or 'length'}]"


def effort(scene: Scene, forces: Forces) -> Figure:
    """The input effort (torque or force) over the input, virtual work's beside
    Newton-Euler's (they agree to rounding), NaN points left as gaps."""
    fig = Figure(figsize=(8.0, 4.5), layout="constrained")
    ax = fig.subplots()
    x, label = _x(forces, forces.units["length"])
    ax.plot(x, forces.input, "-", lw=2.0, label="Newton-Euler")
    ax.plot(x, forces.input_virtual_work, "--", lw=1.0, color="k", label="virtual work")
    ax.axhline(0.0, color="0.5", lw=0.8)
    what = "input torque" if forces.input_kind == "angle" else "input force"
    ax.set_xlabel(label)
    ax.set_ylabel(f"{what} [{forces.effort_unit}]")
    ax.set_title(f"{clean(scene.name, 'scene')}: {what} ({forces.kind})")
    ax.grid(True, alpha=0.25)
    ax.legend(fontsize="small")
    return fig


def reactions(scene: Scene, forces: Forces) -> Figure:
    """The magnitude of every pin reaction over the input."""
    fig = Figure(figsize=(8.0, 4.5), layout="constrained")
    ax = fig.subplots()
    x, label = _x(forces, forces.units["length"])
    for (joint, link), m in forces.reaction_magnitudes().items():
        ax.plot(x, m, lw=1.5, label=f"{clean(joint, '?')} on {clean(link, '?')}")
    ax.set_xlabel(label)
    ax.set_ylabel(f"pin force [{forces.units['force'] or 'force'}]")
    ax.set_title(f"{clean(scene.name, 'scene')}: pin reactions ({forces.kind})")
    ax.grid(True, alpha=0.25)
    ax.legend(fontsize="small", loc="upper left", bbox_to_anchor=(1.01, 1.0))
    return fig


def polar(scene: Scene, forces: Forces, key: tuple[str, str]) -> Figure:
    """The force of the pin ``key`` (joint, link) as a polar curve: its direction and
    magnitude over the input."""
    f = forces.reactions[key]
    fig = Figure(figsize=(5.5, 5.5), layout="constrained")
    ax = fig.add_subplot(projection="polar")
    ax.plot(np.arctan2(f[:, 1], f[:, 0]), np.hypot(f[:, 0], f[:, 1]), lw=1.5)
    ax.set_title(f"force on {clean(key[1], '?')} at {clean(key[0], '?')} "
                 f"[{forces.units['force'] or 'force'}]")  # fmt: skip
    return fig


def arrows(scene: Scene, sweep: SceneSweep, forces: Forces, index: int) -> Figure:
    """The linkage at the sweep's point ``index`` with each pin's force on its link as an
    arrow at the joint (lengths scaled so the largest is a fifth of the drawing)."""
    fig = Figure(figsize=(7.5, 6.0), layout="constrained")
    ax = fig.subplots()
    st = draw.Structure.of(scene)
    xy = {n: v[index] for n, v in sweep.points.items()}
    draw.ground(ax, st, scene.points, ground_size(scene))
    draw.pose(ax, st, xy, fill_alpha=0.15)
    span = float(np.ptp(np.array(list(scene.points.values())), axis=0).max() or 1.0)
    items = [(k, v[index]) for k, v in forces.reactions.items()]
    big = max((float(np.hypot(*f)) for _, f in items if np.isfinite(f).all()), default=0.0)
    cmap = colormaps["tab10"]
    for i, ((joint, link), f) in enumerate(items):
        if not np.isfinite(f).all() or big == 0.0:
            continue
        d = f / big * span / 5
        p = xy[joint]
        ax.annotate("", xy=(p[0] + d[0], p[1] + d[1]), xytext=(p[0], p[1]),
                    arrowprops={"arrowstyle": "->", "color": cmap(i % 10), "lw": 1.8})  # fmt: skip
        ax.plot([], [], color=cmap(i % 10),
                label=f"{clean(joint, '?')} on {clean(link, '?')}: {np.hypot(*f):.4g}")  # fmt: skip
    draw.frame(ax, sweep.coords[index : index + 1])
    ax.set_aspect("equal")
    t = forces.theta[index]
    at = f"θ = {np.degrees(t):.1f}°" if forces.input_kind == "angle" else f"s = {t:.4g}"
    ax.set_title(f"{clean(scene.name, 'scene')}: pin forces at {at} "
                 f"[{forces.units['force'] or 'force'}]")  # fmt: skip
    ax.legend(fontsize="small", loc="upper left", bbox_to_anchor=(1.01, 1.0))
    return fig
