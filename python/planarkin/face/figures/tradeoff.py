"""The Pareto plot of ``planarkin tradeoff``: time per point against max angle error,
log-log, one line per method and a label per tolerance (close ones share a label)."""

from __future__ import annotations

import math

from matplotlib.figure import Figure
from matplotlib.ticker import LogFormatter

from ...fourbar.tradeoff import METHODS, TradeoffResult

__all__ = ["figure", "save"]


def figure(result: TradeoffResult) -> Figure:
    """The Pareto plot as a matplotlib Figure (object API, no pyplot). Tolerances whose
    markers would print their labels on top of each other share one label
    ("1e-12..1e-15"); tick labels are plain numbers."""
    fig = Figure(figsize=(7.5, 5.0), layout="constrained")
    ax = fig.subplots()
    floor = 1e-17  # an error of exactly 0 has no place on a log axis
    labels = []
    for method, (label, _) in METHODS.items():
        rows = [r for r in result.rows if r.method == method]
        if not rows:
            continue
        x = [r.ns_per_point for r in rows]
        y = [max(r.err_max, floor) for r in rows]
        if method == "closed-form":
            ax.plot(x, y, "*", ms=14, label=label, color="k")
            continue
        (line,) = ax.plot(x, y, "o-", ms=4, label=label, alpha=0.8)
        for group in _close_runs(x, y):
            tols = [rows[i].tol for i in group]
            text = f"{tols[0]:.0e}" + (f"..{tols[-1]:.0e}" if len(tols) > 1 else "")
            i = group[len(group) // 2]
            labels.append(
                ax.annotate(
                    text,
                    (x[i], y[i]),
                    fontsize=6,
                    xytext=(3, 2),
                    textcoords="offset points",
                    color=line.get_color(),
                )
            )
    front = sorted((r for r in result.rows if r.pareto_newton), key=lambda r: r.ns_per_point)
    if front:
        ax.step(
            [r.ns_per_point for r in front],
            [max(r.err_max, floor) for r in front],
            where="post",
            color="0.6",
            lw=4,
            alpha=0.4,
            zorder=0,
            label="Pareto front of the Newton rows",
        )
    ax.set_xscale("log")
    ax.set_yscale("log")
    for axis in (ax.xaxis, ax.yaxis):  # "40", not "4x10^1"
        axis.set_major_formatter(LogFormatter(labelOnlyBase=False))
        axis.set_minor_formatter(LogFormatter(labelOnlyBase=False, minor_thresholds=(1, 0.4)))
    ax.set_xlabel("time per point (ns, one thread)")
    ax.set_ylabel("max angle error (rad)")
    ax.set_title(
        f"planarkin: speed vs accuracy ({result.n_links} linkages x {result.n_points} angles)"
    )
    ax.grid(True, which="both", alpha=0.3)
    ax.legend(fontsize=8)
    _drop_overlapping(fig, labels)
    return fig


def save(result: TradeoffResult, path: str) -> None:
    """Saves the Pareto plot (time per point vs max error, log-log); the suffix of
    ``path`` (.png, .svg, .pdf) chooses the format."""
    figure(result).savefig(path, dpi=120)


def _close_runs(x: list[float], y: list[float], near: float = 0.06) -> list[list[int]]:
    """Consecutive points (in tolerance order) whose markers are within ``near`` decades
    of the previous one on both axes: one label for each run."""
    runs: list[list[int]] = []
    for i in range(len(x)):
        if runs and all(
            abs(math.log10(a[i]) - math.log10(a[runs[-1][-1]])) < near * (3 if a is y else 1)
            for a in (x, y)
        ):
            runs[-1].append(i)
        else:
            runs.append([i])
    return runs


def _drop_overlapping(fig, labels: list) -> None:
    """Hides a tolerance label that would overprint one already shown (the rows nearby
    are labelled; the table has every value)."""
    fig.draw_without_rendering()
    shown: list = []
    for t in labels:
        box = t.get_window_extent()
        if any(box.overlaps(b) for b in shown):
            t.set_visible(False)
        else:
            shown.append(box)
