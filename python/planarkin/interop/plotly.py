"""An interactive figure of a scene for notebooks (Plotly, the optional extra ``plotly``):
the linkage at every input value of its sweep behind a slider and a play button, the
tracer points' paths drawn under it. ``figure(scene)`` returns a plotly ``Figure``."""

from __future__ import annotations

import math
from typing import Any

import numpy as np

from ..scene import Scene, SceneSweep
from ._extras import need
from .sheet import hull

_COLOURS = ("#1f77b4", "#ff7f0e", "#2ca02c", "#d62728", "#9467bd", "#8c564b", "#e377c2")


def _link_xy(pose: dict[str, np.ndarray], names: tuple[str, ...]) -> tuple[list, list]:
    """A bar's two ends, or a plate's hull closed, for one pose."""
    pts = [tuple(pose[n]) for n in names]
    ring = pts if len(pts) == 2 else hull(pts) + hull(pts)[:1]
    return [p[0] for p in ring], [p[1] for p in ring]


def _traces(sc: Scene, pose: dict[str, np.ndarray]) -> list[dict[str, Any]]:
    out: list[dict[str, Any]] = []
    for j, (name, on) in enumerate(sc.links.items()):
        x, y = _link_xy(pose, on)
        ground = name == sc.ground
        out.append({
            "type": "scatter", "x": x, "y": y, "mode": "lines", "name": name,
            "fill": "toself" if len(on) > 2 else None, "hoverinfo": "name",
            "line": {"color": "#888" if ground else _COLOURS[j % len(_COLOURS)],
                     "width": 2 if ground else 4},
        })  # fmt: skip
    joints = list(pose)
    marker = {"color": "white", "size": 8, "line": {"color": "black", "width": 1}}
    out.append({
        "type": "scatter", "mode": "markers+text", "name": "points", "text": joints,
        "x": [pose[n][0] for n in joints], "y": [pose[n][1] for n in joints],
        "textposition": "top right", "marker": marker,
    })  # fmt: skip
    return out


def figure(sc: Scene, sweep: SceneSweep | None = None, frames: int = 72) -> Any:
    """The scene moving through ``sweep`` (default: its default sweep, every point), at
    most ``frames`` poses behind a slider (input angle in degrees, or a linear input's
    displacement), the moving points' paths drawn grey."""
    go = need("plotly.graph_objects", "plotly", "an interactive figure")
    if not (isinstance(frames, int) and frames >= 1):
        raise ValueError(f"frames must be a positive integer, got {frames!r}")
    sw = sc.sweep(outputs=list(sc.points)) if sweep is None else sweep
    missing = [p for p in sc.points if p not in sw.points]
    if missing:
        raise ValueError(f"sweep: point {missing[0]!r} is not reported (sweep every point)")
    ok = np.flatnonzero(sw.success)
    if not len(ok):
        raise ValueError("sweep: no input value is solved; nothing to show")
    keep = ok[:: max(1, math.ceil(len(ok) / frames))]
    angle = sw.input == "angle"
    paths = []
    for p, xy in sw.points.items():
        if np.ptp(xy[ok], axis=0).max() > 0:
            grey = {"color": "#bbb", "width": 1}
            paths.append({"type": "scatter", "x": xy[ok, 0].tolist(), "y": xy[ok, 1].tolist(),
                          "mode": "lines", "line": grey, "hoverinfo": "skip",
                          "showlegend": False, "name": f"{p} path"})  # fmt: skip
    poses = [{p: sw.points[p][i] for p in sc.points} for i in keep]
    labels = [
        f"{math.degrees(sw.theta[i]):.1f} deg" if angle else f"{sw.theta[i]:.4g}" for i in keep
    ]
    fig_frames = [
        go.Frame(
            data=_traces(sc, pose),
            name=label,
            traces=list(range(len(paths), len(paths) + len(sc.links) + 1)),
        )
        for pose, label in zip(poses, labels, strict=True)
    ]
    steps = [{"method": "animate", "label": lb,
              "args": [[lb], {"mode": "immediate", "frame": {"duration": 0, "redraw": True}}]}
             for lb in labels]  # fmt: skip
    run = {"frame": {"duration": 40, "redraw": True}, "fromcurrent": True}
    button = {"label": "play", "method": "animate", "args": [None, run]}
    play = {"type": "buttons", "showactive": False, "x": 0.0, "y": -0.12, "buttons": [button]}
    layout = {
        "title": sc.name or "scene",
        "xaxis": {"scaleanchor": "y", "scaleratio": 1, "title": sc.units or ""},
        "yaxis": {"title": sc.units or ""},
        "sliders": [{"steps": steps, "currentvalue": {"prefix": "input: "}, "y": -0.05}],
        "updatemenus": [play],
        "showlegend": False,
    }
    return go.Figure(data=paths + _traces(sc, poses[0]), frames=fig_frames, layout=layout)
