"""Scenes at any scale (1e-300 to 1e300, as FourBar) and of any size: loading,
validation and planning stay near linear in the number of points and joints."""

import numpy as np
import planarkin as pk
import pytest

NAMES = ["fourbar", "jansen", "peaucellier", "stephenson3", "double-butterfly-1"]


def scaled(sc, f):
    d = sc.to_dict()
    return pk.Scene.from_dict(
        {**d, "points": {n: [x * f, y * f] for n, (x, y) in d["points"].items()}}
    )


@pytest.mark.parametrize("name", NAMES)
@pytest.mark.parametrize("e", [-1000, -664, 515, 995])
def test_power_of_two_scaling_is_exact_from_1e_301_to_1e_300(name, e):
    sc = pk.scenes.load(name)
    ref = sc.sweep(outputs="all")
    f = 2.0**e
    sw = scaled(sc, f).sweep(outputs="all")
    np.testing.assert_array_equal(sw.status, ref.status)
    for n, p in ref.points.items():
        if e >= -900:  # every scaled coordinate is a normal number: bit for bit
            np.testing.assert_array_equal(sw.points[n] / f, p)
        else:  # coordinates near zero become subnormal as drawn: their rounding only
            np.testing.assert_allclose(sw.points[n] / f, p, rtol=0, atol=1e-12)
    for n, a in ref.angles.items():
        np.testing.assert_allclose(sw.angles[n], a, rtol=0, atol=1e-12)


@pytest.mark.parametrize("name", NAMES)
@pytest.mark.parametrize("f", [1e-300, 1e-200, 1e155, 1e300])
def test_any_scale_gives_the_same_motion(name, f):
    sc = pk.scenes.load(name)
    size = max(np.ptp(np.array(list(sc.points.values())), axis=0))
    if size * f > 1e307:
        f = 1e307 / size
    ref = sc.sweep(outputs="all")
    sw = scaled(sc, f).sweep(outputs="all")
    np.testing.assert_array_equal(sw.status, ref.status)
    for n, p in ref.points.items():
        np.testing.assert_allclose(sw.points[n] / f, p, rtol=0, atol=1e-12 * size)


def test_coincident_points_are_measured_at_any_scale():
    d = pk.scenes.load("fourbar").to_dict()
    f = 1e-200
    pts = {n: [x * f, y * f] for n, (x, y) in d["points"].items()}
    a = pts["A"]
    pts["Q"] = [a[0] + 3e-213, a[1]]  # 6e-200 across the scene; 3e-213 from A
    links = {**d["links"], "coupler": [*d["links"]["coupler"], "Q"]}
    with pytest.raises(
        ValueError, match=r'links\.coupler.*"A" and "Q" coincide \(distance 2\.99'
    ) as e:
        pk.Scene.from_dict({**d, "points": pts, "links": links})
    assert "0e0" not in str(e.value)


def dyad_chain(n):
    """The seed four-bar with a strip of n triangles (n dyads) on its coupler."""
    d = pk.scenes.load("fourbar").to_dict()
    pts, links = dict(d["points"]), {k: list(v) for k, v in d["links"].items()}
    b = pts["B"]
    prev2, prev1 = "A", "B"
    for k in range(n):
        name = f"P{k}"
        pts[name] = [b[0] + (k + 1), b[1] + (1.0 if k % 2 == 0 else 0.0)]
        links[f"a{k}"] = [prev2, name]
        links[f"b{k}"] = [prev1, name]
        prev2, prev1 = prev1, name
    return {**d, "points": pts, "links": links, "outputs": None}


def test_a_thousand_dyad_chain_loads_plans_and_moves_rigidly():
    n = 1000
    sc = pk.Scene.from_dict(dyad_chain(n))
    plan = sc.plan("all")
    assert sum(s.kind == "dyad" for s in plan) == n + 1  # B and the strip
    sw = sc.sweep(outputs=["A", "B", f"P{n - 1}"])
    assert sw.success.all()
    # the strip of triangles is rigid: its last point keeps its distances to A and B
    for q in ("A", "B"):
        d = np.linalg.norm(sw.points[f"P{n - 1}"] - sw.points[q], axis=1)
        np.testing.assert_allclose(d, d[0], rtol=1e-9)


def test_a_link_with_many_points_is_checked_for_coincident_points():
    d = pk.scenes.load("fourbar").to_dict()
    rng = np.random.default_rng(1)
    pts = dict(d["points"])
    names = [f"T{i}" for i in range(16000)]
    for n, p in zip(names, rng.uniform(-3, 3, (16000, 2)), strict=True):
        pts[n] = p.tolist()
    links = {**d["links"], "coupler": [*d["links"]["coupler"], *names]}
    sc = pk.Scene.from_dict({**d, "points": pts, "links": links, "outputs": None})
    assert sc.sweep(outputs=["T15999"]).success.all()
    pts["T15999"] = list(pts["T7"])
    with pytest.raises(ValueError, match=r'"T7" and "T15999" coincide'):
        pk.Scene.from_dict({**d, "points": pts, "links": links, "outputs": None})


@pytest.mark.slow
def test_a_scene_may_not_ask_for_more_than_a_million_points():
    d = pk.scenes.load("fourbar").to_dict()
    pts = dict(d["points"])
    for i in range(1_000_000):
        pts[f"T{i}"] = [0.001 * (i % 1000), 0.001 * (i // 1000)]
    with pytest.raises(ValueError, match=r"points.*at most 1000000"):
        pk.Scene.from_dict({**d, "points": pts})
