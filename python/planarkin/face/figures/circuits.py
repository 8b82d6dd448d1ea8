"""The circuits figure (``planarkin circuits``): the input angle against the output angle
along every circuit of a scene, turning points marked, and the linkage drawn in each of
its assemblies at one input angle."""

from __future__ import annotations

import math

import numpy as np
from matplotlib import colormaps
from matplotlib.figure import Figure

from ...scene import Circuit, Scene
from .. import draw
from .scene import ground_size

__all__ = ["circuits", "output_angle"]


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


def circuits(scene: Scene, found: list[Circuit], theta: float) -> Figure:
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
    ax.set_title(f"{scene.name or 'scene'}: circuits (dots: turning points)")
    ax.grid(True, alpha=0.3)
    if found:
        ax.legend(loc="best", fontsize="small")
    circuit_of = {id(a): k for k, c in enumerate(found) for a in c.assemblies}
    st = draw.Structure.of(scene)
    size = ground_size(scene)
    for j, a in enumerate(assemblies):
        sub = fig.add_subplot(grid[1 + j // ncol, j % ncol])
        pose = {n: np.asarray(v) for n, v in a.items()}
        draw.pose(sub, st, pose)
        draw.ground(sub, st, pose, size)
        draw.frame(sub, list(pose.values()))
        sub.set_xticks([])
        sub.set_yticks([])
        sub.set_title(
            f"circuit {circuit_of[id(a)] + 1}, {a.label}, det {a.det:+.2g}", fontsize="small"
        )
    return fig
