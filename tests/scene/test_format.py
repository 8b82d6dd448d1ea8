"""The scene file format is read once, in the core (``planarkin_core::scene::format``):
Python hands it the data as given (any mapping, tuples, NumPy numbers and arrays) and
takes its defaults from there."""

from __future__ import annotations

import math
import types

import numpy as np
import planarkin as pk
import pytest
from planarkin import _kernel


def test_numpy_values_mappings_and_tuples_are_taken_as_before():
    d = pk.scenes.data("fourbar")
    plain = pk.Scene(d)
    odd = dict(d)
    odd["points"] = types.MappingProxyType({k: np.asarray(v) for k, v in d["points"].items()})
    odd["links"] = {k: tuple(v) for k, v in d["links"].items()}
    odd["input"] = types.MappingProxyType(dict(d["input"]))
    assert pk.Scene(odd) == plain
    d["points"]["A"] = [np.float32(2.0), np.int64(0)]
    assert pk.Scene(d).points["A"] == (2.0, 0.0)


@pytest.mark.parametrize(
    "value, message",
    [
        ([np.True_, 0], "points.A[0] must be a real number, got np.True_"),
        (np.array([1.0, 2.0, 3.0]), "points.A: must be a pair [x, y], got array([1., 2., 3.])"),
        ([1j, 0], "points.A[0] must be a real number, got 1j"),
    ],
)
def test_numpy_values_are_quoted_by_their_own_repr(value, message):
    d = pk.scenes.data("fourbar")
    d["points"]["A"] = value
    with pytest.raises(ValueError) as e:
        pk.Scene(d)
    assert str(e.value) == message


def test_the_defaults_are_the_cores():
    assert _kernel.MAX_STEP == math.radians(3.0)
    k = _kernel
    assert (k.TOL, k.MAX_ITER, k.SEED, k.RUNS) == (1e-9, 100, 0x5EED_2026, 2)
    assert (_kernel.TRACE_STEP, _kernel.TRACE_MAX_POINTS, _kernel.SWEEP_LEN) == (0.05, 50_000, 361)
    assert tuple(_kernel.SCENE_KEYS[3:7]) == ("points", "links", "ground", "input")
    sc = pk.scenes.load("fourbar")
    t = sc.sweep().theta
    np.testing.assert_array_equal(t, sc.input_angle + np.arange(361) * (math.tau / 360))
    boom = pk.scenes.load("hydraulic-boom")
    np.testing.assert_array_equal(boom.sweep().theta, np.linspace(*boom.stroke(), 361))


def test_a_linear_output_is_the_cores_displacement_along_its_line():
    sc = pk.scenes.load("slider-crank")
    sw = sc.sweep(outputs="all")
    assert sc.output is not None and "link" not in sc.to_dict()["output"]
    kind, name = sc.output
    q, _, (a, b) = sc.slots[name]
    pts, drawn = sw.points, {n: np.asarray(sc.points[n]) for n in (q, a, b)}
    u0 = (drawn[b] - drawn[a]) / np.linalg.norm(drawn[b] - drawn[a])
    u = pts[b] - pts[a]
    u = u / np.linalg.norm(u, axis=1)[:, None]
    want = ((pts[q] - pts[a]) * u).sum(1) - (drawn[q] - drawn[a]) @ u0
    np.testing.assert_allclose(sw.output, want, rtol=0, atol=1e-12 * sc._size())
