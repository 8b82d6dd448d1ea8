"""Small pictures for notebooks (``_repr_svg_``, ``_repr_png_``): a linkage pose and point
paths laid out once as shapes in pixels (``shapes``), written straight into a few
kilobytes of SVG with no plotting library (fast, and the API never imports the face), or
painted as PNG by matplotlib's Agg canvas. Scenes, four-bars and sweeps call
:func:`picture` and :func:`png`."""

from __future__ import annotations

import html
import io
from collections.abc import Iterable, Mapping, Sequence

import numpy as np

__all__ = ["picture", "png", "shapes"]

#: Width and height of the picture, px.
WIDTH, HEIGHT = 320, 240
#: Most points of a path drawn (paths are thinned to this).
PATH_POINTS = 72
_COLOURS = ("#1f77b4", "#ff7f0e", "#2ca02c", "#d62728", "#9467bd", "#8c564b", "#e377c2")


def _hull(pts: np.ndarray) -> list[int]:
    """Indices of the convex hull of ``pts`` (n, 2), counter-clockwise."""
    order = sorted(range(len(pts)), key=lambda i: (pts[i][0], pts[i][1]))

    def half(seq: list[int]) -> list[int]:
        out: list[int] = []
        for i in seq:
            while len(out) >= 2:
                (ox, oy), (ax, ay), (bx, by) = pts[out[-2]], pts[out[-1]], pts[i]
                if (ax - ox) * (by - oy) - (ay - oy) * (bx - ox) > 0:
                    break
                out.pop()
            out.append(i)
        return out

    if len(order) <= 2:
        return order
    return half(order)[:-1] + half(order[::-1])[:-1]


#: A shape in pixels (y down): (kind, points (n, 2), colour, text), kind one of "title",
#: "path", "ground", "bar", "plate", "joint" (its name in text).
Shape = tuple[str, np.ndarray, str, str]


def shapes(
    *,
    pose: Mapping[str, Sequence[float]] | None = None,
    links: Iterable[Sequence[str]] = (),
    ground: Sequence[str] = (),
    paths: Mapping[str, np.ndarray] | None = None,
    title: str = "",
) -> list[Shape]:
    """The picture as shapes in pixels, in drawing order: the ``paths`` (name -> (N, 2))
    as thin grey lines, the ``pose`` (name -> (x, y)) with each of ``links`` as a bar or,
    with three points or more, as its outline (the convex hull), joints as small circles
    and the ``ground`` points as triangles; y up, equal scale, fitted to the view."""
    given = {k: np.asarray(v, dtype=np.float64) for k, v in (pose or {}).items()}
    at_pose = {k: v for k, v in given.items() if np.isfinite(v).all()}
    thin = {}
    for k, v in (paths or {}).items():
        a = np.asarray(v, dtype=np.float64).reshape(-1, 2)
        if (
            not np.isfinite(a).any()
            or np.nanmax(np.ptp(a[np.isfinite(a).all(axis=1)], axis=0)) == 0
        ):
            continue  # a point that does not move (ground) has no path
        step = max(1, -(-len(a) // PATH_POINTS))
        thin[k] = a[::step]
    every = [v.reshape(-1, 2) for v in [*at_pose.values(), *thin.values()]]
    xy = np.concatenate(every) if every else np.zeros((0, 2))
    xy = xy[np.isfinite(xy).all(axis=1)]
    if not len(xy):
        xy = np.zeros((1, 2))
    lo, hi = xy.min(axis=0), xy.max(axis=0)
    span = float(max(hi - lo)) or 1.0
    top = 22 if title else 8
    scale = min((WIDTH - 16) / span, (HEIGHT - top - 18) / span)
    cx, cy = (lo + hi) / 2

    def at(p: np.ndarray) -> np.ndarray:
        x = WIDTH / 2 + (p[..., 0] - cx) * scale
        y = (HEIGHT + top - 10) / 2 - (p[..., 1] - cy) * scale
        return np.stack([x, y], -1)

    out: list[Shape] = []
    if title:
        out.append(("title", np.array([[6.0, 14.0]]), "black", title))
    for a in thin.values():
        for piece in np.split(a, np.flatnonzero(~np.isfinite(a).all(axis=1))):
            piece = piece[np.isfinite(piece).all(axis=1)]
            if len(piece) > 1:
                out.append(("path", at(piece), "#999", ""))
    size = 0.03 * span * scale
    for g in ground:
        if g in at_pose:
            x, y = at(at_pose[g])
            tri = np.array([[x, y], [x - size, y + 1.6 * size], [x + size, y + 1.6 * size]])
            out.append(("ground", tri, "#ccc", ""))
    for j, names in enumerate(links):
        c = _COLOURS[j % len(_COLOURS)]
        ends = [at_pose[n] for n in names if n in at_pose]
        if len(ends) < len(names) or len(ends) < 2:
            continue
        arr = np.array(ends)
        if len(ends) == 2:
            out.append(("bar", at(arr), c, ""))
        else:
            out.append(("plate", at(arr[_hull(arr)]), c, ""))
    for name, p in at_pose.items():
        out.append(("joint", at(p)[None, :], "black", name))
    return out


def _xy(p: np.ndarray) -> str:
    return f"{p[0]:.1f},{p[1]:.1f}"


def picture(**kw: object) -> str:
    """An SVG document of :func:`shapes` (the same arguments)."""
    out = [
        f'<svg xmlns="http://www.w3.org/2000/svg" width="{WIDTH}" height="{HEIGHT}" '
        f'viewBox="0 0 {WIDTH} {HEIGHT}" font-family="sans-serif" font-size="10">',
        f'<rect width="{WIDTH}" height="{HEIGHT}" fill="white"/>',
    ]
    for kind, p, c, text in shapes(**kw):  # type: ignore[arg-type]
        if kind == "title":
            out.append(f'<text x="6" y="14" font-size="11">{html.escape(text)}</text>')
        elif kind == "path":
            pts = " ".join(_xy(q) for q in p)
            out.append(f'<polyline points="{pts}" fill="none" stroke="{c}" stroke-width="1"/>')
        elif kind == "ground":
            pts = " ".join(_xy(q) for q in p)
            out.append(f'<polygon points="{pts}" fill="{c}" stroke="#333"/>')
        elif kind == "bar":
            (x1, y1), (x2, y2) = p
            out.append(
                f'<line class="link" x1="{x1:.1f}" y1="{y1:.1f}" x2="{x2:.1f}" y2="{y2:.1f}" '
                f'stroke="{c}" stroke-width="3" stroke-linecap="round"/>'
            )
        elif kind == "plate":
            ring = " ".join(_xy(q) for q in p)
            out.append(
                f'<polygon class="link" points="{ring}" fill="{c}" fill-opacity="0.25" '
                f'stroke="{c}" stroke-width="2"/>'
            )
        else:
            (px, py) = p[0]
            out.append(f'<circle cx="{px:.1f}" cy="{py:.1f}" r="3" fill="white" stroke="black"/>')
            out.append(f'<text x="{px + 4:.1f}" y="{py - 4:.1f}">{html.escape(text)}</text>')
    out.append("</svg>")
    return "\n".join(out)


def png(**kw: object) -> bytes:
    """The same picture as PNG bytes (WIDTH x HEIGHT px), painted by matplotlib's Agg."""
    from matplotlib.backends.backend_agg import FigureCanvasAgg
    from matplotlib.figure import Figure
    from matplotlib.patches import Circle, Polygon

    fig = Figure(figsize=(WIDTH / 100, HEIGHT / 100), dpi=100, facecolor="white")
    FigureCanvasAgg(fig)
    ax = fig.add_axes((0, 0, 1, 1))
    ax.set_xlim(0, WIDTH)
    ax.set_ylim(HEIGHT, 0)  # pixels, y down, as the shapes are
    ax.set_axis_off()
    for kind, p, c, text in shapes(**kw):  # type: ignore[arg-type]
        if kind == "title":
            ax.text(p[0, 0], p[0, 1], text, fontsize=8, va="baseline", family="sans-serif")
        elif kind == "path":
            ax.plot(p[:, 0], p[:, 1], color=c, lw=0.75)
        elif kind == "ground":
            ax.add_patch(Polygon(p, closed=True, facecolor=c, edgecolor="#333", lw=0.75))
        elif kind == "bar":
            ax.plot(p[:, 0], p[:, 1], color=c, lw=2.25, solid_capstyle="round")
        elif kind == "plate":
            ax.add_patch(Polygon(p, closed=True, facecolor=c, alpha=0.25, lw=0))
            ax.add_patch(Polygon(p, closed=True, fill=False, edgecolor=c, lw=1.5))
        else:
            (px, py) = p[0]
            ax.add_patch(Circle((px, py), 3, facecolor="white", edgecolor="black", lw=0.75,
                                zorder=3))  # fmt: skip
            ax.text(px + 4, py - 4, text, fontsize=7.5, family="sans-serif", zorder=4)
    buf = io.BytesIO()
    fig.savefig(buf, format="png", dpi=100)
    return buf.getvalue()
