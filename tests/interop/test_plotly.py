"""The interactive notebook figure (Plotly): one frame per shown input value behind a
slider, each frame's points where the sweep has them, the paths underneath."""

from __future__ import annotations

import math
import sys

import numpy as np
import planarkin as pk
import pytest


def test_frames_follow_the_sweep() -> None:
    pytest.importorskip("plotly", reason="the plotly extra is not installed")
    from planarkin.interop import plotly as pp

    sc = pk.scenes.load("jansen")
    sw = sc.sweep(outputs=list(sc.points))
    fig = pp.figure(sc, sw, frames=40)
    step = math.ceil(361 / 40)
    keep = np.arange(0, 361, step)
    assert len(fig.frames) == len(keep)
    steps = fig.layout.sliders[0].steps
    assert [s.label for s in steps] == [f"{math.degrees(sw.theta[i]):.1f} deg" for i in keep]
    for frame, i in zip(fig.frames, keep, strict=True):
        points = frame.data[-1]
        names = list(points.text)
        assert names == list(sc.points)
        xy = np.column_stack([points.x, points.y])
        want = np.array([sw.points[n][i] for n in names])
        np.testing.assert_array_equal(xy, want)
        assert len(frame.data) == len(sc.links) + 1
    moving = [p for p in sc.points if np.ptp(sw.points[p], axis=0).max() > 0]
    assert len(fig.data) == len(moving) + len(sc.links) + 1  # paths, links, points


def test_bad_input_and_missing_extra(monkeypatch) -> None:  # noqa: ANN001
    pytest.importorskip("plotly", reason="the plotly extra is not installed")
    from planarkin.interop import plotly as pp

    sc = pk.scenes.load("fourbar")
    with pytest.raises(ValueError, match=r"^sweep: point 'P' is not reported"):
        pp.figure(sc, sc.sweep(outputs=["A"]))
    with pytest.raises(ValueError, match=r"^frames must be a positive integer, got 0$"):
        pp.figure(sc, frames=0)
    monkeypatch.setitem(sys.modules, "plotly.graph_objects", None)
    with pytest.raises(
        ImportError,
        match=r'^an interactive figure needs plotly: pip install "planarkin\[plotly\]"$',
    ):
        pp.figure(sc)
