"""The NumPy scene reference and the built-in scenes against independent truths.

Truths here are written out in the tests (circle intersections, the Peaucellier line,
Gruebler's count, rigidity of every link); nothing but ``planarkin.reference`` and
``planarkin.scenes`` (its data files) is imported from planarkin.
"""

from __future__ import annotations

import functools
import math

import numpy as np
import pytest
from _support import dyad_point
from planarkin import scenes
from planarkin.reference import scene_assemble_check, scene_sweep

DEG = math.pi / 180


def _xy(d, name):
    return np.asarray(d["points"][name], dtype=float)


def _side(p, q, r):
    """+1 where r is left of p -> q, -1 where right (the cross product's sign)."""
    u, v = q - p, r - p
    return np.sign(u[..., 0] * v[..., 1] - u[..., 1] * v[..., 0])


def _wrapdiff(a, b):
    return np.abs(np.angle(np.exp(1j * (np.asarray(a) - np.asarray(b)))))


@functools.cache
def _reference_sweep(name):
    """The reference's sweep of a built-in scene over its default angles, computed once per
    module and shared by the tests that only read it (a double butterfly's takes seconds)."""
    return scene_sweep(scenes.data(name))


def _gruebler(d):
    count = {}
    for pts in d["links"].values():
        for p in set(pts):
            count[p] = count.get(p, 0) + 1
    return 3 * (len(d["links"]) - 1) - 2 * sum(k - 1 for k in count.values())


def _size(d):
    return max(
        float(np.hypot(*(_xy(d, a) - _xy(d, b))))
        for pts in d["links"].values()
        for a in pts
        for b in pts
    )


# --- the scenes package ----------------------------------------------------------------

EXPECTED = {
    "chebyshev-lambda",
    "double-butterfly-1",
    "double-butterfly-2",
    "fourbar",
    "jansen",
    "klann",
    "peaucellier",
    "stephenson3",
    "watt2",
    # with loads (issue 34)
    "fourbar-loaded",
    "jansen-loaded",
    # with slots and prismatic pairs
    "elliptic-trammel",
    "engine",
    "hydraulic-boom",
    "hydraulic-boom-loaded",
    "inverted-slider-crank",
    "scotch-yoke",
    "slider-crank",
    "slider-crank-offset",
    "whitworth",
}
#: The built-ins with slots or prismatic pairs: tests/scene/test_sliders.py holds their
#: closed forms; the checks below are written for pin-jointed scenes.
SLIDERS = {n for n in EXPECTED if {"slots", "prismatic"} & set(scenes.data(n))}
PINNED = sorted(EXPECTED - SLIDERS)


def test_names_path_data():
    assert scenes.names() == sorted(EXPECTED)
    for name in scenes.names():
        assert scenes.path(name).name == f"{name}.json"
        assert scenes.path(name).is_file()
    d = scenes.data("fourbar")
    d["points"].clear()  # a fresh copy each time
    assert scenes.data("fourbar")["points"]
    with pytest.raises(ValueError, match="nope.*fourbar"):
        scenes.path("nope")


@pytest.mark.parametrize("name", PINNED)
def test_builtin_scene_is_well_formed(name):
    d = scenes.data(name)
    for key in ("name", "description", "units", "points", "links", "ground", "input", "outputs"):
        assert key in d, key
    assert len(d["description"]) > 80
    pts = d["points"]
    assert all(len(v) == 2 and all(math.isfinite(c) for c in v) for v in pts.values())
    on_links = {p for ps in d["links"].values() for p in ps}
    assert on_links == set(pts)
    assert d["input"]["pivot"] in d["links"][d["ground"]]
    assert d["input"]["pivot"] in d["links"][d["input"]["link"]]
    if "output" in d:
        assert d["output"]["pivot"] in d["links"][d["ground"]]
        assert d["output"]["pivot"] in d["links"][d["output"]["link"]]
    assert d["outputs"] and set(d["outputs"]) <= set(pts)


@pytest.mark.parametrize("name", PINNED)
def test_builtin_scene_consistent_mobility_one(name):
    d = scenes.data(name)
    assert _gruebler(d) == 1
    assert scene_assemble_check(d) < 1e-12


#: Built-in scenes whose reference sweep takes over a second (pure Python): their cases
#: below are left out of the inner loop (-m "not slow"); the other scenes stay in it.
SLOW_REFERENCE = {"double-butterfly-1", "double-butterfly-2", "peaucellier"}
NAMES = [pytest.param(n, marks=pytest.mark.slow) if n in SLOW_REFERENCE else n
         for n in PINNED]  # fmt: skip


@pytest.mark.parametrize("name", NAMES)
def test_builtin_scene_sweep_keeps_every_link_rigid(name):
    """Wherever the reference converges: every link keeps its drawn distances, ground
    points stay, the input points along theta; and the drawn angle itself converges."""
    d = scenes.data(name)
    sw = _reference_sweep(name)
    ok = sw.status == 0
    assert ok[0] and ok.sum() >= 60
    size = _size(d)
    for pts in d["links"].values():
        for i, a in enumerate(pts):
            for b in pts[i + 1 :]:
                d0 = np.hypot(*(_xy(d, a) - _xy(d, b)))
                d1 = np.hypot(*(sw.points[a][ok] - sw.points[b][ok]).T)
                assert np.max(np.abs(d1 - d0)) / size < 1e-12, (a, b)
    for p in d["links"][d["ground"]]:
        assert np.all(sw.points[p] == _xy(d, p))
    piv = d["input"]["pivot"]
    other = next(p for p in d["links"][d["input"]["link"]] if p != piv)
    v = sw.points[other][ok] - _xy(d, piv)
    assert np.max(_wrapdiff(np.arctan2(v[:, 1], v[:, 0]), sw.theta[ok])) < 1e-12
    assert np.all(np.isnan(sw.points[other][~ok]))


@pytest.mark.parametrize("name", NAMES)
def test_full_turn_scenes_close(name):
    d = scenes.data(name)
    full = "turns fully" in d["description"]
    sw = _reference_sweep(name)
    assert full == bool(np.all(sw.status == 0))
    if full:
        for p, xy in sw.points.items():
            assert np.max(np.abs(xy[-1] - xy[0])) / _size(d) < 1e-10, p


# --- the four-bar against its closed form -------------------------------------------------


def test_fourbar_against_circle_intersection():
    d = scenes.data("fourbar")
    o2, o4, a0, b0, p0 = (_xy(d, n) for n in ("O2", "O4", "A", "B", "P"))
    assert np.allclose(b0, [4.0, math.sqrt(21.0)], rtol=0, atol=1e-14)
    r2, r3, r4 = (np.hypot(*v) for v in (a0 - o2, b0 - a0, b0 - o4))
    assert (r2, r3, r4) == pytest.approx((2, 5, 5), abs=1e-14)
    sw = scene_sweep(d)
    assert np.all(sw.status == 0)
    t2 = sw.theta
    a = np.stack([r2 * np.cos(t2), r2 * np.sin(t2)], -1)
    b = dyad_point(a, r3, np.broadcast_to(o4, a.shape), r4, side=+1)  # open: left of A -> O4
    t3 = np.arctan2(b[:, 1] - a[:, 1], b[:, 0] - a[:, 0])
    t4 = np.arctan2(b[:, 1] - o4[1], b[:, 0] - o4[0])
    assert np.max(_wrapdiff(sw.angles["coupler"], t3)) < 1e-10
    assert np.max(_wrapdiff(sw.angles["rocker"], t4)) < 1e-10
    assert np.max(_wrapdiff(sw.angles["crank"], t2)) < 1e-12
    # P: 3 from A at 30 deg counter-clockwise from A -> B
    p = a + 3.0 * np.stack([np.cos(t3 + 30 * DEG), np.sin(t3 + 30 * DEG)], -1)
    assert np.max(np.abs(sw.points["P"] - p)) < 1e-10 * 6
    assert np.allclose(sw.points["P"][0], p0, rtol=0, atol=1e-13)
    # Freudenstein: K1 cos t4 - K2 cos t2 + K3 = cos(t2 - t4)
    r1 = 6.0
    k1, k2, k3 = r1 / r2, r1 / r4, (r2**2 - r3**2 + r4**2 + r1**2) / (2 * r2 * r4)
    f = k1 * np.cos(t4) - k2 * np.cos(t2) + k3 - np.cos(t2 - sw.angles["rocker"])
    assert np.max(np.abs(f)) < 1e-12


def test_fourbar_theta_order_and_wrap():
    d = scenes.data("fourbar")
    th = np.array([3.0, -3.0, 1.0, 7.0])  # drawn angle 0: marches -> 3, then in order
    sw = scene_sweep(d, th)
    assert np.all(sw.status == 0)
    assert np.array_equal(sw.theta, th)
    a = np.stack([2 * np.cos(th), 2 * np.sin(th)], -1)
    b = dyad_point(a, 5.0, np.broadcast_to([6.0, 0.0], a.shape), 5.0, side=+1)
    assert np.max(np.abs(sw.points["B"] - b)) < 1e-10 * 6


# --- Peaucellier: an exact straight line ---------------------------------------------------


def test_peaucellier_exact_straight_line():
    d = scenes.data("peaucellier")
    o, q, c, a = (_xy(d, n) for n in ("O", "Q", "C", "A"))
    big = np.hypot(*(a - o))
    s = np.hypot(*(c - a))
    r = np.hypot(*(c - q))
    assert np.hypot(*(q - o)) == pytest.approx(r, rel=1e-14)  # C's circle passes through O
    u = (q - o) / r
    dist = (big * big - s * s) / (2 * r)  # |OC| |OP| = L^2 - s^2, |OC| = 2 r cos(phi/2)
    half = 2 * math.acos((big - s) / (2 * r))  # |OC| >= L - s
    base = math.atan2(u[1], u[0])
    th = base + np.linspace(-half, half, 401)[1:-1] * (1 - 1e-3)
    sw = scene_sweep(d, th)
    assert np.all(sw.status == 0)
    along = (sw.points["P"] - o) @ u
    assert np.max(np.abs(along - dist)) / _size(d) < 1e-12
    # and it really moves along the line, on the far side of C from O
    across = (sw.points["P"] - o) @ np.array([-u[1], u[0]])
    assert np.ptp(across) > dist
    # past the end of the range the inversor cannot assemble
    bad = scene_sweep(d, [base + half * 1.01])
    assert bad.status[0] != 0 and np.isnan(bad.points["P"][0, 0])


# --- Jansen: a chain of circle intersections ------------------------------------------------


def test_jansen_foot_against_circle_chain():
    d = scenes.data("jansen")
    p = {n: _xy(d, n) for n in d["points"]}
    dd = {(a, b): float(np.hypot(*(p[a] - p[b]))) for a in p for b in p}
    # the holy numbers are the drawing's lengths
    holy = {
        ("Z", "B"): 41.5, ("Z", "C"): 39.3, ("Z", "D"): 40.1, ("B", "D"): 55.8,
        ("D", "E"): 39.4, ("C", "E"): 36.7, ("E", "foot"): 65.7, ("C", "foot"): 49.0,
        ("M", "B"): 50.0, ("M", "C"): 61.9, ("O", "M"): 15.0,
    }  # fmt: skip
    for k, v in holy.items():
        assert dd[k] == pytest.approx(v, abs=1e-11), k
    assert np.allclose(p["Z"] - p["O"], [-38.0, -7.8], rtol=0, atol=1e-14)
    # sides of each dyad as drawn
    chain = [  # (new point, from, length, from, length)
        ("B", "M", 50.0, "Z", 41.5),
        ("C", "M", 61.9, "Z", 39.3),
        ("D", "B", 55.8, "Z", 40.1),
        ("E", "D", 39.4, "C", 36.7),
        ("foot", "E", 65.7, "C", 49.0),
    ]
    sides = {n: _side(p[f], p[g], p[n]) for n, f, _, g, _ in chain}
    sw = scene_sweep(d)
    assert np.all(sw.status == 0)
    t = sw.theta
    n = t.size
    q = {"O": np.broadcast_to(p["O"], (n, 2)), "Z": np.broadcast_to(p["Z"], (n, 2))}
    q["M"] = p["O"] + 15.0 * np.stack([np.cos(t), np.sin(t)], -1)
    for name, f, rf, g, rg in chain:
        q[name] = dyad_point(q[f], rf, q[g], rg, sides[name])
    assert np.max(np.abs(sw.points["foot"] - q["foot"])) < 1e-10 * 100
    for name in ("B", "C", "D", "E"):
        assert np.max(np.abs(sw.points[name] - q[name])) < 1e-10 * 100
    # the walking stroke: a flat bottom about 40 units long within 1 unit of the lowest y
    y = q["foot"][:, 1]
    flat = q["foot"][y < y.min() + 1.0, 0]
    assert np.ptp(flat) > 30


# --- Chebyshev's lambda: exact points and the straight stretch --------------------------


def test_chebyshev_lambda_points_and_straight_stretch():
    d = scenes.data("chebyshev-lambda")
    # crank at 180 deg: A = (-1, 0), |A O4| = 3, B = (0.5, 2) exactly, P = 2B - A = (2, 4);
    # crank at 0: A = (1, 0), B = (1.5, sqrt 6), P = (2, 2 sqrt 6)
    sw = scene_sweep(d, [0.0, math.pi])
    assert np.all(sw.status == 0)
    assert np.allclose(sw.points["P"][1], [2.0, 4.0], rtol=0, atol=1e-12)
    assert np.allclose(sw.points["P"][0], [2.0, 2 * math.sqrt(6.0)], rtol=0, atol=1e-12)
    # crank 90..270 deg: P within 0.01 of y = 4 over a stroke of length 4 (Chebyshev)
    sw = scene_sweep(d, np.arange(90, 271) * DEG)
    p = sw.points["P"]
    assert np.all(sw.status == 0)
    assert p[:, 1].min() > 4 - 1e-12 and p[:, 1].max() < 4.01
    assert np.ptp(p[:, 0]) == pytest.approx(4.0, abs=1e-12)


# --- the reference's own contract -------------------------------------------------------


def test_reference_result_shapes_and_errors():
    d = scenes.data("double-butterfly-1")
    sw = scene_sweep(d, [0.1, 0.2])
    assert sw.theta.shape == (2,) and sw.status.dtype == np.int8 and sw.nit.shape == (2,)
    assert set(sw.points) == set(d["points"]) and set(sw.angles) == set(d["links"])
    assert all(v.shape == (2, 2) for v in sw.points.values())
    assert all(v.shape == (2,) for v in sw.angles.values())
    for key in ("points", "links", "ground", "input"):
        bad = {k: v for k, v in d.items() if k != key}
        with pytest.raises(ValueError, match=key):
            scene_sweep(bad)


@pytest.mark.slow
def test_double_butterflies_move_through_their_stated_range():
    for name in ("double-butterfly-1", "double-butterfly-2"):
        sw = _reference_sweep(name)
        ok = sw.status == 0
        # converged from the drawn angle up to the first failure, then never again
        first_bad = int(np.argmin(ok)) if not ok.all() else ok.size
        assert ok[:first_bad].all()
        assert first_bad - 1 >= 60  # at least 60 deg of motion
