"""Scenes (pk.Scene) against independent truths: the four-bar's closed form and pk.FourBar,
the Peaucellier line, a chain of circle intersections written here, rigidity of every link,
the NumPy reference (a different route: all joint equations at once, no plan), scaling,
and bad input."""

from __future__ import annotations

import json
import math

import numpy as np
import planarkin as pk
import pytest
from _support import examples
from hypothesis import HealthCheck, given, settings
from hypothesis import strategies as st
from planarkin.reference import scene_sweep

DEG = math.pi / 180
TAU = 2 * math.pi


def fourbar_dict(mode: float = 1.0, coupler=(3.0, 30 * DEG)) -> dict:
    """The seed four-bar (6, 2, 5, 5) drawn at theta2 = 0 in the open (+1) or crossed mode,
    with a coupler point P at distance p from A, angle delta from A->B."""
    b = (4.0, mode * math.sqrt(21.0))
    t3 = math.atan2(b[1], b[0] - 2.0)
    p, delta = coupler
    return {
        "name": "seed four-bar",
        "points": {
            "O2": [0.0, 0.0],
            "O4": [6.0, 0.0],
            "A": [2.0, 0.0],
            "B": list(b),
            "P": [2.0 + p * math.cos(t3 + delta), p * math.sin(t3 + delta)],
        },
        "links": {
            "ground": ["O2", "O4"],
            "crank": ["O2", "A"],
            "coupler": ["A", "B", "P"],
            "rocker": ["O4", "B"],
        },
        "ground": "ground",
        "input": {"link": "crank", "pivot": "O2"},
        "output": {"link": "rocker", "pivot": "O4"},
    }


def dist(a, b):
    return np.hypot(*(np.asarray(a) - np.asarray(b)).T)


# --- the four-bar: pk.FourBar and the closed form ----------------------------------


@pytest.mark.parametrize(("sign", "mode"), [(1.0, "open"), (-1.0, "crossed")])
def test_fourbar_scene_agrees_with_fourbar(sign, mode):
    sc = pk.Scene.from_dict(fourbar_dict(sign))
    sw = sc.sweep(omega=1.5)
    fb = pk.FourBar(6, 2, 5, 5)
    ref = fb.sweep(sw.theta, mode=mode, omega2=1.5)
    t3, t4 = fb.closed_form(sw.theta, mode=mode)
    assert sw.success.all() and ref.success.all()
    np.testing.assert_allclose(sw.angles["coupler"], t3, atol=1e-12, rtol=0)
    np.testing.assert_allclose(sw.angles["rocker"], t4, atol=1e-12, rtol=0)
    np.testing.assert_allclose(sw.angles["crank"], np.angle(np.exp(1j * sw.theta)), atol=1e-15)
    np.testing.assert_allclose(sw.angular_velocities["rocker"], ref.omega4, atol=1e-12, rtol=0)
    np.testing.assert_allclose(sw.angular_velocities["coupler"], ref.omega3, atol=1e-12, rtol=0)
    # the coupler point from the closed-form angles
    x, y = fb.coupler_point(sw.theta, t3, 3.0, 30 * DEG)
    np.testing.assert_allclose(sw.points["P"], np.stack([x, y], -1), atol=1e-12, rtol=0)
    # the branch: sign of the dyad's sine is the mode's, |det| = |sin(theta4 - theta3)|
    np.testing.assert_allclose(sw.det, np.sin(t4 - t3), atol=1e-12)
    assert (np.sign(sw.det) == sign).all()


def test_fourbar_velocity_by_finite_difference():
    sc = pk.Scene.from_dict(fourbar_dict())
    h = 1e-6
    t = np.array([0.3, 1.7, 4.0])
    sw = sc.sweep(t, omega=1.0)
    fwd, bwd = sc.sweep(t + h), sc.sweep(t - h)
    for n in ("B", "P"):
        fd = (fwd.points[n] - bwd.points[n]) / (2 * h)
        np.testing.assert_allclose(sw.velocities[n], fd, atol=1e-8)


def test_non_grashof_spans_are_not_assemblable_exactly_where_the_closed_form_says():
    # (4, 3, 1.5, 2): the crank cannot turn fully
    r1, r2, r3, r4 = 4.0, 3.0, 1.5, 2.0
    fb = pk.FourBar(r1, r2, r3, r4)
    t = np.linspace(-math.pi, math.pi, 721)
    t30, _ = fb.closed_form(0.0, mode="open")
    a = (r2, 0.0)
    b = (a[0] + r3 * math.cos(t30), r3 * math.sin(t30))
    d = {
        "points": {"O2": [0, 0], "O4": [r1, 0], "A": list(a), "B": list(b)},
        "links": {"g": ["O2", "O4"], "c": ["O2", "A"], "k": ["A", "B"], "r": ["O4", "B"]},
        "ground": "g",
        "input": {"link": "c", "pivot": "O2"},
    }
    sw = pk.Scene.from_dict(d).sweep(t)
    _, t4 = fb.closed_form(t, mode="open")
    cst = fb.closed_form_status(t, mode="open")
    lim = fb.limits()
    near = np.min(np.abs(np.subtract.outer(t, lim.toggles)), axis=1) < 1e-9
    agree = (sw.status == pk.Status.NOT_ASSEMBLABLE) == (cst == pk.Status.NOT_ASSEMBLABLE)
    assert agree[~near].all()
    assert (sw.status == pk.Status.NOT_ASSEMBLABLE).sum() > 100
    ok = sw.success & (cst == 0)
    np.testing.assert_allclose(sw.angles["r"][ok], t4[ok], atol=1e-12)


# --- the built-in scenes -----------------------------------------------------------


@pytest.fixture(scope="module", params=pk.scenes.names())
def builtin(request):
    sc = pk.scenes.load(request.param)
    return sc, sc.sweep(outputs="all")


def test_builtin_rigidity_and_orientation(builtin):
    sc, sw = builtin
    ok = sw.success
    assert ok.sum() >= 60, sw.statuses()
    drawn = sc.points
    for link, pts in sc.links.items():
        for i, a in enumerate(pts):
            for b in pts[i + 1 :]:
                d0 = dist(drawn[a], drawn[b])
                err = np.abs(dist(sw.points[a][ok], sw.points[b][ok]) - d0)
                assert err.max() < 1e-12 * max(1.0, d0), (link, a, b)
        for a, b, c in zip(pts, pts[1:], pts[2:], strict=False):

            def cross(p, q, r):
                u, v = np.asarray(q) - np.asarray(p), np.asarray(r) - np.asarray(p)
                return u[..., 0] * v[..., 1] - u[..., 1] * v[..., 0]

            c0 = cross(drawn[a], drawn[b], drawn[c])
            now = cross(sw.points[a][ok], sw.points[b][ok], sw.points[c][ok])
            if abs(c0) > 1e-9:
                assert (np.sign(now) == np.sign(c0)).all(), (link, a, b, c)


#: the scenes whose reference sweep (pure Python) takes over a second: not in the inner loop
SLOW_REFERENCE = {"double-butterfly-1", "double-butterfly-2", "peaucellier"}


@pytest.mark.parametrize(
    "builtin",
    [pytest.param(n, marks=pytest.mark.slow) if n in SLOW_REFERENCE else n
     for n in pk.scenes.names()],
    indirect=True,
)  # fmt: skip
def test_builtin_matches_the_numpy_reference(builtin):
    sc, sw = builtin
    ref = scene_sweep(sc.to_dict(), sw.theta)
    both = sw.success & (ref.status == 0)
    assert both.sum() >= 0.9 * min(sw.success.sum(), (ref.status == 0).sum())
    size = max(np.ptp(np.array(list(sc.points.values())), axis=0))
    for n in sc.points:
        err = np.abs(sw.points[n][both] - ref.points[n][both]).max(initial=0)
        assert err <= 1e-10 * size, (n, err)


def test_builtin_continuity(builtin):
    sc, sw = builtin
    size = max(np.ptp(np.array(list(sc.points.values())), axis=0))
    ok = sw.success[1:] & sw.success[:-1]
    for n in sc.points:
        step = np.hypot(*np.diff(sw.points[n], axis=0).T)[ok]
        # 1 degree steps: no point moves more than the scene's size in one step
        assert (step < 0.5 * size).all(), n


def test_builtin_round_trips(builtin, tmp_path):
    sc, sw = builtin
    for suffix in (".json", ".toml"):
        p = sc.save(tmp_path / f"scene{suffix}")
        again = pk.Scene.load(p)
        assert again == sc
        sw2 = again.sweep(outputs="all")
        np.testing.assert_array_equal(sw2.coords, sw.coords)
        np.testing.assert_array_equal(sw2.status, sw.status)


def test_peaucellier_draws_an_exact_straight_line():
    sc = pk.scenes.load("peaucellier")
    d = sc.to_dict()
    sw = sc.sweep(np.linspace(-math.pi, math.pi, 3601))
    o, q = np.array(d["points"]["O"]), np.array(d["points"]["Q"])
    p0 = np.array(d["points"]["P"])
    a, b = dist(o, d["points"]["A"]), dist(d["points"]["A"], d["points"]["C"])
    r = dist(o, q)
    # inversion in the circle about O of radius^2 a^2 - b^2 maps the crank circle through
    # O to the line perpendicular to O->Q at distance (a^2 - b^2) / (2 r) from O
    e = (q - o) / r
    along = (sw.points["P"][sw.success] - o) @ e
    assert sw.success.sum() > 1000
    np.testing.assert_allclose(along, (a * a - b * b) / (2 * r), rtol=1e-12, atol=0)
    assert abs((p0 - o) @ e - (a * a - b * b) / (2 * r)) < 1e-12
    assert np.ptp((sw.points["P"][sw.success] - o) @ np.array([-e[1], e[0]])) > 1.0


def _circle(p, rp, q, rq, side):
    """The intersection of circles (p, rp), (q, rq) left (+1) or right (-1) of p -> q."""
    u = q - p
    d = np.hypot(u[:, 0], u[:, 1])
    a = (rp * rp - rq * rq + d * d) / (2 * d)
    h = np.sqrt(rp * rp - a * a)
    n = np.stack([-u[:, 1], u[:, 0]], -1) / d[:, None]
    return p + (a / d)[:, None] * u + side * h[:, None] * n


def test_jansen_foot_against_a_chain_of_circle_intersections():
    sc = pk.scenes.load("jansen")
    d = sc.to_dict()
    pts = {k: np.array(v, dtype=float) for k, v in d["points"].items()}
    sw = sc.sweep(outputs=["foot"])
    assert [s.kind for s in sc.plan(["foot"])] == ["dyad"] * len(sc.plan(["foot"]))
    n = len(sw.theta)
    known = {k: np.repeat(pts[k][None], n, 0) for k in d["links"][d["ground"]]}  # ground points
    piv = d["input"]["pivot"]
    crank = [p for p in d["links"][d["input"]["link"]] if p != piv][0]
    rc = dist(pts[piv], pts[crank])
    known[crank] = pts[piv] + rc * np.stack([np.cos(sw.theta), np.sin(sw.theta)], -1)

    def side(p, q, r):
        u, v = pts[q] - pts[p], pts[r] - pts[p]
        return np.sign(u[0] * v[1] - u[1] * v[0])

    # each remaining point from two known points on its links, as a user would chain them
    remaining = [p for p in pts if p not in known]
    on = {p: [ls for ls in d["links"].values() if p in ls] for p in pts}
    while remaining:
        for p in remaining:
            rigid = [ls for ls in on[p] if sum(q in known for q in ls) >= 2]
            if rigid:  # a link with two known points carries p rigidly
                a, b = [q for q in rigid[0] if q in known][:2]
                za, zb, zp = (complex(*pts[q]) for q in (a, b, p))
                m = (zp - za) / (zb - za)
                ka, kb = known[a] @ [1, 1j], known[b] @ [1, 1j]
                z = ka + m * (kb - ka)
                known[p] = np.stack([z.real, z.imag], -1)
                remaining.remove(p)
                break
            ks = []
            for ls in on[p]:
                k = [q for q in ls if q in known and q != p]
                if k:
                    ks.append(k[0])
            ks = list(dict.fromkeys(ks))
            if len(ks) >= 2:
                a, b = ks[:2]
                known[p] = _circle(
                    known[a], dist(pts[a], pts[p]), known[b], dist(pts[b], pts[p]), side(a, b, p)
                )
                remaining.remove(p)
                break
        else:
            raise AssertionError(f"no circle chain for {remaining}")
    assert sw.success.all()
    np.testing.assert_allclose(sw.points["foot"], known["foot"], atol=1e-11, rtol=0)
    ref = scene_sweep(d, sw.theta)
    np.testing.assert_allclose(sw.points["foot"], ref.points["foot"], atol=1e-10, rtol=0)


# --- plans: only what the outputs need ---------------------------------------------


def test_plan_prunes_to_the_requested_outputs():
    # without a declared output (a declared one is always reported: issue 32, item 8)
    d = pk.scenes.data("watt2")
    d.pop("output")
    sc = pk.Scene.from_dict(d)
    full = sc.plan("all")
    assert len(full) == 2 and all(s.kind == "dyad" for s in full)
    first = full[0].points[0]
    one = sc.plan([first])
    assert len(one) == 1 and one[0].unknowns == full[0].unknowns
    assert one[0].points[0] == first and set(one[0].points) <= set(full[0].points)
    sw = sc.sweep(outputs=[first])
    assert set(sw.points) < set(sc.points)
    np.testing.assert_array_equal(sw.points[first], sc.sweep(outputs="all").points[first])


def test_group_plans():
    for name, n in [("stephenson3", 4), ("double-butterfly-1", 6), ("double-butterfly-2", 6)]:
        plan = pk.scenes.load(name).plan("all")
        assert [s.kind for s in plan] == ["group"], name
        assert len(plan[0].unknowns) == n


def test_a_failing_loop_the_output_does_not_need_leaves_the_output_solved():
    d = fourbar_dict()
    # a dyad hung from the coupler point P and a ground point far away: it assembles only
    # over part of the turn
    d["points"]["G"] = [9.0, 0.0]
    p = np.array(d["points"]["P"])
    d["points"]["E"] = [float(p[0] + 3.2), float(p[1] - 1.0)]
    d["links"]["ground"] = ["O2", "O4", "G"]
    d["links"]["e1"] = ["P", "E"]
    d["links"]["e2"] = ["G", "E"]
    sc = pk.Scene.from_dict(d)
    sw = sc.sweep(outputs="all")
    bad = sw.point_status["E"] != 0
    assert bad.sum() > 20 and (~bad).sum() > 20
    # past the fold: LIMIT where the linkage has another assembly (the crossed four-bar
    # carries E), NOT_ASSEMBLABLE where it has none
    expected = [
        pk.Status.LIMIT if sc.assemblies(t) else pk.Status.NOT_ASSEMBLABLE for t in sw.theta[bad]
    ]
    assert {pk.Status.LIMIT, pk.Status.NOT_ASSEMBLABLE} <= set(expected)
    np.testing.assert_array_equal(sw.point_status["E"][bad], expected)
    np.testing.assert_array_equal(sw.status[bad], expected)
    assert (sw.point_status["B"] == 0).all() and np.isfinite(sw.points["P"]).all()
    assert np.isnan(sw.points["E"][bad]).all()
    only = sc.sweep(outputs=["P"])
    assert only.success.all() and "E" not in only.points
    np.testing.assert_array_equal(only.points["P"], sw.points["P"])


# --- scale-free ----------------------------------------------------------------------


@pytest.mark.parametrize("name", ["jansen", "stephenson3", "double-butterfly-1"])
@pytest.mark.parametrize("s", [2.0**-30, 2.0**40, 1e-9, 1e9, 3.7])
def test_scaling_the_drawing(name, s):
    d = pk.scenes.data(name)
    sw = pk.scenes.load(name).sweep(outputs="all")
    d["points"] = {k: [v[0] * s, v[1] * s] for k, v in d["points"].items()}
    sws = pk.Scene.from_dict(d).sweep(outputs="all")
    np.testing.assert_array_equal(sws.status, sw.status)
    if math.log2(s).is_integer():
        np.testing.assert_array_equal(sws.coords, sw.coords * s)
        np.testing.assert_array_equal(sws.nit, sw.nit)
    else:
        # rounding of the scaled drawing moves a pose by about eps / conditioning
        tol = np.where(sw.success, np.maximum(1e-11, 1e-14 / np.abs(sw.det)), np.inf)
        err = np.nanmax(np.abs(sws.coords / s - sw.coords), axis=(1, 2), initial=0)
        assert (err <= tol).all()
        for k in sw.angles:
            assert (np.abs(sws.angles[k] - sw.angles[k])[sw.success] <= tol[sw.success]).all()


# --- the sweep's contract ------------------------------------------------------------


def test_sweep_follows_the_drawn_assembly_from_the_drawn_angle():
    sc = pk.scenes.load("stephenson3")
    t = sc.input_angle + np.array([1.0, 0.5, 0.0, -0.5])
    sw = sc.sweep(t, outputs="all")
    assert sw.success.all()
    # the drawn pose comes back at the drawn angle
    for n, xy in sc.points.items():
        np.testing.assert_allclose(sw.points[n][2], xy, atol=1e-12)
    # and the det keeps the drawn sign
    assert (np.sign(sw.det) == np.sign(sw.det[2])).all()


def test_group_iterations_per_point():
    # continuation of a group: under 1.5 Newton iterations per point at tol 1e-9, 1 deg steps
    for name in ("stephenson3", "double-butterfly-1", "double-butterfly-2"):
        sc = pk.scenes.load(name)
        t = sc.input_angle + np.arange(61) * DEG
        sw = sc.sweep(t)
        assert sw.success.all(), name
        assert sw.nit[1:].mean() < 1.5, (name, sw.nit.mean())


def test_results_are_views_and_shapes():
    sc = pk.scenes.load("fourbar")
    sw = sc.sweep(np.linspace(0, 1, 7), outputs=["P", "rocker"], omega=2.0)
    assert sw.points["P"].shape == (7, 2) and sw.angles["rocker"].shape == (7,)
    assert sw.points["P"].base is not None  # a view of sw.coords
    assert sw.step_det.shape == (7, len(sw.plan)) and sw.det.shape == (7,)
    assert sw.velocities is not None and sw.velocities["P"].shape == (7, 2)
    assert len(repr(sw)) < 200


# --- bad scenes and bad arguments ----------------------------------------------------


@pytest.mark.parametrize(
    ("edit", "message"),
    [
        (lambda d: d["links"]["coupler"].append("Q"), "links.coupler: unknown point 'Q'"),
        (
            lambda d: d["links"].__setitem__("coupler", ["A"]),
            "links.coupler: a link needs at least 2",
        ),
        (
            lambda d: d["points"].__setitem__("B", [2.0, 0.0]),
            "links.coupler: points 'A' and 'B' coincide",
        ),
        (
            lambda d: d["points"].__setitem__("B", [math.nan, 1.0]),
            "points.B: coordinates must be finite",
        ),
        (lambda d: d.__setitem__("ground", "frame"), "ground: 'frame' is not a link"),
        (lambda d: d["input"].__setitem__("link", "crankk"), "input.link: 'crankk' is not a link"),
        (
            lambda d: d["input"].__setitem__("pivot", "A"),
            "input.pivot: 'A' is not on the ground link",
        ),
        (
            lambda d: d["links"].__setitem__("brace", ["A", "O4"]),
            "mobility: Gruebler's count gives M = 0",
        ),
        (
            lambda d: (d["links"].pop("rocker"), d.pop("output")),
            "mobility: Gruebler's count gives M = 2",
        ),
        (lambda d: d.__setitem__("ouputs", ["P"]), "scene: unknown keys ['ouputs']"),
        (lambda d: d.__setitem__("outputs", ["Z"]), "outputs[0]: 'Z' is not a point or link"),
        (lambda d: d["points"].__setitem__("Z", [1.0, 1.0]), "points.Z: is on no link"),
        (lambda d: d["points"].__setitem__("A", [1.0]), "points.A: must be a pair"),
        (lambda d: d.pop("input"), "input: is required"),
    ],
)
def test_bad_scenes_name_the_entry(edit, message):
    d = fourbar_dict()
    edit(d)
    with pytest.raises(ValueError) as e:
        pk.Scene.from_dict(d)
    assert str(e.value).replace('"', "'").startswith(message), str(e.value)


def test_a_special_geometry_that_moves_is_reported():
    # a parallelogram (6, 2, 6, 2) with a second crank in parallel: Gruebler says 0 but it
    # moves; drawn so, the count rejects it. Drawn at a dead point, the rank check does.
    d = {
        "points": {"O2": [0, 0], "O4": [6, 0], "A": [0, 2], "B": [6, 2], "O6": [3, 0], "C": [3, 2]},
        "links": {
            "ground": ["O2", "O4", "O6"],
            "crank": ["O2", "A"],
            "coupler": ["A", "B", "C"],
            "rocker": ["O4", "B"],
            "extra": ["O6", "C"],
        },
        "ground": "ground",
        "input": {"link": "crank", "pivot": "O2"},
    }
    with pytest.raises(ValueError, match="mobility: Gruebler's count gives M = 0"):
        pk.Scene.from_dict(d)
    toggle = fourbar_dict()
    toggle["points"].update({"O4": [12.0, 0.0], "B": [6.0, 0.0], "P": [4.0, 1.0]})
    with pytest.raises(ValueError, match="mobility: the constraint Jacobian at the drawn pose"):
        pk.Scene.from_dict(toggle)


def test_collinear_ternary_is_valid():
    d = fourbar_dict(coupler=(7.5, 0.0))  # P on the line A-B, beyond B
    sw = pk.Scene.from_dict(d).sweep()
    assert sw.success.all()


def test_bad_sweep_arguments():
    sc = pk.scenes.load("fourbar")
    for kw, name in [
        ({"tol": 0}, "tol"),
        ({"max_iter": 0}, "max_iter"),
        ({"max_step": -1.0}, "max_step"),
        ({"omega": "x"}, "omega"),
        ({"outputs": "some"}, "outputs"),
        ({"omega": math.inf}, "omega"),
    ]:
        with pytest.raises(ValueError, match=name):
            sc.sweep(**kw)
    with pytest.raises(ValueError, match="theta"):
        sc.sweep(np.zeros((2, 2)))
    with pytest.raises(ValueError, match="path must end in .json or .toml"):
        pk.Scene.load("scene.yaml")
    with pytest.raises(ValueError, match="unknown built-in scene"):
        pk.scenes.load("nope")


def test_nan_input_angle_is_non_finite_and_the_rest_solve():
    sc = pk.scenes.load("stephenson3")
    t = sc.input_angle + np.array([0.0, 0.01, math.nan, 0.02])
    sw = sc.sweep(t)
    assert sw.status.tolist() == [0, 0, pk.Status.NON_FINITE, 0]


# --- hypothesis: random valid scenes built by adding dyads to a four-bar ----------------


@st.composite
def dyad_scenes(draw):
    d = fourbar_dict()
    rng = np.random.default_rng(draw(st.integers(0, 2**32 - 1)))
    names = ["A", "B", "P", "O2", "O4"]
    for k in range(draw(st.integers(1, 4))):
        a, b = rng.choice(len(names), 2, replace=False)
        pa, pb = np.array(d["points"][names[a]]), np.array(d["points"][names[b]])
        # a new point off the line a-b, at a generic place
        mid = 0.5 * (pa + pb) + rng.normal(0, 2.0, 2)
        name = f"X{k}"
        d["points"][name] = mid.tolist()
        d["links"][f"l{k}a"] = [names[a], name]
        d["links"][f"l{k}b"] = [names[b], name]
        names.append(name)
    return d


@settings(max_examples=examples(40), deadline=None, suppress_health_check=[HealthCheck.too_slow])
@given(dyad_scenes())
def test_random_dyad_scenes_solve_and_round_trip(d):
    try:
        sc = pk.Scene.from_dict(d)
    except ValueError as e:  # a random point may land on a dead point or ground line
        assert "mobility" in str(e) or "coincide" in str(e)
        return
    t = sc.input_angle + np.linspace(0, 0.2, 9)
    sw = sc.sweep(t, outputs="all")
    assert all(s.kind == "dyad" for s in sc.plan("all"))
    again = pk.Scene.from_dict(json.loads(json.dumps(sc.to_dict())))
    np.testing.assert_array_equal(again.sweep(t, outputs="all").coords, sw.coords)
    ref = scene_sweep(sc.to_dict(), t)
    both = sw.success & (ref.status == 0)
    assert both[0]
    for n in sc.points:
        np.testing.assert_allclose(sw.points[n][both], ref.points[n][both], atol=1e-9)


def test_a_dyad_hung_from_a_group():
    # the Stephenson III with a dyad on its group and a ground point: a plan [group, dyad],
    # the dyad solved by the per-angle path after the group's continuation
    d = pk.scenes.data("stephenson3")
    j4, j5 = np.array(d["points"]["j4"]), np.array(d["points"]["j5"])
    g = (j4 + j5) / 2 + np.array([0.3, 2.0])
    d["points"]["G"] = g.tolist()
    d["points"]["X"] = ((j4 + g) / 2 + np.array([-0.4, 0.1])).tolist()
    d["links"][d["ground"]] = [*d["links"][d["ground"]], "G"]
    d["links"]["x1"] = ["j4", "X"]
    d["links"]["x2"] = ["G", "X"]
    d["outputs"] = ["X"]
    sc = pk.Scene.from_dict(d)
    assert [s.kind for s in sc.plan()] == ["group", "dyad"]
    t = sc.input_angle + np.linspace(0, 0.6, 31)
    sw = sc.sweep(t, omega=1.0)
    ref = scene_sweep(sc.to_dict(), t)
    both = sw.success & (ref.status == 0)
    assert both.sum() > 20
    np.testing.assert_allclose(sw.points["X"][both], ref.points["X"][both], atol=1e-10)
    h = 1e-6
    fd = (sc.sweep(t + h).points["X"] - sc.sweep(t - h).points["X"]) / (2 * h)
    np.testing.assert_allclose(sw.velocities["X"][both], fd[both], atol=1e-6)


# --- the reference's det ------------------------------------------------------------

TRIPLE_ROCKER = (5.0, 3.0, 4.0, 2.5)


def test_the_scene_reference_det_is_signed_and_vanishes_at_dead_points():
    """The reference's det is the Hadamard ratio of its own Jacobian: not the kernel's
    number, but the same branch (a fixed sign relation) and the same zeros."""
    fb = pk.FourBar(*TRIPLE_ROCKER)
    sc = fb.to_scene(mode="crossed")
    theta = sc.input_angle + np.linspace(-1.5, 1.5, 301)
    api = sc.sweep(theta)
    ref = pk.reference.scene_sweep(sc.to_dict(), theta)
    both = api.success & ref.success
    assert both.sum() > 250
    assert len(set(np.sign(api.det[both] * ref.det[both]))) == 1
    assert np.all(np.abs(ref.det[both]) <= 1.0)
    # towards a toggle both go to zero together
    toggle = max(fb.limits("crossed").toggles)
    near = sc.input_angle + toggle - 10.0 ** -np.arange(1.0, 9.0)
    a, r = sc.sweep(near).det, pk.reference.scene_sweep(sc.to_dict(), near).det
    assert np.isfinite(a).all() and np.isfinite(r).all()
    assert np.all(np.diff(np.abs(a)) < 0) and np.all(np.diff(np.abs(r)) < 0)
    assert abs(a[-1]) < 1e-3 and abs(r[-1]) < 1e-3
