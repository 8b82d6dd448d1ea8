"""The statics effort's exact derivatives by drawn coordinates against central differences
of statics on redrawn scenes (the scene rebuilt from its data with one coordinate moved,
swept at the same absolute input values)."""

from __future__ import annotations

import numpy as np
import planarkin as pk
import pytest


def central(sc: pk.Scene, free: list[tuple[str, int]], theta: np.ndarray, h: float) -> np.ndarray:
    out = []
    for name, axis in free:
        vals = []
        for s in (h, -h):
            d = sc.to_dict()
            d["points"][name][axis] += s
            moved = pk.Scene.from_dict(d)
            vals.append(moved.statics(moved.sweep(theta, outputs="all", rate=1.0)).input)
        out.append((vals[0] - vals[1]) / (2 * h))
    return np.array(out).T


@pytest.mark.parametrize("name", ["fourbar-loaded", "jansen-loaded"])
def test_effort_gradient_matches_central_differences(name):
    sc = pk.scenes.load(name)
    theta = sc.sweep().theta[::8]
    free = [(p, a) for p in list(sc.points)[:4] for a in (0, 1)]
    labels = [f"{p}.{'xy'[a]}" for p, a in free]
    g = sc.effort_gradient(labels, theta)
    size = float(np.ptp(np.array(list(sc.points.values())), axis=0).max())
    fd = central(sc, free, theta, 1e-6 * size)
    scale = np.abs(fd).max()
    np.testing.assert_allclose(g.input_gradient, fd, rtol=0, atol=1e-6 * scale)
    np.testing.assert_allclose(g.input, sc.statics(sc.sweep(theta, outputs="all")).input)
    # the peak's derivative is the one at the peak, with its sign
    i = int(np.argmax(np.abs(g.input)))
    assert g.value == abs(g.input[i])
    np.testing.assert_allclose(g.gradient, np.sign(g.input[i]) * fd[i], atol=1e-6 * scale)


def test_rms_gradient_and_a_step_that_lowers_it():
    sc = pk.scenes.load("fourbar-loaded")
    free = ["P.x", "P.y", "B.x"]
    g = sc.effort_gradient(free, measure="rms")
    t = g.input
    assert g.value == pytest.approx(np.sqrt(np.mean(t**2)), rel=1e-15)
    np.testing.assert_allclose(g.gradient, (t[:, None] * g.input_gradient).mean(0) / g.value)
    # a small step against the gradient lowers the RMS torque (to first order)
    d = sc.to_dict()
    step = 1e-3 * g.gradient / np.linalg.norm(g.gradient)
    for (p, a), s in zip([("P", 0), ("P", 1), ("B", 0)], step, strict=True):
        d["points"][p][a] -= s
    moved = pk.Scene.from_dict(d)
    r = moved.statics(moved.sweep(sc.sweep().theta, outputs="all", rate=1.0))
    assert np.sqrt(np.mean(r.input**2)) < g.value - 0.5e-3 * np.linalg.norm(g.gradient)


def test_measure_is_checked():
    with pytest.raises(ValueError, match="^measure: must be 'peak' or 'rms'"):
        pk.scenes.load("fourbar-loaded").effort_gradient(["A.x"], measure="max")
