"""Tolerance sensitivity by linearisation with the exact gradients (issue 19, item 5),
checked against sampling: the same noise draws applied to the drawing and the noisy
linkages swept again."""

from __future__ import annotations

import json
from pathlib import Path

import numpy as np
import planarkin as pk
import pytest
from planarkin.synthesis import ackermann
from planarkin.synthesis.robust import linearized_tolerance, output_jacobian
from planarkin.synthesis.verify import tolerance_sensitivity

DESIGN = Path(__file__).parents[2] / "examples" / "ackermann" / "design.json"


def _steering() -> pk.Scene:
    return pk.Scene.from_dict(json.loads(DESIGN.read_text()))


@pytest.mark.parametrize(("sigma", "rtol"), [(1e-5, 2e-3), (1e-4, 2e-2)])
def test_linearized_percentiles_match_sampling_with_the_same_noise(sigma, rtol):
    sc = _steering()
    t = ackermann.target(dense=201)
    phi, out = t.dense_in, t.dense_out
    n = 200
    sampled = tolerance_sensitivity(sc, phi, out, sigmas=(sigma,), samples=n, seed=3)[0]
    # tolerance_sensitivity draws x then y of each point, sample after sample
    noise = np.random.default_rng(3).standard_normal((n, 2 * len(sc.points)))
    lin = linearized_tolerance(sc, phi, out, sigmas=(sigma,), noise=noise)[0]
    assert sampled["failed"] == 0
    for k in ("median_max_error_deg", "p95_max_error_deg"):
        assert lin[k] == pytest.approx(sampled[k], rel=rtol), k


def test_output_jacobian_matches_central_differences_of_the_drawing():
    sc = _steering()
    phi = np.radians(np.linspace(-40.0, 60.0, 11))
    _, jac = output_jacobian(sc, phi)
    d = sc.to_dict()
    names = list(d["points"])
    h = 1e-6
    from planarkin.synthesis.problem import output_from_drawn

    def out(dd: dict) -> np.ndarray:
        s = pk.Scene.from_dict(dd)
        return output_from_drawn(s, s.sweep(s.input_angle + phi, outputs="all", tol=1e-13).output)

    for c in range(2 * len(names)):
        p, a = names[c // 2], c % 2
        vals = []
        for sg in (1, -1):
            dd = json.loads(json.dumps(d))
            dd["points"][p][a] += sg * h
            vals.append(out(dd))
        fd = (vals[0] - vals[1]) / (2 * h)
        np.testing.assert_allclose(jac[:, c], fd, atol=1e-6 * max(1.0, np.abs(fd).max()))


def test_bad_input():
    sc = _steering()
    t = ackermann.target(dense=11)
    with pytest.raises(ValueError, match="sigmas must be finite and > 0"):
        linearized_tolerance(sc, t.dense_in, t.dense_out, sigmas=(0.0,))
    with pytest.raises(ValueError, match="samples must be >= 1"):
        linearized_tolerance(sc, t.dense_in, t.dense_out, samples=0)


def test_tolerance_aware_objective_is_the_linearized_p95():
    from planarkin.synthesis.exact import subgrid
    from planarkin.synthesis.robust import p95_objective

    p = ackermann.problem()
    sc = _steering()
    x = p.space.x_of(sc.points)
    f = p95_objective(p, 1e-4, samples=300, seed=4, grid=101)
    t = p.target
    phi = t.dense_in[subgrid(t.dense_in.size, 101)]
    noise = np.random.default_rng(4).standard_normal((300, 2 * len(sc.points)))
    lin = linearized_tolerance(sc, phi, t.function(phi), sigmas=(1e-4,), noise=noise)[0]
    assert np.degrees(f(x) * t.scale) == pytest.approx(lin["p95_max_error_deg"], rel=1e-12)


@pytest.mark.slow  # a 15-iteration robust start over sampled tolerances: 1-2 s on 2 cores
def test_robust_start_returns_a_verified_design_no_worse_than_its_start():
    import math

    from planarkin.synthesis.robust import p95_objective, robust_start
    from planarkin.synthesis.start import feasible, figures

    p = ackermann.problem()
    x0 = p.space.x_of(_steering().points)
    deg = math.degrees(p.target.scale)
    budget = 0.002
    x, info = robust_start(p, x0, 1e-4, budget / deg, maxiter=15)
    f = p95_objective(p, 1e-4)
    assert f(x) <= f(x0) and info["p95_end"] <= info["p95_start"]
    assert feasible(p, x)
    assert figures(p, x)["max_error"] * deg <= budget * (1 + 1e-6)
