"""The circuits figure (``planarkin circuits``): one small panel per circuit (the input
against the declared output along it, an angle or a slider's displacement; the other
circuits faint behind, turning points marked), and the linkage drawn in each of its
assemblies at one input angle; at an input the linkage cannot reach, the inputs it can
reach instead."""

from __future__ import annotations

import math

import numpy as np
from matplotlib import colormaps
from matplotlib.figure import Figure

from ...scene import Circuit, Scene
from ...scene import output as declared_output
from .. import draw
from ..degrees import on_wrapped_axis, wrapped
from ..fonts import clean
from ..titles import fit_titles
from .scene import ground_size

__all__ = ["circuits", "output_angle", "output_curve", "shown_turn"]

#: Panels per row.
COLUMNS = 3


def output_angle(scene: Scene, points: dict[str, np.ndarray]) -> tuple[str, np.ndarray]:
    """The output link's angle (the scene's angle ``output``, else the last link listed
    that is neither ground nor the input: the far end of the chain, where circuits differ
    most) from positions: (its name, angles in radians, unwrapped)."""
    out = scene.output
    if out is not None and out[0] in scene.links:
        link, pivot = out
    else:
        drive = scene.input[0] if scene.input_kind == "angle" else None
        link = [k for k in scene.links if k not in (scene.ground, drive)][-1]
        pivot = scene.links[link][0]
    tip = next(p for p in scene.links[link] if p != pivot)
    d = np.asarray(points[tip]) - np.asarray(points[pivot])
    return link, np.unwrap(np.arctan2(d[..., 1], d[..., 0]))


def output_curve(scene: Scene, points: dict[str, np.ndarray]) -> tuple[str, np.ndarray]:
    """What a circuit panel plots against the input: the scene's declared output (an
    angle in degrees, continuous, or a slot's or prismatic pair's displacement from the
    drawn pose in the scene's unit), else the far link's angle (:func:`output_angle`).
    Returns (the axis label, the values)."""
    dec = declared_output.declared(scene)
    if dec is not None and all(p in points for p in dec.points()):
        y = declared_output.coordinate(dec, points)
        if dec.kind == "angle":
            return f"angle of {clean(dec.name, '?')} [deg]", np.degrees(y)
        unit = scene.units or "length"
        kind = next(iter(scene.output or ("output",)))
        return f"{kind} {clean(dec.name, '?')} s [{unit}]", y
    link, out = output_angle(scene, points)
    return f"angle of {clean(link, '?')} [deg]", np.degrees(out)


def shown_turn(theta: np.ndarray, at: float) -> np.ndarray:
    """A circuit's continuous input angles (radians) shifted by whole turns so that the
    turn holding ``at`` is the one in (-180, 180] deg: degrees, still continuous."""
    shift = math.tau * round((at - math.radians(wrapped(at))) / math.tau)
    return np.degrees(np.asarray(theta) - shift)


def _span(ranges: list[tuple[float, float]]) -> str:
    return "; ".join(f"{a:.1f} to {b:.1f}" for a, b in ranges)


def circuits(
    scene: Scene,
    found: list[Circuit],
    theta: float,
    *,
    reachable: list[tuple[float, float]] | None = None,
) -> Figure:
    """One panel per circuit and the linkage in each assembly at ``theta``; with no
    circuit there (the input cannot reach ``theta``), one panel saying so and naming the
    ``reachable`` input ranges (degrees) instead of an empty plot."""
    name = clean(scene.name, "scene")
    linear = scene.input_kind == "displacement"
    unit = scene.units or "length"
    at = theta if linear else wrapped(theta)
    shown = f"s = {at:.4g} {unit}" if linear else f"θ = {at:.1f}°"
    if not found:
        fig = Figure(figsize=(7.0, 3.0), layout="constrained")
        ax = fig.subplots()
        ax.set_axis_off()
        where = _span(reachable) if reachable else "none found"
        reach = f"s in [{unit}]" if linear else "θ in [deg]"
        text = f"No assembly at {shown}.\nThe input reaches {reach}: {where}."
        ax.text(0.5, 0.5, text, ha="center", va="center", wrap=True, transform=ax.transAxes)
        ax.set_title(f"{name}: no assembly at {shown}")
        return fit_titles(fig)
    assemblies = [a for c in found for a in c.assemblies]
    ncol = max(1, min(COLUMNS, max(len(found), len(assemblies))))
    crow = math.ceil(len(found) / ncol)
    arow = math.ceil(len(assemblies) / ncol)
    fig = Figure(figsize=(3.6 * ncol + 0.6, 3.1 * (crow + arow) + 0.6), layout="constrained")
    grid = fig.add_gridspec(crow + arow, ncol)
    cmap = colormaps["tab10"]
    ylabel = "output"
    curves = []
    for c in found:
        ylabel, out = output_curve(scene, c.trace.points)
        if linear:  # displacements: no turns to wrap
            curves.append((np.asarray(c.trace.theta), out, c))
        elif c.full_turn and c.trace.closed:  # one curve over (-180, 180]
            x, y = on_wrapped_axis(c.trace.theta, out)
            curves.append((x, y, c))
        else:  # a continuous range, in the turn that holds theta
            curves.append((shown_turn(c.trace.theta, theta), out, c))
    first = None
    for k, (x, y, c) in enumerate(curves):
        ax = fig.add_subplot(grid[k // ncol, k % ncol], sharex=first, sharey=first)
        first = first or ax
        for j, (xo, yo, _) in enumerate(curves):
            if j != k:
                ax.plot(xo, yo, "-", color="0.85", lw=1.0, zorder=1)
        ax.plot(x, y, "-", color=cmap(k % 10), lw=1.8, zorder=2)
        if len(c.trace.turning_points):  # a rocking circuit: x is the trace's own order
            i = [int(np.argmin(np.abs(c.trace.theta - tp))) for tp in c.trace.turning_points]
            ax.plot(x[i], y[i], "o", color=cmap(k % 10), ms=5, zorder=3)
        ax.axvline(at, color="0.4", lw=0.8, ls="--")
        kind = "input turns fully" if c.full_turn else f"{len(c.turning_points)} turning points"
        ax.set_title(f"circuit {k + 1}: {kind}", fontsize="medium")
        ax.grid(True, alpha=0.3)
        if k % ncol == 0:
            ax.set_ylabel(ylabel)
        if linear:
            ax.set_xlabel(f"input s [{unit}] from the drawn pose")
        else:
            ax.set_xlabel("input θ [deg], continuous" if any(not c.full_turn for c in found)
                          else "input θ [deg], in (-180, 180]")  # fmt: skip
    circuit_of = {id(a): k for k, c in enumerate(found) for a in c.assemblies}
    st = draw.Structure.of(scene)
    size = ground_size(scene)
    for j, a in enumerate(assemblies):
        sub = fig.add_subplot(grid[crow + j // ncol, j % ncol])
        pose = {n: np.asarray(v) for n, v in a.items()}
        draw.pose(sub, st, pose)
        draw.ground(sub, st, pose, size)
        draw.frame(sub, list(pose.values()))
        sub.set_xticks([])
        sub.set_yticks([])
        k = circuit_of[id(a)]
        sub.set_title(f"circuit {k + 1}, assembly {a.label}", fontsize="small",
                      color=cmap(k % 10))  # fmt: skip
    fig.suptitle(
        f"{name}: {len(assemblies)} assembl{'y' if len(assemblies) == 1 else 'ies'} at "
        f"{shown} on {len(found)} circuit{'' if len(found) == 1 else 's'} "
        "(dots: turning points, where the input must reverse)"
    )
    return fit_titles(fig)
