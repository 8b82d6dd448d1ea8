"""Path refinement: the objective's and constraints' exact derivatives against central
differences of whole sweeps (four-bar, a hand-drawn Watt II six-bar, an offset
slider-crank), exact recovery of linkages whose closed-form coupler curves are the targets
(every drawn coordinate moved by 1.5 % of the target's size, about 2 % a point), starting
inputs by assignment, the user's constraints honoured, and bad input refused by name."""

from __future__ import annotations

import math

import numpy as np
import planarkin as pk
import pytest
from _path_linkages import (
    WATT2,
    fourbar_curve,
    fourbar_scene,
    perturbed,
    slider_curve,
    slider_scene,
)
from planarkin.synthesis.path.model import (
    INIT_SAMPLES,
    PathModel,
    fourbar_joints,
    initial_inputs,
)
from planarkin.synthesis.path.refine import refine
from planarkin.synthesis.path.targets import CurveTarget
from planarkin.synthesis.path.verify import verify

TURN = np.linspace(0.0, 2 * math.pi, 19)[:-1]
CRANK_ROCKER = ((0.0, 0.0), (6.0, 0.0), 2.0, 5.0, 5.0, 1.5, 2.0)


def _fd_check(model: PathModel, seed: int) -> tuple[float, float, float]:
    """Largest differences (relative to the largest entry) between the exact derivatives
    of the residuals, the objective and the constraints and their central differences."""
    rng = np.random.default_rng(seed)
    u = model.u0 + rng.normal(0.0, 1e-3, model.u0.size)
    jac = model.jacobians(u)
    jr, jc = jac["r"], jac["cons"]
    grad = 2 * jr.T @ model.residuals(u)
    h = 1e-6
    fr, fc, fg = np.zeros_like(jr), np.zeros_like(jc), np.zeros_like(grad)
    for i in range(u.size):
        e = np.zeros(u.size)
        e[i] = h
        fr[:, i] = (model.residuals(u + e) - model.residuals(u - e)) / (2 * h)
        fc[:, i] = (model.constraints(u + e) - model.constraints(u - e)) / (2 * h)
        fg[i] = (model.objective(u + e) - model.objective(u - e)) / (2 * h)
    assert np.all(model.values(u)["ok"])
    return (
        float(np.abs(fr - jr).max() / np.abs(jr).max()),
        float(np.abs(fg - grad).max() / np.abs(grad).max()),
        float(np.abs(fc - jc).max() / np.abs(jc).max()),
    )


def _fourbar_model(timing: bool = False) -> PathModel:
    _, _, p = fourbar_curve(*CRANK_ROCKER, TURN)
    # a target near (not on) the curve: the residuals are not zero
    q = p + 0.05 * np.stack([np.cos(3 * TURN), np.sin(2 * TURN)], -1)
    target = CurveTarget(q, "closed", TURN + 0.3 if timing else None)
    sc = pk.Scene.from_dict(fourbar_scene(*CRANK_ROCKER, 0.2))
    return PathModel(sc, "P", target, TURN + 0.02, box=((-1, 7), (-1, 5)), max_link_ratio=4.0)


def test_objective_gradient_of_a_fourbar_matches_central_differences() -> None:
    for timing in (False, True):
        errs = _fd_check(_fourbar_model(timing), 1)
        assert max(errs) < 1e-6, errs


def test_objective_gradient_of_a_watt2_sixbar_matches_central_differences() -> None:
    sc = pk.Scene.from_dict(WATT2)
    # the tracer's own curve (a sweep) moved off by a wobble: any points serve as a target
    sw = sc.sweep(TURN, outputs="all")
    p = sw.points["P"] + 0.1 * np.stack([np.sin(2 * TURN), np.cos(TURN)], -1)
    model = PathModel(sc, "P", CurveTarget(p, "closed"), TURN - 0.03)
    assert model.nc == 16 and model.nu == 16 + TURN.size
    errs = _fd_check(model, 2)
    assert max(errs) < 1e-6, errs


def test_objective_gradient_of_a_stephenson3_group_matches_central_differences() -> None:
    # a plan with no dyad (one Newton group): the conditioning's derivative along the exact
    # tangent still matches the re-swept one
    sc = pk.scenes.load("stephenson3")
    theta = sc.input_angle + TURN
    p = sc.sweep(theta, outputs="all").points["j5"]
    q = p + 0.05 * np.stack([np.sin(2 * TURN), np.cos(TURN)], -1)
    model = PathModel(sc, "j5", CurveTarget(q, "closed"), theta + 0.02)
    errs = _fd_check(model, 4)
    assert max(errs) < 1e-6, errs


def test_objective_gradient_of_an_offset_slider_crank_matches_central_differences() -> None:
    geo = ((0.5, 0.2), 0.3, 0.4, 1.0, 3.5, 1.2, 0.8)
    _, _, p = slider_curve(*geo, TURN)
    q = p + 0.05 * np.stack([np.sin(3 * TURN), np.cos(TURN)], -1)
    sc = pk.Scene.from_dict(slider_scene(*geo, 0.1))
    model = PathModel(sc, "P", CurveTarget(q, "closed"), TURN + 0.04, max_link_ratio=5.0)
    errs = _fd_check(model, 3)
    assert max(errs) < 1e-6, errs


def test_slider_crank_pose_gradient_matches_central_differences_of_its_closed_form() -> None:
    # the scene's exact gradient (slots: Rust pose_gradient) against the closed form
    geo = [(0.5, 0.2), 0.3, 0.4, 1.0, 3.5, 1.2, 0.8]
    data = slider_scene(*geo, 0.1)  # type: ignore[arg-type]
    sc = pk.Scene.from_dict(data)
    theta = np.array([0.4, 2.5, 4.4])
    g = sc.gradient(["O2", "A", "B", "P"], theta)
    names = list(sc.points)
    h = 1e-6

    def closed(d: dict) -> np.ndarray:
        pts = {k: np.array(v) for k, v in d["points"].items()}
        o2, x = pts["O2"], pts["X"]
        gamma = math.atan2(*(x - o2)[::-1])
        u = (x - o2) / np.hypot(*(x - o2))
        n = np.array([-u[1], u[0]])
        r, ll = np.hypot(*(pts["A"] - o2)), np.hypot(*(pts["B"] - pts["A"]))
        e = float((pts["B"] - o2) @ n)
        w = (pts["B"] - pts["A"]) / ll
        rel = pts["P"] - pts["A"]
        pu, pv = float(rel @ w), float(rel @ np.array([-w[1], w[0]]))
        return np.stack(slider_curve(o2, gamma, e, r, ll, pu, pv, theta), 1)  # (N, 3, 2)

    for j, name in enumerate(g.free):
        p, axis = name.split(".")
        hi, lo = perturbed(data, 0.0, 0), perturbed(data, 0.0, 0)
        hi["points"][p][int(axis == "y")] += h
        lo["points"][p][int(axis == "y")] -= h
        fd = (closed(hi) - closed(lo)) / (2 * h)
        for k, q in enumerate(("A", "B", "P")):
            ex = g.point_array[:, names.index(q), :, j]
            assert np.abs(ex - fd[:, k]).max() < 1e-7, (name, q)


RECOVER = [
    # (name, geometry, kind, inputs): a crank-rocker (the seed four-bar, P off the coupler
    # line), a second crank-rocker, a double crank (ground shortest), a non-Grashof
    # rocking input on an open arc, a partial arc of a crank-rocker
    ("crank-rocker", CRANK_ROCKER, "closed", np.linspace(0, 2 * math.pi, 21)[:-1]),
    ("crank-rocker-2", ((1, 2), (5, 2.5), 1.2, 4.0, 3.0, 2.0, -1.0), "closed", TURN),
    ("double-crank", ((0, 0), (1.5, 0), 3.0, 3.5, 3.2, 1.0, 1.8), "closed", TURN),
    ("rocking-open", ((0, 0), (5, 0), 3.0, 3.0, 4.0, 1.0, 1.5), "open", np.linspace(-0.8, 0.8, 12)),
    ("partial", CRANK_ROCKER, "partial", np.linspace(1.0, 3.0, 9)),
]


@pytest.mark.parametrize("name, geo, kind, theta", RECOVER, ids=[c[0] for c in RECOVER])
def test_exact_recovery_of_fourbars_from_two_percent_off(name, geo, kind, theta) -> None:
    _, _, p = fourbar_curve(*geo, theta)
    assert np.all(np.isfinite(p))
    target = CurveTarget(p, kind)
    data = fourbar_scene(*geo, float(theta[0]))
    start = pk.Scene.from_dict(perturbed(data, 0.015 * target.size, 7))
    rng = np.random.default_rng(8)
    r = refine(start, "P", target, theta + rng.normal(0, 0.03, theta.size))
    assert r.feasible and r.error.max <= 1e-6, r
    v = verify(r.scene, "P", target, r.inputs)
    assert v.ok and v.error.max <= 1e-6, v
    if theta.size >= 12:
        # over-determined (2 n equations, 9 dimensions and n inputs): the inputs found are
        # the generating ones, up to the crank's own turns
        assert np.abs(np.angle(np.exp(1j * (v.inputs - theta)))).max() < 1e-6


def test_exact_recovery_with_timing_given() -> None:
    theta = np.linspace(0.5, 3.5, 10)
    _, _, p = fourbar_curve(*CRANK_ROCKER, theta)
    target = CurveTarget(p, "open", theta - 0.5)  # timing measured from the first point
    data = fourbar_scene(*CRANK_ROCKER, 0.5)
    start = pk.Scene.from_dict(perturbed(data, 0.015 * target.size, 9))
    r = refine(start, "P", target, theta + 0.04)
    assert r.feasible and r.error.max <= 1e-6, r
    # the given steps are kept: only the common offset moved
    assert np.allclose(np.diff(r.inputs), np.diff(theta), atol=1e-12)
    # the given values as they are (absolute): the inputs do not move at all
    exact = CurveTarget(p, "open", theta)
    r = refine(start, "P", exact, theta, timing_offset=False)
    assert r.feasible and r.error.max <= 1e-6, r
    np.testing.assert_array_equal(r.inputs, theta)


def test_exact_recovery_of_an_offset_slider_crank() -> None:
    geo = ((0.5, 0.2), 0.3, 0.4, 1.0, 3.5, 1.2, 0.8)
    _, _, p = slider_curve(*geo, TURN)
    target = CurveTarget(p, "closed")
    start = pk.Scene.from_dict(perturbed(slider_scene(*geo, 0.0), 0.015 * target.size, 11))
    r = refine(start, "P", target, TURN + 0.03)
    assert r.feasible and r.error.max <= 1e-6, r
    v = verify(r.scene, "P", target, r.inputs)
    assert v.ok and v.error.max <= 1e-6 and v.full_turn


def test_min_transmission_box_and_link_ratio_are_honoured() -> None:
    # a target the seed four-bar traces exactly; asked for more than it has
    _, _, p = fourbar_curve(*CRANK_ROCKER, TURN)
    target = CurveTarget(p, "closed")
    sc = pk.Scene.from_dict(fourbar_scene(*CRANK_ROCKER, 0.0))
    own = verify(sc, "P", target, TURN).min_transmission
    r = refine(sc, "P", target, TURN, min_transmission=own + 5.0)
    v = verify(r.scene, "P", target, r.inputs, min_transmission=own + 5.0)
    assert r.feasible and v.min_transmission >= own + 5.0 - 0.5, (own, v.min_transmission)
    # the pivots kept in a box that the seed's O4 (6, 0) is outside of
    box = ((-1.0, 5.5), (-1.0, 1.0))
    r = refine(sc, "P", target, TURN, box=box)
    assert r.feasible
    for q in ("O2", "O4"):
        x, y = r.scene.points[q]
        assert -1.0 - 1e-9 <= x <= 5.5 + 1e-9 and -1.0 - 1e-9 <= y <= 1.0 + 1e-9
    # the seed's links are 6, 2, 5, 5: ratio 3; ask for 2.5
    r = refine(sc, "P", target, TURN, max_link_ratio=2.5)
    o2, a, b, o4 = (np.array(r.scene.points[q]) for q in fourbar_joints(r.scene))  # type: ignore[union-attr]
    bars = [np.hypot(*(u - w)) for u, w in ((o2, o4), (o2, a), (a, b), (o4, b))]
    assert r.feasible and max(bars) / min(bars) <= 2.5 + 1e-7


def test_refined_design_keeps_off_the_dead_point_it_was_started_through() -> None:
    # a rocking four-bar's coupler curve traced up to its crank's limit (theta_max, where
    # A, B and O4 line up) and back on the other branch: no defect-free design of this
    # linkage reaches it all. Started with inputs past the limit, the refinement must
    # return a design whose arc keeps the asked transmission angle (on the real linkage)
    geo = ((0, 0), (5, 0), 3.0, 3.0, 4.0, 1.0, 1.5)
    tmax = math.acos(-0.5)  # |A - O4| = r3 + r4 = 7
    up = np.linspace(1.5, tmax - 1e-3, 6)
    p = np.vstack([fourbar_curve(*geo, up)[2], fourbar_curve(*geo, up[::-1], side=-1.0)[2][1:]])
    target = CurveTarget(p, "open")
    start = pk.Scene.from_dict(fourbar_scene(*geo, 1.5))
    inputs = np.concatenate([up, up[-1] + 0.05 * np.arange(1, 6)])
    assert verify(start, "P", target, inputs).defects.branch
    r = refine(start, "P", target, inputs, min_transmission=10.0)
    v = verify(r.scene, "P", target, r.inputs)
    assert r.feasible
    assert not v.defects.branch and v.min_transmission >= 10.0 - 0.5


def test_bad_input_is_refused_naming_the_parameter() -> None:
    _, _, p = fourbar_curve(*CRANK_ROCKER, TURN)
    target = CurveTarget(p, "closed")
    sc = pk.Scene.from_dict(fourbar_scene(*CRANK_ROCKER, 0.0))
    cases = [
        (dict(tracer="Q"), "tracer"),
        (dict(inputs=TURN[:-1]), "inputs"),
        (dict(inputs=np.full(TURN.size, np.nan)), "inputs"),
        (dict(min_transmission=95.0), "min_transmission"),
        (dict(box=((0, 1),)), "box"),
        (dict(box=((1, 0), (0, 1))), "box"),
        (dict(max_link_ratio=0.5), "max_link_ratio"),
        (dict(time_limit=-1.0), "time_limit"),
        (dict(max_iter=-2), "max_iter"),
        (dict(target=p), "target"),
        (dict(scene="fourbar"), "scene"),
    ]
    for kw, name in cases:
        args = {"scene": sc, "tracer": "P", "target": target, "inputs": TURN}
        args.update(kw)
        s, t, g, i = args.pop("scene"), args.pop("tracer"), args.pop("target"), args.pop("inputs")
        with pytest.raises(ValueError, match=f"^{name}") as e:
            refine(s, t, g, i, **args)
        assert "\n" not in str(e.value)


def test_full_turn_makes_a_rocking_start_a_crank() -> None:
    # an arc of a non-Grashof four-bar (its crank rocks): asked for a full turn, the
    # refinement moves to a linkage whose crank turns (checked on the real linkage)
    geo = ((0, 0), (5, 0), 3.0, 3.0, 4.0, 1.0, 1.5)
    theta = np.linspace(-0.8, 0.8, 12)
    target = CurveTarget(fourbar_curve(*geo, theta)[2], "open")
    start = pk.Scene.from_dict(fourbar_scene(*geo, -0.8))
    assert not verify(start, "P", target, theta).full_turn
    r = refine(start, "P", target, theta, full_turn=True)
    v = verify(r.scene, "P", target, r.inputs)
    assert r.feasible and v.full_turn and v.ok and v.error.max < 1e-3


def test_time_limit_stops_early() -> None:
    _, _, p = fourbar_curve(*CRANK_ROCKER, TURN)
    target = CurveTarget(p + 0.05, "closed")
    start = pk.Scene.from_dict(perturbed(fourbar_scene(*CRANK_ROCKER, 0.0), 0.1, 3))
    r = refine(start, "P", target, TURN, time_limit=0.005)
    full = refine(start, "P", target, TURN)
    assert r.iterations < full.iterations


ROCKING = ((0, 0), (5, 0), 3.0, 3.0, 4.0, 1.0, 1.5)


@pytest.mark.parametrize(
    "geo, kind, theta",
    [
        (CRANK_ROCKER, "closed", TURN + 0.7),
        (CRANK_ROCKER, "closed", (TURN + 0.7)[::-1]),
        (CRANK_ROCKER, "open", np.linspace(2.5, 4.0, 8)),
        (ROCKING, "open", np.linspace(-0.8, 0.8, 12)),
        (ROCKING, "open", np.linspace(0.8, -0.8, 12)),
    ],
    ids=["closed", "closed-reversed", "open", "rocking", "rocking-reversed"],
)
def test_initial_inputs_find_the_generating_inputs_to_the_grid(geo, kind, theta) -> None:
    target = CurveTarget(fourbar_curve(*geo, theta)[2], kind)
    sc = pk.Scene.from_dict(fourbar_scene(*geo, 0.0))
    t = initial_inputs(sc, "P", target)
    # within half a grid step of the generating angles (mod 2 pi), monotone the same way
    assert np.abs(np.angle(np.exp(1j * (t - theta)))).max() <= math.pi / INIT_SAMPLES + 1e-9
    assert np.all(np.sign(np.diff(t)) == np.sign(np.diff(theta)))


def test_initial_inputs_then_refine_recover_from_five_percent_off() -> None:
    _, _, p = fourbar_curve(*CRANK_ROCKER, TURN)
    target = CurveTarget(p, "closed")
    for seed in range(3):
        sc = pk.Scene.from_dict(
            perturbed(fourbar_scene(*CRANK_ROCKER, 0.0), 0.05 * target.size, seed)
        )
        r = refine(sc, "P", target, initial_inputs(sc, "P", target))
        v = verify(r.scene, "P", target, r.inputs)
        assert v.ok and v.error.max <= 1e-6, (seed, v.error)
