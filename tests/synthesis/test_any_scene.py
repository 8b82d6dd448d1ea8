"""Any scene is a template (issue 19, item 3): ``Problem(scene, free=[...], target=...)``.
A four-bar function generator against Freudenstein's exact three-point solution written
here, a slider-crank's displacement law against its closed form, four-bar path
generators with and without prescribed timing against points from mpmath (truth.py),
each design verified by sweeping and tracing the real linkage; the double butterfly as
one scene among them."""

from __future__ import annotations

import math
import pickle

import numpy as np
import planarkin as pk
import pytest
from planarkin.synthesis import (
    TYPE_I,
    DesignSpace,
    FunctionTarget,
    PathPoints,
    PathTarget,
    Problem,
    SceneSpace,
    run_start,
    synthesize,
    verify_scene,
)
from truth import mp_solve


def _fourbar(a_x: float, b_y: float, d: float = 1.0) -> pk.Scene:
    # crank O2-A drawn at 0 deg, rocker O4-B drawn at 90 deg (a signed length each)
    return pk.Scene.from_dict({
        "points": {"O2": [0.0, 0.0], "O4": [d, 0.0], "A": [a_x, 0.0], "B": [d, b_y]},
        "links": {"ground": ["O2", "O4"], "crank": ["O2", "A"], "coupler": ["A", "B"],
                  "rocker": ["O4", "B"]},
        "ground": "ground",
        "input": {"link": "crank", "pivot": "O2"},
        "output": {"link": "rocker", "pivot": "O4"},
    })  # fmt: skip


def test_fourbar_function_generator_is_freudensteins_three_point_solution():
    # Freudenstein: K1 cos t4 - K2 cos t2 + K3 = cos(t2 - t4), K1 = d/a, K2 = d/c,
    # K3 = (a^2 - b^2 + c^2 + d^2) / (2 a c): three precision points, three linear unknowns
    d = 1.0
    t2 = np.radians([0.0, 30.0, 60.0])
    t4 = np.radians([90.0, 80.0, 65.0])
    k = np.linalg.solve(np.stack([np.cos(t4), -np.cos(t2), np.ones(3)], axis=1), np.cos(t2 - t4))
    a, c = d / k[0], d / k[1]  # signed: the crank drawn at 0 deg, the rocker at 90 deg
    b = math.sqrt(a * a + c * c + d * d - 2 * a * c * k[2])
    # the function: output rotations against input rotations, from the first point
    phi, out = t2 - t2[0], t4 - t4[0]
    dense = np.linspace(0.0, phi[-1], 31)
    target = FunctionTarget(phi, out, dense, np.interp(dense, phi, out))
    p = Problem(_fourbar(0.2, -0.35), free=["A.x", "B.y"], target=target)
    assert p.space.names == ["A.x", "B.y"] and p.x0.tolist() == [0.2, -0.35]
    res = run_start(p, p.x0, minimax=False)
    assert res.converged
    np.testing.assert_allclose(res.x, [a, c], rtol=1e-7)
    sc = p.scene(res.x)
    assert math.dist(sc.points["A"], sc.points["B"]) == pytest.approx(b, rel=1e-7)
    # the real linkage, swept, passes the three precision points on one branch
    sw = sc.sweep(sc.input_angle + t2 - t2[0], outputs="all", tol=1e-12)
    flip = math.pi if c < 0 else 0.0  # a negative rocker is drawn at t4 + pi
    np.testing.assert_allclose(np.angle(np.exp(1j * (sw.output - flip - t4))), 0.0, atol=1e-7)
    v = verify_scene(p, res.x)
    assert v["verified"] and v["max_error"] < 1e-7 and v["circuit"]["turning_points"] == 0


def test_slider_crank_displacement_law_from_its_closed_form():
    # x_B = r cos t + sqrt(l^2 - (r sin t - e)^2): recover r, l, e and the drawn crank angle
    r, rod, e, t0 = 40.0, 160.0, 20.0, math.radians(30.0)

    def x_b(t):
        return r * np.cos(t) + np.sqrt(rod**2 - (r * np.sin(t) - e) ** 2)

    phi = np.radians(np.linspace(0.0, 150.0, 7))
    dense = np.radians(np.linspace(0.0, 150.0, 61))
    target = FunctionTarget(phi, x_b(t0 + phi) - x_b(t0), dense, x_b(t0 + dense) - x_b(t0))
    drawn = pk.scenes.load("slider-crank-offset").to_dict()
    drawn["points"]["A"] = [37.0, 23.0]
    drawn["points"]["B"] = [190.0, 18.0]
    p = Problem(pk.Scene.from_dict(drawn), free=["A", "B"], target=target)
    assert np.max(np.abs(p.residuals(p.x0)[0])) > 1e-2  # the drawing is well off
    res = run_start(p, p.x0, minimax=False, maxiter=300)
    sc = p.scene(res.x)
    pts = sc.points
    assert math.hypot(*pts["A"]) == pytest.approx(r, rel=1e-6)
    assert math.dist(pts["A"], pts["B"]) == pytest.approx(rod, rel=1e-6)
    assert pts["B"][1] == pytest.approx(e, rel=1e-6)
    assert sc.input_angle == pytest.approx(t0, abs=1e-6)
    v = verify_scene(p, res.x)
    assert v["verified"] and v["max_error_relative"] < 1e-6


def _coupler(t2: float) -> tuple[float, float]:
    """The built-in four-bar's coupler point P (3 from A, 30 deg from A -> B) in mpmath."""
    s = mp_solve((6.0, 2.0, 5.0, 5.0), t2, "open")
    ax, ay = 2 * math.cos(t2), 2 * math.sin(t2)
    return ax + 3 * math.cos(s.t3 + math.radians(30)), ay + 3 * math.sin(s.t3 + math.radians(30))


def test_fourbar_path_generator_with_prescribed_timing():
    phi = np.radians([0.0, 40.0, 80.0, 120.0, 160.0])
    xy = np.array([_coupler(t) for t in phi])
    d = pk.scenes.load("fourbar").to_dict()
    rng = np.random.default_rng(1)
    for n in ("A", "B", "P", "O4"):
        d["points"][n] = [v + rng.normal(0, 0.05) for v in d["points"][n]]
    target = PathTarget("P", phi, xy, np.linspace(0.0, phi[-1], 41))
    # five points, ten coordinates: Burmester's limit for prescribed timing
    p = Problem(pk.Scene.from_dict(d), free=["O2", "O4", "A", "B", "P"], target=target)
    assert np.max(np.abs(p.residuals(p.x0)[0])) > 1e-2
    res = run_start(p, p.x0, maxiter=300)
    assert res.feasible
    sc = p.scene(res.x)
    sw = sc.sweep(sc.input_angle + phi, outputs="all", tol=1e-12)
    assert np.max(np.hypot(*(sw.points["P"] - xy).T)) < 1e-7
    v = verify_scene(p, res.x)
    assert v["verified"] and v["in_order"] and v["det_sign_changes"] == 0


def test_fourbar_path_generator_through_given_points_without_timing():
    # six points near the built-in four-bar's coupler curve (not on it): the inputs that
    # reach them are found with the linkage, in order
    phi0 = np.radians(np.linspace(0.0, 200.0, 6))
    xy = np.array([_coupler(t) for t in phi0]) + np.random.default_rng(4).normal(0, 0.1, (6, 2))
    target = PathPoints("P", xy, span=(-1.0, 2 * math.pi), phi0=phi0)
    space = SceneSpace(pk.scenes.load("fourbar"), ["A", "B", "P", "O4"], min_link=0.5)
    p = Problem(space, target, det_margin=0.05)
    assert p.timing == 6 and p.x0.size == 8 + 6
    assert np.max(np.abs(p.residuals(p.x0)[0])) > 1e-2
    res = run_start(p, p.x0, maxiter=300)
    assert res.feasible
    sc, found = p.scene(res.x), p.inputs(res.x)
    assert np.all(np.diff(found) >= target.order_margin * (1 - 1e-9))  # in order
    sw = sc.sweep(sc.input_angle + found, outputs="all", tol=1e-12)
    assert np.max(np.hypot(*(sw.points["P"] - xy).T)) < 1e-6
    # the whole way from the first point to the last on one branch, with its margin
    whole = sc.sweep(sc.input_angle + np.linspace(found[0], found[-1], 301), outputs="all")
    assert np.all(whole.status == 0)
    s = np.sign(whole.det[0])
    assert np.min(s * whole.det) >= 0.05 * (1 - 1e-6)
    v = verify_scene(p, res.x)
    assert v["verified"] and v["circuit"]["one_branch"]


def _type1() -> pk.Scene:
    d = pk.scenes.load("double-butterfly-1").to_dict()
    d["output"] = {"link": "output", "pivot": "K"}
    return pk.Scene.from_dict(d)


def test_the_double_butterfly_is_one_scene_among_them():
    sc = _type1()
    phi = np.linspace(0.05, 0.8, 9)
    dense = np.linspace(0.05, 0.8, 21)
    sw = sc.sweep(sc.input_angle + np.concatenate([phi, dense]), outputs="all", tol=1e-12)
    a0 = math.atan2(*(np.array(sc.points["H"]) - sc.points["K"])[::-1])
    rot = np.angle(np.exp(1j * (np.arctan2(*(sw.points["H"] - sw.points["K"]).T[::-1]) - a0)))
    target = FunctionTarget(phi, rot[:9], dense, rot[9:])
    free = ("C", "D", "F", "H", "I")
    template = Problem(DesignSpace(TYPE_I, sc.points, free, -20.0, 20.0), target,
                       det_margin=1e-3, closed_form=False)  # fmt: skip
    scene = Problem(SceneSpace(sc, free, -20.0, 20.0), target, det_margin=1e-3)
    x = template.space.x_of(sc.points)
    np.testing.assert_array_equal(scene.x0, x)
    x1 = x + np.random.default_rng(2).normal(0, 1e-3, x.size)
    for u, w in zip(template.residuals(x1), scene.residuals(x1), strict=True):
        np.testing.assert_allclose(u, w, rtol=1e-9, atol=1e-12)
    res = run_start(scene, x1, maxiter=100, minimax=False)
    assert verify_scene(scene, res.x)["max_error_relative"] < 1e-6


def test_bad_input_names_the_entry():
    sc = _fourbar(0.2, -0.35)
    phi = np.radians([0.0, 30.0])
    target = FunctionTarget(phi, -phi / 3, phi, -phi / 3)
    for free, word in ((["A.z"], "'A.z'"), (["Q"], "'Q'"), (["A", "A.x"], "repeats A.x"),
                       ([], "at least one"), ("A", "list"), ([3], "strings")):  # fmt: skip
        with pytest.raises(ValueError, match=word):
            Problem(sc, free=free, target=target)
    with pytest.raises(ValueError, match="free must name"):
        Problem(sc, target=target)
    with pytest.raises(ValueError, match="objective 'generated'"):
        Problem(sc, free=["A.x"], target=target, objective="generated")
    with pytest.raises(ValueError, match="lower"):
        SceneSpace(sc, ["A.x", "B.y"], lower=[0.0, 0.0, 0.0])
    no_output = sc.to_dict()
    no_output.pop("output")
    with pytest.raises(ValueError, match="output"):
        Problem(pk.Scene.from_dict(no_output), free=["A.x"], target=target)
    with pytest.raises(ValueError, match="target point 'Z'"):
        Problem(
            sc, free=["A.x"], target=PathPoints("Z", np.zeros((3, 2)) + [[0, 0], [1, 0], [2, 0]])
        )
    with pytest.raises(ValueError, match="span"):
        PathPoints("A", [[0, 0], [1, 1]], span=(1.0, 0.0))
    with pytest.raises(ValueError, match="phi0"):
        PathPoints("A", [[0, 0], [1, 1]], phi0=[0.0, 9.0])
    with pytest.raises(ValueError, match="xy"):
        PathPoints("A", [[0, 0]])


def test_a_scene_problem_runs_on_worker_processes():
    # a Scene does not pickle: its space travels as data and is built again
    phi = np.radians([0.0, 30.0, 60.0])
    out = np.radians([0.0, -10.0, -25.0])
    target = FunctionTarget(phi, out, phi, out)
    p = Problem(_fourbar(0.2, -0.35), free=["A.x", "B.y"], target=target)
    q = pickle.loads(pickle.dumps(p))
    assert q.space.names == p.space.names and q.space.drawn.points == p.space.drawn.points
    np.testing.assert_array_equal(q.residuals(q.x0)[0], p.residuals(p.x0)[0])
    res = synthesize(p, starts=2, samples=0, x0=[p.x0, p.x0 + 0.01], workers=1, maxiter=100,
                     minimax=False)  # fmt: skip
    assert [r.index for r in res.runs] == [0, 1] and res.best is not None
    assert res.best.converged and res.best.max_error < 1e-6


def test_watt_six_bar_function_generator_recovers_a_reachable_function():
    # the target: the drawn Watt II's own output rotation against its input rotation,
    # from the NumPy reference (not the Rust solver); C and D moved off it, synthesis by
    # exact gradients (and by forward differences) brings the real linkage back onto it
    from planarkin.reference import scene_sweep

    truth = pk.scenes.load("watt2")
    phi = np.radians(np.linspace(0.0, 300.0, 11))
    dense = np.radians(np.linspace(0.0, 300.0, 61))

    def out_of(t: np.ndarray) -> np.ndarray:
        # the rocker O6-D's rotation from its drawn angle
        sw = scene_sweep(truth.to_dict(), truth.input_angle + t)
        v = sw.points["D"] - sw.points["O6"]
        o6, dd = truth.points["O6"], truth.points["D"]
        a = np.arctan2(v[:, 1], v[:, 0]) - math.atan2(dd[1] - o6[1], dd[0] - o6[0])
        return np.angle(np.exp(1j * a))

    target = FunctionTarget(phi, out_of(phi), dense, out_of(dense))
    d = truth.to_dict()
    d["points"]["C"] = [d["points"]["C"][0] + 0.3, d["points"]["C"][1] - 0.2]
    d["points"]["D"] = [d["points"]["D"][0] - 0.2, d["points"]["D"][1] + 0.3]
    p = Problem(pk.Scene.from_dict(d), free=["C", "D"], target=target, det_margin=1e-3)
    assert np.max(np.abs(p.residuals(p.x0).r)) > 1e-3  # the start is well off
    for gradient in ("exact", "fd"):
        res = run_start(p, p.x0, minimax=False, gradient=gradient)
        assert res.feasible, gradient
        v = verify_scene(p, res.x)
        assert v["verified"] and v["max_error"] < 1e-7, (gradient, v["max_error"])
