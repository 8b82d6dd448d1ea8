"""A slider scene's sweep takes one of two paths: every input value solved at once by the
closed forms (when no step comes near a dead point and the values are at most
``max_step`` apart), or continuation. Both must give the same motion: here every slider
built-in is swept both ways (continuation forced by a ``max_step`` shorter than the
values' spacing) and compared to 1e-12 of the drawing's size, velocities and
accelerations included. Then the result object the fast path builds: every field, and
the output coordinate computed on first access."""

import dataclasses

import numpy as np
import planarkin as pk
import pytest
from planarkin.scene import SceneSweep

SLIDERS = [n for n in pk.scenes.names() if {"slots", "prismatic"} & set(pk.scenes.data(n))]


def _values(sc):
    """The default angles; for a linear input, the default displacements from the drawn
    pose (s = 0) up to 0.1 of the stroke from its far end (its ends are dead points)."""
    t = sc.sweep(outputs="all").theta
    if sc.input_kind == "angle":
        return t
    start = int(np.argmin(np.abs(t)))
    return t[start : len(t) - len(t) // 10]


def _size(sc):
    return float(max(np.ptp(np.array(list(sc.points.values())), axis=0)))


@pytest.mark.parametrize("omega", [None, 2.5])
@pytest.mark.parametrize("name", SLIDERS)
def test_both_paths_give_the_same_motion(name, omega):
    sc = pk.scenes.load(name)
    t = _values(sc)
    h = float(np.max(np.abs(np.diff(t))))
    fast = sc.sweep(t, outputs="all", omega=omega, max_step=2 * h)
    slow = sc.sweep(t, outputs="all", omega=omega, max_step=h / 2)
    # the column path's certificate holds (every step's conditioning at least 0.05, the
    # first value within max_step of the drawn one): ``fast`` took it
    assert fast.success.all() and np.abs(fast.step_det).min() >= 0.05, name
    assert abs(t[0] - (sc.input_angle if sc.input_kind == "angle" else 0.0)) <= 2 * h
    np.testing.assert_array_equal(fast.status, slow.status)
    np.testing.assert_array_equal(fast.step_status, slow.step_status)
    np.testing.assert_array_equal(fast.point_status_array, slow.point_status_array)
    size = _size(sc)
    assert np.max(np.abs(fast.coords - slow.coords)) <= 1e-12 * size
    assert np.max(np.abs(fast.angle_array - slow.angle_array), initial=0) <= 1e-12
    np.testing.assert_allclose(fast.step_det, slow.step_det, rtol=0, atol=1e-12)
    np.testing.assert_allclose(fast.det, slow.det, rtol=0, atol=1e-12)
    if fast.output is not None:
        np.testing.assert_allclose(fast.output, slow.output, rtol=0, atol=1e-12 * size)
    if omega is not None:
        for a, b in [
            (fast.velocity_array, slow.velocity_array),
            (fast.angular_velocity_array, slow.angular_velocity_array),
            (fast.acceleration_array, slow.acceleration_array),
            (fast.angular_acceleration_array, slow.angular_acceleration_array),
        ]:
            big = max(1.0, float(np.max(np.abs(a), initial=0)))
            assert np.max(np.abs(a - b), initial=0) <= 1e-12 * big


def test_the_fast_result_has_every_field():
    sc = pk.scenes.load("slider-crank")
    sw = sc.sweep(outputs=["B"])
    # the output coordinate waits until it is read
    assert "output" not in vars(sw)
    out = sw.output
    assert out is not None and out.shape == sw.theta.shape
    b = sw.points["B"][:, 0]
    np.testing.assert_allclose(out, b - sc.points["B"][0], rtol=0, atol=1e-12 * _size(sc))
    # every dataclass field reads as the dataclass's own __init__ would have set it
    again = dataclasses.replace(sw)
    for f in dataclasses.fields(SceneSweep):
        x, y = getattr(sw, f.name), getattr(again, f.name)
        assert x is y, f.name
    np.testing.assert_array_equal(again.output, out)
    assert sw.input == "angle" and sw.omega is None and sw.velocity_array is None
    assert sw.point_names == sw.plan.points and sw.link_names == sw.plan.links
    with pytest.raises(dataclasses.FrozenInstanceError):
        sw.status = None  # type: ignore[misc]
    kin = sc.sweep(outputs=["B"], omega=3.0)
    assert kin.omega == 3.0 and kin.velocities is not None and kin.accelerations is not None
    assert pk.scenes.load("fourbar").sweep().output is not None
    none = pk.Scene.from_dict({**pk.scenes.data("fourbar"), "output": None})
    assert none.sweep().output is None
