"""Titles that stay on the canvas: every title of a figure wrapped onto more lines
wherever it would leave it, at any resolution."""

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
        if not changed:
            break
    return fig
