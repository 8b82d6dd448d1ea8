"""The bridge between the two halves: ``FourBar.to_scene`` draws a four-bar as a scene and
``Scene.as_fourbar`` recognises one. The scene solver and the four-bar kernel then agree
on every shared name (angles, points, det), for either mode, a ground line rotated and
moved anywhere, and any scale."""

from __future__ import annotations

import math

import numpy as np
import planarkin as pk
import pytest

SEED = (6.0, 2.0, 5.0, 5.0)
P, DELTA = 3.0, math.radians(30.0)


def moved(sc: pk.Scene, phi: float, shift: tuple[float, float], scale: float) -> pk.Scene:
    """The same scene scaled, rotated by ``phi`` about the origin and shifted."""
    c, s = math.cos(phi), math.sin(phi)
    d = sc.to_dict()
    d["points"] = {
        n: [scale * (c * x - s * y) + shift[0], scale * (s * x + c * y) + shift[1]]
        for n, (x, y) in d["points"].items()
    }
    return pk.Scene.from_dict(d)


def wrapped(a: np.ndarray) -> np.ndarray:
    return np.abs(np.angle(np.exp(1j * np.asarray(a))))


CASES = [
    # links, mode, ground angle, shift, scale
    (SEED, "open", 0.0, (0.0, 0.0), 1.0),
    (SEED, "crossed", 0.0, (0.0, 0.0), 1.0),
    (SEED, "open", 0.7, (3.0, -2.0), 1.0),
    (SEED, "crossed", -2.5, (-40.0, 15.0), 1e3),
    ((3.0, 1.0, 3.5, 2.5), "open", 2.0, (0.25, 0.5), 1e-3),  # another crank-rocker
    ((2.0, 6.0, 5.0, 5.0), "crossed", 1.1, (1.0, 1.0), 7.0),  # a double crank
]


@pytest.mark.parametrize(("links", "mode", "phi", "shift", "scale"), CASES, ids=str)
def test_scene_and_fourbar_agree_to_1e12(links, mode, phi, shift, scale):
    sc = moved(pk.FourBar(*links).to_scene(mode=mode, coupler=(P, DELTA)), phi, shift, scale)
    view = sc.as_fourbar()
    fb = view.fourbar
    np.testing.assert_allclose(fb.lengths, np.multiply(links, scale), rtol=1e-13)
    assert view.mode == mode
    assert wrapped(view.ground_angle - phi) < 1e-13
    np.testing.assert_allclose(view.origin, shift, rtol=0, atol=1e-13 * scale + 1e-15)
    assert abs(view.theta2) < 1e-13  # drawn at theta2 = 0
    (p, delta) = view.coupler["P"]
    assert p == pytest.approx(P * scale, rel=1e-13) and wrapped(delta - DELTA) < 1e-13

    sw = sc.sweep(outputs="all")  # the default: from the drawn angle through a full turn
    fs = fb.sweep(sw.theta - view.ground_angle, mode=view.mode)
    both = sw.success & fs.success
    assert both.all()  # crank-rockers and double cranks: every angle on both sides
    names = view.names
    for link in ("crank", "coupler", "rocker"):
        got = sw.angles[names[link]]
        assert wrapped(got - (fs.angles[link] + view.ground_angle)).max() < 1e-12, link
    rot = np.array([[math.cos(phi), -math.sin(phi)], [math.sin(phi), math.cos(phi)]])
    px, py = fb.coupler_curve(fs, *view.coupler["P"])
    ours = {**fs.points, "P": np.column_stack((px, py))}
    for point, xy in ours.items():
        want = np.asarray(view.origin) + xy @ rot.T
        np.testing.assert_allclose(
            sw.points[names.get(point, point)], want, rtol=0, atol=1e-12 * max(fb.lengths)
        )
    np.testing.assert_allclose(sw.det, fs.det, rtol=0, atol=1e-12)
    assert np.all(np.sign(fs.det) == (1 if mode == "open" else -1))


def test_round_trip_gives_back_lengths_and_mode():
    for links in (SEED, (3.0, 1.0, 3.5, 2.5), (2.0, 6.0, 5.0, 5.0), (123.456, 2.5, 119.75, 7.125)):
        fb = pk.FourBar(*links)
        for mode in ("open", "crossed"):
            view = fb.to_scene(mode=mode).as_fourbar()
            assert view.fourbar.lengths == pytest.approx(fb.lengths, rel=1e-14)
            assert view.mode == mode
            assert view.coupler == {}


def test_to_scene_uses_the_builtin_names_and_draws_where_asked():
    sc = pk.FourBar(*SEED).to_scene(math.radians(40), mode="crossed", coupler=(P, DELTA))
    built_in = pk.scenes.load("fourbar")
    assert sc.links == built_in.links
    assert (sc.ground, sc.input, sc.output) == (built_in.ground, built_in.input, built_in.output)
    assert sc.input_angle == pytest.approx(math.radians(40), abs=1e-15)
    # the built-in scene is this four-bar at theta2 = 0, open, with the same coupler point
    same = pk.FourBar(*SEED).to_scene(coupler=(P, DELTA))
    for n, xy in built_in.points.items():
        assert same.points[n] == pytest.approx(xy, abs=1e-14)


def test_to_scene_draws_inside_the_first_interval_when_zero_cannot_assemble():
    fb = pk.FourBar(4.0, 3.0, 2.0, 3.5)  # assembles only in two bands away from theta2 = 0
    assert fb.closed_form_status(0.0) == pk.Status.NOT_ASSEMBLABLE
    view = fb.to_scene().as_fourbar()
    lo, hi = fb.limits().intervals[0]
    assert view.theta2 == pytest.approx(0.5 * (lo + hi))


def test_to_scene_refuses_what_cannot_be_drawn():
    with pytest.raises(ValueError, match="cannot be assembled at any crank angle"):
        pk.FourBar(10.0, 1.0, 1.0, 1.0).to_scene()
    with pytest.raises(ValueError, match="not assemblable"):
        pk.FourBar(5.0, 3.0, 4.0, 2.5).to_scene(math.pi)
    with pytest.raises(ValueError, match="singular"):
        pk.FourBar(6.0, 2.0, 6.0, 2.0).to_scene(0.0)  # a parallelogram's change point
    with pytest.raises(ValueError, match="mode"):
        pk.FourBar(*SEED).to_scene(mode="sideways")
    with pytest.raises(ValueError, match="coupler"):
        pk.FourBar(*SEED).to_scene(coupler=(1.0,))


def test_as_fourbar_of_the_builtin_and_of_other_names():
    view = pk.scenes.load("fourbar").as_fourbar()
    assert view.fourbar == pk.FourBar(*SEED) and view.mode == "open"
    assert view.coupler["P"] == pytest.approx((P, DELTA), abs=1e-14)
    # a four-bar drawn with names of its own, no output declared
    r = (4.0, 3.0, 1.5, 2.0)
    t3, t4 = pk.FourBar(*r).closed_form(0.0, "crossed")
    sc = pk.Scene.from_dict({
        "points": {"g1": [0, 0], "g2": [4, 0], "a": [3, 0],
                   "b": [3 + 1.5 * math.cos(t3), 1.5 * math.sin(t3)]},
        "links": {"base": ["g1", "g2"], "in": ["g1", "a"], "mid": ["a", "b"], "out": ["g2", "b"]},
        "ground": "base",
        "input": {"link": "in", "pivot": "g1"},
    })  # fmt: skip
    view = sc.as_fourbar()
    assert view.fourbar.lengths == pytest.approx(r, rel=1e-14) and view.mode == "crossed"
    assert view.names == {
        "O2": "g1", "O4": "g2", "A": "a", "B": "b",
        "ground": "base", "crank": "in", "coupler": "mid", "rocker": "out",
    }  # fmt: skip


def test_as_fourbar_says_why_a_scene_is_not_a_fourbar():
    with pytest.raises(ValueError, match=r"not a four-bar: it has \d+ links"):
        pk.scenes.load("jansen").as_fourbar()
    d = pk.scenes.data("fourbar")
    d["points"]["G"] = [3.0, -1.0]
    d["links"]["ground"] = ["O2", "O4", "G"]
    with pytest.raises(ValueError, match="ground 'ground' carries 3 points"):
        pk.Scene.from_dict(d).as_fourbar()
    d = pk.scenes.data("fourbar")
    d["links"]["crank"] = ["O2", "A", "P"]
    d["links"]["coupler"] = ["A", "B"]
    with pytest.raises(ValueError, match="'crank' must carry its ground pivot 'O2' and one joint"):
        pk.Scene.from_dict(d).as_fourbar()
