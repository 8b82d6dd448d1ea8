"""Travel limits (DESIGN, "Limits"): a cylinder's stroke and a revolute joint's range stop
the motion from the drawn pose where they bind; checked against the law of cosines and a
four-bar's closed form (the limit's crossing found by root finding on it)."""

import math

import numpy as np
import planarkin as pk
import pytest
from scipy.optimize import brentq


def boom(limits=None):
    d = pk.scenes.load("hydraulic-boom").to_dict()
    if limits is None:
        d.pop("limits", None)
    else:
        d["limits"] = limits
    return pk.Scene.from_dict(d)


def test_the_built_in_boom_has_a_real_cylinders_stroke():
    sc = pk.scenes.load("hydraulic-boom")
    p = {n: np.asarray(v) for n, v in sc.points.items()}
    rho0 = np.hypot(*(p["E"] - p["C1"]))
    lo, hi = sc.limits["cylinder"]
    # a cylinder retracts to no less than about half its extended length
    assert 0.4 * (rho0 + hi) < rho0 + lo < rho0 + hi
    # the piston (rod's inner end R) stays inside the barrel C1-C2 over the whole stroke
    barrel, rod = np.hypot(*(p["C2"] - p["C1"])), np.hypot(*(p["E"] - p["R"]))
    assert rho0 + hi - rod <= barrel and rho0 + lo - rod >= 0.0
    np.testing.assert_allclose(sc.stroke(), (lo, hi), rtol=0, atol=1e-9 * rho0)
    sw = sc.sweep(outputs="all")
    assert sw.success.all()
    np.testing.assert_allclose(sw.theta[[0, -1]], (lo, hi), rtol=0, atol=1e-9 * rho0)


@pytest.mark.parametrize("predictor", ["continuation", "closed-form"])
def test_a_cylinder_stops_at_its_limits(predictor):
    sc = boom({"cylinder": [-150.0, 250.0]})
    p = {n: np.asarray(v) for n, v in sc.points.items()}
    g, b = np.hypot(*(p["C1"] - p["O"])), np.hypot(*(p["E"] - p["O"]))
    rho0 = np.hypot(*(p["E"] - p["C1"]))
    s = np.array([-400.0, -150.0, -149.0, 0.0, 120.0, 250.0, 251.0, 600.0])
    sw = sc.sweep(s, outputs="all", predictor=predictor)
    inside = (s >= -150.0) & (s <= 250.0)
    np.testing.assert_array_equal(sw.success, inside)
    np.testing.assert_array_equal(sw.status[~inside], pk.Status.LIMIT)
    want = np.where(s[~inside] < 0, -150.0, 250.0)
    np.testing.assert_allclose(sw.limit[~inside], want, rtol=1e-13, atol=0)
    assert np.isnan(sw.points["E"][~inside]).all()
    # inside: the boom by the law of cosines
    rho = rho0 + s[inside]
    alpha = np.arccos((g * g + b * b - rho**2) / (2 * g * b))
    boom_angle = math.atan2(*(p["C1"] - p["O"])[::-1]) + alpha
    want = p["O"] + b * np.stack([np.cos(boom_angle), np.sin(boom_angle)], -1)
    np.testing.assert_allclose(sw.points["E"][inside], want, rtol=0, atol=1e-9 * b)


def crank_rocker():
    # (ground 6, crank 2, coupler 5, rocker 5): Grashof, the crank turns fully
    a, b, c, d, t = 2.0, 5.0, 5.0, 6.0, math.radians(60.0)
    pa = np.array([a * math.cos(t), a * math.sin(t)])
    pb = closed_b(a, b, c, d, t)
    return {
        "name": "crank-rocker",
        "points": {"O2": [0.0, 0.0], "O4": [d, 0.0], "A": list(pa), "B": list(pb)},
        "links": {
            "ground": ["O2", "O4"],
            "crank": ["O2", "A"],
            "coupler": ["A", "B"],
            "rocker": ["O4", "B"],
        },
        "ground": "ground",
        "input": {"link": "crank", "pivot": "O2"},
    }, (a, b, c, d)


def closed_b(a, b, c, d, t):
    pa = np.array([a * math.cos(t), a * math.sin(t)])
    q = np.array([d, 0.0]) - pa
    dist = math.hypot(*q)
    along = (b * b - c * c + dist * dist) / (2 * dist)
    h = math.sqrt(b * b - along * along)
    e = q / dist
    return pa + along * e + h * np.array([-e[1], e[0]])


def rocker_angle(dims, t):
    a, b, c, d = dims
    pb = closed_b(a, b, c, d, t)
    return math.atan2(pb[1], pb[0] - d)


def test_a_revolute_limit_stops_the_crank_where_the_rocker_reaches_it():
    data, dims = crank_rocker()
    t0 = math.radians(60.0)
    phi0 = rocker_angle(dims, t0)
    lo, hi = -0.2, 0.3  # the rocker's turn relative to the ground, from the drawn pose
    data["limits"] = {"rock": {"links": ["ground", "rocker"], "range": [lo, hi]}}
    sc = pk.Scene.from_dict(data)

    def rel(t):
        return math.remainder(rocker_angle(dims, t) - phi0, math.tau)

    # the first crank angles each way where the rocker's turn reaches a bound
    grid = t0 + np.radians(np.arange(0.0, 361.0, 0.5))
    vals = np.array([rel(t) for t in grid])
    k = np.argmax((vals > hi) | (vals < lo))
    bound = hi if vals[k] > hi else lo
    up = brentq(lambda t: rel(t) - bound, grid[k - 1], grid[k], xtol=1e-14)
    grid = t0 - np.radians(np.arange(0.0, 361.0, 0.5))
    vals = np.array([rel(t) for t in grid])
    k = np.argmax((vals > hi) | (vals < lo))
    bound = hi if vals[k] > hi else lo
    down = brentq(lambda t: rel(t) - bound, grid[k], grid[k - 1], xtol=1e-14)

    theta = t0 + np.radians(np.arange(-180.0, 180.5, 1.0))
    sw = sc.sweep(theta, outputs="all")
    inside = (theta >= down) & (theta <= up)
    np.testing.assert_array_equal(sw.success, inside)
    stopped = ~inside
    # a value past the stop going up is past it going down too: named on the shorter way
    named = sw.limit[stopped]
    assert np.isin(np.round(named, 9), np.round([down, up], 9)).all()
    np.testing.assert_allclose(
        np.sort(np.unique(np.round(named, 9))), np.round(sorted([down, up]), 9), atol=1e-9
    )
    want = np.array([closed_b(*dims, t) for t in theta[inside]])
    np.testing.assert_allclose(sw.points["B"][inside], want, rtol=0, atol=1e-12)


def test_limits_are_saved_and_read_back(tmp_path):
    sc = boom({"cylinder": [-150.0, 250.0]})
    for suffix in (".json", ".toml"):
        again = pk.Scene.load(sc.save(tmp_path / f"boom{suffix}"))
        assert again.limits == {"cylinder": [-150.0, 250.0]}
        assert again.stroke() == sc.stroke()


@pytest.mark.parametrize(
    ("limits", "message"),
    [
        ({"cyl": [0, 1]}, r"^limits\.cyl: names no slot or prismatic pair"),
        ({"cylinder": [1, 2]}, r"^limits\.cylinder: must hold the drawn pose"),
        ({"cylinder": [2, -1]}, r"^limits\.cylinder: must have lo < hi"),
        ({"cylinder": [-1, float("inf")]}, r"^limits\.cylinder: must be finite"),
        ({"cylinder": "x"}, r"^limits\.cylinder: must be a range \[lo, hi\]"),
        ({"e": {"links": ["ground", "rod"], "range": [-1, 1]}}, r"^limits\.e\.links: .* share"),
        ({"e": {"links": ["boom"], "range": [-1, 1]}}, r"^limits\.e\.links: must be a pair"),
        ({"e": {"links": ["boom", "arm"], "range": [-1, 1]}}, r"^limits\.e\.links: \"arm\""),
        ({"e": {"link": ["boom", "rod"]}}, r"^limits\.e: must have the keys"),
        ([1, 2], r"^limits: must be a table"),
    ],
)
def test_bad_limits_are_one_line_errors_naming_the_entry(limits, message):
    with pytest.raises(ValueError, match=message):
        boom(limits)


def test_traces_and_circuits_stop_at_the_limits():
    # the boom's one circuit (joined at its stroke's dead points, -726 and 716 mm) is cut
    # by the cylinder's limits into two arcs, each from -200 to 300 mm
    sc = pk.scenes.load("hydraulic-boom")
    tr = sc.trace()
    np.testing.assert_allclose(sorted(tr.limits), [-200.0, 300.0], rtol=1e-12)
    assert not tr.closed and len(tr.turning_points) == 0
    assert tr.theta.min() >= -200.0 - 1e-9 and tr.theta.max() <= 300.0 + 1e-9
    circuits = sc.circuits()
    assert len(circuits) == 2
    for c in circuits:
        assert not c.full_turn
        np.testing.assert_allclose(c.range, (-200.0, 300.0), rtol=1e-12)


def test_a_revolute_limit_cuts_the_crank_rockers_trace_where_the_closed_form_says():
    data, dims = crank_rocker()
    t0 = math.radians(60.0)
    phi0 = rocker_angle(dims, t0)
    data["limits"] = {"rock": {"links": ["ground", "rocker"], "range": [-0.2, 0.3]}}
    sc = pk.Scene.from_dict(data)
    tr = sc.trace()
    assert len(tr.limits) == 2 and not tr.closed
    for at in tr.limits:
        rel = math.remainder(rocker_angle(dims, at) - phi0, math.tau)
        assert min(abs(rel + 0.2), abs(rel - 0.3)) < 1e-9
    # the sweep stops at the same inputs
    sw = sc.sweep(np.linspace(t0 - 2.5, t0 + 2.5, 101))
    named = np.unique(np.round(sw.limit[~np.isnan(sw.limit)], 9))
    np.testing.assert_allclose(np.sort(named), np.sort(np.round(tr.limits, 9)), atol=1e-9)
