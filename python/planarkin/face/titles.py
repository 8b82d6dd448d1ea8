"""Titles and axis labels that stay on the canvas and off each other: every title of a
figure wrapped onto more lines wherever it would leave it, and every axis label wherever it
is longer than its axes, at any resolution."""

from __future__ import annotations

import textwrap

from matplotlib.figure import Figure

__all__ = ["fit_titles"]


def fit_titles(fig: Figure) -> Figure:
    """Wraps every title (of the figure and of its axes) onto more lines wherever it
    would leave the canvas; constrained layout then makes room for the lines. Text and
    canvas both scale with the resolution, so what fits at one dpi fits at any."""
    sup = getattr(fig, "_suptitle", None)  # set by fig.suptitle(); no public getter of the Text
    titles = [sup, *(ax.title for ax in fig.axes)]
    for _ in range(4):
        fig.draw_without_rendering()  # lays out (constrained layout) without drawing
        page = fig.bbox
        changed = False
        for t in titles:
            if t is None or not t.get_text():
                continue
            e = t.get_window_extent()
            centre = 0.5 * (e.x0 + e.x1)
            room = 0.96 * 2.0 * min(centre - page.x0, page.x1 - centre)
            if e.width <= room:
                continue
            lines = t.get_text().split("\n")
            chars = max(12, int(max(map(len, lines)) * room / e.width))
            t.set_text("\n".join(textwrap.fill(line, chars) for line in lines))
            changed = True
        changed |= _fit_axis_labels(fig)
        if not changed:
            break
    return fig


def _fit_axis_labels(fig: Figure) -> bool:
    """Wraps each axis label longer than its axes (a y label along the axes' height, an x
    label along its width), so that stacked axes' labels never run into each other."""
    changed = False
    for ax in fig.axes:
        box = ax.get_window_extent()
        for label, room in ((ax.xaxis.label, box.width), (ax.yaxis.label, box.height)):
            text = label.get_text()
            if not text or room <= 0:
                continue
            e = label.get_window_extent()
            length = max(e.width, e.height)
            if length <= 0.98 * room:
                continue
            lines = text.split("\n")
            chars = max(8, int(max(map(len, lines)) * 0.95 * room / length))
            wrapped = "\n".join(textwrap.fill(line, chars) for line in lines)
            if wrapped != text:
                label.set_text(wrapped)
                changed = True
    return changed
