"""Figures of scene results: the linkage drawn at several input angles with its tracer
paths, the conditioning along a sweep, tracer coordinates and velocities, and the motion
as an animation. Each function takes a Scene and its SceneSweep and returns a matplotlib
Figure (object API, no pyplot) or FuncAnimation."""

from __future__ import annotations

import math

import numpy as np
from matplotlib import colormaps
from matplotlib.animation import FuncAnimation
from matplotlib.axes import Axes
from matplotlib.figure import Figure
from matplotlib.patches import Polygon

from .._types import Status
from ._model import Scene
from ._results import SceneSweep

__all__ = [
    "animation",
    "circuits",
    "conditioning",
    "draw_pose",
    "linkage",
    "output_angle",
    "tracer_names",
    "tracers",
]


def tracer_names(scene: Scene, sweep: SceneSweep) -> list[str]:
    """Reported points on one link only (tracers), else the requested points."""
    joints = scene.joints
    t = [p for p in sweep.points if p not in joints]
    out = list(scene.outputs or [])
    return [p for p in dict.fromkeys(out + t) if p in sweep.points]


def _unwrap_deg(theta: np.ndarray) -> np.ndarray:
    return np.degrees(np.asarray(theta, dtype=np.float64))


def draw_pose(ax: Axes, scene: Scene, xy: dict[str, np.ndarray], *, alpha: float = 1.0) -> list:
    """Draws one pose: links as bars (binary) or filled polygons (ternary and up), the ground
    link's points as pivots, joints as circles. ``xy``: point -> (2,). Returns the artists."""
    artists: list = []
    cmap = colormaps["tab10"]
    ground = set(scene.links[scene.ground])
    for k, (name, pts) in enumerate(scene.links.items()):
        if name == scene.ground or not all(p in xy for p in pts):
            continue
        c = np.array([xy[p] for p in pts])
        if not np.isfinite(c).all():
            continue
        color = cmap(k % 10)
        if len(pts) > 2:
            poly = Polygon(c, closed=True, fc=color, ec=color, alpha=0.3 * alpha, zorder=2)
            ax.add_patch(poly)
            artists.append(poly)
        outline = np.vstack([c, c[:1]]) if len(pts) > 2 else c
        (ln,) = ax.plot(
            outline[:, 0], outline[:, 1], "-", color=color, lw=2.5, alpha=alpha, zorder=3
        )
        artists.append(ln)
    joints = [p for p in xy if p in scene.joints and np.isfinite(xy[p]).all()]
    if joints:
        j = np.array([xy[p] for p in joints])
        artists.append(ax.plot(j[:, 0], j[:, 1], "o", mfc="white", mec="k", ms=5,
                               alpha=alpha, zorder=4)[0])  # fmt: skip
    piv = [xy[p] for p in ground if p in xy]
    if piv:
        g = np.array(piv)
        artists.append(ax.plot(g[:, 0], g[:, 1], "^", color="k", ms=9, zorder=5)[0])
    return artists


def _pose(sweep: SceneSweep, i: int) -> dict[str, np.ndarray]:
    return {n: v[i] for n, v in sweep.points.items()}


def _limits(ax: Axes, sweep: SceneSweep, pad: float = 0.08) -> None:
    c = sweep.coords.reshape(-1, 2)
    c = c[np.isfinite(c).all(axis=1)]
    if not len(c):
        return
    lo, hi = c.min(axis=0), c.max(axis=0)
    span = max(hi - lo) or 1.0
    mid = 0.5 * (lo + hi)
    half = 0.5 * span * (1 + 2 * pad)
    ax.set_xlim(mid[0] - half, mid[0] + half)
    ax.set_ylim(mid[1] - half, mid[1] + half)
    ax.set_aspect("equal")


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
    if len(ok):
        idx = ok[np.linspace(0, len(ok) - 1, min(poses, len(ok))).round().astype(int)]
        for k, i in enumerate(idx):
            draw_pose(ax, scene, _pose(sweep, i), alpha=0.25 + 0.75 * (k + 1) / len(idx))
    _limits(ax, sweep)
    ax.grid(True, alpha=0.3)
    ax.set_xlabel(f"x [{scene.units or 'length'}]")
    ax.set_ylabel(f"y [{scene.units or 'length'}]")
    ax.set_title(f"{_title(scene)}: {len(ok)} of {len(sweep)} input angles solved")
    if ax.get_legend_handles_labels()[0]:
        ax.legend(loc="best", fontsize="small")
    return fig


def conditioning(scene: Scene, sweep: SceneSweep) -> Figure:
    """Signed conditioning of each plan step and of the whole solve along the sweep; its
    size is the distance from a dead point, its sign the branch followed."""
    fig = Figure(figsize=(8.0, 4.5), layout="constrained")
    ax = fig.subplots()
    t = _unwrap_deg(sweep.theta)
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
    return fig


def tracers(scene: Scene, sweep: SceneSweep) -> Figure:
    """x and y of each tracer point against the input angle, and its speed when the sweep
    has velocities."""
    names = tracer_names(scene, sweep)
    has_v = sweep.velocities is not None
    fig = Figure(figsize=(8.0, 7.0 if has_v else 4.5), layout="constrained")
    axs = fig.subplots(2 if has_v else 1, 1, sharex=True, squeeze=False)[:, 0]
    t = _unwrap_deg(sweep.theta)
    unit = scene.units or "length"
    for n in names:
        axs[0].plot(t, sweep.points[n][:, 0], label=f"x of {n}")
        axs[0].plot(t, sweep.points[n][:, 1], "--", label=f"y of {n}")
        if has_v:
            assert sweep.velocities is not None
            v = sweep.velocities[n]
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
    return fig


def animation(
    scene: Scene, sweep: SceneSweep, *, frames: int = 72, fps: float = 12, dpi: float = 80
) -> FuncAnimation:
    """The scene moving through the solved angles of the sweep, tracer paths drawn."""
    if frames < 1:
        raise ValueError(f"frames must be >= 1, got {frames}")
    ok = np.flatnonzero(sweep.success)
    if not len(ok):
        raise ValueError("the sweep solved no input angle: nothing to animate")
    idx = ok[np.unique(np.linspace(0, len(ok) - 1, min(frames, len(ok))).round().astype(int))]
    fig = Figure(figsize=(6.0, 5.2), dpi=dpi, layout="constrained")
    ax = fig.subplots()
    for p in tracer_names(scene, sweep):
        ax.plot(*sweep.points[p].T, "-", color="0.75", lw=1.2, zorder=1)
    _limits(ax, sweep)
    ax.grid(True, alpha=0.3)
    ax.set_title(_title(scene), fontsize="medium")
    label = ax.text(0.02, 0.97, "", transform=ax.transAxes, va="top", family="monospace")
    drawn: list = []

    def draw(i: int):
        for a in drawn:
            a.remove()
        drawn.clear()
        drawn.extend(draw_pose(ax, scene, _pose(sweep, i)))
        st = Status(int(sweep.status[i]))
        extra = "" if st == Status.CONVERGED else "  " + st.name.lower()
        label.set_text(f"θ = {math.degrees(sweep.theta[i]):6.1f}°{extra}")
        return [*drawn, label]

    return FuncAnimation(fig, draw, frames=idx.tolist(), interval=1000.0 / fps, blit=False)


def output_angle(scene: Scene, points: dict[str, np.ndarray]) -> tuple[str, np.ndarray]:
    """The output link's angle (the scene's ``output``, else the first link after the
    input that is not ground) from positions: (its name, angles in radians, unwrapped)."""
    if scene.output is not None:
        link, pivot = scene.output
    else:
        link = next(k for k in scene.links if k not in (scene.ground, scene.input[0]))
        pivot = scene.links[link][0]
    tip = next(p for p in scene.links[link] if p != pivot)
    d = np.asarray(points[tip]) - np.asarray(points[pivot])
    return link, np.unwrap(np.arctan2(d[..., 1], d[..., 0]))


def circuits(scene: Scene, found: list, theta: float) -> Figure:
    """Input angle against the output angle along every circuit (turning points marked),
    and the linkage drawn in each assembly at ``theta``."""
    assemblies = [a for c in found for a in c.assemblies]
    ncol = max(1, min(4, len(assemblies)))
    nrow = 1 + math.ceil(len(assemblies) / ncol) if assemblies else 1
    fig = Figure(figsize=(3.2 * ncol + 1.5, 4.0 + 3.0 * (nrow - 1)), layout="constrained")
    grid = fig.add_gridspec(nrow, ncol, height_ratios=[1.4] + [1.0] * (nrow - 1))
    ax = fig.add_subplot(grid[0, :])
    cmap = colormaps["tab10"]
    name = "output"
    for k, c in enumerate(found):
        tr = c.trace
        name, out = output_angle(scene, tr.points)
        kind = "full turn" if c.full_turn else f"{len(c.turning_points)} turning points"
        ax.plot(np.degrees(tr.theta), np.degrees(out), "-", color=cmap(k % 10), lw=1.5,
                label=f"circuit {k + 1}: {len(c.assemblies)} assemblies, {kind}")  # fmt: skip
        if len(tr.turning_points):
            i = [int(np.argmin(np.abs(tr.theta - tp))) for tp in tr.turning_points]
            ax.plot(np.degrees(tr.theta[i]), np.degrees(out[i]), "o", color=cmap(k % 10), ms=6)
    ax.axvline(math.degrees(theta), color="0.4", lw=0.8, ls="--")
    ax.set_xlabel("input angle θ [deg] (continuous along each circuit)")
    ax.set_ylabel(f"angle of {name} [deg]")
    ax.set_title(f"{_title(scene)}: circuits (dots: turning points)")
    ax.grid(True, alpha=0.3)
    if found:
        ax.legend(loc="best", fontsize="small")
    circuit_of = {id(a): k for k, c in enumerate(found) for a in c.assemblies}
    for j, a in enumerate(assemblies):
        sub = fig.add_subplot(grid[1 + j // ncol, j % ncol])
        pose = {n: np.asarray(v) for n, v in a.items()}
        draw_pose(sub, scene, pose)
        c = np.array(list(pose.values()))
        lo, hi = c.min(axis=0), c.max(axis=0)
        half = 0.6 * max(hi - lo)
        mid = 0.5 * (lo + hi)
        sub.set_xlim(mid[0] - half, mid[0] + half)
        sub.set_ylim(mid[1] - half, mid[1] + half)
        sub.set_aspect("equal")
        sub.set_xticks([])
        sub.set_yticks([])
        sub.set_title(
            f"circuit {circuit_of[id(a)] + 1}, {a.label}, det {a.det:+.2g}", fontsize="small"
        )
    return fig
