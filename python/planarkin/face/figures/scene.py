"""Figures of scene results: the linkage drawn at several input angles over its tracer
paths, the conditioning along a sweep, tracer coordinates and speeds. Each function takes
a Scene and its SceneSweep and returns a matplotlib Figure (object API, no pyplot)."""

from __future__ import annotations

import math

import numpy as np
from matplotlib import colormaps
from matplotlib.axes import Axes
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
    ground point (it does not move), a slot's point (a joint), a point that only gives a
    line its direction, or a point of a cylinder's barrel or rod (drawn as the cylinder)."""
    tracers = set(draw.Structure.of(scene).tracers())
    fixed = set(scene.links[scene.ground])
    t = [p for p in sweep.points if p in tracers]
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


def _linear(sweep: SceneSweep) -> bool:
    return sweep.input_kind == "displacement"


def _theta_label(scene: Scene, sweep: SceneSweep) -> str:
    """The input axis' label: an angle in degrees on (-180, 180], or a linear input's
    displacement in the scene's length unit (never wrapped)."""
    if not _linear(sweep):
        return "input angle θ [deg], in (-180, 180]"
    kind, name = scene.input
    return f"input displacement s [{scene.units or 'length'}] of {kind} {clean(name, '?')!r}"


def _on_axis(sweep: SceneSweep, *ys: object) -> tuple[np.ndarray, ...]:
    """The sweep's input values and ``ys`` as the input axis shows them: wrapped angles in
    degrees (:func:`on_wrapped_axis`), or displacements as they are, in input order."""
    if not _linear(sweep):
        return on_wrapped_axis(sweep.theta, *ys)
    t = np.asarray(sweep.theta, dtype=np.float64)
    order = np.argsort(t, kind="stable")
    return (t[order], *(np.asarray(y, dtype=np.float64)[order] for y in ys))


def _input_axis(ax: Axes, scene: Scene, sweep: SceneSweep) -> None:
    ax.set_xlabel(_theta_label(scene, sweep))
    if not _linear(sweep):
        ax.set_xticks(AXIS_TICKS)


def _rate_words(scene: Scene, sweep: SceneSweep) -> str:
    """The constant input rate the velocities are at: ω (and rpm), or a linear speed."""
    w = sweep.omega
    assert w is not None
    if _linear(sweep):
        return f"at v = {w:.4g} {scene.units or 'length'}/s (input speed), constant"
    return f"at ω = {w:.4g} rad/s ({rpm(w):.4g} rpm), constant"


#: Rates beyond this many times the spread of the central 98% of them (a few rows at a
#: dead point, where they are unbounded) are left off the axis, which says so.
RATE_CLIP = 20.0


def _fit_rates(ax: Axes, values: list[np.ndarray]) -> None:
    """Fits a rate panel's y axis to the bulk of ``values`` when a few rows near a dead
    point (rates unbounded there) would flatten every other row to the axis, and says
    so on the panel."""
    if not values:
        return
    v = np.concatenate([np.asarray(x, dtype=np.float64).ravel() for x in values])
    v = v[np.isfinite(v)]
    if len(v) < 10:
        return
    lo, hi = np.percentile(v, [1.0, 99.0])
    spread = float(hi - lo) or float(abs(hi)) or 1.0
    if float(v.max() - v.min()) <= RATE_CLIP * spread:
        return
    ax.set_ylim(min(0.0, lo - 0.15 * spread), hi + 0.15 * spread)
    ax.text(0.99, 0.02, "larger values near the dead points are off the axis", ha="right",
            va="bottom", transform=ax.transAxes, fontsize="x-small", color="0.35")  # fmt: skip


def _poses(sweep: SceneSweep, poses: int) -> np.ndarray:
    """Indices of ``poses`` solved input values, in order on the input axis: evenly
    spread round a full turn, or from end to end of a motion that stops (its last solved
    angles on either side); a linear input's from one end of its solved stroke to the
    other, in increasing displacement."""
    ok = np.flatnonzero(sweep.success)
    t = sweep.theta
    if _linear(sweep):
        if not len(ok):
            return ok
        ok = ok[np.argsort(t[ok], kind="stable")]
        at = np.linspace(0, len(ok) - 1, min(poses, len(ok)))
        return ok[np.unique(at.round().astype(int))]
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
    t, det, steps, bad = _on_axis(
        sweep,
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
    _input_axis(ax, scene, sweep)
    ax.set_ylabel("signed conditioning [-]")
    ax.set_title(f"{_title(scene)}: conditioning along the sweep")
    ax.grid(True, alpha=0.3)
    ax.legend(loc="best", fontsize="small")
    return fit_titles(fig)


def tracers(scene: Scene, sweep: SceneSweep) -> Figure | None:
    """x and y of each tracer point against the input (angle or displacement), its speed
    when the sweep has velocities and the size of its acceleration when it has
    accelerations; None when the scene has no tracer point (no blank figure)."""
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
        t, xy = _on_axis(sweep, sweep.points[n])
        axs[0].plot(t, xy[:, 0], label=f"x of {label}")
        axs[0].plot(t, xy[:, 1], "--", label=f"y of {label}")
        for ax, (d, what, _) in zip(axs[1:], rates, strict=True):
            t, size = _on_axis(sweep, np.hypot(d[n][:, 0], d[n][:, 1]))
            ax.plot(t, size, label=f"{what} of {label}")
    axs[0].set_ylabel(f"position [{unit}]")
    axs[0].set_title(f"{_title(scene)}: tracer points")
    for ax, (d, _, ylabel) in zip(axs[1:], rates, strict=True):
        ax.set_ylabel(ylabel)
        _fit_rates(ax, [np.hypot(d[n][:, 0], d[n][:, 1]) for n in names])
    if rates and sweep.omega is not None:
        axs[1].set_title(_rate_words(scene, sweep), fontsize="medium")
    _input_axis(axs[-1], scene, sweep)
    for ax in axs:
        ax.grid(True, alpha=0.3)
        if ax.get_legend_handles_labels()[0]:
            ax.legend(loc="best", fontsize="small")
    return fit_titles(fig)
