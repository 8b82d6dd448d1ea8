"""The seed sweep: r = (6, 2, 5, 5), open mode, 361 crank angles (0..360 deg), tol 1e-9,
solved every way a user would, side by side in one group."""

from __future__ import annotations

import math

import numpy as np
import peers
import planarkin as pk
import pytest
from conftest import THETA2, closed_truth, max_angle_error, record
from planarkin.reference import closed_form_vectorized

GROUP = "seed sweep: (6, 2, 5, 5), 361 angles"
pytestmark = pytest.mark.benchmark(group=GROUP)


def _check(t3, t4, tol=1e-8):
    c3, c4 = closed_truth(1)
    err = max(max_angle_error(t3, c3[0]), max_angle_error(t4, c4[0]))
    assert err < tol, err
    return err


@pytest.mark.parametrize("predictor", ["quadratic", "tangent", "previous", "closed-form"])
def test_planarkin_sweep(benchmark, seed_fb, predictor):
    s = benchmark(seed_fb.sweep, predictor=predictor)
    assert s.summary().converged == 361
    label = {
        "quadratic": "planarkin fb.sweep() (quadratic predictor, default)",
        "tangent": "planarkin fb.sweep(predictor='tangent')",
        "previous": "planarkin fb.sweep(predictor='previous') (plain Newton)",
        "closed-form": "planarkin fb.sweep(predictor='closed-form') (across angles)",
    }[predictor]
    record(
        benchmark,
        f"pk_sweep_{predictor}",
        label,
        nit_mean=float(s.nit.mean()),
        max_error=_check(s.theta3, s.theta4),
    )


def test_planarkin_sweep_scalar_path(benchmark, seed_fb):
    def scalar():
        with pk.use_simd(False):
            return seed_fb.sweep()

    s = benchmark(scalar)
    assert s.summary().converged == 361
    record(
        benchmark,
        "pk_sweep_scalar",
        "planarkin fb.sweep() with pk.use_simd(False) (bit-exact scalar path)",
        nit_mean=float(s.nit.mean()),
        max_error=_check(s.theta3, s.theta4),
    )


def test_planarkin_sweep_closed_form_method(benchmark, seed_fb):
    s = benchmark(seed_fb.sweep, method="closed-form")
    assert s.summary().converged == 361
    record(
        benchmark,
        "pk_sweep_closed_form",
        "planarkin fb.sweep(method='closed-form') (Sweep with statuses)",
        nit_mean=0.0,
        max_error=_check(s.theta3, s.theta4, 1e-15),
    )


def test_planarkin_closed_form(benchmark, seed_fb):
    t3, t4 = benchmark(seed_fb.closed_form, THETA2)
    record(
        benchmark,
        "pk_closed_form",
        "planarkin fb.closed_form(theta2)",
        max_error=_check(t3, t4, 1e-15),
    )


def test_numpy_closed_form(benchmark):
    t3, t4 = benchmark(closed_form_vectorized, *peers.SEED, THETA2)
    record(
        benchmark, "np_closed_form", "NumPy vectorized closed form", max_error=_check(t3, t4, 1e-14)
    )


def test_reference_scalar_loop(benchmark, seed_fb):
    s = benchmark(pk.reference.sweep, seed_fb)
    record(
        benchmark,
        "reference_sweep",
        "pk.reference.sweep (NumPy/math scalar loop, quadratic)",
        nit_mean=float(s.nit.mean()),
        max_error=_check(s.theta3, s.theta4),
    )


def test_python_math_newton(benchmark):
    t3, t4, nit = benchmark(peers.math_sweep, *peers.SEED, THETA2.tolist())
    record(
        benchmark,
        "math_newton",
        "plain-Python math Newton-Raphson (seed algorithm)",
        nit_mean=float(np.mean(nit)),
        max_error=_check(t3, t4),
    )


def test_seed_code_as_printed(benchmark):
    deg = np.linspace(0, 360, 361)
    t3, t4 = benchmark(peers.seed_as_printed, *peers.SEED, deg)
    err = _check(np.radians(t3), np.radians(t4))
    record(
        benchmark, "seed_as_printed", "seed report code as printed (NumPy scalars)", max_error=err
    )


def test_pylinkage_numba(benchmark):
    pytest.importorskip("numba")
    pylinkage = pytest.importorskip("pylinkage")
    pl = peers.PylinkageFourBar(*peers.SEED)
    traj = benchmark(pl.run)
    t3, t4 = pl.angles(traj)
    record(
        benchmark,
        "pylinkage",
        f"pylinkage {pylinkage.__version__} step_fast (numba)",
        max_error=_check(t3, t4, 1e-12),
    )


def test_pylinkage_numba_kernel(benchmark):
    pytest.importorskip("numba")
    pytest.importorskip("pylinkage")
    pl = peers.PylinkageFourBar(*peers.SEED)
    traj = benchmark(pl.kernel)
    t3, t4 = pl.angles(traj)
    record(
        benchmark,
        "pylinkage_kernel",
        "pylinkage numba loop alone (solver.simulation.simulate)",
        max_error=_check(t3, t4, 1e-12),
    )


# --- where the seed sweep's time goes: the API, the binding alone ------------------------


@pytest.mark.benchmark(group="seed sweep: Python layers")
def test_layers_api(benchmark, seed_fb):
    benchmark(seed_fb.sweep)
    record(benchmark, "layers_api", "fb.sweep() (public API: validation + result object)")


@pytest.mark.benchmark(group="seed sweep: Python layers")
def test_layers_binding(benchmark, seed_fb):
    core = seed_fb._core
    benchmark(core.sweep, THETA2, "open", None, 1e-9, 100, "quadratic", "newton", None, None)
    record(benchmark, "layers_binding", "fb._core.sweep(...) (the pyo3 binding alone)")


@pytest.mark.benchmark(group="seed sweep: Python layers")
def test_layers_binding_one_point(benchmark, seed_fb):
    core = seed_fb._core
    t2 = THETA2[:1].copy()
    benchmark(core.sweep, t2, "open", None, 1e-9, 100, "quadratic", "newton", None, None)
    record(benchmark, "layers_binding_1pt", "fb._core.sweep(...) on 1 angle (fixed call cost)")


def test_math_is_the_seed_algorithm():
    """The plain-math loop reproduces the seed report's continuation from its own guess."""
    t3, t4, nit = peers.math_sweep(*peers.SEED, THETA2.tolist())
    assert not any(math.isnan(v) for v in t3)
    assert np.mean(nit) > 1.5  # zeroth-order continuation: about two steps a point
