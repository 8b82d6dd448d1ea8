"""Figures of scene results: the linkage drawn at several input angles over its tracer
paths, the conditioning along a sweep, tracer coordinates and speeds. Each function takes
a Scene and its SceneSweep and returns a matplotlib Figure (object API, no pyplot)."""

from __future__ import annotations

import math

import numpy as np
from matplotlib import colormaps
from matplotlib.figure import Figure

from ..._angles import rpm
from ...scene import Scene, SceneSweep
from .. import draw
from ..degrees import AXIS_TICKS, on_wrapped_axis, wrap_deg, wrapped
from ..fonts import clean
from ..titles import fit_titles

__all__ = ["conditioning", "ground_size", "linkage", "rpm", "tracer_names", "tracers"]


def tracer_names(scene: Scene, sweep: SceneSweep) -> list[str]:
    """Reported points on one link only (tracers), else the requested points; never a
    ground point (it does not move) or a slot's point (a joint)."""
    joints = set(scene.joints) | {pt for pt, _, _ in scene.slots.values()}
    fixed = set(scene.links[scene.ground])
    t = [p for p in sweep.points if p not in joints and p not in fixed]
    out = list(scene.outputs or [])
    return [p for p in dict.fromkeys(out + t) if p in sweep.points and p not in fixed]


def _input_label(scene: Scene, value: float) -> str:
    """θ in degrees for a crank, s in the scene's units for a linear input."""
    if scene.input_kind == "angle":
        return f"θ = {wrapped(value):.1f}°"
    return f"s = {value:.4g} {scene.units or ''}".rstrip()


def ground_size(scene: Scene) -> float:
    """The size of the ground triangles: 3% of the drawing's extent."""
    xy = np.array(list(scene.points.values()), dtype=np.float64)
    return 0.03 * float(np.ptp(xy, axis=0).max() or 1.0)


def _title(scene: Scene) -> str:
    return clean(scene.name, "scene")


def _theta_label(sweep: SceneSweep) -> str:
    return "input angle θ [deg], in (-180, 180]"


def _poses(sweep: SceneSweep, poses: int) -> np.ndarray:
    """Indices of ``poses`` solved input angles, in order of the angle on the (-180, 180]
    axis: evenly spread round a full turn, or from end to end of a motion that stops (its
    last solved angles on either side)."""
    ok = np.flatnonzero(sweep.success)
    t = sweep.theta
    full = sweep.success.all() and len(t) > 1
    if full and math.isclose(abs(t[-1] - t[0]), math.tau, rel_tol=0, abs_tol=1e-9):
        ok = ok[:-1]  # the last pose is the first again
    if not len(ok):
        return ok
    ok = ok[np.argsort(wrap_deg(t[ok]), kind="stable")]
    k = min(poses, len(ok))
    at = np.linspace(0, len(ok), k, endpoint=False) if full else np.linspace(0, len(ok) - 1, k)
    return ok[np.unique(at.round().astype(int))]


def linkage(scene: Scene, sweep: SceneSweep, *, poses: int = 4) -> Figure:
    """The linkage as an engineer draws it, twice: on the left the drawn pose alone,
    every point named, over the paths of its tracer points; on the right ``poses`` solved
    poses overlaid, each in its own colour and labelled with its input angle. Ground is
    hatched at its pivots, links are their outlines (the convex hull of a plate's points,
    never crossing itself), joints circles, slots and sliders drawn where the scene has
    them."""
    fig = Figure(figsize=(12.0, 5.6), layout="constrained")
    one, many = fig.subplots(1, 2)
    st = draw.Structure.of(scene)
    size = ground_size(scene)
    names = tracer_names(scene, sweep)
    for ax in (one, many):
        for p in names:
            ax.plot(*sweep.points[p].T, "-", color="0.6", lw=1.2, zorder=1,
                    label=f"path of {clean(p, '?')}" if ax is many else None)  # fmt: skip
        draw.ground(ax, st, scene.points, size)
        draw.frame(ax, sweep.coords, list(scene.points.values()))
        ax.grid(True, alpha=0.25)
        ax.set_xlabel(f"x [{scene.units or 'length'}]")
    one.set_ylabel(f"y [{scene.units or 'length'}]")
    draw.pose(one, st, scene.points)
    one.set_title(f"as drawn, {_input_label(scene, scene.input_angle)}")
    idx = _poses(sweep, poses)
    cmap = colormaps["viridis"]
    for k, i in enumerate(idx):
        xy = {n: v[i] for n, v in sweep.points.items()}
        c = cmap(0.85 * k / max(1, len(idx) - 1))
        draw.pose(many, st, xy, color=c, lw=2.0, ms=4, fill_alpha=0.15,
                  label=_input_label(scene, sweep.theta[i]))  # fmt: skip
    solved = int(sweep.success.sum())
    what = "input angles" if scene.input_kind == "angle" else "input displacements"
    many.set_title(f"{len(idx)} poses ({solved} of {len(sweep)} {what} solved)")
    if many.get_legend_handles_labels()[0]:
        many.legend(loc="upper left", bbox_to_anchor=(1.01, 1.0), fontsize="small",
                    borderaxespad=0.0)  # fmt: skip
    fig.suptitle(_title(scene))
    fit_titles(fig)
    draw.labels(one, scene.points, list(scene.points))
    return fig


def conditioning(scene: Scene, sweep: SceneSweep) -> Figure:
    """Signed conditioning of each plan step and of the whole solve along the sweep; its
    size is the distance from a dead point, its sign the branch followed."""
    fig = Figure(figsize=(8.0, 4.5), layout="constrained")
    ax = fig.subplots()
    t, det, steps, bad = on_wrapped_axis(
        sweep.theta,
        sweep.det,
        sweep.step_det if sweep.step_det is not None else np.zeros((len(sweep), 0)),
        np.where(sweep.success, np.nan, 0.0),
    )
    if sweep.plan is not None and sweep.step_det is not None:
        for s, step in enumerate(sweep.plan):
            pts = ", ".join(clean(p, "?") for p in step.points[:2])
            ax.plot(t, steps[:, s], lw=1.2, label=f"step {s + 1} ({step.kind}: {pts})")
    ax.plot(t, det, "k-", lw=2, label="whole solve (product)")
    ax.axhline(0, color="0.5", lw=0.8)
    if np.isfinite(bad).any():
        ax.plot(t, bad, "x", color="tab:red", label="not solved")
    ax.set_xticks(AXIS_TICKS)
    ax.set_xlabel(_theta_label(sweep))
    ax.set_ylabel("signed conditioning [-]")
    ax.set_title(f"{_title(scene)}: conditioning along the sweep")
    ax.grid(True, alpha=0.3)
    ax.legend(loc="best", fontsize="small")
    return fit_titles(fig)


def tracers(scene: Scene, sweep: SceneSweep) -> Figure | None:
    """x and y of each tracer point against the input angle, its speed when the sweep has
    velocities and the size of its acceleration when it has accelerations; None when the
    scene has no tracer point (no blank figure)."""
    names = tracer_names(scene, sweep)
    if not names:
        return None
    unit = scene.units or "length"
    rates = [
        (d, what, f"{what} [{unit}/{per}]")
        for d, what, per in (
            (sweep.velocities, "speed", "s"),
            (sweep.accelerations, "acceleration", "s^2"),
        )
        if d is not None
    ]
    fig = Figure(figsize=(8.0, 4.5 + 2.8 * len(rates)), layout="constrained")
    axs = fig.subplots(1 + len(rates), 1, sharex=True, squeeze=False)[:, 0]
    for n in names:
        label = clean(n, "?")
        t, xy = on_wrapped_axis(sweep.theta, sweep.points[n])
        axs[0].plot(t, xy[:, 0], label=f"x of {label}")
        axs[0].plot(t, xy[:, 1], "--", label=f"y of {label}")
        for ax, (d, what, _) in zip(axs[1:], rates, strict=True):
            t, size = on_wrapped_axis(sweep.theta, np.hypot(d[n][:, 0], d[n][:, 1]))
            ax.plot(t, size, label=f"{what} of {label}")
    axs[0].set_ylabel(f"position [{unit}]")
    axs[0].set_title(f"{_title(scene)}: tracer points")
    for ax, (_, _, ylabel) in zip(axs[1:], rates, strict=True):
        ax.set_ylabel(ylabel)
    if rates and sweep.omega is not None:
        axs[1].set_title(f"at ω = {sweep.omega:.4g} rad/s ({rpm(sweep.omega):.4g} rpm), "
                         "constant", fontsize="medium")  # fmt: skip
    axs[-1].set_xticks(AXIS_TICKS)
    axs[-1].set_xlabel(_theta_label(sweep))
    for ax in axs:
        ax.grid(True, alpha=0.3)
        if ax.get_legend_handles_labels()[0]:
            ax.legend(loc="best", fontsize="small")
    return fit_titles(fig)
