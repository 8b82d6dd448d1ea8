"""Figures of scene results: the linkage drawn at several input angles over its tracer
paths, the conditioning along a sweep, tracer coordinates and speeds. Each function takes
a Scene and its SceneSweep and returns a matplotlib Figure (object API, no pyplot)."""

from __future__ import annotations

import numpy as np
from matplotlib.figure import Figure

from ...scene import Scene, SceneSweep
from .. import draw
from ..titles import fit_titles

__all__ = ["conditioning", "ground_size", "linkage", "tracer_names", "tracers"]


def tracer_names(scene: Scene, sweep: SceneSweep) -> list[str]:
    """Reported points on one link only (tracers), else the requested points."""
    joints = scene.joints
    t = [p for p in sweep.points if p not in joints]
    out = list(scene.outputs or [])
    return [p for p in dict.fromkeys(out + t) if p in sweep.points]


def ground_size(scene: Scene) -> float:
    """The size of the ground triangles: 3% of the drawing's extent."""
    xy = np.array(list(scene.points.values()), dtype=np.float64)
    return 0.03 * float(np.ptp(xy, axis=0).max() or 1.0)


def _title(scene: Scene) -> str:
    return scene.name or "scene"


def linkage(scene: Scene, sweep: SceneSweep, *, poses: int = 6) -> Figure:
    """The linkage drawn at ``poses`` input angles (evenly spaced among the solved ones)
    over the paths of its tracer points."""
    fig = Figure(figsize=(7.0, 6.0), layout="constrained")
    ax = fig.subplots()
    ok = np.flatnonzero(sweep.success)
    for p in tracer_names(scene, sweep):
        ax.plot(*sweep.points[p].T, "-", lw=1.5, label=f"path of {p}", zorder=1)
    st = draw.Structure.of(scene)
    if len(ok):
        idx = ok[np.linspace(0, len(ok) - 1, min(poses, len(ok))).round().astype(int)]
        for k, i in enumerate(idx):
            xy = {n: v[i] for n, v in sweep.points.items()}
            draw.pose(ax, st, xy, alpha=0.25 + 0.75 * (k + 1) / len(idx))
    draw.ground(ax, st, scene.points, ground_size(scene))
    draw.frame(ax, sweep.coords, list(scene.points.values()))
    ax.grid(True, alpha=0.3)
    ax.set_xlabel(f"x [{scene.units or 'length'}]")
    ax.set_ylabel(f"y [{scene.units or 'length'}]")
    ax.set_title(f"{_title(scene)}: {len(ok)} of {len(sweep)} input angles solved")
    if ax.get_legend_handles_labels()[0]:
        ax.legend(loc="best", fontsize="small")
    return fit_titles(fig)


def conditioning(scene: Scene, sweep: SceneSweep) -> Figure:
    """Signed conditioning of each plan step and of the whole solve along the sweep; its
    size is the distance from a dead point, its sign the branch followed."""
    fig = Figure(figsize=(8.0, 4.5), layout="constrained")
    ax = fig.subplots()
    t = np.degrees(sweep.theta)
    if sweep.plan is not None and sweep.step_det is not None:
        for s, step in enumerate(sweep.plan):
            ax.plot(
                t,
                sweep.step_det[:, s],
                lw=1.2,
                label=f"step {s + 1} ({step.kind}: {', '.join(step.points[:2])})",
            )
    ax.plot(t, sweep.det, "k-", lw=2, label="whole solve (product)")
    ax.axhline(0, color="0.5", lw=0.8)
    bad = ~sweep.success
    if bad.any():
        ax.plot(t[bad], np.zeros(bad.sum()), "x", color="tab:red", label="not solved")
    ax.set_xlabel("input angle θ [deg]")
    ax.set_ylabel("signed conditioning [-]")
    ax.set_title(f"{_title(scene)}: conditioning along the sweep")
    ax.grid(True, alpha=0.3)
    ax.legend(loc="best", fontsize="small")
    return fit_titles(fig)


def tracers(scene: Scene, sweep: SceneSweep) -> Figure:
    """x and y of each tracer point against the input angle, and its speed when the sweep
    has velocities."""
    names = tracer_names(scene, sweep)
    velocities = sweep.velocities
    has_v = velocities is not None
    fig = Figure(figsize=(8.0, 7.0 if has_v else 4.5), layout="constrained")
    axs = fig.subplots(2 if has_v else 1, 1, sharex=True, squeeze=False)[:, 0]
    t = np.degrees(sweep.theta)
    unit = scene.units or "length"
    for n in names:
        axs[0].plot(t, sweep.points[n][:, 0], label=f"x of {n}")
        axs[0].plot(t, sweep.points[n][:, 1], "--", label=f"y of {n}")
        if velocities is not None:
            v = velocities[n]
            axs[1].plot(t, np.hypot(v[:, 0], v[:, 1]), label=f"speed of {n}")
    axs[0].set_ylabel(f"position [{unit}]")
    axs[0].set_title(f"{_title(scene)}: tracer points")
    if has_v:
        axs[1].set_ylabel(f"speed [{unit}/s]")
    axs[-1].set_xlabel("input angle θ [deg]")
    for ax in axs:
        ax.grid(True, alpha=0.3)
        if ax.get_legend_handles_labels()[0]:
            ax.legend(loc="best", fontsize="small")
    return fit_titles(fig)
