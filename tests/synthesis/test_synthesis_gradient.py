"""Exact gradients in synthesis (issue 19, item 1): the rows SLSQP sees, from the solver's
implicit differentiation, against central differences of whole sweeps of the redrawn
linkage, on random designs of several problems; and the optimizer reaching the same kind
of design with either."""

from __future__ import annotations

import numpy as np
import planarkin as pk
import pytest
from planarkin.synthesis import FunctionTarget, PathTarget, Problem, SceneSpace, ackermann
from planarkin.synthesis.driver import resolve_gradient, run_start, sample_starts
from planarkin.synthesis.exact import exact_rows, extrema, picks, subgrid

ROWS = ("r", "dense", "branch", "lengths", "envelope")


def _central(p: Problem, x: np.ndarray, h: float) -> list[tuple[np.ndarray, ...]]:
    # d(residual vectors) / dx by central differences, one pair of sweeps per coordinate
    grid = p.grid()
    cols = []
    for j in range(x.size):
        e = np.zeros_like(x)
        e[j] = h
        a, b = p.residuals(x + e, grid), p.residuals(x - e, grid)
        cols.append(tuple((u - v) / (2 * h) for u, v in zip(a, b, strict=True)))
    return cols


def _compare(p: Problem, x: np.ndarray, h: float = 1e-6) -> dict[str, float]:
    ev = p.evaluate(x, p.grid())
    assert ev.ok
    res = p.residuals_of(x, ev)
    pk_ = picks(res, subgrid(res.branch.size, 41), extrema(np.abs(res.dense), 16))
    ex = exact_rows(p, x, ev, res, pk_)
    cols = _central(p, x, h)
    fd = {
        "r": np.stack([c[0] for c in cols], -1),
        "dense": np.stack([c[1] for c in cols], -1)[pk_.dense],
        "branch": np.stack([c[2] for c in cols], -1)[pk_.branch],
        "lengths": np.stack([c[4] for c in cols], -1),
        "envelope": np.stack([c[5] for c in cols], -1)[pk_.envelope, np.arange(pk_.envelope.size)]
        if pk_.envelope.size
        else np.zeros((0, x.size)),
    }
    out = {}
    for name in ROWS:
        a, b = getattr(ex, name), fd[name]
        assert a.shape == b.shape, name
        if b.size:
            out[name] = float(np.max(np.abs(a - b)) / max(np.max(np.abs(b)), 1e-300))
    return out


def _ackermann_designs(
    n: int, seed: int = 5, samples: int = 400
) -> tuple[Problem, list[np.ndarray]]:
    p = ackermann.problem()
    rng = np.random.default_rng(seed)
    found = sample_starts(p, samples, n, rng, ackermann.mirror_sampler(p.space))
    assert len(found) == n
    return p, [x for _, x in found]


def test_exact_rows_match_central_differences_on_random_ackermann_designs():
    p, xs = _ackermann_designs(3)
    for x in xs:
        err = _compare(p, x)
        assert max(err.values()) < 1e-6, err
        assert set(err) == set(ROWS)  # every kind of row was compared


def _fourbar_function() -> Problem:
    sc = pk.scenes.load("fourbar")
    phi = np.radians(np.linspace(0.0, 60.0, 7))
    dense = np.radians(np.linspace(0.0, 60.0, 61))
    target = FunctionTarget(phi, 0.6 * phi, dense, 0.6 * dense)
    pts = np.array(list(sc.points.values()))
    lo, hi = pts.min(0) - 2.0, pts.max(0) + 2.0
    return Problem(
        SceneSpace(sc, ["A", "B", "O4"], min_link=0.1), target, det_margin=1e-3,
        envelope=(tuple(lo), tuple(hi)),
    )  # fmt: skip


def _sixbar_path() -> Problem:
    sc = pk.scenes.load("watt2")
    names = list(sc.points)
    tip = names[-1]
    sw = sc.sweep(sc.input_angle + np.radians(np.linspace(0.0, 40.0, 5)), outputs="all")
    target = PathTarget(tip, np.radians(np.linspace(0.0, 40.0, 5)), sw.points[tip] + 0.01,
                        np.radians(np.linspace(0.0, 40.0, 41)))  # fmt: skip
    free = [n for n in names if n not in sc.links[sc.ground]][:3]
    return Problem(SceneSpace(sc, free, min_link=0.01), target, det_margin=1e-4)


@pytest.mark.parametrize("make", [_fourbar_function, _sixbar_path])
def test_exact_rows_match_central_differences_on_scenes(make):
    p = make()
    rng = np.random.default_rng(11)
    x0 = p.x0
    done = 0
    for _ in range(40):
        x = x0 + rng.normal(0.0, 0.02, x0.size) * np.ptp(list(p.space.points.values()))
        if not p.evaluate(x, p.grid()).ok:
            continue
        err = _compare(p, x)
        assert max(err.values()) < 1e-6, err
        done += 1
        if done == 3:
            break
    assert done == 3


def test_gradient_choice_and_refusal():
    p = ackermann.problem()
    assert resolve_gradient(p, "auto") == "exact"
    assert resolve_gradient(p, "fd") == "fd"
    assert resolve_gradient(ackermann.problem(objective="generated"), "auto") == "fd"
    with pytest.raises(ValueError, match="gradient='exact' is not available here: objective"):
        resolve_gradient(ackermann.problem(objective="generated"), "exact")
    sc = pk.scenes.load("slider-crank-offset")
    phi = np.radians(np.linspace(0.0, 90.0, 5))
    t = FunctionTarget(phi, 0.1 * phi, phi, 0.1 * phi)
    slider = Problem(sc, free=["A"], target=t)
    assert resolve_gradient(slider, "auto") == "fd"
    with pytest.raises(ValueError, match="slots, prismatic pairs or a linear input"):
        resolve_gradient(slider, "exact")
    with pytest.raises(ValueError, match="gradient must be"):
        resolve_gradient(p, "adjoint")


@pytest.mark.slow  # two full least-squares runs: about 15 s on 2 cores
def test_both_gradients_reach_an_envelope_design_from_one_start():
    # one start of the steering problem, least squares only: both feasible (every joint
    # inside the box over the whole motion, verified on the 1001-angle grid) and below
    # 0.01 deg; the exact run is not worse than the differenced one by more than 2x
    p, xs = _ackermann_designs(1, seed=2, samples=600)  # a start that leads somewhere
    deg = np.degrees(p.target.scale)
    got = {g: run_start(p, xs[0], minimax=False, gradient=g) for g in ("exact", "fd")}
    for g, r in got.items():
        assert r.feasible, g
        assert r.max_error * deg < 0.01, (g, r.max_error * deg)
        assert p.residuals(r.x).envelope.min() >= -1e-6
    assert got["exact"].max_error <= 2 * got["fd"].max_error


def test_dets_gradient_checks_its_input():
    sc = pk.scenes.load("fourbar")
    sw = sc.sweep(sc.input_angle + np.array([0.0, 0.1]), outputs="all")
    pts = np.ascontiguousarray(sw.coords.reshape(-1, 2))
    dp = sc._core.pose_gradient(pts, [(2, 0)], True)
    with pytest.raises(ValueError, match="dpoints must hold"):
        sc._core.dets_gradient(pts, dp.ravel()[:-1], [(2, 0)], None)
    with pytest.raises(ValueError, match="points must hold whole poses"):
        sc._core.dets_gradient(pts[:-1], dp.ravel(), [(2, 0)], None)
    with pytest.raises(ValueError, match="unknown|no point|output"):
        sc._core.dets_gradient(pts, dp.ravel(), [(2, 0)], ["nowhere"])
    out = sc._core.dets_gradient(pts, dp.ravel(), [(2, 0)], None)
    assert out.shape == (2, 1) and np.all(np.isfinite(out))
