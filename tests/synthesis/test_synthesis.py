"""Synthesis of double butterflies (seed 003): closed forms, constraints, the generated/true
error relation and recovery, each checked against the scene solver or a formula written
here; the shipped Ackermann design against the Ackermann condition."""

from __future__ import annotations

import json
import math
from concurrent.futures import ThreadPoolExecutor
from dataclasses import replace
from pathlib import Path

import numpy as np
import planarkin as pk
import pytest
from _support import out_rotation
from planarkin.synthesis import (
    STEERING_KNUCKLE,
    TYPE_I,
    TYPE_I_LINKS,
    DesignSpace,
    FunctionTarget,
    PathTarget,
    Problem,
    SeedPlan,
    admissible_loop_choices,
    loops,
    run_start,
    synthesize,
)
from planarkin.synthesis.problem import SWEEP_TOL
from truth import ackermann

ROOT = Path(__file__).resolve().parents[2]
SHIPPED = ROOT / "examples" / "ackermann"


def _type1() -> pk.Scene:
    d = pk.scenes.load("double-butterfly-1").to_dict()
    d["output"] = {"link": "output", "pivot": "K"}
    return pk.Scene.from_dict(d)


def _near_its_lower_dead_point() -> dict[str, tuple[float, float]]:
    """double-butterfly-2's pose 5 deg inside the lower dead point of its circuit (found by
    the sweep's backward pass), as the tests below were drawn."""
    sc = pk.scenes.load("double-butterfly-2")
    sw = sc.sweep(outputs="all")
    side = [
        np.angle(np.exp(1j * (v - sc.input_angle))) for v in np.unique(sw.limit[sw.status == -8])
    ]
    lower = sc.input_angle + min(side)
    pose = sc.sweep(np.array([lower + math.radians(5.0)]), outputs="all")
    assert pose.success[0]
    return {n: (float(x), float(y)) for n, (x, y) in zip(sc.points, pose.coords[0], strict=True)}


def _knuckle_from_builtin() -> dict[str, tuple[float, float]]:
    # double-butterfly-2 relabelled as the steering template with a ternary knuckle
    p = _near_its_lower_dead_point()
    m = {
        "KL": "B",
        "KR": "E",
        "O": "D",
        "A": "A",
        "C": "C",
        "Q": "H",
        "K": "K",
        "I": "I",
        "G": "G",
        "F": "F",
    }
    return {k: p[v] for k, v in m.items()}


# --- the graph -------------------------------------------------------------------------


def test_loops_of_the_double_butterfly():
    ls = loops(TYPE_I_LINKS)
    assert sorted(len(a) for a, _ in ls) == [5, 5, 5, 5, 6, 6, 8]
    # the seed's chosen loops are admissible, in its order
    choices = admissible_loop_choices(TYPE_I_LINKS, "1", "2", "5")
    seed = (frozenset("12578"), frozenset("123567"), frozenset("12345"))
    assert any((c.loop1, c.loop2, c.loop3) == seed for c in choices)
    for c in choices:
        known = {"1", "2", "5"}
        assert known <= c.loop1 and len(c.loop1 - known) == 2
        assert len(c.loop2 - known - c.loop1) == 2
        assert "5" in c.loop3 and len(c.loop3 - known - c.loop1 - c.loop2) == 1


def test_loop_choice_bad_input():
    with pytest.raises(ValueError, match="output"):
        admissible_loop_choices(TYPE_I_LINKS, "1", "2", "9")


# --- closed forms against the scene solver ---------------------------------------------


@pytest.mark.parametrize("which", ["type1", "knuckle"])
def test_zero_split_closed_form_is_the_true_output(which):
    if which == "type1":
        sc, tpl = _type1(), TYPE_I
        phi = np.linspace(0.0, 1.2, 25)
    else:
        pts = _knuckle_from_builtin()
        sc, tpl = pk.Scene.from_dict(STEERING_KNUCKLE.scene_dict(pts)), STEERING_KNUCKLE
        # loop 2's radicand reaches zero near 0.5 rad: past it the real linkage goes on
        # while a fixed-sign closed form changes root (see the next test)
        phi = np.linspace(0.0, 0.45, 25)
    out = out_rotation(sc, phi)
    g = SeedPlan(tpl, sc.points).generated(phi, out)
    assert np.max(np.abs(g.theta - out)) < 1e-12
    assert np.all(g.radicand > 0)
    # another sign combination is another mechanism: it does not reproduce the output
    other = SeedPlan(tpl, sc.points).generated(phi, out, (1, 1, -1))
    assert np.max(np.abs(other.theta - out)) > 1e-3


def test_fixed_signs_lose_the_real_linkage_where_a_radicand_touches_zero():
    pts = _knuckle_from_builtin()
    sc = pk.Scene.from_dict(STEERING_KNUCKLE.scene_dict(pts))
    phi = np.linspace(0.0, 0.9, 19)
    out = out_rotation(sc, phi)
    g = SeedPlan(STEERING_KNUCKLE, sc.points).generated(phi, out)
    i = int(np.argmin(g.radicand[:, 1]))
    assert 0 < i < phi.size - 1 and g.radicand[i, 1] < 1e-3
    assert np.max(np.abs(g.theta - out)[: i - 1]) < 1e-12
    assert np.max(np.abs(g.theta - out)[i + 2 :]) > 1e-2


def test_half_angle_roots_solve_the_equation():
    rng = np.random.default_rng(3)
    c1, c2 = rng.normal(size=50), rng.normal(size=50)
    c3 = 0.9 * np.hypot(c1, c2) * rng.uniform(-1, 1, 50)
    for s in (1, -1):
        x, rad = pk.synthesis.half_angle(c1, c2, c3, s)
        assert np.all(rad > 0)
        np.testing.assert_allclose(c1 * np.cos(x) + c2 * np.sin(x), c3, atol=1e-12)
    x, rad = pk.synthesis.half_angle(np.array([1.0]), np.array([0.0]), np.array([2.0]), 1)
    assert rad[0] < 0 and np.isfinite(x[0])  # not assemblable: flagged, never NaN


def test_generated_and_true_error_relation():
    # prescribed = true output + a small smooth error e_A; then e_g ~= (1 - k) e_A
    rng = np.random.default_rng(11)
    base = _type1().to_dict()
    checked = 0
    for _ in range(12):
        d = json.loads(json.dumps(base))
        for n in d["points"]:
            if n not in ("A", "K"):
                d["points"][n] = [c + rng.normal(0, 0.05) for c in d["points"][n]]
        sc = pk.Scene.from_dict(d)
        phi = np.linspace(0.0, 0.3, 11)
        sw = sc.sweep(sc.input_angle + phi, outputs=["output"])
        if not np.all(sw.status == 0):
            continue
        out = out_rotation(sc, phi)
        e_a = 1e-6 * (1 + np.sin(3 * phi + rng.uniform(0, 6)))
        plan = SeedPlan(TYPE_I, sc.points)
        g = plan.generated(phi, out - e_a)
        if np.min(g.radicand) < 1e-3 or np.max(np.abs(g.theta - out)) > 1e-9 + 1e-3:
            continue
        e_g = g.theta - (out - e_a)
        predicted = e_g / (1 - g.k)
        np.testing.assert_allclose(predicted, e_a, rtol=0.05)
        checked += 1
    assert checked >= 5


# --- constraints -------------------------------------------------------------------------


def _knuckle_problem(lo_deg: float, hi_deg: float) -> Problem:
    pts = _knuckle_from_builtin()
    sc = pk.Scene.from_dict(STEERING_KNUCKLE.scene_dict(pts))
    phi = np.radians(np.linspace(lo_deg, hi_deg, 11))
    dense = np.radians(np.linspace(lo_deg, hi_deg, 41))
    # any smooth target: the constraints do not read it
    target = FunctionTarget(phi, 0.5 * phi + 0.01, dense, 0.5 * dense + 0.01)
    free = ("A", "C", "Q", "K", "I", "G", "F")
    space = DesignSpace(STEERING_KNUCKLE, pts, free, -10.0, 10.0)
    assert sc.output is not None
    return Problem(space, target, det_margin=1e-3, closed_form=False)


def test_branch_constraint_catches_a_dead_point():
    # drawn 5 deg inside a dead point of its circuit
    inside = _knuckle_problem(0.0, 60.0)
    x = inside.space.x_of(inside.space.points)
    branch = inside.residuals(x).branch
    assert np.all(branch > 0)
    across = _knuckle_problem(-20.0, 60.0)
    branch = across.residuals(x).branch
    assert np.min(branch) < 0
    # and the scene solver agrees that the range holds a dead point
    sc = across.space.scene(x)
    sw = sc.sweep(sc.input_angle + across.target.dense_in, tol=SWEEP_TOL)
    assert np.any(sw.status != 0)


def test_order_constraint_rejects_a_non_monotone_input():
    phi = np.radians([0.0, 10.0, 5.0, 20.0])
    with pytest.raises(ValueError, match="phi_in"):
        FunctionTarget(phi, phi, np.linspace(0, 0.3, 5), np.linspace(0, 0.3, 5))
    with pytest.raises(ValueError, match="phi_in"):
        PathTarget("G", phi, np.zeros((4, 2)), np.linspace(0, 0.3, 5))


def test_bad_input_names_the_parameter():
    pts = _knuckle_from_builtin()
    with pytest.raises(ValueError, match="free"):
        DesignSpace(STEERING_KNUCKLE, pts, ("Z",), -1.0, 1.0)
    p = _knuckle_problem(0.0, 30.0)
    with pytest.raises(ValueError, match="objective"):
        Problem(p.space, p.target, objective="fast")
    with pytest.raises(ValueError, match="starts"):
        synthesize(p, starts=0)
    with pytest.raises(ValueError, match="signs"):
        SeedPlan(STEERING_KNUCKLE, pts).generated([0.0], [0.0], (1, 2, 1))


# --- recovery -----------------------------------------------------------------------------


def _type1_space(sc: pk.Scene, x_pert: float, rng: np.random.Generator) -> tuple:
    free = ("C", "D", "F", "H", "I")
    space = DesignSpace(TYPE_I, sc.points, free, -20.0, 20.0)
    x_true = space.x_of(sc.points)
    return space, x_true, x_true + rng.normal(0, x_pert, x_true.size)


@pytest.mark.slow  # a 300-iteration least-squares run and its polish: about 2 s on 2 cores
def test_recovery_function_generation():
    sc = _type1()
    phi = np.linspace(0.05, 1.0, 15)
    dense = np.linspace(0.05, 1.0, 41)
    out, dout = out_rotation(sc, phi), out_rotation(sc, dense)
    space, x_true, x0 = _type1_space(sc, 2e-3, np.random.default_rng(5))
    p = Problem(space, FunctionTarget(phi, out, dense, dout), det_margin=1e-3)
    r0 = np.abs(p.residuals(x0)[0]).max()
    res = run_start(p, x0, maxiter=300)
    assert res.feasible
    # the true linkage of the result, swept here, against the prescribed outputs
    got = out_rotation(space.scene(res.x), phi)
    assert np.max(np.abs(got - out)) / np.ptp(out) < 1e-6 < r0


def test_recovery_path_generation():
    sc = _type1()
    phi = np.linspace(0.05, 1.0, 15)
    sw = sc.sweep(sc.input_angle + phi, outputs=["G"], tol=1e-12)
    xy = sw.points["G"].copy()
    space, x_true, x0 = _type1_space(sc, 2e-3, np.random.default_rng(6))
    p = Problem(space, PathTarget("G", phi, xy, np.linspace(0.05, 1.0, 41)), det_margin=1e-3)
    res = run_start(p, x0, maxiter=300, minimax=False)
    sc2 = space.scene(res.x)
    got = sc2.sweep(sc2.input_angle + phi, outputs=["G"], tol=1e-12).points["G"]
    size = np.ptp(xy, axis=0).max()
    assert np.max(np.linalg.norm(got - xy, axis=1)) / size < 1e-6


# --- the shipped Ackermann design -----------------------------------------------------------


@pytest.mark.skipif(not (SHIPPED / "design.json").exists(), reason="no shipped design")
def test_shipped_ackermann_design_meets_the_target():
    sc = pk.Scene.load(SHIPPED / "design.json")
    rep = json.loads((SHIPPED / "report.json").read_text())
    lo, hi = -math.radians(40.903), math.radians(61.0)
    assert math.degrees(math.atan(1 / (1 / math.tan(math.radians(61)) + 0.6))) == pytest.approx(
        40.903, abs=5e-4
    )
    lo = -math.atan(1 / (1 / math.tan(hi) + 0.6))
    for n, key in ((31, "true_max_error_deg"), (1001, "true_max_error_deg_1001")):
        dl = np.linspace(lo, hi, n)
        err = np.degrees(np.max(np.abs(out_rotation(sc, dl) - ackermann(dl))))
        assert err == pytest.approx(rep[key], rel=1e-6, abs=1e-9)
        assert err <= 0.01
    sw = sc.sweep(sc.input_angle + np.linspace(lo, hi, 1001), outputs="all")
    assert np.all(sw.status == 0)
    assert np.all(sw.det > 0) or np.all(sw.det < 0)
    assert np.min(np.abs(sw.det)) >= 0.02
    # compact: kingpins at (+-0.3, 0), every joint within the 0.35 box
    assert sc.points["KL"] == (-0.3, 0.0) and sc.points["KR"] == (0.3, 0.0)
    xy = np.array(list(sc.points.values()))
    assert np.max(np.abs(xy)) <= 0.35 + 1e-12
    # ... and over the whole steering range, not only as drawn (the packaging envelope):
    # the shipped design and both alternatives written beside it
    for name in ("design.json", "design_accurate.json", "design_robust.json"):
        d = pk.Scene.load(SHIPPED / name)
        sw = d.sweep(d.input_angle + np.linspace(lo, hi, 1001), outputs="all")
        assert np.all(sw.status == 0), name
        # (to SLSQP's feasibility: the constraints hold to 1e-6 of the box's size)
        assert np.max(np.abs(sw.coords)) <= 0.35 + 1e-6, name
        assert np.min(np.abs(sw.det)) >= 1e-4 and (np.all(sw.det > 0) or np.all(sw.det < 0))
        e = np.degrees(
            np.max(
                np.abs(
                    out_rotation(d, np.linspace(lo, hi, 1001))
                    - ackermann(np.linspace(lo, hi, 1001))
                )
            )
        )
        assert e <= 0.01, name
    assert {"designs", "p95_error_deg_at_sigma"} <= set(rep)
    # both at 0: axles collinear (the drawn pose is straight ahead)
    assert sc.input == ("left_knuckle", "KL") and sc.output == ("right_knuckle", "KR")
    assert {"tolerance_sensitivity", "det_sign_changes", "link_ratio", "starts"} <= set(rep)


# --- executors ----------------------------------------------------------------------------


def _small_problem() -> tuple[Problem, np.ndarray]:
    sc = _type1()
    phi = np.linspace(0.05, 0.8, 9)
    dense = np.linspace(0.05, 0.8, 21)
    out, dout = out_rotation(sc, phi), out_rotation(sc, dense)
    space, _, x0 = _type1_space(sc, 1e-3, np.random.default_rng(9))
    return Problem(space, FunctionTarget(phi, out, dense, dout), det_margin=1e-3), x0


@pytest.mark.slow  # two starts to 60 iterations: about 2 s on 2 cores
def test_multistart_on_a_thread_pool():
    p, x0 = _small_problem()
    with ThreadPoolExecutor(2) as ex:
        res = synthesize(p, starts=2, samples=0, x0=[x0, x0 + 1e-4], executor=ex, maxiter=60)
    assert res.starts == 2 and len(res.runs) == 2
    assert res.best.max_error < 1e-5


@pytest.mark.slow  # starts a local dask cluster; the thread pool above runs the same starts
def test_multistart_on_a_dask_local_cluster():
    distributed = pytest.importorskip("dask.distributed")
    p, x0 = _small_problem()
    with (
        distributed.LocalCluster(
            n_workers=2, threads_per_worker=1, processes=False, dashboard_address=None
        ) as cluster,
        distributed.Client(cluster) as client,
    ):
        res = synthesize(
            p, starts=2, samples=0, x0=[x0, x0 + 1e-4], executor=client.get_executor(), maxiter=60
        )
    assert res.starts == 2 and res.best.max_error < 1e-5


@pytest.mark.slow  # 6 s: SLSQP from two starts
def test_seed_objective_on_the_generated_mechanism():
    # the seed's method: SLSQP on the generated output's RMS error over the 8 combinations
    p, x0 = _small_problem()
    seed = replace(p, objective="generated")
    with ThreadPoolExecutor(2) as ex:
        res = synthesize(seed, starts=2, samples=0, x0=[x0, x0], executor=ex, maxiter=150,
                         sign_combinations=[(1, 1, 1), (1, 1, -1)])  # fmt: skip
    assert {r.signs for r in res.runs} == {(1, 1, 1), (1, 1, -1)}
    best = min(res.runs, key=lambda r: r.fun)
    assert best.signs == (1, 1, 1)  # the drawn branch: the target's own mechanism
    g = seed.generated(best.x)
    t = seed.target
    e_g = np.max(np.abs(g.theta - t.phi_out)) / t.scale
    assert e_g < 1e-6
    # and the true linkage, swept here, is as close
    got = out_rotation(seed.space.scene(best.x), t.phi_in)
    assert np.max(np.abs(got - t.phi_out)) / t.scale < 1e-5
