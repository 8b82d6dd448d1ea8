"""Small pictures for notebooks (``_repr_svg_``): a linkage pose and point paths written
straight into a few kilobytes of SVG, with no plotting library (fast, and the API never
imports the face). Scenes, four-bars and sweeps call :func:`picture`."""

from __future__ import annotations

import html
from collections.abc import Iterable, Mapping, Sequence

import numpy as np

__all__ = ["picture"]

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


def picture(
    *,
    pose: Mapping[str, Sequence[float]] | None = None,
    links: Iterable[Sequence[str]] = (),
    ground: Sequence[str] = (),
    paths: Mapping[str, np.ndarray] | None = None,
    title: str = "",
) -> str:
    """An SVG document: the ``paths`` (name -> (N, 2)) as thin grey lines, the ``pose``
    (name -> (x, y)) with each of ``links`` as a bar or, with three points or more, as its
    outline (the convex hull), joints as small circles and the ``ground`` points as
    triangles; y up, equal scale, fitted to the view."""
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

    def at(p: np.ndarray) -> str:
        x = WIDTH / 2 + (p[0] - cx) * scale
        y = (HEIGHT + top - 10) / 2 - (p[1] - cy) * scale
        return f"{x:.1f},{y:.1f}"

    out = [
        f'<svg xmlns="http://www.w3.org/2000/svg" width="{WIDTH}" height="{HEIGHT}" '
        f'viewBox="0 0 {WIDTH} {HEIGHT}" font-family="sans-serif" font-size="10">',
        f'<rect width="{WIDTH}" height="{HEIGHT}" fill="white"/>',
    ]
    if title:
        out.append(f'<text x="6" y="14" font-size="11">{html.escape(title)}</text>')
    for a in thin.values():
        for piece in np.split(a, np.flatnonzero(~np.isfinite(a).all(axis=1))):
            piece = piece[np.isfinite(piece).all(axis=1)]
            if len(piece) > 1:
                pts = " ".join(at(p) for p in piece)
                out.append(f'<polyline points="{pts}" fill="none" stroke="#999" stroke-width="1"/>')
    size = 0.03 * span * scale
    for g in ground:
        if g in at_pose:
            x, y = (float(v) for v in at(at_pose[g]).split(","))
            out.append(
                f'<polygon points="{x:.1f},{y:.1f} {x - size:.1f},{y + 1.6 * size:.1f} '
                f'{x + size:.1f},{y + 1.6 * size:.1f}" fill="#ccc" stroke="#333"/>'
            )
    for j, names in enumerate(links):
        c = _COLOURS[j % len(_COLOURS)]
        ends = [at_pose[n] for n in names if n in at_pose]
        if len(ends) < len(names) or len(ends) < 2:
            continue
        if len(ends) == 2:
            (x1, y1), (x2, y2) = (at(p).split(",") for p in ends)
            out.append(
                f'<line class="link" x1="{x1}" y1="{y1}" x2="{x2}" y2="{y2}" stroke="{c}" '
                'stroke-width="3" stroke-linecap="round"/>'
            )
        else:
            arr = np.array(ends)
            ring = " ".join(at(arr[i]) for i in _hull(arr))
            out.append(
                f'<polygon class="link" points="{ring}" fill="{c}" fill-opacity="0.25" '
                f'stroke="{c}" stroke-width="2"/>'
            )
    for name, p in at_pose.items():
        px, py = (float(v) for v in at(p).split(","))
        out.append(f'<circle cx="{px:.1f}" cy="{py:.1f}" r="3" fill="white" stroke="black"/>')
        out.append(f'<text x="{px + 4:.1f}" y="{py - 4:.1f}">{html.escape(name)}</text>')
    out.append("</svg>")
    return "\n".join(out)
