"""The seed's figures of a synthesized function generator (``planarkin synthesize``): the
true and generated output error against the input, the conditioning along the range and
the linkage at several input angles, and accuracy against tolerance sensitivity of the
designs a search found."""

from __future__ import annotations

import math
from typing import Any

import numpy as np
from matplotlib.figure import Figure

from ...synthesis import SeedPlan
from ...synthesis.problem import DesignSpace, FunctionTarget, Problem
from ...synthesis.verify import output_rotation
from .. import draw
from .scene import ground_size

__all__ = ["conditioning", "error", "linkage", "tolerance"]


def error(problem: Problem, x: np.ndarray, dense: int = 1001) -> Figure:
    """True (scene solver) and generated (seed's closed form) output error against the
    input, degrees."""
    t = problem.target
    assert isinstance(t, FunctionTarget)
    sp = problem.space
    assert isinstance(sp, DesignSpace)
    sc = sp.scene(x)
    grid = np.linspace(t.dense_in[0], t.dense_in[-1], dense)
    want = t.function(grid) if t.function is not None else np.interp(grid, t.dense_in, t.dense_out)
    rot, _ = output_rotation(sc, grid)
    rot31, _ = output_rotation(sc, t.phi_in)
    g = SeedPlan(sp.template, sp.points_of(x)).generated(t.phi_in, t.phi_out)
    fig = Figure(figsize=(7, 4.2), layout="constrained")
    ax = fig.add_subplot()
    ax.plot(
        np.degrees(grid),
        np.degrees(rot - want),
        "C0-",
        lw=1.2,
        label="true (Newton-Raphson, scene solver)",
    )
    ax.plot(
        np.degrees(t.phi_in),
        np.degrees(rot31 - t.phi_out),
        "C0o",
        ms=3,
        label="true at the design points",
    )
    ax.plot(
        np.degrees(t.phi_in),
        np.degrees(g.theta - t.phi_out),
        "C3s--",
        ms=3,
        lw=0.8,
        label=f"generated (closed form, signs {g.signs})",
    )
    ax.axhline(0, color="0.6", lw=0.6)
    lim = 1.3 * max(float(np.max(np.abs(np.degrees(rot - want)))), 1e-9)
    gmax = float(np.max(np.abs(np.degrees(g.theta - t.phi_out))))
    if gmax > 20 * lim:
        ax.set_ylim(-lim, lim)
        ax.set_title(f"output error (generated error up to {gmax:.3g} deg, off the scale)")
    else:
        ax.set_title("output error")
    ax.set_xlabel("input rotation (deg)")
    ax.set_ylabel("output error (deg)")
    ax.legend(fontsize=8)
    ax.grid(alpha=0.3)
    return fig


def conditioning(problem: Problem, x: np.ndarray, dense: int = 1001) -> Figure:
    """The signed, scale-free conditioning (the Jacobian determinant's Hadamard ratio) of
    the true linkage along the range."""
    t = problem.target
    assert isinstance(t, FunctionTarget)
    sc = problem.space.scene(x)
    grid = np.linspace(t.dense_in[0], t.dense_in[-1], dense)
    _, sw = output_rotation(sc, grid)
    fig = Figure(figsize=(7, 3.6), layout="constrained")
    ax = fig.add_subplot()
    ax.plot(np.degrees(grid), sw.det, "C2-")
    ax.axhline(0, color="k", lw=0.8)
    ax.axhline(
        np.sign(sw.det[0]) * problem.det_margin,
        color="C3",
        lw=0.8,
        ls="--",
        label=f"margin {problem.det_margin:g}",
    )
    ax.set_xlabel("input rotation (deg)")
    ax.set_ylabel("conditioning (signed det)")
    ax.set_title("Jacobian determinant (scale-free) along the range: no sign change")
    ax.legend(fontsize=8)
    ax.grid(alpha=0.3)
    return fig


def linkage(problem: Problem, x: np.ndarray, angles_deg: Any = None) -> Figure:
    """The linkage drawn at several input rotations (default: both ends of the range, their
    midpoints and the drawn pose), with the compact box of the drawn pose dashed."""
    t = problem.target
    assert isinstance(t, FunctionTarget)
    sc = problem.space.scene(x)
    lo, hi = float(t.dense_in[0]), float(t.dense_in[-1])
    if angles_deg is None:
        angles = (
            np.array(sorted({lo, lo / 2, 0.0, hi / 2, hi}))
            if lo < 0 < hi
            else np.linspace(lo, hi, 5)
        )
    else:
        angles = np.radians(np.asarray(angles_deg, dtype=np.float64))
    sw = sc.sweep(sc.input_angle + angles, outputs="all", tol=1e-12)
    allxy = np.concatenate([sw.points[n] for n in sw.points])
    allxy = allxy[np.all(np.isfinite(allxy), axis=1)]
    pad = 0.05 * float(np.ptp(allxy, axis=0).max())
    (x0, y0), (x1, y1) = allxy.min(axis=0) - pad, allxy.max(axis=0) + pad
    sp = problem.space
    box = (float(np.min(sp.lower)), float(np.max(sp.upper)))
    fig = Figure(figsize=(3.2 * angles.size, 3.6), layout="constrained")
    st = draw.Structure.of(sc)
    for i, a in enumerate(angles):
        ax = fig.add_subplot(1, angles.size, i + 1)
        xy = {n: sw.points[n][i] for n in sw.points}
        draw.pose(ax, st, xy)
        draw.ground(ax, st, xy, ground_size(sc))
        if abs(a) < 1e-12:
            ax.plot(
                [box[0], box[1], box[1], box[0], box[0]],
                [box[0], box[0], box[1], box[1], box[0]],
                "k--",
                lw=0.7,
            )
            ax.set_title("input 0 deg (as drawn; design box dashed)", fontsize=9)
        else:
            ax.set_title(f"input {math.degrees(a):+.1f} deg", fontsize=9)
        ax.set_aspect("equal")
        ax.set_xlim(x0, x1)
        ax.set_ylim(y0, y1)
        ax.grid(alpha=0.2)
    return fig


def tolerance(
    runs: list[tuple[int, float, float]], shipped: dict[str, int], sigma: float
) -> Figure:
    """Accuracy against tolerance sensitivity of the verified designs of a search: each
    run's nominal true max error against its linearised 95th percentile at joint noise
    ``sigma``; ``shipped`` names the runs written (name -> start index)."""
    fig = Figure(figsize=(5.6, 4.2), layout="constrained")
    ax = fig.add_subplot(1, 1, 1)
    for i, nominal, p95 in runs:
        ax.loglog(nominal, p95, "o", color="0.6", ms=5)
        ax.annotate(str(i), (nominal, p95), fontsize=7, xytext=(3, 3), textcoords="offset points")
    for (name, i), c in zip(shipped.items(), ("C0", "C3"), strict=False):
        hit = [(n, p) for j, n, p in runs if j == i]
        if hit:
            ax.loglog(*hit[0], "o", color=c, ms=9, mfc="none", mew=2, label=f"{name} (start {i})")
    ax.set_xlabel("nominal true max error [deg]")
    ax.set_ylabel(f"95th percentile at joint noise {sigma:g} [deg]")
    ax.set_title("accuracy against tolerance sensitivity", fontsize=10)
    ax.grid(True, which="both", alpha=0.3)
    ax.legend(loc="best", fontsize=8)
    return fig
